// `hilite brdf inspect FILE`: what a measured file (MERL .binary, RGL .bsdf) says of itself and what a user
// checks first (brdf/inspect.hpp), as a report or, with --json, one JSON object.

#include "brdf/inspect.hpp"
#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "hilite/core/error.hpp"

#include <nlohmann/json.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace hilite::cli {

namespace {

struct InspectFlags {
    SceneOptions scene;
    std::string file;
    bool json = false;
};

nlohmann::ordered_json toJson(const brdf::Inspection& in) {
    nlohmann::ordered_json j;
    j["file"] = in.path;
    j["format"] = in.format;
    j["description"] = in.description;
    j["theta_i_nodes_deg"] = in.thetaINodesDeg;
    j["phi_i_nodes_deg"] = in.phiINodesDeg;
    j["tables"] = in.resolution;
    j["missing"] = in.missing;
    j["missing_of"] = in.total;
    j["most_negative_rgb"] = in.mostNegative;
    j["reciprocity"] = {{"pairs", in.reciprocity.pairs},
                        {"median", in.reciprocity.median},
                        {"p95", in.reciprocity.p95},
                        {"max", in.reciprocity.max}};
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& r : in.incidences)
        rows.push_back({{"theta_deg", r.thetaDeg},
                        {"albedo", {r.albedo.x, r.albedo.y, r.albedo.z}},
                        {"peak_theta_o_deg", r.peakThetaODeg},
                        {"peak_phi_o_deg", r.peakPhiODeg},
                        {"peak_offset_deg", r.peakOffsetDeg}});
    j["incidences"] = rows;
    return j;
}

void printReport(const brdf::Inspection& in) {
    auto list = [](const std::vector<double>& v) {
        std::ostringstream s;
        for (size_t i = 0; i < v.size(); ++i) s << (i ? " " : "") << std::setprecision(4) << v[i];
        return s.str();
    };
    std::cout << "file:         " << in.path << "\n";
    if (in.format == "rgl") {
        std::cout << "format:       RGL .bsdf (Dupuy & Jakob 2018), tables indexed by the light direction\n"
                  << "description:  " << in.description << "\n"
                  << "theta_i:      " << list(in.thetaINodesDeg) << " deg (the incidences measured)\n"
                  << "phi_i:        " << list(in.phiINodesDeg) << " deg\n"
                  << "tables:       " << in.resolution << "\n"
                  << "missing:      " << in.missing << " of " << in.total
                  << " rgb nodes not marked valid (the lookup uses them as stored)\n"
                  << "negative rgb: most negative " << in.mostNegative << " (clipped to 0)\n";
    } else {
        std::cout << "format:       MERL .binary (Matusik et al. 2003); no description in the format\n"
                  << "tables:       " << in.resolution << "\n"
                  << "missing:      " << in.missing << " of " << in.total << " bins without data\n";
    }
    const brdf::Reciprocity& r = in.reciprocity;
    std::cout << "reciprocity:  |Y(f(a, b)) - Y(f(b, a))| / max over " << r.pairs
              << " pairs within 80 deg of the normal: median " << r.median << ", 95% " << r.p95 << ", max " << r.max
              << "\n"
              << "# theta_deg    albedo_r    albedo_g    albedo_b  peak_theta_o  peak_phi_o  peak_offset_deg"
                 "\n# (the peak of f cos theta_o on a 0.25 x 0.5 deg scan of theta_o, phi_o; its angle from the mirror "
                 "direction)\n";
    for (const auto& row : in.incidences)
        std::cout << std::setw(11) << row.thetaDeg << std::setw(12) << row.albedo.x << std::setw(12) << row.albedo.y
                  << std::setw(12) << row.albedo.z << std::setw(14) << row.peakThetaODeg << std::setw(12)
                  << row.peakPhiODeg << std::setw(17) << row.peakOffsetDeg << "\n";
}

int runInspect(const InspectFlags& f) {
    scene::Values v = commandValues(f.scene);
    v.set("measured", f.file, "FILE");
    const scene::Resolved r = scene::resolve(v, scene::Purpose::Brdf);  // reads and checks the file
    const brdf::Inspection in = brdf::inspect(r.scene.brdf, r.angles, r.scene.light.azimuthDeg);
    if (f.json) std::cout << toJson(in).dump() << "\n";
    else printReport(in);
    return 0;
}

}  // namespace

std::pair<CLI::App*, Action> addBrdfInspect(CLI::App& app) {
    CLI::App* sub = app.add_subcommand(
        "inspect",
        "a measured file (MERL .binary, RGL .bsdf): description, incidences, missing values, albedo, "
        "the peak's offset from the mirror direction, reciprocity");
    auto f = std::make_shared<InspectFlags>();
    f->scene.defaults["incidence"] = "0:80:10";
    addParamFlags(*sub, f->scene, [](const scene::Param& p) { return p.name == "incidence" || p.name == "azimuth"; });
    sub->add_option("FILE", f->file, "the measured file (told apart by content)")->required();
    sub->add_flag("--json", f->json, "one JSON object instead of the report");
    sub->footer("Example: hilite brdf inspect paper_white_rgb.bsdf --incidence 0,30,60 --json");
    return {sub, [f] { return runInspect(*f); }};
}

}  // namespace hilite::cli
