// parallelFor (core/parallel.hpp): every index once, whatever the thread count; an item's exception reaches the
// caller after the threads have joined.

#include "core/parallel.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

using namespace hilite;

TEST_CASE("parallelFor runs every index exactly once for any thread count") {
    for (int threads : {0, 1, 2, 3, 7, 64}) {
        for (int n : {0, 1, 5, 100}) {
            std::vector<std::atomic<int>> hits(static_cast<size_t>(n));
            parallelFor(
                n, [&](int i) { ++hits[size_t(i)]; }, threads);
            CAPTURE(threads);
            CAPTURE(n);
            for (const auto& h : hits) CHECK(h.load() == 1);
        }
    }
}

TEST_CASE("parallelFor rethrows an item's exception after every thread has finished") {
    std::atomic<int> done{0};
    CHECK_THROWS_AS(parallelFor(
                        64,
                        [&](int i) {
                            if (i == 13) throw std::runtime_error("item 13");
                            ++done;
                        },
                        4),
                    std::runtime_error);
    CHECK(done.load() >= 48);  // the other threads ran their indices to the end (13's thread stopped at it)
}
