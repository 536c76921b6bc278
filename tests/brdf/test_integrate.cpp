// Directional-hemispherical reflectance (albedo): at most 1 + 1e-3 at every angle for every
// energy-conserving combination; Lambert's albedo is rho; the combinations that are not
// energy-conserving exceed 1 somewhere (classic Phong: its closed form 2 pi / (n + 2) at normal incidence).
// The library's integrator is checked against an independent brute-force sum first.

#include "brdf/integrate.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <iomanip>

using namespace hilite;
using brdf::Geometry;
using brdf::Model;

namespace {

const double kThetas[] = {0.0, 30.0, 60.0, 80.0, 89.0};

/// The largest albedo channel over kThetas (light azimuth 10 degrees, off the tangent axes).
double maxAlbedo(const brdf::Params& p, double* at = nullptr) {
    double worst = 0.0;
    for (double t : kThetas) {
        const dvec3 a = brdf::albedo(p, t, 10.0);
        const double m = std::max({a.x, a.y, a.z});
        if (m > worst) {
            worst = m;
            if (at) *at = t;
        }
    }
    return worst;
}

brdf::Params specular(Model m, Geometry g, double param, bool aniso = false) {
    brdf::Params p;
    p.model = m;
    p.geometry = g;
    (brdf::usesExponent(m) ? p.exponent : p.roughness) = param;
    if (aniso) {
        p.roughnessY = 0.25 * param + 0.01;
        p.tangentAngleDeg = 30.0;
    }
    return p;
}

}  // namespace

TEST_CASE("brdf::albedo agrees with a brute-force sum over wo") {
    for (const brdf::Params& p :
         {specular(Model::GGX, Geometry::Smith, 0.3), specular(Model::Phong, Geometry::Implicit, 20),
          specular(Model::Beckmann, Geometry::CookTorrance, 0.5, true)})
        for (double t : {0.0, 50.0, 85.0}) {
            const dvec3 wi = sphericalDirectionDeg(t, 10.0);
            const int n = 600;
            double sum = 0.0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < 2 * n; ++j) {
                    const double th = (i + 0.5) / n * 0.5 * kPi, ph = (j + 0.5) / (2 * n) * 2.0 * kPi;
                    const dvec3 wo = sphericalDirection(th, ph);
                    sum += brdf::evaluate(p, wi, wo).x * wo.z * std::sin(th);
                }
            sum *= (0.5 * kPi / n) * (kPi / n);
            CAPTURE(p);
            CAPTURE(t);
            CHECK(brdf::albedo(p, t, 10.0).x == doctest::Approx(sum).epsilon(2e-3));
        }
}

TEST_CASE("brdf::albedo Lambert = rho within 1e-3 at every angle") {
    brdf::Params p;
    p.model = Model::None;
    p.diffuse = brdf::Diffuse::Lambert;
    p.albedo = {0.25, 0.5, 1.0};
    for (double t : {0.0, 15.0, 45.0, 75.0, 89.0, 89.9}) {
        const dvec3 a = brdf::albedo(p, t, 33.0);
        for (int c = 0; c < 3; ++c) CHECK_NEAR(a[c], p.albedo[c], 1e-3);
    }
}

TEST_CASE("brdf::albedo normalized Phong reflects all at normal incidence") {
    for (double n : {1.0, 10.0, 100.0, 1e3, 1e4}) {
        CAPTURE(n);
        CHECK(brdf::albedo(specular(Model::Phong, Geometry::Implicit, n), 0.0).x == doctest::Approx(1.0).epsilon(1e-6));
    }
}

TEST_CASE("brdf::albedo the retroreflective lobe reflects all at normal incidence, less where the horizon cuts it") {
    for (double n : {1.0, 10.0, 100.0, 1e3, 1e4}) {
        CAPTURE(n);
        const brdf::Params p = specular(Model::Retro, Geometry::Implicit, n);
        CHECK(brdf::albedo(p, 0.0).x == doctest::Approx(1.0).epsilon(1e-6));
        // About wi at 60 deg the lobe is cut by the horizon and weighted by cos(theta_o) < cos of its axis...
        CHECK(brdf::albedo(p, 60.0).x < 1.0);
        // ... and equals the Phong lobe's there (both are the same lobe about an axis at 30 deg elevation).
        CHECK(brdf::albedo(p, 60.0).x ==
              doctest::Approx(brdf::albedo(specular(Model::Phong, Geometry::Implicit, n), 60.0).x).epsilon(1e-9));
    }
}

