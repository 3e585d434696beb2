#include "sim_engine.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numbers>

#include "sim/param_edit.hpp"

namespace impactlab::gui {

// Turns the core's pieces and events into published records, in time order. Lives on the engine's stack
// for one advance_to() call.
class SimEngine::Tap final : public Observer {
public:
    Tap(SimEngine& e, std::chrono::steady_clock::time_point deadline) : e_(e), deadline_(deadline) {}

    void on_piece(const Piece& piece) override {
        SimEngine& e = e_;
        e.ledger_.on_piece(piece);
        e.grazing_.on_piece(piece, e.p_.xI, e.p_.has_bumper() && !e.p_.rigid());
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
        if (GrazingMonitor::Period g; e_.grazing_.on_section(sp.t, e_.p_.xI, g)) {
            SimMsg m = e_.record(MsgKind::Grazing, sp.t);
            m.x = g.x_max;
            m.v = g.v_impact;
            m.force = g.penetration;
            m.energy = g.impacts;
            m.regime = sp.regime;
            e_.put(m);
        }
    }
    void on_impact(const ImpactEvent& ev) override {
        SimMsg m = e_.record(MsgKind::Impact, ev.t);
        m.x = e_.p_.xI;
        m.v = ev.v_plus;
        m.force = ev.v_minus;
        m.energy = ev.duration;
        m.regime = Regime::Sticking;
        e_.grazing_.on_impact(ev);
        e_.put(m);
    }
    bool stop() const override {
        if (e_.sink_ && !e_.sink_->has_room()) return true;   // the reader is behind: defer, never drop
        // Reading the clock costs ~20 ns; a piece costs a few microseconds: check every 8th.
        if ((++calls_ & 7u) != 0) return false;
        return std::chrono::steady_clock::now() >= deadline_;
    }

private:
    void publish(MsgKind kind, double t, double x, double v, Regime regime) {
        SimEngine& e = e_;
        SimMsg m = e.record(kind, t);
        m.x = x;
        m.v = v;
        State at = e.s_;   // the impact in progress (regime II) sets the bumper force
        at.t = t;
        at.x = x;
        at.v = v;
        at.regime = regime;
        m.force = bumper_force(e.p_, e.d_, at);
        m.energy = mechanical_energy(e.p_, x, v);
        m.regime = regime;
        ++e.published_;
        e.put(m);
    }

