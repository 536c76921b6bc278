// Bihemispherical albedo: the cosine-weighted average of the directional albedo.

#include "brdf/bihemispherical.hpp"

#include "brdf/integrate.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace hilite;

TEST_CASE("brdf::bihemisphericalAlbedo") {
    SUBCASE("Lambert: rho_hh = rho in every channel") {
        brdf::Params p;
        p.model = brdf::Model::None;
        p.diffuse = brdf::Diffuse::Lambert;
        p.albedo = {0.2, 0.5, 0.9};
        const dvec3 hh = brdf::bihemisphericalAlbedo(p);
        CHECK(hh.x == doctest::Approx(0.2).epsilon(1e-9));
        CHECK(hh.y == doctest::Approx(0.5).epsilon(1e-9));
        CHECK(hh.z == doctest::Approx(0.9).epsilon(1e-9));
    }
    SUBCASE("a lobe whose albedo is theta-independent averages to that albedo") {
        // Oren-Nayar with sigma = 0 is Lambert; a constant directional albedo must come back unchanged.
        brdf::Params p;
        p.model = brdf::Model::None;
        p.diffuse = brdf::Diffuse::OrenNayar;
        p.sigmaDeg = 0.0;
        p.albedo = dvec3(0.7);
        CHECK(brdf::bihemisphericalAlbedo(p).x == doctest::Approx(0.7).epsilon(1e-9));
    }
    SUBCASE("GGX with Smith G: below 1 (masking loses energy), equal to a plain midpoint sum over theta") {
        brdf::Params p;
        p.model = brdf::Model::GGX;
        p.roughness = 0.5;
        p.geometry = brdf::Geometry::Smith;
        const double hh = brdf::bihemisphericalAlbedo(p).x;
        double midpoint = 0;  // 2 int rho cos sin dtheta, 90 midpoints: an independent, cruder quadrature
        for (int i = 0; i < 90; ++i) {
            const double t = (i + 0.5) * 0.5 * kPi / 90;
            midpoint += 2.0 * brdf::albedo(p, rad2deg(t)).x * std::cos(t) * std::sin(t) * (0.5 * kPi / 90);
        }
        CHECK(hh == doctest::Approx(midpoint).epsilon(1e-4));
        CHECK(hh < 1.0);
        CHECK(hh > 0.7);
    }
    SUBCASE("anisotropic: averaged over azimuth too, and matches the isotropic value when alpha_x = alpha_y") {
        brdf::Params p;
        p.model = brdf::Model::Beckmann;
        p.roughness = 0.3;
        p.geometry = brdf::Geometry::Smith;
        const double iso = brdf::bihemisphericalAlbedo(p).x;
        p.roughnessY = 0.3;
        CHECK(brdf::bihemisphericalAlbedo(p).x == doctest::Approx(iso).epsilon(1e-6));
    }
}
