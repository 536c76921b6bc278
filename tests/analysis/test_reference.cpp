// measureReference against closed forms, a brute-force grid, and ../shared/notes/measurement.md's table.

#include "analysis/lobes.hpp"
#include "hilite/analysis/highlight.hpp"

#include "hilite/core/chart.hpp"
#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <initializer_list>

using namespace hilite;
using namespace hilite::analysis;

namespace {

constexpr double kLn2 = 0.69314718055994530942;

/// L = exp(-(x^2/a^2 + y^2/b^2)), (x, y) the offset from (u0, v0) turned by -phi; visible everywhere.
LobeFunction gaussian(double a, double b, double phi = 0, double u0 = 0, double v0 = 0) {
    LobeFunction f;
    f.lobe = [=](double u, double v) {
        const double du = u - u0, dv = v - v0;
        const double x = std::cos(phi) * du + std::sin(phi) * dv, y = -std::sin(phi) * du + std::cos(phi) * dv;
        return std::exp(-(x * x / (a * a) + y * y / (b * b)));
    };
    f.visible = [](double, double) { return true; };
    return f;
}

/// Moments of {visible, L >= T} by the midpoint rule on an n x n grid over the box (a check that shares
/// nothing with the polar contour integration; lattice error about 1e-5 relative at n = 1500).
AreaMoments bruteMoments(const LobeFunction& f, double T, dvec2 lo, dvec2 hi, int n) {
    const dvec2 h = (hi - lo) / double(n);
    double s0 = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double u = lo.x + (i + 0.5) * h.x, v = lo.y + (j + 0.5) * h.y;
            if (!f.visible(u, v) || f.lobe(u, v) < T) continue;
            s0 += 1;
            su += u;
            sv += v;
            suu += u * u;
            suv += u * v;
            svv += v * v;
        }
    }
    AreaMoments m;
    m.area = s0 * h.x * h.y;
    m.mean_u = su / s0;
    m.mean_v = sv / s0;
    m.cuu = suu / s0 - m.mean_u * m.mean_u + h.x * h.x / 12;  // + a cell's own second moment
    m.cuv = suv / s0 - m.mean_u * m.mean_v;
    m.cvv = svv / s0 - m.mean_v * m.mean_v + h.y * h.y / 12;
    return m;
}

Shape reference(const MirrorChart& chart, const test::DirLobe& lobe, double searchRadius = 0.5) {
    return measureReference(test::chartLobe(chart, lobe), Options{}, searchRadius);
}

struct TableRow {
    double thetaDeg, aspect, eccentricity, major, minor, cu;
};

}  // namespace

