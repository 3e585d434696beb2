#include "omega_ramp.hpp"

#include <cmath>
#include <cstdio>

namespace impactlab::gui {

std::string OmegaRamp::check(double target, double rate, double omega_max, double min_rate, double max_rate) {
    char buf[160];
    if (!std::isfinite(target) || target < 0 || target > omega_max) {
        std::snprintf(buf, sizeof buf, "ramp: the target omega must be in [0, %g] rad/s", omega_max);
        return buf;
    }
    if (!std::isfinite(rate) || rate < min_rate || rate > max_rate) {
        std::snprintf(buf, sizeof buf, "ramp: the rate must be in [%g, %g] rad/s per s", min_rate, max_rate);
        return buf;
    }
    return {};
}

void OmegaRamp::begin(double omega_now, double target, double rate) {
    active_ = true;
    start_ = omega_now;
    target_ = target;
    rate_ = rate;
    points_.clear();
}

bool OmegaRamp::on_msg(const SimMsg& m) {
    if (!active_ || m.source != 0) return false;
    if (m.kind == MsgKind::Section && points_.size() < kMaxPoints) points_.push_back({m.omega, m.x});
    if (m.kind == MsgKind::Sample && std::abs(m.omega - target_) <= 1e-9 * std::max(1.0, target_)) {
        active_ = false;
        return true;
    }
    return false;
}

}  // namespace impactlab::gui
