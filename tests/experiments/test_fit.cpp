// Fitting in-process, as `hilite fit` and `hilite run` with [fit] call the experiments library: tables
// tabulated from each built-in model are fitted back to the model and the parameters that made them (the fit's
// own truth: the generating model), Phong's aspect residual against a GGX table grows with incidence (the
// seed's prediction), the fit_models experiment and its refusals. `hilite fit`'s own flag refusals (exit 2,
// nothing written): tests/cli/test_fit_cli.cpp.

#include "brdf/merl.hpp"
#include "core/text.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/experiments/fit.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include "support/near.hpp"
#include "support/rgl_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

using namespace hilite;
using namespace hilite::testing;

namespace {

/// `hilite brdf tabulate ARGS -o FILE` (src/cli/brdf_cmd.cpp): the MERL table of the resolved terms.
void tabulate(const std::string& args, const std::string& file) {
    const brdf::Params p = scene::resolve(flags(args), scene::Purpose::Brdf).scene.brdf;
    REQUIRE_FALSE(p.anisotropic());
    std::ofstream(file, std::ios::binary) << brdf::merl::encode(brdf::merl::tabulate(p));
}

/// `--models M --thresholds T` (empty: fit's defaults).
experiments::FitOptions options(const std::string& models, const std::vector<double>& thresholds = {}) {
    experiments::FitOptions o;
    o.models = split(models, ',');
    if (!thresholds.empty()) o.thresholds = thresholds;
    return o;
}

/// `hilite fit ARGS [--target FILE]` with `o` (src/cli/fit_cmd.cpp): its defaults under the flags, the target's
/// material, the options checked, then the fit in the test process's session.
experiments::FitResult fit(const std::string& args, const std::string& target, const experiments::FitOptions& o) {
    scene::Values values = flags(args);
    values.setDefault("incidence", "0:85:5");
    values.setDefault("size", "256");
    if (!target.empty()) {
        const std::string ext = std::filesystem::path(target).extension().string();
        REQUIRE((ext == ".binary" || ext == ".brdf"));
        values.set(ext == ".binary" ? "measured" : "brdf", target, "--target");
    }
    experiments::checkFitOptions(o);
    return experiments::fitModels(session(), values, o);
}

/// The lines `hilite fit --json` prints: one object per model.
std::vector<nlohmann::json> jsonLines(const experiments::FitResult& r) {
    std::vector<nlohmann::json> v;
    for (const auto& m : r.fits) v.push_back(nlohmann::json::parse(experiments::toJson(r, m).dump()));
    return v;
}

/// A smaller sweep than the default (0:85:5 x 5 thresholds) so the suite stays short; the README and the
/// benchmark run the default.
const char* kSweep = "--incidence 0:80:20 --size 128";

}  // namespace

TEST_CASE("fit: each built-in model's table is fitted back to its model (rank 1) and parameter within 1%") {
    hilite_test::TempDir dir("hilite-fit");
    struct Case {
        std::string model, param;
        double value;
    };
    const Case cases[] = {{"phong", "exponent", 200},
                          {"blinn", "exponent", 300},
                          {"beckmann", "roughness", 0.08},
                          {"ggx", "roughness", 0.1}};
    for (const Case& c : cases) {
        CAPTURE(c.model);
        const std::string file = dir / (c.model + ".binary");
        std::ostringstream v;
        v << c.value;
        tabulate("--model " + c.model + " --" + c.param + " " + v.str(), file);
        const auto fits = jsonLines(fit(kSweep, file, options("phong,blinn,beckmann,ggx", {0.1, 0.5, 0.9})));
        REQUIRE(fits.size() == 4);
        std::map<std::string, nlohmann::json> by;
        for (const auto& f : fits) by[f["model"]] = f;
        const auto& own = by.at(c.model);
        MESSAGE(c.model << " " << c.value << ": fitted " << own["params"].dump() << ", residual " << own["residual"]
                        << "; the others: " << [&] {
                               std::string s;
                               for (const auto& [m, f] : by) s += m + " " + f["residual"].dump() + " ";
                               return s;
                           }());
        CHECK(own["rank"] == 1);
        const double got = own["params"][c.param].get<double>();
        CHECK_NEAR(got / c.value, 1, 0.01);
        for (const auto& [m, f] : by)
            CHECK(f["params"].contains(m == "phong" || m == "blinn" ? "exponent" : "roughness"));
    }
}

