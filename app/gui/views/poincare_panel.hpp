// The Poincare map's view (views/view.hpp): the map the context shows, fitted to its points (a new decision
// snaps the view, otherwise it glides); while the map settles, the phase portrait's view.
#pragma once

#include <cstdint>
#include <vector>

#include "history.hpp"
#include "plot2d.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

class PoincarePanel {
public:
    void draw(const ViewContext& ctx, const AutoRange& phase_x, const AutoRange& phase_v);

private:
    AutoRange x_, v_;
    WindowExtent x_extent_, v_extent_;
    std::uint64_t fit_generation_ = ~std::uint64_t{0};   // the map's generation the fit last snapped to
    std::vector<std::uint32_t> buckets_[16];             // per frame: map points by age band and impacts
};

}  // namespace impactlab::gui
