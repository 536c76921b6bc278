#pragma once
// Light that bounces more than once, followed path by path:
//  - traceBounces: rays traced on an explicit Gaussian height field (a Beckmann bump field, micro/bump_field.hpp)
//    from a distant light at theta_i until they leave, each bounce a mirror reflection that multiplies the
//    Fresnel of its channels (brdf/colour.hpp: a metal's wavelengths, or sRGB). The surface is the C1 bicubic
//    Hermite interpolant of the field's heights and slopes at the texel centres, so the normal a ray reflects
//    about is the gradient of the very surface it hit (a bilinear height with interpolated slopes is not: see
//    docs/bounces.md), rescaled so that its mean |grad h|^2 is m^2.
//  - walkSmithBounces: the same light on Smith's microsurface, Beckmann with the exact Lambda: the random walk
//    of Heitz, Hanika, d'Eon & Dachsbacher 2016 ("Multiple-scattering microfacet BSDFs with the Smith
//    model", SIGGRAPH; uniform height distribution, visible normals sampled as Heitz & d'Eon 2014). Its first
//    order is the single-scattering BRDF with height-correlated G2: what Kulla & Conty's E(mu) integrates.
// Both tally, per bounce order k (1 .. kMaxReportedOrder, and the rest together), the energy that leaves
// with F = 1 and the reflectance per channel, over independent batches whose spread gives one standard error.
// Deterministic for a seed: every batch has its own engine, whichever thread runs it.

#include "hilite/brdf/colour.hpp"
#include "hilite/micro/bump_field.hpp"

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace hilite::micro {

/// Orders reported one by one; order kMaxReportedOrder + 1 holds every higher order together.
constexpr int kMaxReportedOrder = 4;
/// A path still inside the surface after this many bounces is counted as stuck (light the tally loses).
constexpr int kMaxBounces = 100;

/// The surface traceBounces reflects on.
enum class TracedSurface {
    Hermite,   ///< the C1 bicubic Hermite surface: normals are the gradient of the surface hit (the default)
    Bilinear,  ///< diagnostic: the render's field, bilinear heights with the bilinear slopes as normals (not
               ///< the gradient of those heights: see docs/bounces.md for what that costs)
};
const char* toString(TracedSurface);
std::optional<TracedSurface> parseTracedSurface(const std::string&);

/// Bins of the first reflection's direction (BounceTally::firstExitShare): down, then cos(theta_o) in tenths.
constexpr int kExitBins = 11;

struct BounceOptions {
    TracedSurface surface = TracedSurface::Hermite;
    long paths = 100000;       ///< light paths, split evenly into `batches`
    int batches = 16;          ///< independent batches (their spread is the noise)
    uint64_t seed = 1;         ///< the paths' seed (the field has its own, BumpSpec::seed)
    double stepTexels = 0.25;  ///< traced: the march step along the ray, in texels
};
std::ostream& operator<<(std::ostream&, const BounceOptions&);

/// One order's (or one sum's) mean over the batches and one standard error of it.
struct Estimate {
    double value = 0, error = 0;
};

/// The tally of one incidence. Index 0 .. kMaxReportedOrder - 1 is order 1 .. kMaxReportedOrder, index
/// kMaxReportedOrder the higher orders together.
struct BounceTally {
    double thetaDeg = 0;
    long paths = 0;
    std::vector<Estimate> energy;                ///< share of the light that leaves after k bounces, F = 1
    std::vector<std::vector<double>> reflected;  ///< [order][channel]: light that leaves after k bounces, with F
    std::vector<brdf::Colour> colour;    ///< [order]: the colour of that light, reflected / energy (its mean F product)
    std::vector<Estimate> chroma;        ///< [order]: C* of that colour, the spread over the batches as its error
    Estimate multiple;                   ///< energy of orders >= 2, F = 1
    Estimate total;                      ///< every order, F = 1 (1 - stuck)
    Estimate stuck;                      ///< paths still inside after kMaxBounces (and rays lost to a bad hit)
    std::vector<Estimate> reflectedRgb;  ///< [R, G, B]: the albedo with F, every order, linear sRGB
    Estimate reflectedY;                 ///< the albedo with F, every order, luminance of reflectedRgb
    long backHits = 0;                   ///< traced: hits on a facet facing away from the ray (should be 0)
    /// Where the first reflection goes, by exitBin (bin 0: down, wo.z < 0; bin i >= 1: cos(theta_o) in
    /// [(i - 1), i) / (kExitBins - 1)): its share of the light, and the share of that which leaves at once.
    std::vector<double> firstExitShare, firstExitEscape;
};

/// Told as work finishes, one call at a time: `done` of `total` parts of `stage` (batches of paths; 0 of 1,
/// then 1 of 1, for a step in one piece). For a progress line (a 4096^2 study runs for minutes); may be empty.
using BounceProgress = std::function<void(const std::string& stage, long done, long total)>;

/// Rays on the height field of `f` (Beckmann fields only, paths >= batches >= 2: InputError otherwise).
BounceTally traceBounces(const BumpField& f, double thetaDeg, const brdf::ReflectanceChannels& channels,
                         const BounceOptions& o, const BounceProgress& progress = {});
/// The random walk on Smith's Beckmann microsurface of rms slope m.
BounceTally walkSmithBounces(double m, double thetaDeg, const brdf::ReflectanceChannels& channels,
                             const BounceOptions& o, const BounceProgress& progress = {});

/// The traced surface's realised rms slope before the rescale, over m (the Hermite surface against the
/// bilinear one the field is normalized on; 1.01-1.02 at 16 texels a bump period).
double hermiteSlopeRatio(const BumpField& f);

}  // namespace hilite::micro
