#pragma once
// A measuring session: the GL context and renderer made once, on first need, and reused by every
// measurement after it (a context costs tens of milliseconds; a measurement about two). The library's
// entry point: scene::Values -> scene::resolve -> Session::measure -> results (toJson: their rows).
//
// Threading: a Session belongs to one thread at a time (its GL context is current on the thread that made
// it); use one Session per thread.

#include "hilite/measurement/row.hpp"
#include "hilite/scene/resolve.hpp"

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace hilite::gl {
class Context;
}
namespace hilite::render {
class Renderer;
}

namespace hilite::measurement {

class Session {
public:
    /// `backend`: "" ($HILITE_GL_BACKEND, else auto), "auto", "osmesa" or "egl"; InputError for another name.
    explicit Session(std::string backend = "");
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    /// One result per incidence angle of `r` (r.angles), measured as its values ask.
    std::vector<Result> measure(const scene::Resolved& r);
    /// One result for the scene at r.scene.light.incidenceDeg.
    Result measureOne(const scene::Resolved& r);
    /// The renderer (made on first use), after a .brdf scene's probe and with its time limit set.
    render::Renderer& rendererFor(const scene::Resolved& r);
    /// The GL renderer's description ("llvmpipe (LLVM 15.0.6, 256 bits)"), "" before the first GL render.
    std::string glRenderer() const;
    /// The backend of the session's context; nullopt before the first GL render.
    std::optional<gl::Backend> glBackend() const;
    /// Makes the session's context current again (after another context, e.g. an experiment run's, was
    /// made current in this process); nothing before the first GL render. measure(), measureOne() and
    /// rendererFor() do it themselves; this is for a caller that renders with the renderer directly.
    void makeCurrent();

private:
    std::string m_backend;
    std::unique_ptr<gl::Context> m_context;
    std::unique_ptr<render::Renderer> m_renderer;
    std::set<std::string> m_probed;  ///< .brdf file | values | light: probed once each
};

}  // namespace hilite::measurement
