// measureImage: the highlight of a rendered measurement view.
//   Pass 1 (survey) reads every pixel once: the peak, the smallest visible L, the largest L of each run of
//     32 pixels of a row, and a dense copy of L (4 bytes a pixel instead of 16).
//   Pass 2 visits only the runs that can hold region or contour pixels. Each run becomes two bit masks
//     (visible, in), so the flags and the contour test are a few word operations per 32 pixels, and only
//     the pixels that count read their (u, v, w).
//   Two short walks through the peak give the sub-pixel widths.
// Pass 1 is bound by memory bandwidth (the image is 4 MB at 512^2); pass 2 by the moment sums.

#include "analysis/image_variants.hpp"
#include "analysis/runs.hpp"
#include "hilite/analysis/highlight.hpp"

#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace hilite::analysis {

namespace {

/// Read-only view of the (L, u, v, w) image, plus the dense copy of L (L where w > 0, else -1).
struct Pixels {
    const float* data;
    int width, height;
    float* dense;

    size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
    const float* at(int x, int y) const { return data + 4 * index(x, y); }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
    bool visible(int x, int y) const { return dense[index(x, y)] >= 0.f; }
    float L(int x, int y) const { return dense[index(x, y)]; }
    dvec2 uv(int x, int y) const { return {at(x, y)[1], at(x, y)[2]}; }
    int runs() const { return (width + kRun - 1) / kRun; }
    int runLength(int run) const { return std::min(kRun, width - run * kRun); }
};

/// Pass 1: over the pixels that see the surface (w > 0), the peak, the smallest L, and each run's largest L.
struct Survey {
    float peak = 0.f, minVisible = std::numeric_limits<float>::infinity();
    bool nonFinite = false;  ///< a visible pixel holds an inf or NaN L (float_overflow)
    int x = -1, y = -1;
    std::vector<float> runMax;  ///< height * runs(); -1 for a run of sky
};

Survey survey(const Pixels& px) {
    Survey s;
    const int runs = px.runs();
    s.runMax.resize(size_t(px.height) * size_t(runs));
    for (int y = 0; y < px.height; ++y) {
        for (int r = 0; r < runs; ++r) {
            float m = -1.f, lo = s.minVisible;
            int x = r * kRun;
            const int end = r * kRun + px.runLength(r);
#if defined(__SSE2__)
            // Four pixels at a time, transposed to an L and a w vector: the scalar loop below was a third of
            // the analysis (a branch per pixel). Same values: max(L, 0) is 0 for a NaN L, as std::max(0, L).
            const __m128 zero = _mm_setzero_ps(), minus1 = _mm_set1_ps(-1.f);
            const __m128 inf = _mm_set1_ps(std::numeric_limits<float>::infinity());
            const __m128 floatMax = _mm_set1_ps(std::numeric_limits<float>::max());
            const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
            __m128 mv = minus1, lov = inf, bad = zero;
            for (; x + 4 <= end; x += 4) {
                const float* q = px.at(x, y);
                const __m128 p0 = _mm_loadu_ps(q), p1 = _mm_loadu_ps(q + 4), p2 = _mm_loadu_ps(q + 8),
                             p3 = _mm_loadu_ps(q + 12);
                const __m128 t0 = _mm_unpacklo_ps(p0, p1), t1 = _mm_unpacklo_ps(p2, p3);  // L0 L1 u0 u1, L2 L3 u2 u3
                const __m128 t2 = _mm_unpackhi_ps(p0, p1), t3 = _mm_unpackhi_ps(p2, p3);  // v0 v1 w0 w1, v2 v3 w2 w3
                const __m128 raw = _mm_movelh_ps(t0, t1);
                const __m128 L = _mm_max_ps(raw, zero), w = _mm_movehl_ps(t3, t2);
                const __m128 visible = _mm_cmpgt_ps(w, zero);
                // not |L| <= FLT_MAX: inf or NaN (the unordered compare is true for NaN)
                bad = _mm_or_ps(bad, _mm_and_ps(visible, _mm_cmpnle_ps(_mm_and_ps(raw, absMask), floatMax)));
                const __m128 dense = _mm_or_ps(_mm_and_ps(visible, L), _mm_andnot_ps(visible, minus1));
                _mm_storeu_ps(px.dense + px.index(x, y), dense);
                mv = _mm_max_ps(mv, dense);
                lov = _mm_min_ps(lov, _mm_or_ps(_mm_and_ps(visible, L), _mm_andnot_ps(visible, inf)));
            }
            alignas(16) float mm[4], ll[4];
            _mm_store_ps(mm, mv);
            _mm_store_ps(ll, lov);
            for (int k = 0; k < 4; ++k) m = std::max(m, mm[k]), lo = std::min(lo, ll[k]);
            if (_mm_movemask_ps(bad)) s.nonFinite = true;
#endif
            for (; x < end; ++x) {
                const float* q = px.at(x, y);
                const bool visible = q[3] > 0.f;
                const float L = visible ? std::max(0.f, q[0]) : -1.f;  // (a negative or NaN L counts as 0)
                if (visible && !std::isfinite(q[0])) s.nonFinite = true;
                px.dense[px.index(x, y)] = L;
                m = std::max(m, L);
                lo = std::min(lo, visible ? L : lo);
            }
            s.minVisible = lo;
            s.runMax[size_t(y) * size_t(runs) + size_t(r)] = m;
            s.peak = std::max(s.peak, m);  // the location is found afterwards, once, in the best run
        }
    }
    return s;
}

/// Where the peak is: the first visible pixel holding it (rows bottom-up, then columns).
void locatePeak(const Pixels& px, Survey& s) {
    const int runs = px.runs();
    for (size_t i = 0; i < s.runMax.size(); ++i) {
        if (s.runMax[i] != s.peak) continue;
        const int y = int(i / size_t(runs)), x0 = int(i % size_t(runs)) * kRun;
        for (int x = x0; x < x0 + px.runLength(x0 / kRun); ++x) {
            if (px.L(x, y) == s.peak) {
                s.x = x;
                s.y = y;
                return;
            }
        }
    }
}

/// The threshold as pass 2 compares it.
struct Threshold {
    double T;
    float Tf;  ///< (L >= Tf) <=> (double(L) >= T): the smallest float not below T
    explicit Threshold(double t) : T(t), Tf(float(t)) {
        if (double(Tf) < T) Tf = std::nextafter(Tf, std::numeric_limits<float>::infinity());
    }
};

/// The seed runs grown by one run in every direction: along each row, then across the rows (the square's dilation
/// is separable; each seed's square written run by run took 2% of a table's row, where it is called 16 times).
std::vector<char> runsNear(const Pixels& px, const std::vector<char>& seed) {
    const size_t runs = size_t(px.runs()), rows = size_t(px.height);
    std::vector<char> along(seed.size()), out(seed.size());
    for (size_t y = 0; y < rows; ++y) {
        const char* s = &seed[y * runs];
        char* a = &along[y * runs];
        if (runs == 1) {
            a[0] = s[0];
            continue;
        }
        a[0] = char(s[0] | s[1]);
        for (size_t r = 1; r + 1 < runs; ++r) a[r] = char(s[r - 1] | s[r] | s[r + 1]);
        a[runs - 1] = char(s[runs - 2] | s[runs - 1]);
    }
    for (size_t y = 0; y < rows; ++y) {
        const char* a = &along[y * runs];
        const char* below = y > 0 ? a - runs : a;
        const char* above = y + 1 < rows ? a + runs : a;
        char* o = &out[y * runs];
        for (size_t r = 0; r < runs; ++r) o[r] = char(below[r] | a[r] | above[r]);
    }
    return out;
}

/// Bit masks of one run (bit i: pixel run * 32 + i): visible (w > 0) and in (L >= T). Pixels outside
/// the image have neither bit.
struct RunMask {
    uint32_t vis = 0, in = 0;
};

/// The masks of one run of n <= 32 dense values c.
RunMask runMask(const float* c, int n, float Tf) {
    uint32_t vis = 0, in = 0;
    int b = 0;
#if defined(__SSE2__)
    // Four pixels per compare; the plain loop below is 5x slower (a shift and an or per bit).
    const __m128 zero = _mm_setzero_ps(), t = _mm_set1_ps(Tf);
    for (; b + 4 <= n; b += 4) {
        const __m128 L = _mm_loadu_ps(c + b);
        vis |= uint32_t(_mm_movemask_ps(_mm_cmpge_ps(L, zero))) << b;
        in |= uint32_t(_mm_movemask_ps(_mm_cmpge_ps(L, t))) << b;
    }
#endif
    for (; b < n; ++b) {
        vis |= uint32_t(c[b] >= 0.f) << b;
        in |= uint32_t(c[b] >= Tf) << b;
    }
    return {vis, in};
}

/// The masks of the runs pass 2 visits (active) and of their neighbours (the contour and sky tests look
/// one pixel beyond the run): 0 elsewhere.
std::vector<RunMask> runMasks(const Pixels& px, const std::vector<char>& active, float Tf) {
    const std::vector<char> needed = runsNear(px, active);
    std::vector<RunMask> masks(needed.size());
    const int runs = px.runs();
    for (size_t i = 0; i < needed.size(); ++i) {
        if (!needed[i]) continue;
        const int y = int(i / size_t(runs)), r = int(i % size_t(runs));
        masks[i] = runMask(px.dense + px.index(r * kRun, y), px.runLength(r), Tf);
    }
    return masks;
}

/// Fraction of a unit pixel on the side n.(p - centre) <= d of a line with unit normal (nx, ny): the
/// distribution function of n.p for p uniform in the pixel (trapezoidal density of half-width (a+b)/2).
double coverage(double d, double nx, double ny) {
    const double a = std::max(std::abs(nx), std::abs(ny)), b = std::min(std::abs(nx), std::abs(ny));
    if (d > 0.0) return 1.0 - coverage(-d, nx, ny);
    const double e = d + 0.5 * (a + b);  // distance past the pixel's first corner
    if (e <= 0.0) return 0.0;
    if (e < b) return e * e / (2.0 * a * b);  // a corner triangle (b > 0 here; a >= 1/sqrt(2) always)
    return 0.5 + d / a;
}

/// dL per pixel step (dx, dy) at (x, y): central difference, one-sided beside the sky or the border.
double slope(const Pixels& px, int x, int y, int dx, int dy) {
    const bool fwd = px.inside(x + dx, y + dy) && px.visible(x + dx, y + dy);
    const bool bwd = px.inside(x - dx, y - dy) && px.visible(x - dx, y - dy);
    if (fwd && bwd) return 0.5 * (double(px.L(x + dx, y + dy)) - px.L(x - dx, y - dy));
    if (fwd) return double(px.L(x + dx, y + dy)) - px.L(x, y);
    if (bwd) return double(px.L(x, y)) - px.L(x - dx, y - dy);
    return 0.0;
}

/// Covered fraction of a contour pixel: L ~ L(centre) + g.(p - centre), inside where that is >= T.
double contourFraction(const Pixels& px, int x, int y, double T) {
    const double gx = slope(px, x, y, 1, 0), gy = slope(px, x, y, 0, 1), g = std::sqrt(gx * gx + gy * gy);
    const double L = px.L(x, y);
    if (!(g > 0.0)) return L >= T ? 1.0 : 0.0;     // flat: no line to fit, fall back to the centre
    return coverage((L - T) / g, gx / g, gy / g);  // inside: g.(p - c) >= T - L, i.e. (-g/|g|).(p - c) <= d
}

/// Number of set bits (SWAR; __builtin_popcount is a library call without -mpopcnt).
inline int bitCount(uint32_t m) {
    m = m - ((m >> 1) & 0x55555555u);
    m = (m & 0x33333333u) + ((m >> 2) & 0x33333333u);
    return int((((m + (m >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24);
}

/// Moment sums of some pixels, about a shift point (the peak's (u, v), against cancellation).
struct Sums {
    double s0 = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0;

    void add(const float* q, double f, dvec2 shift) {
        const double w = f * q[3], du = q[1] - shift.x, dv = q[2] - shift.y, wu = w * du, wv = w * dv;
        s0 += w;
        su += wu;
        sv += wv;
        suu += wu * du;
        suv += wu * dv;
        svv += wv * dv;
    }
    void add(const Sums& o) {
        s0 += o.s0;
        su += o.su;
        sv += o.sv;
        suu += o.suu;
        suv += o.suv;
        svv += o.svv;
    }
};

/// What pass 2 gathers.
struct RegionSums {
    Sums m;
    long pixels = 0;
    bool touchesBorder = false, touchesSky = false;
};

/// The weight of a pixel wholly inside the region.
struct WholePixel {
    double operator()(int) const { return 1.0; }
};

/// Adds the pixels of `bits` (of the run starting at x0 in row y), each with weight f(x) * w.
template <typename Fraction>
void accumulate(const Pixels& px, int x0, int y, uint32_t bits, dvec2 shift, Fraction f, Sums& sums) {
    // Two sets of sums, alternating: each sum is a chain of dependent adds, so this halves the time.
    // (__builtin_ctz: gcc and clang; bits != 0 here.)
#if defined(__SSE2__)
    // The two sets as the two lanes of SSE2 doubles: the same operations in the same order, so the same
    // sums bit for bit, two pixels an instruction. A lone last pixel pairs with a zero one (w = 0 adds 0).
    static const float kNone[4] = {0.f, 0.f, 0.f, 0.f};
    const __m128d sx = _mm_set1_pd(shift.x), sy = _mm_set1_pd(shift.y);
    __m128d s0 = _mm_setzero_pd(), su = s0, sv = s0, suu = s0, suv = s0, svv = s0;
    const auto pair = [&](const float* qa, const float* qb, __m128d f2) {
        const __m128 A = _mm_loadu_ps(qa), B = _mm_loadu_ps(qb);
        const __m128 S = _mm_unpacklo_ps(A, B), T = _mm_unpackhi_ps(A, B);  // La Lb ua ub, va vb wa wb
        const __m128d w = _mm_mul_pd(f2, _mm_cvtps_pd(_mm_movehl_ps(T, T)));
        const __m128d du = _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(S, S)), sx);
        const __m128d dv = _mm_sub_pd(_mm_cvtps_pd(T), sy);
        const __m128d wu = _mm_mul_pd(w, du), wv = _mm_mul_pd(w, dv);
        s0 = _mm_add_pd(s0, w);
        su = _mm_add_pd(su, wu);
        sv = _mm_add_pd(sv, wv);
        suu = _mm_add_pd(suu, _mm_mul_pd(wu, du));
        suv = _mm_add_pd(suv, _mm_mul_pd(wu, dv));
        svv = _mm_add_pd(svv, _mm_mul_pd(wv, dv));
    };
    if (bits == ~0u && std::is_same_v<Fraction, WholePixel>) {  // a full run inside: pixels in pairs, no bit scan
        const float* q = px.at(x0, y);
        for (int i = 0; i < 32; i += 2, q += 8) pair(q, q + 4, _mm_set1_pd(1.0));
        bits = 0;
    }
    while (bits != 0) {
        const int xa = x0 + __builtin_ctz(bits);
        bits &= bits - 1;
        const double fa = f(xa);
        const float* qb = kNone;
        double fb = 0.0;
        if (bits != 0) {
            const int xb = x0 + __builtin_ctz(bits);
            bits &= bits - 1;
            qb = px.at(xb, y);
            fb = f(xb);
        }
        pair(px.at(xa, y), qb, _mm_set_pd(fb, fa));
    }
    alignas(16) double l[6][2];
    _mm_store_pd(l[0], s0), _mm_store_pd(l[1], su), _mm_store_pd(l[2], sv);
    _mm_store_pd(l[3], suu), _mm_store_pd(l[4], suv), _mm_store_pd(l[5], svv);
    for (int lane = 0; lane < 2; ++lane)
        sums.add(Sums{l[0][lane], l[1][lane], l[2][lane], l[3][lane], l[4][lane], l[5][lane]});
#else
    Sums a, b;
    while (bits != 0) {
        const int xa = x0 + __builtin_ctz(bits);
        bits &= bits - 1;
        a.add(px.at(xa, y), f(xa), shift);
        if (bits == 0) break;
        const int xb = x0 + __builtin_ctz(bits);
        bits &= bits - 1;
        b.add(px.at(xb, y), f(xb), shift);
    }
    sums.add(a);
    sums.add(b);
#endif
}

/// The masks of the 4-neighbours of every pixel of a run, and which neighbours are inside the image.
struct Around {
    uint32_t visL, inL, visR, inR, visD, inD, visU, inU;  ///< left, right, down (y - 1), up (y + 1)
    uint32_t insideL, insideR, insideD, insideU;
};

Around around(const Pixels& px, const std::vector<RunMask>& masks, int y, int r) {
    const int runs = px.runs(), n = px.runLength(r), x0 = r * kRun;
    auto get = [&](int yy, int rr) {
        return (yy < 0 || yy >= px.height || rr < 0 || rr >= runs) ? RunMask{}
                                                                   : masks[size_t(yy) * size_t(runs) + size_t(rr)];
    };
    const RunMask c = get(y, r), left = get(y, r - 1), right = get(y, r + 1), down = get(y - 1, r), up = get(y + 1, r);
    Around a;
    a.visL = (c.vis << 1) | (left.vis >> 31);
    a.inL = (c.in << 1) | (left.in >> 31);
    a.visR = (c.vis >> 1) | (right.vis << 31);  // a short last run has no bit 31 and no right run
    a.inR = (c.in >> 1) | (right.in << 31);
    a.visD = down.vis, a.inD = down.in, a.visU = up.vis, a.inU = up.in;
    const uint32_t all = n == 32 ? ~0u : (1u << n) - 1u;
    a.insideL = x0 > 0 ? all : all & ~1u;
    a.insideR = x0 + n < px.width ? all : all & ~(1u << (n - 1));
    a.insideD = y > 0 ? all : 0u;
    a.insideU = y + 1 < px.height ? all : 0u;
    return a;
}

/// Pass 2 on one run: flags from the masks, then the moment sums of its in and contour pixels, of those in
/// `only`'s bits (ImageVariants sums a run's pixels in two parts). Returns those of its contour pixels.
uint32_t scanRun(const Pixels& px, const std::vector<RunMask>& masks, int y, int r, const Threshold& th, bool subpixel,
                 dvec2 shift, RegionSums& sums, uint32_t only = ~0u) {
    const RunMask c = masks[size_t(y) * size_t(px.runs()) + size_t(r)];
    const Around a = around(px, masks, y, r);
    const int x0 = r * kRun, n = px.runLength(r);
    const uint32_t sky = (a.insideL & ~a.visL) | (a.insideR & ~a.visR) | (a.insideD & ~a.visD) | (a.insideU & ~a.visU);
    const uint32_t rim =
        (y == 0 || y == px.height - 1) ? ~0u : (x0 == 0 ? 1u : 0u) | (x0 + n == px.width ? 1u << (n - 1) : 0u);
    const uint32_t in = c.in & only;
    sums.pixels += bitCount(in);
    sums.touchesSky = sums.touchesSky || (in & sky) != 0;
    sums.touchesBorder = sums.touchesBorder || (in & rim) != 0;
    // Contour: visible, with a visible 4-neighbour on the other side of T.
    const uint32_t contour = subpixel ? only & c.vis &
                                            ((a.visL & (a.inL ^ c.in)) | (a.visR & (a.inR ^ c.in)) |
                                             (a.visD & (a.inD ^ c.in)) | (a.visU & (a.inU ^ c.in)))
                                      : 0u;
    const auto covered = [&](int x) { return contourFraction(px, x, y, th.T); };
    accumulate(px, x0, y, in & ~contour, shift, WholePixel{}, sums.m);
    if (contour) accumulate(px, x0, y, contour, shift, covered, sums.m);
    return contour;
}

/// The runs pass 2 visits: those that hold an L >= T (and, with sub-pixel coverage, their neighbours).
std::vector<char> activeRuns(const Pixels& px, const std::vector<float>& runMax, const Threshold& th, bool subpixel) {
    std::vector<char> active(runMax.size());
    for (size_t i = 0; i < active.size(); ++i) active[i] = runMax[i] >= th.Tf;
    if (subpixel) active = runsNear(px, active);  // an outside contour pixel neighbours an inside one
    return active;
}

/// Pass 2 over activeRuns.
RegionSums scanRegion(const Pixels& px, const Survey& s, const Threshold& th, bool subpixel, dvec2 shift) {
    const std::vector<char> active = activeRuns(px, s.runMax, th, subpixel);
    const std::vector<RunMask> masks = runMasks(px, active, th.Tf);
    const int runs = px.runs();
    RegionSums sums;
    for (int y = 0; y < px.height; ++y)
        for (int r = 0; r < runs; ++r)
            if (active[size_t(y) * size_t(runs) + size_t(r)]) scanRun(px, masks, y, r, th, subpixel, shift, sums);
    return sums;
}

AreaMoments toMoments(const Sums& r, dvec2 shift) {
    AreaMoments m;
    m.area = r.s0;
    const double du = r.su / r.s0, dv = r.sv / r.s0;
    m.mean_u = shift.x + du;
    m.mean_v = shift.y + dv;
    m.cuu = r.suu / r.s0 - du * du;
    m.cuv = r.suv / r.s0 - du * dv;
    m.cvv = r.svv / r.s0 - dv * dv;
    return m;
}

/// The (u,v) point where L crosses T, walking from the region pixel (x, y) in steps (dx, dy).
/// Between an in pixel and an out pixel: linear interpolation of L, then of (u, v). If the out pixel
/// sees the sky (its u, v are 0) the region ends at the horizon, somewhere between the centres: take
/// the pixel edge, with the out centre extrapolated from the in side. At the image border: the last centre.
dvec2 crossing(const Pixels& px, int x, int y, int dx, int dy, double T) {
    for (;;) {
        const int nx = x + dx, ny = y + dy;
        if (!px.inside(nx, ny)) return px.uv(x, y);
        const bool visible = px.visible(nx, ny);
        if (visible && double(px.L(nx, ny)) >= T) {
            x = nx;
            y = ny;
            continue;
        }
        const dvec2 in = px.uv(x, y);
        if (visible) {
            const double Lin = px.L(x, y), Lout = px.L(nx, ny);
            return in + (Lin - T) / (Lin - Lout) * (px.uv(nx, ny) - in);
        }
        const bool back = px.inside(x - dx, y - dy) && px.visible(x - dx, y - dy);
        return back ? in + 0.5 * (in - px.uv(x - dx, y - dy)) : in;
    }
}

/// Whether the image rows run along u (else along v): compare the change of u and of v to a neighbour.
bool rowsAlongU(const Pixels& px, int x, int y) {
    const int nx = x + 1 < px.width ? x + 1 : x - 1;
    if (px.inside(nx, y) && px.visible(nx, y)) {
        const dvec2 d = px.uv(nx, y) - px.uv(x, y);
        return std::abs(d.x) >= std::abs(d.y);
    }
    const int ny = y + 1 < px.height ? y + 1 : y - 1;
    if (px.inside(x, ny) && px.visible(x, ny)) {
        const dvec2 d = px.uv(x, ny) - px.uv(x, y);
        return std::abs(d.y) >= std::abs(d.x);
    }
    return false;  // a lone visible pixel: the measurement camera's convention (columns along u)
}

void setWidths(Shape& s, const Pixels& px, int x, int y, double T) {
    const double alongRow = glm::length(crossing(px, x, y, 1, 0, T) - crossing(px, x, y, -1, 0, T));
    const double alongCol = glm::length(crossing(px, x, y, 0, 1, T) - crossing(px, x, y, 0, -1, T));
    const bool rowsU = rowsAlongU(px, x, y);
    s.fwhm_u_deg = rad2deg(rowsU ? alongRow : alongCol);
    s.fwhm_v_deg = rad2deg(rowsU ? alongCol : alongRow);
}

/// measureImage after its survey: the flags, the region's moments and the widths. region(th, shift) gathers the
/// region's sums at the threshold th about shift (the peak's (u, v), which it may replace).
template <class Region>
Shape finish(const Pixels& px, Survey& sv, const Options& opt, Region region) {
    Shape s;
    // Pixels past float's range describe no lobe (NaN counts as 0 below, inf swallows the threshold): name it.
    if (sv.nonFinite) {
        setUnmeasured(s, Flag::FloatOverflow);
        return s;
    }
    // A level among the denormals (or below them: 0) compares pixels that have lost the lobe's digits.
    if (sv.peak > 0.f &&
        (opt.level > 0 ? opt.level : opt.threshold * double(sv.peak)) < double(std::numeric_limits<float>::min())) {
        setUnmeasured(s, Flag::FloatUnderflow);
        return s;
    }
    if (!(sv.peak > 0.f) ||
        (opt.level > 0 && double(sv.peak) < opt.level)) {  // all dark, nothing visible or above the level
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    locatePeak(px, sv);
    const Threshold th(opt.level > 0 ? opt.level : opt.threshold * double(sv.peak));
    const dvec2 peakUV = px.uv(sv.x, sv.y);
    dvec2 shift = peakUV;
    const RegionSums sums = region(th, shift);  // never empty: the peak pixel is in it
    setEllipse(s, toMoments(sums.m, shift));
    s.peak = sv.peak;
    s.peak_u_deg = rad2deg(peakUV.x);
    s.peak_v_deg = rad2deg(peakUV.y);
    s.region_pixels = sums.pixels;
    setWidths(s, px, sv.x, sv.y, th.T);

    // Pixel pitch: sqrt of the mean (u,v) area of the region's pixels (their weights sum to about s0).
    const double pitch = std::sqrt(sums.m.s0 / double(sums.pixels));
    s.minor_pixels = 2.0 * deg2rad(s.minor_deg) / pitch;
    if (sums.touchesBorder) s.flags.insert(Flag::Clipped);
    if (sums.touchesSky) s.flags.insert(Flag::HorizonCut);
    if (s.minor_pixels < opt.minPixelsAcross) s.flags.insert(Flag::UnderResolved);
    if (double(sv.minVisible) >= th.T) s.flags.insert(Flag::CoversFrame);
    return s;
}

}  // namespace

Shape measureImage(const float* pixels, int width, int height, const Options& opt) {
    validate(opt);
    if (pixels == nullptr || width <= 0 || height <= 0) throw InputError("measureImage: empty image");
    std::unique_ptr<float[]> dense(new float[size_t(width) * size_t(height)]);  // filled by survey()
    const Pixels px{pixels, width, height, dense.get()};
    Survey sv = survey(px);
    return finish(px, sv, opt,
                  [&](const Threshold& th, dvec2& shift) { return scanRegion(px, sv, th, opt.subpixel, shift); });
}

ImageVariants::ImageVariants(const float* pixels, int width, int height)
    : m_pixels(pixels), m_width(width), m_height(height) {
    if (pixels == nullptr || width <= 0 || height <= 0) throw InputError("measureImage: empty image");
    m_dense.resize(size_t(width) * size_t(height));
    const Pixels px{pixels, width, height, m_dense.data()};
    Survey sv = survey(px);
    locatePeak(px, sv);
    if (sv.x >= 0) m_peakPixel = px.index(sv.x, sv.y);
    m_runMax = sv.runMax;
    m_runMaxKept = sv.runMax;
    m_peak = sv.peak;
    m_nonFinite = sv.nonFinite;
    // No pixel changed yet: measure gives measureImage's shape of the image itself (default options).
    m_minKept = sv.minVisible;
    m_nonFiniteKept = sv.nonFinite;
}

void ImageVariants::setChanged(std::vector<size_t> at, const Options& opt) {
    validate(opt);
    m_opt = opt;
    m_at = std::move(at);
    const size_t n = m_dense.size();
    const Pixels px{m_pixels, m_width, m_height, m_dense.data()};
    const int runs = px.runs();
    std::vector<char> patched(n, 0);
    // Per run, the bits of the pixels a variant changes or that read one as a 4-neighbour (the contour test and
    // the covered share): the pixels whose sums are the variant's own.
    m_dependent.assign(m_runMax.size(), 0u);
    m_atRun.clear();
    auto depend = [&](int x, int y) {
        if (x >= 0 && y >= 0 && x < m_width && y < m_height)
            m_dependent[size_t(y) * size_t(runs) + size_t(x / kRun)] |= 1u << (x % kRun);
    };
    for (const size_t i : m_at) {
        if (i >= n) throw InputError("measureImage: a variant's pixel lies outside the image");
        patched[i] = 1;
        const int x = int(i % size_t(m_width)), y = int(i / size_t(m_width));
        m_atRun.push_back(size_t(y) * size_t(runs) + size_t(x / kRun));
        depend(x, y), depend(x - 1, y), depend(x + 1, y), depend(x, y - 1), depend(x, y + 1);
    }
    // The largest L of each run that holds a changed pixel, of its other pixels (-1: none, or only sky): measure adds
    // the variant's L to it.
    m_runMaxKept = m_runMax;
    for (const size_t r : m_atRun) m_runMaxKept[r] = -1.f;
    for (const size_t r : m_atRun) {
        if (m_runMaxKept[r] != -1.f) continue;  // done (or a run left as it was, which has no changed pixel)
        const int y = int(r / size_t(runs)), x0 = int(r % size_t(runs)) * kRun;
        float m = -1.f;
        for (int x = x0; x < x0 + px.runLength(x0 / kRun); ++x)
            m = patched[px.index(x, y)] ? m : std::max(m, px.L(x, y));
        m_runMaxKept[r] = m;
    }
    m_dependentRuns.clear();
    for (size_t r = 0; r < m_dependent.size(); ++r)
        if (m_dependent[r]) m_dependentRuns.push_back(r);
    m_kept.resize(m_at.size());
    for (size_t j = 0; j < m_at.size(); ++j) m_kept[j] = m_dense[m_at[j]];
    // What the pixels left as they are hold: their smallest visible L (survey: L >= 0 there, -1 elsewhere), and
    // whether one is past float's range (only where the survey found one).
    m_nonFiniteKept = false;
    if (m_nonFinite)
        for (size_t i = 0; i < n; ++i)
            m_nonFiniteKept = m_nonFiniteKept || (!patched[i] && m_dense[i] >= 0.f && !std::isfinite(m_pixels[4 * i]));

    // The fixed pixels' sums (every other pixel's), gathered once here at the image's threshold and about its
    // peak: no variant changes what scanRun reads for them.
    m_fixed = {};
    m_fixedValid = false;
    if (m_nonFinite || !(m_peak > 0.f)) {
        float lo = std::numeric_limits<float>::infinity();
        for (size_t i = 0; i < n; ++i) lo = std::min(lo, patched[i] || m_dense[i] < 0.f ? lo : m_dense[i]);
        m_minKept = lo;
        return;
    }
    Survey sv;
    sv.runMax = m_runMax;
    sv.peak = m_peak;
    locatePeak(px, sv);
    m_shift = px.uv(sv.x, sv.y);
    const Threshold th(opt.level > 0 ? opt.level : opt.threshold * double(m_peak));
    m_Tf = th.Tf;
    const std::vector<char> active = activeRuns(px, m_runMax, th, opt.subpixel);
    const std::vector<RunMask> masks = runMasks(px, active, th.Tf);
    RegionSums sums;
    uint32_t contour = 0;
    for (size_t i = 0; i < active.size(); ++i)
        if (active[i])
            contour |= scanRun(px, masks, int(i / size_t(runs)), int(i % size_t(runs)), th, opt.subpixel, m_shift, sums,
                               ~m_dependent[i]);
    m_fixed = {sums.m.s0, sums.m.su, sums.m.sv, sums.m.suu, sums.m.suv, sums.m.svv};
    m_fixedPixels = sums.pixels;
    m_fixedSky = sums.touchesSky;
    m_fixedBorder = sums.touchesBorder;
    m_fixedContour = contour != 0;
    // The L of the pixels left as they are nearest the threshold on either side: a variant's threshold leaves
    // each on its side (and so every fixed pixel's contour test) while it lies in (below, above].
    float lo = std::numeric_limits<float>::infinity(), below = -lo, above = lo;
    for (size_t i = 0; i < n; ++i) {
        const float L = patched[i] ? -1.f : m_dense[i];  // -1: the sky, or a pixel a variant changes
        lo = std::min(lo, L < 0.f ? lo : L);
        below = std::max(below, L < th.Tf ? L : below);
        above = std::min(above, L < th.Tf ? above : L);
    }
    m_minKept = lo, m_below = below, m_above = above;
    m_fixedValid = true;
}

Shape ImageVariants::measure(const float* values, size_t stride) {
    std::vector<float>& dense = m_dense;  // with the variant's L written in, and taken out again below
    const Pixels px{m_pixels, m_width, m_height, dense.data()};
    // survey()'s values for the patched pixels, then for the runs that hold them.
    Survey sv;
    sv.minVisible = m_minKept;
    sv.nonFinite = m_nonFiniteKept;
    sv.runMax = m_runMaxKept;
    for (size_t j = 0; j < m_at.size(); ++j) {
        if (m_kept[j] < 0.f) continue;  // a pixel that sees no surface (w <= 0) keeps no L
        const float raw = values[j * stride], L = std::max(0.f, raw);
        sv.nonFinite = sv.nonFinite || !std::isfinite(raw);
        dense[m_at[j]] = L;
        sv.minVisible = std::min(sv.minVisible, L);
        sv.runMax[m_atRun[j]] = std::max(sv.runMax[m_atRun[j]], L);
    }
    const int runs = px.runs();
    for (const float m : sv.runMax) sv.peak = std::max(sv.peak, m);
    const Shape shape = finish(px, sv, m_opt, [&](const Threshold& th, dvec2& shift) {
        // The fixed pixels' sums hold where this threshold leaves every pixel left as it is on its side, and, where
        // it is not the image's own, the fixed pixels hold no contour pixel (whose covered share it would move).
        const bool fixedHolds =
            m_fixedValid && (th.Tf == m_Tf || (!m_fixedContour && m_below < th.Tf && th.Tf <= m_above));
        if (!fixedHolds) return scanRegion(px, sv, th, m_opt.subpixel, shift);
        ++m_fixedUsed;
        shift = m_shift;
        RegionSums sums;
        sums.m = Sums{m_fixed[0], m_fixed[1], m_fixed[2], m_fixed[3], m_fixed[4], m_fixed[5]};
        sums.pixels = m_fixedPixels;
        sums.touchesSky = m_fixedSky;
        sums.touchesBorder = m_fixedBorder;
        // The variant's pixels, in the runs scanRegion would visit, with the masks of those runs and their
        // neighbours.
        std::vector<char> active = activeRuns(px, sv.runMax, th, m_opt.subpixel);
        for (size_t r = 0; r < active.size(); ++r) active[r] = active[r] && m_dependent[r] != 0;
        const std::vector<RunMask> masks = runMasks(px, active, th.Tf);
        for (const size_t r : m_dependentRuns)
            if (active[r])
                scanRun(px, masks, int(r / size_t(runs)), int(r % size_t(runs)), th, m_opt.subpixel, shift, sums,
                        m_dependent[r]);
        return sums;
    });
    for (size_t j = 0; j < m_at.size(); ++j) dense[m_at[j]] = m_kept[j];
    return shape;
}

}  // namespace hilite::analysis
