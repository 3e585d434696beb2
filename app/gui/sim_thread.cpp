#include "sim_thread.hpp"

#include <algorithm>
#include <chrono>

namespace impactlab::gui {

using Clock = std::chrono::steady_clock;

SimThread::SimThread(const EngineConfig& cfg) : engine_(cfg, &sink_) {
    paused_.store(engine_.paused(), std::memory_order_relaxed);
}

SimThread::~SimThread() { stop(); }

void SimThread::start() {
    if (thread_.joinable()) return;
    quit_.store(false, std::memory_order_relaxed);
    thread_ = std::thread([this] { run(); });
}

void SimThread::stop() {
    quit_.store(true, std::memory_order_relaxed);
    if (thread_.joinable()) thread_.join();
}

bool SimThread::send(const SimCommand& c) { return commands_.try_push(c); }

SimStatus SimThread::status() const {
    SimStatus s;
    s.sim_time = sim_time_.load(std::memory_order_relaxed);
    s.achieved_speed = achieved_.load(std::memory_order_relaxed);
    s.paused = paused_.load(std::memory_order_relaxed);
    s.lagging = lagging_.load(std::memory_order_relaxed);
    s.dropped = samples_.dropped();
    s.commands_dropped = commands_.dropped();
    return s;
}

void SimThread::run() {
    // Pacing: sim time follows anchor_sim + speed * (wall - anchor_wall). Any command, a pause or a lag
    // re-anchors, so the simulation never tries to catch up on time it could not spend.
    auto anchor_wall = Clock::now();
    double anchor_sim = engine_.state().t;
    double speed = engine_.speed();
    // Achieved speed: sim time per wall time over windows of ~0.5 s.
    auto meter_wall = anchor_wall;
    double meter_sim = anchor_sim;

    engine_.publish_state();   // the UI sees the initial state even when started paused
    sink_.publish();
    while (!quit_.load(std::memory_order_relaxed)) {
        bool changed = false;
        commands_.drain([&](const SimCommand& c) {
            engine_.apply(c);
            changed = true;
        });
        if (changed) sink_.publish();   // a command may publish the new state (reset, model switch)
        const auto now = Clock::now();
        if (changed || engine_.speed() != speed) {
            speed = engine_.speed();
            anchor_wall = now;
            anchor_sim = engine_.state().t;
        }
        paused_.store(engine_.paused() && !engine_.stepping(), std::memory_order_relaxed);

        if (engine_.paused() && !engine_.stepping()) {
            anchor_wall = now;
            anchor_sim = engine_.state().t;
            meter_wall = now;
            meter_sim = anchor_sim;
            achieved_.store(0.0, std::memory_order_relaxed);
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            continue;
        }

        const auto deadline = now + std::chrono::milliseconds(kWorkCapMs);
        double target;
        if (engine_.stepping()) {
            target = engine_.step_target();   // as fast as the cap allows
        } else {
            target = anchor_sim + speed * std::chrono::duration<double>(now - anchor_wall).count();
        }
        const double reached = engine_.advance_to(target, deadline);
        sink_.publish();   // the whole slice at once
        sim_time_.store(reached, std::memory_order_relaxed);

        const auto after = Clock::now();
        if (!engine_.stepping() && !engine_.paused()) {
            // More than 100 ms of wall time behind: give the debt up and report the lag.
            const double behind_s = (target - reached) / speed;
            const bool lag = behind_s > 0.1;
            lagging_.store(lag, std::memory_order_relaxed);
            if (lag) {
                anchor_wall = after;
                anchor_sim = reached;
            }
        }
        const double window = std::chrono::duration<double>(after - meter_wall).count();
        if (window >= 0.5) {
            achieved_.store((reached - meter_sim) / window, std::memory_order_relaxed);
            meter_wall = after;
            meter_sim = reached;
        }
        // Caught up: sleep a little (the UI drains at its frame rate; 1 ms keeps the latency low).
        if (reached >= target) std::this_thread::sleep_for(std::chrono::microseconds(1000));
    }
}

}  // namespace impactlab::gui
