// The parameter registry: every entry well-formed, its defaults valid by its own check, the CLI flags and
// scene-file keys derived from it, and docs/parameters.md's flag table equal to it.

#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"
#include "hilite/scene/scene_file.hpp"

#include "core/text.hpp"
#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <set>
#include <sstream>

using namespace hilite;

TEST_CASE("scene::registry entries are complete and their defaults pass their own checks") {
    std::set<std::string> names, columns;
    for (const scene::Param& p : scene::registry()) {
        CAPTURE(p.name);
        CHECK(names.insert(p.name).second);
        CHECK(!p.help.empty());
        CHECK(!p.appliesTo.empty());
        CHECK(p.column.empty() == (p.value == nullptr));
        if (!p.column.empty()) CHECK(columns.insert(p.column).second);
        if (p.kind == scene::Kind::Choice) CHECK(!p.choices.empty());
        if (!p.def.empty()) CHECK(scene::check(p, p.def) == "");
        CHECK((scene::find(p.flag()) == &p));
    }
    CHECK((scene::resolve(scene::Values{}).scene.brdf.model == brdf::Model::GGX));
}

TEST_CASE("scene::check refuses bad values with the allowed ones named") {
    const scene::Param& r = *scene::find("roughness");
    CHECK(scene::check(r, "-3") == "must be a finite number in [0, 10] (got -3)");
    CHECK(scene::check(r, "") == "'' is not a number");
    CHECK(scene::check(r, "nan").find("must be a finite number") == 0);
    CHECK(scene::check(*scene::find("model"), "gxx").find("allowed: phong") != std::string::npos);
    CHECK(scene::check(*scene::find("f0"), "0.1,0.2") == "expected V or R,G,B (got '0.1,0.2')");
    CHECK(scene::check(*scene::find("threshold"), "1") != "");
    CHECK(scene::check(*scene::find("min_pixels"), "2.5") != "");
    CHECK(scene::check(*scene::find("min_pixels"), "3") == "");
}

TEST_CASE("scene: automatic is a word, never a number in range (--fov 0 meant automatic)") {
    const scene::Param& fov = *scene::find("fov");
    CHECK(fov.allowed() == "auto | (0, 179]");
    CHECK(scene::check(fov, "auto") == "");
    CHECK(scene::check(fov, "0") == "must be auto or a finite number in (0, 179] (got 0)");
    CHECK(scene::check(fov, "Auto") == "expected auto or a number in (0, 179] (got 'Auto')");
    const scene::Param& elevation = *scene::find("elevation");
    CHECK(scene::check(elevation, "0") == "");
    CHECK(scene::check(elevation, "auto") == "");
    scene::Values v;
    CHECK(scene::resolve(v).fovDeg == 0);  // auto: automatic framing
    CHECK_FALSE(scene::resolve(v).elevationDeg.has_value());
    v.set("elevation", "0");
    v.set("fov", "20");
    const auto r = scene::resolve(v, scene::Purpose::Render);
    CHECK(r.elevationDeg == 0.0);
    CHECK(r.fovDeg == 20);
}

TEST_CASE("rangeText: the bounds short where exact (1e+08, not 100000000), else every digit") {
    CHECK(rangeText(0, 1e8) == "[0, 1e+08]");
    CHECK(rangeText(0, 179, true, false) == "(0, 179]");
    CHECK(rangeText(0.1234567, 1) == "[0.1234567, 1]");
    CHECK(rangeText(1e-5, 0.1, false, true) == "[1e-05, 0.1)");
}

TEST_CASE("scene::resolve names the scene file, line and key of a bad value") {
    const scene::Values v = scene::parseSceneToml("[material]\nmodel = \"beckmann\"\nroughness = 11\n", "s.toml");
    try {
        scene::resolve(v);
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "s.toml:3: material.roughness: must be a finite number in [0, 10] (got 11)");
    }
    CHECK_THROWS_AS(scene::parseSceneToml("[light]\nroughness = 0.1\n", "s.toml"), InputError);  // wrong table
}

TEST_CASE("scene::resolve clamps a roughness below float's reach and the row carries the clamped value") {
    scene::Values v;
    v.set("roughness", "1e-9");
    v.set("roughness_y", "1e-9");
    const scene::Resolved r = scene::resolve(v);
    CHECK(r.scene.brdf.roughness == 1e-7);
    CHECK(*r.scene.brdf.roughnessY == 1e-7);
    const nlohmann::json row = scene::parameterColumns(r);
    CHECK(row["roughness"].get<double>() == 1e-7);
    CHECK(row["roughness_y"].get<double>() == 1e-7);
}

TEST_CASE("docs/parameters.md's flag table is the registry's (hilite explain --part flags)") {
    std::ifstream in(std::string(HILITE_SOURCE_DIR_STR) + "/docs/parameters.md");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string readme = ss.str();
    const std::string begin = "<!-- flags:begin (hilite explain --part flags) -->\n", end = "<!-- flags:end -->";
    const auto a = readme.find(begin), b = readme.find(end);
    REQUIRE(a != std::string::npos);
    REQUIRE(b != std::string::npos);
    CHECK(readme.substr(a + begin.size(), b - a - begin.size()) == scene::markdownTable());
}

TEST_CASE("scene::sceneToml writes a file that reads back as the same values") {
    scene::Values v;
    v.set("model", "ggx");
    v.set("roughness", "0.1");
    v.set("f0", "0.9,0.6,0.3");
    v.set("fresnel", "schlick");
    v.set("incidence", "0:85:5");
    v.set("size", "128x96");
    v.set("fov", "auto");
    v.set("reference", "true");
    v.set("view", "photo");
    v.set("elevation", "1e-3");
    const std::string text = scene::sceneToml(v);
    CHECK(text.find("[material]\nmodel = 'ggx'\nroughness = 0.1\n") != std::string::npos);
    CHECK(text.find("f0 = [0.9, 0.6, 0.3]") != std::string::npos);
    CHECK(text.find("reference = true") != std::string::npos);
    CHECK(text.find("incidence = '0:85:5'") != std::string::npos);
    const scene::Values back = scene::parseSceneToml(text, "back.toml");
    for (const auto& given : v.given()) {  // the same text, or the same number (1e-3 reads back as 0.001)
        const auto& name = given.first;
        const auto& value = given.second;
        const auto a = parseNumber(back.text(name)), b = parseNumber(value.text);
        CHECK_MESSAGE((a && b ? *a == *b : back.text(name) == value.text), name);
    }
    CHECK(back.given().size() == v.given().size());
    CHECK(scene::parameterColumns(scene::resolve(back)) == scene::parameterColumns(scene::resolve(v)));

    // A file name is written absolute, so the file reads the same from any folder.
    scene::Values p;
    p.set("model", "tabulated");
    p.set("ndf_table", "tables/x.csv");
    const std::string pt = scene::sceneToml(p);
    CHECK(pt.find("ndf_table = '/") != std::string::npos);
    // A string with quotes and newlines stays one TOML string.
    scene::Values q;
    q.set("brdf", "we\"ird\nname.brdf");
    CHECK(scene::parseSceneToml(scene::sceneToml(q), "q.toml").text("brdf").find("we\"ird\nname.brdf") !=
          std::string::npos);
}
