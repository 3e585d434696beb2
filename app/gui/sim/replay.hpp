// Replay of the recent past: a cursor in simulated time over the UI's
// trajectory history (History<SimMsg>, about 9 min at 1x), which the panels show as it was at that time,
// and the plan of a clip exported from it. The simulation thread is paused meanwhile; nothing here talks
// to it. GL-free, UI thread only.
#pragma once

#include <cstddef>

#include "sim/history.hpp"
#include "sim/sim_messages.hpp"

namespace impactlab::gui {

// Index of the last sample at or before time t [s] (0 if t is before the first). h must not be empty;
// its times are nondecreasing (a reset clears it).
std::size_t sample_at(const History<SimMsg>& h, double t);

// The times [s] the history still holds: the slider's range.
struct HeldSpan {
    double first = 0, last = 0;
    double span() const { return last - first; }
};
HeldSpan held_span(const History<SimMsg>& h);

class Replay {
public:
    static constexpr double kMinRate = 0.05, kMaxRate = 4.0;

    bool active() const { return active_; }
    // Starts at the newest sample of h; false (and nothing changes) if h is empty. `sim_paused` is what the
    // simulation was doing, given back by leave().
    bool enter(const History<SimMsg>& h, bool sim_paused);
    // Returns whether the simulation was paused when replay began.
    bool leave();

    // Each frame, before the panels draw: moves the cursor by rate * dt_wall while playing (stopping at the
    // newest sample), clamps it to what h still holds (the oldest samples are overwritten, a reset clears
    // it), and returns the index of the sample shown. Leaves replay (returns 0) if h became empty.
    std::size_t update(const History<SimMsg>& h, double dt_wall);

    double cursor() const { return t_; }   // [s] simulated time shown
    void seek(double t) { t_ = t; }        // clamped at the next update()
    void step(double dt) { t_ += dt; }     // [s], either way
    bool playing() const { return playing_; }
    void set_playing(bool p) { playing_ = p; }
    double rate() const { return rate_; }  // simulated seconds per wall second while playing
    void set_rate(double r);               // clamped to [kMinRate, kMaxRate]
    bool at_end() const { return at_end_; }   // the cursor is on the newest sample

private:
    bool active_ = false, playing_ = false, was_paused_ = false, at_end_ = true;
    double t_ = 0, rate_ = 1.0;
};

// What a clip covers: `frames` frames at times t0 + k * dt [s] of simulated time (k = 0 .. frames - 1),
// one every rate / fps seconds, so that played at fps the clip runs at `rate` times real time.
struct ClipPlan {
    double t0 = 0, t1 = 0, dt = 0;
    int frames = 0;
    double time_of(int k) const { return t0 + dt * k; }
};
inline constexpr int kMaxClipFrames = 10000;   // 5.5 min at 30 fps: what a folder of PNGs should hold
// The `seconds` [s] of simulated time that end at t_end, limited to what h holds. Throws
// std::invalid_argument for seconds, fps or rate not positive and finite, an empty history, or a clip of
// more than kMaxClipFrames frames.
ClipPlan plan_clip(const History<SimMsg>& h, double t_end, double seconds, double fps, double rate);

}  // namespace impactlab::gui
