#pragma once
// The probe a .brdf shader must pass before hilite renders with it. llvmpipe has no GPU timeout, and a
// draw stuck in a user's loop cannot be interrupted from inside the process, so the shader is first
// compiled and run on tiny renders (8x8, both outputs, a wide and a narrow view at a few incidences) in a
// child process: the small helper hilite-probe (fork + exec; <prefix>/libexec, found relative to the library),
// in a fresh process because llvmpipe's threads do not survive a fork. The parent waits at most the time limit, then kills it.
// Shaders slow only in directions the probe did not visit are caught later by render::Watchdog.

#include "gl/context.hpp"
#include "hilite/render/scene.hpp"

#include <string>

namespace hilite::measurement {

/// \brief Runs the probe for a .brdf scene (nothing for a built-in model).
/// Throws InputError "PATH: shader took longer than T s on a probe render ...; stopped" past the limit, and
/// the child's own one-line InputError when the .brdf does not build (its GLSL errors name its lines).
/// `gpu`: the EGL device (--gpu), -1 unset; the child renders on the context the caller will.
void probeShader(const render::Scene& scene, const std::string& backend, double timeoutSeconds, int gpu = -1);

/// The message for a probe child that ended without its own error line: the .brdf file, how the child ended
/// (signal number and name, or exit status) and the last line it printed ("it printed nothing" if none).
/// `status` is a wait status (waitpid).
std::string probeFailure(const std::string& path, int status, const std::string& err);

/// The hilite-probe helper to run, where it is not found relative to the library (the Python module in the
/// build tree). "" restores the default search.
void setProbeExecutable(const std::string& path);

/// What the child does: compiles both outputs and renders the probe views; a failure is the usual one-line
/// InputError.
void runShaderProbe(render::Scene scene, gl::Backend backend, int gpu = -1);

/// hilite-probe's main (src/probe_main.cpp): the arguments probeShader passes; exit 0, 2 or 3.
int probeMain(int argc, char** argv);

}  // namespace hilite::measurement
