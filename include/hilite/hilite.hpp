#pragma once
// hilite's public umbrella header: #include <hilite/hilite.hpp> and link hilite::hilite (CMake,
// find_package(hilite)) or `pkg-config --cflags --libs hilite`. Installed as <prefix>/include/hilite/hilite.hpp
// beside the layers' headers (<prefix>/include/hilite/<layer>/*.hpp); both <prefix>/include and
// <prefix>/include/hilite are on the include path, so a layer header can also be included alone
// ("render/scene.hpp").
//
// What it provides:
//   hilite/version.hpp            HILITE_VERSION_MAJOR / _MINOR / _PATCH / _STRING, hilite::kVersionString
//   brdf/params.hpp               hilite::brdf::Params: model (Model::GGX, ...), roughness / exponent,
//                                 Fresnel, Geometry (Implicit, Smith, ...), Diffuse, anisotropy
//   brdf/terms.hpp                the reflectance terms in double precision (D, G, F, diffuse), the CPU twin
//                                 of shaders/brdf.glsl
//   render/scene.hpp              hilite::render::Scene: the BRDF, the Light (directional or point,
//                                 incidenceDeg, azimuthDeg), the eye, the surface
//   gl/context.hpp                hilite::gl::Context: an offscreen OpenGL context (OSMesa or EGL, Mesa's llvmpipe)
//   render/renderer.hpp           hilite::render::Renderer: draws a Scene through a camera and reads it back;
//                                 finds its shaders in $HILITE_SHARE_DIR/shaders, beside the executable
//                                 (<exe>/../share/hilite) or in the install prefix compiled in
//   measure/highlight.hpp         hilite::measure::Shape (aspect, major_deg, minor_deg, ...) and Options
//   experiments/measure_scene.hpp the measurement pipeline: hilite::experiments::measure(Renderer*, Scene,
//                                 MeasureSetup) -> Measurement (.shape.aspect), with automatic framing
//
// Minimal use:
//   hilite::gl::Context context;                 // current while the renderer lives
//   hilite::render::Renderer renderer(context);
//   hilite::render::Scene scene;                 // GGX alpha 0.1, directional light
//   scene.light.incidenceDeg = 60;
//   const auto m = hilite::experiments::measure(&renderer, scene, {});  // 512 x 512, automatic framing
//   // m.shape.aspect ~ 0.5017
//
// The layer headers are the library's API as it stands (0.x: it may change with a minor version).

#include "hilite/version.hpp"

#include "brdf/params.hpp"
#include "brdf/terms.hpp"
#include "experiments/measure_scene.hpp"
#include "gl/context.hpp"
#include "measure/highlight.hpp"
#include "render/renderer.hpp"
#include "render/scene.hpp"
