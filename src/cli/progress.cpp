#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace hilite::cli {

void ProgressLine::operator()(const std::string& stage, size_t done, size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (!m_started || stage != m_stage || done == 0) m_started = true, m_stage = stage, m_start = now;
    show(stage, done, total, std::chrono::duration<double>(now - m_start).count());
}

void ProgressLine::show(const std::string& stage, size_t done, size_t total, double seconds) {
    static const bool tty = isatty(fileno(stderr));
    if (!tty) return;
    const double eta = done ? seconds / double(done) * double(total - done) : 0;
    std::fprintf(stderr, "\r%s%s[%zu/%zu] %5.1f%%  elapsed %.1fs  ETA %.1fs   ", stage.c_str(),
                 stage.empty() ? "" : " ", done, total, total ? 100.0 * double(done) / double(total) : 100.0, seconds,
                 eta);
    if (done == total) std::fprintf(stderr, "\n");
}

}  // namespace hilite::cli
