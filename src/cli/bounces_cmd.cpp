// `hilite brdf bounces`: light that bounces more than once, per bounce order, traced on an explicit Beckmann
// height field and walked on Smith's microsurface, beside the analytic single scattering and the Kulla-Conty
// compensation (experiments/bounces.hpp). A table per incidence by default; with --json one object per line
// (the columns of an experiment's [bounces] rows).

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/scene_flags.hpp"
#include "hilite/core/error.hpp"
#include "hilite/experiments/bounces.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

namespace hilite::cli {

namespace {

struct BounceFlags {
    SceneOptions scene;
    experiments::BounceSettings settings;
    std::string surface = "hermite";
    bool json = false, exits = false;
};

std::string pm(const micro::Estimate& e) {
    if (!std::isfinite(e.value)) return "-";  // no light reached this order
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4f +- %.4f", e.value, e.error);
    return buf;
}

void printStudy(const experiments::BounceStudy& s, bool exits) {
    const auto& t = s.traced;
    const auto& w = s.walk;
    std::printf("\ntheta_i = %g deg (%.1f s): order, share of the light leaving after it (F = 1), C* of its colour\n",
                s.thetaDeg, s.seconds);
    std::printf("  %-8s %-18s %-18s %-18s %-18s\n", "order", "traced", "Smith walk", "C* traced", "C* Smith");
    for (size_t k = 0; k < t.energy.size(); ++k) {
        const std::string name = k + 1 < t.energy.size() ? std::to_string(k + 1) : ">=" + std::to_string(k + 1);
        std::printf("  %-8s %-18s %-18s %-18s %-18s\n", name.c_str(), pm(t.energy[k]).c_str(), pm(w.energy[k]).c_str(),
                    pm(t.chroma[k]).c_str(), pm(w.chroma[k]).c_str());
    }
    std::printf("  %-8s %-18s %-18s Kulla-Conty 1 - E(mu) = %.4f (E(mu) = %.4f, Smith single scattering)\n", ">=2",
                pm(t.multiple).c_str(), pm(w.multiple).c_str(), 1.0 - s.smithSingle, s.smithSingle);
    std::printf("  colour of orders >= 2: C* traced %.2f, Smith %.2f, Kulla-Conty F_ms %.2f\n", s.tracedMultiple.chroma,
                s.walkMultiple.chroma, s.kcMultiple.chroma);
    const dvec3 kc = s.kcAlbedo;
    std::printf(
        "  albedo with F (linear sRGB): traced %.4f %.4f %.4f, Kulla-Conty %.4f %.4f %.4f, single %.4f %.4f %.4f\n",
        t.reflectedRgb[0].value, t.reflectedRgb[1].value, t.reflectedRgb[2].value, kc.x, kc.y, kc.z, s.singleAlbedo.x,
        s.singleAlbedo.y, s.singleAlbedo.z);
    std::printf("  albedo Y: traced %s, Smith %s; stuck paths %.5f, back hits %ld\n", pm(t.reflectedY).c_str(),
                pm(w.reflectedY).c_str(), t.stuck.value, t.backHits);
    if (!exits) return;
    std::printf("  first reflection by cos(theta_o): share of the light, and of it the share that leaves at once\n");
    std::printf("  %-12s %-9s %-9s %-9s %-9s\n", "cos theta_o", "traced", "leaves", "Smith", "leaves");
    for (size_t b = 0; b < t.firstExitShare.size(); ++b) {
        char bin[32];
        if (b == 0) std::snprintf(bin, sizeof bin, "< 0 (down)");
        else
            std::snprintf(bin, sizeof bin, "%.1f-%.1f", double(b - 1) / (micro::kExitBins - 1),
                          double(b) / (micro::kExitBins - 1));
        std::printf("  %-12s %-9.4f %-9.4f %-9.4f %-9.4f\n", bin, t.firstExitShare[b], t.firstExitEscape[b],
                    w.firstExitShare[b], w.firstExitEscape[b]);
    }
}

int runBounces(BounceFlags& f) {
    const auto kind = micro::parseTracedSurface(f.surface);
    if (!kind) throw InputError("--surface: '" + f.surface + "' is not a traced surface (allowed: hermite, bilinear)");
    f.settings.options.surface = *kind;
    experiments::checkBounceSettings(f.settings, true);
    const scene::Values values = commandValues(f.scene);
    const scene::Resolved r = experiments::resolveBounceScene(values);  // every check before the first path
    if (!f.json)
        std::cout << "# " << r.scene.brdf << "\n# " << f.settings << ", field seed " << values.text("bump_seed")
                  << "\n";
    ProgressLine line;
    const auto told = [&line](const std::string& stage, long done, long total) {
        line(stage, size_t(done), size_t(total));
    };
    for (const auto& s : experiments::studyBounces(values, f.settings, told)) {
        if (f.json) {
            std::cout << experiments::bounceRow(s).dump() << "\n" << std::flush;
        } else {
            printStudy(s, f.exits);
            std::cout << std::flush;
        }
    }
    return 0;
}

}  // namespace

std::pair<CLI::App*, Action> addBrdfBounces(CLI::App& app) {
    CLI::App* sub = app.add_subcommand("bounces",
                                       "light per bounce order: traced on a Beckmann height field, walked "
                                       "on Smith's microsurface, beside Kulla-Conty (CPU)");
    auto f = std::make_shared<BounceFlags>();
    f->scene.defaults["incidence"] = "0,30,60,75";
    f->scene.defaults["model"] = "beckmann";
    addParamFlags(*sub, f->scene, [](const scene::Param& p) {
        for (const char* name :
             {"model", "roughness", "fresnel", "material", "eta", "k", "f0", "incidence", "bump_seed"})
            if (p.name == name) return true;
        return false;
    });
    auto& o = f->settings.options;
    sub->add_option("--paths", o.paths, "light paths per incidence (and per method)")->capture_default_str();
    sub->add_option("--batches", o.batches, "independent batches; their spread is the error")->capture_default_str();
    sub->add_option("--seed", o.seed, "the paths' seed (the field's is --bump-seed)")->capture_default_str();
    sub->add_option("--texels", f->settings.texels, "the field's tile, texels per side (a power of two, 64-4096)")
        ->capture_default_str();
    sub->add_option("--bumps-per-tile", f->settings.bumpsPerTile, "bump periods across the tile (texels / 8 at most)")
        ->capture_default_str();
    sub->add_option("--surface", f->surface,
                    "hermite (C1, normals the gradient of the surface hit) | bilinear "
                    "(diagnostic: the render's heights and slopes)")
        ->capture_default_str();
    sub->add_flag("--exits", f->exits, "also where the first reflection goes, and how much of it leaves at once");
    sub->add_flag("--json", f->json, "one JSON object per incidence instead of the table");
    sub->footer(
        "F = 1 energies per order, the colour (CIELAB C*, D65) of each order's light with the scene's Fresnel, "
        "and the albedo against --multiscatter kulla-conty. Method and measured numbers: docs/bounces.md.\n"
        "Example: hilite brdf bounces --roughness 0.6 --material gold --incidence 0,60");
    return {sub, [f] { return runBounces(*f); }};
}

}  // namespace hilite::cli
