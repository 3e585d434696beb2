// What the UI keeps of the companion cart (the twin 1 um apart, or the ghost under another impact law):
// its own trajectory, and its separation |dx| from the cart at the same sample instants,
// which the sim thread keeps on one grid for both. GL-free; UI thread only.
#pragma once

#include <cstdint>

#include "sim/history.hpp"
#include "sim/sim_messages.hpp"

namespace impactlab::gui {

// The separation is kept every 20 ms of sim time (the first pair at once): 65,536 of them cover 22 minutes,
// the whole growth from 1 um at the forcing's time scale (a period is 0.2 - 0.7 s).
inline constexpr double kSeparationEvery = 0.02;   // [s]

struct Separation {
    double t = 0;    // [s]
    double dx = 0;   // |x_companion - x_cart| [m]
};

class CompanionTrack {
public:
    CompanionTrack() = default;
    void clear();
    // A record with source 1. `cart` is the cart's trajectory, which holds the samples up to m.t already
    // (the sim thread publishes the cart's slice before the companion's).
    void on_msg(const SimMsg& m, const History<SimMsg>& cart);

    const History<SimMsg>& traj() const { return traj_; }
    const History<Separation>& separation() const { return sep_; }
    bool have() const { return have_; }
    const SimMsg& last() const { return last_; }
    const SimMsg& grazing() const { return grazing_; }   // its grazing monitor's last period (kind Grazing)
    bool have_grazing() const { return have_grazing_; }
    // |dx| at the latest common instant, at the restart (the first pair), and its growth in decades.
    double separation_now() const { return sep_.empty() ? 0.0 : sep_.back().dx; }
    double separation_start() const { return sep0_; }
    double separation_max() const { return sep_max_; }

private:
    History<SimMsg> traj_{std::size_t{1} << 18};
    History<Separation> sep_{std::size_t{1} << 16};
    SimMsg last_{}, grazing_{};
    bool have_ = false, have_grazing_ = false;
    std::uint32_t epoch_ = ~0u;
    double sep0_ = 0, sep_max_ = 0;
    double next_sep_t_ = 0;
};

}  // namespace impactlab::gui
