// `hilite measure`: the highlight's shape per angle of incidence, as a table or JSON lines.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "core/error.hpp"
#include "measurement/session.hpp"

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
};

void printTableHeader() {
    std::printf("%-9s %6s %8s %8s %9s %9s %7s %8s %8s %8s %8s  %-s\n", "model", "theta", "aspect", "ecc", "major",
                "minor", "orient", "cu", "cv", "fwhm_u", "fwhm_v", "flags");
}

void printTableRow(const nlohmann::json& j) {
    std::string flags;
    for (const auto& fl : j["flags"]) flags += (flags.empty() ? "" : ",") + fl.get<std::string>();
    auto num = [&](const char* k) { return j[k].is_null() ? NAN : j[k].get<double>(); };
    // An angle: 4 decimals, or 3 significant digits below 1e-3 deg (near-mirror lobes would print 0.0000).
    auto deg = [&](const char* k, int width) {
        const double v = num(k);
        char buf[32];
        std::snprintf(buf, sizeof buf, v != 0 && std::abs(v) < 1e-3 ? "%*.2e" : "%*.4f", width, v);
        return std::string(buf);
    };
    if (j.value("framed_about", std::string("mirror direction")) != "mirror direction") {
        char about[96];
        std::snprintf(about, sizeof about, "about the peak, %.4g deg from the mirror direction", num("peak_offset_deg"));
        flags += (flags.empty() ? "" : " ") + std::string("(") + about + ")";
    }
    std::printf("%-9s %6.2f %8.5f %8.5f %s %s %7.2f %s %s %s %s  %s\n", j["model"].get<std::string>().c_str(),
                num("incidence_deg"), num("aspect"), num("eccentricity"), deg("major_deg", 9).c_str(),
                deg("minor_deg", 9).c_str(), num("orientation_deg"), deg("centroid_u_deg", 8).c_str(),
                deg("centroid_v_deg", 8).c_str(), deg("fwhm_u_deg", 8).c_str(), deg("fwhm_v_deg", 8).c_str(),
                flags.c_str());
    if (j.contains("error_estimate") && j["error_estimate"].is_object()) {  // a .brdf: resolution convergence
        auto err = [&](const char* k) {
            return j["error_estimate"][k].is_null() ? NAN : j["error_estimate"][k].get<double>();
        };
        std::printf("  error estimate (resolution convergence, no CPU twin for .brdf): aspect %.1e, major %.1e, "
                    "minor %.1e deg\n",
                    err("aspect"), err("major_deg"), err("minor_deg"));
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
    measurement::Session session;
    if (!r.reference && !r.setup.cpu) session.rendererFor(r);  // a .brdf's probe, before anything is printed
    if (!f.json) printTableHeader();
    for (double angle : r.angles) {
        r.scene.light.incidenceDeg = angle;
        const nlohmann::json j = session.measureOne(r);
        if (f.json) std::cout << j.dump() << "\n" << std::flush;
        else printTableRow(j);
        if (!f.json && j.contains("tolerance")) printToleranceLine(j);
    }
    return 0;
}

}  // namespace

Action addMeasure(CLI::App& app) {
    auto f = std::make_shared<MeasureFlags>();
    addParamFlags(app, f->scene);
    app.add_flag("--json", f->json, "one JSON object per line instead of a table")->group("Output");
    app.footer("Example: hilite measure --model ggx --roughness 0.1 --incidence 0:85:5 --json");
    return [f] { return runMeasure(*f); };
}

}  // namespace hilite::cli
