// measureReference: the double-precision oracle. Peak by a grid search then a pattern search over the
// visible points; contour as a polar function r(phi) about the peak, found ray by ray by bisection; the
// area moments as exact polar integrals of r(phi), summed by the trapezoid rule (spectrally accurate for
// a smooth periodic r(phi); second order where the horizon puts a kink in the contour).

#include "hilite/analysis/highlight.hpp"

#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hilite::analysis {

namespace {

constexpr int kCoarseGrid = 64;  ///< coarse peak search: kCoarseGrid^2 points over the search disc
constexpr double kPeakStep =
    1e-12;  ///< pattern search stops at this step (rad); rounding noise in L hides the peak long before
constexpr int kContourAngles = 2048;  ///< a multiple of 4, so that phi = 0, pi/2, pi, 3pi/2 are samples
constexpr double kRadiusTol = 1e-13;  ///< bisection tolerance on r(phi) (rad), ~1e-11 of a 1 deg radius

struct Candidate {
    dvec2 q{0.0};
    double L = -1.0;  ///< -1: none yet (L >= 0 wherever defined)
};

/// The chart covers rho = |(u, v)| < pi. Beyond it the chart's direction(u, v) wraps round onto directions
/// already covered, so a ray whose bracketing steps jump over the band below the horizon would find the
/// region again there: a lobe filling the hemisphere (GGX alpha 1, Phong n 0) measured 1e4 degrees across.
bool inChart(dvec2 q) { return glm::dot(q, q) < kPi * kPi; }

/// L at q if q is visible and within the search disc, else -1 (so that any visible point beats it).
double searchValue(const LobeFunction& f, dvec2 q, dvec2 hint, double radius) {
    if (glm::length(q - hint) > radius || !inChart(q) || !f.visible(q.x, q.y)) return -1.0;
    return f.lobe(q.x, q.y);
}

/// Best point of a kCoarseGrid^2 grid of cell centres over the disc, and the hint itself.
Candidate coarsePeak(const LobeFunction& f, dvec2 hint, double radius) {
    Candidate best{hint, searchValue(f, hint, hint, radius)};
    const double cell = 2.0 * radius / kCoarseGrid;
    for (int j = 0; j < kCoarseGrid; ++j) {
        for (int i = 0; i < kCoarseGrid; ++i) {
            const dvec2 q = hint + dvec2(-radius + (i + 0.5) * cell, -radius + (j + 0.5) * cell);
            const double L = searchValue(f, q, hint, radius);
            if (L > best.L) best = {q, L};
        }
    }
    return best;
}

/// Compass pattern search from `best`: try the 5x5 pattern of step h about it; move to the best point,
/// keeping h if that point is on the pattern's rim (the peak may lie further out, e.g. along a thin
/// ridge), halving it otherwise. Points off the visible hemisphere never win, so a peak on the horizon
/// (rough surfaces at grazing light) is approached from the visible side.
Candidate refinePeak(const LobeFunction& f, Candidate best, double h, dvec2 hint, double radius) {
    for (int iter = 0; iter < 1000 && h > kPeakStep; ++iter) {
        Candidate next = best;
        bool onRim = false;
        for (int j = -2; j <= 2; ++j) {
            for (int i = -2; i <= 2; ++i) {
                const dvec2 q = best.q + h * dvec2(i, j);
                const double L = (i || j) ? searchValue(f, q, hint, radius) : -1.0;
                if (L > next.L) {
                    next = {q, L};
                    onRim = std::abs(i) == 2 || std::abs(j) == 2;
                }
            }
        }
        best = next;
        if (!onRim) h *= 0.5;
    }
    return best;
}

/// Membership of the region along one ray from the peak: visible (within the chart) and L >= T.
struct Ray {
    const LobeFunction& f;
    dvec2 p, dir;
    double T;

    dvec2 at(double r) const { return p + r * dir; }
    bool visible(double r) const {
        dvec2 q = at(r);
        return inChart(q) && f.visible(q.x, q.y);
    }
    bool in(double r) const {
        dvec2 q = at(r);
        return visible(r) && f.lobe(q.x, q.y) >= T;
    }
};

struct Boundary {
    double r = 0;
    bool horizon = false;  ///< the ray leaves the region through the horizon, not the threshold
};

/// Where the ray leaves the region: bracketed by steps from the guess r0 > 0 (the previous ray's radius;
/// growing steps, x1.1 then squared each time, so a far or a zero radius costs a few steps), then bisected.
/// The region is assumed star-shaped about the peak, so the first way out is the boundary. That holds for
/// the single-lobe BRDFs measured here (L falls along every ray from the peak); a region with a notch or an
/// arm gets the contour of the part seen from the peak, which beyondContour() detects on a coarse grid.
Boundary findBoundary(const Ray& ray, double r0) {
    constexpr double kMaxRadius = 2.0 * kPi, kMinRadius = 1e-15;
    double lo = 0.0, hi = r0, step = 1.1;
    if (ray.in(r0)) {
        for (lo = r0, hi = r0 * step; ray.in(hi); step = std::min(step * step, 1e3), hi = lo * step) {
            lo = hi;
            if (hi > kMaxRadius) return {hi, false};  // no way out: cannot happen above a horizon
        }
    } else {
        for (lo = r0 / step; lo > kMinRadius && !ray.in(lo); step = std::min(step * step, 1e3), lo = hi / step) hi = lo;
        if (lo <= kMinRadius) lo = 0.0;  // the peak itself sits on the boundary (a horizon peak)
    }
    for (int i = 0; i < 200 && hi - lo > kRadiusTol; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ray.in(mid) ? lo : hi) = mid;
    }
    return {0.5 * (lo + hi), !ray.visible(hi)};
}

