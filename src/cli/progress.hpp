#pragma once
// The progress line of a long command, on stderr and only when stderr is a terminal (a pipe or a file gets
// nothing: logs and tests read stdout/stderr unchanged).

#include <chrono>
#include <cstddef>
#include <string>

namespace hilite::cli {

class ProgressLine {
public:
    /// "\r<stage> [done/total] pct  elapsed  ETA", a newline when the stage is done; the clock restarts when
    /// the stage's name changes.
    void operator()(const std::string& stage, size_t done, size_t total);
    /// The same with the stage's elapsed seconds given.
    static void show(const std::string& stage, size_t done, size_t total, double seconds);

private:
    bool m_started = false;
    std::string m_stage;
    std::chrono::steady_clock::time_point m_start;
};

}  // namespace hilite::cli
