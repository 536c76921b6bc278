// `hilite probe-shader` (hidden): the child process of measurement::probeShader, which renders a .brdf
// scene's probe views so that a shader that hangs or crashes does so here, not in the parent.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "measurement/shader_probe.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace hilite::cli {

Action addProbeShader(CLI::App& app) {
    auto f = std::make_shared<SceneOptions>();
    addParamFlags(app, *f, [](const scene::Param& p) { return p.table != scene::Table::Measurement; });
    app.group("");  // hidden: run by probeShader() in a child process
    return [f] {
        const scene::Resolved r = scene::resolve(commandValues(*f), scene::Purpose::Render);
        // Test hook: a GL driver crash cannot be provoked on purpose, so tests/cli/test_hostile.cpp makes
        // this child die of the named signal after a line on stderr, as a Mesa compiler abort does.
        if (const char* sig = std::getenv("HILITE_TEST_PROBE_SIGNAL"); sig && std::atoi(sig) > 0) {
            std::fprintf(stderr, "test: simulated shader compiler crash\n");
            std::signal(std::atoi(sig), SIG_DFL);
            std::raise(std::atoi(sig));
        }
        measurement::runShaderProbe(r.scene, scene::backendOf(r), r.gpu);
        return 0;
    };
}

}  // namespace hilite::cli
