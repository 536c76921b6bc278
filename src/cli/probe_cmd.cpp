// `hilite probe-shader` (hidden): the child process of measurement::probeShader, which renders a .brdf
// scene's probe views so that a shader that hangs or crashes does so here, not in the parent.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "measurement/shader_probe.hpp"

#include <memory>

namespace hilite::cli {

Action addProbeShader(CLI::App& app) {
    auto f = std::make_shared<SceneOptions>();
    addParamFlags(app, *f, [](const scene::Param& p) { return p.table != scene::Table::Measurement; });
    app.group("");  // hidden: run by probeShader() in a child process
    return [f] {
        const scene::Resolved r = scene::resolve(commandValues(*f), scene::Purpose::Render);
        measurement::runShaderProbe(r.scene, scene::backendOf(r));
        return 0;
    };
}

}  // namespace hilite::cli
