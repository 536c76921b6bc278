// measureLines: the reference that topology cannot fool. The region {L >= T} is cut by lines v = const;
// on each line it is an exact set of intervals in u (dense samples, every crossing of the threshold or of
// the horizon bisected to rounding), whose moments in u are closed forms; the lines are placed in v by
// adaptive Gauss-Kronrod (7/15), which resolves the square-root ends of every part and the kinks where the
// horizon cuts it. No assumption on the shape: any number of parts, peaks anywhere, notches, rings.

#include "hilite/analysis/highlight.hpp"

#include "core/quadrature.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

namespace hilite::analysis {

namespace {

constexpr int kSamples = 512;  ///< samples per line across each box: finds every interval >= 1/128 of the box wide
constexpr double kTol = 1e-7;  ///< the moments' error, relative to their scale, shared over the panels
constexpr int kMaxDepth = 40;  ///< panel halvings below a box's v-range
constexpr int kMaxGrowth = 8;  ///< box enlargements before giving up (the region runs past the chart)
/// Panels before the integration stops refining and says so (NotConverged): ~1 s. A lobe far thinner than its
/// box everywhere (anisotropic Beckmann 1e-4 x 1) would otherwise take minutes.
constexpr int kMaxPanels = 800;

using gk15::kWg;
using gk15::kWgk;
using gk15::kXgk;

bool inChart(double u, double v) { return u * u + v * v < kPi * kPi; }

struct Interval {
    double a = 0, b = 0;
    bool horizon = false;  ///< an end of it is the horizon
};

/// The moment integrands of one line, about the peak: [int du, int du^2/2... ] as below.
using Vec6 = std::array<double, 6>;

struct Line {
    double v = 0, weight = 0;
    int span = 0;  ///< which merged v-range of the boxes it belongs to
    std::vector<Interval> iv;
};

class Scanner {
public:
    Scanner(const LobeFunction& f, double T, std::vector<ChartBox> boxes) : m_f(f), m_T(T), m_boxes(std::move(boxes)) {}

    bool visible(double u, double v) const { return inChart(u, v) && m_f.visible(u, v); }
    bool in(double u, double v) const { return visible(u, v) && m_f.lobe(u, v) >= m_T; }

    /// The intervals of the line v; a box too small for the region there is marked to grow.
    /// only >= 0: that box's range alone (is the region past the box's end in v?).
    std::vector<Interval> line(double v, int only = -1) {
        std::vector<Interval> out;
        for (auto [i0, i1, box] : ranges(v, only)) {
            // Uniform samples, plus the midpoints of the intervals of the nearest lines already cut: a part
            // thinner than the sample spacing (the tip of a horizon strip) is still found on lines beside one
            // that found it.
            std::vector<double> us(kSamples + 1);
            for (int i = 0; i <= kSamples; ++i) us[size_t(i)] = i == kSamples ? i1 : i0 + i * (i1 - i0) / kSamples;
            addNeighbours(v, i0, i1, us);
            for (const ChartBox& b : m_boxes)
                if (b.su > i0 && b.su < i1) us.push_back(b.su);
            std::sort(us.begin(), us.end());
            double prevU = i0;
            bool prev = in(i0, v);
            if (prev) grow(box, 0);
            Interval cur;
            if (prev) cur.a = i0;
            for (size_t i = 1; i < us.size(); ++i) {
                const double u = us[i];
                const bool now = in(u, v);
                if (now != prev) {
                    bool horizon = false;
                    const double x = crossing(prevU, u, v, prev, horizon);
                    if (now) cur = Interval{x, 0, horizon};
                    else cur.b = x, cur.horizon = cur.horizon || horizon, out.push_back(cur);
                }
                prev = now, prevU = u;
            }
            if (prev) {
                cur.b = i1;
                out.push_back(cur);
                grow(box, 1);
            }
        }
        if (only < 0) m_done[v] = out;
        return out;
    }

