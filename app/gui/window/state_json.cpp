// --state-json: what the panels show after a headless run, for tests and scripts (App::write_state_json).
// One function per section of the file, each from the part that holds it; the keys are sorted on output.
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
using nlohmann::json;

// NaN and infinities have no JSON spelling: null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The Poincare clicker's orbits: where each started, its section points, the last of them.
json clicker_json(const PoincarePanel& poincare) {
    json orbits = json::array();
    for (const ClickedOrbit& o : poincare.orbits())
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
    return {{"on", poincare.clicker()}, {"orbits", std::move(orbits)}};
}

// The time strip's traces and their y ranges [SI units].
json strip_json(const StripPanel& strip) {
    json traces = json::array(), views = json::array();
    traces.push_back(strip_key(strip.first()));
    views.push_back({number(strip.view_y(0).lo), number(strip.view_y(0).hi)});
    if (const auto q = strip.second()) {
        traces.push_back(strip_key(*q));
        views.push_back({number(strip.view_y(1).lo), number(strip.view_y(1).hi)});
    }
    return {{"traces", std::move(traces)}, {"views", std::move(views)}};
}

// The energy bar's numbers [J].
json energy_balance_json(const EnergyBalance& eb) {
    return {{"t0", number(eb.t0)}, {"t", number(eb.t)}, {"E0", number(eb.E0)}, {"E", number(eb.E)},
            {"work_unbalance", number(eb.work_unbalance)},
            {"dissipated_resistance", number(eb.dissipated_resistance)},
            {"dissipated_bumper", number(eb.dissipated_bumper)}, {"residual", number(eb.residual())}};
}

// The companion cart: mode, its state, its separation |dx| from the cart [m].
json companion_json(const Companion& companion, int stiffness) {
    json c;
    c["mode"] = companion.mode == CompanionMode::Twin ? "twin" : companion.mode == CompanionMode::Ghost ? "ghost" : "off";
    if (companion.mode != CompanionMode::Off) {
        if (companion.mode == CompanionMode::Ghost)
            c["model"] = std::string(stiffness_sets()[static_cast<std::size_t>(stiffness)].id) +
                         impact_models()[static_cast<std::size_t>(companion.ghost_impact)].id;
        const CompanionTrack& tr = companion.track;
        c["x"] = tr.have() ? number(tr.last().x) : json(nullptr);
        c["v"] = tr.have() ? number(tr.last().v) : json(nullptr);
        c["t"] = tr.have() ? number(tr.last().t) : json(nullptr);
        c["separation"] = number(tr.separation_now());
        c["separation_start"] = number(tr.separation_start());
        c["separation_max"] = number(tr.separation_max());
    }
    return c;
}

// The grazing monitor over the last whole forcing period (null before one).
json grazing_json(const LiveFeed& feed) {
    if (!feed.have_grazing) return nullptr;
    json g = json::object();
    g["x_max"] = number(feed.grazing.x);
    g["distance"] = number(feed.xI_shown - feed.grazing.x);   // [m] xI - max x
    g["impacts"] = static_cast<int>(feed.grazing.energy);
    g["impact_velocity"] = number(feed.grazing.v);            // [m/s] v- (rigid) or entry (compliant); null: none
    g["penetration"] = number(feed.grazing.force);            // [m] compliant
    return g;
}

// The largest jump of x between two samples in the x(t) strip's window [m] (a bumper moved into the cart
// made a staircase of x(t)).
double x_max_step(const History<SimMsg>& traj, double window) {
    double step = 0;
    const std::size_t n = traj.size();
    if (n > 1) {
        const double t_from = traj.back().t - window;
        for (std::size_t i = traj.lower_bound(t_from, [](const SimMsg& m) { return m.t; }) + 1; i < n; ++i)
            step = std::max(step, std::abs(traj[i].x - traj[i - 1].x));
    }
    return step;
}

