#pragma once
// Small RGL "tensor_file"s written in tests (brdf/rgl.hpp reads them): a synthetic material whose every table
// is known, and the pieces to damage one field at a time. The real files live in ../shared (never committed).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace hilite_test {

struct TensorField {
    std::string name;
    std::uint8_t type = 10;  ///< 1 u8 ... 10 f32, 11 f64
    std::vector<std::uint64_t> shape;
    std::string bytes;
};

inline std::string floatBytes(const std::vector<float>& v) {
    std::string s(v.size() * 4, '\0');
    std::memcpy(&s[0], v.data(), s.size());
    return s;
}

template <typename T>
void put(std::string& s, T v) {
    s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

/// The bytes of a tensor file holding `fields` (header, field table, then the data in order).
inline std::string tensorFile(const std::vector<TensorField>& fields, int major = 1, int minor = 0) {
    std::string head("tensor_file", 12);
    head += char(major);
    head += char(minor);
    put(head, std::uint32_t(fields.size()));
    std::size_t tableBytes = 0;
    for (const auto& f : fields) tableBytes += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    std::size_t offset = head.size() + tableBytes;
    std::string table, data;
    for (const auto& f : fields) {
        put(table, std::uint16_t(f.name.size()));
        table += f.name;
        put(table, std::uint16_t(f.shape.size()));
        table += char(f.type);
        put(table, std::uint64_t(offset + data.size()));
        for (auto d : f.shape) put(table, d);
        data += f.bytes;
    }
    return head + table + data;
}

/// The value of the synthetic material's rgb node (channel c, incidence k, node x, y): distinct everywhere.
inline float syntheticRgb(int k, int c, int x, int y) { return 0.1f + 0.01f * x + 0.02f * y + 0.1f * c + 0.05f * k; }

/// An isotropic RGB material with theta_i = 0, 0.6, pi/2; ndf 2 and sigma 0.5 (so ndf / (4 sigma) = 1); a uniform
/// VNDF (its inverse warp is the identity); rgb nodes syntheticRgb over n x n.
inline std::vector<TensorField> syntheticRgl(int n = 4) {
    const int nTheta = 3, v = 8;
    std::vector<TensorField> f;
    f.push_back({"description", 1, {9}, "synthetic"});
    f.push_back({"jacobian", 1, {1}, std::string(1, '\1')});
    f.push_back({"theta_i", 10, {3}, floatBytes({0.0f, 0.6f, float(M_PI / 2)})});
    f.push_back({"phi_i", 10, {1}, floatBytes({0.0f})});
    f.push_back({"ndf", 10, {2, 8}, floatBytes(std::vector<float>(16, 2.0f))});
    f.push_back({"sigma", 10, {2, 8}, floatBytes(std::vector<float>(16, 0.5f))});
    f.push_back({"vndf",
                 10,
                 {1, std::uint64_t(nTheta), std::uint64_t(v), std::uint64_t(v)},
                 floatBytes(std::vector<float>(std::size_t(nTheta * v * v), 1.0f))});
    f.push_back({"luminance",
                 10,
                 {1, std::uint64_t(nTheta), std::uint64_t(n), std::uint64_t(n)},
                 floatBytes(std::vector<float>(std::size_t(nTheta * n * n), 1.0f))});
    std::vector<float> rgb;
    for (int k = 0; k < nTheta; ++k)
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) rgb.push_back(syntheticRgb(k, c, x, y));
    f.push_back({"rgb", 10, {1, std::uint64_t(nTheta), 3, std::uint64_t(n), std::uint64_t(n)}, floatBytes(rgb)});
    return f;
}

/// The synthetic material with a GGX NDF of roughness `alpha` as its `ndf` table (n theta_m nodes, uniform in
/// sqrt(theta_m / (pi/2)) as the files' are, 2 phi nodes) and GGX's exact projected area cos(theta) (1 + Lambda) as
/// its `sigma`: the NDF a microfacet surface with that roughness would have measured.
inline std::vector<TensorField> syntheticGgxNdf(double alpha, int n = 256) {
    std::vector<TensorField> f = syntheticRgl();
    std::vector<float> ndf, sigma;
    for (int phi = 0; phi < 2; ++phi)
        for (int k = 0; k < n; ++k) {
            const double u = double(k) / (n - 1), theta = 0.5 * M_PI * u * u;
            const double c = std::cos(theta), t2 = std::pow(std::tan(theta), 2), a2 = alpha * alpha;
            const double D = k == n - 1 ? 0.0 : a2 / (M_PI * std::pow(c, 4) * std::pow(a2 + t2, 2));
            const double lambda = k == n - 1 ? 0.0 : 0.5 * (-1.0 + std::sqrt(1.0 + a2 * t2));
            ndf.push_back(float(D));
            sigma.push_back(float(k == n - 1 ? 0.5 * alpha : c * (1.0 + lambda)));  // the limit at 90 deg: alpha / 2
        }
    for (TensorField& t : f)
        if (t.name == "ndf" || t.name == "sigma") {
            t.shape = {2, std::uint64_t(n)};
            t.bytes = floatBytes(t.name == "ndf" ? ndf : sigma);
        }
    return f;
}

/// The synthetic material as a spectral file: its rgb field replaced by `spectra` [1, 3, W, n, n] and `wavelengths`
/// (W samples from 360 to 830 nm), each node's spectrum spectrum(lambda) x syntheticRgb(k, 0, x, y).
template <class Spectrum>
std::vector<TensorField> syntheticSpectral(Spectrum spectrum, int n = 4, int W = 48) {
    std::vector<TensorField> f = syntheticRgl(n);
    std::vector<float> lambda, spectra;
    for (int i = 0; i < W; ++i) lambda.push_back(float(360.0 + 470.0 * i / (W - 1)));
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < W; ++i)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    spectra.push_back(float(spectrum(lambda[size_t(i)]) * syntheticRgb(k, 0, x, y)));
    for (TensorField& t : f)
        if (t.name == "rgb") {
            t.name = "spectra";
            t.shape = {1, 3, std::uint64_t(W), std::uint64_t(n), std::uint64_t(n)};
            t.bytes = floatBytes(spectra);
        }
    f.push_back({"wavelengths", 10, {std::uint64_t(W)}, floatBytes(lambda)});
    return f;
}

/// The field named `name` of `fields` (the test's own list: it is there).
inline TensorField& field(std::vector<TensorField>& fields, const std::string& name) {
    for (auto& f : fields)
        if (f.name == name) return f;
    return fields.front();
}

/// Where the real files are, beside the clone (CI has ../shared; a user's clone does not).
inline std::string sharedMeasured() { return std::string(HILITE_SOURCE_DIR_STR) + "/../shared/data/measured"; }

}  // namespace hilite_test
