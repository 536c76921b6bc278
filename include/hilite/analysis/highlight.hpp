#pragma once
// The highlight measurement of ../shared/notes/measurement.md: the region {L >= frac * peak} in the
// azimuthal-equidistant chart (u, v) about the mirror direction, reduced to the ellipse with the same
// area moments. Two implementations share the definition and the ellipse fit:
//   - measureImage: the GL measurement view, pixel by pixel (each pixel in or out, weighted by its (u,v) area);
//   - measureReference: a double-precision oracle on an analytic lobe (polar contour about the peak).
// Depends on core only: no GL, no BRDF.

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <iosfwd>
#include <limits>
#include <vector>

namespace hilite::analysis {

/// Diagnostics that qualify (or replace) the numbers.
enum class Flag {
    Clipped,        ///< the region touches the image border: it may continue outside the frame
    HorizonCut,     ///< the region ends at the horizon (we.z = 0) rather than at the threshold
    UnderResolved,  ///< fewer than Options::minPixelsAcross pixels across the minor axis
    NoHighlight,    ///< peak is 0 (or nothing visible): the shape fields are left 0
    CoversFrame,    ///< every visible pixel is in the region: the frame shows no outside
    Mirror,         ///< a perfect mirror (roughness 0): the lobe is a delta with no finite shape; fields left 0
    /// the lobe's half-width is below what float32 directions resolve (measurement/diagnose.hpp): the GL
    /// numbers are reported but quantization-limited; the double reference still measures it
    EffectivelyMirror,
    /// the lobe grows without bound towards the horizon (G = 1: f ~ 1 / cos(theta_o)), so it has no peak and
    /// no half-maximum region: the numbers describe where the sampling stopped, not the lobe
    UnboundedAtHorizon,
    /// reference only: the region is not star-shaped about its peak (a ring, two lobes), so the polar
    /// contour from the peak misses part of it; the GL pixels have no such assumption
    NotStarShaped,
    /// the survey of the hemisphere found parts of the region that this measurement did not measure (a
    /// part no view could frame): the numbers describe the measured parts only
    PartsNotMeasured,
    /// reference only: the scan lines' adaptive quadrature ran out of its budget before its tolerance (a lobe
    /// far thinner than any box the survey could give it): the numbers are the last estimate
    NotConverged,
    /// a sphere or disk light: the GL rule's points over the light are too sparse for the lobe (its radiance
    /// differs from the exact integral by more than 1% of the peak: light_rule_error); raise --light-rings
    LightUndersampled,
    /// the radiance left float32's range: pixels hold inf or NaN (an infinite peak, or f, L or a product of them
    /// above 3.4e38), or the double twin's peak is above it; the shape fields are not measured (NaN, null in rows)
    FloatOverflow,
    /// the region's level (threshold x peak) is below the smallest normal float32 (1.2e-38): the pixels hold 0 or
    /// denormals there, not the lobe; the shape fields are not measured (NaN, null in rows)
    FloatUnderflow,
    /// the peak lies on the horizon (the lobe still rises there) and the chart's u or v line through it leaves
    /// the visible hemisphere on both sides at the peak: the width along that line (fwhm_u or fwhm_v) is not a
    /// property of the lobe (0 in the limit, and any pixel's offset from the horizon changes it by degrees), so it
    /// is null; the region's ellipse (aspect, axes, area, centroid) is measured as usual
    PeakOnHorizon,
    /// lobe = mirror: no lobe holds the mirror direction. The climb from the mirror direction ends at a maximum
    /// (or on the horizon) whose region at threshold x its value leaves the mirror direction out, or the region
    /// reaches the threshold on no ray (a flat radiance); the shape fields are not measured (NaN, null in rows)
    NoMirrorLobe,
    /// lobe = mirror: on some rays from the peak the radiance falls to a valley and rises again (towards a
    /// brighter part: the strip above the horizon) before it reaches the threshold; there the region ends at the
    /// valley's floor
    SaddleCut,
};

/// "clipped", "horizon_cut", "under_resolved", "no_highlight", "covers_frame", "mirror",
/// "effectively_mirror", "unbounded_at_horizon", "not_star_shaped", ..., "float_overflow", "float_underflow" (the
/// CLI/JSON spelling).
const char* toString(Flag);
std::ostream& operator<<(std::ostream&, Flag);

/// A shape's flags: each flag at most once, in the order they were raised (the order the row lists them in).
class FlagSet {
public:
    FlagSet() = default;
    FlagSet(std::initializer_list<Flag> flags) {
        for (Flag f : flags) insert(f);
    }
    bool has(Flag f) const { return std::find(m_flags.begin(), m_flags.end(), f) != m_flags.end(); }
    /// Adds `f` after the others; nothing if it is there already.
    void insert(Flag f) {
        if (!has(f)) m_flags.push_back(f);
    }
    void erase(Flag f) { m_flags.erase(std::remove(m_flags.begin(), m_flags.end(), f), m_flags.end()); }
    bool empty() const { return m_flags.empty(); }
    size_t size() const { return m_flags.size(); }
    std::vector<Flag>::const_iterator begin() const { return m_flags.begin(); }
    std::vector<Flag>::const_iterator end() const { return m_flags.end(); }
    bool operator==(const FlagSet& o) const { return m_flags == o.m_flags; }
    bool operator!=(const FlagSet& o) const { return m_flags != o.m_flags; }

private:
    std::vector<Flag> m_flags;
};

/// Which highlight is measured (measurement.lobe, --lobe).
enum class Lobe {
    All,     ///< the region {L >= threshold * global peak}, every part of it (../shared/notes/measurement.md)
    Mirror,  ///< the lobe around the mirror direction: docs/measurement.md, "The lobe around the mirror direction"
};
/// "all", "mirror".
const char* toString(Lobe);

struct Options {
    double threshold = 0.5;   ///< frac: region = L >= threshold * peak, in (0, 1)
    Lobe lobe = Lobe::All;    ///< which highlight; measureImage and the analytic references measure what they are
                              ///< given (the measurement layer masks the mirror lobe's rivals before)
    int minPixelsAcross = 8;  ///< under-resolved below this many pixels across the minor axis (full width 2*minor)
    /// measureImage only. true: a pixel the contour crosses counts with its covered fraction, estimated from
    /// a straight contour through the pixel located by linear interpolation of L (errors O(pixel^2)).
    /// false: each pixel counts whole or not at all by the L at its centre (lattice noise of ~pixel^1.5).
    bool subpixel = true;
    /// measureImage and the Supersampler: > 0 sets the region's level L >= level outright (the global peak
    /// x threshold, known from another view: a part of a region in several parts measured in a view of its
    /// own); 0: threshold x the image's own peak.
    double level = 0;
};
std::ostream& operator<<(std::ostream&, const Options&);
/// Throws InputError unless threshold is in (0, 1) and minPixelsAcross >= 1 (both measure functions call it).
void validate(const Options&);

/// Zeroth, first and central second area moments of a region in the (u,v) plane (radians).
struct AreaMoments {
    double area = 0;                   ///< M0 (rad^2)
    double mean_u = 0, mean_v = 0;     ///< centroid (rad)
    double cuu = 0, cuv = 0, cvv = 0;  ///< central second moments / M0 (rad^2)
};

/// The moments of the union of two disjoint regions (parallel-axis theorem).
AreaMoments combine(const AreaMoments& a, const AreaMoments& b);

/// One connected part of the region, with its own ellipse (the same definition, on the part alone).
struct PartShape {
    double aspect = 0, eccentricity = 0, major_deg = 0, minor_deg = 0, orientation_deg = 0;
    double centroid_u_deg = 0, centroid_v_deg = 0, area_deg2 = 0;
    bool horizon_cut = false;  ///< the horizon bounds this part
    bool holds_peak = false;   ///< the global peak lies in it
    bool measured = true;      ///< false: found by the survey but not measured (see Flag::PartsNotMeasured)
    AreaMoments moments;       ///< radians
};

/// The measured highlight. Angles in degrees, relative to the mirror direction (u = v = 0).
struct Shape {
    double peak = 0;                        ///< largest L
    double peak_u_deg = 0, peak_v_deg = 0;  ///< where it is (image: the peak pixel's centre)
    double aspect = 0, eccentricity = 0;    ///< sqrt(lmin/lmax), sqrt(1 - lmin/lmax)
    double major_deg = 0, minor_deg = 0;    ///< semi-axes 2 sqrt(lmax), 2 sqrt(lmin)
    double orientation_deg = 0;             ///< major axis angle from +u towards +v, in (-90, 90]
    double centroid_u_deg = 0, centroid_v_deg = 0;
    double fwhm_u_deg = 0, fwhm_v_deg = 0;  ///< full width of the region on the lines through the peak along u, v
    double area_deg2 = 0;                   ///< area of the region in the (u,v) plane
    long region_pixels = 0;                 ///< 0 for the reference
    double minor_pixels = 0;                ///< pixels across the minor axis, 2*minor / pitch; +inf for the reference
    FlagSet flags;
    /// Connected parts of the region {L >= frac * peak} (rule 3 of the definition: every part counts; the
    /// fields above describe them all together). 0 with no highlight.
    int components = 1;
    /// Each part's own ellipse, the part holding the peak first; empty when the region is one part.
    std::vector<PartShape> parts;
    AreaMoments moments;  ///< of the whole region (radians), as the ellipse fields above were set from

