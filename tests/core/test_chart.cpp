// MirrorChart: the (u, v) chart of ../shared/notes/measurement.md.

#include "hilite/core/chart.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <initializer_list>

using namespace hilite;

namespace {

void checkClose(const dvec3& a, const dvec3& b, double eps) {
    CHECK_NEAR(a.x, b.x, eps);
    CHECK_NEAR(a.y, b.y, eps);
    CHECK_NEAR(a.z, b.z, eps);
}

/// 1 / |d we/du x d we/dv| by central differences: (u,v) area per unit solid angle.
double numericAreaPerSolidAngle(const MirrorChart& chart, double u, double v) {
    const double h = 1e-5;
    const dvec3 du = (chart.direction(u + h, v) - chart.direction(u - h, v)) / (2 * h);
    const dvec3 dv = (chart.direction(u, v + h) - chart.direction(u, v - h)) / (2 * h);
    return 1.0 / glm::length(glm::cross(du, dv));
}

}  // namespace

TEST_CASE("MirrorChart::MirrorChart") {
    for (double thetaDeg : {0.0, 30.0, 60.0, 85.0}) {
        for (double phiDeg : {0.0, 40.0}) {
            CAPTURE(thetaDeg);
            CAPTURE(phiDeg);
            const MirrorChart chart(deg2rad(thetaDeg), deg2rad(phiDeg));
            SUBCASE("orthonormal frame about the mirror direction") {
                CHECK(glm::length(chart.wr()) == doctest::Approx(1.0));
                CHECK(glm::length(chart.eu()) == doctest::Approx(1.0));
                CHECK(glm::length(chart.ev()) == doctest::Approx(1.0));
                CHECK_NEAR(glm::dot(chart.eu(), chart.wr()), 0.0, 1e-15);
                CHECK_NEAR(glm::dot(chart.ev(), chart.wr()), 0.0, 1e-15);
                CHECK_NEAR(glm::dot(chart.eu(), chart.ev()), 0.0, 1e-15);
            }
            SUBCASE("wr is the mirror of wi, +u points towards the normal") {
                const dvec3 n(0, 0, 1);
                checkClose(chart.wr(), 2.0 * glm::dot(chart.wi(), n) * n - chart.wi(), 1e-15);
                CHECK(chart.eu().z >= 0.0);
                // Moving by theta_i along +u from wr reaches the normal.
                checkClose(chart.direction(deg2rad(thetaDeg), 0.0), n, 1e-14);
            }
        }
    }
}

TEST_CASE("MirrorChart::direction") {
    const MirrorChart chart(deg2rad(50.0), deg2rad(20.0));
    SUBCASE("origin is the mirror direction") { CHECK(chart.direction(0.0, 0.0) == chart.wr()); }
    SUBCASE("unit length, angle from wr is |(u, v)|") {
        for (double u : {-2.0, -0.3, 0.0, 1e-9, 0.7, 2.5}) {
            for (double v : {-1.1, 0.0, 0.2, 3e-7}) {
                const dvec3 we = chart.direction(u, v);
                CHECK(glm::length(we) == doctest::Approx(1.0).epsilon(1e-15));
                CHECK(std::acos(std::min(1.0, glm::dot(we, chart.wr()))) ==
                      doctest::Approx(std::hypot(u, v)).epsilon(1e-7));
            }
        }
    }
}

TEST_CASE("MirrorChart::coords") {
    const MirrorChart chart(deg2rad(35.0), deg2rad(-70.0));
    SUBCASE("round trip coords(direction(u, v)) = (u, v) for rho < pi") {
        for (double u : {-2.0, -0.3, 0.0, 1e-9, 0.7, 2.5}) {
            for (double v : {-1.1, 0.0, 0.2, 3e-7}) {
                CAPTURE(u);
                CAPTURE(v);
                const dvec2 uv = chart.coords(chart.direction(u, v));
                CHECK_NEAR(uv.x, u, 1e-12);
                CHECK_NEAR(uv.y, v, 1e-12);
            }
        }
    }
    SUBCASE("mirror direction maps to the origin") {
        const dvec2 uv = chart.coords(chart.wr());
        CHECK_NEAR(uv.x, 0.0, 1e-15);
        CHECK_NEAR(uv.y, 0.0, 1e-15);
    }
}

TEST_CASE("MirrorChart::areaPerSolidAngle") {
    const MirrorChart chart(deg2rad(60.0), 0.0);
    SUBCASE("1 at the mirror direction") { CHECK(chart.areaPerSolidAngle(chart.wr()) == 1.0); }
    SUBCASE("rho / sin(rho), the chart's Jacobian, by finite differences") {
        for (double u : {-1.0, -0.2, 0.05, 0.6}) {
            for (double v : {-0.4, 0.0, 0.3}) {
                CAPTURE(u);
                CAPTURE(v);
                const dvec3 we = chart.direction(u, v);
                const double rho = std::hypot(u, v);
                CHECK(chart.areaPerSolidAngle(we) == doctest::Approx(rho / std::sin(rho)).epsilon(1e-12));
                CHECK(chart.areaPerSolidAngle(we) ==
                      doctest::Approx(numericAreaPerSolidAngle(chart, u, v)).epsilon(1e-8));
            }
        }
    }
}
