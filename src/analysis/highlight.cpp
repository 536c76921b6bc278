#include "hilite/analysis/highlight.hpp"

#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>
#include <utility>

namespace hilite::analysis {

const char* toString(Flag f) {
    switch (f) {
        case Flag::Clipped: return "clipped";
        case Flag::HorizonCut: return "horizon_cut";
        case Flag::UnderResolved: return "under_resolved";
        case Flag::NoHighlight: return "no_highlight";
        case Flag::CoversFrame: return "covers_frame";
        case Flag::Mirror: return "mirror";
        case Flag::EffectivelyMirror: return "effectively_mirror";
        case Flag::UnboundedAtHorizon: return "unbounded_at_horizon";
        case Flag::NotStarShaped: return "not_star_shaped";
        case Flag::PartsNotMeasured: return "parts_not_measured";
        case Flag::NotConverged: return "not_converged";
        case Flag::LightUndersampled: return "light_undersampled";
        case Flag::FloatOverflow: return "float_overflow";
        case Flag::FloatUnderflow: return "float_underflow";
        case Flag::PeakOnHorizon: return "peak_on_horizon";
        case Flag::NoMirrorLobe: return "no_mirror_lobe";
        case Flag::SaddleCut: return "saddle_cut";
    }
    return "unknown";
}

const char* toString(Lobe l) { return l == Lobe::Mirror ? "mirror" : "all"; }

std::ostream& operator<<(std::ostream& os, Flag f) { return os << toString(f); }

std::ostream& operator<<(std::ostream& os, const Options& o) {
    return os << "{threshold=" << o.threshold << ", minPixelsAcross=" << o.minPixelsAcross
              << ", lobe=" << toString(o.lobe) << "}";
}

std::ostream& operator<<(std::ostream& os, const Shape& s) {
    os << "{peak=" << s.peak << " at (" << s.peak_u_deg << ", " << s.peak_v_deg << ") deg, aspect=" << s.aspect
       << ", ecc=" << s.eccentricity << ", major=" << s.major_deg << ", minor=" << s.minor_deg
       << ", orientation=" << s.orientation_deg << ", centroid=(" << s.centroid_u_deg << ", " << s.centroid_v_deg
       << "), fwhm=(" << s.fwhm_u_deg << ", " << s.fwhm_v_deg << "), area=" << s.area_deg2
       << " deg2, pixels=" << s.region_pixels << ", minor_pixels=" << s.minor_pixels << ", flags=[";
    const char* sep = "";
    for (Flag f : s.flags) os << std::exchange(sep, ",") << f;
    return os << "]}";
}

bool Shape::has(Flag f) const { return flags.has(f); }

bool unmeasured(const Shape& s) {
    return s.has(Flag::FloatOverflow) || s.has(Flag::FloatUnderflow) || s.has(Flag::NoMirrorLobe);
}

void setUnmeasured(Shape& s, Flag why) {
    const bool over = s.has(Flag::FloatOverflow) || why == Flag::FloatOverflow;
    const bool under = s.has(Flag::FloatUnderflow) || why == Flag::FloatUnderflow;
    const bool noLobe = s.has(Flag::NoMirrorLobe) || why == Flag::NoMirrorLobe;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double* v : {&s.peak, &s.peak_u_deg, &s.peak_v_deg, &s.aspect, &s.eccentricity, &s.major_deg, &s.minor_deg,
                      &s.orientation_deg, &s.centroid_u_deg, &s.centroid_v_deg, &s.fwhm_u_deg, &s.fwhm_v_deg,
                      &s.area_deg2, &s.minor_pixels})
        *v = nan;
    s.region_pixels = 0;
    s.components = 0;
    s.parts.clear();
    s.moments = AreaMoments{};
    // Only the float flags stay: the others (no_highlight, under_resolved, clipped) described numbers not measured.
    s.flags = FlagSet{};
    if (over) s.flags.insert(Flag::FloatOverflow);
    if (under) s.flags.insert(Flag::FloatUnderflow);
    if (noLobe) s.flags.insert(Flag::NoMirrorLobe);
}

