#pragma once
// Renders the plane through a pinhole camera into the float framebuffer and reads it back.
// Programs are compiled once per effect set and reused; the framebuffer is reused while its size holds.

#include "gl/context.hpp"
#include "gl/framebuffer.hpp"
#include "gl/program.hpp"
#include "hilite/core/camera.hpp"
#include "hilite/core/image.hpp"
#include "hilite/render/scene.hpp"
#include "render/shader_source.hpp"
#include "render/watchdog.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace hilite::render {

/// Both stages of the program for an effect set: the assembled terms (assemble()) plus the light,
/// which is an effect too (the point-light code of shade.frag compiles only when named).
ProgramSources programSources(const brdf::Params& p, Output out, LightType light, const std::string& shaderDir,
                              bool bumps = false);
/// The program a scene compiles: its .brdf file's (the file's BRDF() in hilite's frame) or programSources().
ProgramSources programSources(const Scene& scene, Output out, const std::string& shaderDir);
/// The effects a scene runs, in the program and in the CPU twin alike: the term blocks and the light.
std::vector<std::string> activeEffects(const Scene& scene);
/// The light as `explain` names it; for a sphere or disk also the GL rule it renders with (render::lightRule).
std::string describeLight(const Scene& scene);

class Renderer {
public:
    /// Needs `context` current while it lives. `shaderDir` empty: found with shaderDirectory().
    explicit Renderer(gl::Context& context, std::string shaderDir = "");
    ~Renderer();

    /// Draws and reads back: 4 floats per pixel, row 0 at the bottom (see shaders/shade.frag for the
    /// channels of each output). `jitter` moves every pixel's sample point by that many pixels (the
    /// shader's uJitter; (0, 0) = the pixel centre), for supersampling. A non-empty `crop` draws and reads
    /// only those pixels of the camera's image (the viewport): `image` is then crop.width x crop.height.
    /// `whileDrawing`, if given, runs on this thread after the draw is submitted and before the readback waits
    /// for it: CPU work beside llvmpipe's, which also keeps this core from idling before the next render.
    void render(const Scene& scene, const PinholeCamera& camera, Output out, ImageF& image, dvec2 jitter = dvec2(0.0),
                const PixelRect& crop = {}, const std::function<void()>& whileDrawing = {});
    ImageF render(const Scene& scene, const PinholeCamera& camera, Output out);

    /// The two halves of render(), for benchmarks: draw() queues the frame, finish() waits for it,
    /// readback() reads the last drawn frame (waiting for it too).
    void draw(const Scene& scene, const PinholeCamera& camera, Output out, dvec2 jitter = dvec2(0.0),
              const PixelRect& crop = {});
    void finish() const;
    void readback(ImageF& image);

    /// The program for an effect set (compiled on first use).
    const gl::Program& program(const brdf::Params& p, Output out, LightType light = LightType::Directional,
                               bool bumps = false);
    /// The program a scene renders with: its .brdf file's when it has one, else program(scene.brdf, ...).
    /// A .brdf whose GLSL does not build throws InputError naming the file and line.
    const gl::Program& program(const Scene& scene, Output out);

    /// Time limit in seconds on each compile and draw of a .brdf program (0: none, the default): past it
    /// the process ends with exit code 2 and a one-line message (see render/watchdog.hpp). Built-in terms
    /// are hilite's own code and never limited.
    void setShaderTimeLimit(double seconds) { m_shaderTimeLimit = seconds; }
    size_t programCount() const { return m_programs.size(); }
    const std::string& shaderDir() const { return m_shaderDir; }

private:
    /// draw() with the program already chosen (render() compiles it before arming the watchdog).
    void drawWith(const gl::Program& prog, const Scene& scene, const PinholeCamera& camera, dvec2 jitter,
                  const PixelRect& crop);
    void setUniforms(const gl::Program& prog, const Scene& scene, const PinholeCamera& cam, dvec2 jitter) const;
    void setBrdfFileUniforms(const gl::Program& prog, const Scene& scene) const;

    std::string m_shaderDir;
    std::map<std::string, std::unique_ptr<gl::Program>> m_programs;
    /// Framebuffers by size, most recent first: automatic framing alternates a coarse and a final size,
    /// and reallocating a 512x512 float target per render costs more than drawing it.
    std::vector<std::unique_ptr<gl::Framebuffer>> m_fbos;
    gl::Framebuffer& framebuffer(int width, int height);
    gl::Framebuffer* m_drawn = nullptr;  ///< the framebuffer of the last draw()
    PixelRect m_drawnCrop;               ///< and what of it was drawn
    unsigned int m_vao = 0;
    std::unique_ptr<class BumpTextures> m_bumpTextures;  ///< the bump fields' textures
    /// Measured tables uploaded as 3D textures (shaders/brdf_gl.glsl, block Measured), one per table read; the
    /// shared_ptr keeps the table's address from being reused by another while its texture lives.
    /// Measured tables' textures by table, weakly: a table nobody holds any more has its texture deleted.
    /// Each has two: f per channel (RGB32F, colour renders) and its luminance (R32F, measurements: one texel per tap).
    struct MeasuredTexture {
        std::weak_ptr<const brdf::merl::MeasuredBrdf> table;
        unsigned int rgb = 0, y = 0;
    };
    std::vector<MeasuredTexture> m_measuredTextures;
    void bindMeasured(const gl::Program& prog, const std::shared_ptr<const brdf::merl::MeasuredBrdf>& table);
    /// RGL materials as texture buffers (block Rgl), by material, weakly as the MERL tables: {buffer, texture}.
    struct RglTexture {
        std::weak_ptr<const brdf::rgl::Material> material;
        unsigned int buffer = 0, texture = 0;
    };
    std::vector<RglTexture> m_rglTextures;
    void bindRgl(const gl::Program& prog, const std::shared_ptr<const brdf::rgl::Material>& material);
    double m_shaderTimeLimit = 0;
    Watchdog m_watchdog;
};

}  // namespace hilite::render