TEST_CASE("fit: the defaults recover the generator of a table with Fresnel, masking and a diffuse part") {
    // Before: Beckmann 0.15 + Smith + Schlick 0.04 + Lambert 0.1 ranked GGX first and Beckmann third (m 0.115),
    // every residual 0.58, as the defaults fitted the lobe alone (no F, implicit G, no diffuse).
    hilite_test::TempDir dir("hilite-fit-defaults");
    const brdf::Params gold = scene::resolve(flags("--model ggx --material gold"), scene::Purpose::Brdf).scene.brdf;
    const double goldF0 = brdf::luminance(brdf::fresnel(gold, 1.0));  // Schlick's F0 is F at normal incidence
    struct Case {
        std::string args, model, width;
        double value, f0, albedo;  ///< f0, albedo < 0: not checked
        std::string geometry;
    };
    const Case cases[] = {
        {"--model beckmann --roughness 0.15 --geometry smith --fresnel schlick --f0 0.04 --diffuse lambert --albedo "
         "0.1",
         "beckmann", "roughness", 0.15, 0.04, 0.1, "smith"},
        {"--model ggx --roughness 0.3 --geometry smith --material gold", "ggx", "roughness", 0.3, goldF0, -1, "smith"},
        {"--model blinn --exponent 300", "blinn", "exponent", 300, 1.0, -1, "implicit"},  // F = 1, implicit G
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const std::string file = dir / (c.model + ".binary");
        tabulate(c.args, file);
        const experiments::FitResult r = fit("--incidence 0:80:10 --size 128", file, experiments::FitOptions{});
        const auto fits = jsonLines(r);
        MESSAGE(c.model << ": " << fits[0]["model"] << " " << fits[0]["params"].dump() << " shape "
                        << fits[0]["shape_residual"] << " values " << fits[0]["values_residual"] << ", verdict "
                        << r.verdict << "; second " << fits[1]["model"] << " " << fits[1]["shape_residual"]);
        REQUIRE(fits[0]["model"] == c.model);
        CHECK(fits[0]["rank"] == 1);
        const auto& p = fits[0]["params"];
        CHECK_NEAR(p[c.width].get<double>() / c.value, 1, 0.01);
        CHECK_NEAR(p["f0"].get<double>() / c.f0, 1, 0.05);
        CHECK(p["geometry"] == c.geometry);
        if (c.albedo > 0) CHECK_NEAR(p["albedo"].get<double>() / c.albedo, 1, 0.05);
        else CHECK_FALSE(p.contains("albedo"));  // no diffuse part: none fitted
        CHECK(fits[0]["values_residual"].get<double>() < fits[1]["values_residual"].get<double>());
    }
}

