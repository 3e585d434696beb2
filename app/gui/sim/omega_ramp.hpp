// The live omega ramp, a teaching overlay: the simulation's omega moves slowly from where it is to a
// target (the engine's CmdKind::Ramp, the paper's EF protocol run live) while the rig keeps running, and the
// section points it passes are collected as (omega, x) to be drawn over the bifurcation diagram as it grows.
// GL-free; UI thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/sim_messages.hpp"

namespace impactlab::gui {

class OmegaRamp {
public:
    struct Point { double omega, x; };   // [rad/s], [m]
    static constexpr std::size_t kMaxPoints = std::size_t{1} << 18;

    // Checks a request: target in [0, omega_max], rate in [min_rate, max_rate]. Returns "" or the problem.
    static std::string check(double target, double rate, double omega_max, double min_rate, double max_rate);
    // A ramp was sent from `omega_now` (the points of an earlier ramp are dropped).
    void begin(double omega_now, double target, double rate);
    void stop() { active_ = false; }
    // Every record the UI drains, while active: section points of the cart (not its companion) join the
    // list; the ramp ends when a sample reaches the target. Returns true if it has just ended.
    bool on_msg(const SimMsg& m);

    bool active() const { return active_; }
    double target() const { return target_; }
    double rate() const { return rate_; }
    double omega_start() const { return start_; }
    const std::vector<Point>& points() const { return points_; }

private:
    bool active_ = false;
    double start_ = 0, target_ = 0, rate_ = 0;
    std::vector<Point> points_;
};

}  // namespace impactlab::gui
