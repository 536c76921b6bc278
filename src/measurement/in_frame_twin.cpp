#include "measurement/in_frame_twin.hpp"

#include "analysis/image_variants.hpp"
#include "analysis/runs.hpp"
#include "core/parallel.hpp"
#include "render/cpu_view.hpp"

#include "brdf/merl.hpp"
#include "hilite/render/area_light.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace hilite::measurement {

namespace {

using analysis::bitsWithin;
using analysis::extremes;
using analysis::kRun;

/// Pixels within this many along a row or a column of a contour pixel (one with a 4-neighbour on the other side of
/// the level): measureImage reads a contour pixel's 4-neighbours to place the contour in it, so they must hold the
/// variant's L too.
constexpr int kReach = 1;
/// Rounds of asking the twins about pixels that the changes found so far could move.
constexpr size_t kRounds = 4;
/// Beyond this share of the peak a variant is not "a little different": it is rendered.
constexpr double kMaxChange = 0.1;

/// The smallest float not below x, and the largest not above it: a float L compares with them as double(L) with x.
float floatAtLeast(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, INFINITY) : f;
}
float floatAtMost(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -INFINITY) : f;
}

}  // namespace

PixelChanges twinChanges(const render::Scene& scene, const std::vector<render::Scene>& variants) {
    const int rings = scene.light.area() ? render::lightRings(scene) : 0;
    return [&scene, &variants, rings](const PinholeCamera& cam, double px, double py, double* changes) {
        const double full = render::measureLuminanceCpu(scene, cam, px, py, rings);
        for (size_t v = 0; v < variants.size(); ++v)
            changes[v] = render::measureLuminanceCpu(variants[v], cam, px, py, rings) - full;
    };
}

std::optional<PixelChanges> tableHalvesChanges(const render::Scene& scene) {
    const brdf::Params& p = scene.brdf;
    const bool directional = scene.light.type == render::LightType::Directional;
    if ((!directional && !(scene.light.area() && !scene.light.ltc)) || !p.measured || p.rgl || scene.brdfFile ||
        p.diffuse != brdf::Diffuse::None || p.multiscatter != brdf::Multiscatter::None)
        return std::nullopt;
    const std::shared_ptr<const brdf::merl::HalvesLuminance> lum = brdf::merl::halvesLuminance(p.measured);
    const int rings = directional ? 0 : render::lightRings(scene);
    constexpr size_t kTables = brdf::merl::HalvesLuminance::kTables;
    // The same sums as measureLuminanceCpu's (brdf::radiance: f E max(0, cos theta_i); areaRadianceRule: the
    // rule's weighted sum of it times 2 pi / 4n), of the seven tables' luminances at once.
    const dvec3 sun = scene.light.direction();  // (directional)
    return [lum, scene, rings, sun](const PinholeCamera& cam, double px, double py, double* changes) {
        double L[kTables], f[kTables];
        std::fill(L, L + kTables, 0.0);
        const dvec3 we = render::sampleExitant(cam, px, py);
        if (we.z > 0.0 && rings == 0) {
            lum->evaluate(sun, we, f);
            for (size_t k = 0; k < kTables; ++k) L[k] = f[k] * (scene.light.irradiance * std::max(0.0, sun.z));
        } else if (we.z > 0.0) {
            const render::LightCap cap = render::lightCap(scene.light, cam.position - (cam.position.z / we.z) * we);
            render::capRulePoints(cap, rings, [&](const dvec3& wi, double w) {
                if (!(wi.z > 0)) return;
                lum->evaluate(wi, we, f);
                for (size_t k = 0; k < kTables; ++k) L[k] += w * (f[k] * (cap.radiance * std::max(0.0, wi.z)));
            });
            for (double& l : L) l *= render::capRuleScale(rings);
        }
        for (size_t v = 0; v + 1 < kTables; ++v) changes[v] = L[v + 1] - L[0];
    };
}

