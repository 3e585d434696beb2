#include "companion_track.hpp"

#include <algorithm>
#include <cmath>

namespace impactlab::gui {

void CompanionTrack::clear() {
    traj_.clear();
    sep_.clear();
    have_ = have_grazing_ = false;
    epoch_ = ~0u;
    sep0_ = sep_max_ = 0;
    next_sep_t_ = -1e300;
}

void CompanionTrack::on_msg(const SimMsg& m, const History<SimMsg>& cart) {
    if (m.epoch != epoch_) {
        // A restart from the cart's state (SimEngine::restart_from counts runs in the high 16 bits): what
        // came before is another run. A change within the run (omega, xI) keeps the track.
        if (!have_ || (m.epoch >> 16) != (epoch_ >> 16)) {
            traj_.clear();
            sep_.clear();
            sep0_ = sep_max_ = 0;
        }
        have_grazing_ = false;
        epoch_ = m.epoch;
    }
    switch (m.kind) {
        case MsgKind::Grazing:
            grazing_ = m;
            have_grazing_ = true;
            return;
        case MsgKind::Sample:
            break;
        default:
            return;
    }
    traj_.push(m);
    last_ = m;
    have_ = true;
    // The cart's sample at the same instant (the grids coincide; else the nearest later one).
    const std::size_t i = cart.lower_bound(m.t, [](const SimMsg& c) { return c.t; });
    if (i >= cart.size()) return;
    const SimMsg& c = cart[i];
    if (std::abs(c.t - m.t) > 1e-9 * std::max(1.0, std::abs(m.t))) return;
    if (m.t < next_sep_t_) return;
    next_sep_t_ = m.t + kSeparationEvery;
    const double dx = std::abs(m.x - c.x);
    if (sep_.empty()) sep0_ = dx;
    sep_max_ = std::max(sep_max_, dx);
    sep_.push({m.t, dx});
}

}  // namespace impactlab::gui
