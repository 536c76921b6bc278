// `hilite render`: one image of the plane, as a PNG for people and/or a PFM of the exact floats.

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "cli/scene_file.hpp"
#include "cli/shader_probe.hpp"
#include "core/error.hpp"
#include "io/image_io.hpp"
#include "render/renderer.hpp"

#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

struct RenderFlags {
    SceneFlags scene;
    std::string png, pfm, exposure = "auto";
};

double parseExposure(const std::string& s, const ImageF& img) {
    if (s == "auto") return 0.0;
    try {
        size_t used = 0;
        const double ev = std::stod(s, &used);
        if (used == s.size()) return checkRange("--exposure", ev, -64, 64);
    } catch (const InputError&) {
        throw;
    } catch (...) {
    }
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
    render::Scene scene = sceneOf(f.scene);
    scene.light.incidenceDeg = parseIncidence(f.scene.incidence, false).front();
    int width = 0, height = 0;
    parseSize(f.scene.size, width, height);
    checkRange("--fov", f.scene.fov, 0, 179);
    const View view = parseView(f.scene.view);
    const PinholeCamera camera = viewCamera(f.scene, view, scene, width, height);
    if (f.png.empty() && f.pfm.empty()) throw InputError("-o/--float: give at least one output file");
    if (!f.png.empty()) io::checkWritable(f.png, "-o");
    if (!f.pfm.empty()) io::checkWritable(f.pfm, "--float");
    const ImageF probe;
    parseExposure(f.exposure, probe);

    if (scene.brdfFile)
        for (const std::string& note : scene.brdfFile->notes) std::cerr << "hilite: note: " << note << "\n";
    probeShader(scene, f.scene.backend, f.scene.shaderTimeout);  // a .brdf runs in a child first, time-limited
    gl::Context context(parseBackendFlag(f.scene.backend));
    render::Renderer renderer(context);
    renderer.setShaderTimeLimit(f.scene.shaderTimeout);
    const ImageF img = renderer.render(scene, camera, render::Output::Color);
    const double peak = peakOf(img);
    if (!f.png.empty()) {
        io::Exposure e;
        e.ev = parseExposure(f.exposure, img);
        if (f.exposure == "auto") e.normalizeTo = peak;
        io::writePng(f.png, img, e);
    }
    if (!f.pfm.empty()) io::writePfm(f.pfm, img);
    std::cout << "rendered " << width << "x" << height << " " << f.scene.view << " view: " << scene
              << " peak=" << peak << " [" << context.info().renderer << ", " << gl::toString(context.info().backend)
              << "]\n";
    return 0;
}

}  // namespace

Action addRender(CLI::App& app) {
    auto f = std::make_shared<RenderFlags>();
    f->scene.size = "512";
    addSceneFlags(app, f->scene, "angle of incidence theta_i in degrees, [0, 90]");
    app.add_option("--fov", f->scene.fov, "field of view across the width in degrees, (0, 179]; default 30 (measure), 40 (photo)");
    app.add_option("-o,--output", f->png, "PNG output (sRGB-encoded)");
    app.add_option("--float", f->pfm, "float dump (PFM, exact RGB radiance)");
    app.add_option("--exposure", f->exposure, "PNG exposure: auto (peak = white) or stops EV (radiance x 2^EV)")
        ->capture_default_str();
    assignSections(app, 0);
    app.footer("Example: hilite render --model ggx --roughness 0.1 --incidence 60 --view photo -o ggx60.png");
    return [f] { return runRender(*f); };
}

}  // namespace hilite::cli
