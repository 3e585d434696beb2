// The x(t) strip's view (views/view.hpp): it scrolls once the history covers its window.
#pragma once

#include "history.hpp"
#include "plot2d.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

class StripPanel {
public:
    ViewAction draw(const ViewContext& ctx);

private:
    void draw_separation(const ViewContext& ctx, ImVec2 size);   // beside x(t): log10 |dx| of cart and companion
    AutoRange y_;
    WindowExtent x_extent_;
};

}  // namespace impactlab::gui
