#pragma once
// The scene flags shared by `render`, `measure` and later subcommands, their ranges, and their checks.
// Every check throws InputError naming the flag, the allowed range and the value given.

#include "cli/surface_flags.hpp"
#include "core/camera.hpp"
#include "gl/context.hpp"
#include "render/scene.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace hilite::cli {

enum class View { Measure, Photo };

struct SceneFlags {
    std::string model = "ggx";
    double exponent = 1000.0;
    double roughness = 0.1;
    std::string roughnessY;          ///< "" = isotropic
    double tangentAngle = 0.0;       ///< degrees
    std::string fresnel;             ///< "" = the material's, else none
    std::string f0;                  ///< "" = from --eta/--k, the material, else 0.04
    std::string eta, k;              ///< "" = the material's, else 1.5 and 0
    std::string material;            ///< "" = none
    std::string geometry = "implicit";
    std::string diffuse = "none";
    std::string albedo = "0.5";
    double sigma = 20.0;             ///< Oren-Nayar, degrees
    std::string ndfTable;            ///< --model tabulated: the CSV of D against theta_h (issue 10)
    int spectralStepNm = 5;          ///< spectral Fresnel: 5 nm (81 GPU uniforms) for renders, 1 nm (full tables) for `brdf`
    std::string incidence = "45";  ///< render: one angle; measure: one, a list or a range
    double azimuth = 0.0;
    double irradiance = 1.0;
    std::string size = "512";
    double fov = 0.0;  ///< 0: the view's default (render) or automatic framing (measure)
    std::string view = "measure";
    double elevation = -1.0;  ///< photo view; < 0: 90 - incidence (the mirror direction)
    double distance = 10.0;   ///< the eye's distance from the origin (photo view; point light in any view)
    std::string light = "directional";
    double intensity = 1.0;       ///< point light I
    double lightDistance = 10.0;  ///< point light distance from the origin
    std::string backend = "";  ///< empty: $HILITE_GL_BACKEND or auto
    std::string brdf;                 ///< a BRDF Explorer .brdf file instead of --model ("" = none)
    std::vector<std::string> params;  ///< its --param NAME=VALUE assignments, in order (later ones win)
    double shaderTimeout = 10.0;      ///< seconds a .brdf shader may take: probe render, each compile, each draw
    std::string sceneFile;     ///< --scene: already expanded into flags by cli::run
    SurfaceFlags surface;      ///< [surface]: explicit micro-geometry (issue 10)
};

/// Adds the scene flags to a subcommand; `incidenceHelp` describes the accepted --incidence forms.
void addSceneFlags(CLI::App& app, SceneFlags& f, const std::string& incidenceHelp);

/// The validated BRDF of the flags.
brdf::Params brdfParams(const SceneFlags& f);
/// The validated scene of the flags (BRDF, light, eye distance); the incidence is left to the caller.
/// With --brdf, the file is read and its --param values assigned (InputError naming file:line:param).
render::Scene sceneOf(const SceneFlags& f);
/// Parses --size "N" or "WxH" within 1..16384 and the memory this machine has.
void parseSize(const std::string& s, int& width, int& height);
/// Parses --incidence: "30", "0,30,60" or "0:85:5" (start:stop:step, inclusive), each in [0, 90].
std::vector<double> parseIncidence(const std::string& s, bool allowMany);
View parseView(const std::string& s);
gl::Backend parseBackendFlag(const std::string& s);
/// The number `text` spells, or throws InputError "flag: 'text' is not a number".
double parseNumberFlag(const std::string& flag, const std::string& text);
/// A finite number within [lo, hi] or throws InputError "flag: must be ... (got ...)".
double checkRange(const std::string& flag, double v, double lo, double hi);

/// The camera of the chosen view, for a scene at one incidence angle.
PinholeCamera viewCamera(const SceneFlags& f, View view, const render::Scene& scene, int width, int height);

}  // namespace hilite::cli
