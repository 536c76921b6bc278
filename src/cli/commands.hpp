#pragma once
// One function per subcommand: each adds its flags to the app and returns the action to run.

#include <CLI/CLI.hpp>

#include <functional>

namespace hilite::cli {

using Action = std::function<int()>;

Action addRender(CLI::App& app);
Action addMeasure(CLI::App& app);
Action addBrdf(CLI::App& app);
Action addRun(CLI::App& app);
Action addMerge(CLI::App& app);
Action addExplain(CLI::App& app);
Action addProbeShader(CLI::App& app);  ///< cli/shader_probe.cpp

}  // namespace hilite::cli
