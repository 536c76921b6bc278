// The NDFs are normalized: int D(h) (n.h) dw_h = 1 over the hemisphere, within 1e-3 for roughness
// 0.02 .. 1 and exponents 1 .. 1e4, integrated in double by an adaptive quadrature in theta_h.

#include "brdf/integrate.hpp"
#include "brdf/ndf.hpp"
#include "brdf/quadrature.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/brdf/params.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace hilite;
using brdf::Model;

namespace {

const double kRoughness[] = {0.02, 0.05, 0.1, 0.2, 0.5, 1.0};
const double kExponents[] = {1.0, 10.0, 100.0, 1e3, 1e4};

/// int D(h) (n.h) dw over the hemisphere: theta_h adaptive (tolerance 1e-9), phi_h by the periodic
/// trapezoid rule (1 point for an isotropic D, 256 for an anisotropic one).
double normalization(const brdf::Params& p) {
    const int nPhi = p.anisotropic() ? 256 : 1;
    const double width = brdf::lobeWidth(p);
    double sum = 0.0;
    for (int j = 0; j < nPhi; ++j) {
        const double phi = 2.0 * kPi * j / nPhi;
        sum += test::adaptiveGraded(
            [&](double t) {
                const dvec3 h = sphericalDirection(t, phi);
                return brdf::distribution(p, h) * h.z * std::sin(t);
            },
            0.5 * kPi, width, 1e-9);
    }
    return sum * 2.0 * kPi / nPhi;
}

std::string label(const brdf::Params& p) {
    std::string s = brdf::toString(p.model);
    return p.anisotropic() ? s + "-aniso" : s;
}

}  // namespace

TEST_CASE("brdf::D_* normalization: int D (n.h) dw = 1 within 1e-3") {
    std::map<std::string, double> worst;
    auto check = [&](const brdf::Params& p) {
        const double I = normalization(p);
        CAPTURE(p);
        CHECK_NEAR(I, 1.0, 1e-3);
        worst[label(p)] = std::max(worst[label(p)], std::abs(I - 1.0));
        // The library's own integral (graded Gauss-Legendre, used by `hilite brdf normalization`) agrees.
        CHECK_NEAR(brdf::ndfIntegral(p), I, 1e-6);
    };
    SUBCASE("exponents 1 .. 1e4 (blinn)") {
        for (double n : kExponents) {
            brdf::Params p;
            p.model = Model::Blinn;
            p.exponent = n;
            check(p);
        }
    }
    SUBCASE("roughness 0.02 .. 1 (gaussian, beckmann, ggx; anisotropic beckmann, ggx)") {
        for (Model m : {Model::Gaussian, Model::Beckmann, Model::GGX})
            for (double r : kRoughness) {
                brdf::Params p;
                p.model = m;
                p.roughness = r;
                check(p);
                if (m == Model::Gaussian) continue;
                for (double ratio : {0.5, 3.0}) {  // alpha_y = alpha_x * ratio, within 0.02 .. 3
                    p.roughnessY = r * ratio;
                    p.tangentAngleDeg = 30.0;
                    check(p);
                }
            }
    }
    for (const auto& [name, err] : worst) MESSAGE(name << ": worst |int D (n.h) dw - 1| = " << err);
}

TEST_CASE("brdf::gaussianNormalization") {
    SUBCASE("tends to 1 / (pi m^2 (1 - 2 m^2 / 3)) as m -> 0") {
        for (double m : {0.005, 0.01, 0.02}) {
            const double asymptotic = 1.0 / (kPi * m * m * (1.0 - 2.0 * m * m / 3.0));
            CAPTURE(m);
            CHECK_NEAR(brdf::gaussianNormalization(m) / asymptotic, 1.0, 1e-6);
        }
    }
    SUBCASE("is cached: the same value on every call") {
        const double a = brdf::gaussianNormalization(0.3), b = brdf::gaussianNormalization(0.7);
        CHECK(brdf::gaussianNormalization(0.3) == a);
        CHECK(brdf::gaussianNormalization(0.7) == b);
    }
}

TEST_CASE("brdf::D_*Aniso with ax = ay equal the isotropic NDFs, for any tangent angle") {
    for (Model m : {Model::Beckmann, Model::GGX})
        for (double r : {0.05, 0.3}) {
            brdf::Params iso, aniso;
            iso.model = aniso.model = m;
            iso.roughness = aniso.roughness = r;
            aniso.roughnessY = r;
            aniso.tangentAngleDeg = 37.0;
            for (double t = 0.0; t < 89.0; t += 7.3)
                for (double phi = 0.0; phi < 360.0; phi += 41.0) {
                    const dvec3 h = sphericalDirectionDeg(t, phi);
                    const double a = brdf::distribution(iso, h), b = brdf::distribution(aniso, h);
                    CHECK_NEAR(a, b, 1e-12 * a);
                }
        }
}

TEST_CASE("brdf::D_*Aniso stretch along the tangent axis with the larger alpha") {
    for (Model m : {Model::Beckmann, Model::GGX}) {
        brdf::Params p;
        p.model = m;
        p.roughness = 0.4;  // alpha_x
        p.roughnessY = 0.1;
        p.tangentAngleDeg = 90.0;  // the alpha_x axis along +y
        const dvec3 alongY = sphericalDirectionDeg(20.0, 90.0), alongX = sphericalDirectionDeg(20.0, 0.0);
        CHECK(brdf::distribution(p, alongY) > 10.0 * brdf::distribution(p, alongX));
    }
}
