// Supersampling: the jitter grid, n = 1 against measureImage's pixel boundary, and the error against the
// double reference falling as the grid grows (CPU twin images: no GL).

#include "analysis/supersample.hpp"

#include "analysis/lobes.hpp"

#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <limits>

using namespace hilite;

namespace {

/// Measures a lobe with n x n jittered renders of one frame.
analysis::Shape supersampled(const MirrorChart& chart, const test::DirLobe& lobe, double fov, int size, int n) {
    analysis::Supersampler ss(size, size, n * n);
    for (const dvec2 j : analysis::jitterGrid(n))
        ss.add(test::renderView(chart, lobe, chart.wr(), fov, size, size, j).data.data());
    return ss.measure({});
}

}  // namespace

TEST_CASE("analysis::jitterGrid") {
    for (int n = 1; n <= 8; ++n) {
        CAPTURE(n);
        const auto g = analysis::jitterGrid(n);
        REQUIRE(g.size() == size_t(n * n));
        dvec2 mean(0.0);
        for (const dvec2 j : g) {
            CHECK_NEAR(j.x, 0.0, 0.5);
            CHECK_NEAR(j.y, 0.0, 0.5);
            mean += j / double(n * n);
        }
        CHECK_NEAR(mean.x, 0.0, 1e-12);  // symmetric: the samples' mean is the pixel centre
        CHECK_NEAR(mean.y, 0.0, 1e-12);
    }
    CHECK(analysis::jitterGrid(1).front() == dvec2(0.0));
}

TEST_CASE("analysis::Supersampler") {
    const MirrorChart chart = MirrorChart::fromDegrees(60, 0);
    const test::DirLobe lobe = test::ggxNdfLobe(chart, 0.1);
    const analysis::Shape ref = analysis::measureReference(test::chartLobe(chart, lobe), {}, 0.5);

    SUBCASE("n = 1 is the pixel in/out boundary of measureImage") {
        const ImageF img = test::renderView(chart, lobe, chart.wr(), 20, 96, 96);
        analysis::Options pixel;
        pixel.subpixel = false;
        const analysis::Shape a = analysis::measureImage(img.data.data(), 96, 96, pixel);
        analysis::Supersampler ss(96, 96, 1);
        ss.add(img.data.data());
        const analysis::Shape b = ss.measure({});
        CHECK(b.aspect == doctest::Approx(a.aspect).epsilon(1e-9));
        CHECK(b.major_deg == doctest::Approx(a.major_deg).epsilon(1e-9));
        CHECK(b.minor_deg == doctest::Approx(a.minor_deg).epsilon(1e-9));
        CHECK(b.area_deg2 == doctest::Approx(a.area_deg2).epsilon(1e-9));
        CHECK(b.region_pixels == a.region_pixels);
        CHECK(b.flags == a.flags);
    }
    SUBCASE("a finer grid reduces the error against the double reference") {
        // 64^2 over 20 deg: the region is ~30 x 15 pixels, where the pixel boundary's lattice noise dominates.
        const double e1 = std::abs(supersampled(chart, lobe, 20, 64, 1).aspect - ref.aspect);
        const double e4 = std::abs(supersampled(chart, lobe, 20, 64, 4).aspect - ref.aspect);
        CAPTURE(e1);
        CAPTURE(e4);
        CHECK(e4 < e1);
        CHECK(e4 < 2e-3);
    }
    SUBCASE("flags: the horizon crossing a pixel, the frame's border") {
        const MirrorChart grazing = MirrorChart::fromDegrees(85, 0);
        const analysis::Shape cut = supersampled(grazing, test::ggxNdfLobe(grazing, 0.3), 40, 64, 2);
        CHECK(cut.has(analysis::Flag::HorizonCut));
        const analysis::Shape clipped = supersampled(chart, lobe, 5, 32, 2);
        CHECK(clipped.has(analysis::Flag::Clipped));
    }
    SUBCASE("float_overflow and float_underflow, as measureImage") {
        ImageF img(4, 4, 4);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                float* p = img.pixel(x, y);
                p[0] = x == 1 && y == 1 ? 1.f : 0.5f, p[1] = float(x), p[2] = float(y), p[3] = 1.f;
            }
        ImageF over = img, under = img;
        over.pixel(2, 2)[0] = std::numeric_limits<float>::infinity();
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) under.pixel(x, y)[0] *= 1e-39f;  // the level: a float denormal
        analysis::Supersampler a(4, 4, 2), b(4, 4, 2);
        for (int k = 0; k < 2; ++k) a.add(k ? over.data.data() : img.data.data()), b.add(under.data.data());
        const analysis::Shape sa = a.measure({}), sb = b.measure({});
        CHECK(sa.flags == analysis::FlagSet{analysis::Flag::FloatOverflow});
        CHECK(std::isnan(sa.aspect));
        CHECK(sb.flags == analysis::FlagSet{analysis::Flag::FloatUnderflow});
        CHECK(std::isnan(sb.major_deg));
    }
    SUBCASE("misuse") {
        CHECK_THROWS_AS(analysis::Supersampler(0, 4, 1), InputError);
        CHECK_THROWS_AS(analysis::Supersampler(4, 4, 0), InputError);
        analysis::Supersampler ss(4, 4, 2);
        CHECK_THROWS_AS(ss.measure({}), InputError);  // a render missing
    }
}