TEST_CASE("fit: the literature's models (abc, sgd, lafortune) are fitted back from the tables they make") {
    // Each tabulated (MERL binning) with a Lambertian body and fitted alone with the defaults: its width, its second
    // shape parameter (abc C, sgd p), its height and the albedo come back (SGD's F and G1, ABC's eta held at the
    // defaults, the target's here). ABC's B and C trade against each other (the lobe's width is about
    // 1 / sqrt(B C)): each within 5%, their product within 1%.
    hilite_test::TempDir dir("hilite-fit-literature");
    struct Case {
        std::string args, model;
        std::map<std::string, double> want;  ///< parameter: value (each within `tolerance` of it)
        double tolerance;
    };
    const Case cases[] = {
        {"--model abc --abc-a 40 --abc-b 2000 --abc-c 1.4 --diffuse lambert --albedo 0.1",
         "abc",
         {{"abc_b", 2000}, {"abc_c", 1.4}, {"abc_a", 40}, {"albedo", 0.1}},
         0.05},
        {"--model sgd --sgd-alpha 0.03 --sgd-p 0.7 --sgd-rho-s 0.4 --diffuse lambert --albedo 0.1",
         "sgd",
         {{"sgd_alpha", 0.03}, {"sgd_p", 0.7}, {"sgd_rho_s", 0.4}, {"albedo", 0.1}},
         0.02},
        {"--model lafortune --exponent 300 --lafortune-rho-s 0.5 --diffuse lambert --albedo 0.1",
         "lafortune",
         {{"exponent", 300}, {"lafortune_rho_s", 0.5}, {"albedo", 0.1}},
         0.02},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const std::string file = dir / (c.model + ".binary");
        tabulate(c.args, file);
        const auto fits = jsonLines(fit("--incidence 0:80:20 --size 128", file, options(c.model, {0.25, 0.5, 0.75})));
        REQUIRE(fits.size() == 1);
        MESSAGE(c.model << ": " << fits[0]["params"].dump() << " shape " << fits[0]["shape_residual"] << " values "
                        << fits[0]["values_residual"]);
        for (const auto& want : c.want) {
            const std::string& name = want.first;
            const double value = want.second;
            CAPTURE(name);
            REQUIRE(fits[0]["params"].contains(name));
            CHECK_NEAR(fits[0]["params"][name].get<double>() / value, 1, c.tolerance);
        }
        if (c.model == "abc")
            CHECK_NEAR(fits[0]["params"]["abc_b"].get<double>() * fits[0]["params"]["abc_c"].get<double>() / 2800, 1,
                       0.01);
        CHECK(fits[0]["shape_residual"].get<double>() < 0.02);
    }
}

TEST_CASE("fit: --fit-color fits F0 and the albedo per channel: gold's F(0) and a red plastic's albedo") {
    hilite_test::TempDir dir("hilite-fit-color");
    const brdf::Params gold = scene::resolve(flags("--model ggx --material gold"), scene::Purpose::Brdf).scene.brdf;
    const dvec3 goldF0 = brdf::fresnel(gold, 1.0);  // linear sRGB: red above 1 (gold is outside the gamut there)
    experiments::FitOptions o = options("ggx");
    o.color = true;
    tabulate("--model ggx --roughness 0.3 --geometry smith --material gold", dir / "gold.binary");
    const auto g = jsonLines(fit(kSweep, dir / "gold.binary", o));
    MESSAGE("gold: " << g[0]["params"].dump() << ", F(0) " << goldF0.x << " " << goldF0.y << " " << goldF0.z);
    REQUIRE(g[0]["params"]["f0"].is_array());
    for (int c = 0; c < 3; ++c)  // Schlick's F0 is at most 1
        CHECK_NEAR(g[0]["params"]["f0"][size_t(c)].get<double>() / std::min(goldF0[c], 1.0), 1, 0.05);
    CHECK_NEAR(g[0]["params"]["roughness"].get<double>() / 0.3, 1, 0.01);
    tabulate("--model beckmann --roughness 0.15 --geometry smith --f0 0.04 --diffuse lambert --albedo 0.5,0.1,0.05",
             dir / "red.binary");
    o.models = {"beckmann"};
    const auto p = jsonLines(fit(kSweep, dir / "red.binary", o));
    MESSAGE("red plastic: " << p[0]["params"].dump());
    const double albedo[3] = {0.5, 0.1, 0.05};
    for (int c = 0; c < 3; ++c) CHECK_NEAR(p[0]["params"]["albedo"][size_t(c)].get<double>() / albedo[c], 1, 0.05);
    CHECK_NEAR(p[0]["params"]["roughness"].get<double>() / 0.15, 1, 0.01);
}