    /// Distance from p along the unit direction d to where the region ends (bisection to 1e-15 rad);
    /// `horizon`: it ends at the horizon.
    double reach(dvec2 p, dvec2 d, bool& horizon) const {
        auto inAt = [&](double r) {
            const dvec2 q = p + r * d;
            return in(q.x, q.y);
        };
        double lo = 0, hi = 1e-9;
        while (hi < 2 * kPi && inAt(hi)) lo = hi, hi *= 1.5;
        for (int i = 0; i < 100 && hi - lo > 1e-15; ++i) {
            const double mid = 0.5 * (lo + hi);
            (inAt(mid) ? lo : hi) = mid;
        }
        const dvec2 out = p + hi * d;
        horizon = !visible(out.x, out.y);
        return 0.5 * (lo + hi);
    }

    std::vector<ChartBox>& boxes() { return m_boxes; }
    bool grew() const { return m_grew; }
    void resetGrew() {
        m_grew = false;
        m_done.clear();
    }
    const LobeFunction& f() const { return m_f; }
    double T() const { return m_T; }

private:
    /// Adds to the sorted samples `us` in [i0, i1] the midpoints of the intervals of the nearest cut lines.
    void addNeighbours(double v, double i0, double i1, std::vector<double>& us) const {
        const auto above = m_done.lower_bound(v);
        const size_t n = us.size();
        for (auto it : {above, above == m_done.begin() ? m_done.end() : std::prev(above)}) {
            if (it == m_done.end()) continue;
            for (const Interval& x : it->second) {
                const double mid = 0.5 * (x.a + x.b);
                if (mid > i0 && mid < i1) us.push_back(mid);
            }
        }
        if (us.size() != n) std::sort(us.begin(), us.end());
    }

    /// The boxes' u-ranges on line v, merged where they overlap, clipped to the chart.
    struct Range {
        double u0, u1;
        int box;  ///< one box it came from (the one to grow)
    };
    std::vector<Range> ranges(double v, int only) const {
        std::vector<Range> r;
        const double half = std::sqrt(std::max(0.0, kPi * kPi - v * v));
        for (size_t i = 0; i < m_boxes.size(); ++i) {
            const ChartBox& b = m_boxes[i];
            if ((only >= 0 && int(i) != only) || v < b.v0 || v > b.v1) continue;
            const double a = std::max(b.u0, -half), c = std::min(b.u1, half);
            if (a < c) r.push_back({a, c, int(i)});
        }
        std::sort(r.begin(), r.end(), [](const Range& x, const Range& y) { return x.u0 < y.u0; });
        std::vector<Range> merged;
        for (const Range& x : r) {
            if (!merged.empty() && x.u0 <= merged.back().u1) merged.back().u1 = std::max(merged.back().u1, x.u1);
            else merged.push_back(x);
        }
        return merged;
    }

    /// L - T where visible, NaN where not (outside, whatever the threshold).
    double excess(double u, double v) const { return visible(u, v) ? m_f.lobe(u, v) - m_T : std::nan(""); }

    /// Boundary between u = a (membership `inA`) and u = b (the other), to 1e-13 rad: regula falsi with the
    /// Illinois step where both ends see the lobe (~10 evaluations), bisection where one end is below the
    /// horizon (the lobe is not continuous across it).
    double crossing(double a, double b, double v, bool inA, bool& horizon) const {
        double lo = a, hi = b;  // lo has membership inA
        double flo = excess(lo, v), fhi = excess(hi, v);
        int kept = 0;  // +1: lo kept last step, -1: hi kept
        for (int i = 0; i < 200 && std::abs(hi - lo) > 1e-13; ++i) {
            double x = 0.5 * (lo + hi);
            if (std::isfinite(flo) && std::isfinite(fhi) && flo != fhi) {
                const double t = flo / (flo - fhi);
                if (t > 1e-3 && t < 1.0 - 1e-3) x = lo + t * (hi - lo);
            }
            const double fx = excess(x, v);
            const bool inX = std::isfinite(fx) && fx >= 0;
            if (inX == inA) {
                lo = x, flo = fx;
                if (kept == +1) fhi *= 0.5;
                kept = +1;
            } else {
                hi = x, fhi = fx;
                if (kept == -1) flo *= 0.5;
                kept = -1;
            }
        }
        horizon = !visible(inA ? hi : lo, v);  // the side outside the region is below the horizon
        return 0.5 * (lo + hi);
    }

