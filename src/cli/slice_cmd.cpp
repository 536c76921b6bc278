// `hilite brdf slice`: f and f cos(theta_o) in the plane of incidence and across it, several BRDFs overlaid
// (the flags' model, a measured table, --curve entries), as CSV, JSON and plots (experiments/slice.hpp).

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "core/text.hpp"
#include "experiments/plot.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"
#include "hilite/experiments/slice.hpp"
#include "io/image_io.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace hilite::cli {

namespace {

struct SliceFlags {
    SceneOptions scene;
    std::vector<std::string> curves;  ///< --curve "KEY=VALUE KEY=VALUE"
    double step = 0.5;
    bool polar = false, logY = false;
    std::string out;
};

bool materialParam(const scene::Param& p) {
    return p.table == scene::Table::Material && p.name != "brdf" && p.name != "param";
}

/// The curves: the flags' model (unless only --measured names a material), the measured table, each --curve.
std::vector<experiments::SliceCurve> sliceCurves(const SliceFlags& f) {
    const scene::Values given = commandValues(f.scene);
    std::vector<experiments::SliceCurve> curves;
    scene::Values analytic;  // the given values but --measured (the incidence's default kept)
    for (const auto& [name, value] : given.given())
        if (name != "measured") analytic.set(name, value.text, value.origin);
    analytic.setDefault("incidence", given.text("incidence"));
    bool modelGiven = false;
    for (const auto& [name, value] : given.given())
        if (name != "measured" && name != "incidence" && name != "azimuth") modelGiven = true;
    if (!given.given("measured") || modelGiven) {
        const scene::Resolved r = scene::resolve(analytic, scene::Purpose::Brdf);
        std::string label = r.values.text("model");
        for (const char* width : {"roughness", "exponent", "roughness_y"})
            if (analytic.given(width)) label += " " + std::string(width) + "=" + analytic.text(width);
        curves.push_back({label, r});
    }
    if (given.given("measured")) {
        const std::string file = given.text("measured");
        scene::Values table;  // the table is the whole BRDF: only the light's flags apply to it
        for (const char* name : {"measured", "azimuth"})
            if (given.given(name)) table.set(name, given.text(name), given.given().at(name).origin);
        table.setDefault("incidence", given.text("incidence"));
        curves.push_back({"measured " + std::filesystem::path(file).filename().string(),
                          scene::resolve(table, scene::Purpose::Brdf)});
    }
    for (const std::string& spec : f.curves) {
        scene::Values v = analytic;
        std::istringstream in(spec);
        for (std::string kv; in >> kv;) {
            const auto eq = kv.find('=');
            if (eq == std::string::npos || eq == 0)
                throw InputError("--curve '" + printable(spec) +
                                 "': give KEY=VALUE pairs (e.g. \"model=beckmann "
                                 "roughness=0.08\"), '" +
                                 printable(kv) + "' is not one");
            const std::string key = kv.substr(0, eq);
            const scene::Param* p = scene::find(key);
            if (!p || !materialParam(*p))
                throw InputError("--curve '" + printable(spec) + "': '" + printable(key) +
                                 "' is not a material parameter (model, roughness, exponent, fresnel, f0, ...)");
            v.set(key, kv.substr(eq + 1), "--curve");
        }
        curves.push_back({spec, scene::resolve(v, scene::Purpose::Brdf)});
    }
    return curves;
}

int runSlice(const SliceFlags& f) {
    if (f.out.empty()) throw InputError("-o: give the folder for slice.csv, slice.json and the plots");
    const auto curves = sliceCurves(f);  // every curve resolved (and refused) before anything is written
    const scene::Resolved first = curves.front().scene;
    const auto points = experiments::brdfSlices(curves, first.angles, f.step);
    io::checkOutputDir(f.out, "-o");
    const std::vector<std::string> files = {"slice.csv", "slice.json", "slice_in.png", "slice_across.png"};
    if (std::filesystem::is_directory(f.out))
        for (const auto& file : files) io::checkWritable(f.out + "/" + file, "-o");
    io::makeOutputDir(f.out, "-o");
    const auto& columns = experiments::sliceColumns();
    std::string csv = experiments::csvHeaderLine(columns);
    nlohmann::json all = nlohmann::json::array();
    std::vector<nlohmann::json> rows[2];
    for (const auto& p : points) {
        nlohmann::json j = experiments::toJson(p);
        csv += experiments::csvRowLine(columns, j);
        all.push_back(j);
        std::ostringstream series;
        series << p.curve << ", theta_i " << p.incidenceDeg;
        j["series"] = series.str();
        rows[p.plane == "in" ? 0 : 1].push_back(j);
    }
    io::writeFileAtomic(f.out + "/slice.csv", csv);
    io::writeFileAtomic(f.out + "/slice.json", all.dump(1) + "\n");
    for (int k = 0; k < 2; ++k) {
        experiments::PlotSpec spec;
        spec.file = k == 0 ? "slice_in.png" : "slice_across.png";
        spec.title = k == 0 ? "f cos(theta_o) in the plane of incidence (the mirror direction at +theta_i)"
                            : "f cos(theta_o) across the plane of incidence, through the mirror direction";
        spec.x = "angle_deg", spec.y = "f_cos", spec.series = "series";
        spec.xlabel = k == 0 ? "theta_o (deg), signed: + on the mirror side" : "angle from the mirror direction (deg)";
        spec.ylabel = "f cos(theta_o) (1/sr, luminance)";
        spec.key = "top left", spec.logy = f.logY, spec.polar = f.polar;
        std::string why;
        if (!experiments::plot(f.out, spec, rows[k], why))
            std::cerr << "hilite: " << spec.file << " not made: " << why << "\n";
    }
    std::cout << "wrote " << f.out << "/slice.csv, slice.json, slice_in.png, slice_across.png: " << curves.size()
              << " curve(s) x " << first.angles.size() << " incidence(s) x 2 planes, every " << f.step << " deg\n";
    return 0;
}

}  // namespace

std::pair<CLI::App*, Action> addBrdfSlice(CLI::App& app) {
    CLI::App* sub = app.add_subcommand(
        "slice", "f and f cos(theta_o) in the plane of incidence and across it, BRDFs overlaid (CSV, JSON, PNG)");
    auto f = std::make_shared<SliceFlags>();
    f->scene.defaults["incidence"] = "60";
    addParamFlags(*sub, f->scene, [](const scene::Param& p) {
        return materialParam(p) || p.name == "incidence" || p.name == "azimuth";
    });
    sub->add_option("--curve", f->curves,
                    "another BRDF overlaid: \"KEY=VALUE ...\" of material parameters over the flags' (repeatable)");
    sub->add_option("--step", f->step, "angle step (deg), in (0, 10]")->capture_default_str();
    sub->add_flag("--polar", f->polar, "polar plots (the normal up) instead of Cartesian");
    sub->add_flag("--log", f->logY, "a logarithmic f axis");
    sub->add_option("-o,--output", f->out, "folder for slice.csv, slice.json, slice_in.png, slice_across.png");
    sub->footer(
        "Example: hilite brdf slice --model ggx --roughness 0.1 --incidence 30,60 --curve \"model=beckmann "
        "roughness=0.1\" -o slices");
    return {sub, [f] { return runSlice(*f); }};
}

}  // namespace hilite::cli