TEST_CASE("fit: a narrow plus a wide lobe gets no_model_fits, and two models within the resolution get tie") {
    hilite_test::TempDir dir("hilite-fit-verdicts");
    // GGX 0.08 plus three times GGX 0.25 (Smith, Schlick 0.04): no single lobe has both the core and the shoulder
    // (the wide lobe's peak is a quarter of the narrow one's, so the thresholds see both).
    auto table = [](const std::string& args) {
        return brdf::merl::tabulate(scene::resolve(flags(args), scene::Purpose::Brdf).scene.brdf);
    };
    brdf::merl::MeasuredBrdf sum = table("--model ggx --roughness 0.08 --geometry smith --f0 0.04");
    const brdf::merl::MeasuredBrdf wide = table("--model ggx --roughness 0.25 --geometry smith --f0 0.04");
    for (size_t i = 0; i < sum.raw.size(); ++i)
        if (sum.raw[i] >= 0 && wide.raw[i] >= 0) sum.raw[i] += 3 * wide.raw[i];
    const std::string file = dir / "two_lobes.binary";
    std::ofstream(file, std::ios::binary) << brdf::merl::encode(sum);
    const experiments::FitResult two = fit(kSweep, file, options("beckmann,ggx"));
    MESSAGE("two lobes: " << two.fits[0].model << " shape " << two.fits[0].shapeResidual << ", values "
                          << two.fits[0].valuesResidual << ", resolution " << two.resolution << ", tolerance "
                          << two.tolerance);
    CHECK(two.verdict == "no_model_fits");
    CHECK(two.fits[0].residual > two.tolerance);
    for (const auto& j : jsonLines(two)) CHECK(j["verdict"] == "no_model_fits");
    // Beckmann 0.03 and Blinn-Phong of matched width differ by less than the measurement resolves (2e-4 here,
    // against a resolution of 8e-4 at 128 px): a tie, both marked; the generator first.
    const experiments::FitResult tie =
        fit(std::string("--model beckmann --roughness 0.03 ") + kSweep, "", options("blinn,beckmann"));
    MESSAGE("tie: " << tie.fits[0].model << " " << tie.fits[0].residual << ", " << tie.fits[1].model << " "
                    << tie.fits[1].residual << ", margin " << tie.tieMargin);
    CHECK(tie.verdict == "tie");
    CHECK(tie.fits[0].model == "beckmann");
    CHECK((tie.fits[0].tie && tie.fits[1].tie));
    CHECK(tie.fits[1].residual - tie.fits[0].residual < tie.tieMargin);
    for (const auto& j : jsonLines(tie)) CHECK(j["tie"] == true);
}

