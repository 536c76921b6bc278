// Fresnel terms: exact dielectric values (eta = 1.5: 0.04 at normal incidence, 0.0502399 at 45 degrees,
// Rp = 0 at Brewster's angle), total internal reflection, F -> 1 at grazing for every material, the
// conductor form against pbrt-v4's complex arithmetic, and Schlick's error against the exact curve.

#include "brdf/materials.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/brdf/terms.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <complex>
#include <random>

using namespace hilite;

namespace {

/// pbrt-v4's FrComplex (src/pbrt/util/scattering.h), the reference for the real-arithmetic conductor form.
double frComplex(double cosTheta_i, std::complex<double> eta) {
    using C = std::complex<double>;
    const double sin2Theta_i = 1.0 - cosTheta_i * cosTheta_i;
    const C sin2Theta_t = sin2Theta_i / (eta * eta);
    const C cosTheta_t = std::sqrt(C(1.0) - sin2Theta_t);
    const C rParl = (eta * cosTheta_i - cosTheta_t) / (eta * cosTheta_i + cosTheta_t);
    const C rPerp = (cosTheta_i - eta * cosTheta_t) / (cosTheta_i + eta * cosTheta_t);
    return 0.5 * (std::norm(rParl) + std::norm(rPerp));
}

double cosDeg(double deg) {
    double c, s;
    cosSinDeg(deg, c, s);
    return c;
}

}  // namespace

TEST_CASE("brdf::F_Dielectric") {
    SUBCASE("eta = 1.5: 0.04 at normal incidence, 0.0502399 at 45 degrees") {
        CHECK(brdf::F_Dielectric(1.0, 1.5) == doctest::Approx(0.04).epsilon(1e-12));
        CHECK_NEAR(brdf::F_Dielectric(cosDeg(45.0), 1.5), 0.0502399, 5e-8);
    }
    SUBCASE("Rp vanishes at Brewster's angle atan(1.5) = 56.31 degrees, Rs does not") {
        const double brewster = rad2deg(std::atan(1.5));
        CHECK(brewster == doctest::Approx(56.31).epsilon(1e-4));
        const dvec2 sp = brdf::F_DielectricSP(std::cos(std::atan(1.5)), 1.5);
        CHECK(sp.y < 1e-20);
        CHECK(sp.x > 0.1);
        CHECK(brdf::F_DielectricSP(cosDeg(56.31), 1.5).y < 1e-9);  // at the rounded angle too
        CHECK(brdf::F_DielectricSP(cosDeg(50.0), 1.5).y > 1e-4);
        CHECK(brdf::F_DielectricSP(cosDeg(62.0), 1.5).y > 1e-4);
    }
    SUBCASE("eta < 1: the same F(0), total internal reflection beyond the critical angle") {
        const double eta = 1.0 / 1.5, critical = rad2deg(std::asin(eta));  // 41.81 degrees
        CHECK(brdf::F_Dielectric(1.0, eta) == doctest::Approx(0.04).epsilon(1e-12));
        CHECK(brdf::F_Dielectric(cosDeg(critical + 0.01), eta) == 1.0);
        CHECK(brdf::F_Dielectric(cosDeg(60.0), eta) == 1.0);
        CHECK(brdf::F_Dielectric(cosDeg(critical - 1.0), eta) < 0.5);
    }
}

TEST_CASE("brdf::F_Conductor equals pbrt-v4's complex FrComplex, with k = 0 it is F_Dielectric") {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const double c = u01(rng), eta = 0.03 + 4.0 * u01(rng), k = 10.0 * u01(rng);
        worst = std::max(worst, std::abs(brdf::F_Conductor(c, eta, k) - frComplex(c, {eta, k})));
    }
    MESSAGE("max |F_Conductor - FrComplex| = " << worst);
    CHECK(worst < 1e-12);
    for (double eta : {1.333, 1.5, 2.417, 1.0 / 1.5})
        for (double t = 0.0; t <= 90.0; t += 0.5)
            CHECK_NEAR(brdf::F_Conductor(cosDeg(t), eta, 0.0), brdf::F_Dielectric(cosDeg(t), eta), 1e-12);
}

TEST_CASE("brdf::F_Schlick") {
    SUBCASE("F(0) = F0 and F(90) = 1") {
        const dvec3 f0(0.9, 0.6, 0.3);
        CHECK(glm::length(brdf::F_Schlick(f0, 1.0) - f0) == 0.0);
        CHECK(glm::length(brdf::F_Schlick(f0, 0.0) - dvec3(1.0)) == 0.0);
    }
    SUBCASE("against the exact dielectric: max error < 0.07 for water and glass, above 80 degrees") {
        for (const char* name : {"water", "glass"}) {
            const brdf::Material* m = brdf::findMaterial(name);
            REQUIRE(m != nullptr);
            double worst = 0.0, at = 0.0;
            for (int i = 0; i <= 9000; ++i) {
                const double t = 0.01 * i, c = cosDeg(t);
                const double err = std::abs(brdf::F_Schlick(m->f0, c).x - brdf::F_Dielectric(c, m->eta.x));
                if (err > worst) worst = err, at = t;
            }
            MESSAGE(std::string(name) << " (eta " << m->eta.x << "): Schlick max error " << worst << " at " << at
                                      << " degrees");
            CAPTURE(name);
            CHECK(worst < 0.07);
            CHECK(at > 80.0);
        }
    }
}

TEST_CASE("brdf::fresnel F -> 1 at grazing for every material preset") {
    for (const brdf::Material& m : brdf::materials()) {
        brdf::Params p;
        p.fresnel = m.fresnel;
        p.eta = m.eta;
        p.k = m.k;
        p.f0 = m.f0;
        if (m.fresnel == brdf::Fresnel::Spectral)
            p.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, m.name, brdf::kFullStepNm);
        CAPTURE(m.name);
        const dvec3 grazing = brdf::fresnel(p, 0.0), near = brdf::fresnel(p, cosDeg(89.9)),
                    at80 = brdf::fresnel(p, cosDeg(80.0));
        for (int c = 0; c < 3; ++c) {
            CHECK_NEAR(grazing[c], 1.0, 1e-12);
            CHECK(near[c] > at80[c]);
            CHECK(near[c] > 0.97);
        }
    }
}

TEST_CASE("brdf::materials presets") {
    CHECK(brdf::findMaterial("glass")->f0.x == doctest::Approx(0.04));
    CHECK(brdf::findMaterial("water")->f0.x == doctest::Approx(0.0204).epsilon(1e-2));
    CHECK(brdf::findMaterial("diamond")->f0.x == doctest::Approx(0.172).epsilon(1e-2));
    const dvec3 silver = brdf::findMaterial("silver")->f0, aluminium = brdf::findMaterial("aluminium")->f0;
    CHECK(silver.x > 0.9);
    CHECK(aluminium.y == doctest::Approx(0.92).epsilon(1e-2));
    CHECK(brdf::findMaterial("unobtainium") == nullptr);
    for (const auto& name : {"water", "glass", "plastic", "diamond", "copper", "gold", "silver", "aluminium", "iron"})
        CHECK(brdf::findMaterial(name) != nullptr);
}
