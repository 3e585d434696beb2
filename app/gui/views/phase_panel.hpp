// The phase portrait's view (views/view.hpp): its auto-fit follows the trail; a click sets the state.
#pragma once

#include "sim/history.hpp"
#include "render/plot2d.hpp"
#include "sim/state_pick.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

class PhasePanel {
public:
    ViewAction draw(const ViewContext& ctx);
    // The view on screen: the Poincare map starts from it while it settles.
    const AutoRange& view_x() const { return x_; }
    const AutoRange& view_v() const { return v_; }

private:
    AutoRange x_, v_;
    WindowExtent x_extent_, v_extent_;   // the trail's extent, kept incrementally
    ClickDelay click_;
};

}  // namespace impactlab::gui