TEST_CASE("brdf::albedo <= 1 + 1e-3 for every energy-conserving combination") {
    auto check = [&](const brdf::Params& p) {
        double at = 0.0;
        const double a = maxAlbedo(p, &at);
        CAPTURE(p);
        CAPTURE(at);
        CHECK(a <= 1.0 + 1e-3);
        return a;
    };
    double worst = 0.0;
    SUBCASE("normalized Phong, exponents 1 .. 1e4") {
        for (double n : {1.0, 10.0, 100.0, 1e4})
            worst = std::max(worst, check(specular(Model::Phong, Geometry::Implicit, n)));
    }
    SUBCASE("microfacet NDFs with the implicit and Cook-Torrance G") {
        for (Geometry g : {Geometry::Implicit, Geometry::CookTorrance}) {
            for (double n : {1.0, 10.0, 100.0, 1e4}) worst = std::max(worst, check(specular(Model::Blinn, g, n)));
            for (Model m : {Model::Gaussian, Model::Beckmann, Model::GGX})
                for (double r : {0.02, 0.1, 0.5, 1.0}) worst = std::max(worst, check(specular(m, g, r)));
        }
    }
    SUBCASE("Beckmann and GGX, isotropic and anisotropic, with Smith G (separable and correlated)") {
        for (Geometry g : {Geometry::SmithSeparable, Geometry::Smith})
            for (Model m : {Model::Beckmann, Model::GGX})
                for (double r : {0.02, 0.1, 0.5, 1.0})
                    for (bool aniso : {false, true}) worst = std::max(worst, check(specular(m, g, r, aniso)));
    }
    SUBCASE(
        "Blinn-Phong and Gaussian with Smith G in the narrow-lobe range of Beckmann's Lambda (n >= 100, m <= 0.1)") {
        for (Geometry g : {Geometry::SmithSeparable, Geometry::Smith}) {
            for (double n : {100.0, 1e4}) worst = std::max(worst, check(specular(Model::Blinn, g, n)));
            for (double r : {0.02, 0.1}) worst = std::max(worst, check(specular(Model::Gaussian, g, r)));
        }
    }
    SUBCASE("with a Fresnel term F <= 1 (schlick, dielectric, conductor, spectral copper)") {
        brdf::Params p = specular(Model::GGX, Geometry::Smith, 0.1);
        for (brdf::Fresnel f :
             {brdf::Fresnel::Schlick, brdf::Fresnel::Dielectric, brdf::Fresnel::Conductor, brdf::Fresnel::Spectral}) {
            p.fresnel = f;
            p.f0 = dvec3(0.95);
            p.eta = {0.2, 1.5, 0.7};
            p.k = {3.6, 0.0, 0.0};
            p.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, "copper", brdf::kFullStepNm);
            worst = std::max(worst, check(p));
        }
    }
    SUBCASE("Lambert, rho = 1") {
        brdf::Params p;
        p.model = Model::None;
        p.diffuse = brdf::Diffuse::Lambert;
        p.albedo = dvec3(1.0);
        worst = std::max(worst, check(p));
    }
    MESSAGE("largest albedo among these energy-conserving combinations: " << std::setprecision(9) << worst);
}

TEST_CASE("brdf::albedo of the combinations that are not energy-conserving exceeds 1 somewhere") {
    auto exceeds = [](const std::string& what, const brdf::Params& p) {
        double at = 0.0;
        const double a = maxAlbedo(p, &at);
        MESSAGE(what << ": max albedo " << a << " at theta_i = " << at);
        CAPTURE(what);
        CHECK(a > 1.0 + 1e-3);
    };
    // Classic Phong (k_s = 1) at normal incidence: the lobe about the normal, integral of cos^n cos = 2 pi / (n + 2)
    // (pi for n = 0, f = 1), which is also its largest albedo; n = 1000 is dim instead of bright.
    for (double n : {0.0, 1.0, 1000.0}) {
        const brdf::Params p = specular(Model::PhongClassic, Geometry::Implicit, n);
        CAPTURE(n);
        CHECK_NEAR(brdf::albedo(p, 0.0, 10.0).x, 2.0 * kPi / (n + 2.0), 1e-6 * 2.0 * kPi / (n + 2.0));
        CHECK_NEAR(maxAlbedo(p), 2.0 * kPi / (n + 2.0), 1e-6 * 2.0 * kPi / (n + 2.0));
    }
    exceeds("ggx alpha 1, geometry none (G = 1)", specular(Model::GGX, Geometry::None, 1.0));
    exceeds("beckmann m 0.1, geometry none", specular(Model::Beckmann, Geometry::None, 0.1));
    exceeds("blinn n = 1, smith (Beckmann's Lambda at m = sqrt(2/3))", specular(Model::Blinn, Geometry::Smith, 1.0));
    exceeds("blinn n = 10, smith", specular(Model::Blinn, Geometry::Smith, 10.0));
    exceeds("gaussian m = 0.7, smith (Beckmann's Lambda)", specular(Model::Gaussian, Geometry::Smith, 0.7));
    brdf::Params on;
    on.model = Model::None;
    on.diffuse = brdf::Diffuse::OrenNayar;
    on.albedo = dvec3(1.0);
    on.sigmaDeg = 10.0;
    exceeds("oren-nayar rho = 1, sigma = 10 (qualitative model)", on);
    brdf::Params sum = specular(Model::GGX, Geometry::Smith, 0.1);
    sum.diffuse = brdf::Diffuse::Lambert;
    sum.albedo = dvec3(1.0);
    exceeds("ggx + lambert rho = 1 (no coupling between the layers)", sum);
    brdf::Params gold = specular(Model::GGX, Geometry::Smith, 0.02);
    gold.fresnel = brdf::Fresnel::Spectral;
    gold.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kFullStepNm);
    exceeds("ggx + spectral gold (red outside the sRGB gamut, > 1 at normal incidence)", gold);
}