    bool has(Flag f) const;
};
std::ostream& operator<<(std::ostream&, const Shape&);

/// Whether the shape carries a flag that leaves its numbers unmeasured (float_overflow, float_underflow,
/// no_mirror_lobe).
bool unmeasured(const Shape& s);
/// Marks the shape's numbers as not measured under `why` (float_overflow, float_underflow, no_mirror_lobe): every
/// number NaN
/// (null in a row, "-" in a table), no parts, components 0, and the flags that described the numbers
/// (no_highlight, under_resolved, clipped, ...) dropped, so a row cannot read as a clean measurement.
void setUnmeasured(Shape& s, Flag why);

/// \brief Fill the ellipse fields of `s` (aspect, eccentricity, axes, orientation, centroid, area)
/// from the moments, by the closed-form eigen-decomposition of the symmetric 2x2 matrix.
void setEllipse(Shape& s, const AreaMoments& m);
/// The same for one part.
void setEllipse(PartShape& s, const AreaMoments& m);

/// \brief Analyse the GL measurement view.
/// \param pixels width*height*4 floats, row-major, row 0 at the bottom, per pixel (L, u, v, w): L the
///   lobe value, (u, v) the pixel centre's chart coordinates in radians, w the pixel's area in the (u,v)
///   plane in rad^2 (w = 0: the pixel sees no surface, sky or below the horizon, and has L = 0).
/// Boundary treatment: a pixel is "in" (region_pixels, the flags) when the L at its centre is
/// >= threshold * peak. For the moments each pixel counts with weight w * f at its centre's (u, v), where
/// f = 1 inside and 0 outside; with opt.subpixel, the pixels on the contour (a visible 4-neighbour on
/// the other side) get f = the fraction of the pixel on the inside of the straight line L = T fitted by
/// the local gradient (central differences). A pixel beside the sky counts whole: the horizon is taken at
/// the pixel edge. fwhm_u/v are sub-pixel in both modes (linear interpolation of L across each crossing).
/// peak is the largest pixel value and peak_u/v its pixel's centre: the true peak lies up to half a pixel
/// away and is higher by O(pixel^2), so the threshold, and the region with it, come out slightly low/large.
/// Errors against measureReference (GGX alpha 0.1, region ~60% of the frame): semi-axes ~2e-4 at 256^2,
/// ~5e-5 at 512^2 with subpixel (second order); 5-10x more, and noisy, with pixels in/out.
Shape measureImage(const float* pixels, int width, int height, const Options& opt);

/// A lobe as a function of the chart coordinates (radians).
struct LobeFunction {
    std::function<double(double u, double v)> lobe;   ///< L >= 0, and 0 below the horizon
    std::function<bool(double u, double v)> visible;  ///< (u,v) is above the horizon (we.z > 0)
};

/// \brief Double-precision reference, independent of GL: ~1e-9 relative on smooth contours (closed-form
/// tests), ~1e-5 where the horizon cuts the contour (a kink: the trapezoid rule drops to second order).
/// Flags: HorizonCut, NoHighlight, NotStarShaped (Clipped, UnderResolved, CoversFrame do not apply). ~5 ms.
/// \param searchRadius bounds the peak search: a disc of this radius (radians) about the hint.
/// \param hint_u, hint_v a starting guess for the peak (radians).
/// The region is assumed star-shaped about the peak (true of every single-lobe BRDF here); a coarse grid
/// over the search disc checks it, and NotStarShaped says when it fails.
Shape measureReference(const LobeFunction& f, const Options& opt, double searchRadius, double hint_u = 0,
                       double hint_v = 0);

/// A box of the chart (radians) that holds part of the region (from a survey of the hemisphere).
struct ChartBox {
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    /// a point of the region in the box (NaN: none known): every line samples it, and the lines are placed
    /// about it on the scale of the region's extent there, so a part far smaller than its box is still found
    double su = std::numeric_limits<double>::quiet_NaN(), sv = std::numeric_limits<double>::quiet_NaN();
};

/// \brief The reference that no topology fools: the region {L >= threshold * peak} cut by lines v = const
/// over the boxes, each line an exact set of intervals (every crossing of the threshold or the horizon
/// bisected to rounding; 256 samples per box find every interval wider than 1/256 of it), the lines placed
/// by adaptive Gauss-Kronrod 7/15 to 1e-8 of the moments. Any number of parts (components, parts), peaks
/// anywhere; a box the region runs past grows. `peak` and its place (radians) come from the caller: the
/// global peak, found over the whole hemisphere. Flags: HorizonCut, NoHighlight.
Shape measureLines(const LobeFunction& f, const Options& opt, double peak, double peak_u, double peak_v,
                   std::vector<ChartBox> boxes);

}  // namespace hilite::analysis
