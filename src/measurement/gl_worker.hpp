#pragma once
// One GL thread: one measurement::Session (one GL context, made on first need) lives on one thread for the life
// of its owner, and every call that needs it runs there, one at a time, in the order the calls arrive. A GL
// context is current on one thread (gl/context.hpp), while calls come from any thread: the Python module's
// (python/src/module.cpp: callers wait with the GIL released, so other Python threads keep running) and
// `hilite serve`'s HTTP threads (cli/serve_cmd.cpp: one render at a time, the others queue).

#include "hilite/measurement/session.hpp"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <mutex>
#include <sstream>
#include <thread>

namespace hilite::measurement {

class GlWorker {
public:
    using Job = std::function<void(measurement::Session&)>;

    /// Runs `job` on the GL thread and waits for it; its exception is rethrown here.
    void run(const Job& job) {
        std::packaged_task<void()> task([this, &job] {
            if (!m_session) m_session = std::make_unique<measurement::Session>();
            job(*m_session);
        });
        std::future<void> done = task.get_future();
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            if (m_stopped)
                throw std::runtime_error("hilite: the GL thread has stopped (interpreter exit or server shutdown)");
            if (!m_thread.joinable()) m_thread = std::thread([this] { loop(); });
            m_jobs.push_back(std::move(task));
        }
        m_wake.notify_one();
        done.get();
    }

    /// Ends the thread after the jobs queued (the Session and its context are released on it).
    void stop() {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stopped = true;
        }
        m_wake.notify_one();
        if (m_thread.joinable()) m_thread.join();
    }

    /// The GL thread's id as text ("" before the first call): the threading tests read it.
    std::string threadId() {
        std::lock_guard<std::mutex> lock(m_mutex);
        if (!m_thread.joinable()) return "";
        std::ostringstream s;
        s << m_thread.get_id();
        return s.str();
    }

private:
    void loop() {
        for (;;) {
            std::packaged_task<void()> task;
            {
                std::unique_lock<std::mutex> lock(m_mutex);
                m_wake.wait(lock, [this] { return m_stopped || !m_jobs.empty(); });
                if (m_jobs.empty()) break;  // stopped, and nothing left to run
                task = std::move(m_jobs.front());
                m_jobs.pop_front();
            }
            task();
        }
        m_session.reset();  // the context is released on the thread it is current on
    }

    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<std::packaged_task<void()>> m_jobs;
    std::thread m_thread;
    bool m_stopped = false;
    std::unique_ptr<measurement::Session> m_session;  ///< touched only on the GL thread
};

}  // namespace hilite::measurement
