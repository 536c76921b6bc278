// The tabulated NDF in GL: a table sampled from GGX measures like GGX.

#include "brdf/ndf_tables.hpp"
#include "hilite/measurement/measure_scene.hpp"

#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;

TEST_CASE("measurement::measureGl a table sampled from GGX measures like GGX") {
    measurement::MeasureSetup setup;
    setup.width = setup.height = 128;
    auto& renderer = *test::glEnv().renderer;
    for (double alpha : {0.1, 0.3}) {
        render::Scene ggx;
        ggx.brdf.model = brdf::Model::GGX;
        ggx.brdf.roughness = alpha;
        render::Scene tab = ggx;
        tab.brdf.model = brdf::Model::Tabulated;
        tab.brdf.ndfTable = brdf::parseNdfTable(test::ggxTableText(alpha), "ggx.csv");
        for (double inc : {0.0, 30.0, 60.0, 75.0}) {
            ggx.light.incidenceDeg = tab.light.incidenceDeg = inc;
            const auto a = measurement::measureGl(renderer, ggx, setup),
                       b = measurement::measureGl(renderer, tab, setup);
            CAPTURE(alpha);
            CAPTURE(inc);
            CHECK_NEAR(a.shape.aspect, b.shape.aspect, 0.005);
            CHECK(b.shape.major_deg == doctest::Approx(a.shape.major_deg).epsilon(0.005));
            CHECK(b.shape.minor_deg == doctest::Approx(a.shape.minor_deg).epsilon(0.005));
            CHECK(b.shape.flags == a.shape.flags);
        }
    }
}
