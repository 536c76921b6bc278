#pragma once
// One highlight measurement of a scene, end to end: aim and zoom the measurement view (automatic
// framing), render, read back, analyse. Also the double-precision reference of the same scene.

#include "hilite/analysis/highlight.hpp"
#include "hilite/core/camera.hpp"
#include "hilite/core/image.hpp"
#include "hilite/render/scene.hpp"
#include "hilite/scene/setup.hpp"

#include <array>
#include <iosfwd>
#include <optional>
#include <string>

namespace hilite::render {
class Renderer;  // render/renderer.hpp: internal (the GL renderer)
}

namespace hilite::measurement {

using scene::kMaxSupersample;
using scene::MeasureSetup;

struct Measurement {
    analysis::Shape shape;
    int renders = 0;        ///< GL renders it took (aiming + final)
    double fovDeg = 0;      ///< field of view of the final render
    dvec3 center{0, 0, 1};  ///< exitant direction at the centre of the final frame
    /// The final render's crop of that frame (empty: the whole frame) and the region's level there (0: the
    /// threshold times the frame's own peak), when one frame of one part was measured (inFrame true): what
    /// measureInFrame needs to measure another material in the same pixels.
    PixelRect crop;
    double level = 0;
    bool inFrame = false;
    double render_ms = 0;     ///< GL draw + readback (or the CPU twin's render), all renders
    double measure_ms = 0;    ///< analysis of the final render (and framing arithmetic)
    long shadedPixels = 0;    ///< pixels of the final frame drawn per sample (the crop, or the whole frame)
    std::string framing;      ///< "automatic" (seeded by the twin), "blind" (coarse renders only) or "fixed"
    std::string framingNote;  ///< blind framing: why it found no highlight, when it gave up ("" otherwise)
    /// Without a CPU twin (a .brdf file) the error estimate comes from resolution convergence: the same
    /// frame measured again at half the size (halfWidth x halfHeight); |final - this| per field estimates
    /// the final measurement's error.
    std::optional<analysis::Shape> halfResolution;
    int halfWidth = 0, halfHeight = 0;
    /// MeasureSetup::keepImage: the final render as analysed, (L, u, v, w) per pixel (the crop when cropped;
    /// the maps make it self-describing); empty otherwise
    ImageF image;
};

/// The lobe of a scene as a function of chart coordinates, evaluated by the double twin. Like everything
/// twin-based below, it throws InputError for a .brdf scene (render::requireTwin).
analysis::LobeFunction twinLobe(const render::Scene& scene);

/// twinLobe's two functions in one evaluation, with what the scene fixes (chart, eye, the light's direction)
/// computed once: for searches that call the twin thousands of times per measurement.
class TwinSampler {
public:
    explicit TwinSampler(const render::Scene& scene);
    /// False where (u, v) is below the horizon; else true, with L the twin's luminance there.
    bool at(double u, double v, double& L) const;
    /// The luminance, 0 below the horizon (twinLobe's lobe).
    double lobe(double u, double v) const {
        double L = 0;
        return at(u, v, L) ? L : 0.0;
    }

private:
    const render::Scene& m_scene;  ///< outlives the sampler (twinLobe's functions keep a copy)
    MirrorChart m_chart;
    dvec3 m_eye, m_wi;
};

/// Angular radii (radians) at which the twin's lobe falls to `threshold` of its value at the mirror
/// direction, along +u, -u, +v, -v (bisection to 1e-9 of the bracket; the horizon ends a ray too).
std::array<double, 4> twinRadii(const render::Scene& scene, double threshold);
/// The largest of twinRadii: a seed for framing and for the reference's search disc.
double twinHalfWidth(const render::Scene& scene, double threshold);

/// Measures the highlight in GL with fixed or automatic framing. A .brdf scene has no twin to seed the
/// framing: it is measured by measureBlind (measurement/blind_framing.hpp).
Measurement measureGl(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup);
/// The scene measured in GL in the frame `like` was (its camera, crop and level; like.inFrame must hold): one
/// render and its analysis, no framing and no diagnoses. For a variant of the same material whose region
/// differs from like's by a fraction of its size (table_error's half-resolution tables, measurement/row.cpp).
Measurement measureInFrame(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup,
                           const Measurement& like);
/// The same measurement with every render made by the CPU double twin (render/cpu_view.hpp).
Measurement measureCpu(const render::Scene& scene, const MeasureSetup& setup);
/// measureCpu when setup.cpu, else measureGl (`renderer` may be null for the CPU path).
Measurement measure(render::Renderer* renderer, const render::Scene& scene, const MeasureSetup& setup);

/// The CPU double-precision reference of the same definition (no GL). InputError for a .brdf scene.
Measurement measureReference(const render::Scene& scene, const analysis::Options& options);

/// The measurement camera looking along `center` with the given field of view.
PinholeCamera measurementCamera(const render::Scene& scene, const dvec3& center, double fovDeg, int w, int h);

}  // namespace hilite::measurement
