// Explicit micro-geometry on the CPU: the realised slope distribution of the bump fields, and masking and
// shadowing traced against the height field beside Smith's G.

#include "hilite/micro/bump_field.hpp"
#include "micro/masking.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;

namespace {

micro::BumpSpec smallSpec(micro::BumpKind kind, double roughness, uint64_t seed = 1) {
    micro::BumpSpec s;
    s.kind = kind;
    s.roughness = roughness;
    s.seed = seed;
    s.texels = 256;
    s.bumpsPerTile = 16;
    return s;
}

}  // namespace

TEST_CASE("micro::makeBumpField") {
    SUBCASE("Beckmann: Gaussian slopes with mean |s|^2 = m^2, isotropic, following the Beckmann radial CDF") {
        const auto f = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.2));
        const auto st = micro::slopeStats(f);
        CHECK(std::hypot(st.rmsX, st.rmsY) == doctest::Approx(0.2).epsilon(1e-6));
        CHECK(st.rmsX / st.rmsY == doctest::Approx(1.0).epsilon(0.1));
        CHECK(st.ks < 0.03);  // 256 bumps only: the default 64^2-bump tile gives 0.0025
        for (double share : st.binShares) CHECK(share == doctest::Approx(0.125).epsilon(0.2));
    }
    SUBCASE("GGX: the remapped slopes follow the GGX radial CDF r^2 / (a^2 + r^2)") {
        const auto st = micro::slopeStats(micro::makeBumpField(smallSpec(micro::BumpKind::GGX, 0.1)));
        CHECK(st.ks < 0.03);
        CHECK(st.maxSlopeDeg > 60.0);  // GGX's long tail: steep facets exist
    }
    SUBCASE("seeded and reproducible") {
        const auto a = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.1, 7));
        const auto b = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.1, 7));
        const auto c = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.1, 8));
        CHECK(a.tex0 == b.tex0);
        CHECK(a.tex1 == b.tex1);
        CHECK(a.tex0 != c.tex0);
    }
    SUBCASE("the stored slope derivative J is that of the slopes: central differences at texel centres") {
        const auto f = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.1));
        const double h = 1.0 / f.n;
        double err2 = 0, ref2 = 0, herr2 = 0, href2 = 0;
        for (int k = 0; k < 200; ++k) {
            const double x = (37 * k % f.n + 0.5) * h, y = (91 * k % f.n + 0.5) * h;  // texel centres
            const auto c = f.sample(x, y);
            const double d = (f.sample(x + h, y).s.x - f.sample(x - h, y).s.x) / (2 * h);
            err2 += (d - c.Jxx) * (d - c.Jxx), ref2 += c.Jxx * c.Jxx;
            // and s is the gradient of h (up to the same O(h^2) difference error)
            const double g = (f.height(x, y + h) - f.height(x, y - h)) / (2 * h);
            herr2 += (g - c.s.y) * (g - c.s.y), href2 += c.s.y * c.s.y;
        }
        // 16 texels a bump period: central differences are (2 pi / 16)^2 / 6 = 2.6% low at the ring's centre.
        CHECK(std::sqrt(err2 / ref2) < 0.06);
        CHECK(std::sqrt(herr2 / href2) < 0.06);
    }
}

TEST_CASE("micro::traceMasking") {
    const auto f = micro::makeBumpField(smallSpec(micro::BumpKind::Beckmann, 0.3));
    // 40000 facets: one standard error of G2 at 85 deg is ~0.007, a tenth of the Smith-separable gap (0.06).
    const auto rows = micro::traceMasking(f, {70.0, 85.0}, 40000, 3);
    REQUIRE(rows.size() == 2);
    for (const auto& r : rows) {
        CAPTURE(r.thetaDeg);
        // Every line of sight meets a height field once: traced G1 = 1 / (1 + Lambda) of the realised slopes.
        CHECK_NEAR(r.g1, r.g1Realized, 3 * r.g1Err + 0.01);
        CHECK_NEAR(r.g1, r.g1Smith, 3 * r.g1Err + 0.02);
        CHECK(r.g2 <= r.g1h + 1e-12);  // visible from both is rarer than from one
    }
    // At grazing the height correlation matters: the height-correlated Smith G2 is much closer than G1^2.
    const auto& g = rows[1];
    CHECK_NEAR(g.g2, g.g2Smith, std::abs(g.g2 - g.g2Uncorrelated));
    CHECK(micro::lambdaBeckmannExact(1.0, 0.3) == 0.0);
}
