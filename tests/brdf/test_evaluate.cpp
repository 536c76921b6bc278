// The BRDF as a whole: reciprocity f(wi, wo) = f(wo, wi) for every model and term combination, and
// the isotropic limit of the anisotropic path.

#include "brdf/combos.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <random>

using namespace hilite;

namespace {

/// A direction above the horizon: uniform in (cos theta, phi) with cos theta in [0.01, 1].
dvec3 randomDirection(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double z = 0.01 + 0.99 * u(rng), phi = 2.0 * kPi * u(rng), s = std::sqrt(1.0 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
}

/// Near the mirror direction of wi (inside the lobes), kept above the horizon.
dvec3 nearMirror(std::mt19937_64& rng, const dvec3& wi) {
    std::normal_distribution<double> n(0.0, 0.15);
    dvec3 w = glm::normalize(dvec3(-wi.x, -wi.y, wi.z) + dvec3(n(rng), n(rng), n(rng)));
    w.z = std::max(w.z, 0.01);
    return glm::normalize(w);
}

}  // namespace

TEST_CASE("brdf::evaluate is reciprocal within 1e-9 for every model and term combination") {
    std::mt19937_64 rng(7);
    double worst = 0.0;
    int combos = 0, nonzero = 0;
    for (const brdf::Params& p : test::allCombinations()) {
        ++combos;
        for (int i = 0; i < 200; ++i) {
            const dvec3 wi = randomDirection(rng), wo = i % 2 ? randomDirection(rng) : nearMirror(rng, wi);
            const dvec3 a = brdf::evaluate(p, wi, wo), b = brdf::evaluate(p, wo, wi);
            for (int c = 0; c < 3; ++c) {
                const double scale = std::max(std::abs(a[c]), std::abs(b[c]));
                if (scale == 0.0) continue;
                ++nonzero;
                const double rel = std::abs(a[c] - b[c]) / scale;
                worst = std::max(worst, rel);
                if (rel > 1e-9) {
                    CAPTURE(p);
                    CAPTURE(rel);
                    CHECK(rel <= 1e-9);
                }
            }
        }
    }
    MESSAGE(combos << " combinations, " << nonzero << " non-zero values: worst relative reciprocity error " << worst);
    CHECK(combos == 10 * 5 * 5 * 3);
    CHECK(worst <= 1e-9);
}

TEST_CASE("brdf::evaluate the anisotropic path with ax = ay is the isotropic BRDF") {
    std::mt19937_64 rng(11);
    for (brdf::Model m : {brdf::Model::Beckmann, brdf::Model::GGX})
        for (brdf::Geometry g : {brdf::Geometry::Implicit, brdf::Geometry::SmithSeparable, brdf::Geometry::Smith}) {
            brdf::Params iso;
            iso.model = m;
            iso.geometry = g;
            iso.roughness = 0.25;
            brdf::Params aniso = iso;
            aniso.roughnessY = 0.25;
            aniso.tangentAngleDeg = -71.0;
            for (int i = 0; i < 500; ++i) {
                const dvec3 wi = randomDirection(rng), wo = nearMirror(rng, wi);
                const double a = brdf::evaluate(iso, wi, wo).x, b = brdf::evaluate(aniso, wi, wo).x;
                CHECK_NEAR(a, b, 1e-10 * a);
            }
        }
}

TEST_CASE("brdf::evaluate diffuse + specular is the sum of the parts") {
    brdf::Params p;
    p.model = brdf::Model::GGX;
    p.diffuse = brdf::Diffuse::Lambert;
    p.albedo = {0.2, 0.4, 0.6};
    const dvec3 wi = sphericalDirectionDeg(30, 0), wo = sphericalDirectionDeg(40, 170);
    const dvec3 sum = brdf::evaluateSpecular(p, wi, wo) + p.albedo * kInvPi;
    CHECK(glm::length(brdf::evaluate(p, wi, wo) - sum) < 1e-15);
    p.model = brdf::Model::None;
    CHECK(glm::length(brdf::evaluate(p, wi, wo) - p.albedo * kInvPi) < 1e-15);
}
