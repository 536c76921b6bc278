#pragma once
// The probe a .brdf shader must pass before hilite renders with it. llvmpipe has no GPU timeout, and a
// draw stuck in a user's loop cannot be interrupted from inside the process, so the shader is first
// compiled and run on tiny renders (8x8, both outputs, a wide and a narrow view at a few incidences) in a
// child process: this executable again (fork + exec, hidden subcommand `probe-shader`), in a fresh process
// because llvmpipe's threads do not survive a fork. The parent waits at most the time limit, then kills it.
// Shaders slow only in directions the probe did not visit are caught later by render::Watchdog.

#include "gl/context.hpp"
#include "render/scene.hpp"

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

/// The hilite executable that runs the probe from a process that is not hilite (the Python module: python3
/// is /proc/self/exe there). "" restores the default: this executable when it is hilite, else the installed one.
void setProbeExecutable(const std::string& path);

/// What the child does (the hidden subcommand `hilite probe-shader`): compiles both outputs and renders the
/// probe views; a failure is the usual one-line InputError.
void runShaderProbe(render::Scene scene, gl::Backend backend, int gpu = -1);

}  // namespace hilite::measurement
