// measureImage: the highlight of a rendered measurement view. Pass 1 reads every pixel once (the peak,
// the smallest visible L, the largest L of each 32-pixel run of a row, and a dense copy of L); pass 2
// visits only the runs that can hold region or contour pixels and gathers the moments and the flags;
// two short walks through the peak give the sub-pixel widths. The image is 16 bytes a pixel, so pass 1
// is bound by memory bandwidth; pass 2 reads the dense L (4 bytes a pixel) and u, v, w only where needed.

#include "measure/highlight.hpp"

#include "core/error.hpp"
#include "core/math.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace hilite::measure {

namespace {

constexpr int kRun = 32;  ///< pixels per run of a row for the culling of pass 2

/// Read-only view of the (L, u, v, w) image, plus a dense copy of L (filled by pass 1) with a border of
/// one pixel all round: L where w > 0, -1 for the sky, NaN outside the image (every comparison with NaN is
/// false, so an outside neighbour is neither sky nor on the other side of the threshold).
struct Pixels {
    const float* data;
    int width, height;
    float* dense;  ///< denseSize(width, height) floats

    static size_t denseSize(int w, int h) { return size_t(w + 2) * size_t(h + 2); }
    size_t stride() const { return size_t(width) + 2; }
    size_t index(int x, int y) const { return size_t(y + 1) * stride() + size_t(x + 1); }
    const float* at(int x, int y) const { return data + 4 * (size_t(y) * size_t(width) + size_t(x)); }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
    bool visible(int x, int y) const { return dense[index(x, y)] >= 0.f; }
    float L(int x, int y) const { return dense[index(x, y)]; }
    dvec2 uv(int x, int y) const { return {at(x, y)[1], at(x, y)[2]}; }
    int runs() const { return (width + kRun - 1) / kRun; }
};

/// Pass 1: over the pixels that see the surface (w > 0), the peak, the smallest L, and each run's largest L.
struct Survey {
    float peak = 0.f, minVisible = std::numeric_limits<float>::infinity();
    int x = -1, y = -1;
    std::vector<float> runMax;  ///< height * runs(); -1 for a run of sky
};

Survey survey(const Pixels& px) {
    Survey s;
    const int runs = px.runs();
    s.runMax.resize(size_t(px.height) * size_t(runs));
    std::fill(px.dense, px.dense + Pixels::denseSize(px.width, px.height), std::numeric_limits<float>::quiet_NaN());
    for (int y = 0; y < px.height; ++y) {
        for (int r = 0; r < runs; ++r) {
            float m = -1.f, lo = s.minVisible;
            const int x1 = std::min(px.width, (r + 1) * kRun);
            for (int x = r * kRun; x < x1; ++x) {
                const float* q = px.at(x, y);
                const bool visible = q[3] > 0.f;
                const float L = visible ? std::max(q[0], 0.f) : -1.f;  // (a NaN L counts as 0)
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
        for (int x = x0; x < std::min(px.width, x0 + kRun); ++x) {
            if (px.L(x, y) == s.peak) {
                s.x = x;
                s.y = y;
                return;
            }
        }
    }
}

/// Runs pass 2 must visit: those holding an L >= T, and with sub-pixel coverage their 8 neighbours too
/// (an outside pixel on the contour is 4-adjacent to an inside one, hence in a neighbouring run).
std::vector<char> activeRuns(const Pixels& px, const Survey& s, float Tf, bool dilate) {
    const int runs = px.runs(), reach = dilate ? 1 : 0;
    std::vector<char> active(s.runMax.size(), 0);
    for (int y = 0; y < px.height; ++y) {
        for (int r = 0; r < runs; ++r) {
            if (s.runMax[size_t(y) * size_t(runs) + size_t(r)] < Tf) continue;
            for (int yy = std::max(0, y - reach); yy <= std::min(px.height - 1, y + reach); ++yy)
                for (int rr = std::max(0, r - reach); rr <= std::min(runs - 1, r + reach); ++rr)
                    active[size_t(yy) * size_t(runs) + size_t(rr)] = 1;
        }
    }
    return active;
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
    const double gx = slope(px, x, y, 1, 0), gy = slope(px, x, y, 0, 1), g = std::hypot(gx, gy);
    const double L = px.L(x, y);
    if (!(g > 0.0)) return L >= T ? 1.0 : 0.0;  // flat: no line to fit, fall back to the centre
    return coverage((L - T) / g, gx / g, gy / g);  // inside: g.(p - c) >= T - L, i.e. (-g/|g|).(p - c) <= d
}

/// What pass 2 gathers: weighted sums about a shift point (the peak's (u, v), against cancellation).
struct RegionSums {
    double s0 = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0;
    long pixels = 0;
    bool touchesBorder = false, touchesSky = false;

    void add(double w, double du, double dv) {
        s0 += w;
        su += w * du;
        sv += w * dv;
        suu += w * du * du;
        suv += w * du * dv;
        svv += w * dv * dv;
    }
    void merge(const RegionSums& o) {
        s0 += o.s0;
        su += o.su;
        sv += o.sv;
        suu += o.suu;
        suv += o.suv;
        svv += o.svv;
        pixels += o.pixels;
        touchesBorder = touchesBorder || o.touchesBorder;
        touchesSky = touchesSky || o.touchesSky;
    }
};

/// The threshold as pass 2 compares it.
struct Threshold {
    double T;
    float Tf;  ///< (L >= Tf) <=> (double(L) >= T): the smallest float not below T
    explicit Threshold(double t) : T(t), Tf(float(t)) {
        if (double(Tf) < T) Tf = std::nextafter(Tf, std::numeric_limits<float>::infinity());
    }
};

/// Is n visible and on the other side of the threshold from a pixel that is `in`? (NaN: no.)
inline bool otherSide(float n, bool in, float Tf) { return (n >= 0.f) & ((n >= Tf) != in); }

/// Pass 2 over one active run [x0, x1) of row y. Per visible pixel: in = L >= T; with sub-pixel coverage
/// its 4-neighbours say whether it is on the contour (one visible and on the other side).
RegionSums scanRun(const Pixels& px, int y, int x0, int x1, const Threshold& th, bool subpixel, dvec2 shift) {
    RegionSums r;
    const ptrdiff_t stride = ptrdiff_t(px.stride());
    const float* c = px.dense + px.index(x0, y);
    for (int x = x0; x < x1; ++x, ++c) {
        const float L = *c;
        if (!(L >= 0.f)) continue;  // sky
        const bool in = L >= th.Tf;
        const bool contour = subpixel && (otherSide(c[-1], in, th.Tf) | otherSide(c[1], in, th.Tf) |
                                          otherSide(c[-stride], in, th.Tf) | otherSide(c[stride], in, th.Tf));
        if (!in && !contour) continue;
        if (in) {
            ++r.pixels;
            // Sky beside a region pixel: the horizon cuts the region (NaN, outside the image, is not sky).
            r.touchesSky |= (c[-1] < 0.f) | (c[1] < 0.f) | (c[-stride] < 0.f) | (c[stride] < 0.f);
            r.touchesBorder |= (x == 0) | (y == 0) | (x == px.width - 1) | (y == px.height - 1);
        }
        const double f = contour ? contourFraction(px, x, y, th.T) : 1.0;
        const float* q = px.at(x, y);
        r.add(f * q[3], q[1] - shift.x, q[2] - shift.y);
    }
    return r;
}

/// Pass 2 over the active runs.
RegionSums scanRegion(const Pixels& px, const Survey& s, const Threshold& th, bool subpixel) {
    const std::vector<char> active = activeRuns(px, s, th.Tf, subpixel);
    const dvec2 shift = px.uv(s.x, s.y);
    const int runs = px.runs();
    RegionSums total;
    for (int y = 0; y < px.height; ++y) {
        for (int run = 0; run < runs; ++run) {
            if (active[size_t(y) * size_t(runs) + size_t(run)])
                total.merge(scanRun(px, y, run * kRun, std::min(px.width, (run + 1) * kRun), th, subpixel, shift));
        }
    }
    return total;
}

AreaMoments toMoments(const RegionSums& r, dvec2 shift) {
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

}  // namespace

Shape measureImage(const float* pixels, int width, int height, const Options& opt) {
    validate(opt);
    if (pixels == nullptr || width <= 0 || height <= 0) throw InputError("measureImage: empty image");
    std::unique_ptr<float[]> dense(new float[Pixels::denseSize(width, height)]);  // filled by survey()
    const Pixels px{pixels, width, height, dense.get()};
    Shape s;
    Survey sv = survey(px);
    if (!(sv.peak > 0.f)) {  // all dark, or nothing visible
        s.flags.push_back(Flag::NoHighlight);
        return s;
    }
    locatePeak(px, sv);
    const Threshold th(opt.threshold * double(sv.peak));
    const RegionSums sums = scanRegion(px, sv, th, opt.subpixel);  // never empty: the peak pixel is in it
    const dvec2 peakUV = px.uv(sv.x, sv.y);
    setEllipse(s, toMoments(sums, peakUV));
    s.peak = sv.peak;
    s.peak_u_deg = rad2deg(peakUV.x);
    s.peak_v_deg = rad2deg(peakUV.y);
    s.region_pixels = sums.pixels;
    setWidths(s, px, sv.x, sv.y, th.T);

    // Pixel pitch: sqrt of the mean (u,v) area of the region's pixels (their weights sum to about s0).
    const double pitch = std::sqrt(sums.s0 / double(sums.pixels));
    s.minor_pixels = 2.0 * deg2rad(s.minor_deg) / pitch;
    if (sums.touchesBorder) s.flags.push_back(Flag::Clipped);
    if (sums.touchesSky) s.flags.push_back(Flag::HorizonCut);
    if (s.minor_pixels < opt.minPixelsAcross) s.flags.push_back(Flag::UnderResolved);
    if (double(sv.minVisible) >= th.T) s.flags.push_back(Flag::CoversFrame);
    return s;
}

}  // namespace hilite::measure
