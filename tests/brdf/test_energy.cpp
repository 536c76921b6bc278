// The energy terms (brdf/energy.hpp) against what they promise, integrated by brdf::albedo:
// - multiple scattering (Kulla & Conty 2017): the white furnace, albedo 1 with F = 1, for GGX alpha 0.1-1 at
//   theta_i 0-85 deg (and Beckmann), where single scattering alone loses up to 69% (1 - ln 2 kept at alpha 1,
//   normal incidence: a closed form the quadrature meets independently);
// - the coupled diffuse: specular + diffuse albedo <= 1 for a GGX dielectric over roughness x angle, where an
//   uncoupled Lambert exceeds 1; and both terms' refusals.

#include "brdf/energy.hpp"
#include "brdf/integrate.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

using namespace hilite;
using brdf::Diffuse;
using brdf::Fresnel;
using brdf::Geometry;
using brdf::Model;
using brdf::Multiscatter;

namespace {

brdf::Params smith(Model m, double roughness) {
    brdf::Params p;
    p.model = m;
    p.roughness = roughness;
    p.geometry = Geometry::Smith;
    return p;
}

brdf::Params withTables(brdf::Params p) {
    p.energy = brdf::energyTables(p);
    return p;
}

}  // namespace

TEST_CASE("brdf::energyTables white furnace: F = 1 with kulla-conty reflects 1 (GGX alpha 0.1-1, 0-85 deg)") {
    double worst = 0.0, worstTable = 0.0, largestLoss = 0.0;
    for (int a = 1; a <= 10; ++a) {
        const double alpha = 0.1 * a;
        brdf::Params single = smith(Model::GGX, alpha);
        brdf::Params ms = single;
        ms.multiscatter = Multiscatter::KullaConty;
        ms = withTables(ms);
        worstTable = std::max(worstTable, ms.energy->eError);
        for (double theta = 0.0; theta <= 85.0; theta += 5.0) {
            const double loss = 1.0 - brdf::albedo(single, theta).x;
            const dvec3 rho = brdf::albedo(ms, theta);
            CAPTURE(alpha);
            CAPTURE(theta);
            CHECK(rho.x == doctest::Approx(rho.z));
            CHECK_NEAR(rho.x, 1.0, 1e-3);  // the issue asks 1%; the table's interpolation error is what is left
            worst = std::max(worst, std::abs(rho.x - 1.0));
            largestLoss = std::max(largestLoss, loss);
        }
    }
    CHECK(worstTable < 1e-3);
    CHECK(largestLoss > 0.6);  // the furnace test fails without the term
    MESSAGE("white furnace, GGX alpha 0.1-1, 0-85 deg: worst |albedo - 1| "
            << worst << "; single scattering loses up to " << largestLoss << "; worst table interpolation error "
            << worstTable);
}

TEST_CASE("brdf::albedo single-scattering GGX alpha 1 with Smith keeps 1 - ln 2 at normal incidence") {
    // D = 1 / pi and Lambda(wo) = (sqrt(1 + tan^2) - 1) / 2 at alpha 1: rho(0) = 1 - ln 2 in closed form.
    CHECK(brdf::albedo(smith(Model::GGX, 1.0), 0.0).x == doctest::Approx(1.0 - std::log(2.0)).epsilon(1e-9));
}

TEST_CASE("brdf::energyTables white furnace for Beckmann and separable Smith too") {
    for (Geometry g : {Geometry::Smith, Geometry::SmithSeparable})
        for (double m : {0.2, 0.7}) {
            brdf::Params p = smith(Model::Beckmann, m);
            p.geometry = g;
            p.multiscatter = Multiscatter::KullaConty;
            p = withTables(p);
            for (double theta : {0.0, 45.0, 80.0}) {
                CAPTURE(m);
                CAPTURE(theta);
                CHECK_NEAR(brdf::albedo(p, theta).x, 1.0, 1e-3);
            }
        }
}

TEST_CASE("brdf::energyTables kulla-conty with a conductor: E_F + (1 - E) F_ms, coloured, below 1") {
    brdf::Params p = smith(Model::GGX, 0.6);
    p.fresnel = Fresnel::Conductor;
    p.eta = {0.143, 0.374, 1.442};  // a yellow conductor (gold-like: red reflects most, blue least)
    p.k = {3.983, 2.385, 1.603};
    brdf::Params ms = p;
    ms.multiscatter = Multiscatter::KullaConty;
    ms = withTables(ms);
    const brdf::EnergyTables& t = *ms.energy;
    for (int c = 0; c < 3; ++c) {
        CHECK(t.Fms[c] == doctest::Approx(t.Favg[c] * t.Favg[c] * t.Eavg / (1.0 - t.Favg[c] * (1.0 - t.Eavg))));
        CHECK(t.Fms[c] < t.Favg[c]);  // each further bounce reflects F_avg < 1 again
    }
    for (double theta : {0.0, 40.0, 80.0}) {
        const dvec3 single = brdf::albedo(p, theta), total = brdf::albedo(ms, theta);
        const double e = brdf::energyE(std::cos(deg2rad(theta)), t);
        for (int c = 0; c < 3; ++c) {
            CAPTURE(theta);
            CAPTURE(c);
            CHECK(total[c] > single[c]);
            CHECK(total[c] < 1.0);
            CHECK(total[c] == doctest::Approx(single[c] + (1.0 - e) * t.Fms[c]).epsilon(1e-9));
        }
    }
    // The compensation is more saturated than the single bounce: blue gains least (F_ms ~ F_avg^2).
    CHECK(t.Fms.z / t.Fms.x < t.Favg.z / t.Favg.x);
}

