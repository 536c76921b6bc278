// The slope-moment pyramid of a bump field (the moments prefilter's data): each level the exact average of the
// rendered (bilinear) field, the footprint probes, and the whole tile's covariance.

#include "micro/slope_moments.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;

namespace {

micro::BumpSpec smallSpec() {
    micro::BumpSpec s;
    s.kind = micro::BumpKind::Beckmann;
    s.roughness = 0.1;
    s.texels = 128;
    s.bumpsPerTile = 8;
    return s;
}

/// Moments of the bilinear field over the square [x0, x0 + w]^2 (tile lengths) by a fine midpoint rule.
micro::Moments brute(const micro::BumpField& f, double x0, double y0, double w, int per) {
    micro::Moments m;
    const int N = int(std::lround(w * f.n)) * per;
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            const dvec2 s = f.sample(x0 + (i + 0.5) * w / N, y0 + (j + 0.5) * w / N).s;
            m.mean += s;
            m.xx += s.x * s.x, m.yy += s.y * s.y, m.xy += s.x * s.y;
        }
    const double n2 = double(N) * N;
    m.mean /= n2;
    m.xx /= n2, m.yy /= n2, m.xy /= n2;
    return m;
}

}  // namespace

TEST_CASE("micro::makeSlopeMoments") {
    const micro::BumpField f = micro::makeBumpField(smallSpec());
    const micro::SlopeMoments m = micro::makeSlopeMoments(f);
    REQUIRE(m.levels == 8);  // 128 .. 1
    SUBCASE("a level's texel is the exact average of the bilinear field over its 2^L x 2^L cells") {
        // Level 3, texel (5, 9): cells 40..47 x 72..79, i.e. [(40 + 0.5)/n, (48 + 0.5)/n) on each axis.
        const int L = 3, i = 5, j = 9, side = 1 << L;
        const double x0 = (i * side + 0.5) / f.n, y0 = (j * side + 0.5) / f.n, w = double(side) / f.n;
        const micro::Moments b = brute(f, x0, y0, w, 16);
        const micro::Moments a = m.at(L, x0 + 0.5 * w, y0 + 0.5 * w);  // the texel's centre: no interpolation
        CHECK(a.mean.x == doctest::Approx(b.mean.x).epsilon(1e-3));
        CHECK(a.mean.y == doctest::Approx(b.mean.y).epsilon(1e-3));
        const dvec3 ca = a.covariance(), cb = b.covariance();
        CHECK(ca.x == doctest::Approx(cb.x).epsilon(1e-3));
        CHECK(ca.y == doctest::Approx(cb.y).epsilon(1e-3));
        CHECK(ca.z == doctest::Approx(cb.z).epsilon(1e-2).scale(cb.x));
    }
    SUBCASE("the top level is the whole tile: mean slope 0, mean |s|^2 = m^2 (the field's normalization)") {
        const micro::Moments t = m.at(m.levels - 1, 0.3, 0.7);
        CHECK_NEAR(t.mean.x, 0.0, 1e-6);
        CHECK_NEAR(t.mean.y, 0.0, 1e-6);
        CHECK(t.xx + t.yy == doctest::Approx(0.01).epsilon(1e-5));
        CHECK(t.xx / t.yy == doctest::Approx(1.0).epsilon(0.15));  // 64 bumps: the realisation's anisotropy
    }
    SUBCASE("footprints: a large one is the tile; a long thin one probes along its length") {
        const micro::Moments big = m.footprint(0.1, 0.2, {3.0, 0.0}, {0.0, 2.0});
        const micro::Moments t = m.at(m.levels - 1, 0.0, 0.0);
        CHECK(big.xx == doctest::Approx(t.xx).epsilon(1e-6));
        // A 1/4 x 1/32 tile strip: the probes' average against the strip's brute-force moments.
        const double x0 = 0.3, y0 = 0.6;
        const micro::Moments strip = m.footprint(x0 + 0.125, y0 + 1.0 / 64, {0.25, 0.0}, {0.0, 1.0 / 32});
        micro::Moments b;
        const int per = 4;
        for (int k = 0; k < 8; ++k) {  // eight squares of side 1/32 along the strip
            const micro::Moments q = brute(f, x0 + k / 32.0, y0, 1.0 / 32, per);
            b.mean += q.mean / 8.0;
            b.xx += q.xx / 8, b.yy += q.yy / 8, b.xy += q.xy / 8;
        }
        // Trilinear probes are a slightly blurred box (measured: mean 0.0058 against 0.0058, E|s|^2 to 4e-4).
        const double var = b.covariance().x + b.covariance().y;
        CHECK_NEAR(strip.mean.x, b.mean.x, 0.05 * std::sqrt(var));
        CHECK_NEAR(strip.xx + strip.yy, b.xx + b.yy, 0.01 * (b.xx + b.yy));
    }
}
