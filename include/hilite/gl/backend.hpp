#pragma once
// The offscreen GL backends by name: what a scene's `gl_backend` and $HILITE_GL_BACKEND choose between
// (gl/context.hpp makes the context).

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace hilite::gl {

enum class Backend { Auto, OSMesa, EGL, EGLDevice };
const char* toString(Backend);
std::ostream& operator<<(std::ostream&, Backend);
std::optional<Backend> parseBackend(const std::string&);  ///< "auto", "osmesa", "egl", "egl-device"
/// Every backend name, in the order help lists them.
std::vector<std::string> backendNames();
/// The backend asked for by the environment variable HILITE_GL_BACKEND, or Auto.
Backend backendFromEnvironment();

}  // namespace hilite::gl
