// Speed of the measurement pipeline (Google Benchmark; tests never time things). Wall-clock times
// (UseRealTime): llvmpipe renders on its own threads. On a shared machine run with
// --benchmark_repetitions=5 --benchmark_report_aggregates_only=true and read the medians.
//   --benchmark_filter=MeasureAutoFramed   one auto-framed measurement at 512x512 (target <= 2 ms)
//   --benchmark_filter='Draw|Readback|Analysis'   the pipeline's stages, 128^2 .. 2048^2
//   --benchmark_filter=EffectSet            shading cost of each effect set at 512^2 (spectral: table and exact)
//   --benchmark_filter=Sweep                configurations per second (the 90 x 4 sweep's measurements)
//   --benchmark_filter=View                 GL float path against the CPU double path, same pixels, all cores
//   --benchmark_filter=Session              the library route of the Python module: Values -> resolve -> Session
//   --benchmark_filter=MeasureMaterial      a real RGL .bsdf material against analytic GGX, 512^2 (target: within 3x)

#include "brdf/merl.hpp"
#include "brdf/spectral.hpp"
#include "gl/context.hpp"
#include "hilite/experiments/fit.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/scene/resolve.hpp"
#include "measurement/tolerance.hpp"
#include "render/cpu_view.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

using namespace hilite;

