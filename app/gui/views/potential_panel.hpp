// The potential well's view (views/view.hpp): V(x) of the current stiffness, its y range following the
// largest energy of the phase portrait's trail; a click puts the cart there at rest.
#pragma once

#include <string>
#include <vector>

#include "sim/history.hpp"
#include "render/plot2d.hpp"
#include "sim/state_pick.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

class PotentialPanel {
public:
    ViewAction draw(const ViewContext& ctx);
    double trail_energy_max() const { return e_max_; }   // [J] at the last frame (--state-json)
    Range view_y() const { return y_.cur; }              // [J] the y range on screen

private:
    AutoRange y_;
    WindowExtent energy_extent_;   // the energy over the trail
    double e_max_ = 0;
    std::vector<double> curve_x_, curve_v_;   // V(x) of the stiffness and revision curve_for_
    std::string curve_for_;
    ClickDelay click_;
};

}  // namespace impactlab::gui
