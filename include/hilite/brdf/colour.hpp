#pragma once
// What a Fresnel term reflects, channel by channel, and the colour of a reflectance: the channels are the
// wavelengths of a measured metal (brdf/spectral.hpp) or, for every other Fresnel mode, the three linear
// sRGB channels. Each channel carries its CIE 1931 XYZ weight under D65 (a reflectance of 1 in every
// channel is the white, Y = 1) and its linear sRGB weight, so a light path that multiplies F per channel at
// each bounce (micro/bounces.hpp) ends in a colour, and a colour in CIELAB chroma C* (CIE 15:2004, sec. 8.2.1).

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <string>
#include <vector>

namespace hilite::brdf {

/// Entries of a channel table over cos theta_d in [0, 1], spaced evenly in sqrt(cos) as the spectral Fresnel
/// table (kFresnelTableSize, brdf/spectral.hpp), read linearly: within 1e-5 of the exact F (the same spacing
/// and size as tests/brdf/test_spectral.cpp measures for gold and copper).
constexpr int kChannelTableSize = 512;

struct ReflectanceChannels {
    std::string description;       ///< "gold: 471 wavelengths 360..830 nm" or "linear sRGB"
    std::vector<double> lambdaNm;  ///< per channel: its wavelength (spectral), empty for sRGB channels
    std::vector<dvec3> xyz;     ///< per channel: CIE XYZ weight under D65; summed over the channels, the white (Y = 1)
    std::vector<dvec3> rgb;     ///< per channel: linear sRGB weight; each of R, G, B sums to 1 over the channels
    std::vector<double> table;  ///< F per channel at kChannelTableSize angles, entry-major

    size_t size() const { return xyz.size(); }
    /// F per channel at cos theta_d (clamped to [0, 1]) into out[0 .. size()): the table, linear in sqrt(cos).
    void fresnel(double cosTheta_d, double* out) const;
};

/// The channels of p's Fresnel: spectral -> the spectrum's wavelengths (p.spectrum), otherwise three linear
/// sRGB channels with p's per-channel F (none: 1).
ReflectanceChannels reflectanceChannels(const Params& p);

/// A reflectance's colour: XYZ (Y = 1 for white), linear sRGB, chromaticity xy, CIELAB against the white
/// (D65, Y = 1), chroma C* = sqrt(a*^2 + b*^2), saturation s = C* / L*, and the distance from the white in xy.
struct Colour {
    dvec3 xyz{0.0}, rgb{0.0};
    double x = 0, y = 0, L = 0, a = 0, b = 0, chroma = 0, saturation = 0, xyFromWhite = 0;
};
Colour colourOf(const std::vector<double>& reflectance, const ReflectanceChannels& c);
/// The colour of a linear sRGB reflectance (white (1, 1, 1)): through the IEC 61966-2-1 matrix to XYZ.
Colour colourOfRgb(const dvec3& rgb);
/// CIELAB of XYZ against the white XYZ (CIE 15:2004 eq. 8.1-8.3): L*, a*, b*.
dvec3 labFromXyz(const dvec3& xyz, const dvec3& white);

}  // namespace hilite::brdf
