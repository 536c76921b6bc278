// What users wait for (issue 37): lights with size, measured tables with their table_error, exact references.
// Each benchmark times a whole row through measurement::Session (what `hilite measure` and hilite.measure run),
// warm (the same scene each iteration: context, program, caches) or fresh (incidence 60 + 1e-6 i deg: every
// per-scene cache missed, as in an experiment). Ratios are read between rows of one run (bench/speed_table.py).
//   --benchmark_filter=LightRow      directional against the sun's disk (auto rule), GGX 0.02 + Smith at 60 deg, 512^2
//   --benchmark_filter=TableRow      analytic GGX 0.1, 0.2 against its MERL table with table_error, directional and disk
//   --benchmark_filter=DiskReference --reference of GGX 0.02 under a 5 deg disk at 30, 60 and 80 deg

#include "brdf/merl.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/render/ltc.hpp"
#include "hilite/scene/resolve.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

using namespace hilite;

namespace {

scene::Values values(std::initializer_list<std::pair<const char*, std::string>> pairs) {
    scene::Values v;
    for (const auto& [name, text] : pairs) v.set(name, text);
    return v;
}

/// A MERL table of GGX alpha (implicit G, no Fresnel), written once per process and roughness.
const std::string& ggxTable(double alpha = 0.1) {
    static std::map<double, std::string> files;
    std::string& file = files[alpha];
    if (file.empty()) {
        const std::string name = "hilite-bench-speed-ggx-" + std::to_string(int(std::lround(alpha * 1000))) + ".binary";
        file = (std::filesystem::temp_directory_path() / name).string();
        brdf::Params p;
        p.model = brdf::Model::GGX;
        p.roughness = alpha;
        std::ofstream(file, std::ios::binary) << brdf::merl::encode(brdf::merl::tabulate(p));
    }
    return file;
}

measurement::Session& session() {
    static measurement::Session s;
    return s;
}

/// Times measureOne of `v` (arg 1: warm, 0: fresh), and reports the row's aspect, rings and renders.
void timeRows(benchmark::State& state, scene::Values v, const std::string& label) {
    const bool fresh = state.range(1) == 0;
    v.set("incidence", "60");
    measurement::Result row = session().measureOne(scene::resolve(v));  // warm-up: compile, upload, caches
    long i = 0;
    for (auto _ : state) {
        if (fresh) {
            char text[32];
            std::snprintf(text, sizeof text, "%.9f", 60.0 + 1e-6 * double(++i));
            v.set("incidence", text);
        }
        row = session().measureOne(scene::resolve(v));
    }
    state.counters["aspect"] = row.shape().aspect;
    state.counters["renders"] = row.measurement.renders;
    if (row.light && row.light->ruleError) state.counters["light_rule_error"] = *row.light->ruleError;
    if (row.tableError) state.counters["table_error_aspect"] = row.tableError->aspect;
    state.SetLabel(label + (fresh ? ", fresh" : ", warm"));
}

/// Arg 0: 0 directional, 1 the sun's disk (0.266 deg, auto rule), 2 the sun's disk by linearly transformed
/// cosines (light_rule ltc; its fit is cached per process, timed by BM_LtcFit); arg 1: warm or fresh.
void BM_LightRow(benchmark::State& state) {
    scene::Values v = values({{"model", "ggx"}, {"roughness", "0.02"}, {"geometry", "smith"}, {"size", "512"}});
    if (state.range(0)) v.set("light", "disk");
    if (state.range(0) == 2) v.set("light_rule", "ltc");
    timeRows(state, v,
             state.range(0) == 2 ? "GGX 0.02 + Smith, sun disk by LTC"
             : state.range(0)    ? "GGX 0.02 + Smith, sun disk"
                                 : "GGX 0.02 + Smith, directional");
}
BENCHMARK(BM_LightRow)->ArgsProduct({{0, 1, 2}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();

/// The LTC fit of one BRDF (32 elevations), uncached: arg 0: GGX alpha x 1000.
void BM_LtcFit(benchmark::State& state) {
    brdf::Params p;
    p.model = brdf::Model::GGX;
    p.roughness = double(state.range(0)) / 1000;
    p.geometry = brdf::Geometry::Smith;
    int evaluations = 0;
    for (auto _ : state) evaluations = render::ltcFit(p).objectiveEvaluations;
    state.counters["objective_evaluations"] = evaluations;
    state.SetLabel("GGX " + std::to_string(p.roughness) + " + Smith");
}
BENCHMARK(BM_LtcFit)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Arg 0: 0 analytic GGX, 1 its MERL table (the row with table_error), 2 analytic under the sun's disk,
/// 3 the table under the sun's disk; arg 1: warm or fresh; arg 2: GGX alpha x 1000 (0.1: the sun's auto rule
/// takes 1 ring, 4 points a pixel; 0.2: the cap's centre alone).
void BM_TableRow(benchmark::State& state) {
    const int kind = int(state.range(0));
    const double alpha = double(state.range(2)) / 1000;
    char a[16];
    std::snprintf(a, sizeof a, "%g", alpha);
    scene::Values v = kind % 2 ? values({{"measured", ggxTable(alpha)}, {"size", "512"}})
                               : values({{"model", "ggx"}, {"roughness", a}, {"size", "512"}});
    if (kind >= 2) v.set("light", "disk");
    timeRows(state, v,
             (kind % 2 ? "MERL table of GGX " + std::string(a) + " + table_error" : "analytic GGX " + std::string(a)) +
                 (kind >= 2 ? ", sun disk" : ", directional"));
}
BENCHMARK(BM_TableRow)->ArgsProduct({{0, 1, 2, 3}, {1, 0}, {100, 200}})->Unit(benchmark::kMillisecond)->UseRealTime();

/// The measurement alone (no table_error): arg 0: 0 analytic GGX 0.1, 1 its MERL table, directional, warm.
void BM_TableMeasurement(benchmark::State& state) {
    scene::Values v = state.range(0) ? values({{"measured", ggxTable()}, {"size", "512"}})
                                     : values({{"model", "ggx"}, {"roughness", "0.1"}, {"size", "512"}});
    v.set("incidence", "60");
    const scene::Resolved r = scene::resolve(v);
    render::Renderer& renderer = session().rendererFor(r);
    measurement::Measurement m = measurement::measureGl(renderer, r.scene, r.setup);
    double renderMs = 0;
    for (auto _ : state) {
        m = measurement::measureGl(renderer, r.scene, r.setup);
        renderMs += m.render_ms;
    }
    state.counters["render_ms"] = renderMs / double(state.iterations());
    state.counters["renders"] = m.renders;
    state.counters["shaded_px"] = double(m.shadedPixels);
    state.SetLabel(state.range(0) ? "MERL table of GGX 0.1, the measurement alone" : "analytic GGX 0.1");
}
BENCHMARK(BM_TableMeasurement)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

/// `hilite measure --reference` of GGX 0.02 (+ Smith) under a 5 deg disk at 30, 60 and 80 deg: three rows.
void BM_DiskReference(benchmark::State& state) {
    const scene::Values v = values({{"model", "ggx"},
                                    {"roughness", "0.02"},
                                    {"geometry", "smith"},
                                    {"light", "disk"},
                                    {"light_angle", "5"},
                                    {"incidence", "30,60,80"},
                                    {"reference", "true"}});
    std::vector<measurement::Result> rows;
    for (auto _ : state) rows = session().measure(scene::resolve(v));
    for (const auto& r : rows)
        state.counters["aspect_" + std::to_string(int(std::lround(r.resolved.scene.light.incidenceDeg)))] =
            r.shape().aspect;
}
BENCHMARK(BM_DiskReference)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
