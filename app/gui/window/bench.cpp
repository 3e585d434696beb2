#include "bench.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>
#include <algorithm>

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif

#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "sim/sim_engine.hpp"
#include "sim/spsc_ring.hpp"

namespace impactlab::gui {

using Clock = std::chrono::steady_clock;

namespace {
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

namespace {
// Pins the calling thread to one CPU (cpu >= 0) or lets it run on any (cpu < 0), so "across cores"
// means what it says. Linux only; a no-op elsewhere.
void pin_to_cpu(int cpu) {
#ifdef __linux__
    cpu_set_t set;
    CPU_ZERO(&set);
    const unsigned n = std::thread::hardware_concurrency();
    for (unsigned i = 0; i < n; ++i)
        if (cpu < 0 || static_cast<unsigned>(cpu) == i) CPU_SET(i, &set);
    pthread_setaffinity_np(pthread_self(), sizeof set, &set);
#else
    (void)cpu;
#endif
}

// Spins for about `n` pause instructions: cheaper than a yield, and it keeps a polling consumer from
// pulling the producer's head_ line across on every item.
void cpu_relax(int n) {
    for (int i = 0; i < n; ++i) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#elif defined(__aarch64__)
        asm volatile("yield");
#else
        std::atomic_signal_fence(std::memory_order_seq_cst);
#endif
    }
}

// One run: a producer thread pushes n samples (retrying when full), publishing every `batch` of them the
// way the simulation thread does (1 = a release store per sample); this thread drains. Samples/s.
double ring_run(std::size_t capacity, std::uint64_t n, std::uint64_t batch, int producer_cpu, int consumer_cpu,
                bool& intact) {
    SpscRing<SimMsg> ring(capacity);
    std::atomic<bool> go{false};
    // n and batch by value: read on every push, they must not share a line with the consumer's locals.
    std::thread producer([&ring, &go, n, batch, producer_cpu] {
        if (producer_cpu >= 0) pin_to_cpu(producer_cpu);
        while (!go.load(std::memory_order_acquire)) std::this_thread::yield();
        SimMsg m;
        for (std::uint64_t i = 0; i < n; ++i) {
            m.t = static_cast<double>(i);
            // Full: show what is staged and let the consumer run (a spinning producer only burns its slice).
            while (!ring.try_stage_no_drop(m)) {
                ring.publish();
                std::this_thread::yield();
            }
            if (ring.unpublished() >= batch) ring.publish();
        }
        ring.publish();
    });
    if (consumer_cpu >= 0) pin_to_cpu(consumer_cpu);
    std::uint64_t got = 0;
    int idle = 0;
    double check = 0;
    const auto t0 = Clock::now();
    go.store(true, std::memory_order_release);
    while (got < n) {
        const std::size_t k = ring.drain([&](const SimMsg& m) { check += m.t; });
        // Empty: back off a little before polling head_ again (a UI that drains per frame does far more),
        // and give the CPU away if that does not help (the producer may be waiting for this very core).
        idle = k ? 0 : idle + 1;
        if (idle > 16) std::this_thread::yield();
        else if (idle > 0) cpu_relax(64);
        got += k;
    }
    const double s = seconds_since(t0);
    producer.join();
    intact = check == 0.5 * static_cast<double>(n) * static_cast<double>(n - 1);
    return static_cast<double>(n) / s;
}
}  // namespace

int bench_ring() {
    // Several runs per case: on a shared machine the two threads do not always get two cores.
    constexpr std::uint64_t kItems = 20'000'000;
    constexpr int kRuns = 5;
    const unsigned cpus = std::thread::hardware_concurrency();
    struct Case {
        const char* where;
        int producer_cpu, consumer_cpu;
    };
    std::vector<Case> cases{{"same core", 0, 0}};
    if (cpus >= 2) cases.push_back({"across cores", 1, 0});
    for (const Case& c : cases) {
        for (std::uint64_t batch : {std::uint64_t{1}, std::uint64_t{256}}) {
            const std::size_t cap = std::size_t{1} << 17;   // the app's sample ring
            std::vector<double> rates;
            bool all_intact = true;
            for (int r = 0; r < kRuns; ++r) {
                bool intact = false;
                rates.push_back(ring_run(cap, kItems, batch, c.producer_cpu, c.consumer_cpu, intact));
                all_intact = all_intact && intact;
            }
            std::sort(rates.begin(), rates.end());
            std::printf("ring buffer, %s, publish every %llu: %d runs of %llu samples of %zu bytes, capacity %zu: "
                        "best %.1f, median %.1f million samples/s (median %.2f GB/s)%s\n",
                        c.where, static_cast<unsigned long long>(batch), kRuns,
                        static_cast<unsigned long long>(kItems), sizeof(SimMsg), cap, rates.back() / 1e6,
                        rates[kRuns / 2] / 1e6, rates[kRuns / 2] * sizeof(SimMsg) / 1e9,
                        all_intact ? "" : "  CONTENT MISMATCH");
        }
    }
    pin_to_cpu(-1);   // this thread runs anywhere again
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
        std::uint64_t consumed = 0;
#ifdef __EMSCRIPTEN__
        // A browser page has no threads: the ring is drained between slices of 0.5 s simulated (a frame's
        // worth at 30x real time), as the page's frames drain it.
        eng.advance_to(kTransient);
        t0 = Clock::now();
        for (double t = kTransient; t < kTransient + kSpan;) {
            t = std::min(t + 0.5, kTransient + kSpan);
            eng.advance_to(t);
            consumed += ring.drain([](const SimMsg&) {});
        }
        const double engine = seconds_since(t0);
#else
        std::atomic<bool> done{false};
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
#endif
        std::printf("simulation %s, omega = %.0f rad/s, %.0f s simulated: bare simulator %.0fx real time "
                    "(%llu steps, %llu impacts); GUI engine with 1 ms samples %.0fx real time (%llu samples, %llu dropped)\n",
                    model, kOmega, kSpan, kSpan / bare, static_cast<unsigned long long>(s.steps - steps0),
                    static_cast<unsigned long long>(s.impacts), kSpan / engine,
                    static_cast<unsigned long long>(consumed), static_cast<unsigned long long>(ring.dropped()));
    }
    return 0;
}

}  // namespace impactlab::gui
