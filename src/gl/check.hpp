#pragma once
// GL error checking: every error is reported by name with the call site.

namespace hilite::gl {

/// Throws SystemError("GL_INVALID_OPERATION after <what> at file:line") if glGetError() reports anything.
void checkErrors(const char* what, const char* file, int line);
const char* errorName(unsigned int code);

}  // namespace hilite::gl

#define HILITE_GL_CHECK_WHAT(what) ::hilite::gl::checkErrors(what, __FILE__, __LINE__)
#define HILITE_GL_CHECK() ::hilite::gl::checkErrors(__func__, __FILE__, __LINE__)
