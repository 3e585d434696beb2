// The Poincare map's view (views/view.hpp): the map the context shows, fitted to its points (a new decision
// snaps the view, otherwise it glides); while the map settles, the phase portrait's view.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "sim/history.hpp"
#include "render/plot2d.hpp"
#include "sim/state_pick.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

// The clicker's orbits (as in DynamicalSystems.jl's interactive Poincare maps): each click on the map starts
// the cart from that (x, v) at the next section, and the section points that follow are kept in the
// orbit's own colour until the next click or change, so coexisting attractors are mapped by hand.
struct ClickedOrbit {
    double x0 = 0, v0 = 0;                       // where it was started [m, m/s]
    std::vector<std::pair<double, double>> pts;  // its section points (x, v)
    std::uint32_t click_epoch = 0, epoch = 0;    // the epoch at the click, and the orbit's own once it runs
    bool waiting = true;                         // the restart has not arrived yet
    std::size_t taken = 0;                       // sections of its epoch already copied
};

class PoincarePanel {
public:
    ViewAction draw(const ViewContext& ctx, const AutoRange& phase_x, const AutoRange& phase_v);
    bool clicker() const { return clicker_; }
    void set_clicker(bool on) { clicker_ = on; }
    // A new orbit from (x, v); the App restarts the cart there (epoch: the App's now).
    void start_orbit(double x, double v, std::uint32_t epoch);
    void clear_orbits() { orbits_.clear(); }
    // Orbits as a session saved them: shown as they ended, none of them fed again.
    void restore_orbits(std::vector<ClickedOrbit> orbits) {
        for (ClickedOrbit& o : orbits) {
            o.waiting = false;
            o.epoch = kNoEpoch;
        }
        orbits_ = std::move(orbits);
    }
    const std::vector<ClickedOrbit>& orbits() const { return orbits_; }
    static constexpr std::size_t kMaxOrbits = 8, kMaxOrbitPoints = 4000;
    static constexpr std::uint32_t kNoEpoch = 0xffffffffu;   // a restored orbit's: no run's epoch

private:
    void feed_orbits(const ViewContext& ctx);
    // draw()'s layers: the map's points into buckets_ (noting the impact counts seen), the view fitted to the
    // map or the orbits, the points and orbits drawn, the clicker's note, tooltip and click.
    void sort_points(const History<MapPoint>& pts, bool periodic, bool (&impacts_seen)[4]);
    void fit_view(const ViewContext& ctx, const AutoRange& phase_x, const AutoRange& phase_v, double area_w, double area_h,
                  double edge, double label_band);
    void draw_points(Plot& plot, const History<MapPoint>& pts, float dot, float ring, float ui_scale);
    void draw_clicker(Plot& plot, const ViewContext& ctx, ViewAction& act);
    bool clicker_ = false;
    std::vector<ClickedOrbit> orbits_;
    ClickDelay click_;

    AutoRange x_, v_;
    WindowExtent x_extent_, v_extent_;
    std::uint64_t fit_generation_ = ~std::uint64_t{0};   // the map's generation the fit last snapped to
    std::vector<std::uint32_t> buckets_[16];             // per frame: map points by age band and impacts
};

}  // namespace impactlab::gui