namespace {

struct Env {
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<render::Renderer> renderer;
    Env() {
        setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
        context = std::make_unique<gl::Context>(gl::backendFromEnvironment());
        renderer = std::make_unique<render::Renderer>(*context);
    }
};
Env& env() {
    static Env e;
    return e;
}

render::Scene ggx(double incidence, double alpha = 0.1) {
    render::Scene s;
    s.brdf.model = brdf::Model::GGX;
    s.brdf.roughness = alpha;
    s.light.incidenceDeg = incidence;
    return s;
}

/// The measurement camera on the mirror direction with a 30 degree field: the whole frame is shaded.
PinholeCamera frameOf(const render::Scene& s, int size) {
    return measurement::measurementCamera(s, s.light.chart().wr(), 30, size, size);
}

void pixelRate(benchmark::State& state, double pixels) {
    state.counters["Mpixel/s"] =
        benchmark::Counter(pixels * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}

// ---- One measurement ----

void BM_MeasureAutoFramed(benchmark::State& state) {
    measurement::MeasureSetup setup;
    setup.width = setup.height = int(state.range(0));
    setup.crop = state.range(1) != 0;
    const render::Scene s = ggx(60);
    measurement::measureGl(*env().renderer, s, setup);  // warm-up: compile, allocate
    measurement::Measurement m;
    double renderMs = 0, measureMs = 0;
    for (auto _ : state) {
        m = measurement::measureGl(*env().renderer, s, setup);
        renderMs += m.render_ms, measureMs += m.measure_ms;
    }
    state.counters["render_ms"] = renderMs / double(state.iterations());    // draw + readback, all renders
    state.counters["measure_ms"] = measureMs / double(state.iterations());  // analysis + framing arithmetic
    state.counters["renders"] = m.renders;
    state.counters["shaded_px"] = double(m.shadedPixels);
    state.SetLabel(setup.crop ? "crop" : "whole frame");
}
BENCHMARK(BM_MeasureAutoFramed)->ArgsProduct({{128, 512, 2048}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MeasureAutoFramed)
    ->Name("BM_MeasureAutoFramed_cpu_time")
    ->Args({512, 1})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

/// The same measurement of a new scene each time (incidence 60 + 1e-6 i deg): what an experiment pays, the
/// per-scene caches (the survey of the hemisphere, the peak) missed every time.
void BM_MeasureAutoFramedFresh(benchmark::State& state) {
    measurement::MeasureSetup setup;
    setup.width = setup.height = 512;
    measurement::measureGl(*env().renderer, ggx(60), setup);  // warm-up: compile, allocate
    long i = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(measurement::measureGl(*env().renderer, ggx(60 + 1e-6 * double(++i)), setup));
}
BENCHMARK(BM_MeasureAutoFramedFresh)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Reference(benchmark::State& state) {
    const render::Scene s = ggx(60);
    for (auto _ : state) benchmark::DoNotOptimize(measurement::measureReference(s, {}));
}
BENCHMARK(BM_Reference)->Unit(benchmark::kMillisecond);

void BM_Tolerance(benchmark::State& state) {
    const render::Scene s = state.range(0) == 0 ? ggx(60) : ggx(80, 0.02);
    measurement::ToleranceSetup t;
    t.tolerance = 1e-3;
    measurement::measureToTolerance(env().renderer.get(), s, t);  // warm-up
    measurement::ToleranceResult r;
    for (auto _ : state) r = measurement::measureToTolerance(env().renderer.get(), s, t);
    state.counters["size"] = r.setup.width;
    state.counters["error_estimate"] = r.errorEstimate;
    state.SetLabel(state.range(0) == 0 ? "ggx 0.1 @60" : "ggx 0.02 @80");
}
BENCHMARK(BM_Tolerance)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// ---- Stages: draw, readback, analysis ----

void BM_Draw(benchmark::State& state) {
    const int size = int(state.range(0));
    const render::Scene s = ggx(60);
    const PinholeCamera cam = frameOf(s, size);
    ImageF img;
    env().renderer->render(s, cam, render::Output::Measure, img);
    for (auto _ : state) {
        env().renderer->draw(s, cam, render::Output::Measure);
        env().renderer->finish();
    }
    pixelRate(state, double(size) * size);
}
BENCHMARK(BM_Draw)->RangeMultiplier(2)->Range(128, 2048)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The final render of an auto-framed 512^2 measurement alone: a 438 x 234 crop (102k pixels, what
/// BM_MeasureAutoFramed/512/1 shades at 60 deg), and the 64^2 aiming render (arg 0).
void BM_DrawCrop(benchmark::State& state) {
    const render::Scene s = ggx(60);
    const bool aim = state.range(0) == 0;
    const PinholeCamera cam = frameOf(s, aim ? 64 : 512);
    const PixelRect crop = aim ? PixelRect{} : PixelRect{37, 139, 438, 234};
    ImageF img;
    env().renderer->render(s, cam, render::Output::Measure, img, dvec2(0.0), crop);
    for (auto _ : state) env().renderer->render(s, cam, render::Output::Measure, img, dvec2(0.0), crop);
    pixelRate(state, aim ? 64.0 * 64.0 : 438.0 * 234.0);
    state.SetLabel(aim ? "64^2 aim, draw + readback" : "512^2 final crop, draw + readback");
}
BENCHMARK(BM_DrawCrop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Readback(benchmark::State& state) {
    const int size = int(state.range(0));
    const render::Scene s = ggx(60);
    ImageF img;
    env().renderer->render(s, frameOf(s, size), render::Output::Measure, img);
    for (auto _ : state) env().renderer->readback(img);
    state.counters["MB/s"] =
        benchmark::Counter(16.0 * size * size * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Readback)->RangeMultiplier(2)->Range(128, 2048)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Analysis(benchmark::State& state) {
    const int size = int(state.range(0));
    const render::Scene s = ggx(60);
    const ImageF img = env().renderer->render(s, frameOf(s, size), render::Output::Measure);
    analysis::Options opt;
    opt.subpixel = state.range(1) != 0;
    for (auto _ : state) benchmark::DoNotOptimize(analysis::measureImage(img.data.data(), size, size, opt));
    state.SetLabel(opt.subpixel ? "subpixel" : "pixel");
}
BENCHMARK(BM_Analysis)->ArgsProduct({{128, 256, 512, 1024, 2048}, {0, 1}})->Unit(benchmark::kMillisecond);

// ---- Effect sets: shading cost of what the program contains ----

render::Scene effectSet(int k) {
    render::Scene s = ggx(60);
    brdf::Params& p = s.brdf;
    if (k >= 1) p.fresnel = brdf::Fresnel::Dielectric, p.geometry = brdf::Geometry::Smith;  // D + F + G
    if (k >= 2) p.diffuse = brdf::Diffuse::Lambert;                                         // + diffuse
    if (k >= 3) {                                                                           // + spectral
        p.spectrum = brdf::loadSpectrum(render::dataDirectory(), "copper", 5);
        p.fresnel = brdf::Fresnel::Spectral;
    }
    if (k == 4) p.roughnessY = 0.2;       // + anisotropy
    if (k == 5) p.spectralTable = false;  // + spectral, the exact per-pixel sum (--spectral-fresnel exact)
    if (k == 6) p.geometry = brdf::Geometry::Implicit, p.diffuse = brdf::Diffuse::None;  // NDF + spectral table
    return s;
}
const char* kEffectNames[] = {"NDF only",
                              "D+F+G",
                              "+ diffuse",
                              "+ spectral (table)",
                              "+ anisotropy",
                              "+ spectral (exact)",
                              "NDF + spectral (table)"};

void BM_EffectSet(benchmark::State& state) {
    const render::Scene s = effectSet(int(state.range(0)));
    const int size = 512;
    const PinholeCamera cam = frameOf(s, size);
    ImageF img;
    env().renderer->render(s, cam, render::Output::Measure, img);  // compile
    for (auto _ : state) env().renderer->render(s, cam, render::Output::Measure, img);
    pixelRate(state, double(size) * size);
    state.SetLabel(kEffectNames[state.range(0)]);
}
BENCHMARK(BM_EffectSet)->DenseRange(0, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

// ---- Sweep throughput: configurations per second ----

void BM_Sweep(benchmark::State& state) {
    measurement::MeasureSetup setup;
    setup.width = setup.height = int(state.range(0));
    const brdf::Model models[] = {brdf::Model::Phong, brdf::Model::Blinn, brdf::Model::Beckmann, brdf::Model::GGX};
    const double params[] = {1000, 395, 0.1, 0.1};
    long configs = 0;
    for (auto _ : state)
        for (int mi = 0; mi < 4; ++mi)
            for (int inc = 0; inc < 90; ++inc) {
                render::Scene s = ggx(inc);
                s.brdf.model = models[mi];
                (brdf::usesExponent(models[mi]) ? s.brdf.exponent : s.brdf.roughness) = params[mi];
                benchmark::DoNotOptimize(measurement::measureGl(*env().renderer, s, setup));
                ++configs;
            }
    state.counters["configs/s"] = benchmark::Counter(double(configs), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Sweep)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// ---- GL float path against the CPU double path on the same pixels ----

void BM_View(benchmark::State& state) {
    const int size = int(state.range(0));
    const bool cpu = state.range(1) != 0;
    const render::Scene s = ggx(60);
    const PinholeCamera cam = frameOf(s, size);
    ImageF img;
    env().renderer->render(s, cam, render::Output::Measure, img);
    for (auto _ : state) {
        if (cpu) render::renderMeasureCpu(s, cam, img);
        else env().renderer->render(s, cam, render::Output::Measure, img);
    }
    pixelRate(state, double(size) * size);
    state.SetLabel(cpu ? "cpu double, " + std::to_string(std::thread::hardware_concurrency()) + " threads"
                       : std::string("gl float"));
}
BENCHMARK(BM_View)->ArgsProduct({{128, 512}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// ---- The library route (what the Python module's hilite.measure takes) ----

/// GGX 0.1, height-correlated Smith, Schlick F0 0.04 at 512x512, as text, the way Python hands it over.
scene::Values sessionValues(const char* incidence) {
    scene::Values v;
    for (auto [name, text] : {std::pair{"model", "ggx"},
                              {"roughness", "0.1"},
                              {"geometry", "smith"},
                              {"fresnel", "schlick"},
                              {"f0", "0.04"},
                              {"size", "512"}})
        v.set(name, text);
    v.set("incidence", incidence);
    return v;
}

/// resolve + measureOne per iteration, the same scene each time: the warm case (context, program, survey cached).
void BM_SessionMeasure(benchmark::State& state) {
    const scene::Values values = sessionValues("60");
    measurement::Session session;
    measurement::Result row = session.measureOne(scene::resolve(values));  // warm-up: context, compile, allocate
    for (auto _ : state) row = session.measureOne(scene::resolve(values));
    state.counters["renders"] = row.measurement.renders;  // 60 deg: two parts (the horizon strip), a view each
    state.counters["components"] = row.shape().components;
}
BENCHMARK(BM_SessionMeasure)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The 86-angle sweep (incidence 0:85:1) through Session::measure: 86 rows per iteration.
void BM_SessionSweep86(benchmark::State& state) {
    const scene::Values values = sessionValues("0:85:1");
    measurement::Session session;
    session.measure(scene::resolve(values));  // warm-up
    for (auto _ : state) benchmark::DoNotOptimize(session.measure(scene::resolve(values)));
    state.counters["rows/s"] = benchmark::Counter(86.0 * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SessionSweep86)->Unit(benchmark::kMillisecond)->UseRealTime();

/// One 512^2 measurement of a real RGL material (cc_ibiza_sunset, a glossy film, from ../shared/data/measured) against
/// the analytic GGX 0.2 + Smith + Schlick lobe, at 40 deg, through the Session (what `hilite measure` runs), warm.
/// Arg 0: 0 GGX, 1 the .bsdf file; arg 1: 0 lobe all, 1 lobe mirror; arg 2: 0 the measurement (measureGl), 1 the
/// row hilite measure prints (Session::measureOne, with table_error for the file).
void BM_MeasureMaterial(benchmark::State& state) {
    const std::string file = std::string(HILITE_SOURCE_DIR_STR) + "/../shared/data/measured/cc_ibiza_sunset_rgb.bsdf";
    scene::Values v;
    if (state.range(0)) {
        if (!std::filesystem::exists(file)) {
            state.SkipWithError(
                ("missing " + file + " (the RGL files are not part of the project; see README)").c_str());
            return;
        }
        v.set("measured", file);
    } else {
        for (auto [name, text] : {std::pair{"model", "ggx"},
                                  {"roughness", "0.2"},
                                  {"geometry", "smith"},
                                  {"fresnel", "schlick"},
                                  {"f0", "0.04"}})
            v.set(name, text);
    }
    v.set("incidence", "40");
    v.set("size", "512");
    v.set("lobe", state.range(1) ? "mirror" : "all");
    const std::string label = std::string(state.range(0) ? "rgl cc_ibiza_sunset" : "ggx 0.2") +
                              (state.range(1) ? ", lobe mirror" : ", lobe all");
    const scene::Resolved r = scene::resolve(v);
    if (state.range(2)) {  // the whole row: resolve, measure, and a measured material's table_error
        measurement::Session session;
        measurement::Result row = session.measureOne(r);  // warm-up: context, compile, upload, survey
        for (auto _ : state) row = session.measureOne(scene::resolve(v));
        state.counters["renders"] = row.measurement.renders;
        state.SetLabel(label + ", the row (table_error: 3 more measurements)");
        return;
    }
    measurement::Measurement m = measurement::measureGl(*env().renderer, r.scene, r.setup);  // warm-up
    for (auto _ : state) m = measurement::measureGl(*env().renderer, r.scene, r.setup);
    state.counters["renders"] = m.renders;
    state.SetLabel(label);
}
BENCHMARK(BM_MeasureMaterial)->ArgsProduct({{0, 1}, {0, 1}, {0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MeasureMaterial)->ArgsProduct({{0, 1}, {0}, {1}})->Unit(benchmark::kMillisecond)->UseRealTime();

/// `hilite fit`'s default job: phong, blinn, beckmann and ggx fitted to a GGX 0.1 MERL table over 18 angles
/// (0:85:5) x 5 thresholds at 256^2 (the target: under 30 s). One iteration: a fit is seconds long.
void BM_Fit4Models(benchmark::State& state) {
    const std::string file = (std::filesystem::temp_directory_path() / "hilite-bench-ggx.binary").string();
    {
        brdf::Params p;
        p.model = brdf::Model::GGX;
        p.roughness = 0.1;
        const std::string bytes = brdf::merl::encode(brdf::merl::tabulate(p));
        std::ofstream(file, std::ios::binary) << bytes;
    }
    scene::Values values;
    values.set("measured", file);
    values.set("incidence", "0:85:5");
    values.set("size", "256");
    measurement::Session session;
    double evaluations = 0;
    for (auto _ : state) {
        const experiments::FitResult r = experiments::fitModels(session, values, experiments::FitOptions{});
        for (const auto& f : r.fits) evaluations += f.evaluations;
    }
    state.counters["sweeps"] = evaluations / double(state.iterations());
    std::filesystem::remove(file);
}
BENCHMARK(BM_Fit4Models)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
