#pragma once
// Scene files (TOML): every command-line flag of `render`/`measure` is a key, grouped in the tables
// [material] [light] [camera] [measurement] [output]; `--roughness 0.1` is `roughness = 0.1` under
// [material]. A file becomes a list of flag arguments placed before the command line's own, so flags
// given on the command line override the file. Every argument remembers where it came from, so an
// error names "scene.toml:4: material.roughness" instead of a flag the user never typed.

#include <CLI/CLI.hpp>
#include <toml++/toml.h>

#include <map>
#include <string>
#include <vector>

namespace hilite::cli {

struct SceneArg {
    std::string flag;    ///< "--roughness"
    std::string value;   ///< as the command line would spell it: "0.1", "0.9,0.6,0.3", "true"
    std::string origin;  ///< "scene.toml:4: material.roughness"
};

/// The table a flag belongs to in a scene file (its CLI11 group, lower-cased), e.g. "material".
std::string sectionOf(const CLI::Option& opt);

/// Parses a TOML document against the options of `app` (a subcommand with the scene flags).
/// `name` is used in messages. Throws InputError "file:line: key: problem (allowed ...)" on syntax errors,
/// unknown keys (with a did-you-mean suggestion), keys in the wrong table and values of the wrong type.
std::vector<SceneArg> parseSceneToml(const std::string& text, const std::string& name, const CLI::App& app);
std::vector<SceneArg> loadSceneFile(const std::string& path, const CLI::App& app);
/// The scene tables of an already parsed document (e.g. an experiment's [scene]); `name` for messages.
std::vector<SceneArg> sceneArgs(const toml::table& doc, const std::string& name, const CLI::App& app);
/// One "section.key = value" (e.g. a sweep axis value) as a flag argument.
SceneArg sceneArg(const std::string& name, const std::string& dottedKey, const toml::node& value, const CLI::App& app);

/// Closest of `candidates` to `word` by edit distance, or "" if none is close.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

/// Puts the section of each scene flag of `app` (the options added since `firstOption`) into its CLI11
/// group, so help lists them by table and the scene-file loader knows where each key belongs.
void assignSections(CLI::App& app, size_t firstOption);

/// Inserts the arguments of `--scene FILE` (if given after the subcommand) into `args` right after the
/// subcommand name, so the command line's own flags come later and win. Returns flag -> origin for the
/// values that came from the file and were not overridden.
std::map<std::string, std::string> expandSceneFile(std::vector<std::string>& args, CLI::App& app);

/// Rewrites an error that starts with "--flag:" to name the scene file and key the value came from,
/// when that flag's value came from a file (origins: flag -> origin).
std::string withOrigin(const std::string& message, const std::map<std::string, std::string>& origins);

}  // namespace hilite::cli
