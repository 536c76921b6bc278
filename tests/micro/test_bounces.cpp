// Light per bounce order: the tracer on the explicit height field and the random walk on Smith's
// microsurface (micro/bounces.hpp), each against what must hold whatever the surface: every path leaves
// (F = 1), the walk's first order is the analytic single scattering, repeated Fresnel saturates gold.

#include "brdf/integrate.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/colour.hpp"
#include "hilite/core/error.hpp"
#include "hilite/micro/bounces.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <stdexcept>

using namespace hilite;

namespace {

/// A small field: 256^2 texels, 16 bumps a tile (16 texels a bump, as the renders' 1024 / 64).
micro::BumpField smallField(double m, uint64_t seed = 1) {
    micro::BumpSpec s;
    s.kind = micro::BumpKind::Beckmann;
    s.roughness = m;
    s.seed = seed;
    s.texels = 256;
    s.bumpsPerTile = 16;
    return micro::makeBumpField(s);
}

brdf::Params beckmann(double m, brdf::Fresnel fresnel = brdf::Fresnel::None) {
    brdf::Params p;
    p.model = brdf::Model::Beckmann;
    p.roughness = m;
    p.geometry = brdf::Geometry::Smith;
    p.fresnel = fresnel;
    return p;
}

micro::BounceOptions options(long paths) {
    micro::BounceOptions o;
    o.paths = paths;
    return o;
}

double sum(const std::vector<micro::Estimate>& v) {
    double s = 0;
    for (const auto& e : v) s += e.value;
    return s;
}

}  // namespace

TEST_CASE("micro::traceBounces") {
    const auto white = brdf::reflectanceChannels(beckmann(0.6));
    SUBCASE("F = 1: every path leaves, the orders sum to 1, no facet is hit from behind") {
        const auto f = smallField(1.0);
        for (double theta : {0.0, 60.0, 85.0}) {
            CAPTURE(theta);
            const auto t = micro::traceBounces(f, theta, white, options(4000));
            CHECK(t.stuck.value == 0.0);
            CHECK(t.backHits == 0);
            CHECK(sum(t.energy) == doctest::Approx(1.0).epsilon(1e-12));
            CHECK(t.reflectedY.value == doctest::Approx(1.0).epsilon(1e-12));
            CHECK(t.multiple.value == doctest::Approx(1.0 - t.energy[0].value).epsilon(1e-12));
        }
    }
    SUBCASE("normal incidence: the first order is Smith's single scattering, within the field's own spread") {
        // Seeds 1-6 of this small field put the first order 0.0012-0.0102 above E(mu) = 0.8561 (m 0.6, 20000
        // paths; docs/bounces.md): 0.02 is twice the largest, and a tracer that lost the consistency of its
        // normals (or its bisection) moves it by more.
        const double E = brdf::albedo(beckmann(0.6), 0.0).x;
        const auto t = micro::traceBounces(smallField(0.6), 0.0, white, options(20000));
        CHECK_NEAR(t.energy[0].value, E, 0.02);
        CHECK(t.energy[0].error < 0.004);
    }
    SUBCASE("the same seed gives the same tally; another seed another") {
        const auto f = smallField(0.6);
        auto o = options(2000);
        const auto a = micro::traceBounces(f, 45.0, white, o), b = micro::traceBounces(f, 45.0, white, o);
        CHECK(a.energy[1].value == b.energy[1].value);
        o.seed = 2;
        CHECK(micro::traceBounces(f, 45.0, white, o).energy[1].value != a.energy[1].value);
    }
    SUBCASE("a GGX field is a normal map, not a height field: refused") {
        micro::BumpSpec s;
        s.kind = micro::BumpKind::GGX;
        s.texels = 64;
        s.bumpsPerTile = 8;
        CHECK_THROWS_AS(micro::traceBounces(micro::makeBumpField(s), 0.0, white, options(100)), InputError);
    }
    SUBCASE("fewer paths than batches, or one batch: InputError, as every public entry point") {
        const auto f = smallField(0.6);
        micro::BounceOptions o = options(100);
        o.batches = 1;
        CHECK_THROWS_AS(micro::traceBounces(f, 0.0, white, o), InputError);
        CHECK_THROWS_AS(micro::walkSmithBounces(0.3, 0.0, white, o), InputError);
        o.batches = 16, o.paths = 8;
        CHECK_THROWS_AS(micro::walkSmithBounces(0.3, 0.0, white, o), InputError);
    }
}

TEST_CASE("micro::hermiteSlopeRatio") {
    // The bicubic surface follows the Gaussian field between the texel centres; the bilinear one it is normalized
    // on is smoother (its slopes' mean square is below the texel centres'), so the ratio is above 1, by little.
    const double r = micro::hermiteSlopeRatio(smallField(0.3));
    CHECK(r > 1.0);
    CHECK(r < 1.05);
}

TEST_CASE("micro::walkSmithBounces") {
    const auto white = brdf::reflectanceChannels(beckmann(0.3));
    SUBCASE("the first order is the analytic single scattering with height-correlated G2") {
        // brdf::albedo uses Beckmann's rational Lambda (< 0.35% in G1): 0.003 covers it beside 4 standard errors.
        for (double m : {0.3, 1.0})
            for (double theta : {0.0, 45.0, 75.0}) {
                CAPTURE(m);
                CAPTURE(theta);
                const auto w = micro::walkSmithBounces(m, theta, white, options(40000));
                const double E = brdf::albedo(beckmann(m), theta).x;
                CHECK_NEAR(w.energy[0].value, E, 4.0 * w.energy[0].error + 0.003);
                CHECK(w.stuck.value == 0.0);
                CHECK(sum(w.energy) == doctest::Approx(1.0).epsilon(1e-12));
            }
    }
}

TEST_CASE("micro bounces: gold's second bounce is more saturated than its first") {
    brdf::Params p = beckmann(0.6, brdf::Fresnel::Spectral);
    p.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kGpuStepNm);
    const auto ch = brdf::reflectanceChannels(p);
    const auto t = micro::traceBounces(smallField(0.6), 0.0, ch, options(8000));
    const auto w = micro::walkSmithBounces(0.6, 0.0, ch, options(8000));
    for (const auto* tally : {&t, &w}) {
        const auto& c = tally->chroma;
        CHECK(c[1].value - c[0].value > 5.0 * std::hypot(c[0].error, c[1].error));
        // Each bounce multiplies by F < 1 in every channel: the light with F is less than without.
        CHECK(tally->reflectedY.value < tally->total.value);
    }
}

TEST_CASE("micro bounces: a dielectric reflects little at normal incidence, and its colour stays white") {
    brdf::Params p = beckmann(0.3, brdf::Fresnel::Dielectric);
    p.eta = dvec3(1.5);
    const auto ch = brdf::reflectanceChannels(p);
    const auto t = micro::traceBounces(smallField(0.3), 0.0, ch, options(4000));
    // F(0) = ((1.5 - 1) / (1.5 + 1))^2 = 0.04; the tilted facets reflect a little more.
    CHECK(t.reflectedY.value > 0.04);
    CHECK(t.reflectedY.value < 0.045);
    CHECK(t.chroma[0].value < 1e-6);
}
