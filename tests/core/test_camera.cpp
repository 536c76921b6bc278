// PinholeCamera: rays, projection, pixel solid angles, and the measurement / photo views.

#include "hilite/core/camera.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <initializer_list>

using namespace hilite;

namespace {

/// Solid angle of a pyramid with rectangular cross-section of half extents tan(a), tan(b): 4 asin(sin a sin b).
double frustumSolidAngle(double tanHalfX, double tanHalfY) {
    return 4.0 * std::asin(std::sin(std::atan(tanHalfX)) * std::sin(std::atan(tanHalfY)));
}

}  // namespace

TEST_CASE("PinholeCamera::ray") {
    const MirrorChart chart(deg2rad(40.0), 0.0);
    const PinholeCamera cam = PinholeCamera::measurement(chart, chart.wr(), 30.0, 64, 48);
    SUBCASE("right-handed orthonormal frame") {
        CHECK(glm::length(glm::cross(cam.right, cam.up) - cam.back) < 1e-15);
        CHECK_NEAR(glm::dot(cam.right, cam.up), 0.0, 1e-15);
    }
    SUBCASE("the image centre looks along -center") {
        const dvec3 r = cam.ray(32.0, 24.0);
        CHECK(glm::length(r + chart.wr()) < 1e-15);
    }
    SUBCASE("field of view spans the width") {
        const dvec3 left = cam.ray(0.0, 24.0), right = cam.ray(64.0, 24.0);
        CHECK(rad2deg(std::acos(glm::dot(left, right))) == doctest::Approx(30.0).epsilon(1e-12));
    }
    SUBCASE("image up is +u, so up the image the exitant direction goes to -u (the horizon at the top)") {
        const dvec2 top = chart.coords(-cam.ray(32.0, 47.5));
        const dvec2 bottom = chart.coords(-cam.ray(32.0, 0.5));
        CHECK(top.x < 0.0);
        CHECK(bottom.x > 0.0);
        CHECK_NEAR(top.y, 0.0, 1e-12);
        CHECK_NEAR(bottom.y, 0.0, 1e-12);
    }
}

TEST_CASE("PinholeCamera::project") {
    const MirrorChart chart(deg2rad(70.0), deg2rad(15.0));
    const PinholeCamera cam = PinholeCamera::measurement(chart, chart.wr(), 45.0, 100, 60);
    SUBCASE("round trip with ray()") {
        for (double px : {0.0, 13.25, 50.0, 99.5, 100.0}) {
            for (double py : {0.0, 7.5, 30.0, 60.0}) {
                double ndcX = 0, ndcY = 0;
                REQUIRE(cam.project(cam.ray(px, py), ndcX, ndcY));
                CHECK(ndcX == doctest::Approx(2.0 * px / 100 - 1.0).epsilon(1e-12));
                CHECK(ndcY == doctest::Approx(2.0 * py / 60 - 1.0).epsilon(1e-12));
            }
        }
    }
    SUBCASE("directions behind the camera do not project") {
        double ndcX = 0, ndcY = 0;
        CHECK_FALSE(cam.project(cam.back, ndcX, ndcY));
    }
}

TEST_CASE("PinholeCamera::pixelSolidAngle") {
    SUBCASE("the pixels tile the frustum's solid angle") {
        for (double fov : {10.0, 60.0, 100.0}) {
            CAPTURE(fov);
            const MirrorChart chart(deg2rad(30.0), 0.0);
            const PinholeCamera cam = PinholeCamera::measurement(chart, chart.wr(), fov, 200, 150);
            double sum = 0;
            for (int iy = 0; iy < cam.height; ++iy)
                for (int ix = 0; ix < cam.width; ++ix) sum += cam.pixelSolidAngle(ix, iy);
            // Midpoint rule per pixel: relative error O(pixel^2), under 1e-4 here.
            CHECK(sum == doctest::Approx(frustumSolidAngle(cam.tanHalfX, cam.tanHalfY)).epsilon(1e-4));
        }
    }
    SUBCASE("the centre pixel is (pixel width)^2 at unit focal distance") {
        const PinholeCamera cam = PinholeCamera::photo(30.0, 0.0, 5.0, 40.0, 101, 101);
        const double w = 2.0 * cam.tanHalfX / 101;
        CHECK(cam.pixelSolidAngle(50, 50) == doctest::Approx(w * w).epsilon(1e-12));
    }
}

TEST_CASE("PinholeCamera::photo") {
    const PinholeCamera cam = PinholeCamera::photo(30.0, 45.0, 5.0, 40.0, 80, 60);
    SUBCASE("placed at the elevation and azimuth, looking at the origin") {
        CHECK(glm::length(cam.position) == doctest::Approx(5.0));
        CHECK(rad2deg(std::asin(cam.position.z / 5.0)) == doctest::Approx(30.0));
        CHECK(rad2deg(std::atan2(cam.position.y, cam.position.x)) == doctest::Approx(45.0));
        const dvec3 centre = cam.ray(40.0, 30.0);
        CHECK(glm::length(cam.position + 5.0 * centre) < 1e-12);
    }
    SUBCASE("world up is image up") {
        CHECK(cam.up.z > 0.0);
        CHECK_NEAR(cam.right.z, 0.0, 1e-15);
    }
}
