#include "hilite/measurement/session.hpp"
#include "render/renderer.hpp"

#include "measurement/shader_probe.hpp"

#include <iostream>

namespace hilite::measurement {

Session::Session(std::string backend) : m_backend(std::move(backend)) {
    scene::backendOf(m_backend);  // an unknown backend is refused now, before a caller writes anything
}
Session::~Session() = default;

render::Renderer& Session::rendererFor(const scene::Resolved& r) {
    const std::string backend = r.backend.empty() ? m_backend : r.backend;
    if (const auto& file = r.scene.brdfFile) {
        // Each .brdf file with each set of values passes the probe once (measurement/shader_probe.hpp).
        const std::string key =
            file->path + "|" + brdf_file::valuesText(*file) + "|" + render::toString(r.scene.light.type);
        if (m_probed.insert(key).second) {
            for (const std::string& note : file->notes) std::cerr << "hilite: note: " << note << "\n";
            probeShader(r.scene, backend, r.shaderTimeoutS, r.gpu);
        }
    }
    if (!m_renderer) {
        m_context = std::make_unique<gl::Context>(scene::backendOf(backend), r.gpu);
        m_renderer = std::make_unique<render::Renderer>(*m_context);
    }
    m_context->ensureCurrent();  // another context made in this process since (an experiment's) is not ours
    m_renderer->setShaderTimeLimit(r.shaderTimeoutS);
    return *m_renderer;
}

Result Session::measureOne(const scene::Resolved& r) {
    render::Renderer* gl = r.reference || r.setup.cpu ? nullptr : &rendererFor(r);
    Result res = measureRow(gl, r);
    if (gl) {  // what rendered it: a GPU or llvmpipe
        const gl::ContextInfo& info = m_context->info();
        res.gl = GlInfo{gl::toString(info.backend), info.renderer, info.vendor};
    }
    return res;
}

std::vector<Result> Session::measure(const scene::Resolved& r) {
    std::vector<Result> rows;
    scene::Resolved one = r;
    for (double angle : r.angles) {
        one.scene.light.incidenceDeg = angle;
        rows.push_back(measureOne(one));
    }
    return rows;
}

std::optional<gl::Backend> Session::glBackend() const {
    if (!m_context) return std::nullopt;
    return m_context->info().backend;
}

void Session::makeCurrent() {
    if (m_context) m_context->makeCurrent();
}

std::string Session::glRenderer() const { return m_context ? m_context->info().renderer : ""; }

}  // namespace hilite::measurement
