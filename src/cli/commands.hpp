#pragma once
// One function per subcommand: each adds its flags to the app and returns the action to run.

#include <CLI/CLI.hpp>

#include <functional>
#include <utility>

namespace hilite::cli {

using Action = std::function<int()>;

/// A validator refusing an empty value (`-o ''`, `--scene ''`): an empty name never means "the default".
inline CLI::Validator nonEmpty() {
    return CLI::Validator(
        [](std::string& s) { return s.empty() ? std::string("empty value (give a name)") : std::string(); },
        "NONEMPTY");
}

Action addRender(CLI::App& app);
Action addMeasure(CLI::App& app);
Action addBrdf(CLI::App& app);
Action addRun(CLI::App& app);
Action addMerge(CLI::App& app);
Action addSubmit(CLI::App& app);  ///< cli/submit_cmd.cpp
Action addStatus(CLI::App& app);
Action addExplain(CLI::App& app);
Action addFit(CLI::App& app);    ///< cli/fit_cmd.cpp
Action addServe(CLI::App& app);  ///< cli/serve_cmd.cpp
/// `brdf bounces` (cli/bounces_cmd.cpp): the subcommand, added to `brdf`, and its action.
std::pair<CLI::App*, Action> addBrdfBounces(CLI::App& brdf);
std::pair<CLI::App*, Action> addBrdfSlice(CLI::App& brdf);
std::pair<CLI::App*, Action> addBrdfInspect(CLI::App& brdf);

}  // namespace hilite::cli
