// measurement.lobe = mirror (--lobe mirror): the highlight around the mirror direction, in GL, on the CPU twin and in
// the double reference, beside today's definition (lobe = all), and the diagnoses where no lobe holds the mirror
// direction.

#include "support/in_process.hpp"
#include "support/rgl_file.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

using namespace hilite;
using namespace hilite::testing;

namespace {

const std::string kGgx03 = "--model ggx --roughness 0.3 --geometry smith --fresnel schlick --f0 0.04 ";

bool hasFlag(const nlohmann::json& row, const std::string& flag) {
    for (const auto& f : row["flags"])
        if (f == flag) return true;
    return false;
}

}  // namespace

TEST_CASE("lobe mirror: GGX 0.3 + Smith + Schlick 0.04 over 0:80:5 measures the lobe, never the horizon strip") {
    const auto mirror = measureJson(flags(kGgx03 + "--incidence 0:80:5 --lobe mirror --size 256"));
    const auto reference = measureJson(flags(kGgx03 + "--incidence 0:80:5 --lobe mirror --reference"));
    const auto all = measureJson(flags(kGgx03 + "--incidence 0:80:5 --size 256"));
    REQUIRE(mirror.size() == 17);
    REQUIRE(reference.size() == 17);
    int measured = 0;
    for (size_t i = 0; i < mirror.size(); ++i) {
        const auto &g = mirror[i], &r = reference[i];
        const double theta = g["incidence_deg"].get<double>();
        CAPTURE(theta);
        CHECK(g["lobe"] == "mirror");
        CHECK(all[i]["lobe"] == "all");
        // Where one path finds no lobe around the mirror direction, so does the other, and neither gives numbers.
        CHECK(hasFlag(g, "no_mirror_lobe") == hasFlag(r, "no_mirror_lobe"));
        if (hasFlag(g, "no_mirror_lobe")) {
            CHECK(g["aspect"].is_null());
            CHECK(g["major_deg"].is_null());
            CHECK(r["aspect"].is_null());
            continue;
        }
        ++measured;
        // The lobe, not a strip: the horizon bounds no part of it, and its centroid stays near the mirror direction
        // (the global region's lies 19-26 deg below it from 30 deg on, at the horizon strip).
        CHECK_FALSE(hasFlag(g, "horizon_cut"));
        CHECK(std::abs(g["centroid_u_deg"].get<double>()) < 12.0);
        // GL against the double reference: the same lobe through the same mask (256^2; where a valley ends the
        // region, the mask's edge is a kink the pixels resolve to ~0.3%).
        const double tol = hasFlag(g, "saddle_cut") ? 5e-3 : 1e-3;
        CHECK(g["aspect"].get<double>() == doctest::Approx(r["aspect"].get<double>()).epsilon(tol));
        CHECK(g["major_deg"].get<double>() == doctest::Approx(r["major_deg"].get<double>()).epsilon(tol));
        CHECK(g["minor_deg"].get<double>() == doctest::Approx(r["minor_deg"].get<double>()).epsilon(tol));
        // Up to 25 deg the lobe is the whole region: the same numbers as lobe = all.
        if (theta <= 20)
            CHECK(g["aspect"].get<double>() == doctest::Approx(all[i]["aspect"].get<double>()).epsilon(1e-4));
        // From 30 deg the region at half the lobe's peak runs over a saddle into the strip: ended at the valley.
        if (theta >= 30) CHECK(hasFlag(g, "saddle_cut"));
    }
    CHECK(hasFlag(all[6], "horizon_cut"));  // lobe = all at 30 deg: the strip
    MESSAGE("lobe mirror, GGX 0.3 + Smith + Schlick 0.04: " << measured
                                                            << " of 17 incidences have a lobe around the "
                                                               "mirror direction");
    CHECK(measured >= 9);  // 0-40 deg; beyond, the radiance rises from the mirror direction to the horizon
    CHECK(hasFlag(mirror[16], "no_mirror_lobe"));
}

