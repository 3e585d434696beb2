#include "replay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace impactlab::gui {

std::size_t sample_at(const History<SimMsg>& h, double t) {
    // The first sample after t, less one: the newest the panels may show at t.
    const std::size_t after = h.lower_bound(std::nextafter(t, INFINITY), [](const SimMsg& m) { return m.t; });
    return after == 0 ? 0 : after - 1;
}

HeldSpan held_span(const History<SimMsg>& h) {
    if (h.empty()) return {};
    return {h[0].t, h.back().t};
}

bool Replay::enter(const History<SimMsg>& h, bool sim_paused) {
    if (h.empty()) return false;
    if (!active_) was_paused_ = sim_paused;
    active_ = true;
    playing_ = false;
    t_ = h.back().t;
    at_end_ = true;
    return true;
}

bool Replay::leave() {
    active_ = false;
    playing_ = false;
    return was_paused_;
}

void Replay::set_rate(double r) {
    rate_ = std::isfinite(r) ? std::clamp(r, kMinRate, kMaxRate) : 1.0;
}

std::size_t Replay::update(const History<SimMsg>& h, double dt_wall) {
    if (!active_) return h.empty() ? 0 : h.size() - 1;
    if (h.empty()) {
        leave();
        return 0;
    }
    if (playing_ && std::isfinite(dt_wall) && dt_wall > 0) t_ += rate_ * dt_wall;
    const HeldSpan held = held_span(h);
    if (!std::isfinite(t_)) t_ = held.last;
    t_ = std::clamp(t_, held.first, held.last);
    at_end_ = t_ >= held.last;
    if (at_end_) playing_ = false;   // played up to the newest sample: stays there, paused
    return sample_at(h, t_);
}

ClipPlan plan_clip(const History<SimMsg>& h, double t_end, double seconds, double fps, double rate) {
    auto ok = [](double v) { return std::isfinite(v) && v > 0; };
    if (!ok(seconds)) throw std::invalid_argument("clip length must be a positive number of seconds");
    if (!ok(fps)) throw std::invalid_argument("clip frame rate must be positive");
    if (!ok(rate)) throw std::invalid_argument("clip playback rate must be positive");
    if (h.empty()) throw std::invalid_argument("nothing recorded yet");
    const HeldSpan held = held_span(h);
    ClipPlan p;
    p.t1 = std::clamp(std::isfinite(t_end) ? t_end : held.last, held.first, held.last);
    p.t0 = std::max(held.first, p.t1 - seconds);
    p.dt = rate / fps;
    // One frame at each end at least; the last frame lands on or just before t1.
    const double n = 1 + std::floor((p.t1 - p.t0) / p.dt + 1e-9);
    if (n > kMaxClipFrames)
        throw std::invalid_argument("a clip of " + std::to_string(static_cast<long long>(n)) + " frames is too long (at most " +
                                    std::to_string(kMaxClipFrames) + ")");
    p.frames = static_cast<int>(n);
    return p;
}

}  // namespace impactlab::gui
