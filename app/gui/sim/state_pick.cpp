#include "state_pick.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/sim_engine.hpp"

namespace impactlab::gui {

PickedState pick_state(double x, double v, double xI, bool has_bumper) {
    PickedState s;
    s.x = std::isfinite(x) ? x : 0.0;
    s.v = std::isfinite(v) ? v : 0.0;
    char buf[128];
    if (std::abs(s.x) > kMaxAbsStateX) {
        s.x = std::clamp(s.x, -kMaxAbsStateX, kMaxAbsStateX);
        std::snprintf(buf, sizeof buf, "x kept on the rail: %+.1f mm", s.x * 1e3);
        s.note = buf;
    }
    if (has_bumper && s.x > xI) {
        s.x = xI;
        std::snprintf(buf, sizeof buf, "beyond the bumper: the cart is put on it, x = x_I = %+.2f mm", xI * 1e3);
        s.note = buf;
    }
    if (std::abs(s.v) > kMaxAbsStateV) {
        s.v = std::clamp(s.v, -kMaxAbsStateV, kMaxAbsStateV);
        s.note += s.note.empty() ? "" : "; ";
        s.note += "v limited to 2 m/s";
    }
    return s;
}

void ClickDelay::click(double x, double v, double now) {
    if (swallow_) {
        swallow_ = false;
        return;
    }
    pending_ = true;
    x_ = x;
    v_ = v;
    t_ = now;
}

std::optional<std::pair<double, double>> ClickDelay::due(double now, double delay) {
    if (!pending_ || now - t_ < delay) return std::nullopt;
    pending_ = false;
    return std::pair{x_, v_};
}

}  // namespace impactlab::gui
