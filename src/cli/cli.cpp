#include "cli/cli.hpp"

#include "cli/commands.hpp"
#include "cli/help_format.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>

namespace hilite::cli {

namespace {

/// Exit code `code`, or 3 when what was printed did not all reach stdout (a full disk, /dev/full, a closed
/// pipe): a result that was not delivered is not a success.
int finishStdout(int code) {
    errno = 0;
    std::cout.flush();
    const bool flushed = std::fflush(stdout) == 0;
    if (flushed && std::cout.good() && !std::ferror(stdout)) return code;
    std::cerr << "hilite: writing to stdout failed" << (errno ? std::string(": ") + std::strerror(errno) : "") << "\n";
    return 3;
}

}  // namespace

int run(int argc, char** argv) {
    CLI::App app{
        "hilite: the highlight analyzer. Renders a plane under a light (distant, point, sphere or the sun's disk) "
        "offscreen (OpenGL via OSMesa or EGL) and measures the specular highlight's shape against the angle of "
        "incidence.",
        "hilite"};
    app.formatter(std::make_shared<HelpFormatter>(helpWidth()));  // the subcommands take it as they are added
    app.require_subcommand(1);
    app.set_version_flag("--version", "hilite 0.1.0");
    // A flag given twice: the last one wins.
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    std::map<CLI::App*, Action> actions;
    auto add = [&](const char* name, const char* desc, Action (*fn)(CLI::App&)) {
        CLI::App* sub = app.add_subcommand(name, desc);
        actions[sub] = fn(*sub);
    };
    add("render", "render the plane to PNG / PFM (measurement or photo view)", &addRender);
    add("measure", "measure the highlight: ellipse, aspect, eccentricity, per incidence angle", &addMeasure);
    add("brdf",
        "the reflectance terms' physics: albedo, fresnel, normalization (tables / JSON), strip (PNG), tabulate (MERL)",
        &addBrdf);
    add("explain", "print the resolved scene, its active effects and the GLSL it compiles", &addExplain);
    add("fit",
        "fit analytic models (phong, blinn, beckmann, ggx, ...) to a measured or given BRDF by its highlight's shape "
        "and its values, rank them and say whether any fits",
        &addFit);
    add("run", "run an experiment (sweeps, plots, contact sheet, summary) into results/<name>/", &addRun);
    add("merge", "join the outputs of sharded runs into what a single run writes", &addMerge);
    add("submit", "run an experiment on a Slurm cluster: an array job of shards and a merge job after it", &addSubmit);
    add("status", "a submitted folder's progress: rows per shard, failed shards and their last error line", &addStatus);
    add("serve", "the highlight explorer in the browser: a local web server over the library (loopback by default)",
        &addServe);
    if (argc <= 1) {  // bare `hilite`: the usage, as --help prints it, where CLI11 said only "A subcommand is required"
        std::cout << app.help();
        return finishStdout(0);
    }
    try {
        std::vector<std::string> args(argv + 1, argv + argc);
        std::reverse(args.begin(), args.end());  // CLI11 takes the vector last argument first
        app.parse(args);
    } catch (const CLI::CallForHelp& e) {
        return finishStdout(app.exit(e));  // help into /dev/full is not delivered either
    } catch (const CLI::CallForAllHelp& e) {
        return finishStdout(app.exit(e));  // help into /dev/full is not delivered either
    } catch (const CLI::CallForVersion& e) {
        return finishStdout(app.exit(e));  // help into /dev/full is not delivered either
    } catch (const CLI::ParseError& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 2;
    } catch (const InputError& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 2;
    }
    try {
        for (auto& [sub, action] : actions)
            if (sub->parsed()) return finishStdout(action());
    } catch (const InputError& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 2;
    } catch (const SystemError& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "hilite: internal error: " << e.what() << "\n";
        return 3;
    }
    return 0;
}

}  // namespace hilite::cli
