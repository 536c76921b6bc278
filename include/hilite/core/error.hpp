#pragma once
// Errors are values: a failing operation returns (or throws, at the CLI boundary) an Error whose
// message is one line naming what was wrong and what is allowed.

#include <stdexcept>
#include <string>

namespace hilite {

/// Bad input from a user (flag, file, key): the CLI prints the message and exits with code 2.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The machine or a library failed (GL context, shader compile, I/O): exit code 3.
class SystemError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace hilite
