#pragma once
// A time limit on GL work that runs user shader code. llvmpipe has no GPU timeout: a .brdf whose BRDF()
// loops for ever would hang the tool inside glReadPixels, where no exception or flag can reach it (the
// fragment shader runs on llvmpipe's own threads). So the watchdog thread ends the process: when a limit
// armed with arm() passes before disarm(), it writes its message to stderr and calls _exit(code). Files
// already written stay whole (results are appended row by row, images written after their render).
// The CLI first runs a probe render in a child process (measurement/shader_probe.cpp), which catches most slow
// shaders with a clean error; this is the backstop for a shader slow only in directions the probe missed.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace hilite::render {

class Watchdog {
public:
    Watchdog() = default;
    ~Watchdog();
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

    /// Starts the clock: unless disarm() comes within `seconds`, the process ends with `message` on stderr.
    void arm(double seconds, std::string message, int exitCode = 2);
    void disarm();

    /// Disarms when it goes out of scope (an exception between arm and disarm must not end the process).
    struct Scope {
        Watchdog* dog;
        ~Scope() {
            if (dog) dog->disarm();
        }
    };

private:
    void loop();

    std::thread m_thread;  ///< started by the first arm()
    std::mutex m_mutex;
    std::condition_variable m_wake;
    bool m_armed = false, m_quit = false;
    std::chrono::steady_clock::time_point m_deadline;
    std::string m_message;
    int m_exitCode = 2;
};

}  // namespace hilite::render
