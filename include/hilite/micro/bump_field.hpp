#pragma once
// Explicit micro-geometry: a seeded, periodic random bump field on the plane, made on the CPU.
// The field is a Gaussian random height field h(x, y) on one square tile (periodic, so it repeats
// seamlessly), synthesized by FFT from a ring spectrum centred on `bumpsPerTile` cycles per tile: its bumps
// have a dominant period of 1 / bumpsPerTile tiles. A Gaussian field has Gaussian slopes, i.e. exactly the
// Beckmann slope distribution P22(s) = exp(-|s|^2 / m^2) / (pi m^2); the slopes are scaled so that the
// realised mean |s|^2 over the tile of the field as rendered (bilinear between texel centres) is m^2 exactly
// (Beckmann & Spizzichino 1963; Walter et al. 2007).
// GGX slopes (P22 = 1 / (pi a^2 (1 + |s|^2/a^2)^2)) come from the same field by a radial remapping of each
// slope (the Rayleigh CDF of |s| onto the GGX one): a normal map whose slope histogram is GGX, but which
// is no longer the gradient of a height field, so masking is traced on Beckmann fields only.
//
// Storage (the texture the shader reads, and the CPU twin): per texel, at its centre ((i + 0.5) / n),
//   tex0 = (s_x, s_y, J_xx, J_xy), tex1 = (J_yx, J_yy, h, 0), tex2 = (h_xxx, h_xxy, h_xyy, h_yyy),
// s the slope (m = normalize(-s_x, -s_y, 1)), J = ds/dx per tile length (the Hessian of h for Beckmann),
// h the height in tile lengths, tex2 the third derivatives of h (the slope's curvature; 0 for GGX normal maps),
// which give a patch's mean slope to second order. Values between texel centres are bilinear, wrapping.

#include "hilite/core/math.hpp"

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace hilite::micro {

enum class BumpKind {
    None,      ///< a flat mirror-smooth plane: the BRDF is evaluated directly (no micro-geometry)
    Beckmann,  ///< Gaussian random height field: Gaussian (Beckmann) slopes, rms |s| = roughness
    GGX,       ///< the same field's slopes remapped radially to the GGX slope distribution (a normal map)
};
const char* toString(BumpKind);
std::optional<BumpKind> parseBumpKind(const std::string&);
std::ostream& operator<<(std::ostream&, BumpKind);

struct BumpSpec {
    BumpKind kind = BumpKind::None;
    double roughness = 0.1;  ///< Beckmann m / GGX alpha of the slope distribution
    uint64_t seed = 1;       ///< the random field's seed (std::mt19937_64)
    int texels = 1024;       ///< tile resolution, a power of two in [64, 4096]
    int bumpsPerTile = 64;   ///< centre of the ring spectrum, cycles per tile; texels / bumpsPerTile >= 8
    bool operator<(const BumpSpec& o) const;
};
std::ostream& operator<<(std::ostream&, const BumpSpec&);

/// One point of the field: slope, its derivative per tile length, height (tile lengths).
struct BumpSample {
    dvec2 s{0.0};
    double Jxx = 0, Jxy = 0, Jyx = 0, Jyy = 0;
    double h = 0;
    double hxxx = 0, hxxy = 0, hxyy = 0, hyyy = 0;  ///< third derivatives of h: the slope's second derivatives
};

struct BumpField {
    BumpSpec spec;
    int n = 0;
    std::vector<float> tex0, tex1, tex2;  ///< 4 floats per texel each, row-major, row y = j
    double heightMin = 0, heightMax = 0;

    /// Bilinear at (x, y) in tile lengths (any real: the tile repeats). The twin of bumpSample() in GLSL.
    BumpSample sample(double x, double y) const;
    /// Height alone (bilinear), for ray marching.
    double height(double x, double y) const;
};

/// Makes the field (~0.5 s for 1024^2). Deterministic: the same spec gives the same floats on every machine.
BumpField makeBumpField(const BumpSpec& spec);
/// The field of `spec`, made once per process and kept (a few fields at most are ever in use).
const BumpField& cachedBumpField(const BumpSpec& spec);

/// How well the realised slopes follow the target distribution: the field as rendered (bilinear between the
/// texel centres), rms exactly, the distribution at 2 x 2 stratified points of every cell.
struct SlopeStats {
    double rmsX = 0,
           rmsY = 0;  ///< realised sqrt(mean s_x^2), sqrt(mean s_y^2); target roughness / sqrt(2) each (Beckmann)
    double ks = 0;    ///< Kolmogorov-Smirnov distance of the radial CDF from the target's
    std::vector<double> binShares;  ///< share of points in each of 8 equal-probability bins of |s| (target 1/8 each)
    double maxSlopeDeg = 0;         ///< steepest facet's tilt theta_m
};
SlopeStats slopeStats(const BumpField& f);
std::ostream& operator<<(std::ostream&, const SlopeStats&);

}  // namespace hilite::micro
