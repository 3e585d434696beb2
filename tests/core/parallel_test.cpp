// The work pool behind for_each_index: every index exactly once, nested batches, exceptions, several callers.
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "parallel.hpp"

using impactlab::detail::for_each_index;

TEST_CASE("parallel: each index is computed exactly once, into its own slot") {
    for (std::size_t n : {0u, 1u, 2u, 3u, 100u, 10000u}) {
        CAPTURE(n);
        std::vector<std::atomic<int>> hits(n);
        for_each_index(n, [&](std::size_t i) { hits[i].fetch_add(1); });
        for (std::size_t i = 0; i < n; ++i) CHECK(hits[i].load() == 1);
    }
}

TEST_CASE("parallel: a batch started from inside another's index completes (nested)") {
    // The continuation's maps run side by side, and each map's tangent runs its pieces side by side.
    constexpr std::size_t outer = 6, inner = 50;
    std::vector<std::vector<int>> out(outer, std::vector<int>(inner, 0));
    for (int round = 0; round < 50; ++round)
        for_each_index(outer,
                       [&](std::size_t i) { for_each_index(inner, [&](std::size_t j) { out[i][j] = static_cast<int>(i * 1000 + j); }); });
    for (std::size_t i = 0; i < outer; ++i)
        for (std::size_t j = 0; j < inner; ++j) CHECK(out[i][j] == static_cast<int>(i * 1000 + j));
}

TEST_CASE("parallel: the first exception is rethrown to the caller, and the pool goes on working") {
    std::atomic<int> ran{0};
    CHECK_THROWS_AS(for_each_index(1000,
                                   [&](std::size_t i) {
                                       ran.fetch_add(1);
                                       if (i == 3) throw std::runtime_error("index 3");
                                   }),
                    std::runtime_error);
    CHECK(ran.load() >= 1);
    CHECK(ran.load() <= 1000);
    std::atomic<int> after{0};
    for_each_index(100, [&](std::size_t) { after.fetch_add(1); });
    CHECK(after.load() == 100);
}

TEST_CASE("parallel: callers on several threads at once each get their own batch done") {
    constexpr int callers = 4;
    std::vector<long> sums(callers, 0);
    std::vector<std::thread> threads;
    for (int c = 0; c < callers; ++c)
        threads.emplace_back([&, c] {
            for (int round = 0; round < 20; ++round) {
                std::vector<long> part(500, 0);
                for_each_index(part.size(), [&](std::size_t i) { part[i] = static_cast<long>(i) * (c + 1); });
                long s = 0;
                for (long v : part) s += v;
                sums[static_cast<std::size_t>(c)] += s;
            }
        });
    for (auto& t : threads) t.join();
    for (int c = 0; c < callers; ++c) CHECK(sums[static_cast<std::size_t>(c)] == 20L * (c + 1) * (499L * 500L / 2));
}
