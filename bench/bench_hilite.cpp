// Speed of the measurement pipeline (Google Benchmark; tests never time things).
//   hilite_bench --benchmark_filter=Measure   one auto-framed measurement at 512x512 (target <= 2 ms)

#include "experiments/measure_scene.hpp"
#include "gl/context.hpp"
#include "render/renderer.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

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

render::Scene ggx(double incidence) {
    render::Scene s;
    s.brdf.model = brdf::Model::GGX;
    s.brdf.roughness = 0.1;
    s.light.incidenceDeg = incidence;
    return s;
}

void BM_MeasureAutoFramed(benchmark::State& state) {
    const int size = int(state.range(0));
    experiments::MeasureSetup setup;
    setup.width = setup.height = size;
    const render::Scene s = ggx(60);
    experiments::measureGl(*env().renderer, s, setup);  // warm-up: compile, allocate
    int renders = 0;
    for (auto _ : state) renders = experiments::measureGl(*env().renderer, s, setup).renders;
    state.counters["renders"] = renders;
}
BENCHMARK(BM_MeasureAutoFramed)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

void BM_RenderReadback(benchmark::State& state) {
    const int size = int(state.range(0));
    const render::Scene s = ggx(60);
    const PinholeCamera cam = experiments::measurementCamera(s, s.light.chart().wr(), 30, size, size);
    ImageF img;
    const auto out = state.range(1) ? render::Output::Measure : render::Output::Color;
    env().renderer->render(s, cam, out, img);
    for (auto _ : state) env().renderer->render(s, cam, out, img);
    state.SetLabel(state.range(1) ? "measure" : "color");
    state.counters["Mpixel/s"] =
        benchmark::Counter(double(size) * size * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderReadback)->ArgsProduct({{128, 256, 512, 1024, 2048}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Analysis(benchmark::State& state) {
    const int size = int(state.range(0));
    const render::Scene s = ggx(60);
    const PinholeCamera cam = experiments::measurementCamera(s, s.light.chart().wr(), 30, size, size);
    const ImageF img = env().renderer->render(s, cam, render::Output::Measure);
    measure::Options opt;
    opt.subpixel = state.range(1) != 0;
    for (auto _ : state) benchmark::DoNotOptimize(measure::measureImage(img.data.data(), size, size, opt));
    state.SetLabel(opt.subpixel ? "subpixel" : "pixel");
}
BENCHMARK(BM_Analysis)->ArgsProduct({{128, 512, 2048}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_Reference(benchmark::State& state) {
    const render::Scene s = ggx(60);
    for (auto _ : state) benchmark::DoNotOptimize(experiments::measureReference(s, {}));
}
BENCHMARK(BM_Reference)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