    SimEngine& e_;
    std::chrono::steady_clock::time_point deadline_;
    mutable unsigned calls_ = 0;
};

SimEngine::SimEngine(const EngineConfig& cfg, MsgSink* sink)
    : p_(make_version(cfg.model)), d_(std::clamp(cfg.omega, 0.0, kMaxOmega)), sink_(sink) {
    p_.xI = std::clamp(cfg.xI, -kMaxAbsXI, kMaxAbsXI);
    xI_target_ = p_.xI;
    paused_ = cfg.paused;
    speed_ = std::clamp(cfg.speed, kMinSpeed, kMaxSpeed);
    dt_ = sample_dt_for(speed_);
    s_.x = cfg.x0;
    s_.v = cfg.v0;
    sim_.set_section_phase(std::isfinite(cfg.phi0) ? std::clamp(cfg.phi0, 0.0, kTwoPi) : 0.0);
    Simulator::make_consistent(p_, d_, s_);
    ledger_.reset(s_);
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
    SimMsg m = record(MsgKind::Sample, s_.t);
    m.x = s_.x;
    m.v = s_.v;
    m.force = bumper_force(p_, d_, s_);
    m.energy = mechanical_energy(p_, s_.x, s_.v);
    m.regime = s_.regime;
    ++published_;
    put(m);
    grid_t0_ = s_.t;
    grid_k_ = 1;
}

SimMsg SimEngine::record(MsgKind kind, double t) const {
    SimMsg m;
    m.kind = kind;
    m.t = t;
    m.phi = d_.phi(t);
    m.omega = d_.omega(t);
    m.epoch = epoch_;
    return m;
}

void SimEngine::put(SimMsg& m) {
    m.source = source_;
    if (sink_) sink_->put(m);
}

double SimEngine::next_section_time() const {
    const double t_sec = sim_.next_section_time(d_, s_);
    return std::isfinite(t_sec) ? t_sec : s_.t + 1.0;   // a stopped drive: a second, not forever
}

void SimEngine::change_drive(const Drive& d) {
    d_ = d;
    Simulator::sync_sections(d_, s_);
    if (stepping_) step_target_ = next_section_time();   // the stepped period ends at the new drive's section
    ++epoch_;   // not bump(): the energy balance goes on through a change of omega (the new rate's work counts)
    emit_now();
}

// Ramp: omega from now to c.a at the rate |c.b| [rad/s per s].
bool SimEngine::apply_ramp(const SimCommand& c) {
    const double w0 = d_.omega(s_.t);
    const double w1 = std::clamp(std::isfinite(c.a) ? c.a : w0, 0.0, kMaxOmega);
    const double rate = std::clamp(std::isfinite(c.b) ? std::abs(c.b) : kMaxRampRate, kMinRampRate, kMaxRampRate);
    if (std::abs(w1 - w0) < 1e-9) return true;   // nothing to ramp (and the knots must differ in t)
    // Knots at now and at the end of the ramp: constant after it, phi continuous through both.
    change_drive(Drive::piecewise_linear({s_.t, s_.t + std::abs(w1 - w0) / rate}, {w0, w1}, d_.phi(s_.t)));
    return true;
}

// SetModel: another version by name (c.model); the state carries over.
bool SimEngine::apply_model(const SimCommand& c) {
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

// SetParam (c.model names the key, c.a the value) and ResetParams (the version's own values).
bool SimEngine::apply_params(const SimCommand& c) {
    Params np = p_;
    if (c.kind == CmdKind::ResetParams) {
        try {
            np = make_version(p_.name);
        } catch (const ParamError&) {
            return false;
        }
        np.xI = p_.xI;
    } else if (std::string error; !set_param(np, std::string(c.model, std::find(c.model, c.model + sizeof(c.model), '\0')), c.a, error)) {
        return false;
    }
    p_ = std::move(np);
    Simulator::make_consistent(p_, d_, s_);
    bump();
    emit_now();
    return true;
}

// SetSectionPhase: the Poincare section at phi = c.a + 2 pi k.
bool SimEngine::apply_section_phase(const SimCommand& c) {
    // The trajectory goes on; only the instants that are sections change. A new epoch: the map
    // and the clicker's orbit of the old phase are another section's points, and the grazing
    // monitor's periods end at the sections.
    if (!std::isfinite(c.a) || c.a < 0.0 || c.a > kTwoPi) return false;
    if (c.a == sim_.section_phase()) return true;
    sim_.set_section_phase(c.a);
    // The revolution running now may still have its section at the new phase ahead.
    Simulator::sync_sections(d_, s_);
    if (stepping_) step_target_ = next_section_time();
    ++epoch_;
    grazing_.reset();
    emit_now();
    return true;
}

// Reset: from (c.a, c.b) at rest at t = 0, phi = 0, the omega running now.
bool SimEngine::apply_reset(const SimCommand& c) {
    const double w = d_.omega(s_.t);
    held_ = false;
    if (p_.xI != xI_target_) Simulator::move_bumper(p_, d_, s_, xI_target_);   // no push from a ramp
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

// Restart: from (c.a, c.b) at t = c.t0, phi = c.phi0, the omega running now.
bool SimEngine::apply_restart(const SimCommand& c) {
    // A replayed instant or a saved session: the clock and the phase go back (or forward) to it, the
    // rate stays. A sticking impact in progress there restarts as contact or free flight.
    if (!std::isfinite(c.t0) || !std::isfinite(c.phi0) || c.t0 < 0) return false;
    const double w = d_.omega(s_.t);
    held_ = false;
    if (p_.xI != xI_target_) Simulator::move_bumper(p_, d_, s_, xI_target_);
    s_ = State{};
    s_.t = c.t0;
    s_.x = std::isfinite(c.a) ? std::clamp(c.a, -kMaxAbsStateX, kMaxAbsStateX) : 0.0;
    s_.v = std::isfinite(c.b) ? std::clamp(c.b, -kMaxAbsStateV, kMaxAbsStateV) : 0.0;
    d_ = Drive(w, c.t0, c.phi0);
    Simulator::sync_sections(d_, s_);
    Simulator::make_consistent(p_, d_, s_);
    stepping_ = false;
    bump();
    emit_now();
    return true;
}

bool SimEngine::apply(const SimCommand& c) {
    switch (c.kind) {
        case CmdKind::SetOmega: {
            const double w = std::clamp(std::isfinite(c.a) ? c.a : 0.0, 0.0, kMaxOmega);
            // Same phase, new rate from now on: phi stays continuous.
            change_drive(Drive(w, s_.t, d_.phi(s_.t)));
            return true;
        }
        case CmdKind::Ramp: return apply_ramp(c);
        case CmdKind::SetXI: {
            xI_target_ = std::clamp(std::isfinite(c.a) ? c.a : 0.0, -kMaxAbsXI, kMaxAbsXI);
            // Running, the bumper travels there over the next steps (advance_to); paused, at once.
            if (paused_ && !stepping_) Simulator::move_bumper(p_, d_, s_, xI_target_);
            bump();
            emit_now();
            return true;
        }
        case CmdKind::SetModel: return apply_model(c);
        case CmdKind::SetParam:
        case CmdKind::ResetParams: return apply_params(c);
        case CmdKind::SetPaused:
            paused_ = c.a != 0.0;
            if (!paused_) stepping_ = false;
            return true;
        case CmdKind::SetSectionPhase: return apply_section_phase(c);
        case CmdKind::StepPeriod: {
            // Run to the next section phi = phi0 + 2 pi k (one forcing period away at most), then pause.
            step_target_ = next_section_time();
            stepping_ = true;
            paused_ = true;
            return true;
        }
        case CmdKind::Reset: return apply_reset(c);
        case CmdKind::Restart: return apply_restart(c);
        case CmdKind::SetState:
            held_ = false;
            set_state(c.a, std::isfinite(c.b) ? c.b : 0.0);
            bump();
            emit_now();
            return true;
        case CmdKind::Hold:
            set_state(c.a, 0.0);
            held_ = true;
            bump();
            emit_now();
            return true;
        case CmdKind::SetCompanion:   // the sim thread's business (SimThread::apply): not the engine's
            return false;
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

void SimEngine::set_state(double x, double v) {
    // The bumper's ramp ends where it was going: the state is set against the bumper the user sees.
    if (p_.xI != xI_target_) Simulator::move_bumper(p_, d_, s_, xI_target_);
    s_.x = std::isfinite(x) ? std::clamp(x, -kMaxAbsStateX, kMaxAbsStateX) : s_.x;
    s_.v = std::clamp(v, -kMaxAbsStateV, kMaxAbsStateV);
    if (p_.has_bumper() && s_.x > p_.xI) s_.x = p_.xI;   // never inside the bumper (the UI says so)
    s_.regime = Regime::Free;   // a sticking in progress belonged to the old state
    Simulator::make_consistent(p_, d_, s_);
}

bool SimEngine::restart_from(const SimEngine& src, const std::string& model, double dx) {
    Params np;
    try {
        np = make_version(model);
    } catch (const ParamError&) {
        return false;
    }
    np.xI = src.p_.xI;
    p_ = std::move(np);
    sim_.set_section_phase(src.sim_.section_phase());   // the companion's sections are the cart's
    xI_target_ = src.xI_target_;
    d_ = src.d_;
    s_ = State{};
    s_.t = src.s_.t;
    s_.x = src.s_.x;
    s_.v = src.s_.v;
    // The same impact law carries a regime II or III over; another law starts free (make_consistent puts
    // a cart resting on a rigid bumper back on it).
    if (p_.impact == src.p_.impact) {
        s_.regime = src.s_.regime;
        s_.t_release = src.s_.t_release;
        s_.v_release = src.s_.v_release;
        s_.v_impact = src.s_.v_impact;
    }
    if (dx != 0.0) {
        s_.regime = Regime::Free;
        s_.x = std::min(s_.x + dx, p_.has_bumper() ? p_.xI : s_.x + dx);
    }
    Simulator::make_consistent(p_, d_, s_);
    held_ = src.held_;
    paused_ = src.paused_;
    stepping_ = src.stepping_;
    step_target_ = src.step_target_;
    speed_ = src.speed_;
    dt_ = src.dt_;
    // A restart opens a new run: the epoch's high 16 bits count runs (CompanionTrack clears on a new one),
    // the low bits the changes within a run, as for the cart.
    epoch_ |= 0xFFFFu;   // bump() below carries into the high bits
    bump();
    emit_now();
    grid_t0_ = src.grid_t0_;   // the same sample instants as src from here: the UI compares them one to one
    grid_k_ = src.grid_k_;
    return true;
}

double SimEngine::move_bumper_toward_target(double t_end) {
    // One push of at most kBumperPush, then the time the bumper takes for it at its speed.
    const double rate = kBumperWallSpeed / speed_;   // [m per sim second]
    const double dx = std::clamp(xI_target_ - p_.xI, -kBumperPush, kBumperPush);
    const double x_before = s_.x;
    Simulator::move_bumper(p_, d_, s_, std::abs(xI_target_ - p_.xI) <= kBumperPush ? xI_target_ : p_.xI + dx);
    if (s_.x != x_before) ledger_.reset(s_);   // the push is work the balance does not book
    if (p_.xI == xI_target_) bump();             // there: the map settles afresh on the new bumper
    return std::min(t_end, s_.t + std::abs(dx) / rate);
}

void SimEngine::advance_held(double t_end) {
    // Nothing moves but the unbalance: samples on the grid at the held x, v = 0; no sections (the map
    // starts afresh when the cart is let go).
    for (;;) {
        const double t = grid_t0_ + dt_ * static_cast<double>(grid_k_);
        if (t > t_end) break;
        ++grid_k_;
        if (t < s_.t) continue;
        SimMsg m = record(MsgKind::Sample, t);
        m.x = s_.x;
        m.energy = mechanical_energy(p_, s_.x, 0.0);
        ++published_;
        put(m);
    }
    s_.t = t_end;
    s_.v = 0;
    Simulator::sync_sections(d_, s_);
}

double SimEngine::advance_to(double t_end, std::chrono::steady_clock::time_point deadline) {
    if (stepping_) t_end = std::min(t_end, step_target_);
    if (held_ && t_end > s_.t) advance_held(t_end);
    Tap tap(*this, deadline);
    while (t_end > s_.t) {
        const double t_stop = p_.xI != xI_target_ ? move_bumper_toward_target(t_end) : t_end;
        try {
            sim_.advance(p_, d_, s_, t_stop, &tap);
        } catch (const SimulationStalled& e) {
            // Never with the built-in versions; a stall pauses the run (the state stays inspectable).
            std::fprintf(stderr, "impactlab-gui: %s; paused\n", e.what());
            paused_ = true;
            stepping_ = false;
            break;
        }
        if (s_.t < t_stop) break;   // the deadline: the sim thread comes back for the rest
    }
    if (stepping_ && s_.t >= step_target_) stepping_ = false;   // stays paused
    return s_.t;
}

}  // namespace impactlab::gui
