#include "measurement/prefilter_check.hpp"
#include "render/renderer.hpp"

#include "render/bump_moments.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::measurement {

namespace {

/// Mean L of each kBlock x kBlock block (partial blocks at the edges dropped), row-major.
std::vector<double> blockMeans(const ImageF& img, int bx, int by) {
    const int b = PrefilterCheck::kBlock;
    std::vector<double> out(size_t(bx) * size_t(by), 0.0);
    for (int j = 0; j < by; ++j)
        for (int i = 0; i < bx; ++i) {
            double s = 0;
            for (int y = 0; y < b; ++y)
                for (int x = 0; x < b; ++x) s += img.pixel(i * b + x, j * b + y)[0];
            out[size_t(j) * size_t(bx) + size_t(i)] = s / (b * b);
        }
    return out;
}

}  // namespace

PrefilterCheck checkPrefilter(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup,
                              const Measurement& m) {
    const PinholeCamera cam = measurementCamera(scene, m.center, m.fovDeg, setup.width, setup.height);
    render::Scene ss = scene, mom = scene, next = scene;
    ss.surface.filter = next.surface.filter = render::BumpFilter::Supersample;
    mom.surface.filter = render::BumpFilter::Moments;
    next.surface.seed = scene.surface.seed + 1;
    PrefilterCheck c;
    ImageF a, b, n;
    renderer.render(ss, cam, render::Output::Measure, a);
    renderer.render(mom, cam, render::Output::Measure, b);
    renderer.render(next, cam, render::Output::Measure, n);
    c.supersampled = analysis::measureImage(a.data.data(), a.width, a.height, setup.options);
    c.moments = analysis::measureImage(b.data.data(), b.width, b.height, setup.options);
    c.nextSeed = analysis::measureImage(n.data.data(), n.width, n.height, setup.options);
    const int bx = cam.width / PrefilterCheck::kBlock, by = cam.height / PrefilterCheck::kBlock;
    const auto A = blockMeans(a, bx, by), B = blockMeans(b, bx, by), N = blockMeans(n, bx, by);
    const double top = B.empty() ? 0.0 : *std::max_element(B.begin(), B.end());
    double d2 = 0, n2 = 0, mean = 0;
    for (size_t k = 0; k < B.size(); ++k) {
        if (!(B[k] >= 0.5 * top) || !(top > 0)) continue;  // outside the highlight
        // Only where supersampling resolves the bumps: all four corner pixels within the patch cap.
        const int side = PrefilterCheck::kBlock, i = int(k % size_t(bx)) * side, j = int(k / size_t(bx)) * side;
        bool resolved = true;
        for (int q = 0; q < 4; ++q)
            resolved = resolved && render::bumpSamplesAt(ss, cam, i + (q % 2) * (side - 1) + 0.5,
                                                         j + (q / 2) * (side - 1) + 0.5) <= render::kMaxBumpSamples;
        if (!resolved) {
            ++c.unresolvedBlocks;
            continue;
        }
        ++c.blocks;
        d2 += (A[k] - B[k]) * (A[k] - B[k]);
        n2 += (A[k] - N[k]) * (A[k] - N[k]);
        mean += B[k];
    }
    if (c.blocks == 0) return c;
    mean /= c.blocks;
    c.blockError = std::sqrt(d2 / c.blocks) / mean;
    c.blockNoise = std::sqrt(n2 / c.blocks / 2.0) / mean;
    c.prefilterError = std::sqrt(std::max(0.0, c.blockError * c.blockError - c.blockNoise * c.blockNoise));
    return c;
}

}  // namespace hilite::measurement
