#pragma once
// Shared pieces of the command-line tests: run the hilite executable and capture what it prints, count
// lines of output, and a scratch directory that is removed again (support/temp_dir.hpp).
//
// The including test target defines HILITE_EXE (the path of the hilite executable), as hilite_test()
// targets with a cli label do in tests/CMakeLists.txt.
//
// The namespace is hilite_test, not hilite::test: a function named hilite, found unqualified through a
// using-directive, would be ambiguous with the namespace hilite. For the same reason a file using these
// helpers unqualified should not also include the project's own headers.

#include "support/temp_dir.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <string>

#ifndef HILITE_EXE
#error "run_hilite.hpp needs HILITE_EXE, the path of the hilite executable (target_compile_definitions)"
#endif

namespace hilite_test {

/// What one run of hilite gave: its exit code, its output, and the wall-clock time the run took.
struct Result {
    int code = -1;       ///< exit code; -1 when hilite did not exit normally (or could not be started)
    std::string out;     ///< stdout, and stderr too unless the run was stdoutOnly
    double seconds = 0;  ///< wall-clock time from starting hilite to its exit
};

/// Runs the shell command line `cmd`; the output holds stdout, and stderr too unless `stdoutOnly`.
inline Result command(const std::string& cmd, bool stdoutOnly = false) {
    const std::string line = cmd + (stdoutOnly ? " 2>/dev/null" : " 2>&1");
    Result r;
    const auto t0 = std::chrono::steady_clock::now();
    FILE* p = popen(line.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

/// Runs `hilite <args>` through the shell; the output holds stdout, and stderr too unless `stdoutOnly`.
inline Result hilite(const std::string& args, bool stdoutOnly = false) {
    return command(std::string(HILITE_EXE) + " " + args, stdoutOnly);
}

/// The number of lines in `s` (its newline characters).
inline int lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace hilite_test
