// The lock-free SPSC ring buffer of the visualiser: single-thread behaviour, then two threads under load.
// Run this file under ThreadSanitizer with a build configured -DIMPACTLAB_SANITIZE=thread.
#include <doctest/doctest.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <thread>
#include <vector>

#include "../../app/gui/sim/sim_messages.hpp"
#include "../../app/gui/sim/spsc_ring.hpp"

using impactlab::gui::SpscRing;

TEST_CASE("ring: capacity must be a power of two") {
    CHECK_THROWS_AS(SpscRing<int>(0), std::invalid_argument);
    CHECK_THROWS_AS(SpscRing<int>(1), std::invalid_argument);
    CHECK_THROWS_AS(SpscRing<int>(6), std::invalid_argument);
    CHECK_NOTHROW(SpscRing<int>(8));
    CHECK(SpscRing<int>(1024).capacity() == 1024);
}

TEST_CASE("ring: empty ring pops nothing") {
    SpscRing<int> r(4);
    int out = -1;
    CHECK(r.empty());
    CHECK(r.size() == 0);
    CHECK_FALSE(r.try_pop(out));
    CHECK(out == -1);
    CHECK(r.drain([](int) { FAIL("drained from an empty ring"); }) == 0);
}

TEST_CASE("ring: full ring refuses, counts drops, and keeps its items") {
    SpscRing<int> r(4);
    for (int i = 0; i < 4; ++i) CHECK(r.try_push(i));
    CHECK(r.size() == 4);
    CHECK_FALSE(r.try_push(99));
    CHECK_FALSE(r.try_push(100));
    CHECK(r.dropped() == 2);
    CHECK_FALSE(r.try_push_no_drop(101));   // a refusal the caller retries is not a drop
    CHECK(r.dropped() == 2);
    for (int i = 0; i < 4; ++i) {
        int out = -1;
        REQUIRE(r.try_pop(out));
        CHECK(out == i);
    }
    int out = -1;
    CHECK_FALSE(r.try_pop(out));
    CHECK(r.pushed() == 4);
}

TEST_CASE("ring: wrap-around keeps FIFO order over many laps") {
    SpscRing<std::uint64_t> r(8);
    std::uint64_t next_in = 0, next_out = 0;
    // Uneven batch sizes so the indices cross the end of the array at every offset.
    for (int lap = 0; lap < 1000; ++lap) {
        const int n_in = 1 + lap % 8;
        for (int i = 0; i < n_in; ++i) REQUIRE(r.try_push(next_in++));
        const int n_out = 1 + (lap * 5) % n_in;
        for (int i = 0; i < n_out; ++i) {
            std::uint64_t v = 0;
            REQUIRE(r.try_pop(v));
            CHECK(v == next_out++);
        }
        r.drain([&](std::uint64_t v) { CHECK(v == next_out++); });
        CHECK(r.empty());
    }
    CHECK(next_out == next_in);
    CHECK(r.dropped() == 0);
}

TEST_CASE("ring: drain honours its limit and releases in one go") {
    SpscRing<int> r(16);
    for (int i = 0; i < 10; ++i) r.try_push(i);
    std::vector<int> got;
    CHECK(r.drain([&](int v) { got.push_back(v); }, 4) == 4);
    CHECK(r.size() == 6);
    CHECK(r.drain([&](int v) { got.push_back(v); }) == 6);
    REQUIRE(got.size() == 10);
    for (int i = 0; i < 10; ++i) CHECK(got[static_cast<std::size_t>(i)] == i);
}

TEST_CASE("ring: staged items stay hidden until publish, then arrive in order") {
    SpscRing<int> r(4);
    CHECK(r.try_stage(1));
    CHECK(r.try_stage(2));
    CHECK(r.unpublished() == 2);
    CHECK(r.empty());   // the consumer sees nothing yet
    int out = -1;
    CHECK_FALSE(r.try_pop(out));
    r.publish();
    CHECK(r.unpublished() == 0);
    CHECK(r.size() == 2);
    CHECK(r.pushed() == 2);
    CHECK(r.try_stage(3));
    CHECK(r.try_stage(4));
    CHECK_FALSE(r.try_stage(5));           // staged items take slots: the ring is full now
    CHECK(r.dropped() == 1);
    CHECK_FALSE(r.try_stage_no_drop(6));   // retried, not dropped
    CHECK(r.dropped() == 1);
    CHECK_FALSE(r.try_push(7));            // try_push also sees the staged slots
    CHECK(r.dropped() == 2);
    std::vector<int> got;
    r.drain([&](int v) { got.push_back(v); });
    CHECK(got == std::vector<int>{1, 2});   // 3 and 4 are still staged
    r.publish();
    r.drain([&](int v) { got.push_back(v); });
    CHECK(got == std::vector<int>{1, 2, 3, 4});
    r.publish();   // nothing staged: a no-op
    CHECK(r.pushed() == 4);
}