TEST_CASE("fit: Phong fitted to a GGX table leaves an aspect residual that grows with incidence") {
    hilite_test::TempDir dir("hilite-fit-phong");
    const std::string file = dir / "ggx.binary";
    tabulate("--model ggx --roughness 0.1", file);
    // To 70 deg: beyond, GGX 0.1's region reaches the horizon (horizon_cut), a sample the fit leaves out.
    const experiments::FitResult result = fit("--incidence 0:70:10 --size 128", file, options("phong,ggx"));
    std::filesystem::create_directories(dir / "out");  // `-o DIR`: the folder made, then the fit written into it
    std::string why;
    CHECK(experiments::writeFitFolder(dir / "out", result, why));
    const auto fits = jsonLines(result);
    REQUIRE(fits.size() == 2);
    REQUIRE(fits[0]["model"] == "ggx");  // ranked
    const auto& phong = fits[1];
    REQUIRE(phong["model"] == "phong");
    const auto& res = phong["aspect_residual"];
    REQUIRE(res.size() == 8);
    MESSAGE("phong's aspect residual, 0..70 deg: " << res.dump());
    CHECK_NEAR(res[0].get<double>(), 0.0, 1e-3);  // round at normal incidence, both
    for (size_t i = 1; i < res.size(); ++i) CHECK(res[i].get<double>() > res[i - 1].get<double>());
    // Phong stays round while GGX narrows towards cos(theta_i): at 70 deg the residual is most of 1 - cos.
    CHECK(res[7].get<double>() > 0.5 * (1 - std::cos(70 * M_PI / 180)));
    CHECK(fits[0]["rank"] == 1);
    for (const char* f : {"fit.json", "fit.csv"})
        CHECK(std::filesystem::exists(std::filesystem::path(dir / "out") / f));
    // One colour per model in both plots (the aspect plot has the target's series first, the residual plot not).
    auto colourOf = [&](const std::string& script, const std::string& series) {
        std::ifstream in(std::filesystem::path(dir / "out") / script);
        const std::string gp((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const size_t title = gp.find("title '" + series);  // "ggx (rank 1) (on target)": it lies on the target
        REQUIRE(title != std::string::npos);
        const size_t rgb = gp.rfind("lc rgb '", title);
        REQUIRE(rgb != std::string::npos);
        return gp.substr(rgb + 8, 7);
    };
    for (const char* series : {"ggx (rank 1)", "phong (rank 2)"}) {
        CAPTURE(series);
        CHECK(colourOf("fit_aspect.gp", series) == colourOf("fit_residual.gp", series));
    }
}

TEST_CASE("fit: the fit_models experiment over a folder of tables writes the ranking, and a bad fit table is refused") {
    hilite_test::TempDir dir("hilite-fit-exp");
    std::filesystem::create_directories(std::filesystem::path(dir / "tables"));
    tabulate("--model blinn --exponent 300", dir / "tables/a_blinn.binary");
    tabulate("--model ggx --roughness 0.1", dir / "tables/b_ggx.binary");
    { std::ofstream(dir / "tables/notes.txt") << "not a table"; }  // other files in the folder are not targets
    const std::string head =
        "[experiment]\nname = \"fit_folder\"\n[scene.light]\nincidence = \"0:80:20\"\n"
        "[scene.camera]\nsize = \"128\"\n[[sweep]]\nkey = \"material.measured\"\nfolder = \"tables\"\n";
    { std::ofstream(dir / "fit.toml") << head << "[fit]\nmodels = [\"blinn\", \"ggx\"]\nthresholds = [0.25, 0.75]\n"; }
    const std::string out = dir / "out";
    runExperiment(dir / "fit.toml", out);
    std::ifstream rows(std::filesystem::path(out) / "results.jsonl");
    std::vector<nlohmann::json> got;
    for (std::string line; std::getline(rows, line);)
        if (!line.empty()) got.push_back(nlohmann::json::parse(line));
    REQUIRE(got.size() == 2);  // the two .binary files, in name order
    CHECK(got[0]["target"].get<std::string>().find("a_blinn.binary") != std::string::npos);
    CHECK(got[0]["best_model"] == "blinn");
    CHECK(got[1]["best_model"] == "ggx");
    CHECK(got[0]["blinn_rank"] == 1);
    CHECK(got[1]["ggx_residual"].get<double>() < got[1]["blinn_residual"].get<double>());
    CHECK(got[1]["ggx_at_bound"] == "");  // a column each model has: its parameters at their search bound
    std::ifstream summary(std::filesystem::path(out) / "summary.md");
    const std::string md((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
    CHECK(md.find("## Which model fits") != std::string::npos);
    CHECK(md.find("First place: blinn 1; ggx 1; of 2 targets.") != std::string::npos);

    struct Case {
        std::string text, message;
    };
    const Case bad[] = {
        {head + "[fit]\nmodels = [\"blinn\", \"foo\"]\n", "fit.models: 'foo' is not a model"},
        {head + "[fit]\nthresholds = [0.5, 2]\n", "fit.thresholds: each must be in (0, 1)"},
        {head + "[fit]\nweights = [1]\n", "fit.weights: one per threshold"},
        {head + "[fit]\ngeometry = \"bogus\"\n", "fit.geometry: 'bogus'"},
        {head + "[fit]\nmodels = [\"ggx\"]\n[match]\nmaterial.model = \"ggx\"\n", "[match]: not with [fit]"},
        {"[experiment]\nname = \"x\"\n[[sweep]]\nkey = \"material.measured\"\nfolder = \"nowhere\"\n[fit]\n",
         "is not a folder"},
        {"[experiment]\nname = \"x\"\n[[sweep]]\nkey = \"material.measured\"\nfolder = \".\"\n[fit]\n",
         "holds no .binary or .bsdf file"},
        {"[experiment]\nname = \"x\"\n[[sweep]]\nkey = \"material.roughness\"\nfolder = \"tables\"\n[fit]\n",
         "folder: lists files for"},
    };
    for (const Case& c : bad) {
        CAPTURE(c.text);
        { std::ofstream(dir / "bad.toml") << c.text; }
        const std::string badOut = dir / "bad_out";
        const std::string why = runRefusal(dir / "bad.toml", badOut);
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.message) != std::string::npos);
        CHECK(!std::filesystem::exists(badOut));
    }
}

/// This process's resident memory now (VmRSS), in MB.
double residentMb() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
    return -1;
}

TEST_CASE("fit: a folder of tables is measured and fitted holding at most 3 tables at once, memory flat") {
    // Before, every table measured stayed in memory (400 MB each): 40 of them ran out of memory. A sweep now
    // holds the current table and the 2 most recent (brdf/merl.cpp), and gives a freed table's pages back: 100
    // tables fitted peaked at 1.51 GB, 329 MB since (docs/speed.md). Symlinks: each is its own path, read again.
    hilite_test::TempDir dir("hilite-fit-held");
    tabulate("--model ggx --roughness 0.2", dir / "ggx.binary");
    auto sweep = [&](const std::string& name, int tables) {
        std::filesystem::create_directories(std::filesystem::path(dir / name));
        for (int i = 0; i < tables; ++i)
            std::filesystem::create_symlink(std::string(dir / "ggx.binary"),
                                            std::string(dir / (name + "/t" + std::to_string(i) + ".binary")));
        std::ofstream(dir / (name + ".toml"))
            << "[experiment]\nname = \"held\"\n[scene.light]\nincidence = \"0:60:60\"\n[scene.camera]\nsize = "
               "\"64\"\n[[sweep]]\nkey = \"material.measured\"\nfolder = \""
            << name
            << "\"\n[fit]\nmodels = [\"ggx\"]\nthresholds = [0.5]\n"
               "f0 = false\ngeometry = \"implicit\"\ndiffuse = \"off\"\n";  // the lobe's width alone: quick
        brdf::merl::tablesHeld(true);                                       // the peak from here on
        runExperiment(dir / (name + ".toml"), dir / (name + "_out"));
        std::ifstream rows(std::filesystem::path(dir / (name + "_out")) / "results.jsonl");
        int n = 0;
        for (std::string line; std::getline(rows, line);) n += !line.empty();
        CHECK(n == tables);
        const auto held = brdf::merl::tablesHeld();
        CHECK(held.peak >= 1);
        CHECK(held.peak <= 3);
        return residentMb();
    };
    const double after4 = sweep("four", 4), after34 = sweep("thirty", 30);
    // 30 more tables leave memory where 4 left it, within less than one table's doubles (35 MB): measured -1 to
    // +0.2 MB. Before glibc's thresholds were fixed (brdf/merl.cpp), 0 to +97 MB from run to run: the tables'
    // big buffers came from a heap whose holes it keeps.
    INFO("VmRSS after 4 tables " << after4 << " MB, after 30 more " << after34 << " MB");
#if defined(__SANITIZE_ADDRESS__)
    (void)after4, (void)after34;  // AddressSanitizer's quarantine holds freed memory on purpose (256 MB)
#else
    CHECK(after34 - after4 < 30.0);
#endif
}

TEST_CASE("fit: a .brdf target (framed blind, no twin) fits back to its model") {
    const std::string file = std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/ggx.brdf";  // GGX alpha 0.1
    const auto fits = jsonLines(fit("--incidence 0:80:20", file, options("ggx,beckmann", {0.25, 0.5, 0.75})));
    REQUIRE(fits.size() == 2);
    CHECK(fits[0]["model"] == "ggx");
    CHECK(fits[0]["rank"] == 1);
    CHECK(fits[0]["target"] == "brdf:" + file);
    CHECK_NEAR(fits[0]["params"]["roughness"].get<double>() / 0.1, 1, 0.01);  // measured: 0.100016
}

TEST_CASE("fit: --fit-anisotropy recovers both roughnesses, --fit-f0 Schlick's F0") {
    const std::string sweep = " --incidence 0:80:20";
    experiments::FitOptions aniso = options("ggx", {0.25, 0.5, 0.75}), f0 = aniso;
    aniso.anisotropy = true;  // --fit-anisotropy
    f0.f0 = true;             // --fit-f0
    // Measured: 0.100012 x 0.200011 (from both splits of the target's aspect at 0 deg; an isotropic start stalled
    // at 0.148 x 0.139), and F0 0.49989 with roughness 0.100009.
    const auto a = jsonLines(fit("--model ggx --roughness 0.1 --roughness-y 0.2" + sweep, "", aniso));
    REQUIRE(a.size() == 1);
    CHECK_NEAR(a[0]["params"]["roughness"].get<double>() / 0.1, 1, 0.01);
    CHECK_NEAR(a[0]["params"]["roughness_y"].get<double>() / 0.2, 1, 0.01);
    const auto f = jsonLines(fit("--model ggx --roughness 0.1 --fresnel schlick --f0 0.5" + sweep, "", f0));
    REQUIRE(f.size() == 1);
    CHECK_NEAR(f[0]["params"]["roughness"].get<double>() / 0.1, 1, 0.01);
    CHECK_NEAR(f[0]["params"]["f0"].get<double>() / 0.5, 1, 0.01);
}

TEST_CASE("fit: a threshold whose level underflows float is refused in one line, not fitted at a search bound") {
    // Before: --thresholds 1e-300 ranked ggx at its bound (roughness 0.001) first against GGX 0.1, residual 2.1e-3.
    const std::string why = inputError([] {
        fit("--model ggx --roughness 0.1 --incidence 30 --size 64", "", options("ggx", {1e-300, 0.5}));
    });
    CAPTURE(why);
    CHECK(oneLine(why));
    CHECK(why.rfind("--thresholds: 1e-300 cannot be measured", 0) == 0);
    CHECK(why.find("float_underflow") != std::string::npos);
    // A threshold whose level stays a normal float still fits back to the target.
    const auto r = fit("--model ggx --roughness 0.1 --incidence 30 --size 64", "", options("ggx", {1e-20, 0.5}));
    CHECK(r.fits.at(0).params.at("roughness").get<double>() == doctest::Approx(0.1).epsilon(0.05));
}

TEST_CASE("fit: a parameter at its search bound is named (at_bound), never passed as the target's value") {
    // Beckmann m 0.0006 is narrower than GGX's lowest roughness (0.001) and Phong's highest exponent (1e6): each
    // fit stops at its bound. Before, the rows read "roughness=0.001", "exponent=1e+06" as answers.
    const auto narrow =
        fit("--model beckmann --roughness 0.0006 --incidence 0:60:30 --size 128", "", options("ggx,phong"));
    for (const auto& m : narrow.fits) {
        CAPTURE(m.model);
        const std::string width = m.model == "ggx" ? "roughness" : "exponent";
        REQUIRE(m.atBound.size() >= 1);
        CHECK(m.atBound.front() == width);
    }
    for (const auto& j : jsonLines(narrow))
        CHECK(j["at_bound"].at(0) == (j["model"] == "ggx" ? "roughness" : "exponent"));
    // A fit inside its bounds names none.
    const auto inside = fit("--model ggx --roughness 0.1 --incidence 30 --size 64", "", options("ggx"));
    CHECK(inside.fits.at(0).atBound.empty());
    CHECK(jsonLines(inside).at(0)["at_bound"].empty());
}

TEST_CASE("fit: real materials get the verdicts the README reports") {
    // The README's table at a smaller sweep (mirror lobe, 0:60:30 at 96^2): a glossy vinyl film has a lobe no
    // single model follows (no_model_fits: GGX 27% off at 128^2); by values GGX with a Lambertian body fits the
    // paper (7.1e-3). (The paint's target_unresolved needs the grazing angles: at 0:60:30 its resolution is 2e-3.)
    const std::string dir = hilite_test::sharedMeasured();
    struct Case {
        std::string file, rankBy, verdict;
    };
    const Case cases[] = {{"cc_ibiza_sunset_rgb.bsdf", "shape", "no_model_fits"},
                          {"paper_white_rgb.bsdf", "values", "fits"}};
    for (const Case& c : cases) {
        const std::string file = dir + "/" + c.file;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        CAPTURE(c.file);
        experiments::FitOptions o;
        o.rankBy = c.rankBy;
        scene::Values values = flags("--lobe mirror --incidence 0:60:30 --size 96");
        values.set("measured", file, "--target");
        const experiments::FitResult r = experiments::fitModels(session(), values, o);
        MESSAGE(c.file << " by " << c.rankBy << ": " << r.verdict << ", " << r.fits[0].model << " "
                       << r.fits[0].residual << ", resolution " << r.resolution);
        CHECK(r.verdict == c.verdict);
    }
}
