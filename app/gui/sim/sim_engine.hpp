// The simulation side of the GUI without the thread: owns Params, Drive, State and the core Simulator,
// applies UI commands between steps and publishes samples, section points and impacts to a sink.
// SimThread runs one of these on its own thread; the headless tests drive one directly. GL-free.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "impactlab/analysis.hpp"
#include "impactlab/drive.hpp"
#include "impactlab/energy.hpp"
#include "impactlab/params.hpp"
#include "sim/grazing_monitor.hpp"
#include "impactlab/simulator.hpp"
#include "sim/sim_messages.hpp"

namespace impactlab::gui {

// Where published records go (the sample ring in the app, a vector in tests). Called on the engine's thread.
class MsgSink {
public:
    virtual ~MsgSink() = default;
    virtual void put(const SimMsg& m) = 0;
    // False while the reader is behind: the engine ends its slice after the current piece instead of
    // having records dropped (a lost Poincare section would break the map's sequence of periods).
    virtual bool has_room() { return true; }
};

struct EngineConfig {
    std::string model = "A1H";
    double omega = 9.0;       // [rad/s]
    double xI = 0.0;          // [m]
    double x0 = -0.011;       // initial state [m], [m/s]
    double v0 = 0.0;
    double speed = 1.0;       // real-time factor
    bool paused = false;
    double phi0 = 0.0;        // the Poincare section phase [rad], 0 .. 2 pi
};

inline constexpr double kMinSpeed = 0.01, kMaxSpeed = 100.0;
inline constexpr double kMaxOmega = 30.0;      // [rad/s], the slider's range
inline constexpr double kMaxAbsXI = 0.020;     // [m]
inline constexpr double kMinRampRate = 1e-3, kMaxRampRate = 2.0;   // [rad/s per s] of the live omega ramp
// The bumper moves to a new xI at this speed in wall-clock time (sim time: divided by the real-time factor),
// pushing the cart ahead of it in steps of at most kBumperPush: x(t) stays continuous instead of stepping
// by the slider's jump each frame (a cart seen to teleport). Paused, it moves at once.
inline constexpr double kBumperWallSpeed = 0.1;   // [m/s]
inline constexpr double kBumperPush = 1e-4;       // [m]
// How far the mouse may put the cart: the rail's travel, as a reset allows [m].
inline constexpr double kMaxAbsStateX = 0.05;
inline constexpr double kMaxAbsStateV = 2.0;     // [m/s]

class SimEngine {
public:
    // Throws ParamError for an unknown model name.
    explicit SimEngine(const EngineConfig& cfg, MsgSink* sink = nullptr);

    void set_sink(MsgSink* sink) { sink_ = sink; }

    // Applies one command. Commands that change the dynamics (omega, xI, model, reset) bump the epoch.
    // Returns false for a command it had to refuse (unknown model name); nothing changes then.
    bool apply(const SimCommand& c);

    // Advances to sim time t_end (clamped to the step-period target while stepping), publishing every
    // sample on the way; returns early once the wall clock passes `deadline`. Returns the sim time reached.
    double advance_to(double t_end, std::chrono::steady_clock::time_point deadline =
                                        std::chrono::steady_clock::time_point::max());

    // Publishes the current state as a sample now (the sample grid restarts after it).
    void publish_state() { emit_now(); }

    // The companion: this engine restarts from `src`'s state now (its t, phi, omega, xI and
    // pace), x moved by dx, under its own model `model` (the twin: src's; the ghost: another). Bumps the
    // epoch and publishes. False for an unknown model (nothing changes then).
    bool restart_from(const SimEngine& src, const std::string& model, double dx);
    // Records this engine publishes carry this source tag (SimMsg::source).
    void set_source(std::uint8_t tag) { source_ = tag; }

    const Params& params() const { return p_; }
    const Drive& drive() const { return d_; }
    const State& state() const { return s_; }
    double bumper_target() const { return xI_target_; }   // where the bumper is moving to (params().xI: now)
    bool held() const { return held_; }                    // the mouse holds the cart
    double phi() const { return d_.phi(s_.t); }
    double section_phase() const { return sim_.section_phase(); }   // phi0 [rad]
    std::uint32_t epoch() const { return epoch_; }
    bool paused() const { return paused_; }
    bool stepping() const { return stepping_; }
    double step_target() const { return step_target_; }   // valid while stepping()
    double speed() const { return speed_; }
    double sample_dt() const { return dt_; }
    // The sample step for a given real-time factor: about four samples per 60 Hz frame, 20 us .. 1 ms.
    static double sample_dt_for(double speed);
    std::uint64_t samples_published() const { return published_; }
    // The energy balance since the last change of model, xI or state (an omega change keeps it: the
    // unbalance's work is integrated at the new rate).
    const EnergyBalance& energy() const { return ledger_.balance(); }

private:
    class Tap;   // the Observer that turns the simulator's pieces and events into records
    // apply()'s longer commands, one each (true: applied).
    bool apply_ramp(const SimCommand& c);
    bool apply_model(const SimCommand& c);
    bool apply_params(const SimCommand& c);   // SetParam and ResetParams
    bool apply_section_phase(const SimCommand& c);
    bool apply_reset(const SimCommand& c);
    bool apply_restart(const SimCommand& c);
    void emit_now();
    void restart_grid();
    double next_section_time() const;   // when phi reaches the next section phi0 + 2 pi k under the current drive
    // A new drive from now (SetOmega, Ramp): phi continuous, the sections and a stepped period follow it.
    void change_drive(const Drive& d);
    void put(SimMsg& m);   // tags and hands a record to the sink
    SimMsg record(MsgKind kind, double t) const;   // a record at t: the drive's phi and omega, the epoch
    double move_bumper_toward_target(double t_end);   // one push; returns the sim time it lasts to
    void advance_held(double t_end);                   // time passes with the cart in the hand
    // Sets x, v from now with t and phi going on (clamped to the rail and to the bumper's near side).
    void set_state(double x, double v);
    void bump() {
        ++epoch_;
        ledger_.reset(s_);
        grazing_.reset();
    }

    Params p_;
    Drive d_;
    State s_;
    // Tighter than a sweep's rtol 1e-8: a label must agree with the core's orbits, and at 1e-8 the section
    // points of a weakly stable orbit (A3C's period 24 at 18.1608 rad/s) recur within 1.6 map tolerances, at
    // 1e-9 within 0.45 (the hold is 2). The analysis' 1e-10 (0.05) would cost the page its 1000x real time.
    Simulator sim_{analysis::analysis_tolerances(1e-9)};
    EnergyLedger ledger_{p_, d_};   // holds p_ and d_ by reference: declared after them
    MsgSink* sink_;
    std::uint32_t epoch_ = 0;
    bool paused_ = false;
    bool stepping_ = false;
    double step_target_ = 0;
    double speed_ = 1.0;
    double dt_ = 1e-3;
    double grid_t0_ = 0;       // samples at grid_t0_ + k dt_
    std::int64_t grid_k_ = 0;
    std::uint64_t published_ = 0;
    double xI_target_ = 0;     // [m]
    bool held_ = false;        // Hold: the cart sits at s_.x, v = 0, nothing is integrated
    std::uint8_t source_ = 0;
    GrazingMonitor grazing_;
};

}  // namespace impactlab::gui
