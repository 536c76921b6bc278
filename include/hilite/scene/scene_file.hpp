#pragma once
// Scene files (TOML): every registry parameter is a key in its table ([material] roughness = 0.1 is
// --roughness 0.1). Every value remembers its file and line, so an error names
// "scene.toml:4: material.roughness" instead of a flag the user never typed.

#include "hilite/scene/resolve.hpp"

#include <toml++/toml.h>

#include <string>

namespace hilite::scene {

/// The values of a scene file's text; `name` is the file in messages (and where relative paths are
/// read from). Throws InputError "file:line: key: problem (allowed ...)" on syntax errors, unknown tables
/// and keys (with a did-you-mean suggestion), keys in the wrong table and values of the wrong type.
Values parseSceneToml(const std::string& text, const std::string& name);
Values loadSceneFile(const std::string& path);
/// The TOML text of a scene file holding `values` (each given value in its table; numbers as numbers, flat
/// lists as arrays, file names made absolute so the file reads the same from any folder). parseSceneToml of
/// it gives the same values (tests/scene/test_scene_files.cpp).
std::string sceneToml(const Values& values);
/// The scene tables of an already parsed document (an experiment's [scene], a sweep case).
Values sceneValues(const toml::table& doc, const std::string& name);
/// One "table.key = value" (a sweep value) into `out`.
void setKey(Values& out, const std::string& name, const std::string& dottedKey, const toml::node& value);
/// The text of a TOML value as the command line spells it: numbers (shortest exact form), strings,
/// booleans, and flat arrays joined with ','. False for tables and nested arrays.
bool valueText(const toml::node& node, std::string& out);
/// "file:line" of a node.
std::string where(const std::string& name, const toml::node& node);
/// Reads a whole regular file (InputError naming `what` if it cannot be read).
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace hilite::scene
