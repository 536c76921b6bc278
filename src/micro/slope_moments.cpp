#include "micro/slope_moments.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

namespace hilite::micro {

SlopeMoments makeSlopeMoments(const BumpField& f) {
    SlopeMoments m;
    m.n = f.n;
    m.levels = 1;
    while ((f.n >> (m.levels - 1)) > 1) ++m.levels;
    // Level 0 in double: (E sx, E sy, E sx^2, E sy^2, E sx sy) of the bilinear field over each cell between
    // four texel centres (i, j) .. (i + 1, j + 1): the surface the render sees. With the 1D linear-element
    // mass matrix M = [[1/3, 1/6], [1/6, 1/3]], E[f g] = sum over corner pairs of f_p g_q M(px, qx) M(py, qy).
    const int n = f.n;
    const size_t nn = size_t(n) * size_t(n);
    std::vector<double> cur(5 * nn);
    const double M[2][2] = {{1.0 / 3.0, 1.0 / 6.0}, {1.0 / 6.0, 1.0 / 3.0}};
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double sx[4], sy[4];  // corners (0,0), (1,0), (0,1), (1,1)
            for (int c = 0; c < 4; ++c) {
                const size_t k = size_t((j + c / 2) % n) * size_t(n) + size_t((i + c % 2) % n);
                sx[c] = f.tex0[4 * k], sy[c] = f.tex0[4 * k + 1];
            }
            double v[5] = {0.25 * (sx[0] + sx[1] + sx[2] + sx[3]), 0.25 * (sy[0] + sy[1] + sy[2] + sy[3]), 0, 0, 0};
            for (int p = 0; p < 4; ++p)
                for (int q = 0; q < 4; ++q) {
                    const double w = M[p % 2][q % 2] * M[p / 2][q / 2];
                    v[2] += w * sx[p] * sx[q], v[3] += w * sy[p] * sy[q], v[4] += w * sx[p] * sy[q];
                }
            std::copy(v, v + 5, cur.begin() + long(5 * (size_t(j) * size_t(n) + size_t(i))));
        }
    for (int level = 0; level < m.levels; ++level) {
        const int side = m.side(level);
        const size_t count = size_t(side) * size_t(side);
        std::vector<float> a(4 * count), b(count);
        for (size_t k = 0; k < count; ++k) {
            for (int c = 0; c < 4; ++c) a[4 * k + size_t(c)] = float(cur[5 * k + size_t(c)]);
            b[k] = float(cur[5 * k + 4]);
        }
        m.a.push_back(std::move(a));
        m.b.push_back(std::move(b));
        if (side == 1) break;
        // The next level: each texel the mean of its 2 x 2 children (moments average linearly).
        const int half = side / 2;
        std::vector<double> next(5 * size_t(half) * size_t(half));
        for (int j = 0; j < half; ++j)
            for (int i = 0; i < half; ++i)
                for (int c = 0; c < 5; ++c) {
                    auto at = [&](int x, int y) { return cur[5 * (size_t(y) * size_t(side) + size_t(x)) + size_t(c)]; };
                    next[5 * (size_t(j) * size_t(half) + size_t(i)) + size_t(c)] =
                        0.25 *
                        (at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) + at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1));
                }
        cur = std::move(next);
    }
    return m;
}

const SlopeMoments& cachedSlopeMoments(const BumpSpec& spec) {
    static std::mutex mutex;
    static std::map<BumpSpec, std::unique_ptr<SlopeMoments>> cache;
    const BumpField& f = cachedBumpField(spec);  // before the lock: it takes its own
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = cache[spec];
    if (!slot) slot = std::make_unique<SlopeMoments>(makeSlopeMoments(f));
    return *slot;
}

Moments SlopeMoments::at(int level, double x, double y) const {
    x -= 0.5 / n, y -= 0.5 / n;  // level-0 cells sit between texel centres: half a texel off the field's grid
    const int s = side(level);
    const double u = (x - std::floor(x)) * s - 0.5, v = (y - std::floor(y)) * s - 0.5;
    const double iu = std::floor(u), iv = std::floor(v), fx = u - iu, fy = v - iv;
    auto wrap = [s](double i) { return size_t(((long(i) % s) + s) % s); };
    const size_t i0 = wrap(iu), i1 = wrap(iu + 1), j0 = wrap(iv), j1 = wrap(iv + 1);
    const size_t k[4] = {j0 * size_t(s) + i0, j0 * size_t(s) + i1, j1 * size_t(s) + i0, j1 * size_t(s) + i1};
    const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    const std::vector<float>& A = a[size_t(level)];
    const std::vector<float>& B = b[size_t(level)];
    double r[5] = {0, 0, 0, 0, 0};
    for (int q = 0; q < 4; ++q) {
        for (int c = 0; c < 4; ++c) r[c] += w[q] * A[4 * k[q] + size_t(c)];
        r[4] += w[q] * B[k[q]];
    }
    Moments m;
    m.mean = {r[0], r[1]};
    m.xx = r[2], m.yy = r[3], m.xy = r[4];
    return m;
}

Moments SlopeMoments::at(double level, double x, double y) const {
    level = std::clamp(level, 0.0, double(levels - 1));
    const int l0 = std::min(int(std::floor(level)), levels - 1), l1 = std::min(l0 + 1, levels - 1);
    const double t = level - l0;
    const Moments p = at(l0, x, y);
    if (t == 0.0 || l1 == l0) return p;
    const Moments q = at(l1, x, y);
    Moments m;
    m.mean = p.mean + t * (q.mean - p.mean);
    m.xx = p.xx + t * (q.xx - p.xx), m.yy = p.yy + t * (q.yy - p.yy), m.xy = p.xy + t * (q.xy - p.xy);
    return m;
}

Moments SlopeMoments::footprint(double x, double y, const dvec2& ea, const dvec2& eb) const {
    const double la = glm::length(ea), lb = glm::length(eb);
    const dvec2 eLong = la >= lb ? ea : eb;
    const double lLong = std::max(la, lb), lShort = std::min(la, lb);
    const int K = std::clamp(int(std::ceil(lLong / std::max(lShort, 1e-30))), 1, kMaxProbes);
    // Each probe covers lLong / K along the long edge and lShort across it: its level is set by the larger.
    const double level = std::log2(std::max(std::max(lShort, lLong / K) * n, 1e-30)) - 0.5;
    Moments sum;
    for (int k = 0; k < K; ++k) {
        const double t = (k + 0.5) / K - 0.5;
        const Moments p = at(level, x + t * eLong.x, y + t * eLong.y);
        sum.mean += p.mean;
        sum.xx += p.xx, sum.yy += p.yy, sum.xy += p.xy;
    }
    sum.mean /= double(K);
    sum.xx /= K, sum.yy /= K, sum.xy /= K;
    return sum;
}

}  // namespace hilite::micro
