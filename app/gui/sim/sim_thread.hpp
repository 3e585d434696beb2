// The simulation thread: the only owner of the simulator state (a SimEngine) once started. It paces the
// simulation against the wall clock at a chosen real-time factor, with a cap on the work done per
// iteration so commands are handled within milliseconds even when the model runs slower than asked.
//
//   UI thread --SimCommand--> [SpscRing commands_] --> sim thread   (UI produces, sim consumes)
//   sim thread --SimMsg-----> [SpscRing samples_]  --> UI thread    (sim produces, UI consumes)
//
// Besides the rings, a few relaxed atomics report status (sim time, achieved speed) for the status bar, and
// the energy balance travels under a mutex the sim thread only try-locks (it never waits for the UI).
// GL-free.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <mutex>
#include <thread>

#include "sim/sim_engine.hpp"
#include "sim/spsc_ring.hpp"

namespace impactlab::gui {

struct SimStatus {
    double sim_time = 0;          // [s]
    double achieved_speed = 0;    // measured real-time factor over the last ~0.5 s
    bool paused = false;
    bool lagging = false;         // the model cannot keep up with the requested speed
    double xI = 0;                // [m] the bumper where the simulation has it now (it travels to the one asked)
    std::uint64_t dropped = 0;    // samples refused by a full ring
    std::uint64_t commands_dropped = 0;   // commands refused by a full ring (CommandLink holds and resends them)
    EnergyBalance energy;         // since the last change of model, xI or state (the energy bar)
};

class SimThread {
public:
    static constexpr std::size_t kSampleCapacity = std::size_t{1} << 17;   // ~1.3 s at 100x
    static constexpr std::size_t kCommandCapacity = 256;
    // Work per iteration before the loop checks its commands again [ms].
    static constexpr int kWorkCapMs = 6;

    // UI thread. Builds the engine (throws ParamError for an unknown model); call start() to run it.
    explicit SimThread(const EngineConfig& cfg);
    ~SimThread();   // UI thread: stops and joins
    SimThread(const SimThread&) = delete;
    SimThread& operator=(const SimThread&) = delete;

    // UI thread.
    void start();
    // UI thread. Idempotent.
    void stop();
    // UI thread (the commands ring's only producer). False if the ring is full (the command is dropped and
    // counted in status().commands_dropped). The app sends through a CommandLink, which resends what is refused.
    bool send(const SimCommand& c);
    // UI thread. Like send, for a command refused before and sent again: a refusal is not counted twice.
    bool resend(const SimCommand& c) { return commands_.try_push_no_drop(c); }
    // UI thread (the samples ring's only consumer) drains this.
    SpscRing<SimMsg>& samples() { return samples_; }
#ifdef __EMSCRIPTEN__
    // UI thread, once a frame, in a browser (no threads there): one slice of the loop run() repeats.
    void pump() { slice(); }
#endif
    // Any thread.
    SimStatus status() const;

private:
    class RingSink final : public MsgSink {
    public:
        explicit RingSink(SpscRing<SimMsg>& r) : ring_(r) {}
        // Sim thread (the producer). Stages the record; shows the batch every kPublishEvery records and
        // at the end of each work slice (SimThread::run calls publish()).
        void put(const SimMsg& m) override {
            ring_.try_stage(m);
            if (ring_.unpublished() >= kPublishEvery) ring_.publish();
        }
        void publish() { ring_.publish(); }   // sim thread
        // Sim thread. Room for the largest piece the engine can publish after asking (a slice's span of
        // 1 ms samples, ~10 s at 100x behind the clock) and for the companion's share of the slice.
        bool has_room() override { return ring_.has_room(ring_.capacity() / 4); }
        static constexpr std::size_t kPublishEvery = 256;
    private:
        SpscRing<SimMsg>& ring_;
    };

    void run();   // sim thread
    // Sim thread: the pacing's starting point, then one iteration of run()'s loop (commands, then at most
    // kWorkCapMs of simulation up to where the clock says); returns how long to sleep [us], 0 for not at all.
    void begin_pacing();
    int slice();
    struct Pacing {
        std::chrono::steady_clock::time_point anchor_wall, meter_wall;
        double anchor_sim = 0, meter_sim = 0, speed = 1;
    };
    Pacing pace_;   // sim thread only
    // Sim thread: a command for the cart, mirrored to the companion (SetCompanion configures it).
    void apply(const SimCommand& c);
    // Sim thread: the companion starts again from the cart's state (the twin kTwinOffset to the right).
    void restart_companion();

    SpscRing<SimMsg> samples_{kSampleCapacity};
    SpscRing<SimCommand> commands_{kCommandCapacity};
    RingSink sink_{samples_};
    SimEngine engine_;   // touched by the UI thread only before start()
    // The companion cart: a second engine advanced to the same sim time as engine_ after
    // every slice, fed the same commands; its records carry SimMsg::source = 1. Sim thread only.
    std::unique_ptr<SimEngine> companion_;
    CompanionMode companion_mode_ = CompanionMode::Off;
    std::string ghost_impact_;   // the ghost's impact law id ("G"); its stiffness follows the cart's
    double twin_offset_ = kTwinOffset;
    std::thread thread_;
    std::atomic<bool> quit_{false};
    std::atomic<double> sim_time_{0.0};
    std::atomic<double> achieved_{0.0};
    std::atomic<bool> paused_{false};
    std::atomic<bool> lagging_{false};
    std::atomic<double> bumper_{0.0};
    mutable std::mutex energy_mutex_;   // guards energy_: the UI locks it, the sim thread only try-locks
    EnergyBalance energy_;
};

}  // namespace impactlab::gui
