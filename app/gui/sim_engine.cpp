#include "sim_engine.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numbers>

namespace impactlab::gui {

// Turns the core's pieces and events into published records, in time order. Lives on the engine's stack
// for one advance_to() call.
class SimEngine::Tap final : public Observer {
public:
    Tap(SimEngine& e, std::chrono::steady_clock::time_point deadline) : e_(e), deadline_(deadline) {}

    void on_piece(const Piece& piece) override {
        SimEngine& e = e_;
        for (;;) {
            const double t = e.grid_t0_ + e.dt_ * static_cast<double>(e.grid_k_);
            if (t > piece.t1) break;
            ++e.grid_k_;
            if (t < piece.t0) continue;   // a grid point before this piece (only right after a restart)
            const Vec2 y = piece.at(t);
            publish(MsgKind::Sample, t, y[0], y[1], piece.regime);
        }
    }
    void on_section(const SectionPoint& sp) override {
        publish(MsgKind::Section, sp.t, sp.x, sp.v, sp.regime);
    }
    void on_impact(const ImpactEvent& ev) override {
        SimMsg m;
        m.kind = MsgKind::Impact;
        m.t = ev.t;
        m.x = e_.p_.xI;
        m.v = ev.v_plus;
        m.phi = e_.d_.phi(ev.t);
        m.omega = e_.d_.omega(ev.t);
        m.force = ev.v_minus;
        m.energy = ev.duration;
        m.epoch = e_.epoch_;
        m.regime = Regime::Sticking;
        if (e_.sink_) e_.sink_->put(m);
    }
    bool stop() const override {
        // Reading the clock costs ~20 ns; a piece costs a few microseconds: check every 8th.
        if ((++calls_ & 7u) != 0) return false;
        return std::chrono::steady_clock::now() >= deadline_;
    }

private:
    void publish(MsgKind kind, double t, double x, double v, Regime regime) {
        SimEngine& e = e_;
        SimMsg m;
        m.kind = kind;
        m.t = t;
        m.x = x;
        m.v = v;
        m.phi = e.d_.phi(t);
        m.omega = e.d_.omega(t);
        State at = e.s_;   // the impact in progress (regime II) sets the bumper force
        at.t = t;
        at.x = x;
        at.v = v;
        at.regime = regime;
        m.force = bumper_force(e.p_, e.d_, at);
        m.energy = mechanical_energy(e.p_, x, v);
        m.epoch = e.epoch_;
        m.regime = regime;
        ++e.published_;
        if (e.sink_) e.sink_->put(m);
    }

