#include "hilite/micro/bump_field.hpp"

#include "micro/fft.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <random>
#include <tuple>

namespace hilite::micro {

const char* toString(BumpKind k) {
    switch (k) {
        case BumpKind::None: return "none";
        case BumpKind::Beckmann: return "beckmann";
        case BumpKind::GGX: return "ggx";
    }
    return "?";
}

std::optional<BumpKind> parseBumpKind(const std::string& s) {
    for (BumpKind k : {BumpKind::None, BumpKind::Beckmann, BumpKind::GGX})
        if (s == toString(k)) return k;
    return std::nullopt;
}

std::ostream& operator<<(std::ostream& os, BumpKind k) { return os << toString(k); }

bool BumpSpec::operator<(const BumpSpec& o) const {
    return std::tie(kind, roughness, seed, texels, bumpsPerTile) <
           std::tie(o.kind, o.roughness, o.seed, o.texels, o.bumpsPerTile);
}

std::ostream& operator<<(std::ostream& os, const BumpSpec& s) {
    return os << "bumps=" << s.kind << " roughness=" << s.roughness << " seed=" << s.seed << " texels=" << s.texels
              << " bumps_per_tile=" << s.bumpsPerTile;
}

namespace {

/// Standard normal pairs by Box-Muller on the engine's raw 64-bit output: std::normal_distribution is not
/// specified bit for bit, and the field must be the same on every standard library.
struct Gaussian {
    std::mt19937_64 engine;
    explicit Gaussian(uint64_t seed) : engine(seed) {}
    double uniform() { return (double(engine() >> 11) + 0.5) * 0x1.0p-53; }  // (0, 1), never 0
    std::pair<double, double> pair() {
        const double r = std::sqrt(-2.0 * std::log(uniform())), a = 2.0 * kPi * uniform();
        return {r * std::cos(a), r * std::sin(a)};
    }
};

/// Radial slope remap of unit-Rayleigh slopes (mean |s|^2 = 1) onto GGX with width alpha: the CDF
/// 1 - exp(-r^2) carried to r'^2 / (alpha^2 + r'^2), i.e. r' = alpha sqrt(expm1(r^2)). Returns r'/r and dr'/dr.
std::pair<double, double> ggxRemap(double r, double alpha) {
    if (r < 1e-8) return {alpha, alpha};  // r' = alpha r (1 + r^2/4 + ...): the ratio is alpha to 1e-16
    const double e = std::expm1(r * r), rp = alpha * std::sqrt(e);
    return {rp / r, alpha * r * (e + 1.0) / std::sqrt(e)};
}

/// Mean over the periodic tile of the square of the bilinear interpolation of texel values a (texel centres
/// at (i + 0.5) / n): what the render samples. Per axis a linear element gives (a0^2 + a0 a1 + a1^2) / 3 per
/// cell, i.e. weights c(0) = 2/3, c(+-1) = 1/6 on the autocorrelation at lag 0, +-1; in 2D their product.
template <class Get>
double bilinearMeanSquare(int n, Get a) {
    const double c[3] = {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0};
    double sum = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    sum += c[dx + 1] * c[dy + 1] * a(i, j) * a((i + dx + n) % n, (j + dy + n) % n);
    return sum / (double(n) * double(n));
}

}  // namespace

BumpField makeBumpField(const BumpSpec& spec) {
    BumpField f;
    f.spec = spec;
    const int n = f.n = spec.texels;
    const size_t nn = size_t(n) * size_t(n);
    const double K = spec.bumpsPerTile, sigmaK = 0.25 * K;  // ring spectrum: centre K, width K/4 cycles/tile
    std::vector<Complex> c(nn);
    Gaussian g(spec.seed);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double fx = i < n / 2 ? i : i - n, fy = j < n / 2 ? j : j - n, fr = std::hypot(fx, fy);
            const auto [a, b] = g.pair();
            const double amp = fr == 0.0 ? 0.0 : std::exp(-0.25 * (fr - K) * (fr - K) / (sigmaK * sigmaK));
            c[size_t(j) * size_t(n) + size_t(i)] = amp * Complex(a, b);
        }
    // Each quantity is the real part of the inverse transform of the spectrum times its derivative factor.
    auto field = [&](auto factor) {
        std::vector<Complex> d(nn);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double fx = i < n / 2 ? i : i - n, fy = j < n / 2 ? j : j - n;
                d[size_t(j) * size_t(n) + size_t(i)] = c[size_t(j) * size_t(n) + size_t(i)] * factor(fx, fy);
            }
        fft2d(d, n, true);
        std::vector<double> out(nn);
        for (size_t k = 0; k < nn; ++k) out[k] = d[k].real();
        return out;
    };
    const Complex I(0.0, 2.0 * kPi);
    const auto h = field([](double, double) { return Complex(1.0); });
    const auto hx = field([&](double fx, double) { return I * fx; });
    const auto hy = field([&](double, double fy) { return I * fy; });
    const auto hxx = field([&](double fx, double) { return I * I * fx * fx; });
    const auto hxy = field([&](double fx, double fy) { return I * I * fx * fy; });
    const auto hyy = field([&](double, double fy) { return I * I * fy * fy; });
    const bool curvature = spec.kind != BumpKind::GGX;  // the remapped normal map has no height to differentiate
    const std::vector<double> none;
    const auto hxxx = curvature ? field([&](double fx, double) { return I * I * I * fx * fx * fx; }) : none;
    const auto hxxy = curvature ? field([&](double fx, double fy) { return I * I * I * fx * fx * fy; }) : none;
    const auto hxyy = curvature ? field([&](double fx, double fy) { return I * I * I * fx * fy * fy; }) : none;
    const auto hyyy = curvature ? field([&](double, double fy) { return I * I * I * fy * fy * fy; }) : none;
    // The mean |s|^2 of the field as rendered (bilinear between texel centres: ~3% below the texel centres'
    // own mean square for 16 texels a bump period).
    auto at = [n](const std::vector<double>& v) {
        return [&v, n](int i, int j) { return v[size_t(j) * size_t(n) + size_t(i)]; };
    };
    const double msq = bilinearMeanSquare(n, at(hx)) + bilinearMeanSquare(n, at(hy));
    // Beckmann: realised mean |s|^2 = m^2 exactly. GGX: unit-Rayleigh slopes first, then the remap.
    const double scale = (spec.kind == BumpKind::GGX ? 1.0 : spec.roughness) / std::sqrt(msq);
    f.tex0.resize(4 * nn);
    f.tex1.resize(4 * nn);
    f.tex2.assign(4 * nn, 0.f);
    f.heightMin = 1e300, f.heightMax = -1e300;
    for (size_t k = 0; k < nn; ++k) {
        dvec2 s(scale * hx[k], scale * hy[k]);
        double J[4] = {scale * hxx[k], scale * hxy[k], scale * hxy[k], scale * hyy[k]};
        if (spec.kind == BumpKind::GGX) {
            // s' = (r'/r) s: ds'/ds = (r'/r) I + (dr'/dr - r'/r) shat shat^T, then J' = (ds'/ds) J.
            const double r = glm::length(s);
            const auto [ratio, deriv] = ggxRemap(r, spec.roughness);
            const dvec2 u = r > 0 ? s / r : dvec2(1, 0);
            const double A[4] = {ratio + (deriv - ratio) * u.x * u.x, (deriv - ratio) * u.x * u.y,
                                 (deriv - ratio) * u.x * u.y, ratio + (deriv - ratio) * u.y * u.y};
            const double Jn[4] = {A[0] * J[0] + A[1] * J[2], A[0] * J[1] + A[1] * J[3], A[2] * J[0] + A[3] * J[2],
                                  A[2] * J[1] + A[3] * J[3]};
            std::copy(Jn, Jn + 4, J);
            s *= ratio;
        }
        const double hk = scale * h[k] * (spec.kind == BumpKind::GGX ? spec.roughness : 1.0);
        f.heightMin = std::min(f.heightMin, hk), f.heightMax = std::max(f.heightMax, hk);
        const float t0[4] = {float(s.x), float(s.y), float(J[0]), float(J[1])};
        const float t1[4] = {float(J[2]), float(J[3]), float(hk), 0.f};
        std::copy(t0, t0 + 4, f.tex0.begin() + long(4 * k));
        std::copy(t1, t1 + 4, f.tex1.begin() + long(4 * k));
        if (curvature)
            for (int q = 0; q < 4; ++q)
                f.tex2[4 * k + size_t(q)] = float(scale * (q == 0 ? hxxx : q == 1 ? hxxy : q == 2 ? hxyy : hyyy)[k]);
    }
    return f;
}

