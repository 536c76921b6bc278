// analysis::ImageVariants (table_error's half tables, measurement/in_frame_twin.cpp) against measureImage of each
// variant's whole image: the same shape to rounding, whether a variant's threshold keeps the pixels left as they are
// on their side (the fixed pixels' sums, gathered once) or not (its whole region summed again).

#include "analysis/image_variants.hpp"
#include "analysis/lobes.hpp"
#include "hilite/analysis/highlight.hpp"

#include "hilite/core/chart.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/image.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

using namespace hilite;
using namespace hilite::analysis;

namespace {

/// Both NaN (an unmeasured shape's), or equal.
bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

/// The shapes agree to rounding: the region's pixels, flags, peak and widths exactly, the moments' values to 1e-12
/// (both NaN where nothing was measured).
void checkSame(const Shape& a, const Shape& b) {
    CHECK(a.flags == b.flags);
    CHECK(a.region_pixels == b.region_pixels);
    CHECK(same(a.peak, b.peak));
    CHECK(same(a.peak_u_deg, b.peak_u_deg));
    CHECK(same(a.fwhm_u_deg, b.fwhm_u_deg));
    CHECK(same(a.fwhm_v_deg, b.fwhm_v_deg));
    const double scale = 1.0 + std::abs(b.major_deg) + std::abs(b.area_deg2);
    // Plain arrays, not structured bindings: C++17 lambdas (CAPTURE's) cannot capture bindings (clang rejects it).
    for (const std::array<double, 2>& xy : {std::array<double, 2>{a.aspect, b.aspect},
                                            {a.major_deg, b.major_deg},
                                            {a.minor_deg, b.minor_deg},
                                            {a.centroid_u_deg, b.centroid_u_deg},
                                            {a.centroid_v_deg, b.centroid_v_deg},
                                            {a.area_deg2, b.area_deg2},
                                            {a.orientation_deg, b.orientation_deg}}) {
        const double x = xy[0], y = xy[1];
        CAPTURE(x);
        CAPTURE(y);
        CHECK((same(x, y) || std::abs(x - y) <= 1e-12 * scale));
    }
}

}  // namespace

TEST_CASE("analysis::ImageVariants: each variant's shape is measureImage's of its image") {
    const MirrorChart chart(deg2rad(60.0), 0.0);
    ImageF img = test::renderView(chart, test::ggxNdfLobe(chart, 0.1), chart.wr(), 2.0 * 7.42 / 0.6, 96, 80);
    const int W = img.width, H = img.height;
    const size_t n = size_t(W) * size_t(H);
    for (int x = 0; x < 10; ++x) img.pixel(x, 0)[3] = 0.f;  // a few pixels of sky
    float peak = 0;
    for (size_t i = 0; i < n; ++i) peak = std::max(peak, img.data[4 * i]);
    // The pixels changed: those near the half-maximum contour, the peak's, and one of the sky (ignored).
    std::vector<size_t> at;
    size_t peakAt = n;  // the first pixel holding it (two do: the lobe is symmetric about the row)
    for (size_t i = 0; i < n; ++i) {
        if (img.data[4 * i] == peak && peakAt == n) peakAt = i;
        if (std::abs(img.data[4 * i] - 0.5f * peak) < 0.08f * peak || img.data[4 * i] == peak) at.push_back(i);
    }
    at.push_back(3);  // sky
    REQUIRE(at.size() > 100);
    REQUIRE(at.size() < n / 3);
    const size_t k = 5;
    std::vector<float> values(at.size() * k);
    for (size_t j = 0; j < at.size(); ++j) {
        const float L = img.data[4 * at[j]];
        const double wobble = std::sin(0.7 * double(at[j]));
        values[j * k + 0] = L * float(1.0 + 1e-3 * wobble);   // a little different, as a half table is
        values[j * k + 1] = at[j] == peakAt ? L * 1.01f : L;  // the peak up by 1%: the level moves with it
        values[j * k + 2] = L * float(1.0 + 0.2 * wobble);    // far: the level passes pixels left as they are
        values[j * k + 3] = at[j] == peakAt ? INFINITY : L;   // past float's range
        values[j * k + 4] = L * 0.5f;                         // every changed pixel halved: another peak
    }
    for (const bool subpixel : {true, false})
        for (const double level : {0.0, 0.4 * double(peak)}) {
            CAPTURE(subpixel);
            CAPTURE(level);
            Options opt;
            opt.subpixel = subpixel;
            opt.level = level;
            ImageVariants variants(img.data.data(), W, H);
            CHECK(variants.peak() == peak);
            CHECK(variants.peakPixel() == peakAt);
            const std::vector<float> before = variants.luminance();
            variants.setChanged(at, opt);
            for (size_t v = 0; v < k; ++v) {
                CAPTURE(v);
                ImageF patched = img;
                for (size_t j = 0; j < at.size(); ++j) patched.data[4 * at[j]] = values[j * k + v];
                const Shape whole = measureImage(patched.data.data(), W, H, opt);
                const long used = variants.fixedSumsUsed();
                checkSame(variants.measure(&values[v], k), whole);
                CHECK(variants.luminance() == before);  // the variant's L taken out again
                // The small change and the peak's keep every other pixel on its side of the level, and so does
                // any change at a level given: the fixed pixels' sums served them. The far change moves the level past
                // pixels left as they are: the whole region is summed again. Past float's range: no sums.
                const bool fixed = variants.fixedSumsUsed() > used;
                if (v <= 1 || (level > 0 && v != 3)) CHECK(fixed);
                if ((level == 0 && v == 2) || v == 3) CHECK_FALSE(fixed);
            }
            CHECK(measureImage(img.data.data(), W, H, opt).flags.empty());
        }
    ImageVariants variants(img.data.data(), W, H);
    checkSame(variants.measure(nullptr, 0), measureImage(img.data.data(), W, H, Options{}));  // nothing changed yet
    CHECK_THROWS_AS(variants.setChanged({n}, Options{}), InputError);
    CHECK_THROWS_AS(ImageVariants(nullptr, W, H), InputError);
}