std::vector<std::optional<analysis::Shape>> measureInFrameByTwin(const render::Scene& scene, size_t k,
                                                                 const PixelChanges& changes, const MeasureSetup& setup,
                                                                 const Measurement& like) {
    std::vector<std::optional<analysis::Shape>> out(k);
    const ImageF& img = like.image;
    if (!like.inFrame || setup.supersample > 1 || img.channels != 4 || img.data.empty()) return out;
    const PinholeCamera cam = measurementCamera(scene, like.center, like.fovDeg, setup.width, setup.height);
    int x0 = 0, y0 = 0;    // the image's first pixel in the frame
    bool cropped = false;  // the image is the crop (else the whole frame, drawn again when the crop clipped)
    if (img.width != cam.width || img.height != cam.height) {
        if (like.crop.width != img.width || like.crop.height != img.height) return out;
        x0 = like.crop.x, y0 = like.crop.y, cropped = true;
    }
    const int W = img.width, H = img.height;
    const size_t n = size_t(W) * size_t(H);
    // The image surveyed once (analysis::ImageVariants): its L as measureImage reads it (max(0, L), -1 where the
    // pixel sees no surface) is what every scan below reads, and what each variant's measureImage starts from.
    analysis::ImageVariants image(img.data.data(), W, H);
    const std::vector<float>& lum = image.luminance();
    const double peak = image.peak();
    if (image.nonFinite() || !(peak > 0)) return out;
    auto L = [&](size_t i) { return double(lum[i]); };

    // Each run of kRun pixels of a row: its smallest and largest L (-1: the sky), so that the scans below visit only
    // the runs that can hold what they look for (each whole-image pass was 0.1 ms; a round took four).
    const int runs = (W + kRun - 1) / kRun;
    const size_t runCount = size_t(runs) * size_t(H);
    auto runOf = [&](size_t i) { return (i / size_t(W)) * size_t(runs) + (i % size_t(W)) / size_t(kRun); };
    auto runLength = [&](size_t q) { return std::min(kRun, W - int(q % size_t(runs)) * kRun); };
    auto firstPixel = [&](size_t q) { return (q / size_t(runs)) * size_t(W) + (q % size_t(runs)) * size_t(kRun); };
    std::vector<float> runLo(runCount), runHi(runCount);
    for (size_t q = 0; q < runCount; ++q) std::tie(runLo[q], runHi[q]) = extremes(&lum[firstPixel(q)], runLength(q));

    // The band: the contour's pixels (a 4-neighbour on the other side of the level: measureImage's contour test)
    // and their 4-neighbours (kReach; what its covered share of a contour pixel reads). The 8-neighbourhoods
    // asked 4,908 pixels at 60 deg where these are 3,656 (table_error the same to 4 digits or more).
    const double level = like.level > 0 ? like.level : setup.options.threshold * peak;
    // Per run, a bit per pixel at or above the level (float's compare as double's: the smallest float not below it).
    const float levelF = floatAtLeast(level);
    std::vector<uint32_t> inBits(runCount, 0u);
    for (size_t q = 0; q < runCount; ++q) {
        if (runHi[q] >= levelF) inBits[q] = bitsWithin(&lum[firstPixel(q)], runLength(q), levelF, INFINITY);
    }
    // A pixel whose 4-neighbour is on the other side (a missing neighbour, past the image's edge: the pixel itself),
    // by bit operations on a run and its neighbours' bits, in the order of the image.
    std::vector<char> band(n, 0);
    std::vector<size_t> marked;
    for (int y = 0; y < H; ++y)
        for (int r = 0; r < runs; ++r) {
            const size_t q = size_t(y) * size_t(runs) + size_t(r);
            const int len = runLength(q);
            const uint32_t all = len == kRun ? ~0u : (1u << len) - 1u, c = inBits[q];
            const uint32_t left = (c << 1) | (r > 0 ? inBits[q - 1] >> (kRun - 1) : c & 1u);
            const uint32_t right = (c >> 1) | (r + 1 < runs ? inBits[q + 1] << (kRun - 1) : c & (1u << (len - 1)));
            const uint32_t down = y > 0 ? inBits[q - size_t(runs)] : c, up = y + 1 < H ? inBits[q + size_t(runs)] : c;
            uint32_t differs = ((c ^ left) | (c ^ right) | (c ^ down) | (c ^ up)) & all;
            for (; differs != 0; differs &= differs - 1)
                marked.push_back(firstPixel(q) + size_t(__builtin_ctz(differs)));
        }
    // The marked pixels and their 4-neighbours (kReach) that see the surface and are not in the band yet: into it.
    std::vector<uint32_t> bandBits(runCount, 0u);  // per run, a bit per pixel in the band
    auto grow = [&](const std::vector<size_t>& seeds) {
        std::vector<size_t> added;
        for (const size_t i : seeds) {
            const int x = int(i % size_t(W)), y = int(i / size_t(W));
            for (int v = std::max(0, y - kReach); v <= std::min(H - 1, y + kReach); ++v)
                for (int u = std::max(0, x - kReach); u <= std::min(W - 1, x + kReach); ++u) {
                    if (u != x && v != y) continue;
                    const size_t j = size_t(v) * size_t(W) + size_t(u);
                    if (!band[j] && lum[j] >= 0.f)
                        band[j] = 1, bandBits[runOf(j)] |= 1u << (u % kRun), added.push_back(j);
                }
        }
        return added;
    };
    // The changes at the pixel centres (jitter 0: not supersampled).
    std::vector<size_t> at;     // the pixels asked, in the order asked
    std::vector<double> delta;  // their changes, k per pixel
    auto ask = [&](size_t from) {
        delta.resize(at.size() * k);
        // In chunks of 64 pixels: interleaved, two threads wrote neighbouring changes into one cache line (1.7 ms
        // at 60 deg against one thread's 1.3).
        constexpr size_t kChunk = 64;
        const size_t count = at.size() - from;
        parallelFor(int((count + kChunk - 1) / kChunk), [&](int c) {
            for (size_t j = from + size_t(c) * kChunk; j < std::min(at.size(), from + (size_t(c) + 1) * kChunk); ++j) {
                const size_t i = at[j];
                changes(cam, x0 + double(i % size_t(W)) + 0.5, y0 + double(i / size_t(W)) + 0.5, &delta[j * k]);
            }
        });
    };
    at = grow(marked);
    // Each variant's peak and level, from the pixels asked so far; the pixels left as they are that could cross
    // either (within twice the largest change) are asked next, with their neighbours, until none is left:
    // a change at the peak moves the level, and the contour with it (a theta_h halving about theta_h = 0).
    struct Moved {
        double change = 0, peak = 0, level = 0;
        bool finite = true;
    };
    std::vector<Moved> moved(k);
    double outsideMax = 0;  // the largest L left as it is
    size_t asked = 0;
    std::vector<Moved> askedSoFar(k);
    for (size_t round = 0; asked < at.size() && round < kRounds && at.size() <= n / 4; ++round) {
        ask(asked);
        const size_t askedBefore = asked;
        asked = at.size();
        // (No pixel lies above the peak: where the peak's pixel is left as it is, it is the largest.)
        float top = 0.f;
        if (!band[image.peakPixel()]) top = float(peak);
        else {  // the largest L of the runs without a band pixel, then of the pixels of the others that can beat it
            for (size_t q = 0; q < runCount; ++q) top = bandBits[q] ? top : std::max(top, runHi[q]);
            for (size_t q = 0; q < runCount; ++q) {
                if (!bandBits[q] || runHi[q] <= top) continue;
                for (size_t i = firstPixel(q); i < firstPixel(q) + size_t(runLength(q)); ++i)
                    top = std::max(top, band[i] ? 0.f : lum[i]);
            }
        }
        outsideMax = top;
        // The L that a variant could cross: above its peak less twice its change, or within that of its level.
        std::vector<std::pair<double, double>> near;
        for (size_t v = 0; v < k; ++v) {
            Moved& m = moved[v];
            Moved& a = askedSoFar[v];  // over the pixels asked in earlier rounds, then this round's
            for (size_t j = askedBefore; j < at.size(); ++j) {
                const double d = delta[j * k + v];
                a.finite = a.finite && std::isfinite(d);
                a.change = std::max(a.change, std::abs(d));
                a.peak = std::max(a.peak, double(float(L(at[j]) + d)));
            }
            m = Moved{a.change, std::max(outsideMax, a.peak), 0, a.finite};
            if (!m.finite) continue;
            m.level = like.level > 0 ? like.level : setup.options.threshold * m.peak;
            near.push_back({m.peak - 2 * m.change, INFINITY});
            near.push_back({m.level - 2 * m.change, m.level + 2 * m.change});
        }
        // The intervals merged (the variants' levels lie close together), then the pixels in them marked.
        std::sort(near.begin(), near.end());
        std::vector<std::pair<double, double>> merged;
        for (const auto& r : near)
            if (!merged.empty() && r.first <= merged.back().second)
                merged.back().second = std::max(merged.back().second, r.second);
            else merged.push_back(r);
        // Each interval's ends as floats that compare as the doubles do (the smallest float not below lo, the
        // largest not above hi); then the pixels in one that see the surface and are not in the band, in the runs
        // that reach one.
        std::vector<std::pair<float, float>> ends;
        for (const auto& [lo, hi] : merged) ends.push_back({floatAtLeast(lo), floatAtMost(hi)});
        auto within = [&](float lo, float hi) {
            for (const auto& [flo, fhi] : ends)
                if (lo <= fhi && hi >= flo) return true;
            return false;
        };
        marked.clear();
        for (size_t q = 0; q < runCount; ++q) {
            if (!within(runLo[q], runHi[q])) continue;
            const size_t first = firstPixel(q);
            uint32_t hit = 0;
            for (const auto& [flo, fhi] : ends) hit |= bitsWithin(&lum[first], runLength(q), flo, fhi);
            hit &= ~bandBits[q] & bitsWithin(&lum[first], runLength(q), 0.f, INFINITY);  // sees the surface
            for (; hit != 0; hit &= hit - 1) marked.push_back(first + size_t(__builtin_ctz(hit)));
        }
        const std::vector<size_t> added = grow(marked);
        at.insert(at.end(), added.begin(), added.end());
    }
    if (asked < at.size()) return out;  // the changes are not small (or reach too far): render the variants

    analysis::Options opt = setup.options;
    opt.level = like.level;
    // Each variant's L at the pixels asked; the image itself is surveyed once (analysis::ImageVariants).
    std::vector<float> values(at.size() * k);
    for (size_t j = 0; j < at.size(); ++j)
        for (size_t v = 0; v < k; ++v) values[j * k + v] = float(L(at[j]) + delta[j * k + v]);
    image.setChanged(at, opt);
    // One thread: the halves alternating on two (each with its own dense L) measured no faster on the 2-core machine.
    for (size_t v = 0; v < k; ++v) {
        const Moved& m = moved[v];
        // What the twins were not asked does not matter: the rounds above ended when every pixel left as it is lay
        // farther than twice the largest change from each variant's level and below its peak by as much.
        if (!m.finite || !(m.peak > 0) || !(m.change < kMaxChange * peak)) continue;
        const analysis::Shape s = image.measure(&values[v], k);
        if (cropped && s.has(analysis::Flag::Clipped)) continue;  // measureInFrame draws the whole frame
        out[v] = s;
    }
    return out;
}

}  // namespace hilite::measurement