    /// The region reaches a box's side on a line: widen it by half on that side (0: low u, 1: high u).
    void grow(int box, int side) {
        ChartBox& b = m_boxes[size_t(box)];
        const double w = 0.5 * (b.u1 - b.u0);
        (side == 0 ? b.u0 : b.u1) += side == 0 ? -w : w;
        m_grew = true;
    }

    const LobeFunction& m_f;
    double m_T;
    std::vector<ChartBox> m_boxes;
    bool m_grew = false;
    std::map<double, std::vector<Interval>> m_done;  ///< every line cut so far, by v
};

Vec6 integrand(const std::vector<Interval>& iv, double v, dvec2 p) {
    double r0 = 0, r1 = 0, r2 = 0;
    for (const Interval& i : iv) {
        const double a = i.a - p.x, b = i.b - p.x;
        r0 += b - a;
        r1 += 0.5 * (b - a) * (b + a);
        r2 += (b - a) * (a * a + a * b + b * b) / 3.0;
    }
    const double dv = v - p.y;
    return {r0, r1, dv * r0, r2, dv * r1, dv * dv * r0};
}

/// Adaptive Gauss-Kronrod over v in [v0, v1]: the accepted panels' lines (with Kronrod weights).
class Integrator {
public:
    Integrator(Scanner& s, dvec2 p) : m_s(s), m_p(p) {}

    /// Integrates every box's v-range (merged); false if a box had to grow (then start again).
    bool run(std::vector<Line>& lines) {
        lines.clear();
        std::vector<std::pair<double, double>> spans;
        for (const ChartBox& b : m_s.boxes()) spans.push_back({b.v0, b.v1});
        std::sort(spans.begin(), spans.end());
        std::vector<std::pair<double, double>> merged;
        for (auto s : spans) {
            if (!merged.empty() && s.first <= merged.back().second)
                merged.back().second = std::max(merged.back().second, s.second);
            else merged.push_back(s);
        }
        // The ends of every span must be outside the region, or the box grows in v.
        for (size_t i = 0; i < m_s.boxes().size(); ++i) {
            ChartBox& b = m_s.boxes()[i];
            const double h = 0.5 * (b.v1 - b.v0);
            if (!m_s.line(b.v0, int(i)).empty()) b.v0 -= h, m_grew = true;
            if (!m_s.line(b.v1, int(i)).empty()) b.v1 += h, m_grew = true;
        }
        if (m_grew || m_s.grew()) return false;
        // About each seed, panel edges on the scale of the region's extent there (the lines would otherwise
        // miss a part far smaller than its box), and a floor for the moments' scale.
        std::vector<double> edges;
        double floor0 = 0, floor2 = 0;
        for (const ChartBox& b : m_s.boxes()) {
            if (!std::isfinite(b.su) || !std::isfinite(b.sv) || !m_s.in(b.su, b.sv)) continue;
            bool h = false;
            const dvec2 q(b.su, b.sv);
            const double up = m_s.reach(q, {0, 1}, h), down = m_s.reach(q, {0, -1}, h);
            const double wu = m_s.reach(q, {1, 0}, h) + m_s.reach(q, {-1, 0}, h);
            for (double f : {0.25, 0.5, 1.0, 2.0}) edges.push_back(b.sv + f * up), edges.push_back(b.sv - f * down);
            edges.push_back(b.sv);
            floor0 += wu * (up + down);
            floor2 += wu * (up + down) * (wu * wu + (up + down) * (up + down)) / 16;
            lineAt(b.sv);  // the seed's line first: its intervals guide the lines beside it
        }
        // Scale of each moment for the error test: a first pass of 64 lines per span.
        Vec6 coarse{};
        for (auto [a, b] : merged)
            for (int i = 0; i < 64; ++i) {
                const double v = a + (i + 0.5) * (b - a) / 64;
                const Vec6 g = integrand(lineAt(v), v, m_p);
                for (int k = 0; k < 6; ++k) coarse[size_t(k)] += g[size_t(k)] * (b - a) / 64;
            }
        // (The seeds' estimate only where the first pass saw nothing: a part thinner than its lines.)
        const double s0 = std::max(coarse[0] > 0 ? coarse[0] : floor0, 1e-300);
        const double s2 = std::max(coarse[0] > 0 ? coarse[3] + coarse[5] : floor2, 1e-300);
        m_scale = {s0, std::sqrt(s0 * s2), std::sqrt(s0 * s2), s2, s2, s2};
        // (Only there too: where the first pass saw the region, the seeds' edges cost accuracy instead — measured
        // at 60 deg, two parts: aspect off by 1.4e-5 with them, 2e-10 without.)
        if (coarse[0] > 0) edges.clear();
        for (size_t i = 0; i < merged.size(); ++i) {
            std::vector<double> cut = {merged[i].first, merged[i].second};
            for (double e : edges)
                if (e > merged[i].first && e < merged[i].second) cut.push_back(e);
            std::sort(cut.begin(), cut.end());
            cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
            for (size_t k = 0; k + 1 < cut.size(); ++k) panel(cut[k], cut[k + 1], 0, int(i), lines);
        }
        return !(m_grew || m_s.grew());
    }

private:
    std::vector<Interval> lineAt(double v) { return m_s.line(v); }

