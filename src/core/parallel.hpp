#pragma once
// parallelFor: f(0) ... f(n - 1) on every core, indices interleaved across the threads (uneven costs spread), for
// work whose items are independent (each writes its own slot), so that the result does not depend on how many
// threads ran it. The first exception an item throws is rethrown after every thread has joined.

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace hilite {

/// threads 0: std::thread::hardware_concurrency, at most 16; never more threads than items.
template <class F>
void parallelFor(int n, F&& f, int threads = 0) {
    if (n <= 0) return;
    int t = threads > 0 ? threads : int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
    t = std::clamp(t, 1, n);
    std::exception_ptr error;
    std::mutex guard;
    auto run = [&](int first) {
        try {
            for (int i = first; i < n; i += t) f(i);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(guard);
            if (!error) error = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (int k = 1; k < t; ++k) pool.emplace_back(run, k);
    run(0);
    for (std::thread& th : pool) th.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace hilite
