// --state-json: what the panels show after a headless run, for tests and scripts (App::write_state_json).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "window/app.hpp"
#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/json_text.hpp"
#include "sim/param_edit.hpp"
#include "views/contact_label.hpp"

namespace impactlab::gui {

namespace {
// NaN and infinities have no JSON spelling: null.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

// UI thread, after the last frame.
bool App::write_state_json(const std::string& path) {
    using nlohmann::json;
    json j;
    j["model"] = model_name();
    j["model_file"] = opt_.model_file.empty() ? json(nullptr) : json(opt_.model_file);   // --model FILE.json
    {   // The Poincare clicker's orbits: where each started, its section points, the last of them.
        json orbits = json::array();
        for (const ClickedOrbit& o : poincare_.orbits())
            orbits.push_back({{"start", {number(o.x0), number(o.v0)}}, {"points", o.pts.size()},
                              {"last", o.pts.empty() ? json(nullptr) : json{number(o.pts.back().first), number(o.pts.back().second)}},
                              {"spread", o.pts.size() < 20 ? json(nullptr) : [&] {
                                   // max - min of x over its last 20 points [m]: ~0 on a periodic orbit of period <= 20
                                   double lo = 1e300, hi = -1e300;
                                   for (std::size_t i = o.pts.size() - 20; i < o.pts.size(); ++i) {
                                       lo = std::min(lo, o.pts[i].first);
                                       hi = std::max(hi, o.pts[i].first);
                                   }
                                   return number(hi - lo);
                               }()}});
        j["clicker"] = {{"on", poincare_.clicker()}, {"orbits", std::move(orbits)}};
    }
    j["guide"] = {{"open", demos_.show}, {"demo", demos_.last}, {"details", view_.details}, {"basins_open", layout_.panel_visible[static_cast<std::size_t>(PanelId::Basins)]},
                  {"collapsed", demos_.panel.collapsed()},
                  {"controls_tab", layout_.controls_tab < 0 || !layout_.frame.controls_tabbed ? json(nullptr) : json(layout_.controls_tab == 0 ? "Run" : layout_.controls_tab == 1 ? "View" : "State")},
                  {"rect", {demos_.panel.rect()[0], demos_.panel.rect()[1], demos_.panel.rect()[2], demos_.panel.rect()[3]}}};
    {   // The time strip's traces and their y ranges [SI units].
        json traces = json::array(), views = json::array();
        traces.push_back(strip_key(strip_.first()));
        views.push_back({number(strip_.view_y(0).lo), number(strip_.view_y(0).hi)});
        if (const auto q = strip_.second()) {
            traces.push_back(strip_key(*q));
            views.push_back({number(strip_.view_y(1).lo), number(strip_.view_y(1).hi)});
        }
        j["strip"] = {{"traces", std::move(traces)}, {"views", std::move(views)}};
    }
    {   // The running model's parameters as the Parameters panel shows them, and whether any was edited.
        json ps = json::object();
        for (const EditableParam& e : editable_params(run_.params)) ps[e.key] = number(e.value);
        j["params"] = std::move(ps);
        j["params_edited"] = params_edited(run_.params);
    }
    j["omega"] = number(run_.omega);
    j["xI"] = number(run_.xI);
    j["speed"] = number(run_.speed);
    j["preset"] = opt_.preset > 0 ? json(presets_for(model_name())[static_cast<std::size_t>(opt_.preset - 1)].label)
                                  : json(nullptr);
    j["sim_time"] = number(feed_.have_last ? feed_.last.t : sim_->status().sim_time);
    // Commands to the simulation thread: held back by a full ring (resent each frame), given up, and the
    // ring's own count of refusals (each held command once).
    j["commands"] = {{"waiting", commands_.waiting()}, {"deferred", commands_.deferred()}, {"lost", commands_.lost()},
                     {"refused", sim_->status().commands_dropped}};
    j["fps"] = number(frames_.fps);
    // The trajectory history (replay's range): a continued run keeps the past and drops the old future.
    j["history"] = {{"samples", feed_.traj.size()},
                    {"t_first", feed_.traj.empty() ? json(nullptr) : number(feed_.traj[0].t)},
                    {"t_last", feed_.traj.empty() ? json(nullptr) : number(feed_.traj.back().t)},
                    {"replay_t", replay_.player.active() ? number(replay_.player.cursor()) : json(nullptr)}};
    j["ramp"] = {{"active", ramp_.live.active()}, {"omega_from", number(ramp_.live.omega_start())},
                 {"omega_to", number(ramp_.live.target())}, {"rate", number(ramp_.live.rate())},
                 {"points", ramp_.live.points().size()}};
    j["frames"] = frames_.count;
    j["epoch"] = feed_.epoch;
    j["energy"] = number(feed_.last.energy);                 // [J] now
    j["energy_max_trail"] = number(potential_.trail_energy_max());       // [J] over the phase portrait's trail
    {
        const EnergyBalance eb = sim_->status().energy;   // the energy bar's numbers [J]
        j["energy_balance"] = {{"t0", number(eb.t0)}, {"t", number(eb.t)}, {"E0", number(eb.E0)}, {"E", number(eb.E)},
                               {"work_unbalance", number(eb.work_unbalance)},
                               {"dissipated_resistance", number(eb.dissipated_resistance)},
                               {"dissipated_bumper", number(eb.dissipated_bumper)}, {"residual", number(eb.residual())}};
    }
    {
        // The companion cart: mode, its state, its separation |dx| from the cart [m].
        json c;
        c["mode"] = companion_.mode == CompanionMode::Twin ? "twin" : companion_.mode == CompanionMode::Ghost ? "ghost" : "off";
        if (companion_.mode != CompanionMode::Off) {
            if (companion_.mode == CompanionMode::Ghost)
                c["model"] = std::string(stiffness_sets()[static_cast<std::size_t>(run_.stiffness)].id) +
                             impact_models()[static_cast<std::size_t>(companion_.ghost_impact)].id;
            c["x"] = companion_.track.have() ? number(companion_.track.last().x) : json(nullptr);
            c["v"] = companion_.track.have() ? number(companion_.track.last().v) : json(nullptr);
            c["t"] = companion_.track.have() ? number(companion_.track.last().t) : json(nullptr);
            c["separation"] = number(companion_.track.separation_now());
            c["separation_start"] = number(companion_.track.separation_start());
            c["separation_max"] = number(companion_.track.separation_max());
        }
        j["companion"] = std::move(c);
        // The grazing monitor over the last whole forcing period (null before one).
        json g = nullptr;
        if (feed_.have_grazing) {
            g = json::object();
            g["x_max"] = number(feed_.grazing.x);
            g["distance"] = number(feed_.xI_shown - feed_.grazing.x);   // [m] xI - max x
            g["impacts"] = static_cast<int>(feed_.grazing.energy);
            g["impact_velocity"] = number(feed_.grazing.v);         // [m/s] v- (rigid) or entry (compliant); null: none
            g["penetration"] = number(feed_.grazing.force);          // [m] compliant
        }
        j["grazing"] = std::move(g);
        j["regime_label"] = contact_label(run_.params, feed_.last.regime, feed_.last.force);   // the rig's and the status bar's
        j["x"] = number(feed_.last.x);
        j["v"] = number(feed_.last.v);
        // The largest jump of x between two samples in the x(t) strip's window [m] (a bumper moved
        // into the cart made a staircase of x(t)).
        double step = 0;
        const std::size_t n = feed_.traj.size();
        if (n > 1) {
            const double t_from = feed_.traj.back().t - view_.strip_window;
            for (std::size_t i = feed_.traj.lower_bound(t_from, [](const SimMsg& m) { return m.t; }) + 1; i < n; ++i)
                step = std::max(step, std::abs(feed_.traj[i].x - feed_.traj[i - 1].x));
        }
        j["x_max_step"] = step;
    }
    j["potential_view"] = {potential_.view_y().lo, potential_.view_y().hi};   // [J] the potential plot's y range
    const PoincareMap& map = shown_map();   // replaying: the map at the cursor, as the panel shows it
    const PoincareMap::Status st = map.status();
    j["poincare_status"] = st == PoincareMap::Status::Periodic ? "periodic"
                           : st == PoincareMap::Status::Chaotic ? "chaos"
                           : map.provisional()                   ? "provisional" : "settling";
    j["poincare_period"] = st == PoincareMap::Status::Settling ? json(nullptr) : json(map.period());
    j["poincare_slow"] = map.slow();   // settling on an alternation still dying out (a multiplier near -1)
    j["poincare_decay"] = std::isfinite(map.decay()) ? json(map.decay()) : json(nullptr);   // its shrink per period
    j["poincare_omega_moving"] = ramp_.live.active();   // the label says omega moves
    j["poincare_seen"] = map.seen();   // section points since the last change, the transient included
    j["poincare_tol"] = {map.tol_x(), map.tol_v()};
    json pts = json::array(), imp = json::array();
    const History<MapPoint>& h = map.points();
    for (std::size_t i = 0; i < h.size(); ++i) {
        pts.push_back({h[i].x, h[i].v});
        imp.push_back(h[i].impacts);
    }
    j["poincare_points"] = std::move(pts);
    // The section's phase asked for [rad], and the newest section point the engine sent in this epoch: its
    // t, its phi reduced to [0, 2 pi) (phi0 there, up to rounding), x and v.
    j["poincare_phi0"] = number(view_.section_phase);
    if (!feed_.sections.empty()) {
        const SimMsg& m = feed_.sections.back();
        j["poincare_last_section"] = {{"t", number(m.t)}, {"phi_mod", number(m.phi - kTwoPi * std::floor(m.phi / kTwoPi))},
                                      {"x", number(m.x)}, {"v", number(m.v)}};
    } else {
        j["poincare_last_section"] = nullptr;
    }
    j["session_window"] = session_.open ? json(session_.saving ? "save" : "load") : json(nullptr);
    j["session_path"] = session_.path;
    j["session_overwrite_asked"] = session_.overwrite_pending.empty() ? json(nullptr) : json(session_.overwrite_pending);
    j["session_browser"] = session_.open ? session_.browser.state() : json(nullptr);   // the files it lists
    j["plane"] = analysis_.plane.state();
    j["basins"] = analysis_.basins.state();   // the basins shown: their box, grid and attractors   // the plane shown and the doubling continued over it
    if (const auto& ov = analysis_.overlay()) {   // the continued branches' special points, as the hover names them
        json bif_pts = json::array();
        for (const analysis::BifPoint& b : ov->points)
            bif_pts.push_back({{"kind", analysis::bif_kind_name(b.kind)}, {"omega", b.param}, {"x", b.y[0]}, {"v", b.y[1]},
                               {"period", b.period}, {"precision", b.precision}});
        j["continuation"] = {{"model", ov->model}, {"omega_lo", ov->omega_lo}, {"omega_hi", ov->omega_hi},
                             {"cancelled", ov->cancelled}, {"curves", ov->curves.size()}, {"points", std::move(bif_pts)},
                             {"end", ov->end}};
        double lo = 1e300, hi = -1e300;   // the branches' x [m]: what the diagram's y range must hold
        for (const BranchCurve& cv : ov->curves)
            for (const double x : cv.x) lo = std::min(lo, x), hi = std::max(hi, x);
        j["continuation"]["x_range"] = hi >= lo ? json{number(lo), number(hi)} : json(nullptr);
        if (ov->from_orbit)
            j["continuation"]["from_orbit"] = {{"omega", ov->start_omega}, {"x", ov->start_x}, {"v", ov->start_v},
                                               {"period", ov->start_period}};
    } else {
        j["continuation"] = nullptr;
    }
    {   // The bifurcation panel: the diagram shown (its omega range, columns done, stale after a switch) and
        // the Lyapunov strip under it.
        const BifurcationState b = bif_.panel.state(bifurcation_context());
        json d = b.have ? json{{"model", b.model}, {"protocol", b.protocol}, {"omega_lo", number(b.omega_lo)},
                               {"omega_hi", number(b.omega_hi)}, {"steps", b.steps}, {"levels_done", b.levels_done},
                               {"points", b.points}, {"running", b.running}, {"cancelled", b.cancelled},
                               {"stale", b.stale}, {"progress", number(b.progress)}}
                        : json{{"model", nullptr}, {"running", b.running}};
        d["over"] = sweep_param_name(b.over);   // the horizontal axis: omega, xI or m0e
        if (b.have) {
            d["lo"] = number(b.lo);   // its range [rad/s, m or kg m]
            d["hi"] = number(b.hi);
            d["omega"] = b.over == SweepParam::Omega ? json(nullptr) : json(number(b.omega));
            json lv = json::array();
            for (const auto& l : b.level_x) lv.push_back({number(l.at), number(l.x_min), number(l.x_max)});
            d["level_x"] = std::move(lv);   // each level's value, least and greatest x [m]
        }
        d["view_omega"] = {number(b.view_omega.lo), number(b.view_omega.hi)};
        d["y"] = b.y_is_v ? "v" : "x";
        d["view_y"] = {number(b.view_y.lo), number(b.view_y.hi)};
        d["range_error"] = b.range_error;
        d["live_points"] = {{"total", b.live.total}, {"in_view", b.live.in_view}, {"beyond", b.live.beyond},
                            {"above", b.live.above}, {"below", b.live.below}};
        d["lyapunov"] = {{"on", b.lyap_on}, {"running", b.lyap_running}, {"steps", b.lyap_steps},
                         {"done", b.lyap_done}, {"positive", b.lyap_positive}};
        const auto& om = bif_.panel.omega_label();
        d["omega_label_rect"] = {om[0], om[1], om[2], om[3]};   // [px] the running omega's label
        const auto& pr = bif_.panel.plot_rect();
        d["plot_rect"] = {pr[0], pr[1], pr[2], pr[3]};   // [px] the data area drawn (zeros: not drawn)
        const auto& lg = analysis_.legend_rect();
        d["legend_rect"] = lg[2] > lg[0] ? json{lg[0], lg[1], lg[2], lg[3]} : json(nullptr);   // the branches' legend
        json mk = json::array();
        for (const auto& q : analysis_.markers()) mk.push_back({q[0], q[1]});
        d["markers_px"] = std::move(mk);   // the bifurcation points drawn
        j["diagram"] = std::move(d);
    }
    j["poincare_impacts"] = std::move(imp);   // impacts in the forcing period ending at each point

    j["layout"] = layout_json();   // tiles.cpp: mode, scale, panels, tiles, magnification

    // Written whole (a partial file beside the target, every write checked, renamed over it); a file name in
    // any bytes (--browse over a folder holding one) is written escaped: the dump never throws.
    try {
        write_file_whole(path, json_dump(std::move(j), 1) + "\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "impactlab-gui: error: --state-json: %s\n", printable(e.what()).c_str());
        return false;
    }
    return true;
}

}  // namespace impactlab::gui