TEST_CASE("ring: has_room counts staged items and sees the consumer's releases") {
    SpscRing<int> r(8);
    CHECK(r.has_room(8));
    CHECK_FALSE(r.has_room(9));
    for (int i = 0; i < 6; ++i) CHECK(r.try_stage(i));
    CHECK(r.has_room(2));            // staged but unpublished items take their slots
    CHECK_FALSE(r.has_room(3));
    r.publish();
    r.drain([](int) {}, 4);          // the consumer frees four
    CHECK(r.has_room(6));            // seen at once, though the producer's cache still said full
    CHECK_FALSE(r.has_room(7));
    CHECK(r.dropped() == 0);
}

TEST_CASE("ring: the sample record is one cache line and the counters sit on separate lines") {
    CHECK(sizeof(impactlab::gui::SimMsg) == 64);
    CHECK(alignof(SpscRing<int>) >= 64);
    CHECK(sizeof(SpscRing<int>) >= 128);
}

namespace {
// A payload whose fields all derive from the sequence number, so torn or stale reads are caught.
struct Item {
    std::uint64_t seq;
    std::uint64_t check;
    double as_double;
};
constexpr std::uint64_t mix(std::uint64_t s) { return s * 0x9E3779B97F4A7C15ull ^ (s >> 7); }

// Consumer side of the lossless stress tests: drains at least `count` items made as Item{i, mix(i), i * 0.5};
// reports how many arrived and how many of those were not the next one expected, intact.
struct Consumed {
    std::uint64_t received, bad;
};
Consumed consume_in_order(SpscRing<Item>& r, std::uint64_t count) {
    std::uint64_t expected = 0, bad = 0;
    while (expected < count) {
        const std::size_t n = r.drain([&](const Item& it) {
            if (it.seq != expected || it.check != mix(expected) || it.as_double != static_cast<double>(expected) * 0.5)
                ++bad;
            ++expected;
        });
        if (n == 0) std::this_thread::yield();
    }
    return {expected, bad};
}
}  // namespace

TEST_CASE("ring: two threads, 10 million items, lossless, in order, intact") {
    constexpr std::uint64_t kItems = 10'000'000;
    SpscRing<Item> r(1024);
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kItems; ++i) {
            const Item it{i, mix(i), static_cast<double>(i) * 0.5};
            while (!r.try_push_no_drop(it)) std::this_thread::yield();
        }
    });
    const Consumed got = consume_in_order(r, kItems);
    producer.join();
    CHECK(got.bad == 0);
    CHECK(got.received == kItems);
    CHECK(r.dropped() == 0);
    CHECK(r.empty());
}

TEST_CASE("ring: two threads, 10 million items published in batches, lossless, in order, intact") {
    // The simulation thread's way: stage a work slice, publish it with one release store.
    constexpr std::uint64_t kItems = 10'000'000;
    SpscRing<Item> r(1024);
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kItems; ++i) {
            const Item it{i, mix(i), static_cast<double>(i) * 0.5};
            while (!r.try_stage_no_drop(it)) {
                r.publish();
                std::this_thread::yield();
            }
            if (r.unpublished() >= 1 + i % 300) r.publish();   // uneven batches
        }
        r.publish();
    });
    const Consumed got = consume_in_order(r, kItems);
    producer.join();
    CHECK(got.bad == 0);
    CHECK(got.received == kItems);
    CHECK(r.dropped() == 0);
    CHECK(r.pushed() == kItems);
}

TEST_CASE("ring: two threads, 10 million items, lossy producer: drops counted, survivors in order") {
    constexpr std::uint64_t kItems = 10'000'000;
    SpscRing<Item> r(256);
    std::atomic<bool> done{false};
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kItems; ++i) r.try_push(Item{i, mix(i), static_cast<double>(i)});
        done.store(true, std::memory_order_release);
    });
    std::uint64_t received = 0, bad = 0;
    std::uint64_t last = 0;
    bool first = true;
    auto take = [&](const Item& it) {
        if (it.check != mix(it.seq) || it.as_double != static_cast<double>(it.seq)) ++bad;
        if (!first && it.seq <= last) ++bad;
        first = false;
        last = it.seq;
        ++received;
    };
    for (;;) {
        const bool finished = done.load(std::memory_order_acquire);
        const std::size_t n = r.drain(take);
        if (finished && n == 0 && r.empty()) break;
    }
    producer.join();
    CHECK(bad == 0);
    CHECK(received + r.dropped() == kItems);
    CHECK(received == r.pushed());
    CHECK(received > 0);
}
