#pragma once
// The hard cases of where the maths breaks (grazing angles, mirror-like lobes, huge exponents,
// degenerate geometry) the tool must give finite numbers or a named diagnosis, on both paths:
//   - GL: the shader, float32 (every pixel of both outputs, and the measurement through GL);
//   - double: the CPU twin (the same pixels in double, and the double reference measurement).
// Two tables, each row one doctest case per path (tests/hard/test_hard.cpp; add a row, get two cases):
//   - scene rows (scene_cases.cpp): a scene, a camera for the pixel checks, the measurement, and the
//     flags each path must answer with;
//   - term rows (term_cases.cpp): one GLSL term at given arguments against its C++ twin.
// build/bin/hilite_hard_report prints the measured outcome of every row as docs/hard_cases.md's tables.

#include "hilite/analysis/highlight.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "render/renderer.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hilite::hard {

// ---- Scene rows ----

/// Where the pixel checks look.
enum class View {
    Lobe,   ///< the measurement view on the mirror direction, framed on the twin's lobe (as automatic framing seeds it)
    Fixed,  ///< the measurement view on the mirror direction with a fixed field of view
    Photo,  ///< looking across the plane from `elevationDeg` (negative: from below it), opposite the light
};

struct Camera {
    View view = View::Lobe;
    double fovDeg = 30;        ///< Fixed, Photo
    double elevationDeg = 10;  ///< Photo
    int size = 128;            ///< square image
};

struct SceneCase {
    std::string name;
    render::Scene scene;
    Camera camera;
    measurement::MeasureSetup setup;  ///< the measurement (default: automatic framing, 256^2)
    analysis::FlagSet glFlags;        ///< exactly the flags the GL measurement must report
    analysis::FlagSet refFlags;       ///< exactly the flags the double reference must report
    double tolerance = 0;             ///< GL vs twin, relative, per pixel; 0: pixelTolerance() of the lobe
    double aspectTolerance = 0;       ///< GL vs reference in aspect; 0: the suite's (0.005)
};

const std::vector<SceneCase>& sceneCases();

/// The stated GL-vs-twin tolerance for a lobe of minor half-width r (rad): max(1e-4, 16 * 2^-24 / r), and
/// none (infinite) below measurement::kEffectivelyMirrorHalfWidth, where GL says effectively_mirror.
/// The shader knows a pixel's direction only to about a float step (2^-24 rad, measurement/diagnose.hpp),
/// and a lobe's log changes by a few units per r radians, so a pixel's relative error grows as step / r:
/// measured 1-6.5 step / r over the rows (largest: anisotropic Beckmann, steepest at the 1e-3-of-peak
/// floor of the comparison; docs/hard_cases.md); 16 leaves a factor 2.4. 1e-4 is the floor of wide lobes.
double pixelTolerance(double minorHalfWidth);

/// Every pixel of both outputs (colour, measurement) of one path, and its agreement with the other.
struct PixelCheck {
    long values = 0;            ///< floats checked (4 per pixel and output)
    long nonFinite = 0;         ///< NaN or Inf among them
    long negative = 0;          ///< negative radiance, L or pixel weight
    long compared = 0;          ///< pixels above 1e-3 of the peak, compared with the other path
    double maxRelError = 0;     ///< colour and L, relative, over the compared pixels
    double maxUvError = 0;      ///< chart coordinates, absolute (rad), over the visible pixels
    double maxWeightError = 0;  ///< pixel (u, v) area, relative, over the visible pixels
};

struct SceneOutcome {
    PixelCheck pixels;
    measurement::Measurement measurement;
    double minorHalfWidth = 0;  ///< the twin's lobe (rad), 0 if it has none at the mirror direction
    double tolerance = 0;       ///< the pixel tolerance applied
};

/// The GL path: renders both outputs with the row's camera (compared with the double twin pixel by
/// pixel) and measures through GL. `renderer` must have its context current.
SceneOutcome runSceneGl(render::Renderer& renderer, const SceneCase& c);
/// The double path: the twin's value of both outputs at the same pixels, and the double reference.
SceneOutcome runSceneDouble(const SceneCase& c);

/// The shape fields are finite (the reference's minor_pixels is +inf by definition and not a field).
bool shapeFinite(const analysis::Shape& s);
/// A measurement answers with numbers (peak > 0 and a semi-major axis > 0) or a diagnosis that replaces
/// them: no_highlight, mirror, under_resolved.
bool numbersOrDiagnosis(const analysis::Shape& s);
std::string flagList(const analysis::FlagSet& flags);

// ---- Term rows ----

struct TermCase {
    std::string name;
    std::vector<std::string> blocks;  ///< the shaders/brdf.glsl blocks the GLSL calls
    std::string glsl;                 ///< statements setting `vec4 r` from `float a[8]` (uniforms)
    std::vector<double> args;         ///< a[0..]
    std::function<glm::dvec4(const std::vector<double>& a)> twin;  ///< the C++ twin, same components
    int components = 1;                                            ///< how many of r's components are checked
    std::optional<glm::dvec4> expected;  ///< the exact answer where known (checked on the double path)
    double tolerance = 1e-5;             ///< GL vs twin at the float-rounded arguments, relative (absolute below 1e-30)
};

const std::vector<TermCase>& termCases();

struct TermOutcome {
    glm::dvec4 value{0.0};  ///< the path's result
    glm::dvec4 twin{0.0};   ///< GL path: the twin at the float-rounded arguments
    double error = 0;       ///< GL path: largest relative difference (absolute where |twin| < 1e-30)
};

TermOutcome runTermGl(const TermCase& c);  ///< needs a current GL context
TermOutcome runTermDouble(const TermCase& c);

}  // namespace hilite::hard
