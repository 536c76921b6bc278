// `hilite measure`: the highlight's shape per angle of incidence, as a table or JSON lines.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/scene/registry.hpp"
#include "io/image_io.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

struct MeasureFlags {
    SceneOptions scene;
    bool json = false;
    std::string csv;  ///< --csv FILE, or "-" for stdout
};

void printTableHeader() {
    std::printf("%-9s %6s %8s %8s %9s %9s %7s %8s %8s %8s %8s  %-s\n", "model", "theta", "aspect", "ecc", "major",
                "minor", "orient", "cu", "cv", "fwhm_u", "fwhm_v", "flags");
}

/// printf text of `v`, or "-" in the same width when it is not a number.
std::string cell(double v, const char* format, int width) {
    char buf[48];
    if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%*s", width, "-");
    else std::snprintf(buf, sizeof buf, format, width, v);
    return buf;
}

void printTableRow(const nlohmann::json& j) {
    std::string flags;
    for (const auto& fl : j["flags"]) flags += (flags.empty() ? "" : ",") + fl.get<std::string>();
    auto num = [&](const char* k) { return j[k].is_null() ? NAN : j[k].get<double>(); };
    // An angle: 4 decimals, or 3 significant digits below 1e-3 deg (near-mirror lobes would print 0.0000).
    auto deg = [&](const char* k, int width) {
        const double v = num(k);
        return cell(v, v != 0 && std::abs(v) < 1e-3 ? "%*.2e" : "%*.4f", width);
    };
    if (j.value("framed_about", std::string("mirror direction")) != "mirror direction") {
        char about[96];
        std::snprintf(about, sizeof about, "about the peak, %.4g deg from the mirror direction",
                      num("peak_offset_deg"));
        flags += (flags.empty() ? "" : " ") + std::string("(") + about + ")";
    }
    std::printf("%-9s %s %s %s %s %s %s %s %s %s %s  %s\n", j["model"].get<std::string>().c_str(),
                cell(num("incidence_deg"), "%*.2f", 6).c_str(), cell(num("aspect"), "%*.5f", 8).c_str(),
                cell(num("eccentricity"), "%*.5f", 8).c_str(), deg("major_deg", 9).c_str(), deg("minor_deg", 9).c_str(),
                cell(num("orientation_deg"), "%*.2f", 7).c_str(), deg("centroid_u_deg", 8).c_str(),
                deg("centroid_v_deg", 8).c_str(), deg("fwhm_u_deg", 8).c_str(), deg("fwhm_v_deg", 8).c_str(),
                flags.c_str());
    if (j.contains("parts")) {  // a region in several parts: the line above is all of them, these each one
        int k = 0;
        for (const auto& p : j["parts"]) {
            auto pn = [&](const char* key) { return p[key].is_null() ? NAN : p[key].get<double>(); };
            std::printf("  part %d%s: aspect %.5f major %.4f minor %.4f orient %.2f cu %.4f cv %.4f area %.4g deg2%s\n",
                        ++k, p["holds_peak"].get<bool>() ? " (peak)" : "", pn("aspect"), pn("major_deg"),
                        pn("minor_deg"), pn("orientation_deg"), pn("centroid_u_deg"), pn("centroid_v_deg"),
                        pn("area_deg2"), p["horizon_cut"].get<bool>() ? " horizon_cut" : "");
        }
    }
    if (j.contains("error_estimate") && j["error_estimate"].is_object()) {  // a .brdf: resolution convergence
        auto err = [&](const char* k) {
            return j["error_estimate"][k].is_null() ? NAN : j["error_estimate"][k].get<double>();
        };
        std::printf(
            "  error estimate (resolution convergence, no CPU twin for .brdf): aspect %s, major %s, minor %s deg\n",
            cell(err("aspect"), "%*.1e", 0).c_str(), cell(err("major_deg"), "%*.1e", 0).c_str(),
            cell(err("minor_deg"), "%*.1e", 0).c_str());
    }
    if (j.contains("framing_note")) std::printf("  note: %s\n", j["framing_note"].get<std::string>().c_str());
}

void printToleranceLine(const nlohmann::json& j) {
    std::printf("  tolerance %g: %s, %s boundary, supersample %d -> error estimate %.2g (%s), %.2f ms\n",
                j["tolerance"].get<double>(), j["settings"]["size"].get<std::string>().c_str(),
                j["settings"]["boundary"].get<std::string>().c_str(), j["settings"]["supersample"].get<int>(),
                j["error_estimate"].get<double>(), j["tolerance_met"].get<bool>() ? "met" : "NOT met",
                j["time_ms"].get<double>());
}

int runMeasure(const MeasureFlags& f) {
    scene::Resolved r = scene::resolve(commandValues(f.scene));
    const bool csvOut = f.csv == "-", csvFile = !f.csv.empty() && !csvOut;
    if (csvOut && f.json) throw InputError("--csv -: not with --json (both print the rows on stdout)");
    if (csvFile) io::checkWritable(f.csv, "--csv");  // before anything is measured
    // The columns of an experiment's results.csv (less `config` and its sweep axes): every parameter, then
    // every measurement field.
    std::vector<std::string> columns = scene::columns();
    for (const auto& c : measurement::measurementColumns()) columns.push_back(c);
    std::string csv = experiments::csvHeaderLine(columns);
    measurement::Session session;
    if (!r.reference && !r.setup.cpu) session.rendererFor(r);  // a .brdf's probe, before anything is printed
    const bool table = !f.json && !csvOut;
    if (table) printTableHeader();
    if (csvOut) std::cout << csv << std::flush;
    for (double angle : r.angles) {
        r.scene.light.incidenceDeg = angle;
        nlohmann::json j = measurement::toJson(session.measureOne(r));
        experiments::nameNonFinite(j);
        if (f.json) std::cout << j.dump() << "\n" << std::flush;
        if (csvOut) std::cout << experiments::csvRowLine(columns, j) << std::flush;
        if (csvFile) csv += experiments::csvRowLine(columns, j);
        if (table) printTableRow(j);
        if (table && j.contains("tolerance")) printToleranceLine(j);
    }
    if (csvFile) io::writeFileAtomic(f.csv, csv);
    return 0;
}

}  // namespace

Action addMeasure(CLI::App& app) {
    auto f = std::make_shared<MeasureFlags>();
    addParamFlags(app, f->scene);
    app.add_flag("--json", f->json, "one JSON object per line instead of a table")->group("Output");
    app.add_option("--csv", f->csv,
                   "the rows as CSV, the columns of an experiment's results.csv: to FILE (the table still printed), "
                   "or - for stdout instead of the table")
        ->check(nonEmpty())
        ->group("Output");
    app.footer("Example: hilite measure --model ggx --roughness 0.1 --incidence 0:85:5 --json");
    return [f] { return runMeasure(*f); };
}

}  // namespace hilite::cli
