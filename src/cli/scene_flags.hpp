#pragma once
// The registry's parameters as command-line flags: one CLI11 option per entry, with the entry's
// validator, help (range, unit, default) and group (its scene-file table). Values land in a
// scene::Values with no origin, so errors name the flag; --scene FILE adds the file's values under them.

#include "hilite/scene/resolve.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>

namespace hilite::cli {

struct SceneOptions {
    scene::Values given;                          ///< the command line's values
    std::string sceneFile;                        ///< --scene
    std::map<std::string, std::string> defaults;  ///< the command's own defaults (name -> text)
};

/// Adds --scene and the flags of the registry parameters `keep` accepts (all when empty) to `app`.
void addParamFlags(CLI::App& app, SceneOptions& o, const std::function<bool(const scene::Param&)>& keep = {});
/// Keeps the parameters of the given tables.
std::function<bool(const scene::Param&)> tablesOf(std::initializer_list<scene::Table> t);
/// The values a command resolves: the scene file's, then the command line's over them, with its defaults.
scene::Values commandValues(const SceneOptions& o);

}  // namespace hilite::cli
