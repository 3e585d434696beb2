// The rig's view (views/view.hpp): RigView's drawing, the labels, the companion's outline; the cart can be
// dragged (the simulation holds it at the mouse, and letting go starts it there at rest).
#pragma once

#include <string>

#include "render/rig_view.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

class RigPanel {
public:
    bool init(std::string& error) { return rig_.init(error); }   // with the GL context current
    void shutdown() { rig_.shutdown(); }
    ViewAction draw(const ViewContext& ctx);

private:
    ViewAction mouse(const ViewContext& ctx, ImVec2 image_min, float fbs);   // drag the cart (left button)
    RigView rig_;
    bool dragging_ = false;
    double drag_grab_ = 0;   // [m] where on the cart the mouse took it (cart centre - mouse)
    double drag_x_ = 0;      // [m] where the mouse holds the cart
};

}  // namespace impactlab::gui
