// The moments prefilter's lobe (CPU twin): the Gaussian slope distribution of given moments is the Beckmann
// NDF when the moments are Beckmann's, and the filter choice follows the centre pixel's patch count.

#include "brdf/ndf.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "render/bump_moments.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace hilite;

TEST_CASE("render::bumpMomentsLobe") {
    SUBCASE("moments (0, m^2/2 I) under a point-like sun: the Beckmann NDF, L = D wi.z / 4") {
        const double m = 0.1;
        micro::Moments M;
        M.xx = M.yy = 0.5 * m * m;
        for (double ti : {0.0, 30.0, 75.0})
            for (auto [du, dv] : {std::pair{0.0, 0.0}, {0.05, 0.0}, {-0.1, 0.07}, {0.0, 0.2}}) {
                const MirrorChart chart = MirrorChart::fromDegrees(ti, 20.0);
                const dvec3 we = chart.direction(du, dv), wi = chart.wi();
                if (we.z <= 0.0) continue;
                const dvec3 h = glm::normalize(we + wi);
                double VoH = 0;
                const double l = render::bumpMomentsLobe(M, we, wi, deg2rad(1e-4), VoH);
                const double d = brdf::D_Beckmann(h.z, h.x * h.x + h.y * h.y, m);
                CHECK(l == doctest::Approx(d * wi.z / 4).epsilon(1e-6));
                CHECK(VoH == doctest::Approx(glm::dot(we, h)));
            }
    }
    SUBCASE("a mean slope moves the lobe: its peak is at the half vector of the mean facet") {
        micro::Moments M;
        M.mean = {0.05, -0.02};
        M.xx = 0.005 + M.mean.x * M.mean.x, M.yy = 0.005 + M.mean.y * M.mean.y, M.xy = M.mean.x * M.mean.y;
        const dvec3 wi = sphericalDirectionDeg(40.0, 0.0), m = glm::normalize(dvec3(-M.mean.x, -M.mean.y, 1.0));
        const dvec3 peak = 2.0 * glm::dot(wi, m) * m - wi;  // wi mirrored about the mean facet
        double VoH = 0;
        const double at = render::bumpMomentsLobe(M, peak, wi, deg2rad(0.1), VoH);
        for (const dvec3& off : {dvec3(0.01, 0, 0), dvec3(-0.01, 0, 0), dvec3(0, 0.01, 0), dvec3(0, -0.01, 0)})
            CHECK(render::bumpMomentsLobe(M, glm::normalize(peak + off), wi, deg2rad(0.1), VoH) < at);
    }
    SUBCASE("the sun widens the lobe by its own width: the peak falls as 1 / (var + sun var) for a narrow lobe") {
        micro::Moments M;
        M.xx = M.yy = 1e-6;  // rms slope 1e-3: the sun (1 mrad in direction = 0.5 mrad in slope) matters
        const dvec3 wi(0, 0, 1), we(0, 0, 1);
        double VoH = 0;
        const double sharp = render::bumpMomentsLobe(M, we, wi, 1e-9, VoH);
        const double soft = render::bumpMomentsLobe(M, we, wi, 1e-3, VoH);
        // slope variance 1e-6 per axis + (1e-3 / 2)^2 from the sun (at normal incidence dr = 2 ds)
        CHECK(soft / sharp == doctest::Approx(1e-6 / (1e-6 + 0.25e-6)).epsilon(1e-6));
    }
}

TEST_CASE("render::usesMoments") {
    render::Scene s;
    s.brdf.model = brdf::Model::Beckmann;
    s.light.incidenceDeg = 60;
    s.surface.bumps = true;
    auto cam = [&] { return measurement::measurementCamera(s, s.light.chart().wr(), 20.0, 64, 64); };
    s.surface.bumpPeriodPx = 0.25;  // 4 periods across the centre pixel, 8 along: 32 patches an axis (33: perspective)
    CHECK(render::centreBumpSamples(s, cam()) >= 32);
    CHECK(render::centreBumpSamples(s, cam()) <= 33);
    CHECK_FALSE(render::usesMoments(s, cam()));
    s.surface.bumpPeriodPx = 0.1;  // 80 patches: beyond the cap of 64
    CHECK(render::usesMoments(s, cam()));
    s.brdf.model = brdf::Model::GGX;  // not Gaussian slopes: supersampled (capped) all the same
    CHECK_FALSE(render::usesMoments(s, cam()));
    s.brdf.model = brdf::Model::Beckmann;
    s.surface.filter = render::BumpFilter::Supersample;
    CHECK_FALSE(render::usesMoments(s, cam()));
    s.surface.filter = render::BumpFilter::Moments;
    s.surface.bumpPeriodPx = 8;
    CHECK(render::usesMoments(s, cam()));
}