const BumpField& cachedBumpField(const BumpSpec& spec) {
    static std::mutex mutex;
    static std::map<BumpSpec, std::unique_ptr<BumpField>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = cache[spec];
    if (!slot) slot = std::make_unique<BumpField>(makeBumpField(spec));
    return *slot;
}

namespace {

/// Bilinear weights and the four texel indices around (x, y) (tile lengths), texel centres at (i + 0.5) / n.
struct Bilinear {
    size_t k00, k10, k01, k11;
    double fx, fy;
};
Bilinear bilinear(int n, double x, double y) {
    const double u = x * n - 0.5, v = y * n - 0.5;
    const double iu = std::floor(u), iv = std::floor(v);
    auto wrap = [n](double i) { return size_t(((long(i) % n) + n) % n); };
    const size_t i0 = wrap(iu), i1 = wrap(iu + 1), j0 = wrap(iv), j1 = wrap(iv + 1);
    return {j0 * size_t(n) + i0, j0 * size_t(n) + i1, j1 * size_t(n) + i0, j1 * size_t(n) + i1, u - iu, v - iv};
}

double lerp2(const std::vector<float>& t, const Bilinear& b, int c) {
    const double a = t[4 * b.k00 + size_t(c)] + b.fx * (t[4 * b.k10 + size_t(c)] - t[4 * b.k00 + size_t(c)]);
    const double d = t[4 * b.k01 + size_t(c)] + b.fx * (t[4 * b.k11 + size_t(c)] - t[4 * b.k01 + size_t(c)]);
    return a + b.fy * (d - a);
}

}  // namespace

