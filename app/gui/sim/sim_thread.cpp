#include "sim_thread.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace impactlab::gui {

using Clock = std::chrono::steady_clock;

SimThread::SimThread(const EngineConfig& cfg) : engine_(cfg, &sink_) {
    paused_.store(engine_.paused(), std::memory_order_relaxed);
    bumper_.store(engine_.params().xI, std::memory_order_relaxed);
    energy_ = engine_.energy();
}

SimThread::~SimThread() { stop(); }

void SimThread::start() {
#ifdef __EMSCRIPTEN__
    begin_pacing();   // no threads in a file:// page: the UI runs a slice per frame (pump)
#else
    if (thread_.joinable()) return;
    quit_.store(false, std::memory_order_relaxed);
    thread_ = std::thread([this] { run(); });
#endif
}

void SimThread::stop() {
    quit_.store(true, std::memory_order_relaxed);
    if (thread_.joinable()) thread_.join();
}

bool SimThread::send(const SimCommand& c) { return commands_.try_push(c); }

void SimThread::apply(const SimCommand& c) {
    if (c.kind == CmdKind::SetCompanion) {
        const auto mode = static_cast<CompanionMode>(std::clamp(static_cast<int>(c.a), 0, 2));
        if (mode == CompanionMode::Ghost) {
            const std::string name(c.model, std::find(c.model, c.model + sizeof(c.model), '\0'));
            try {
                ghost_impact_ = make_version(name).impact->id;
            } catch (const ParamError&) {
                return;   // the UI validated the name: nothing changes
            }
        }
        companion_mode_ = mode;
        twin_offset_ = std::isfinite(c.b) ? std::clamp(c.b, -1e-3, 1e-3) : kTwinOffset;
        if (mode == CompanionMode::Off) companion_.reset();
        else restart_companion();
        return;
    }
    const bool ok = engine_.apply(c);
    if (!companion_ || !ok) return;
    switch (c.kind) {
        case CmdKind::SetModel:
        case CmdKind::Reset:
        case CmdKind::Restart:
        case CmdKind::SetState:
        case CmdKind::Hold:
            restart_companion();   // from the cart's new state: where the two part is what is shown
            break;
        default:
            companion_->apply(c);   // omega, xI, pause, step, speed: the same for both
            break;
    }
}

void SimThread::restart_companion() {
    const bool twin = companion_mode_ == CompanionMode::Twin;
    const std::string model = twin ? engine_.params().name : engine_.params().stiffness_id + ghost_impact_;
    if (!companion_) {
        EngineConfig cfg;
        cfg.model = model;
        companion_ = std::make_unique<SimEngine>(cfg, &sink_);
        companion_->set_source(1);
    }
    if (!companion_->restart_from(engine_, model, twin ? twin_offset_ : 0.0)) companion_.reset();
}

SimStatus SimThread::status() const {
    SimStatus s;
    s.sim_time = sim_time_.load(std::memory_order_relaxed);
    s.achieved_speed = achieved_.load(std::memory_order_relaxed);
    s.paused = paused_.load(std::memory_order_relaxed);
    s.lagging = lagging_.load(std::memory_order_relaxed);
    s.xI = bumper_.load(std::memory_order_relaxed);
    s.dropped = samples_.dropped();
    s.commands_dropped = commands_.dropped();
    const std::lock_guard<std::mutex> lock(energy_mutex_);
    s.energy = energy_;
    return s;
}

void SimThread::run() {
    begin_pacing();
    while (!quit_.load(std::memory_order_relaxed)) {
        const int nap_us = slice();
        if (nap_us > 0) std::this_thread::sleep_for(std::chrono::microseconds(nap_us));
    }
}

void SimThread::begin_pacing() {
    // Pacing: sim time follows anchor_sim + speed * (wall - anchor_wall). Any command, a pause or a lag
    // re-anchors, so the simulation never tries to catch up on time it could not spend.
    pace_.anchor_wall = Clock::now();
    pace_.anchor_sim = engine_.state().t;
    pace_.speed = engine_.speed();
    // Achieved speed: sim time per wall time over windows of ~0.5 s.
    pace_.meter_wall = pace_.anchor_wall;
    pace_.meter_sim = pace_.anchor_sim;
    engine_.publish_state();   // the UI sees the initial state even when started paused
    sink_.publish();
}

int SimThread::slice() {
    Pacing& p = pace_;
    bool changed = false;
    commands_.drain([&](const SimCommand& c) {
        apply(c);
        changed = true;
    });
    if (changed) sink_.publish();   // a command may publish the new state (reset, model switch)
    bumper_.store(engine_.params().xI, std::memory_order_relaxed);
    const auto now = Clock::now();
    if (changed || engine_.speed() != p.speed) {
        p.speed = engine_.speed();
        p.anchor_wall = now;
        p.anchor_sim = engine_.state().t;
    }
    paused_.store(engine_.paused() && !engine_.stepping(), std::memory_order_relaxed);

    if (engine_.paused() && !engine_.stepping()) {
        p.anchor_wall = now;
        p.anchor_sim = engine_.state().t;
        p.meter_wall = now;
        p.meter_sim = p.anchor_sim;
        achieved_.store(0.0, std::memory_order_relaxed);
        return 2000;
    }

    const auto deadline = now + std::chrono::milliseconds(kWorkCapMs);
    double target;
    if (engine_.stepping()) {
        target = engine_.step_target();   // as fast as the cap allows
    } else {
        target = p.anchor_sim + p.speed * std::chrono::duration<double>(now - p.anchor_wall).count();
    }
    const double reached = engine_.advance_to(target, deadline);
    // Lockstep: the companion covers the same span (no deadline: it costs about what the cart did).
    if (companion_) companion_->advance_to(reached);
    sink_.publish();   // the whole slice at once
    sim_time_.store(reached, std::memory_order_relaxed);
    bumper_.store(engine_.params().xI, std::memory_order_relaxed);
    if (std::unique_lock<std::mutex> lock(energy_mutex_, std::try_to_lock); lock.owns_lock())
        energy_ = engine_.energy();   // a busy UI skips one update, never stalls the simulation

    const auto after = Clock::now();
    if (!engine_.stepping() && !engine_.paused()) {
        // More than 100 ms of wall time behind: give the debt up and report the lag.
        const double behind_s = (target - reached) / p.speed;
        const bool lag = behind_s > 0.1;
        lagging_.store(lag, std::memory_order_relaxed);
        if (lag) {
            p.anchor_wall = after;
            p.anchor_sim = reached;
        }
    }
    const double window = std::chrono::duration<double>(after - p.meter_wall).count();
    if (window >= 0.5) {
        achieved_.store((reached - p.meter_sim) / window, std::memory_order_relaxed);
        p.meter_wall = after;
        p.meter_sim = reached;
    }
    // Caught up: sleep a little (the UI drains at its frame rate; 1 ms keeps the latency low).
    return reached >= target ? 1000 : 0;
}

}  // namespace impactlab::gui
