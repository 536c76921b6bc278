// measureImage on images made on the CPU (the twin of the GL measurement view, see lobes.hpp) and on
// small hand-made images whose moments are known exactly.

#include "analysis/lobes.hpp"
#include "hilite/analysis/highlight.hpp"

#include "hilite/core/chart.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/image.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <vector>

using namespace hilite;
using namespace hilite::analysis;

namespace {

Shape analyse(const ImageF& img, const Options& opt = {}) {
    return measureImage(img.data.data(), img.width, img.height, opt);
}

Options inOut() {
    Options opt;
    opt.subpixel = false;
    return opt;
}

/// GGX NDF lobe (alpha 0.1) at theta_i, framed about wr so that the half-max region's major axis
/// (semi-axis about 7.4 deg) fills 60% of the frame.
ImageF ggxView(const MirrorChart& chart, int size, double fovDeg = 2.0 * 7.42 / 0.6) {
    return test::renderView(chart, test::ggxNdfLobe(chart, 0.1), chart.wr(), fovDeg, size, size);
}

Shape ggxReference(const MirrorChart& chart) {
    return measureReference(test::chartLobe(chart, test::ggxNdfLobe(chart, 0.1)), Options{}, 0.5);
}

/// A hand-made image: w = 1, (u, v) = (x, y) in radians, L given per pixel.
ImageF gridImage(int width, int height, const std::function<float(int, int)>& L) {
    ImageF img(width, height, 4);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            float* p = img.pixel(x, y);
            p[0] = L(x, y);
            p[1] = float(x);
            p[2] = float(y);
            p[3] = 1.f;
        }
    }
    return img;
}

ImageF transposed(const ImageF& img) {
    ImageF t(img.height, img.width, img.channels);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < img.channels; ++c) t.pixel(y, x)[c] = img.pixel(x, y)[c];
    return t;
}

struct Errors {
    double aspect, major;  ///< |image - reference| in aspect, relative in the semi-major axis
};

Errors errors(const Shape& image, const Shape& ref) {
    return {std::abs(image.aspect - ref.aspect), std::abs(image.major_deg / ref.major_deg - 1.0)};
}

/// The in/out measurement written the obvious way, pixel by pixel, to check the bit-mask pass against.
Shape naiveInOut(const ImageF& img, const Options& opt) {
    Shape s;
    auto visible = [&](int x, int y) { return img.pixel(x, y)[3] > 0.f; };
    double peak = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (visible(x, y)) peak = std::max(peak, double(img.pixel(x, y)[0]));
    if (peak == 0) {
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    const double T = opt.threshold * peak;
    auto in = [&](int x, int y) { return visible(x, y) && double(img.pixel(x, y)[0]) >= T; };
    auto sky = [&](int x, int y) { return x >= 0 && y >= 0 && x < img.width && y < img.height && !visible(x, y); };
    double s0 = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0;
    bool clipped = false, cut = false, covers = true;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            if (visible(x, y) && !in(x, y)) covers = false;
            if (!in(x, y)) continue;
            const float* p = img.pixel(x, y);
            const double w = p[3], u = p[1], v = p[2];
            s0 += w, su += w * u, sv += w * v, suu += w * u * u, suv += w * u * v, svv += w * v * v;
            ++s.region_pixels;
            clipped = clipped || x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1;
            cut = cut || sky(x - 1, y) || sky(x + 1, y) || sky(x, y - 1) || sky(x, y + 1);
        }
    }
    const AreaMoments m{s0,
                        su / s0,
                        sv / s0,
                        suu / s0 - su * su / (s0 * s0),
                        suv / s0 - su * sv / (s0 * s0),
                        svv / s0 - sv * sv / (s0 * s0)};
    setEllipse(s, m);
    s.minor_pixels = 2.0 * deg2rad(s.minor_deg) / std::sqrt(s0 / double(s.region_pixels));
    if (clipped) s.flags.insert(Flag::Clipped);
    if (cut) s.flags.insert(Flag::HorizonCut);
    if (s.minor_pixels < opt.minPixelsAcross) s.flags.insert(Flag::UnderResolved);
    if (covers) s.flags.insert(Flag::CoversFrame);
    return s;
}

}  // namespace

