#pragma once
// hilite's public umbrella header: #include <hilite/hilite.hpp> and link hilite::hilite (CMake,
// find_package(hilite)) or `pkg-config --cflags --libs hilite`. Installed as <prefix>/include/hilite/hilite.hpp
// with the public headers below it (<prefix>/include/hilite/<layer>/*.hpp); the include path is <prefix>/include,
// so a public header can also be included alone (<hilite/scene/registry.hpp>). The internals (the GL context,
// the renderer, the shader generator, ...) are not installed.
//
// What it provides:
//   hilite/version.hpp               HILITE_VERSION_MAJOR / _MINOR / _PATCH / _STRING, hilite::kVersionString
//   hilite/scene/registry.hpp        the parameter registry: every scene and measurement parameter (name, table,
//                                    kind, default, range or choices, help, which scenes it applies to, its column)
//   hilite/scene/resolve.hpp         hilite::scene::Values (parameters by name, as text, with their origin) and
//                                    scene::resolve(values) -> Resolved (the render::Scene, the MeasureSetup, the
//                                    angles), or an InputError naming the parameter and the allowed values
//   hilite/scene/scene_file.hpp      scene files (TOML) read into Values
//   hilite/measurement/session.hpp   hilite::measurement::Session: one GL context reused; measure(resolved) -> one
//                                    Result per angle
//   hilite/measurement/result.hpp    the typed Result (the scene as measured, .shape() with its flags, the extras
//                                    the scene asks for) and toJson(result): its row (every applicable parameter
//                                    as rendered, every field), what `hilite measure --json` prints
//   hilite/measurement/measure_scene.hpp  Measurement (.shape.aspect, ...), measureReference()
//   hilite/measurement/row.hpp       measureRow(renderer, resolved) -> Result; measurementColumns()
//   hilite/render/scene.hpp          the scene (hilite/brdf/params.hpp: the BRDF's parameters)
//   hilite/brdf/terms.hpp, hilite/brdf/evaluate.hpp   the BRDF's terms and the whole BRDF in double
//   hilite/experiments/run.hpp       runExperiment(RunOptions) and mergeShards(): what `hilite run` / `merge` do
//   hilite/experiments/fit.hpp       fitting models to a measured material: what `hilite fit` does
//   hilite/core/error.hpp            InputError (bad input: a one-line message), SystemError, MachineError
//
// Minimal use (errors are hilite::InputError, a std::runtime_error with a one-line message):
//   hilite::scene::Values values;
//   values.set("model", "ggx");
//   values.set("roughness", "0.1");
//   values.set("incidence", "60");
//   hilite::measurement::Session session;
//   const hilite::measurement::Result result = session.measureOne(hilite::scene::resolve(values));
//   // result.shape().aspect ~ 0.5017, result.shape().flags.empty()
//   const nlohmann::json row = hilite::measurement::toJson(result);  // row["roughness"] == 0.1, row["flags"] == []
//
// Threading: a Session (its GL context) belongs to one thread at a time; use one per thread.
// 1.x: the headers under include/hilite/ are the API; a minor version adds to it, a major one may change it.

#include "hilite/version.hpp"

#include "hilite/analysis/highlight.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/brdf/params.hpp"
#include "hilite/brdf/terms.hpp"
#include "hilite/core/error.hpp"
#include "hilite/experiments/bounces.hpp"
#include "hilite/experiments/fit.hpp"
#include "hilite/experiments/run.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/result.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/render/area_light.hpp"
#include "hilite/render/scene.hpp"
#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"
#include "hilite/scene/scene_file.hpp"
