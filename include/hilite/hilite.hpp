#pragma once
// hilite's public umbrella header: #include <hilite/hilite.hpp> and link hilite::hilite (CMake,
// find_package(hilite)) or `pkg-config --cflags --libs hilite`. Installed as <prefix>/include/hilite/hilite.hpp
// beside the layers' headers (<prefix>/include/hilite/<layer>/*.hpp); both <prefix>/include and
// <prefix>/include/hilite are on the include path, so a layer header can also be included alone
// ("render/scene.hpp").
//
// What it provides:
//   hilite/version.hpp            HILITE_VERSION_MAJOR / _MINOR / _PATCH / _STRING, hilite::kVersionString
//   scene/registry.hpp            the parameter registry: every scene and measurement parameter (name, table,
//                                 kind, default, range or choices, help, which scenes it applies to, its column)
//   scene/resolve.hpp             hilite::scene::Values (parameters by name, as text, with their origin) and
//                                 scene::resolve(values) -> Resolved (the render::Scene, the MeasureSetup, the
//                                 angles), or an InputError naming the parameter and the allowed values
//   scene/scene_file.hpp          scene files (TOML) read into Values
//   measurement/session.hpp       hilite::measurement::Session: one GL context reused; measure(resolved) -> one
//                                 JSON row per angle (every applicable parameter as rendered, every field)
//   measurement/measure_scene.hpp the typed pipeline: measurement::measure(Renderer*, Scene, MeasureSetup) ->
//                                 Measurement (.shape.aspect, ...), measureReference(Scene, Options)
//   measurement/row.hpp           the row of a Measurement; measurementColumns()
//   render/scene.hpp, render/renderer.hpp, gl/context.hpp   the scene, the renderer and the offscreen context
//   brdf/params.hpp, brdf/terms.hpp, brdf/evaluate.hpp     the BRDF's parameters and its terms in double
//   experiments/experiment.hpp    experiment files, their configurations and the runner
//   experiments/run.hpp           runExperiment(RunOptions) and mergeShards(): what `hilite run` / `merge` do
//
// Minimal use (errors are hilite::InputError, a std::runtime_error with a one-line message):
//   hilite::scene::Values values;
//   values.set("model", "ggx");
//   values.set("roughness", "0.1");
//   values.set("incidence", "60");
//   hilite::measurement::Session session;
//   const nlohmann::json row = session.measureOne(hilite::scene::resolve(values));
//   // row["aspect"] ~ 0.5017, row["roughness"] == 0.1, row["flags"] == []
//
// Threading: a Session (its GL context) belongs to one thread at a time; use one per thread.
// The layer headers are the library's API as it stands (0.x: it may change with a minor version).

#include "hilite/version.hpp"

#include "brdf/evaluate.hpp"
#include "brdf/params.hpp"
#include "brdf/terms.hpp"
#include "core/error.hpp"
#include "experiments/bounces.hpp"
#include "experiments/experiment.hpp"
#include "experiments/fit.hpp"
#include "experiments/run.hpp"
#include "gl/context.hpp"
#include "measure/highlight.hpp"
#include "measurement/measure_scene.hpp"
#include "measurement/row.hpp"
#include "measurement/session.hpp"
#include "render/area_light.hpp"
#include "render/renderer.hpp"
#include "render/scene.hpp"
#include "scene/registry.hpp"
#include "scene/resolve.hpp"
#include "scene/scene_file.hpp"
