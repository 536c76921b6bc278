#include "hilite/brdf/colour.hpp"

#include "brdf/spectral.hpp"
#include "hilite/brdf/terms.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace hilite::brdf {

namespace {

/// Linear sRGB -> XYZ, IEC 61966-2-1:1999 (D65 white), columns R, G, B: the XYZ weight of each sRGB channel.
constexpr double kSrgbToXyz[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};

/// F per channel at cos theta_d, exactly (the table's entries).
std::vector<double> exactFresnel(const Params& p, double c) {
    switch (p.fresnel) {
        case Fresnel::Spectral: {
            std::vector<double> f(p.spectrum->size());
            for (size_t i = 0; i < f.size(); ++i) f[i] = F_Conductor(c, p.spectrum->eta[i], p.spectrum->k[i]);
            return f;
        }
        case Fresnel::Schlick: {
            const dvec3 f = F_Schlick(p.f0, c);
            return {f.x, f.y, f.z};
        }
        case Fresnel::Dielectric: return {F_Dielectric(c, p.eta.x), F_Dielectric(c, p.eta.y), F_Dielectric(c, p.eta.z)};
        case Fresnel::Conductor:
            return {F_Conductor(c, p.eta.x, p.k.x), F_Conductor(c, p.eta.y, p.k.y), F_Conductor(c, p.eta.z, p.k.z)};
        case Fresnel::None: break;
    }
    return {1.0, 1.0, 1.0};
}

}  // namespace

void ReflectanceChannels::fresnel(double cosTheta_d, double* out) const {
    const size_t n = size();
    const double cd = cosTheta_d > 0.0 ? std::min(cosTheta_d, 1.0) : 0.0;  // NaN reads as grazing, not as an int
    const double x = std::sqrt(cd) * (kChannelTableSize - 1);
    const int i = std::min(int(x), kChannelTableSize - 2);
    const double t = x - double(i);
    const double* a = table.data() + size_t(i) * n;
    const double* b = a + n;
    for (size_t c = 0; c < n; ++c) out[c] = a[c] + t * (b[c] - a[c]);
}

ReflectanceChannels reflectanceChannels(const Params& p) {
    ReflectanceChannels ch;
    std::ostringstream d;
    if (p.fresnel == Fresnel::Spectral && p.spectrum) {
        const Spectrum& s = *p.spectrum;
        ch.lambdaNm = s.lambdaNm;
        ch.xyz = s.xyzWeight;
        ch.rgb = s.weight;
        d << s.name << ": " << s.size() << " wavelengths " << s.lambdaNm.front() << ".." << s.lambdaNm.back()
          << " nm (CIE 1931 2-degree, D65)";
    } else {
        for (int c = 0; c < 3; ++c) {
            ch.xyz.emplace_back(kSrgbToXyz[0][c], kSrgbToXyz[1][c], kSrgbToXyz[2][c]);
            ch.rgb.push_back(dvec3(0.0));
            ch.rgb.back()[c] = 1.0;
        }
        d << "linear sRGB (fresnel=" << p.fresnel << ")";
    }
    ch.description = d.str();
    ch.table.reserve(size_t(kChannelTableSize) * ch.size());
    for (int i = 0; i < kChannelTableSize; ++i) {
        const double u = double(i) / (kChannelTableSize - 1);  // sqrt(cos theta_d)
        const std::vector<double> f = exactFresnel(p, u * u);
        ch.table.insert(ch.table.end(), f.begin(), f.end());
    }
    return ch;
}

dvec3 labFromXyz(const dvec3& xyz, const dvec3& white) {
    // f(t) = t^(1/3) above (6/29)^3, its linear continuation below (CIE 15:2004 eq. 8.3).
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(xyz.x / white.x), fy = f(xyz.y / white.y), fz = f(xyz.z / white.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Colour colourOfRgb(const dvec3& rgb) {
    static const ReflectanceChannels srgb = reflectanceChannels(Params{});  // fresnel none: the sRGB channels
    return colourOf({rgb.x, rgb.y, rgb.z}, srgb);
}

Colour colourOf(const std::vector<double>& reflectance, const ReflectanceChannels& c) {
    Colour out;
    dvec3 white(0.0);
    for (size_t i = 0; i < c.size(); ++i) {
        out.xyz += reflectance[i] * c.xyz[i];
        out.rgb += reflectance[i] * c.rgb[i];
        white += c.xyz[i];
    }
    const double sum = out.xyz.x + out.xyz.y + out.xyz.z, whiteSum = white.x + white.y + white.z;
    if (sum > 0) out.x = out.xyz.x / sum, out.y = out.xyz.y / sum;
    const double xw = white.x / whiteSum, yw = white.y / whiteSum;
    out.xyFromWhite = sum > 0 ? std::hypot(out.x - xw, out.y - yw) : 0.0;
    const dvec3 lab = labFromXyz(out.xyz, white);
    out.L = lab.x, out.a = lab.y, out.b = lab.z;
    out.chroma = std::hypot(out.a, out.b);
    out.saturation = out.L > 0 ? out.chroma / out.L : 0.0;
    return out;
}

}  // namespace hilite::brdf
