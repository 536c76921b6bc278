#include "hilite/micro/bounces.hpp"

#include "hilite/core/error.hpp"
#include "micro/masking.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <random>
#include <stdexcept>
#include <thread>

namespace hilite::micro {

const char* toString(TracedSurface s) { return s == TracedSurface::Hermite ? "hermite" : "bilinear"; }
std::optional<TracedSurface> parseTracedSurface(const std::string& s) {
    for (TracedSurface t : {TracedSurface::Hermite, TracedSurface::Bilinear})
        if (s == toString(t)) return t;
    return std::nullopt;
}

std::ostream& operator<<(std::ostream& os, const BounceOptions& o) {
    return os << "surface=" << toString(o.surface) << " paths=" << o.paths << " batches=" << o.batches
              << " seed=" << o.seed << " step=" << o.stepTexels << " texel";
}

namespace {

// ---- The traced surface ----

/// Cubic Hermite basis on [0, 1]: A0, A1 weigh the values at 0 and 1, B0, B1 the derivatives; and d/dt.
struct Hermite {
    double A0, A1, B0, B1, dA0, dA1, dB0, dB1;
    explicit Hermite(double t) {
        const double t2 = t * t, t3 = t2 * t;
        A0 = 2 * t3 - 3 * t2 + 1, A1 = -2 * t3 + 3 * t2, B0 = t3 - 2 * t2 + t, B1 = t3 - t2;
        dA0 = 6 * t2 - 6 * t, dA1 = -dA0, dB0 = 3 * t2 - 4 * t + 1, dB1 = 3 * t2 - 2 * t;
    }
};

/// The bicubic Hermite surface through the field's texel centres: there its height, slope and cross
/// derivative are the field's (h, s = grad h, J_xy = h_xy), and it is C1 everywhere (each cell edge depends on
/// its two corners alone), so every point has one normal, the gradient's. Scaled by `scale` (heights and all).
struct Surface {
    int n = 0;
    std::vector<double> h, hx, hy, hxy;  ///< per texel, scaled; derivatives per tile length
    double top = 0;                      ///< above every point of the surface
    /// TracedSurface::Bilinear: the render's field instead (bilinear heights; normals from the bilinear slopes)
    const BumpField* bilinear = nullptr;

