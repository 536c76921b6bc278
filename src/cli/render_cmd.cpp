// `hilite render`: one image of the plane, as a PNG for people and/or a PFM of the exact floats.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "hilite/core/error.hpp"
#include "io/image_io.hpp"
#include "measurement/shader_probe.hpp"
#include "render/renderer.hpp"

#include "core/text.hpp"

#include <cmath>
#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

struct RenderFlags {
    SceneOptions scene;
    std::string png, pfm, exposure = "auto";
};

double parseExposure(const std::string& s, const ImageF& img) {
    if (s == "auto") return 0.0;
    const auto ev = parseNumber(s);
    if (ev && *ev >= -64 && *ev <= 64) return *ev;
    (void)img;
    throw InputError("--exposure: 'auto' or stops EV in [-64, 64] (got '" + s + "')");
}

double peakOf(const ImageF& img) {
    double peak = 0;
    for (size_t i = 0; i < img.data.size(); i += 4)
        peak = std::max({peak, double(img.data[i]), double(img.data[i + 1]), double(img.data[i + 2])});
    return peak;
}

int runRender(const RenderFlags& f) {
    const scene::Resolved r = scene::resolve(commandValues(f.scene), scene::Purpose::Render);
    const render::Scene& scene = r.scene;
    if (r.angles.size() > 1)
        throw InputError(r.values.where("incidence") + ": render takes one angle (got '" + r.values.text("incidence") +
                         "')");
    const int width = r.setup.width, height = r.setup.height;
    const PinholeCamera camera = scene::viewCamera(r, r.view, width, height);
    if (f.png.empty() && f.pfm.empty()) throw InputError("-o/--float: give at least one output file");
    if (!f.png.empty()) io::checkWritable(f.png, "-o");
    if (!f.pfm.empty()) io::checkWritable(f.pfm, "--float");
    const ImageF probe;
    parseExposure(f.exposure, probe);

    if (scene.brdfFile)
        for (const std::string& note : scene.brdfFile->notes) std::cerr << "hilite: note: " << note << "\n";
    measurement::probeShader(scene, r.backend, r.shaderTimeoutS, r.gpu);  // a .brdf runs in a child first, time-limited
    gl::Context context(scene::backendOf(r), r.gpu);
    render::Renderer renderer(context);
    renderer.setShaderTimeLimit(r.shaderTimeoutS);
    const ImageF img = renderer.render(scene, camera, render::Output::Color);
    // A NaN or Inf pixel would be a black PNG, a PFM nobody can use and a printed peak=inf: refuse instead.
    size_t nonFinite = 0;
    for (float v : img.data) nonFinite += !std::isfinite(v);
    if (nonFinite)
        throw InputError("render: " + std::to_string(nonFinite) +
                         " pixel values are NaN or Inf (the BRDF is not finite "
                         "there, e.g. a lobe infinite at its peak); nothing written");
    const double peak = peakOf(img);
    if (!f.png.empty()) {
        io::Exposure e;
        e.ev = parseExposure(f.exposure, img);
        if (f.exposure == "auto") e.normalizeTo = peak;
        io::writePng(f.png, img, e);
    }
    if (!f.pfm.empty()) io::writePfm(f.pfm, img);
    std::cout << "rendered " << width << "x" << height << " " << scene::toString(r.view) << " view: " << scene
              << " peak=" << peak << " [" << context.info().renderer << ", " << gl::toString(context.info().backend)
              << "]\n";
    return 0;
}

}  // namespace

Action addRender(CLI::App& app) {
    auto f = std::make_shared<RenderFlags>();
    addParamFlags(app, f->scene, [](const scene::Param& p) { return p.table != scene::Table::Measurement; });
    app.add_option("-o,--output", f->png, "PNG output (sRGB-encoded)")->group("Output")->check(nonEmpty());
    app.add_option("--float", f->pfm, "float dump (PFM, exact RGB radiance)")->group("Output")->check(nonEmpty());
    app.add_option("--exposure", f->exposure, "PNG exposure: auto (peak = white) or stops EV (radiance x 2^EV)")
        ->capture_default_str()
        ->group("Output");
    app.footer("Example: hilite render --model ggx --roughness 0.1 --incidence 60 --view photo -o ggx60.png");
    return [f] { return runRender(*f); };
}

}  // namespace hilite::cli