TEST_CASE("brdf::energyTables coupled diffuse: GGX dielectric specular + diffuse albedo <= 1 (roughness x angle)") {
    double worstUncoupled = 0.0, worstCoupled = 0.0;
    for (double alpha : {0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0})
        for (Multiscatter ms : {Multiscatter::None, Multiscatter::KullaConty}) {
            brdf::Params p = smith(Model::GGX, alpha);
            p.fresnel = Fresnel::Dielectric;
            p.eta = dvec3(1.5);
            p.multiscatter = ms;
            p.albedo = dvec3(1.0);  // the strictest body: all it gets, it returns
            brdf::Params lambert = p;
            lambert.diffuse = Diffuse::Lambert;
            p.diffuse = Diffuse::Coupled;
            p = withTables(p);
            lambert.energy = p.energy;
            for (double theta = 0.0; theta <= 85.0; theta += 5.0) {
                const double coupled = brdf::albedo(p, theta).x, uncoupled = brdf::albedo(lambert, theta).x;
                const double es = brdf::energyEs(std::cos(deg2rad(theta)), *p.energy).x;
                CAPTURE(alpha);
                CAPTURE(theta);
                CHECK(coupled <= 1.0 + 1e-9);
                // rho (1 - E_s) is what the body returns: the sum is E_s + 1 - E_s less the table's raise.
                CHECK(coupled > 1.0 - 3.0 * p.energy->esError - 1e-9);
                CHECK(brdf::albedo(p, theta).x - brdf::albedo(lambert, theta).x == doctest::Approx(-es).epsilon(1e-6));
                worstCoupled = std::max(worstCoupled, coupled);
                worstUncoupled = std::max(worstUncoupled, uncoupled);
            }
        }
    CHECK(worstUncoupled > 1.05);  // uncoupled, specular + Lambert rho = 1 exceeds 1 (the problem the term solves)
    MESSAGE("GGX dielectric eta 1.5 + diffuse rho 1, alpha 0.05-1 x 0-85 deg: largest albedo coupled "
            << worstCoupled << ", lambert " << worstUncoupled);
}

TEST_CASE("brdf::energyRefusal names what the energy terms cannot take") {
    brdf::Params p = smith(Model::GGX, 0.3);
    p.multiscatter = Multiscatter::KullaConty;
    CHECK(brdf::energyRefusal(p).empty());
    brdf::Params implicit = p;
    implicit.geometry = Geometry::Implicit;
    CHECK(brdf::energyRefusal(implicit).find("smith") != std::string::npos);
    brdf::Params aniso = p;
    aniso.roughnessY = 0.1;
    CHECK(brdf::energyRefusal(aniso).find("isotropic") != std::string::npos);
    brdf::Params phong = p;
    phong.model = Model::Phong;
    CHECK(brdf::energyRefusal(phong).find("microfacet") != std::string::npos);
    brdf::Params mirror = p;
    mirror.roughness = 0.0;
    CHECK(!brdf::energyRefusal(mirror).empty());
    CHECK_THROWS_AS(brdf::energyTables(implicit), std::invalid_argument);
    // The coupled diffuse under a lobe that gains energy (G = 1 at grazing): refused, not a negative body.
    brdf::Params gains = smith(Model::GGX, 0.5);
    gains.geometry = Geometry::None;
    gains.diffuse = Diffuse::Coupled;
    CHECK_THROWS_AS(brdf::energyTables(gains), std::invalid_argument);
}

TEST_CASE("brdf::energyE the table's lookup: entries exact, linear in sqrt(mu) between") {
    brdf::Params p = smith(Model::GGX, 0.5);
    p.multiscatter = Multiscatter::KullaConty;
    p = withTables(p);
    const brdf::EnergyTables& t = *p.energy;
    REQUIRE(t.E.size() == size_t(brdf::kEnergyTableSize));
    for (int i : {0, 1, 17, brdf::kEnergyTableSize - 1})
        CHECK(brdf::energyE(brdf::energyTableMu(i), t) == doctest::Approx(t.E[size_t(i)]).epsilon(1e-12));
    const double u = 0.5 * (std::sqrt(brdf::energyTableMu(20)) + std::sqrt(brdf::energyTableMu(21)));
    CHECK(brdf::energyE(u * u, t) == doctest::Approx(0.5 * (t.E[20] + t.E[21])).epsilon(1e-12));
    CHECK(brdf::energyE(-1.0, t) == t.E.front());
    CHECK(brdf::energyE(2.0, t) == t.E.back());
    // E_avg is the interpolant's cosine average; single scattering at alpha 0.5 keeps most but not all.
    CHECK(t.Eavg > 0.7);
    CHECK(t.Eavg < 0.95);
}

TEST_CASE("brdf::evaluate with kulla-conty and a NaN direction gives NaN, not an index from NaN") {
    // fuzz_entry_points found it (UBSan: "nan is outside the range of representable values of type 'unsigned
    // long'" in the table lookup): the library takes any direction a caller passes.
    brdf::Params p = smith(Model::GGX, 0.3);
    p.multiscatter = Multiscatter::KullaConty;
    p = withTables(p);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const dvec3 f = brdf::evaluate(p, dvec3(0, 0, 1), dvec3(nan, 0, nan));
    CHECK(std::isnan(f.x));
    CHECK(std::isnan(brdf::energyE(nan, *p.energy)));
    CHECK(std::isfinite(brdf::energyE(0.5, *p.energy)));
}