    void panel(double a, double b, int depth, int span, std::vector<Line>& lines) {
        const double c = 0.5 * (a + b), h = 0.5 * (b - a);
        std::array<Line, 15> ls;
        Vec6 k{}, g{};
        for (int i = 0; i < 15; ++i) {
            const int j = i < 7 ? i : (i == 7 ? 7 : 14 - i);  // node index into the tables
            const double x = i < 7 ? -kXgk[size_t(j)] : (i == 7 ? 0.0 : kXgk[size_t(j)]);
            ls[size_t(i)].v = c + h * x;
            ls[size_t(i)].span = span;
            ls[size_t(i)].iv = lineAt(ls[size_t(i)].v);
            ls[size_t(i)].weight = h * kWgk[size_t(j)];
            const Vec6 f = integrand(ls[size_t(i)].iv, ls[size_t(i)].v, m_p);
            const double wg = (j % 2 == 1) ? kWg[size_t(j / 2)] : 0.0;  // Gauss nodes: odd indices of xgk
            for (int q = 0; q < 6; ++q)
                k[size_t(q)] += kWgk[size_t(j)] * f[size_t(q)], g[size_t(q)] += wg * f[size_t(q)];
        }
        double err = 0;
        for (int q = 0; q < 6; ++q) err = std::max(err, h * std::abs(k[size_t(q)] - g[size_t(q)]) / m_scale[size_t(q)]);
        // Each panel's share of the tolerance: its width's, but at least 1/64 (a panel at the square-root end
        // of a part converges as h^1.5, so a share proportional to h alone would halve it ~60 times).
        const double share = kTol * std::max(2.0 * h / fullSpan(), 1.0 / 64);
        if (err > share && depth < kMaxDepth && ++m_panels > kMaxPanels) m_exhausted = true;
        if (err <= share || depth >= kMaxDepth || m_exhausted) {
            for (Line& l : ls) lines.push_back(std::move(l));
            return;
        }
        panel(a, c, depth + 1, span, lines);
        panel(c, b, depth + 1, span, lines);
    }

