// The caches of what is computed from a scene (the lobe survey, measurement/lobe_survey.cpp; the energy tables,
// scene/resolve.cpp) are keyed on the resolved registry values (issue 31): changing any parameter that reaches
// the cache's input changes its key; the ones that cannot reach it are listed here, each with why.

#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"

#include "brdf/merl.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <set>

using namespace hilite;

namespace {

const std::string kSource = HILITE_SOURCE_DIR_STR;

struct Case {
    std::string name, value;
    std::vector<std::pair<std::string, std::string>> context;  ///< set in both scenes
};

scene::Resolved resolveWith(const Case& c, bool changed) {
    scene::Values v;
    for (const auto& [k, t] : c.context) v.set(k, t);
    if (changed) v.set(c.name, c.value);
    return scene::resolve(v);
}

}  // namespace

TEST_CASE("scene::sceneKey and energyKey: every registry parameter changes them, or is listed as not reaching them") {
    const std::string other = "/tmp/hilite_test_cache_keys_ndf.csv";
    {
        std::ofstream f(other);
        f << "theta_h_deg, D\n0, 4\n20, 1\n40, 0\n";
    }
    const std::string fitsA = "/tmp/hilite_test_cache_keys_fits_a.tsv",
                      fitsB = "/tmp/hilite_test_cache_keys_fits_b.tsv";
    for (const auto& [file, b] : {std::pair<std::string, const char*>{fitsA, "1000"}, {fitsB, "2000"}}) {
        std::ofstream f(file);
        f << "material\tkD_r\tkD_g\tkD_b\tA_r\tA_g\tA_b\tB\tC\tior\nm\t0.1\t0.1\t0.1\t100\t100\t100\t" << b
          << "\t1.2\t1.5\nn\t0.2\t0.1\t0.1\t100\t100\t100\t3000\t1.2\t1.5\n";
    }
    const std::vector<std::pair<std::string, std::string>> fits = {{"fit_table", fitsA}, {"fit_material", "m"}};
    const std::string painted = kSource + "/data/ndf/hand_painted.csv",
                      brdfFile = kSource + "/fuzz/corpus/brdf/ggx.brdf";
    const std::vector<Case> cases = {
        {"model", "beckmann", {}},
        {"exponent", "500", {}},
        {"roughness", "0.2", {}},
        {"roughness_y", "0.05", {}},
        {"tangent_angle", "10", {}},
        {"fresnel", "schlick", {}},
        {"material", "glass", {}},
        {"spectral_fresnel", "exact", {}},
        {"eta", "1.7", {}},
        {"k", "0.5", {{"fresnel", "conductor"}}},
        {"f0", "0.1", {}},
        {"geometry", "smith", {}},
        {"multiscatter", "kulla-conty", {{"geometry", "smith"}}},
        {"diffuse", "coupled", {{"geometry", "smith"}}},
        {"albedo", "0.3", {}},
        {"sigma", "30", {}},
        {"abc_a", "50", {}},
        {"abc_b", "500", {}},
        {"abc_c", "2", {}},
        {"sgd_rho_s", "0.2", {}},
        {"sgd_alpha", "0.1", {}},
        {"sgd_p", "0.9", {}},
        {"sgd_f0", "0.1", {}},
        {"sgd_f1", "0.1", {}},
        {"sgd_lambda", "0.5", {}},
        {"sgd_c", "0.1", {}},
        {"sgd_k", "3", {}},
        {"sgd_theta0", "0.1", {}},
        {"lafortune_rho_s", "0.2", {}},
        {"lafortune_cxy", "-0.5", {}},
        {"lafortune_cz", "0.5", {}},
        {"fit_table", fitsB, fits},
        {"fit_material", "n", fits},
        {"ndf_table", other, {{"model", "tabulated"}, {"ndf_table", painted}}},
        {"brdf", brdfFile, {}},
        {"param", "alpha=0.2", {{"brdf", brdfFile}}},
        {"incidence", "30", {}},
        {"azimuth", "10", {}},
        {"light", "point", {}},
        {"irradiance", "2", {}},
        {"intensity", "2", {}},
        {"light_distance", "20", {}},
        {"light_radius", "0.2", {}},
        {"light_angle", "0.5", {}},
        {"light_rings", "4", {}},
        {"light_rule", "ltc", {}},
        {"distance", "20", {}},
        {"bumps", "explicit", {}},
        {"bump_period_px", "8", {}},
        {"bump_seed", "2", {}},
        {"bump_samples", "3", {}},
        {"sun", "0.2", {}},
        {"bump_filter", "supersample", {}},
        {"prefilter_check", "true", {}},
        {"tolerance", "0.01", {}},  // the area light's rule target (tolerance / 4) is part of the scene
        // How the scene is rendered and measured, not the scene: the lobe and its albedo are functions of
        // render::Scene (brdf::Params) alone.
        {"size", "256", {}},
        {"fov", "20", {}},
        {"view", "photo", {}},
        {"elevation", "30", {}},
        {"gl_backend", "osmesa", {}},
        {"shader_timeout", "5", {}},
        {"threshold", "0.4", {}},
        {"lobe", "mirror", {}},
        {"min_pixels", "4", {}},
        {"boundary", "pixel", {}},
        {"supersample", "2", {}},
        {"renderer", "cpu", {}},
        {"crop", "off", {}},
        {"aim_size", "32", {}},
        {"reference", "true", {}},
    };
    // Not resolved here: --measured needs a 33 MB MERL file (its key is checked below on a table made in memory);
    // --gpu needs an EGL device (it picks the device, a setting of the run, not of the scene).
    const std::set<std::string> untested = {"measured", "gpu"};
    const std::set<std::string> notInScene = {
        "size",       "fov",      "view",        "elevation", "gl_backend", "lobe",     "gpu",       "threshold",
        "min_pixels", "boundary", "supersample", "renderer",  "crop",       "aim_size", "reference", "shader_timeout"};
    // The energy tables are the specular lobe's albedo (brdf::Params alone): not the light, the view, the bumps or
    // the measurement; not the diffuse albedo or sigma (brdf/energy.cpp makeEs sets the diffuse term aside); a
    // .brdf file replaces the built-in BRDF and takes none.
    std::set<std::string> notInEnergy = {"albedo", "sigma", "brdf", "param"};
    for (const scene::Param& p : scene::registry())
        if (p.table != scene::Table::Material) notInEnergy.insert(p.name);

    std::set<std::string> covered = untested;
    for (const Case& c : cases) {
        CAPTURE(c.name);
        covered.insert(c.name);
        const scene::Resolved a = resolveWith(c, false), b = resolveWith(c, true);
        const bool scene = !notInScene.count(c.name), energy = !notInEnergy.count(c.name);
        CHECK((scene::sceneKey(a.scene) != scene::sceneKey(b.scene)) == scene);
        CHECK((scene::energyKey(a.scene.brdf) != scene::energyKey(b.scene.brdf)) == energy);
        // The same values give the same key (a .brdf file is keyed by its loaded object: each resolve loads it
        // again, a new key, a new survey, never a stale one).
        if (!a.scene.brdfFile) CHECK(scene::sceneKey(resolveWith(c, false).scene) == scene::sceneKey(a.scene));
    }
    for (const scene::Param& p : scene::registry()) CHECK_MESSAGE(covered.count(p.name), p.name);
    std::remove(other.c_str());
    std::remove(fitsA.c_str());
    std::remove(fitsB.c_str());

    // A measured table: keyed by the object (the survey's cache holds the scene, so the table, while it keys).
    render::Scene flat, measured;
    measured.brdf.measured = std::make_shared<const brdf::merl::MeasuredBrdf>();
    CHECK(scene::sceneKey(flat) != scene::sceneKey(measured));
    CHECK(scene::energyKey(flat.brdf) != scene::energyKey(measured.brdf));
}

TEST_CASE("scene::sceneKey: the scene's fields no parameter sets change it too") {
    const render::Scene s;
    auto differs = [&](auto change) {
        render::Scene t = s;
        change(t);
        return scene::sceneKey(t) != scene::sceneKey(s);
    };
    CHECK(differs([](render::Scene& t) { t.light.chartCenter = dvec3(0, 0, 1); }));
    CHECK(differs([](render::Scene& t) { t.light.ruleTarget = 1e-4; }));
    CHECK(differs([](render::Scene& t) { t.surface.texels = 512; }));
    CHECK(differs([](render::Scene& t) { t.surface.bumpsPerTile = 32; }));
    CHECK(differs([](render::Scene& t) { t.surface.samplesPerPeriod = 8; }));
    // Full precision: a change in the last digit is a different scene.
    CHECK(differs([](render::Scene& t) { t.brdf.roughness = std::nextafter(0.1, 1.0); }));
}