// The Poincare map as the panel shows it (replaying: the map at the cursor), and the section's phase asked
// for [rad] with the newest section point the engine sent in this epoch: its t, its phi reduced to
// [0, 2 pi) (phi0 there, up to rounding), x and v.
void put_poincare(json& j, const PoincareMap& map, const History<SimMsg>& sections, double section_phase, bool omega_moving) {
    const PoincareMap::Status st = map.status();
    j["poincare_status"] = st == PoincareMap::Status::Periodic ? "periodic"
                           : st == PoincareMap::Status::Chaotic ? "chaos"
                           : map.provisional()                   ? "provisional" : "settling";
    j["poincare_period"] = st == PoincareMap::Status::Settling ? json(nullptr) : json(map.period());
    j["poincare_slow"] = map.slow();   // settling on an alternation still dying out (a multiplier near -1)
    j["poincare_decay"] = std::isfinite(map.decay()) ? json(map.decay()) : json(nullptr);   // its shrink per period
    j["poincare_omega_moving"] = omega_moving;   // the label says omega moves
    j["poincare_seen"] = map.seen();   // section points since the last change, the transient included
    j["poincare_tol"] = {map.tol_x(), map.tol_v()};
    json pts = json::array(), imp = json::array();
    const History<MapPoint>& h = map.points();
    for (std::size_t i = 0; i < h.size(); ++i) {
        pts.push_back({h[i].x, h[i].v});
        imp.push_back(h[i].impacts);
    }
    j["poincare_points"] = std::move(pts);
    j["poincare_impacts"] = std::move(imp);   // impacts in the forcing period ending at each point
    j["poincare_phi0"] = number(section_phase);
    if (!sections.empty()) {
        const SimMsg& m = sections.back();
        j["poincare_last_section"] = {{"t", number(m.t)}, {"phi_mod", number(m.phi - kTwoPi * std::floor(m.phi / kTwoPi))},
                                      {"x", number(m.x)}, {"v", number(m.v)}};
    } else {
        j["poincare_last_section"] = nullptr;
    }
}

// The session window: open to save or load, the path, a replacement asked about, the files it lists.
void put_session(json& j, const SessionWindow& s) {
    j["session_window"] = s.open ? json(s.saving ? "save" : "load") : json(nullptr);
    j["session_path"] = s.path;
    j["session_overwrite_asked"] = s.overwrite_pending.empty() ? json(nullptr) : json(s.overwrite_pending);
    j["session_browser"] = s.open ? s.browser.state() : json(nullptr);
}

// The continued branches' special points, as the hover names them (null: none continued).
json continuation_json(const AnalysisPanels& analysis) {
    const auto& ov = analysis.overlay();
    if (!ov) return nullptr;
    json bif_pts = json::array();
    for (const analysis::BifPoint& b : ov->points)
        bif_pts.push_back({{"kind", analysis::bif_kind_name(b.kind)}, {"omega", b.param}, {"x", b.y[0]}, {"v", b.y[1]},
                           {"period", b.period}, {"precision", b.precision}});
    json c = {{"model", ov->model}, {"omega_lo", ov->omega_lo}, {"omega_hi", ov->omega_hi},
              {"cancelled", ov->cancelled}, {"curves", ov->curves.size()}, {"points", std::move(bif_pts)},
              {"end", ov->end}};
    double lo = 1e300, hi = -1e300;   // the branches' x [m]: what the diagram's y range must hold
    for (const BranchCurve& cv : ov->curves)
        for (const double x : cv.x) lo = std::min(lo, x), hi = std::max(hi, x);
    c["x_range"] = hi >= lo ? json{number(lo), number(hi)} : json(nullptr);
    if (ov->from_orbit)
        c["from_orbit"] = {{"omega", ov->start_omega}, {"x", ov->start_x}, {"v", ov->start_v}, {"period", ov->start_period}};
    return c;
}