TEST_CASE("analysis::measureImage") {
    SUBCASE("GGX alpha 0.1 at 256^2 agrees with the reference") {
        for (double thetaDeg : {0.0, 30.0, 60.0, 75.0}) {
            CAPTURE(thetaDeg);
            const MirrorChart chart(deg2rad(thetaDeg), 0.0);
            const Shape ref = ggxReference(chart);
            const ImageF img = ggxView(chart, 256);
            for (bool subpixel : {false, true}) {
                CAPTURE(subpixel);
                Options opt;
                opt.subpixel = subpixel;
                const Shape s = analyse(img, opt);
                // In/out pixels: lattice noise, ~1e-3 here; sub-pixel coverage: ~1e-4.
                const double axisTol = subpixel ? 2e-3 : 1e-2, aspectTol = subpixel ? 5e-4 : 5e-3;
                CHECK_NEAR(s.aspect, ref.aspect, aspectTol);
                CHECK(s.major_deg == doctest::Approx(ref.major_deg).epsilon(axisTol));
                CHECK(s.minor_deg == doctest::Approx(ref.minor_deg).epsilon(axisTol));
                CHECK(s.area_deg2 == doctest::Approx(ref.area_deg2).epsilon(2 * axisTol));
                CHECK_NEAR(s.centroid_u_deg, ref.centroid_u_deg, 0.01);
                CHECK_NEAR(s.centroid_v_deg, 0.0, 1e-6);
                CHECK(s.fwhm_u_deg == doctest::Approx(ref.fwhm_u_deg).epsilon(0.01));
                CHECK(s.fwhm_v_deg == doctest::Approx(ref.fwhm_v_deg).epsilon(0.01));
                if (thetaDeg > 0) CHECK_NEAR(s.orientation_deg, 0.0, 0.01);
                CHECK_NEAR(s.peak_u_deg, 0.0, 0.1);  // within a pixel (0.058 deg) of wr
                CHECK(s.peak == doctest::Approx(ref.peak).epsilon(1e-3));
                CHECK(s.flags.empty());
            }
        }
    }
    SUBCASE("errors shrink as the pixels do (64 -> 512)") {
        // RMS over four framings, the view centre moved by fractions of a pixel: in/out pixels give a
        // lattice error that depends on where the contour falls between pixel centres.
        const MirrorChart chart(deg2rad(60.0), 0.0);
        const Shape ref = ggxReference(chart);
        const double fov = 2.0 * 7.42 / 0.6;
        std::vector<Errors> sub, whole;
        for (int size : {64, 128, 256, 512}) {
            Errors s2{0, 0}, w2{0, 0};
            for (const dvec2 shift : {dvec2(0, 0), dvec2(0.3, 0.1), dvec2(0.6, 0.45), dvec2(0.15, 0.8)}) {
                const dvec2 centre = deg2rad(fov / size) * shift;
                const dvec3 view = chart.direction(centre.x, centre.y);
                const ImageF img = test::renderView(chart, test::ggxNdfLobe(chart, 0.1), view, fov, size, size);
                const Errors es = errors(analyse(img), ref), ew = errors(analyse(img, inOut()), ref);
                s2 = {s2.aspect + es.aspect * es.aspect / 4, s2.major + es.major * es.major / 4};
                w2 = {w2.aspect + ew.aspect * ew.aspect / 4, w2.major + ew.major * ew.major / 4};
            }
            sub.push_back({std::sqrt(s2.aspect), std::sqrt(s2.major)});
            whole.push_back({std::sqrt(w2.aspect), std::sqrt(w2.major)});
            MESSAGE("size " << size << ": subpixel aspect " << sub.back().aspect << " major " << sub.back().major
                            << ", in/out aspect " << whole.back().aspect << " major " << whole.back().major);
        }
        // In/out pixels: lattice noise, not monotone, but far smaller at 512 than at 64.
        CHECK(whole[3].aspect < whole[0].aspect / 4);
        CHECK(whole[3].major < whole[0].major / 4);
        CHECK(whole[3].aspect < 1e-3);
        // Sub-pixel coverage: second order, every halving of the pixel divides the axis error by ~4.
        for (size_t i = 1; i < sub.size(); ++i) CHECK(sub[i].major < sub[i - 1].major / 3);
        CHECK(sub[3].aspect < sub[0].aspect / 4);
        CHECK(sub[3].aspect < 1e-4);
        CHECK(sub[3].major < 1e-4);
    }
    SUBCASE("sizes that are not multiples of 32") {
        const MirrorChart chart(deg2rad(30.0), 0.0);
        const Shape ref = ggxReference(chart);
        for (const dvec2 size : {dvec2(250, 170), dvec2(77, 301), dvec2(333, 333)}) {
            CAPTURE(size.x);
            const ImageF img =
                test::renderView(chart, test::ggxNdfLobe(chart, 0.1), chart.wr(), 30.0, int(size.x), int(size.y));
            const Shape s = analyse(img);
            CHECK(s.major_deg == doctest::Approx(ref.major_deg).epsilon(5e-3));
            CHECK(s.minor_deg == doctest::Approx(ref.minor_deg).epsilon(5e-3));
            CHECK(s.flags.empty());
        }
    }
    SUBCASE("random images: same as the pixel-by-pixel in/out measurement") {
        // Noise L, random sky, widths around the 32-pixel runs: every mask and edge case of the fast pass.
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> uniform(0.f, 1.f);
        Options opt = inOut();
        for (int width : {1, 5, 31, 32, 33, 64, 70}) {
            for (int height : {1, 3, 40}) {
                for (float skyFraction : {0.f, 0.2f}) {
                    CAPTURE(width);
                    CAPTURE(height);
                    CAPTURE(skyFraction);
                    ImageF img(width, height, 4);
                    for (int y = 0; y < height; ++y) {
                        for (int x = 0; x < width; ++x) {
                            if (uniform(rng) < skyFraction) continue;
                            float* p = img.pixel(x, y);
                            p[0] = uniform(rng);
                            p[1] = 0.01f * x + 0.002f * y;
                            p[2] = 0.01f * y - 0.003f * x;
                            p[3] = 1e-4f * (1.f + 0.1f * uniform(rng));
                        }
                    }
                    opt.threshold = 0.3 + 0.4 * uniform(rng);
                    const Shape fast = analyse(img, opt), naive = naiveInOut(img, opt);
                    CHECK(fast.region_pixels == naive.region_pixels);
                    CHECK(fast.flags == naive.flags);
                    CHECK(fast.area_deg2 == doctest::Approx(naive.area_deg2).epsilon(1e-12));
                    CHECK(fast.major_deg == doctest::Approx(naive.major_deg).epsilon(1e-9));
                    // (absolute: a single row of pixels along a line has minor = 0 up to rounding)
                    CHECK_NEAR(fast.minor_deg, naive.minor_deg, 1e-6 * naive.major_deg);
                    CHECK(fast.centroid_u_deg == doctest::Approx(naive.centroid_u_deg).epsilon(1e-12));
                }
            }
        }
    }
    SUBCASE("u and v are read from the channels, not from the image axes") {
        const MirrorChart chart(deg2rad(60.0), 0.0);
        const ImageF img = ggxView(chart, 128);
        const Shape a = analyse(img), b = analyse(transposed(img));
        CHECK(b.aspect == doctest::Approx(a.aspect).epsilon(1e-12));
        CHECK(b.major_deg == doctest::Approx(a.major_deg).epsilon(1e-12));
        CHECK(b.orientation_deg == doctest::Approx(a.orientation_deg).epsilon(1e-9));
        CHECK(b.fwhm_u_deg == doctest::Approx(a.fwhm_u_deg).epsilon(1e-12));
        CHECK(b.fwhm_v_deg == doctest::Approx(a.fwhm_v_deg).epsilon(1e-12));
        CHECK(a.fwhm_u_deg > 1.5 * a.fwhm_v_deg);  // u is the long way at 60 deg
    }
    SUBCASE("rotated lobe: orientation") {
        // L = exp(-(x^2/a^2 + y^2/b^2)) in (u, v) turned by 30 deg: semi-axes a sqrt(ln 2), b sqrt(ln 2).
        const MirrorChart chart(deg2rad(30.0), 0.0);
        const double phi = deg2rad(30.0), a = 0.1, b = 0.05, k = std::sqrt(std::log(2.0));
        const test::DirLobe lobe = [&](const dvec3& we) {
            const dvec2 uv = chart.coords(we);
            const double x = std::cos(phi) * uv.x + std::sin(phi) * uv.y,
                         y = -std::sin(phi) * uv.x + std::cos(phi) * uv.y;
            return std::exp(-(x * x / (a * a) + y * y / (b * b)));
        };
        const Shape s = analyse(test::renderView(chart, lobe, chart.wr(), 20.0, 256, 256));
        CHECK(s.orientation_deg == doctest::Approx(30.0).epsilon(1e-3));
        CHECK(s.major_deg == doctest::Approx(rad2deg(a * k)).epsilon(1e-3));
        CHECK(s.minor_deg == doctest::Approx(rad2deg(b * k)).epsilon(1e-3));
    }
    SUBCASE("hard-edged 3x3 block: exact moments in both modes") {
        const ImageF img =
            gridImage(10, 8, [](int x, int y) { return (x >= 4 && x <= 6 && y >= 2 && y <= 4) ? 1.f : 0.f; });
        for (const Options& opt : {Options{}, inOut()}) {
            const Shape s = analyse(img, opt);
            CHECK(s.region_pixels == 9);
            CHECK(s.area_deg2 == doctest::Approx(9.0 * rad2deg(1.0) * rad2deg(1.0)).epsilon(1e-12));
            CHECK(s.centroid_u_deg == doctest::Approx(rad2deg(5.0)).epsilon(1e-12));
            CHECK(s.centroid_v_deg == doctest::Approx(rad2deg(3.0)).epsilon(1e-12));
            // Variance of {-1, 0, 1} is 2/3 on each axis: semi-axes 2 sqrt(2/3) rad.
            CHECK(s.major_deg == doctest::Approx(rad2deg(2.0 * std::sqrt(2.0 / 3.0))).epsilon(1e-12));
            CHECK(s.aspect == doctest::Approx(1.0).epsilon(1e-12));
            CHECK(s.minor_pixels == doctest::Approx(4.0 * std::sqrt(2.0 / 3.0)).epsilon(1e-12));
            CHECK(s.flags == FlagSet{Flag::UnderResolved});
        }
    }
    SUBCASE("linear ramp: sub-pixel coverage and the width crossings") {
        // L = x + 1 over 20 x 5, threshold 0.52: T = 10.4, so the contour is at x = 9.4 and pixel 9
        // ([8.5, 9.5]) is one tenth inside. Rows run along u.
        Options opt;
        opt.threshold = 0.52;
        const ImageF img = gridImage(20, 5, [](int x, int) { return float(x + 1); });
        const Shape sub = analyse(img, opt);
        opt.subpixel = false;
        const Shape whole = analyse(img, opt);
        const double deg2 = rad2deg(1.0) * rad2deg(1.0);
        CHECK(sub.area_deg2 == doctest::Approx(5 * 10.1 * deg2).epsilon(1e-6));
        CHECK(whole.area_deg2 == doctest::Approx(5 * 10.0 * deg2).epsilon(1e-12));
        for (const Shape& s : {sub, whole}) {
            CHECK(s.region_pixels == 50);
            CHECK(s.fwhm_u_deg == doctest::Approx(rad2deg(19.0 - 9.4)).epsilon(1e-6));  // border: last centre
            CHECK(s.fwhm_v_deg == doctest::Approx(rad2deg(4.0)).epsilon(1e-6));
            CHECK(s.has(Flag::Clipped));
            CHECK_FALSE(s.has(Flag::CoversFrame));
        }
    }
    SUBCASE("a region beside the sky is cut by the horizon") {
        ImageF img = gridImage(
            12, 12, [](int x, int y) { return float(std::exp(-0.1 * ((x - 6) * (x - 6) + (y - 6) * (y - 6)))); });
        for (int x = 0; x < 12; ++x) {  // rows 8.. see the sky
            for (int y = 8; y < 12; ++y) {
                float* p = img.pixel(x, y);
                p[0] = p[1] = p[2] = p[3] = 0.f;
            }
        }
        const Shape s = analyse(img);
        CHECK(s.has(Flag::HorizonCut));
        CHECK_FALSE(s.has(Flag::Clipped));
        // Along v the region stops at the sky: the crossing is taken at the pixel edge, y = 7.5.
        const double below = 6.0 - std::sqrt(std::log(2.0) / 0.1);
        CHECK(s.fwhm_v_deg == doctest::Approx(rad2deg(7.5 - below)).epsilon(0.03));
    }
}

