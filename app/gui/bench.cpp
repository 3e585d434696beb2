#include "bench.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>
#include <algorithm>

#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "sim_engine.hpp"
#include "spsc_ring.hpp"

namespace impactlab::gui {

using Clock = std::chrono::steady_clock;

namespace {
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

namespace {
// One run: a producer thread pushes n samples (retrying when full), this thread drains; samples/s.
double ring_run(std::size_t capacity, std::uint64_t n, bool& intact) {
    SpscRing<SimMsg> ring(capacity);
    std::atomic<bool> go{false};
    std::thread producer([&] {
        while (!go.load(std::memory_order_acquire)) std::this_thread::yield();
        SimMsg m;
        for (std::uint64_t i = 0; i < n; ++i) {
            m.t = static_cast<double>(i);
            // Full: let the consumer run (on a busy machine a spinning producer only burns its slice).
            while (!ring.try_push_no_drop(m)) std::this_thread::yield();
        }
    });
    std::uint64_t got = 0;
    double check = 0;
    const auto t0 = Clock::now();
    go.store(true, std::memory_order_release);
    while (got < n) {
        const std::size_t k = ring.drain([&](const SimMsg& m) { check += m.t; });
        if (k == 0) std::this_thread::yield();
        got += k;
    }
    const double s = seconds_since(t0);
    producer.join();
    intact = check == 0.5 * static_cast<double>(n) * static_cast<double>(n - 1);
    return static_cast<double>(n) / s;
}
}  // namespace

int bench_ring() {
    // Several runs per capacity: on a shared machine the two threads do not always get two cores.
    constexpr std::uint64_t kItems = 20'000'000;
    constexpr int kRuns = 5;
    for (std::size_t cap : {std::size_t{1} << 10, std::size_t{1} << 17}) {
        std::vector<double> rates;
        bool all_intact = true;
        for (int r = 0; r < kRuns; ++r) {
            bool intact = false;
            rates.push_back(ring_run(cap, kItems, intact));
            all_intact = all_intact && intact;
        }
        std::sort(rates.begin(), rates.end());
        std::printf("ring buffer: %d runs of %llu samples of %zu bytes, capacity %zu: best %.1f, median %.1f million "
                    "samples/s (best %.2f GB/s)%s\n",
                    kRuns, static_cast<unsigned long long>(kItems), sizeof(SimMsg), cap, rates.back() / 1e6,
                    rates[kRuns / 2] / 1e6, rates.back() * sizeof(SimMsg) / 1e9, all_intact ? "" : "  CONTENT MISMATCH");
    }
    return 0;
}

namespace {
struct CountSink final : MsgSink {
    SpscRing<SimMsg>* ring = nullptr;
    void put(const SimMsg& m) override { ring->try_push(m); }
};
}  // namespace

int bench_sim() {
    constexpr double kOmega = 18.0, kTransient = 20.0, kSpan = 300.0;
    for (const char* model : {"A1H", "A1C"}) {
        // The bare simulator.
        const Params p = make_version(model);
        const Drive d(kOmega);
        State s;
        s.x = -0.011;
        Simulator::make_consistent(p, d, s);
        Simulator sim;
        sim.advance(p, d, s, kTransient);
        const auto steps0 = s.steps;
        auto t0 = Clock::now();
        sim.advance(p, d, s, kTransient + kSpan);
        const double bare = seconds_since(t0);

        // The GUI engine: samples every 1 ms with energy and bumper force, through the ring to a consumer.
        SpscRing<SimMsg> ring(std::size_t{1} << 17);
        CountSink sink;
        sink.ring = &ring;
        EngineConfig cfg;
        cfg.model = model;
        cfg.omega = kOmega;
        cfg.speed = 100.0;   // 1 ms samples
        SimEngine eng(cfg, &sink);
        std::atomic<bool> done{false};
        std::uint64_t consumed = 0;
        std::thread consumer([&] {
            while (!done.load(std::memory_order_acquire) || !ring.empty()) {
                const std::size_t n = ring.drain([](const SimMsg&) {});
                if (n == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));   // like a UI frame
                consumed += n;
            }
        });
        eng.advance_to(kTransient);
        t0 = Clock::now();
        eng.advance_to(kTransient + kSpan);
        const double engine = seconds_since(t0);
        done.store(true, std::memory_order_release);
        consumer.join();
        std::printf("simulation %s, omega = %.0f rad/s, %.0f s simulated: bare simulator %.0fx real time "
                    "(%llu steps, %llu impacts); GUI engine with 1 ms samples %.0fx real time (%llu samples, %llu dropped)\n",
                    model, kOmega, kSpan, kSpan / bare, static_cast<unsigned long long>(s.steps - steps0),
                    static_cast<unsigned long long>(s.impacts), kSpan / engine,
                    static_cast<unsigned long long>(consumed), static_cast<unsigned long long>(ring.dropped()));
    }
    return 0;
}

}  // namespace impactlab::gui