void validate(const Options& opt) {
    // Checked where the numbers enter the library: a threshold of 0 or 1 makes the region everything
    // visible or a single point, and neither has a shape.
    if (!(opt.threshold > 0.0 && opt.threshold < 1.0)) {
        std::ostringstream msg;
        msg << "measure threshold must be in (0, 1), got " << opt.threshold;
        throw InputError(msg.str());
    }
    if (opt.minPixelsAcross < 1) {
        std::ostringstream msg;
        msg << "measure minPixelsAcross must be >= 1, got " << opt.minPixelsAcross;
        throw InputError(msg.str());
    }
}

AreaMoments combine(const AreaMoments& a, const AreaMoments& b) {
    if (!(a.area > 0)) return b;
    if (!(b.area > 0)) return a;
    AreaMoments m;
    m.area = a.area + b.area;
    const double wa = a.area / m.area, wb = b.area / m.area;
    m.mean_u = wa * a.mean_u + wb * b.mean_u;
    m.mean_v = wa * a.mean_v + wb * b.mean_v;
    const double au = a.mean_u - m.mean_u, av = a.mean_v - m.mean_v;
    const double bu = b.mean_u - m.mean_u, bv = b.mean_v - m.mean_v;
    m.cuu = wa * (a.cuu + au * au) + wb * (b.cuu + bu * bu);
    m.cuv = wa * (a.cuv + au * av) + wb * (b.cuv + bu * bv);
    m.cvv = wa * (a.cvv + av * av) + wb * (b.cvv + bv * bv);
    return m;
}

namespace {

struct EllipseFields {
    double aspect, eccentricity, major, minor, orientation;
};

EllipseFields ellipseOf(const AreaMoments& m) {
    // Eigenvalues of [[cuu, cuv], [cuv, cvv]]: lmax = mean + hypot(half difference, cuv), which adds
    // non-negative terms; lmin = det / lmax avoids the cancellation of mean - hypot for thin ellipses.
    const double halfSum = 0.5 * (m.cuu + m.cvv);
    const double halfDiff = 0.5 * (m.cuu - m.cvv);
    const double lmax = std::max(0.0, halfSum + std::hypot(halfDiff, m.cuv));
    const double det = m.cuu * m.cvv - m.cuv * m.cuv;
    const double lmin = lmax > 0.0 ? std::clamp(det / lmax, 0.0, lmax) : 0.0;
    const double ratio = lmax > 0.0 ? lmin / lmax : 1.0;  // a single point counts as round
    // Major axis angle, 0.5 atan2(2 cuv, cuu - cvv) in [-90, 90]; fold -90 (from atan2(-0, x<0)) onto 90.
    double orientation = rad2deg(0.5 * std::atan2(2.0 * m.cuv, m.cuu - m.cvv));
    // -90 and 90 are the same axis: fold -90 (from atan2(-0, x < 0)) and what rounding leaves near it onto 90.
    if (orientation <= -90.0 + 1e-4) orientation = std::min(90.0, orientation + 180.0);
    return {std::sqrt(ratio), safeSqrt(1.0 - ratio), rad2deg(2.0 * std::sqrt(lmax)), rad2deg(2.0 * std::sqrt(lmin)),
            orientation};
}

template <class S>
void fill(S& s, const AreaMoments& m) {
    const EllipseFields e = ellipseOf(m);
    s.aspect = e.aspect;
    s.eccentricity = e.eccentricity;
    s.major_deg = e.major;
    s.minor_deg = e.minor;
    s.orientation_deg = e.orientation;
    s.centroid_u_deg = rad2deg(m.mean_u);
    s.centroid_v_deg = rad2deg(m.mean_v);
    s.area_deg2 = rad2deg(rad2deg(m.area));
    s.moments = m;
}

}  // namespace

void setEllipse(Shape& s, const AreaMoments& m) { fill(s, m); }
void setEllipse(PartShape& s, const AreaMoments& m) { fill(s, m); }

}  // namespace hilite::analysis
