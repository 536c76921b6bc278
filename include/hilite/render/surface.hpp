#pragma once
// The plane's surface: flat (the BRDF is evaluated directly) or an explicit bump field of mirror
// facets whose slopes realise the material's NDF (micro/bump_field.hpp), lit by a soft sun.

#include "hilite/core/names.hpp"
#include "hilite/micro/bump_field.hpp"

#include <cstdint>
#include <iosfwd>

namespace hilite::render {

/// How a pixel integrates the bumps it covers.
enum class BumpFilter {
    Auto,         ///< supersample while the centre pixel needs at most kMaxBumpSamples patches per axis, else moments
    Supersample,  ///< S x S Gaussian mirror patches per pixel (exact as the patches shrink)
    Moments,      ///< the footprint's realised slope moments (LEAN mapping): a prefilter, its error measured
};
/// --bump-filter's spellings, in help order.
inline constexpr Named<BumpFilter> kBumpFilters[] = {
    {BumpFilter::Auto, "auto"}, {BumpFilter::Supersample, "supersample"}, {BumpFilter::Moments, "moments"}};
inline const char* toString(BumpFilter f) { return nameIn(kBumpFilters, f); }
std::ostream& operator<<(std::ostream&, BumpFilter);

struct Surface {
    bool bumps = false;         ///< the material's NDF as explicit geometry instead of the analytic BRDF
    double bumpPeriodPx = 4.0;  ///< bump period in pixels of the view, at the image centre, across the view
    uint64_t seed = 1;
    int samples = 0;  ///< sub-pixel samples per axis: 0 = automatic (4 per bump period, at most kMaxSamples)
    double samplesPerPeriod = 4;  ///< automatic: patches per bump period along each axis
    double sunDeg = 0.1;          ///< the sun's angular standard deviation per axis, degrees (Gaussian profile)
    int texels = 1024;            ///< tile resolution
    int bumpsPerTile = 64;        ///< bump periods across the periodic tile
    BumpFilter filter = BumpFilter::Auto;
    bool prefilterCheck = false;  ///< measurements also render the moments prefilter and a second seed (its error)
};
std::ostream& operator<<(std::ostream&, const Surface&);

constexpr int kMaxBumpSamples = 64;  ///< per axis: 4096 patches a pixel at most (llvmpipe: ~5e6 patches/s)
constexpr double kMinBumpPeriodPx = 1.0 / 256, kMaxBumpPeriodPx = 4096;
constexpr double kMinSunDeg = 0.01, kMaxSunDeg = 5.0;

}  // namespace hilite::render