    /// The width the tolerance is shared over (the whole v-range of the boxes).
    double fullSpan() const {
        double lo = 1e300, hi = -1e300;
        for (const ChartBox& b : m_s.boxes()) lo = std::min(lo, b.v0), hi = std::max(hi, b.v1);
        return std::max(hi - lo, 1e-300);
    }

    Scanner& m_s;
    dvec2 m_p;
    Vec6 m_scale{};
    bool m_grew = false;
    int m_panels = 0;

public:
    bool m_exhausted = false;  ///< the panel budget ran out before the tolerance was met
};

/// Union-find over the lines' intervals: intervals of neighbouring lines (sorted by v) that overlap in u
/// are one part.
struct Parts {
    std::vector<int> up;
    int find(int i) { return up[size_t(i)] == i ? i : up[size_t(i)] = find(up[size_t(i)]); }
};

AreaMoments momentsOf(const Vec6& m, dvec2 p) {
    AreaMoments r;
    r.area = m[0];
    if (!(m[0] > 0)) return r;
    const double du = m[1] / m[0], dv = m[2] / m[0];
    r.mean_u = p.x + du;
    r.mean_v = p.y + dv;
    r.cuu = m[3] / m[0] - du * du;
    r.cuv = m[4] / m[0] - du * dv;
    r.cvv = m[5] / m[0] - dv * dv;
    return r;
}

/// Full width of the region along the line through p in direction d; `horizon`: an end is the horizon.
double widthThrough(const Scanner& s, dvec2 p, dvec2 d, bool& horizon) {
    bool a = false, b = false;
    const double w = s.reach(p, d, a) + s.reach(p, -d, b);
    horizon = a || b;
    return w;
}

}  // namespace

Shape measureLines(const LobeFunction& f, const Options& opt, double peak, double peak_u, double peak_v,
                   std::vector<ChartBox> boxes) {
    validate(opt);
    if (!f.lobe || !f.visible) throw InputError("measureLines: lobe and visible must both be set");
    Shape s;
    s.minor_pixels = std::numeric_limits<double>::infinity();
    if (!(peak > 0) || boxes.empty()) {
        s.flags.insert(Flag::NoHighlight);
        s.components = 0;
        return s;
    }
    const dvec2 p(peak_u, peak_v);
    Scanner scanner(f, opt.threshold * peak, std::move(boxes));
    std::vector<Line> lines;
    bool exhausted = false;
    for (int g = 0;; ++g) {
        scanner.resetGrew();
        Integrator integ(scanner, p);
        const bool done = integ.run(lines);
        exhausted = integ.m_exhausted;
        if (done) break;
        // A region that still grows after kMaxGrowth enlargements (a thin ring of a tabulated NDF 30 deg off the
        // mirror direction spreads over most of the hemisphere): its budget ran out, named, not an internal error.
        if (g >= kMaxGrowth) {
            exhausted = true;
            break;
        }
    }
    // Parts: each interval belongs to the box (a part of the survey) that holds its midpoint, the one with the
    // nearest seed where boxes overlap; parts whose intervals overlap on neighbouring lines are one. (Linking
    // the intervals alone splits a part wherever the lines are sparse beside a slanting sliver of it.)
    std::sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) { return a.v < b.v; });
    const std::vector<ChartBox>& bx = scanner.boxes();
    auto ownerOf = [&](const Interval& x, double v) {
        const double u = 0.5 * (x.a + x.b);
        int best = 0;
        double bestD = 1e300;
        for (size_t k = 0; k < bx.size(); ++k) {
            const ChartBox& b = bx[k];
            const bool inside = u >= b.u0 && u <= b.u1 && v >= b.v0 && v <= b.v1;
            const double d = (inside ? 0.0 : 1e100) +
                             (std::isfinite(b.su) ? std::hypot(u - b.su, v - b.sv)
                                                  : std::hypot(u - 0.5 * (b.u0 + b.u1), v - 0.5 * (b.v0 + b.v1)));
            if (d < bestD) bestD = d, best = int(k);
        }
        return best;
    };
    std::vector<std::vector<int>> owner(lines.size());
    for (size_t i = 0; i < lines.size(); ++i)
        for (const Interval& x : lines[i].iv) owner[i].push_back(ownerOf(x, lines[i].v));
    Parts parts;
    parts.up.resize(bx.size());
    std::iota(parts.up.begin(), parts.up.end(), 0);
    for (size_t i = 0; i + 1 < lines.size(); ++i)
        for (size_t a = 0; lines[i].span == lines[i + 1].span && a < lines[i].iv.size(); ++a)
            for (size_t b = 0; b < lines[i + 1].iv.size(); ++b) {
                const Interval &x = lines[i].iv[a], &y = lines[i + 1].iv[b];
                if (x.a <= y.b && y.a <= x.b) parts.up[size_t(parts.find(owner[i][a]))] = parts.find(owner[i + 1][b]);
            }
    // Moments per part and in all.
    std::vector<int> partOf(parts.up.size(), -1);
    std::vector<Vec6> sums;
    std::vector<char> cut;
    Vec6 all{};
    bool anyCut = false;
    int peakPart = -1;
    for (size_t i = 0; i < lines.size(); ++i)
        for (size_t a = 0; a < lines[i].iv.size(); ++a) {
            const int root = parts.find(owner[i][a]);
            if (partOf[size_t(root)] < 0) partOf[size_t(root)] = int(sums.size()), sums.push_back({}), cut.push_back(0);
            const int k = partOf[size_t(root)];
            const Vec6 g = integrand({lines[i].iv[a]}, lines[i].v, p);
            for (int q = 0; q < 6; ++q)
                sums[size_t(k)][size_t(q)] += lines[i].weight * g[size_t(q)],
                    all[size_t(q)] += lines[i].weight * g[size_t(q)];
            cut[size_t(k)] = cut[size_t(k)] || lines[i].iv[a].horizon;
            anyCut = anyCut || lines[i].iv[a].horizon;
        }
    // The part holding the peak: the interval nearest p on the lines nearest p's v.
    double best = 1e300;
    for (size_t i = 0; i < lines.size(); ++i)
        for (size_t a = 0; a < lines[i].iv.size(); ++a) {
            const Interval& x = lines[i].iv[a];
            const double du = p.x < x.a ? x.a - p.x : (p.x > x.b ? p.x - x.b : 0.0);
            const double d = std::hypot(du, lines[i].v - p.y);
            if (d < best) best = d, peakPart = partOf[size_t(parts.find(owner[i][a]))];
        }
    setEllipse(s, momentsOf(all, p));
    s.peak = peak;
    s.peak_u_deg = rad2deg(p.x);
    s.peak_v_deg = rad2deg(p.y);
    // The lines through the peak: their ends at the horizon count as a cut (a region that touches the
    // horizon at a point alone, e.g. the peak on it, is cut on no line v = const).
    bool cutU = false, cutV = false;
    s.fwhm_u_deg = rad2deg(widthThrough(scanner, p, {1, 0}, cutU));
    s.fwhm_v_deg = rad2deg(widthThrough(scanner, p, {0, 1}, cutV));
    anyCut = anyCut || cutU || cutV;
    s.components = int(sums.size());
    if (sums.size() > 1) {
        for (size_t k = 0; k < sums.size(); ++k) {
            PartShape ps;
            setEllipse(ps, momentsOf(sums[k], p));
            ps.horizon_cut = cut[k] != 0;
            ps.holds_peak = int(k) == peakPart;
            s.parts.push_back(ps);
        }
        std::stable_sort(s.parts.begin(), s.parts.end(), [](const PartShape& a, const PartShape& b) {
            if (a.holds_peak != b.holds_peak) return a.holds_peak;
            return a.area_deg2 > b.area_deg2;
        });
    }
    if (anyCut) s.flags.insert(Flag::HorizonCut);
    if (exhausted) s.flags.insert(Flag::NotConverged);
    return s;
}

}  // namespace hilite::analysis