// The bifurcation panel: the diagram shown (its omega range, columns done, stale after a switch), the
// Lyapunov strip under it, and where its labels, legend and markers were drawn [px].
json diagram_json(const BifurcationState& b, const BifurcationPanel& panel, const AnalysisPanels& analysis) {
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
        for (const auto& l : b.level_x) lv.push_back({number(l.at), number(l.x_min), number(l.x_max), l.period});
        d["level_x"] = std::move(lv);   // each level's value, least and greatest x [m], period (-1 not settled, 0 not judged)
        d["settle"] = b.settle;               // more records a level may run to settle (0: not judged)
        d["not_settled"] = b.not_settled;     // levels drawn grey
    }
    d["view_omega"] = {number(b.view_omega.lo), number(b.view_omega.hi)};
    d["y"] = b.y_is_v ? "v" : "x";
    d["view_y"] = {number(b.view_y.lo), number(b.view_y.hi)};
    d["range_error"] = b.range_error;
    d["live_points"] = {{"total", b.live.total}, {"in_view", b.live.in_view}, {"beyond", b.live.beyond},
                        {"above", b.live.above}, {"below", b.live.below}};
    d["lyapunov"] = {{"on", b.lyap_on}, {"running", b.lyap_running}, {"steps", b.lyap_steps},
                     {"done", b.lyap_done}, {"positive", b.lyap_positive}};
    const auto& om = panel.omega_label();
    d["omega_label_rect"] = {om[0], om[1], om[2], om[3]};   // [px] the running omega's label
    const auto& pr = panel.plot_rect();
    d["plot_rect"] = {pr[0], pr[1], pr[2], pr[3]};   // [px] the data area drawn (zeros: not drawn)
    const auto& ir = panel.info_rect();
    d["info_rect"] = ir[2] > ir[0] ? json{ir[0], ir[1], ir[2], ir[3]} : json(nullptr);   // the model, levels, points line
    const auto& lg = analysis.legend_rect();
    d["legend_rect"] = lg[2] > lg[0] ? json{lg[0], lg[1], lg[2], lg[3]} : json(nullptr);   // the branches' legend
    json mk = json::array();
    for (const auto& q : analysis.markers()) mk.push_back({q[0], q[1]});
    d["markers_px"] = std::move(mk);   // the bifurcation points drawn
    return d;
}
}  // namespace

// UI thread, after the last frame.
bool App::write_state_json(const std::string& path) {
    json j;
    j["model"] = model_name();
    j["model_file"] = opt_.model_file.empty() ? json(nullptr) : json(opt_.model_file);   // --model FILE.json
    j["clicker"] = clicker_json(poincare_);
    j["guide"] = {{"open", demos_.show}, {"demo", demos_.last}, {"details", view_.details}, {"basins_open", layout_.panel_visible[static_cast<std::size_t>(PanelId::Basins)]},
                  {"collapsed", demos_.panel.collapsed()},
                  {"controls_tab", layout_.controls_tab < 0 || !layout_.frame.controls_tabbed ? json(nullptr) : json(layout_.controls_tab == 0 ? "Run" : layout_.controls_tab == 1 ? "View" : "State")},
                  {"rect", {demos_.panel.rect()[0], demos_.panel.rect()[1], demos_.panel.rect()[2], demos_.panel.rect()[3]}}};
    j["strip"] = strip_json(strip_);
    // The running model's parameters as the Parameters panel shows them, and whether any was edited.
    json ps = json::object();
    for (const EditableParam& e : editable_params(run_.params)) ps[e.key] = number(e.value);
    j["params"] = std::move(ps);
    j["params_edited"] = params_edited(run_.params);
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
    j["energy"] = number(feed_.last.energy);                          // [J] now
    j["energy_max_trail"] = number(potential_.trail_energy_max());   // [J] over the phase portrait's trail
    j["energy_balance"] = energy_balance_json(sim_->status().energy);
    j["companion"] = companion_json(companion_, run_.stiffness);
    j["grazing"] = grazing_json(feed_);
    j["regime_label"] = contact_label(run_.params, feed_.last.regime, feed_.last.force);   // the rig's and the status bar's
    j["x"] = number(feed_.last.x);
    j["v"] = number(feed_.last.v);
    j["x_max_step"] = x_max_step(feed_.traj, view_.strip_window);
    j["potential_view"] = {potential_.view_y().lo, potential_.view_y().hi};   // [J] the potential plot's y range
    put_poincare(j, shown_map(), feed_.sections, view_.section_phase, ramp_.live.active());
    put_session(j, session_);
    j["data"] = data_panel_.state();          // the measured record in the data window
    j["data"]["open"] = view_.show_data;
    j["plane"] = analysis_.plane.state();     // the plane shown and the doubling continued over it
    j["basins"] = analysis_.basins.state();   // the basins shown: their box, grid and attractors
    j["continuation"] = continuation_json(analysis_);
    j["diagram"] = diagram_json(bif_.panel.state(bifurcation_context()), bif_.panel, analysis_);
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
