// The hand-painted (tabulated) NDF: reading, normalization, interpolation, Smith's Lambda from the table,
// and one-line errors naming file:line for bad tables.

#include "brdf/integrate.hpp"
#include "brdf/ndf_tables.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/brdf/terms.hpp"
#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace hilite;

TEST_CASE("brdf::parseNdfTable") {
    SUBCASE("a constant D over the hemisphere: normalized by 1 / (pi c), exactly") {
        const auto t = brdf::parseNdfTable("0, 2.5\n90, 2.5\n", "flat.csv");
        CHECK(t->normalization == doctest::Approx(1.0 / (kPi * 2.5)).epsilon(1e-14));
        CHECK(t->D[0] == doctest::Approx(kInvPi).epsilon(1e-14));
    }
    SUBCASE("GGX sampled (x 3): the factor applied is 1/3, the table is GGX, int D (n.h) dw = 1") {
        const auto t = brdf::parseNdfTable(test::ggxTableText(0.1), "ggx.csv");
        CHECK(t->theta.size() == 401);
        CHECK(t->normalization == doctest::Approx(1.0 / 3.0).epsilon(2e-4));  // linear between rows
        for (double deg : {0.0, 1.0, 3.0, 3.7, 6.0, 20.0, 60.0}) {
            const double th = deg2rad(deg), c = std::cos(th), s2 = std::sin(th) * std::sin(th);
            CAPTURE(deg);
            CHECK(brdf::D_Tabulated(c, s2, *t) == doctest::Approx(brdf::D_GGX(c, s2, 0.1)).epsilon(1e-3));
        }
        brdf::Params p;
        p.model = brdf::Model::Tabulated;
        p.ndfTable = t;
        CHECK(brdf::ndfIntegral(p) == doctest::Approx(1.0).epsilon(1e-5));
        // GGX's half maximum: tan(theta) = alpha sqrt((sqrt 2 - 1) / (1 - sqrt 2 alpha^2)).
        const double halfMax = std::atan(0.1 * std::sqrt((std::sqrt(2.0) - 1) / (1 - std::sqrt(2.0) * 0.01)));
        CHECK(t->halfWidth == doctest::Approx(halfMax).epsilon(1e-4));
        // Smith's Lambda integrated from the table: GGX's closed form (Heitz 2014 eq. 72).
        for (double deg : {0.0, 30.0, 60.0, 80.0, 85.0, 88.0}) {
            const double c = std::cos(deg2rad(deg));
            CAPTURE(deg);
            CHECK(brdf::Lambda_Tabulated(c, *t) == doctest::Approx(brdf::Lambda_GGX(c, 0.1)).epsilon(2e-3).scale(1e-3));
        }
    }
    SUBCASE("a header, comments, blank lines and whitespace separators are accepted; D is 0 beyond the last row") {
        const auto t = brdf::parseNdfTable("theta, D   # header\n\n0 1\n# comment\n10\t0.5\n20, 0  # end\n", "h.csv");
        CHECK(t->theta.size() == 3);
        CHECK(brdf::D_Tabulated(std::cos(deg2rad(25.0)), std::pow(std::sin(deg2rad(25.0)), 2), *t) == 0.0);
        CHECK(brdf::D_Tabulated(std::cos(deg2rad(5.0)), std::pow(std::sin(deg2rad(5.0)), 2), *t) ==
              doctest::Approx(0.75 * t->normalization));
    }
}

TEST_CASE("brdf::parseNdfTable bad tables: one line naming file:line") {
    struct Case {
        const char* text;
        const char* starts;    ///< the message's beginning: file:line
        const char* mentions;  ///< and what it says
    };
    for (const Case& c :
         {Case{"0, 1\n10, 0.5\n5, 0.2\n", "bad.csv:3: ", "increase"},
          Case{"0, 1\n10, 0.5\n10, 0.2\n", "bad.csv:3: ", "increase"}, Case{"0, 1\n10, -0.5\n", "bad.csv:2: ", ">= 0"},
          Case{"0, 1\n10, nan\n", "bad.csv:2: ", "finite"}, Case{"0, 1\n10, inf\n", "bad.csv:2: ", "finite"},
          Case{"theta, D\n0, 1\n", "bad.csv:2: ", "too few rows"}, Case{"", "bad.csv:0: ", "too few rows"},
          Case{"5, 1\n10, 0.5\n", "bad.csv:1: ", "start at theta_h = 0"},
          Case{"0, 1\n95, 0.5\n", "bad.csv:2: ", "[0, 90]"}, Case{"0, 1\n10, 0.5, 3\n", "bad.csv:2: ", "two numbers"},
          Case{"0, 1\n10, x\n", "bad.csv:2: ", "two numbers"}, Case{"0, 0\n10, 0\n", "bad.csv:2: ", "0 everywhere"}}) {
        CAPTURE(c.text);
        try {
            brdf::parseNdfTable(c.text, "bad.csv");
            FAIL("no error");
        } catch (const InputError& e) {
            const std::string m = e.what();
            CHECK(m.rfind(c.starts, 0) == 0);
            CHECK(m.find(c.mentions) != std::string::npos);
            CHECK(m.find('\n') == std::string::npos);
        }
    }
    CHECK_THROWS_WITH_AS(brdf::loadNdfTable("/nonexistent/d.csv"),
                         doctest::Contains("--ndf-table: cannot read '/nonexistent/d.csv'"), InputError);
}
