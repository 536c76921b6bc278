#include "render/watchdog.hpp"

#include <unistd.h>

#include <cstdio>

namespace hilite::render {

Watchdog::~Watchdog() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_quit = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable()) m_thread.join();
}

void Watchdog::arm(double seconds, std::string message, int exitCode) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_armed = true;
        m_deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                            std::chrono::duration<double>(seconds));
        m_message = std::move(message);
        m_exitCode = exitCode;
        if (!m_thread.joinable()) m_thread = std::thread([this] { loop(); });
    }
    m_wake.notify_all();
}

void Watchdog::disarm() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_armed = false;
}

void Watchdog::loop() {
    std::unique_lock<std::mutex> lock(m_mutex);
    while (!m_quit) {
        if (!m_armed) {
            m_wake.wait(lock);
            continue;
        }
        m_wake.wait_until(lock, m_deadline);
        if (m_armed && !m_quit && std::chrono::steady_clock::now() >= m_deadline) {
            // The GL call cannot be interrupted: end the process, as the message says.
            std::fputs(m_message.c_str(), stderr);
            std::fflush(stderr);
            _exit(m_exitCode);
        }
    }
}

}  // namespace hilite::render