    struct Cell {
        size_t k[4];  ///< corners (0,0), (1,0), (0,1), (1,1)
        double u, v;  ///< position in the cell, [0, 1)
    };
    Cell cell(double x, double y) const {
        const double u = x * n - 0.5, v = y * n - 0.5, iu = std::floor(u), iv = std::floor(v);
        auto wrap = [this](double i) { return size_t(((long(i) % n) + n) % n); };
        const size_t i0 = wrap(iu), i1 = wrap(iu + 1), j0 = wrap(iv), j1 = wrap(iv + 1);
        return {{j0 * size_t(n) + i0, j0 * size_t(n) + i1, j1 * size_t(n) + i0, j1 * size_t(n) + i1}, u - iu, v - iv};
    }
    /// Height at (x, y) in tile lengths, and the gradient when asked.
    double height(double x, double y, dvec2* grad = nullptr) const {
        if (bilinear) {
            if (grad) *grad = bilinear->sample(x, y).s;
            return bilinear->height(x, y);
        }
        const Cell c = cell(x, y);
        const Hermite a(c.u), b(c.v);
        const double inv = 1.0 / n;  // d/du = (1/n) d/dx
        const double Au[2] = {a.A0, a.A1}, Bu[2] = {a.B0, a.B1}, Av[2] = {b.A0, b.A1}, Bv[2] = {b.B0, b.B1};
        double z = 0;
        for (int q = 0; q < 4; ++q) {
            const int i = q & 1, j = q >> 1;
            const size_t k = c.k[q];
            z += h[k] * Au[i] * Av[j] + inv * (hx[k] * Bu[i] * Av[j] + hy[k] * Au[i] * Bv[j]) +
                 inv * inv * hxy[k] * Bu[i] * Bv[j];
        }
        if (grad) {
            const double dAu[2] = {a.dA0, a.dA1}, dBu[2] = {a.dB0, a.dB1}, dAv[2] = {b.dA0, b.dA1},
                         dBv[2] = {b.dB0, b.dB1};
            double gu = 0, gv = 0;
            for (int q = 0; q < 4; ++q) {
                const int i = q & 1, j = q >> 1;
                const size_t k = c.k[q];
                gu += h[k] * dAu[i] * Av[j] + inv * (hx[k] * dBu[i] * Av[j] + hy[k] * dAu[i] * Bv[j]) +
                      inv * inv * hxy[k] * dBu[i] * Bv[j];
                gv += h[k] * Au[i] * dAv[j] + inv * (hx[k] * Bu[i] * dAv[j] + hy[k] * Au[i] * dBv[j]) +
                      inv * inv * hxy[k] * Bu[i] * dBv[j];
            }
            *grad = dvec2(gu, gv) * double(n);
        }
        return z;
    }
};

/// Mean |grad h|^2 over the tile (4 x 4 Gauss-Legendre points a cell: exact for the bicubic's squared
/// gradient, a polynomial of degree 6 per axis), and the largest |grad h| met.
std::pair<double, double> meanSquareSlope(const Surface& s) {
    const double g[4] = {0.5 - 0.4305681557970263, 0.5 - 0.1699905217924281, 0.5 + 0.1699905217924281,
                         0.5 + 0.4305681557970263};
    const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
    double sum = 0, maxGrad = 0;
    for (int j = 0; j < s.n; ++j)
        for (int i = 0; i < s.n; ++i)
            for (int q = 0; q < 16; ++q) {
                dvec2 gr;
                s.height((i + 0.5 + g[q % 4]) / s.n, (j + 0.5 + g[q / 4]) / s.n, &gr);
                sum += w[q % 4] * w[q / 4] * glm::dot(gr, gr);
                maxGrad = std::max(maxGrad, glm::length(gr));
            }
    return {sum / (double(s.n) * double(s.n)), maxGrad};
}

Surface makeSurface(const BumpField& f, double* ratio) {
    Surface s;
    s.n = f.n;
    const size_t nn = size_t(f.n) * size_t(f.n);
    s.h.resize(nn), s.hx.resize(nn), s.hy.resize(nn), s.hxy.resize(nn);
    for (size_t k = 0; k < nn; ++k) {
        s.hx[k] = f.tex0[4 * k], s.hy[k] = f.tex0[4 * k + 1], s.hxy[k] = f.tex0[4 * k + 3];
        s.h[k] = f.tex1[4 * k + 2];
    }
    const auto [msq, maxGrad] = meanSquareSlope(s);
    const double scale = f.spec.roughness / std::sqrt(msq);
    if (ratio) *ratio = 1.0 / scale;
    double hMax = -1e300;
    for (size_t k = 0; k < nn; ++k) {
        s.h[k] *= scale, s.hx[k] *= scale, s.hy[k] *= scale, s.hxy[k] *= scale;
        hMax = std::max(hMax, s.h[k]);
    }
    // Within a cell no point is further than sqrt(2)/2 texel from a corner; 1.5x the steepest sampled slope
    // over one texel bounds the rise above the highest corner with room to spare.
    s.top = hMax + 1.5 * scale * maxGrad / s.n;
    return s;
}

/// The surface of the field last traced, kept for the next call (a sweep of incidences traces one field many
/// times; the rescale reads 16 points a texel, ~1 s at 1024^2). One slot: a sweep over roughness would
/// otherwise keep 32 MB a field.
std::shared_ptr<const Surface> cachedSurface(const BumpField& f) {
    static std::mutex mutex;
    static std::shared_ptr<const Surface> last;
    static BumpSpec lastSpec;
    std::lock_guard<std::mutex> lock(mutex);
    if (!last || lastSpec < f.spec || f.spec < lastSpec) {
        last = std::make_shared<const Surface>(makeSurface(f, nullptr));
        lastSpec = f.spec;
    }
    return last;
}

/// The first point where the ray o + t d (t > 0) goes below the surface, marched in `step` and refined by
/// bisection to the last point above it; false when the ray leaves (rises above the surface's top) or
/// wanders too long (a ray held level below the top: counted as lost).
enum class Hit { Surface, Leaves, Lost };
Hit intersect(const Surface& s, const dvec3& o, const dvec3& d, double step, dvec3& at) {
    constexpr long kMaxSteps = 1 << 22;  // 10^3 tiles of travel at a quarter texel a step (1024^2)
    double tPrev = 0;
    for (long i = 1; i <= kMaxSteps; ++i) {
        const double t = double(i) * step;
        const dvec3 p = o + t * d;
        if (d.z >= 0 && p.z > s.top) return Hit::Leaves;
        if (p.z < s.height(p.x, p.y)) {
            double lo = tPrev, hi = t;
            for (int k = 0; k < 60 && hi - lo > 1e-15 * step; ++k) {
                const double mid = 0.5 * (lo + hi);
                const dvec3 q = o + mid * d;
                (q.z < s.height(q.x, q.y) ? hi : lo) = mid;
            }
            at = o + lo * d;
            return Hit::Surface;
        }
        tPrev = t;
    }
    return Hit::Lost;
}

// ---- Smith's microsurface (Heitz et al. 2016), Beckmann, uniform heights in [-1, 1] ----

/// Lambda of a direction going up (w.z > 0) or down (Lambda(-w) = -1 - Lambda(w)). Heitz et al. 2016, sec. 4.
double lambdaSigned(const dvec3& w, double m) {
    return w.z >= 0 ? lambdaBeckmannExact(w.z, m) : -1.0 - lambdaBeckmannExact(-w.z, m);
}

/// The next height the walk reaches along w from height hr, or +inf when it leaves. Heitz et al. 2016, Alg. 2
/// (C1(h) = (h + 1) / 2: a ray going down always meets the surface).
double sampleHeight(const dvec3& w, double hr, double m, double U) {
    const double c1 = std::clamp(0.5 * (hr + 1.0), 0.0, 1.0);
    if (w.z > 0.9999) return INFINITY;  // straight up: Lambda = 0, nothing above is met
    if (w.z < -0.9999) return 2.0 * (U * c1) - 1.0;
    if (std::abs(w.z) < 1e-6) return hr;  // level: met at once (Lambda infinite)
    const double lambda = lambdaSigned(w, m);
    if (w.z > 0) {
        const double g1 = std::pow(c1, lambda);  // the chance to leave from here
        if (U > 1.0 - g1) return INFINITY;
    }
    const double c = std::min(1.0, c1 / std::pow(1.0 - U, 1.0 / lambda));
    return 2.0 * c - 1.0;
}

/// A normal of the Beckmann NDF (rms slope m) seen from wi (wi.z > 0), by the distribution of visible normals.
/// Heitz & d'Eon 2014: stretch to unit roughness, sample the visible slopes there -- separable for wi in the
/// xz plane: x with density (cos t - x sin t) exp(-x^2) / sqrt(pi) for x < cot t (its CDF inverted by bisection
/// in double), y ~ N(0, 1/2) -- then rotate to wi's azimuth and unstretch.
dvec3 sampleVisibleNormal(const dvec3& wi, double m, double U1, double U2, double U3) {
    const dvec3 ws = glm::normalize(dvec3(m * wi.x, m * wi.y, wi.z));
    const double sinT = std::hypot(ws.x, ws.y), cosT = ws.z;
    double sx, sy;
    if (sinT < 1e-7) {  // normal incidence: the slopes' own Gaussian, a Box-Muller pair of variance 1/2
        const double r = std::sqrt(-std::log(1.0 - U1));
        sx = r * std::cos(2.0 * kPi * U3), sy = r * std::sin(2.0 * kPi * U3);
    } else {
        const double cotT = cosT / sinT;
        auto cdf = [&](double x) {  // int_-inf^x (cos t - u sin t) exp(-u^2) / sqrt(pi) du
            return 0.5 * cosT * (1.0 + std::erf(x)) + 0.5 * sinT * std::exp(-x * x) / std::sqrt(kPi);
        };
        const double target = U1 * cdf(cotT);
        const double hi0 = std::min(cotT, 9.0), lo0 = std::min(-9.0, hi0 - 9.0);  // exp(-81): nothing lies beyond
        double lo = lo0, hi = hi0;
        for (int k = 0; k < 64; ++k) {
            const double mid = 0.5 * (lo + hi);
            (cdf(mid) < target ? lo : hi) = mid;
        }
        sx = 0.5 * (lo + hi);
        sy = std::sqrt(-std::log(1.0 - U2)) * std::cos(2.0 * kPi * U3);
    }
    const double cp = sinT < 1e-7 ? 1.0 : ws.x / sinT, sp = sinT < 1e-7 ? 0.0 : ws.y / sinT;
    const dvec2 slope(m * (cp * sx - sp * sy), m * (sp * sx + cp * sy));
    return glm::normalize(dvec3(-slope.x, -slope.y, 1.0));
}

// ---- The tally ----

/// The first reflection's bin: wo.z < 0 is bin 0, then kExitBins - 1 equal steps of cos(theta_o) in [0, 1].
size_t exitBin(double cosTheta_o) {
    if (cosTheta_o < 0.0) return 0;
    return 1 + std::min(size_t(kExitBins - 2), size_t(cosTheta_o * (kExitBins - 1)));
}

struct BatchTally {
    long paths = 0, stuck = 0, backHits = 0;
    std::vector<double> exitCount = std::vector<double>(kExitBins, 0.0),
                        exitEscaped = std::vector<double>(kExitBins, 0.0);
    std::vector<double> count;                   ///< [order]
    std::vector<std::vector<double>> reflected;  ///< [order][channel]
    BatchTally(size_t channels)
        : count(kMaxReportedOrder + 1, 0.0), reflected(kMaxReportedOrder + 1, std::vector<double>(channels, 0.0)) {}
    void firstReflection(size_t bin) { exitCount[bin] += 1.0; }
    void leave(int order, const std::vector<double>& w, size_t firstBin) {
        if (order == 1) exitEscaped[firstBin] += 1.0;
        const size_t k = size_t(std::min(order, kMaxReportedOrder + 1) - 1);
        count[k] += 1.0;
        for (size_t c = 0; c < w.size(); ++c) reflected[k][c] += w[c];
    }
};

struct Engine {
    std::mt19937_64 engine;
    explicit Engine(uint64_t seed) : engine(seed) {}
    double uniform() { return double(engine() >> 11) * 0x1.0p-53; }  // [0, 1)
};

/// splitmix64 of (seed, batch): each batch its own well-separated engine seed.
uint64_t batchSeed(uint64_t seed, int batch) {
    uint64_t z = seed + 0x9E3779B97F4A7C15ull * uint64_t(batch + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/// Runs path(engine, tally) for every path of every batch, the batches spread over the cores.
template <class Path>
std::vector<BatchTally> runBatches(const BounceOptions& o, size_t channels, Path path, const BounceProgress& progress,
                                   const std::string& stage) {
    if (o.paths < 1 || o.batches < 2 || o.paths < o.batches)
        throw InputError("bounces: need paths >= batches >= 2 (paths " + std::to_string(o.paths) + ", batches " +
                         std::to_string(o.batches) + ")");
    std::mutex told;
    long done = 0;
    if (progress) progress(stage, 0, o.batches);
    std::vector<BatchTally> tallies(size_t(o.batches), BatchTally(channels));
    const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), unsigned(o.batches)));
    auto work = [&](unsigned t) {
        for (int b = int(t); b < o.batches; b += int(threads)) {
            Engine e(batchSeed(o.seed, b));
            BatchTally& tally = tallies[size_t(b)];
            tally.paths = o.paths / o.batches + (b < o.paths % o.batches ? 1 : 0);
            for (long i = 0; i < tally.paths; ++i) path(e, tally);
            if (!progress) continue;
            const std::lock_guard<std::mutex> lock(told);
            progress(stage, ++done, o.batches);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (auto& th : pool) th.join();
    return tallies;
}

Estimate estimate(const std::vector<double>& perBatch) {
    const double n = double(perBatch.size());
    double mean = 0;
    for (double v : perBatch) mean += v / n;
    double var = 0;
    for (double v : perBatch) var += (v - mean) * (v - mean) / (n - 1);
    return {mean, std::sqrt(var / n)};
}

BounceTally summarize(double thetaDeg, const std::vector<BatchTally>& batches, const brdf::ReflectanceChannels& ch) {
    BounceTally t;
    t.thetaDeg = thetaDeg;
    const size_t orders = kMaxReportedOrder + 1, nc = ch.size();
    for (const auto& b : batches) t.paths += b.paths, t.backHits += b.backHits;
    auto perBatch = [&](auto f) {
        std::vector<double> v;
        for (const auto& b : batches) v.push_back(f(b));
        return estimate(v);
    };
    t.reflected.assign(orders, std::vector<double>(nc, 0.0));
    for (size_t k = 0; k < orders; ++k) {
        t.energy.push_back(perBatch([&](const BatchTally& b) { return b.count[k] / double(b.paths); }));
        double count = 0;
        for (const auto& b : batches) {
            count += b.count[k];
            for (size_t c = 0; c < nc; ++c) t.reflected[k][c] += b.reflected[k][c] / double(t.paths);
        }
        std::vector<double> mean(nc, 0.0);  // the order's mean F product: its light's colour, whatever its share
        if (count > 0)
            for (size_t c = 0; c < nc; ++c) mean[c] = t.reflected[k][c] * double(t.paths) / count;
        t.colour.push_back(brdf::colourOf(mean, ch));
        std::vector<double> chromas;
        for (const auto& b : batches) {
            if (b.count[k] == 0) continue;
            std::vector<double> r(nc);
            for (size_t c = 0; c < nc; ++c) r[c] = b.reflected[k][c] / b.count[k];
            chromas.push_back(brdf::colourOf(r, ch).chroma);
        }
        Estimate e = chromas.size() >= 2 ? estimate(chromas) : Estimate{NAN, NAN};
        e.value =
            count > 0 ? t.colour.back().chroma : NAN;  // pooled; the batches' spread as its error (no light: none)
        t.chroma.push_back(e);
    }
    t.multiple = perBatch([&](const BatchTally& b) {
        double s = 0;
        for (size_t k = 1; k < orders; ++k) s += b.count[k];
        return s / double(b.paths);
    });
    t.total = perBatch([&](const BatchTally& b) {
        double s = 0;
        for (size_t k = 0; k < orders; ++k) s += b.count[k];
        return s / double(b.paths);
    });
    for (size_t bin = 0; bin < size_t(kExitBins); ++bin) {
        double count = 0, escaped = 0;
        for (const auto& b : batches) count += b.exitCount[bin], escaped += b.exitEscaped[bin];
        t.firstExitShare.push_back(count / double(t.paths));
        t.firstExitEscape.push_back(count > 0 ? escaped / count : 0.0);
    }
    t.stuck = perBatch([&](const BatchTally& b) { return double(b.stuck) / double(b.paths); });
    auto weighted = [&](auto weight) {
        return perBatch([&](const BatchTally& b) {
            double s = 0;
            for (size_t k = 0; k < orders; ++k)
                for (size_t c = 0; c < nc; ++c) s += b.reflected[k][c] * weight(c);
            return s / double(b.paths);
        });
    };
    for (int c = 0; c < 3; ++c) t.reflectedRgb.push_back(weighted([&](size_t i) { return ch.rgb[i][c]; }));
    // Luminance of the linear sRGB albedo (the Y row of IEC 61966-2-1), as of any other sRGB albedo.
    t.reflectedY =
        weighted([&](size_t i) { return 0.2126 * ch.rgb[i].x + 0.7152 * ch.rgb[i].y + 0.0722 * ch.rgb[i].z; });
    return t;
}

}  // namespace

double hermiteSlopeRatio(const BumpField& f) {
    double ratio = 1.0;
    makeSurface(f, &ratio);
    return ratio;
}

BounceTally traceBounces(const BumpField& f, double thetaDeg, const brdf::ReflectanceChannels& ch,
                         const BounceOptions& o, const BounceProgress& progress) {
    if (f.spec.kind != BumpKind::Beckmann)
        throw InputError("bounces are traced on Beckmann height fields only (a GGX field is a normal map)");
    Surface flat;  // TracedSurface::Bilinear
    flat.n = f.n, flat.bilinear = &f, flat.top = f.heightMax;
    const std::shared_ptr<const Surface> hermite = o.surface == TracedSurface::Hermite ? cachedSurface(f) : nullptr;
    const Surface& s = hermite ? *hermite : flat;
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, 0.0);
    const double step = o.stepTexels / s.n;
    const size_t nc = ch.size();
    const auto batches = runBatches(
        o, nc,
        [&](Engine& e, BatchTally& tally) {
            std::vector<double> w(nc, 1.0), F(nc);
            // Uniform over the plane above the surface: the hits are weighted by projected area, as light falls.
            dvec3 p(e.uniform(), e.uniform(), s.top), d = -wi;
            size_t firstBin = 0;
            for (int order = 0;; ++order) {
                dvec3 at;
                const Hit hit = intersect(s, p, d, step, at);
                if (hit == Hit::Leaves) return tally.leave(order, w, firstBin);
                if (hit == Hit::Lost || order == kMaxBounces) return void(++tally.stuck);
                dvec2 g;
                s.height(at.x, at.y, &g);
                const dvec3 m = glm::normalize(dvec3(-g.x, -g.y, 1.0));
                const double cosD = -glm::dot(d, m);
                // A facet facing away from the ray: the march stepped over a ridge's far side (never seen so far).
                if (cosD <= 0.0) {
                    ++tally.stuck, ++tally.backHits;
                    return;
                }
                ch.fresnel(cosD, F.data());
                for (size_t c = 0; c < nc; ++c) w[c] *= F[c];
                p = at, d = d + 2.0 * cosD * m;
                if (order == 0) tally.firstReflection(firstBin = exitBin(d.z));
            }
        },
        progress, "traced");
    return summarize(thetaDeg, batches, ch);
}

BounceTally walkSmithBounces(double m, double thetaDeg, const brdf::ReflectanceChannels& ch, const BounceOptions& o,
                             const BounceProgress& progress) {
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, 0.0);
    const size_t nc = ch.size();
    const auto batches = runBatches(
        o, nc,
        [&](Engine& e, BatchTally& tally) {
            std::vector<double> w(nc, 1.0), F(nc);
            dvec3 wr = -wi;   // the ray's direction, going down at first
            double hr = 2.0;  // above the surface: C1 = 1
            size_t firstBin = 0;
            for (int order = 0;; ++order) {
                hr = sampleHeight(wr, hr, m, e.uniform());
                if (std::isinf(hr)) return tally.leave(order, w, firstBin);
                if (order == kMaxBounces) return void(++tally.stuck);
                const double u1 = e.uniform(), u2 = e.uniform(), u3 = e.uniform();
                const dvec3 wm = sampleVisibleNormal(-wr, m, u1, u2, u3);
                const double cosD = glm::dot(-wr, wm);
                ch.fresnel(cosD, F.data());
                for (size_t c = 0; c < nc; ++c) w[c] *= F[c];
                wr = wr + 2.0 * cosD * wm;
                if (order == 0) tally.firstReflection(firstBin = exitBin(wr.z));
            }
        },
        progress, "Smith walk");
    return summarize(thetaDeg, batches, ch);
}

}  // namespace hilite::micro