/// Polar area moments about the peak, from r(phi) at uniform angles (trapezoid rule):
/// A = int r^2/2, M_x = int cos r^3/3, M_xx = int cos^2 r^4/4, and likewise with sin.
AreaMoments polarMoments(const std::vector<double>& r, dvec2 p) {
    const int K = int(r.size());
    double A = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
    for (int k = 0; k < K; ++k) {
        const double phi = 2.0 * kPi * k / K, c = std::cos(phi), s = std::sin(phi);
        const double r2 = r[k] * r[k], r3 = r2 * r[k], r4 = r2 * r2;
        A += r2 / 2;
        mx += c * r3 / 3;
        my += s * r3 / 3;
        mxx += c * c * r4 / 4;
        mxy += c * s * r4 / 4;
        myy += s * s * r4 / 4;
    }
    // The common factor 2 pi / K cancels in every ratio but the area.
    AreaMoments m;
    m.area = A * (2.0 * kPi / K);
    const double du = mx / A, dv = my / A;
    m.mean_u = p.x + du;
    m.mean_v = p.y + dv;
    m.cuu = mxx / A - du * du;
    m.cuv = mxy / A - du * dv;
    m.cvv = myy / A - dv * dv;
    return m;
}

/// Whether a point of the coarse grid over the search disc is in the region yet beyond the contour r(phi)
/// seen from the peak p (with 0.1% to spare for the chord between rays): then the region is not star-shaped
/// about p (a ring, two lobes) and the polar moments silently miss part of it.
bool beyondContour(const LobeFunction& f, const std::vector<double>& r, dvec2 p, double T, dvec2 hint, double radius) {
    const int K = int(r.size());
    const double cell = 2.0 * radius / kCoarseGrid;
    for (int j = 0; j < kCoarseGrid; ++j) {
        for (int i = 0; i < kCoarseGrid; ++i) {
            const dvec2 q = hint + dvec2(-radius + (i + 0.5) * cell, -radius + (j + 0.5) * cell);
            if (searchValue(f, q, hint, radius) < T) continue;
            const dvec2 d = q - p;
            const double x = std::atan2(d.y, d.x) / (2.0 * kPi) * K;
            const int k0 = int(std::floor(x));
            const double t = x - k0, rc = (1 - t) * r[size_t((k0 + K) % K)] + t * r[size_t((k0 + 1 + K) % K)];
            if (glm::length(d) > 1.001 * rc + 1e-12) return true;
        }
    }
    return false;
}

/// Whether some ray from the peak comes back into the region after leaving it: every 8th contour ray is
/// sampled at 64 points from just past its boundary to where it leaves the visible chart. With the grid of
/// beyondContour (inside the search disc) this is the test that makes the polar contour a proven fast path.
bool raysReenter(const LobeFunction& f, const std::vector<double>& r, dvec2 p, double T) {
    const int K = int(r.size());
    for (int k = 0; k < K; k += 8) {
        const double phi = 2.0 * kPi * k / K;
        const dvec2 dir(std::cos(phi), std::sin(phi));
        const Ray ray{f, p, dir, T};
        double end = 1.01 * r[size_t(k)] + 1e-9;
        while (end < 2.0 * kPi && ray.visible(end * 1.25)) end *= 1.25;
        for (int i = 1; i <= 64; ++i) {
            const double t = 1.01 * r[size_t(k)] + 1e-9 + (end * 1.25 - 1.01 * r[size_t(k)]) * i / 64.0;
            if (ray.in(t)) return true;
        }
    }
    return false;
}

}  // namespace

Shape measureReference(const LobeFunction& f, const Options& opt, double searchRadius, double hint_u, double hint_v) {
    validate(opt);
    if (!f.lobe || !f.visible) throw InputError("measureReference: lobe and visible must both be set");
    if (!(searchRadius > 0.0)) throw InputError("measureReference: searchRadius must be > 0");
    const dvec2 hint(hint_u, hint_v);
    Shape s;
    s.minor_pixels = std::numeric_limits<double>::infinity();
    Candidate peak = coarsePeak(f, hint, searchRadius);
    if (!(peak.L > 0.0)) {
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    peak = refinePeak(f, peak, 2.0 * searchRadius / kCoarseGrid, hint, searchRadius);

    std::vector<double> r(kContourAngles);
    bool cut = false;
    double guess = 1e-3 * searchRadius;
    for (int k = 0; k < kContourAngles; ++k) {
        const double phi = 2.0 * kPi * k / kContourAngles;
        const Boundary b = findBoundary({f, peak.q, {std::cos(phi), std::sin(phi)}, opt.threshold * peak.L}, guess);
        r[k] = b.r;
        cut = cut || b.horizon;
        guess = std::max(b.r, 1e-6 * searchRadius);
    }
    setEllipse(s, polarMoments(r, peak.q));
    s.peak = peak.L;
    s.peak_u_deg = rad2deg(peak.q.x);
    s.peak_v_deg = rad2deg(peak.q.y);
    s.fwhm_u_deg = rad2deg(r[0] + r[kContourAngles / 2]);
    s.fwhm_v_deg = rad2deg(r[kContourAngles / 4] + r[3 * kContourAngles / 4]);
    if (cut) s.flags.insert(Flag::HorizonCut);
    if (beyondContour(f, r, peak.q, opt.threshold * peak.L, hint, searchRadius) ||
        raysReenter(f, r, peak.q, opt.threshold * peak.L))
        s.flags.insert(Flag::NotStarShaped);
    return s;
}

}  // namespace hilite::analysis