BumpSample BumpField::sample(double x, double y) const {
    const Bilinear b = bilinear(n, x, y);
    BumpSample s;
    s.s = {lerp2(tex0, b, 0), lerp2(tex0, b, 1)};
    s.Jxx = lerp2(tex0, b, 2), s.Jxy = lerp2(tex0, b, 3);
    s.Jyx = lerp2(tex1, b, 0), s.Jyy = lerp2(tex1, b, 1);
    s.h = lerp2(tex1, b, 2);
    s.hxxx = lerp2(tex2, b, 0), s.hxxy = lerp2(tex2, b, 1), s.hxyy = lerp2(tex2, b, 2), s.hyyy = lerp2(tex2, b, 3);
    return s;
}

double BumpField::height(double x, double y) const { return lerp2(tex1, bilinear(n, x, y), 2); }

SlopeStats slopeStats(const BumpField& f) {
    SlopeStats st;
    const int n = f.n;
    const double a = f.spec.roughness;
    auto comp = [&f, n](int c) {
        return [&f, n, c](int i, int j) { return double(f.tex0[4 * (size_t(j) * size_t(n) + size_t(i)) + size_t(c)]); };
    };
    st.rmsX = std::sqrt(bilinearMeanSquare(n, comp(0))), st.rmsY = std::sqrt(bilinearMeanSquare(n, comp(1)));
    // The radial CDF of the target: Beckmann 1 - exp(-r^2/m^2), GGX r^2 / (a^2 + r^2).
    auto cdf = [&](double r) {
        return f.spec.kind == BumpKind::GGX ? r * r / (a * a + r * r) : -std::expm1(-r * r / (a * a));
    };
    // The rendered field at 2 x 2 stratified points of every cell between texel centres.
    std::vector<double> u;
    u.reserve(4 * size_t(n) * size_t(n));
    double maxR = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (int q = 0; q < 4; ++q) {
                const BumpSample b = f.sample((i + 0.75 + 0.5 * (q % 2)) / n, (j + 0.75 + 0.5 * (q / 2)) / n);
                const double r = glm::length(b.s);
                maxR = std::max(maxR, r);
                u.push_back(cdf(r));
            }
    st.maxSlopeDeg = rad2deg(std::atan(maxR));
    std::sort(u.begin(), u.end());
    st.binShares.assign(8, 0.0);
    const size_t N = u.size();
    for (size_t k = 0; k < N; ++k) {
        // KS: the empirical CDF jumps from k/N to (k+1)/N at u[k]; the target CDF there is u[k].
        st.ks = std::max({st.ks, std::abs(u[k] - double(k) / double(N)), std::abs(u[k] - double(k + 1) / double(N))});
        st.binShares[std::min<size_t>(7, size_t(u[k] * 8.0))] += 1.0 / double(N);
    }
    return st;
}

std::ostream& operator<<(std::ostream& os, const SlopeStats& s) {
    os << "rms slope x=" << s.rmsX << " y=" << s.rmsY << " KS=" << s.ks << " max tilt=" << s.maxSlopeDeg
       << " deg, shares of 8 equal-probability |s| bins:";
    for (double b : s.binShares) os << " " << b;
    return os;
}

}  // namespace hilite::micro