TEST_CASE("analysis::measureReference") {
    const Options opt;
    SUBCASE("Gaussian ellipse: semi-axes a sqrt(ln 2), b sqrt(ln 2)") {
        const double a = 0.1, b = 0.04;
        const Shape s = measureReference(gaussian(a, b), opt, 0.5);
        CHECK(s.major_deg == doctest::Approx(rad2deg(a * std::sqrt(kLn2))).epsilon(1e-9));
        CHECK(s.minor_deg == doctest::Approx(rad2deg(b * std::sqrt(kLn2))).epsilon(1e-9));
        CHECK(s.aspect == doctest::Approx(b / a).epsilon(1e-9));
        CHECK_NEAR(s.orientation_deg, 0.0, 1e-9);
        CHECK(s.area_deg2 == doctest::Approx(kPi * rad2deg(a) * rad2deg(b) * kLn2).epsilon(1e-9));
        CHECK(s.fwhm_u_deg == doctest::Approx(rad2deg(2 * a * std::sqrt(kLn2))).epsilon(1e-9));
        CHECK(s.fwhm_v_deg == doctest::Approx(rad2deg(2 * b * std::sqrt(kLn2))).epsilon(1e-9));
        CHECK(s.peak == doctest::Approx(1.0).epsilon(1e-15));
        CHECK_NEAR(s.centroid_u_deg, 0.0, 1e-9);
        CHECK(s.flags.empty());
        CHECK(s.region_pixels == 0);
        CHECK(std::isinf(s.minor_pixels));
    }
    SUBCASE("rotated, off-centre Gaussian, threshold 1/4") {
        Options quarter;
        quarter.threshold = 0.25;
        const double a = 0.08, b = 0.05, phi = deg2rad(25.0), u0 = 0.03, v0 = -0.02;
        const Shape s = measureReference(gaussian(a, b, phi, u0, v0), quarter, 0.3, 0.01, 0.0);
        const double k = std::sqrt(std::log(4.0));
        CHECK(s.major_deg == doctest::Approx(rad2deg(a * k)).epsilon(1e-9));
        CHECK(s.minor_deg == doctest::Approx(rad2deg(b * k)).epsilon(1e-9));
        CHECK(s.orientation_deg == doctest::Approx(25.0).epsilon(1e-9));
        CHECK(s.centroid_u_deg == doctest::Approx(rad2deg(u0)).epsilon(1e-9));
        CHECK(s.centroid_v_deg == doctest::Approx(rad2deg(v0)).epsilon(1e-9));
        CHECK(s.peak_u_deg == doctest::Approx(rad2deg(u0)).epsilon(1e-6));
        CHECK(s.peak_v_deg == doctest::Approx(rad2deg(v0)).epsilon(1e-6));
    }
    SUBCASE("Phong n = 1000: circles of radius acos(2^(-1/n)) about wr, 2.1331 deg") {
        const double exact = rad2deg(std::acos(std::pow(0.5, 1.0 / 1000)));
        CHECK(exact == doctest::Approx(2.1331).epsilon(5e-5));
        for (double thetaDeg : {0.0, 30.0, 60.0, 75.0, 85.0}) {
            CAPTURE(thetaDeg);
            const MirrorChart chart(deg2rad(thetaDeg), 0.0);
            const Shape s = reference(chart, test::phongLobe(chart, 1000.0));
            CHECK(s.major_deg == doctest::Approx(exact).epsilon(1e-9));
            CHECK(s.minor_deg == doctest::Approx(exact).epsilon(1e-9));
            CHECK(s.aspect == doctest::Approx(1.0).epsilon(1e-9));
            CHECK_NEAR(s.centroid_u_deg, 0.0, 1e-9);
            CHECK(s.flags.empty());
        }
    }
    SUBCASE("GGX NDF at normal incidence: a circle of radius 2 theta_h") {
        const double alpha = 0.1, a2 = alpha * alpha;
        const double cosThetaH = std::sqrt((1.0 - a2 / std::sqrt(0.5)) / (1.0 - a2));  // D(theta_h) = D(0) / 2
        const double exact = rad2deg(2.0 * std::acos(cosThetaH));
        const MirrorChart chart(0.0, 0.0);
        const Shape s = reference(chart, test::ggxNdfLobe(chart, alpha));
        CHECK(s.major_deg == doctest::Approx(exact).epsilon(1e-9));
        CHECK(s.minor_deg == doctest::Approx(exact).epsilon(1e-9));
        CHECK(s.area_deg2 == doctest::Approx(kPi * exact * exact).epsilon(1e-9));
        CHECK(s.peak == doctest::Approx(1.0 / (kPi * a2)).epsilon(1e-12));
    }
    SUBCASE("GGX NDF, alpha 0.1: measurement.md's table") {
        // The table is converged to about 1e-4; cu is given to 3 decimals.
        for (const TableRow& row : {TableRow{0, 1.00000, 0.00000, 7.4175, 7.4175, 0.0000},
                                    TableRow{30, 0.86593, 0.50017, 7.4170, 6.4226, 0.018},
                                    TableRow{60, 0.50173, 0.86503, 7.4059, 3.7158, 0.156},
                                    TableRow{75, 0.26404, 0.96451, 7.3636, 1.9443, 0.419}}) {
            CAPTURE(row.thetaDeg);
            const MirrorChart chart(deg2rad(row.thetaDeg), 0.0);
            const Shape s = reference(chart, test::ggxNdfLobe(chart, 0.1));
            CHECK_NEAR(s.aspect, row.aspect, 2e-4);
            CHECK_NEAR(s.eccentricity, row.eccentricity, 2e-4);
            CHECK(s.major_deg == doctest::Approx(row.major).epsilon(5e-4));
            CHECK(s.minor_deg == doctest::Approx(row.minor).epsilon(5e-4));
            CHECK_NEAR(s.centroid_u_deg, row.cu, 1e-3);
            CHECK_NEAR(s.centroid_v_deg, 0.0, 1e-9);
            if (row.thetaDeg > 0) CHECK_NEAR(s.orientation_deg, 0.0, 1e-6);  // major axis along u (a circle at 0)
            CHECK(s.flags.empty());
        }
    }
    SUBCASE("GGX NDF, alpha 0.1, 85 deg: the horizon cuts the lobe") {
        const MirrorChart chart(deg2rad(85.0), 0.0);
        const LobeFunction f = test::chartLobe(chart, test::ggxNdfLobe(chart, 0.1));
        const Shape s = measureReference(f, opt, 0.5);
        CHECK(s.has(Flag::HorizonCut));
        CHECK_NEAR(s.aspect, 0.11798, 5e-4);
        CHECK(s.major_deg == doctest::Approx(6.3043).epsilon(2e-3));
        CHECK(s.minor_deg == doctest::Approx(0.7438).epsilon(2e-3));
        CHECK_NEAR(s.centroid_u_deg, 1.687, 5e-3);
        // Against the brute-force grid, which shares nothing with the polar contour.
        Shape b;
        setEllipse(b, bruteMoments(f, 0.5 * s.peak, {-0.1, -0.03}, {0.25, 0.03}, 1500));
        CHECK(s.major_deg == doctest::Approx(b.major_deg).epsilon(5e-4));
        CHECK(s.minor_deg == doctest::Approx(b.minor_deg).epsilon(5e-4));
        CHECK(s.area_deg2 == doctest::Approx(b.area_deg2).epsilon(5e-4));
        CHECK_NEAR(s.centroid_u_deg, b.centroid_u_deg, 2e-3);
    }
    SUBCASE("full microfacet BRDF (F = 1, GGX 0.1, Smith G2), 45 deg: the off-specular shift") {
        const MirrorChart chart(deg2rad(45.0), 0.0);
        const Shape s = reference(chart, test::ggxBrdfLobe(chart, 0.1));
        CHECK_NEAR(s.aspect, 0.69421, 2e-4);
        CHECK(s.major_deg == doctest::Approx(7.5702).epsilon(5e-4));
        CHECK(s.minor_deg == doctest::Approx(5.2553).epsilon(5e-4));
        CHECK_NEAR(s.centroid_u_deg, (-0.79), 5e-3);
        CHECK(s.peak_u_deg < 0.0);  // the peak itself moves away from the normal too
    }
    SUBCASE("peak on the horizon: a lobe centred below it") {
        // Chart at 80 deg: the horizon crosses v = 0 at u = -10 deg; the Gaussian's centre, u = -0.3 rad,
        // is below it, so the largest visible L is at the horizon point and the region is a thin lens.
        const MirrorChart chart(deg2rad(80.0), 0.0);
        LobeFunction f = gaussian(0.1, 0.1, 0.0, -0.3, 0.0);
        f.visible = [chart](double u, double v) { return chart.direction(u, v).z > 0.0; };
        const LobeFunction g = f;
        f.lobe = [g](double u, double v) { return g.visible(u, v) ? g.lobe(u, v) : 0.0; };
        const Shape s = measureReference(f, opt, 0.5);
        CHECK(s.has(Flag::HorizonCut));
        CHECK(s.peak_u_deg == doctest::Approx(-10.0).epsilon(1e-9));
        CHECK_NEAR(s.peak_v_deg, 0.0, 1e-6);
        Shape b;
        setEllipse(b, bruteMoments(f, 0.5 * s.peak, {-0.18, -0.12}, {-0.14, 0.12}, 1500));
        CHECK(s.area_deg2 == doctest::Approx(b.area_deg2).epsilon(1e-3));
        CHECK(s.major_deg == doctest::Approx(b.major_deg).epsilon(1e-3));
        CHECK(s.minor_deg == doctest::Approx(b.minor_deg).epsilon(1e-3));
        CHECK(s.centroid_u_deg == doctest::Approx(b.centroid_u_deg).epsilon(1e-4));
    }
    SUBCASE("no highlight") {
        LobeFunction f = gaussian(0.1, 0.1);
        f.lobe = [](double, double) { return 0.0; };
        const Shape s = measureReference(f, opt, 0.5);
        CHECK(s.has(Flag::NoHighlight));
        CHECK(s.flags.size() == 1);
        CHECK(s.peak == 0.0);
        CHECK(s.major_deg == 0.0);
    }
    SUBCASE("bad input") {
        CHECK_THROWS_AS(measureReference(gaussian(0.1, 0.1), opt, 0.0), InputError);
        CHECK_THROWS_AS(measureReference(LobeFunction{}, opt, 0.5), InputError);
        Options bad;
        bad.threshold = 1.0;
        CHECK_THROWS_AS(measureReference(gaussian(0.1, 0.1), bad, 0.5), InputError);
    }
}