TEST_CASE("lobe mirror: a one-part lobe measures as lobe all in the reference, GL and the CPU pixels") {
    const std::string ggx = "--model ggx --roughness 0.1 --incidence 30 ";
    const auto refAll = measureJson(flags(ggx + "--reference"));
    const auto refMirror = measureJson(flags(ggx + "--reference --lobe mirror"));
    CHECK(refMirror[0]["aspect"].get<double>() == doctest::Approx(refAll[0]["aspect"].get<double>()).epsilon(1e-9));
    CHECK(refMirror[0]["area_deg2"].get<double>() ==
          doctest::Approx(refAll[0]["area_deg2"].get<double>()).epsilon(1e-9));
    for (const char* renderer : {"gl", "cpu"}) {
        CAPTURE(renderer);
        const auto a = measureJson(flags(ggx + "--size 256 --renderer " + renderer));
        const auto m = measureJson(flags(ggx + "--size 256 --lobe mirror --renderer " + renderer));
        CHECK(m[0]["aspect"].get<double>() == doctest::Approx(a[0]["aspect"].get<double>()).epsilon(1e-3));
        CHECK(m[0]["major_deg"].get<double>() == doctest::Approx(a[0]["major_deg"].get<double>()).epsilon(1e-3));
        CHECK(m[0]["flags"].empty());
    }
}

TEST_CASE("lobe mirror: no lobe around the mirror direction is a named diagnosis, a delta is a mirror") {
    // A retroreflective lobe: its peak is toward the light, 60 deg away.
    const auto retro = measureJson(flags("--model retro --exponent 100 --incidence 30 --lobe mirror"));
    CHECK(retro[0]["flags"] == nlohmann::json::array({"no_mirror_lobe"}));
    CHECK(retro[0]["aspect"].is_null());
    // A Lambertian plane: a flat radiance, no maximum anywhere.
    const auto flat = measureJson(flags("--model none --diffuse lambert --incidence 30 --lobe mirror --reference"));
    CHECK(flat[0]["flags"] == nlohmann::json::array({"no_mirror_lobe"}));
    const auto delta = measureJson(flags("--model ggx --roughness 0 --incidence 30 --lobe mirror --reference"));
    CHECK(delta[0]["flags"] == nlohmann::json::array({"mirror"}));
}

TEST_CASE("lobe mirror: refused where it has no twin to find the lobe, and an unknown lobe") {
    CHECK(refusal(flags("--lobe sideways")).find("--lobe") != std::string::npos);
    const std::string bumps = refusal(flags("--model beckmann --roughness 0.2 --bumps explicit --lobe mirror"));
    CHECK(oneLine(bumps));
    CHECK(bumps.find("--lobe mirror") != std::string::npos);
}

TEST_CASE("lobe mirror: the real RGL films, GL against the double reference, no horizon growth in the rows") {
    const std::string dir = hilite_test::sharedMeasured();
    for (const char* name : {"cc_ibiza_sunset_rgb.bsdf", "cc_iris_purple_gem_rgb.bsdf", "vch_golden_yellow_rgb.bsdf"}) {
        const std::string file = dir + "/" + name;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        CAPTURE(file);
        const std::string base = "--measured " + file + " --incidence 20,40,60 --lobe mirror ";
        const auto gl = measureJson(flags(base + "--size 256"));
        const auto cpu = measureJson(flags(base + "--size 256 --renderer cpu"));
        const auto ref = measureJson(flags(base + "--reference"));
        double worst = 0;
        for (size_t i = 0; i < gl.size(); ++i) {
            CAPTURE(gl[i]["incidence_deg"].get<double>());
            // lobe = all says unbounded_at_horizon for every film (f = stored / cos theta_o): the lobe does not.
            CHECK_FALSE(hasFlag(gl[i], "unbounded_at_horizon"));
            CHECK_FALSE(hasFlag(gl[i], "no_mirror_lobe"));
            // The same pixels in float and in double: the same lobe.
            CHECK(gl[i]["aspect"].get<double>() == doctest::Approx(cpu[i]["aspect"].get<double>()).epsilon(1e-4));
            CHECK(gl[i]["major_deg"].get<double>() == doctest::Approx(cpu[i]["major_deg"].get<double>()).epsilon(1e-4));
            // Against the reference's contour: the table's bilinear kinks cost 256^2 pixels up to ~0.7%.
            CHECK(gl[i]["aspect"].get<double>() == doctest::Approx(ref[i]["aspect"].get<double>()).epsilon(1e-2));
            CHECK(gl[i]["major_deg"].get<double>() == doctest::Approx(ref[i]["major_deg"].get<double>()).epsilon(1e-2));
            CHECK(std::abs(gl[i]["centroid_u_deg"].get<double>() - ref[i]["centroid_u_deg"].get<double>()) < 0.05);
            for (const char* k : {"aspect", "major_deg", "minor_deg"})
                worst = std::max(worst, std::abs(gl[i][k].get<double>() / ref[i][k].get<double>() - 1));
        }
        MESSAGE(std::string(name) << ", lobe mirror at 20, 40, 60 deg: GL 256^2 against the reference, worst relative "
                                  << worst);
    }
}
