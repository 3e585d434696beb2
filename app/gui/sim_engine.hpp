// The simulation side of the GUI without the thread: owns Params, Drive, State and the core Simulator,
// applies UI commands between steps and publishes samples, section points and impacts to a sink.
// SimThread runs one of these on its own thread; the headless tests drive one directly. GL-free.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "sim_messages.hpp"

namespace impactlab::gui {

// Where published records go (the sample ring in the app, a vector in tests). Called on the engine's thread.
class MsgSink {
public:
    virtual ~MsgSink() = default;
    virtual void put(const SimMsg& m) = 0;
};

struct EngineConfig {
    std::string model = "A1H";
    double omega = 9.0;       // [rad/s]
    double xI = 0.0;          // [m]
    double x0 = -0.011;       // initial state [m], [m/s]
    double v0 = 0.0;
    double speed = 1.0;       // real-time factor
    bool paused = false;
};

inline constexpr double kMinSpeed = 0.01, kMaxSpeed = 100.0;
inline constexpr double kMaxOmega = 30.0;      // [rad/s], the slider's range
inline constexpr double kMaxAbsXI = 0.020;     // [m]

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

    const Params& params() const { return p_; }
    const Drive& drive() const { return d_; }
    const State& state() const { return s_; }
    double phi() const { return d_.phi(s_.t); }
    std::uint32_t epoch() const { return epoch_; }
    bool paused() const { return paused_; }
    bool stepping() const { return stepping_; }
    double step_target() const { return step_target_; }   // valid while stepping()
    double speed() const { return speed_; }
    double sample_dt() const { return dt_; }
    // The sample step for a given real-time factor: about four samples per 60 Hz frame, 20 us .. 1 ms.
    static double sample_dt_for(double speed);
    std::uint64_t samples_published() const { return published_; }

private:
    class Tap;   // the Observer that turns the simulator's pieces and events into records
    void emit_now();
    void restart_grid();
    void bump() { ++epoch_; }

    Params p_;
    Drive d_;
    State s_;
    Simulator sim_;
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
};

}  // namespace impactlab::gui