    SimEngine& e_;
    std::chrono::steady_clock::time_point deadline_;
    mutable unsigned calls_ = 0;
};

SimEngine::SimEngine(const EngineConfig& cfg, MsgSink* sink)
    : p_(make_version(cfg.model)), d_(std::clamp(cfg.omega, 0.0, kMaxOmega)), sink_(sink) {
    p_.xI = std::clamp(cfg.xI, -kMaxAbsXI, kMaxAbsXI);
    paused_ = cfg.paused;
    speed_ = std::clamp(cfg.speed, kMinSpeed, kMaxSpeed);
    dt_ = sample_dt_for(speed_);
    s_.x = cfg.x0;
    s_.v = cfg.v0;
    Simulator::make_consistent(p_, d_, s_);
    restart_grid();
}

double SimEngine::sample_dt_for(double speed) {
    return std::clamp(speed / 240.0, 2e-5, 1e-3);
}

void SimEngine::restart_grid() {
    grid_t0_ = s_.t;   // the next sample is at the current time
    grid_k_ = 0;
}

void SimEngine::emit_now() {
    // The state as it is now, so a change shows at once; the sample grid restarts after it.
    SimMsg m;
    m.kind = MsgKind::Sample;
    m.t = s_.t;
    m.x = s_.x;
    m.v = s_.v;
    m.phi = d_.phi(s_.t);
    m.omega = d_.omega(s_.t);
    m.force = bumper_force(p_, d_, s_);
    m.energy = mechanical_energy(p_, s_.x, s_.v);
    m.epoch = epoch_;
    m.regime = s_.regime;
    ++published_;
    if (sink_) sink_->put(m);
    grid_t0_ = s_.t;
    grid_k_ = 1;
}

bool SimEngine::apply(const SimCommand& c) {
    switch (c.kind) {
        case CmdKind::SetOmega: {
            const double w = std::clamp(std::isfinite(c.a) ? c.a : 0.0, 0.0, kMaxOmega);
            // Same phase, new rate from now on: phi stays continuous.
            d_ = Drive(w, s_.t, d_.phi(s_.t));
            Simulator::sync_sections(d_, s_);
            if (stepping_) {   // the period being stepped ends at the next section of the new drive
                const double t_sec = d_.time_of_phase(kTwoPi * static_cast<double>(s_.next_section));
                step_target_ = std::isfinite(t_sec) ? t_sec : s_.t + 1.0;
            }
            bump();
            emit_now();
            return true;
        }
        case CmdKind::SetXI: {
            const double xI = std::clamp(std::isfinite(c.a) ? c.a : 0.0, -kMaxAbsXI, kMaxAbsXI);
            Simulator::move_bumper(p_, d_, s_, xI);
            bump();
            emit_now();
            return true;
        }
        case CmdKind::SetModel: {
            Params np;
            try {
                np = make_version(std::string(c.model, std::find(c.model, c.model + sizeof(c.model), '\0')));
            } catch (const ParamError&) {
                return false;
            }
            if (np.name == p_.name) return true;   // the same version: nothing changes, no new epoch
            np.xI = p_.xI;
            p_ = std::move(np);
            // x, v and phi carry over; only the hybrid bookkeeping is made consistent with the new law.
            Simulator::make_consistent(p_, d_, s_);
            bump();
            emit_now();
            return true;
        }
        case CmdKind::SetPaused:
            paused_ = c.a != 0.0;
            if (!paused_) stepping_ = false;
            return true;
        case CmdKind::StepPeriod: {
            // Run to the next section phi = 2 pi n (one forcing period away at most), then pause.
            const double t_sec = d_.time_of_phase(kTwoPi * static_cast<double>(s_.next_section));
            step_target_ = std::isfinite(t_sec) ? t_sec : s_.t + 1.0;
            stepping_ = true;
            paused_ = true;
            return true;
        }
        case CmdKind::Reset: {
            const double w = d_.omega(s_.t);
            s_ = State{};
            s_.x = std::isfinite(c.a) ? std::clamp(c.a, -0.05, 0.05) : 0.0;
            s_.v = std::isfinite(c.b) ? std::clamp(c.b, -2.0, 2.0) : 0.0;
            d_ = Drive(w, 0.0, 0.0);
            Simulator::make_consistent(p_, d_, s_);
            stepping_ = false;
            bump();
            emit_now();
            return true;
        }
        case CmdKind::SetSpeed:
            speed_ = std::clamp(std::isfinite(c.a) ? c.a : 1.0, kMinSpeed, kMaxSpeed);
            if (const double dt = sample_dt_for(speed_); dt != dt_) {
                dt_ = dt;
                grid_t0_ = s_.t;
                grid_k_ = 1;
            }
            return true;
    }
    return false;
}

double SimEngine::advance_to(double t_end, std::chrono::steady_clock::time_point deadline) {
    if (stepping_) t_end = std::min(t_end, step_target_);
    if (t_end > s_.t) {
        Tap tap(*this, deadline);
        try {
            sim_.advance(p_, d_, s_, t_end, &tap);
        } catch (const SimulationStalled& e) {
            // Never with the built-in versions; a stall pauses the run (the state stays inspectable).
            std::fprintf(stderr, "impactlab-gui: %s; paused\n", e.what());
            paused_ = true;
            stepping_ = false;
        }
    }
    if (stepping_ && s_.t >= step_target_) stepping_ = false;   // stays paused
    return s_.t;
}

}  // namespace impactlab::gui
