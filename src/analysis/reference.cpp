// measureReference: the double-precision oracle. Peak by a grid search then a pattern search over the
// visible points; contour as a polar function r(phi) about the peak, found ray by ray by the Illinois method
// (regula falsi that halves a stale end's value, with a bisection whenever a bracket fails to halve); the
// area moments as exact polar integrals of r(phi), summed by the trapezoid rule (spectrally accurate for
// a smooth periodic r(phi): the rays double from 128 until the moments agree to 1e-12; second order where the
// horizon puts a kink in the contour: then 2048 rays, as always before).

#include "analysis/lobe_bounds.hpp"
#include "hilite/analysis/highlight.hpp"

#include "core/parallel.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace hilite::analysis {

namespace {

constexpr int kCoarseGrid = 64;  ///< coarse peak search: kCoarseGrid^2 points over the search disc
/// The pattern search stops at this step (rad): the peak's value is then within ~(1e-10 / lobe width)^2 of the
/// true maximum, far below rounding (1e-12 took ~7 more rounds of 24 evaluations, a tenth of an exact reference
/// under a disk light).
constexpr double kPeakStep = 1e-10;
constexpr int kContourAngles = 2048;  ///< the most rays: a multiple of 4, so that phi = 0, pi/2, pi, 3pi/2 are samples
constexpr int kFirstAngles = 128;     ///< the fewest; doubled until the moments settle (kContourAngles / 2^k)
constexpr double kMomentTol = 1e-12;  ///< moments of K and 2K rays that agree this well (relative) end the doubling
constexpr int kReentryRays = 256;     ///< rays raysReenter samples beyond the contour (every 1.4 deg)
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
bool inSearch(const LobeFunction& f, dvec2 q, dvec2 hint, double radius) {
    return glm::length(q - hint) <= radius && inChart(q) && f.visible(q.x, q.y);
}
double searchValue(const LobeFunction& f, dvec2 q, dvec2 hint, double radius) {
    return inSearch(f, q, hint, radius) ? f.lobe(q.x, q.y) : -1.0;
}

/// The kCoarseGrid^2 cell centres over the search disc and searchValue at each (the peak search's start and
/// the star-shape check's points), or an enclosure [lo, hi] of it where LobeBounds gives one.
struct CoarseGrid {
    dvec2 hint;
    double radius, cell;
    std::vector<double> lo, hi;  ///< row by row; lo == hi: the value itself
    double seconds = 0;          ///< how long the grid took: whether the lobe is dear enough to share out
    dvec2 at(int i, int j) const { return hint + dvec2(-radius + (i + 0.5) * cell, -radius + (j + 0.5) * cell); }
};

CoarseGrid coarseGrid(const LobeFunction& f, const LobeBounds& bounds, dvec2 hint, double radius) {
    const auto t0 = std::chrono::steady_clock::now();
    CoarseGrid g{hint, radius, 2.0 * radius / kCoarseGrid, {}, {}, 0.0};
    g.lo.resize(size_t(kCoarseGrid) * kCoarseGrid);
    g.hi.resize(g.lo.size());
    parallelFor(kCoarseGrid, [&](int j) {
        for (int i = 0; i < kCoarseGrid; ++i) {
            const size_t n = size_t(j * kCoarseGrid + i);
            const dvec2 q = g.at(i, j);
            if (!(bounds && inSearch(f, q, hint, radius) && bounds(q.x, q.y, g.lo[n], g.hi[n])))
                g.lo[n] = g.hi[n] = searchValue(f, q, hint, radius);
        }
    });
    g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return g;
}

/// Best point of the grid, and the hint itself; an enclosed point that might beat the best so far is evaluated.
Candidate coarsePeak(const LobeFunction& f, const CoarseGrid& g) {
    Candidate best{g.hint, searchValue(f, g.hint, g.hint, g.radius)};
    for (int j = 0; j < kCoarseGrid; ++j)
        for (int i = 0; i < kCoarseGrid; ++i) {
            const size_t n = size_t(j * kCoarseGrid + i);
            if (!(g.hi[n] > best.L)) continue;
            const double L = g.lo[n] == g.hi[n] ? g.hi[n] : searchValue(f, g.at(i, j), g.hint, g.radius);
            if (L > best.L) best = {g.at(i, j), L};
        }
    return best;
}

/// Compass pattern search from `best`: try the 5x5 pattern of step h about it; move to the best point,
/// keeping h if that point is on the pattern's rim (the peak may lie further out, e.g. along a thin
/// ridge), halving it otherwise. Points off the visible hemisphere never win, so a peak on the horizon
/// (rough surfaces at grazing light) is approached from the visible side.
/// threads: for each round's 24 points (parallelFor's; 1 where the lobe is cheap, so that no round waits on
/// starting threads for microseconds of work).
Candidate refinePeak(const LobeFunction& f, Candidate best, double h, dvec2 hint, double radius, int threads) {
    for (int iter = 0; iter < 1000 && h > kPeakStep; ++iter) {
        Candidate next = best;
        bool onRim = false;
        double values[25];  // the pattern's points evaluated (in parallel), then compared in order as before
        parallelFor(
            25,
            [&](int k) {
                const int i = k % 5 - 2, j = k / 5 - 2;
                values[k] = (i || j) ? searchValue(f, best.q + h * dvec2(i, j), hint, radius) : -1.0;
            },
            threads);
        for (int j = -2; j <= 2; ++j) {
            for (int i = -2; i <= 2; ++i) {
                const double L = values[(j + 2) * 5 + i + 2];
                if (L > next.L) {
                    next = {best.q + h * dvec2(i, j), L};
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
    /// L - T where visible, -T beyond the horizon (L = 0 there): in the region where >= 0.
    double value(double r) const {
        dvec2 q = at(r);
        return visible(r) ? f.lobe(q.x, q.y) - T : -T;
    }
    bool in(double r) const { return value(r) >= 0; }
    /// in(r), decided by the enclosure where it lies wholly on one side of T.
    bool inEnclosed(double r, const LobeBounds& bounds) const {
        if (!visible(r)) return false;
        const dvec2 q = at(r);
        double lo = 0, hi = 0;
        if (bounds && bounds(q.x, q.y, lo, hi) && (hi < T || lo >= T)) return lo >= T;
        return f.lobe(q.x, q.y) >= T;
    }
};

struct Boundary {
    double r = 0;
    bool horizon = false;  ///< the ray leaves the region through the horizon, not the threshold
};

/// Where the ray leaves the region: bracketed by steps from the guess r0 > 0 (the previous ray's radius;
/// growing steps, x1.1 then squared each time, so a far or a zero radius costs a few steps), then narrowed by
/// the Illinois method to kRadiusTol: superlinear where L is smooth (7-10 evaluations from a 10% bracket
/// instead of bisection's 40), a bisection step whenever two steps did not halve the bracket (the horizon's
/// jump, rounding noise in L), so never much slower than bisection. lo stays in the region, hi outside.
/// The region is assumed star-shaped about the peak, so the first way out is the boundary. That holds for
/// the single-lobe BRDFs measured here (L falls along every ray from the peak); a region with a notch or an
/// arm gets the contour of the part seen from the peak, which beyondContour() detects on a coarse grid.
Boundary findBoundary(const Ray& ray, double r0, double firstStep = 1.1) {
    constexpr double kMaxRadius = 2.0 * kPi, kMinRadius = 1e-15;
    double lo = 0.0, hi = r0, step = firstStep;
    double vLo = ray.T, vHi = ray.value(r0);  // at r = 0, the peak (L - T > 0): T stands in, for interpolation only
    if (vHi >= 0) {
        lo = r0, vLo = vHi;
        for (hi = r0 * step; (vHi = ray.value(hi)) >= 0; step = std::min(step * step, 1e3), hi = lo * step) {
            lo = hi, vLo = vHi;
            if (hi > kMaxRadius) return {hi, false};  // no way out: cannot happen above a horizon
        }
    } else {
        for (lo = r0 / step; lo > kMinRadius && (vLo = ray.value(lo)) < 0;
             step = std::min(step * step, 1e3), lo = hi / step)
            hi = lo, vHi = vLo;
        if (lo <= kMinRadius) lo = 0.0, vLo = ray.T;  // the peak itself sits on the boundary (a horizon peak)
    }
    int side = 0;
    double w1 = std::numeric_limits<double>::infinity(), w2 = w1;  // the bracket's width one and two steps ago
    for (int i = 0; i < 200 && hi - lo > kRadiusTol; ++i) {
        const double width = hi - lo;
        double x = 0.5 * (lo + hi);
        if (width <= 0.5 * w2) {  // the last two steps halved the bracket: interpolate
            x = (lo * vHi - hi * vLo) / (vHi - vLo);
            x = std::clamp(x, lo + 0.25 * kRadiusTol, hi - 0.25 * kRadiusTol);
        }
        w2 = w1, w1 = width;
        const double v = ray.value(x);
        if (v >= 0) {
            lo = x, vLo = v;
            if (side == 1) vHi *= 0.5;  // the same end moved twice: halve the other's weight (Illinois)
            side = 1;
        } else {
            hi = x, vHi = v;
            if (side == -1) vLo *= 0.5;
            side = -1;
        }
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
bool beyondContour(const LobeFunction& f, const CoarseGrid& g, const std::vector<double>& r, dvec2 p, double T) {
    const int K = int(r.size());
    for (int j = 0; j < kCoarseGrid; ++j) {
        for (int i = 0; i < kCoarseGrid; ++i) {
            const dvec2 q = g.at(i, j);
            const size_t n = size_t(j * kCoarseGrid + i);
            if (g.hi[n] < T) continue;
            if (g.lo[n] < T && g.lo[n] != g.hi[n] && searchValue(f, q, g.hint, g.radius) < T) continue;
            const dvec2 d = q - p;
            const double x = std::atan2(d.y, d.x) / (2.0 * kPi) * K;
            const int k0 = int(std::floor(x));
            const double t = x - k0, rc = (1 - t) * r[size_t((k0 + K) % K)] + t * r[size_t((k0 + 1 + K) % K)];
            if (glm::length(d) > 1.001 * rc + 1e-12) return true;
        }
    }
    return false;
}

/// Whether some ray from the peak comes back into the region after leaving it: kReentryRays of the contour's
/// rays are sampled at 64 points from just past their boundary to where they leave the visible chart. With the
/// grid of beyondContour (inside the search disc) this is the test that makes the polar contour a proven fast path.
bool raysReenter(const LobeFunction& f, const LobeBounds& bounds, const std::vector<double>& r, dvec2 p, double T) {
    const int K = int(r.size()), stride = std::max(1, K / kReentryRays), rays = (K + stride - 1) / stride;
    std::vector<char> reenters(size_t(rays), 0);
    parallelFor(rays, [&](int n) {
        const int k = n * stride;
        const double phi = 2.0 * kPi * k / K;
        const dvec2 dir(std::cos(phi), std::sin(phi));
        const Ray ray{f, p, dir, T};
        double end = 1.01 * r[size_t(k)] + 1e-9;
        while (end < 2.0 * kPi && ray.visible(end * 1.25)) end *= 1.25;
        for (int i = 1; i <= 64 && !reenters[size_t(n)]; ++i) {
            const double t = 1.01 * r[size_t(k)] + 1e-9 + (end * 1.25 - 1.01 * r[size_t(k)]) * i / 64.0;
            reenters[size_t(n)] = ray.inEnclosed(t, bounds);
        }
    });
    return std::any_of(reenters.begin(), reenters.end(), [](char c) { return c != 0; });
}

}  // namespace

Shape measureReference(const LobeFunction& f, const Options& opt, double searchRadius, double hint_u, double hint_v) {
    return measureReference(f, LobeBounds{}, opt, searchRadius, hint_u, hint_v);
}

Shape measureReference(const LobeFunction& f, const LobeBounds& bounds, const Options& opt, double searchRadius,
                       double hint_u, double hint_v) {
    validate(opt);
    if (!f.lobe || !f.visible) throw InputError("measureReference: lobe and visible must both be set");
    if (!(searchRadius > 0.0)) throw InputError("measureReference: searchRadius must be > 0");
    const dvec2 hint(hint_u, hint_v);
    Shape s;
    s.minor_pixels = std::numeric_limits<double>::infinity();
    const CoarseGrid grid = coarseGrid(f, bounds, hint, searchRadius);
    Candidate peak = coarsePeak(f, grid);
    if (!(peak.L > 0.0)) {
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    // Threads pay where the lobe is dear (an exact integral over a light: the grid takes seconds), not for a
    // directional lobe's 0.1-1 us (the grid in ~1 ms; rounds in parallel made GGX 0.02 at 85 deg slower).
    peak = refinePeak(f, peak, 2.0 * searchRadius / kCoarseGrid, hint, searchRadius, grid.seconds > 0.02 ? 0 : 1);

    const double T = opt.threshold * peak.L;
    auto boundary = [&](int k, int K, double guess, double firstStep = 1.1) {
        const double phi = 2.0 * kPi * k / K;
        return findBoundary({f, peak.q, {std::cos(phi), std::sin(phi)}, T}, std::max(guess, 1e-6 * searchRadius),
                            firstStep);
    };
    // The first rays in kChains runs, each ray started from the one before it in its run: the runs in parallel,
    // the same rays whatever the number of threads.
    std::vector<double> r(kFirstAngles);
    std::vector<char> horizon(kFirstAngles, 0);
    constexpr int kChains = 8, kChain = kFirstAngles / kChains;
    parallelFor(kChains, [&](int c) {
        double guess = 1e-3 * searchRadius;
        for (int k = c * kChain; k < (c + 1) * kChain; ++k) {
            const Boundary b = boundary(k, kFirstAngles, guess);
            r[size_t(k)] = guess = b.r;
            horizon[size_t(k)] = b.horizon;
        }
    });
    bool cut = std::any_of(horizon.begin(), horizon.end(), [](char c) { return c != 0; });
    AreaMoments moments = polarMoments(r, peak.q);
    // Doubling: the new rays bisect the old ones' angles, each started from its neighbour's radius. A smooth
    // contour settles at 256-512 rays; a kink where the horizon cuts it never does (2048, second order).
    while (int(r.size()) < kContourAngles) {
        const int K = 2 * int(r.size());
        std::vector<double> finer(static_cast<size_t>(K));
        std::vector<char> cuts(size_t(K / 2), 0);
        parallelFor(K / 2, [&](int n) {
            // Started from the mean of its neighbours (within ~1e-4 on a smooth contour) with a bracket 1e-3 wide.
            const double between = 0.5 * (r[size_t(n)] + r[size_t((n + 1) % (K / 2))]);
            const Boundary b = boundary(2 * n + 1, K, between, 1.001);
            finer[size_t(2 * n)] = r[size_t(n)];
            finer[size_t(2 * n + 1)] = b.r;
            cuts[size_t(n)] = b.horizon;
        });
        cut = cut || std::any_of(cuts.begin(), cuts.end(), [](char c) { return c != 0; });
        r.swap(finer);
        const AreaMoments next = polarMoments(r, peak.q);
        const double spread = next.cuu + next.cvv;
        const bool settled =
            std::abs(next.area - moments.area) <= kMomentTol * next.area &&
            std::max({std::abs(next.cuu - moments.cuu), std::abs(next.cuv - moments.cuv),
                      std::abs(next.cvv - moments.cvv)}) <= kMomentTol * spread &&
            std::hypot(next.mean_u - moments.mean_u, next.mean_v - moments.mean_v) <= kMomentTol * std::sqrt(spread);
        moments = next;
        if (settled && !cut) break;
    }
    const size_t K = r.size();
    setEllipse(s, moments);
    s.peak = peak.L;
    s.peak_u_deg = rad2deg(peak.q.x);
    s.peak_v_deg = rad2deg(peak.q.y);
    s.fwhm_u_deg = rad2deg(r[0] + r[K / 2]);
    s.fwhm_v_deg = rad2deg(r[K / 4] + r[3 * K / 4]);
    if (cut) s.flags.insert(Flag::HorizonCut);
    if (beyondContour(f, grid, r, peak.q, T) || raysReenter(f, bounds, r, peak.q, T))
        s.flags.insert(Flag::NotStarShaped);
    return s;
}

}  // namespace hilite::analysis