TEST_CASE("analysis::measureImage flags") {
    SUBCASE("clipped: the frame is smaller than the region") {
        const MirrorChart chart(deg2rad(60.0), 0.0);
        const Shape s = analyse(ggxView(chart, 128, 11.0));
        CHECK(s.has(Flag::Clipped));
        CHECK_FALSE(s.has(Flag::CoversFrame));
        CHECK_FALSE(s.has(Flag::HorizonCut));
    }
    SUBCASE("under-resolved: a narrow lobe in a wide, coarse frame") {
        const MirrorChart chart(deg2rad(30.0), 0.0);
        const test::DirLobe phong = test::phongLobe(chart, 1000.0);
        const Shape coarse = analyse(test::renderView(chart, phong, chart.wr(), 60.0, 32, 32));
        CHECK(coarse.has(Flag::UnderResolved));
        CHECK(coarse.minor_pixels < 8.0);
        const Shape fine = analyse(test::renderView(chart, phong, chart.wr(), 10.0, 256, 256));
        CHECK(fine.flags.empty());
        CHECK(fine.minor_pixels > 100.0);
    }
    SUBCASE("no highlight: all dark, or nothing visible") {
        ImageF dark = gridImage(16, 16, [](int, int) { return 0.f; });
        Shape s = analyse(dark);
        CHECK(s.flags == FlagSet{Flag::NoHighlight});
        CHECK(s.peak == 0.0);
        CHECK(s.major_deg == 0.0);
        const ImageF sky(16, 16, 4);
        s = analyse(sky);
        CHECK(s.flags == FlagSet{Flag::NoHighlight});
    }
    SUBCASE("covers the frame: a wide lobe in a tiny field of view") {
        const MirrorChart chart(0.0, 0.0);
        const Shape s = analyse(ggxView(chart, 64, 2.0));
        CHECK(s.has(Flag::CoversFrame));
        CHECK(s.has(Flag::Clipped));
    }
    SUBCASE("horizon cut: GGX alpha 0.3 at 85 deg in a wide frame") {
        const MirrorChart chart(deg2rad(85.0), 0.0);
        const test::DirLobe lobe = test::ggxNdfLobe(chart, 0.3);
        const Shape s = analyse(test::renderView(chart, lobe, chart.wr(), 60.0, 256, 256));
        const Shape ref = measureReference(test::chartLobe(chart, lobe), Options{}, 1.0);
        CHECK(s.has(Flag::HorizonCut));
        CHECK(ref.has(Flag::HorizonCut));
        CHECK_FALSE(s.has(Flag::Clipped));
        // Pixels beside the horizon count whole: a bias of a fraction of a pixel along the cut.
        CHECK_NEAR(s.aspect, ref.aspect, 0.005);
        CHECK(s.major_deg == doctest::Approx(ref.major_deg).epsilon(0.01));
        CHECK(s.minor_deg == doctest::Approx(ref.minor_deg).epsilon(0.02));
    }
    SUBCASE("float_overflow: an inf or NaN pixel leaves the numbers unmeasured, not 0 or 1") {
        // A bright spot of 5 x 5 pixels with one pixel past float's range (before: aspect 1, major 0, no flag).
        for (const float bad : {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
            CAPTURE(bad);
            const Shape s = analyse(gridImage(16, 16, [bad](int x, int y) {
                if (x == 8 && y == 8) return bad;
                return std::abs(x - 8) <= 2 && std::abs(y - 8) <= 2 ? 1.f : 0.f;
            }));
            CHECK(s.flags == FlagSet{Flag::FloatOverflow});
            CHECK(std::isnan(s.aspect));
            CHECK(std::isnan(s.major_deg));
            CHECK(std::isnan(s.peak));
            CHECK(s.components == 0);
        }
    }
    SUBCASE("float_underflow: a level below the smallest normal float") {
        // The same spot at 1e-39 (a float denormal): its level 5e-40 compares digits float no longer holds.
        const Shape s = analyse(gridImage(
            16, 16, [](int x, int y) { return std::abs(x - 8) <= 2 && std::abs(y - 8) <= 2 ? 1e-39f : 0.f; }));
        CHECK(s.flags == FlagSet{Flag::FloatUnderflow});
        CHECK(std::isnan(s.aspect));
        // At 1e-30 (normal) the spot measures: the check is the level's, not the values' size.
        const Shape normal = analyse(gridImage(
            16, 16, [](int x, int y) { return std::abs(x - 8) <= 2 && std::abs(y - 8) <= 2 ? 1e-30f : 0.f; }));
        CHECK_FALSE(unmeasured(normal));
        CHECK(normal.aspect == doctest::Approx(1.0));
    }
    SUBCASE("bad input") {
        const ImageF img = gridImage(4, 4, [](int, int) { return 1.f; });
        CHECK_THROWS_AS(measureImage(nullptr, 4, 4, Options{}), InputError);
        CHECK_THROWS_AS(measureImage(img.data.data(), 0, 4, Options{}), InputError);
        Options bad;
        bad.threshold = 0.0;
        CHECK_THROWS_AS(measureImage(img.data.data(), 4, 4, bad), InputError);
    }
}
