#include "bifurcation_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <tuple>
#include <utility>
#include <vector>

#include "render/gl_util.hpp"
#include "sim/sim_engine.hpp"   // kMaxOmega
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

// The section points a live omega ramp passed, over the diagram: the paper's EF protocol growing as it runs.
void draw_ramp_points(Plot& plot, const OmegaRamp& ramp) {
    const auto& pts = ramp.points();
    if (pts.empty()) return;
    // Green, apart from the density image's magma ramp and the live points' cyan.
    const ImU32 col = IM_COL32(110, 235, 120, 255);
    struct Dot { double x, y; };
    plot.scatter(pts.size(), [&](std::size_t i) { return Dot{pts[i].omega, pts[i].x}; }, col, 3.0f);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s ramp: %zu points", ramp.active() ? "live" : "last", pts.size());
    plot.text(plot.x_range().lo, plot.y_range().hi, buf, col, ImVec2(-0.05f, -1.4f));
}

// The swept parameter on the axis: its symbol and its label, in the unit and scale plots show it in (the
// core's sweep_param_axis: xI in mm).
struct OverAxis { const char* symbol; const char* label; double scale; };
OverAxis over_axis(SweepParam s) {
    const double scale = sweep_param_axis(s).scale;
    switch (s) {
        case SweepParam::Omega: return {"ω", "ω [rad/s]", scale};
        case SweepParam::XI: return {"xI", "xI [mm]", scale};
        case SweepParam::M0e: return {"m0e", "m0e [kg m]", scale};
    }
    return {"?", "?", 1.0};
}
const char* over_unit(SweepParam s) { return sweep_param_axis(s).unit; }

// The live section points: a colour the density map does not use, with a dark rim.
constexpr ImU32 kLiveColor = IM_COL32(90, 230, 255, 255);

double wall_s() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void BifurcationPanel::configure(const Options& opt) {
    want_start_ = !opt.bifurcation.empty();
    show_v_ = opt.bif_y == "v";
    nowait_ = opt.bif_nowait;
    if (const auto over = parse_sweep_param(opt.bif_over)) set_over(*over);
    if (opt.bif_range_hi > opt.bif_range_lo) {
        lo_edit_ = opt.bif_range_lo;
        hi_edit_ = opt.bif_range_hi;
    }
    if (opt.bif_box_hi > opt.bif_box_lo) {
        script_box_ = true;
        script_box_x_ = {opt.bif_box_lo, opt.bif_box_hi};
    }
    if (opt.bif_zoom_hi > opt.bif_zoom_lo) {
        zoom_x_ = {opt.bif_zoom_lo, opt.bif_zoom_hi};
        zoom_applied_ = false;
    }
    lyap_on_ = lyap_want_ = opt.bif_lyapunov;
    if (opt.lyap_steps > 0) lyap_steps_ = opt.lyap_steps;
    settle_ = opt.bif_settle;
}

BifRequest BifurcationPanel::request(const BifurcationContext& c, double lo, double hi) const {
    BifRequest req;
    req.params = *c.params;
    req.protocol = static_cast<BifProtocol>(std::clamp(c.protocol ? *c.protocol : 0, 0, 2));
    req.steps = c.steps ? *c.steps : 300;
    req.settle = settle_;
    req.over = over_;
    if (over_ == SweepParam::Omega) {
        req.omega_lo = lo;
        req.omega_hi = hi;
    } else {
        // At the omega the simulation runs: the diagram's vertical line through the running attractor.
        req.lo = lo;
        req.hi = hi;
        req.omega = c.omega;
        req.omega_lo = kept_[0].lo;   // kept for the omega axis the continuation follows
        req.omega_hi = kept_[0].hi;
    }
    return req;
}

void BifurcationPanel::set_over(SweepParam over) {
    if (over == over_) return;
    kept_[static_cast<int>(over_)] = {lo_edit_, hi_edit_};
    over_ = over;
    lo_edit_ = kept_[static_cast<int>(over)].lo;
    hi_edit_ = kept_[static_cast<int>(over)].hi;
    range_error_.clear();
}

std::string BifurcationPanel::start(const BifurcationContext& c) {
    const BifRequest req = request(c, lo_edit_, hi_edit_);
    if (over_ == SweepParam::Omega) {
        range_error_ = check_omega_range(lo_edit_, hi_edit_);
    } else if (req.protocol == BifProtocol::Ef) {
        range_error_ = std::string("the EF ramp is a ramp of ω: choose CF up or down for a diagram over ") + sweep_param_name(over_);
    } else {
        range_error_ = check_sweep(req.params, param_sweep(req));
        if (range_error_.empty() && !(hi_edit_ > lo_edit_)) range_error_ = std::string(sweep_param_name(over_)) + " range is empty";
    }
    if (!range_error_.empty()) return "bifurcation diagram not started: " + range_error_;
    begin(c, req);
    return "";
}

std::string BifurcationPanel::toggle(const BifurcationContext& c) {
    if (job_.running()) {
        job_.cancel();
        return "";
    }
    return start(c);
}

void BifurcationPanel::begin(const BifurcationContext& c, const BifRequest& req) {
    job_.start(req);
    started_ = wall_s();
    // The old diagram goes at once: the new one fills in column by column over its own omega range.
    shown_ = Diagram{};
    shown_.model = c.model;
    shown_.protocol = req.protocol == BifProtocol::Ef ? "ef" : req.protocol == BifProtocol::CfDown ? "cf-down" : "cf-up";
    shown_req_ = req;
    have_ = true;
    levels_done_ = 0;
    shown_.over = req.over;
    const auto [lo, hi] = swept_range(req);
    fit_x_ = {lo, hi};
    fit_y_empty_ = true;   // the y fit keeps its old range until the first points (no jump to nothing)
    dirty_ = true;
    set_over(req.over);
    if (req.protocol != BifProtocol::Ef) lo_edit_ = lo;   // EF: the ramp starts at 0 whatever the input says
    hi_edit_ = hi;
    range_error_.clear();
    if (lyap_on_ && req.over == SweepParam::Omega) start_strip(c);
}

void BifurcationPanel::grow_fit(std::size_t from) {
    double lo = fit_y_empty_ ? 1e300 : fit_y_.lo, hi = fit_y_empty_ ? -1e300 : fit_y_.hi;
    bool grew = false;
    for (std::size_t i = from; i < shown_.points.size(); ++i) {
        const double x = y_of(shown_.points[i]);
        const double pad = 0.06 * std::max(hi - lo, 1e-3);
        if (x < lo) lo = x - pad, grew = true;
        if (x > hi) hi = x + pad, grew = true;
    }
    if (grew) {
        fit_y_ = {lo, hi};
        fit_y_empty_ = false;
    }
}

void BifurcationPanel::set_show_v(bool v) {
    if (v == show_v_) return;
    show_v_ = v;
    dirty_ = true;
    fit_y_empty_ = true;
    snap_fit();
    // The user's zoom was in the other quantity's units: the view goes back to the whole diagram.
    Plot::set_user_view("##bif", fit_x_, fit_y_);
}

void BifurcationPanel::snap_fit() {
    if (shown_.points.empty()) return;
    double lo = 1e300, hi = -1e300;
    for (const auto& p : shown_.points) {
        lo = std::min(lo, y_of(p));
        hi = std::max(hi, y_of(p));
    }
    const double pad = 0.06 * std::max(hi - lo, 1e-3);
    fit_y_ = {lo - pad, hi + pad};
    fit_y_empty_ = false;
}

std::string BifurcationPanel::poll(const BifurcationContext& c) {
    std::string toast;
    // The diagram: what arrived since the last frame, then (once) the whole result.
    const std::size_t before = shown_.points.size(), judged = shown_.levels.size();
    const int levels = job_.take_new(shown_.points, &shown_.levels);
    if (shown_.levels.size() != judged) dirty_ = true;
    if (shown_.points.size() != before) {
        levels_done_ = levels;
        grow_fit(before);
        dirty_ = true;
    }
    if (std::string err = job_.take_error(); !err.empty()) toast = "bifurcation diagram failed: " + err;
    if (auto d = job_.take_result()) {
        // The chunks hold every point the result does, in the same order (the last may have come after the
        // take above: its level count is read again); the result adds the totals.
        std::vector<DiagramPoint> last;
        std::vector<DiagramLevel> last_levels;
        if (const int lv = job_.take_new(last, &last_levels); lv > 0) levels_done_ = lv;
        const std::string model = shown_.model;
        shown_ = std::move(*d);
        shown_.model = model;
        snap_fit();
        dirty_ = true;
        shown_.over = shown_req_.over;
        char buf[160];
        const OverAxis ax = over_axis(shown_req_.over);
        const auto [lo, hi] = swept_range(shown_req_);
        std::snprintf(buf, sizeof buf, "bifurcation diagram %s%s: %zu points over %s %.3g-%.3g %s in %.0f s",
                      shown_.model.c_str(), shown_.cancelled ? " (cancelled, partial)" : " done", shown_.points.size(),
                      ax.symbol, ax.scale * lo, ax.scale * hi, over_unit(shown_req_.over), wall_s() - started_);
        toast = buf;
    }
    // The strip.
    const std::size_t lb = lyap_.size();
    const int ld = lyap_job_.take_new(lyap_);
    if (lyap_.size() != lb) lyap_done_ = ld;
    if (std::string err = lyap_job_.take_error(); !err.empty()) toast = "Lyapunov strip failed: " + err;
    if (auto r = lyap_job_.take_result()) {
        lyap_ = std::move(*r);
        lyap_done_ = static_cast<int>(lyap_.size());
    }
    if (lyap_want_ && (have_ || !want_start_)) {   // --bif-lyapunov: with the first diagram, if one is asked for
        lyap_want_ = false;
        if (!lyap_job_.running() && lyap_.empty() && shown_req_.over == SweepParam::Omega) start_strip(c);
    }
    if (dark_ != palette().dark) {
        dark_ = palette().dark;
        dirty_ = true;
    }
    return toast;
}

bool BifurcationPanel::busy() const {
    const bool diagram = want_start_ && !nowait_ && (job_.running() || !have_ || script_box_);
    const bool strip = lyap_on_ && !nowait_ && (lyap_job_.running() || lyap_want_);
    return diagram || strip;
}

bool BifurcationPanel::stale(const BifurcationContext& c) const {
    if (!have_) return false;
    if (shown_.model != c.model) return true;
    // The parameters held fixed along the sweep: xI over omega or m0e; omega over xI or m0e.
    const SweepParam over = shown_req_.over;
    if (over != SweepParam::XI && std::abs(shown_req_.params.xI - c.xI) > 1e-9) return true;
    return over != SweepParam::Omega && std::abs(shown_req_.omega - c.omega) > 1e-9;
}

BifurcationState BifurcationPanel::state(const BifurcationContext& c) const {
    BifurcationState s;
    s.have = have_;
    s.model = shown_.model;
    s.protocol = shown_.protocol;
    s.over = have_ ? shown_req_.over : over_;
    if (have_) {
        std::tie(s.lo, s.hi) = swept_range(shown_req_);
        if (s.over == SweepParam::Omega) std::tie(s.omega_lo, s.omega_hi) = std::pair{s.lo, s.hi};
        else s.omega = shown_req_.omega;
    }
    std::size_t judged = 0;   // the next verdict: levels come in the points' order
    for (std::size_t i = 0; i < shown_.points.size(); ++i) {   // consecutive points of one value form a CF level
        const DiagramPoint& p = shown_.points[i];
        if (shown_req_.protocol == BifProtocol::Ef) break;
        if (s.level_x.empty() || s.level_x.back().at != p.omega) {
            while (judged < shown_.levels.size() && shown_.levels[judged].first < i) ++judged;
            const bool has = judged < shown_.levels.size() && shown_.levels[judged].first == i;
            s.level_x.push_back({p.omega, p.x, p.x, has ? shown_.levels[judged].period : 0});
        }
        s.level_x.back().x_min = std::min(s.level_x.back().x_min, p.x);
        s.level_x.back().x_max = std::max(s.level_x.back().x_max, p.x);
    }
    s.settle = have_ && shown_req_.protocol != BifProtocol::Ef ? shown_req_.settle : 0;
    s.not_settled = not_settled();
    s.steps = have_ && shown_req_.protocol != BifProtocol::Ef ? shown_req_.steps : 0;
    s.levels_done = have_ && shown_req_.protocol != BifProtocol::Ef ? levels_done_ : 0;
    s.points = shown_.points.size();
    s.running = job_.running();
    s.cancelled = shown_.cancelled;
    s.stale = stale(c);
    s.progress = job_.progress();
    s.view_omega = view_x_;
    s.y_is_v = show_v_;
    s.view_y = view_y_;
    s.range_error = range_error_;
    s.lyap_on = lyap_on_;
    s.lyap_running = lyap_job_.running();
    s.lyap_steps = lyap_req_.steps;
    s.lyap_done = lyap_done_;
    for (const auto& q : lyap_) s.lyap_positive += q.lambda_max > 0;
    s.live = live_;
    return s;
}

void BifurcationPanel::show_bench(Diagram d, Range x, Range y) {
    shown_ = std::move(d);
    shown_req_ = BifRequest{};
    shown_req_.omega_lo = x.lo;
    shown_req_.omega_hi = x.hi;
    shown_req_.steps = 300;
    shown_req_.params.name = shown_.model;
    have_ = true;
    fit_x_ = x;
    fit_y_ = y;
    fit_y_empty_ = false;
    dirty_ = true;
}

void BifurcationPanel::release_gl() {
    if (tex_) {
        const GLuint t = tex_;
        glDeleteTextures(1, &t);
        tex_ = 0;
    }
}

int BifurcationPanel::not_settled() const {
    int n = 0;
    for (const DiagramLevel& l : shown_.levels) n += l.period == kLevelNotSettled;
    return n;
}

void BifurcationPanel::update_texture(int w, int h) {
    if (!have_ || w <= 0 || h <= 0) return;
    if (!dirty_ && w == tex_w_ && h == tex_h_) return;
    dirty_ = false;
    tex_w_ = w;
    tex_h_ = h;
    std::vector<float> count(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
    // Each level of a CF sweep is splatted over its share of the width (the request's span over its
    // steps, in the pixels of the view shown), so the diagram has no gaps between columns. Over omega a level
    // stands for the band below it; over xI or m0e (levels from lo to hi, both included) for the band around it.
    const bool cf = shown_.protocol != "ef", centred = shown_req_.over != SweepParam::Omega;
    const auto [range_lo, range_hi] = swept_range(shown_req_);
    const int bands = centred ? std::max(1, shown_req_.steps - 1) : std::max(1, shown_req_.steps);
    const double col_px = w * (range_hi - range_lo) / bands / view_x_.span();
    const int splat = cf ? std::clamp(static_cast<int>(col_px), 1, 12) : 1;
    const int first = centred ? -(splat / 2) : 0;
    // Points of a level that has not settled (its verdict kLevelNotSettled) are counted apart and drawn grey:
    // a transient or chaos, which a finite run cannot tell apart, never in the colours of a settled orbit.
    std::vector<float> grey(count.size(), 0.0f);
    std::vector<std::uint8_t> unsettled(shown_.points.size(), 0);
    for (const DiagramLevel& l : shown_.levels) {
        if (l.period != kLevelNotSettled) continue;
        for (std::size_t i = l.first; i < l.first + l.count && i < unsettled.size(); ++i) unsettled[i] = 1;
    }
    for (std::size_t pi = 0; pi < shown_.points.size(); ++pi) {
        const DiagramPoint& p = shown_.points[pi];
        std::vector<float>& into = unsettled[pi] ? grey : count;
        const double fx = (p.omega - view_x_.lo) / view_x_.span(), fy = (view_y_.hi - y_of(p)) / view_y_.span();
        if (!(fx > -0.1 && fx < 1.1)) continue;
        const int ix = static_cast<int>(std::floor(fx * w)), iy = static_cast<int>(std::floor(fy * h));
        if (iy < 0 || iy >= h) continue;
        // A CF level stands for the band of omega below it (omega_j - span/steps, omega_j] up to the
        // next: the splat covers the pixels to its left, so the last column ends at omega_hi.
        for (int k = first; k < first + splat; ++k) {
            const int x = cf ? ix - k : ix;
            if (x < 0 || x >= w) continue;
            into[static_cast<std::size_t>(iy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] += 1.0f;
        }
    }
    float mx = 0;
    for (std::size_t i = 0; i < count.size(); ++i) mx = std::max(mx, count[i] + grey[i]);
    max_count_ = mx;
    const float norm = 1.0f / std::log1p(std::max(mx, 1.0f));
    image_.assign(count.size() * 4, 0);
    for (std::size_t i = 0; i < count.size(); ++i) {
        if (count[i] > 0) density_color(palette().dark, std::log1p(count[i]) * norm, &image_[i * 4]);
        else if (grey[i] > 0) not_settled_color(palette().dark, std::log1p(grey[i]) * norm, &image_[i * 4]);
    }
    tex_ = upload_rgba_texture(static_cast<GLuint>(tex_), w, h, image_.data());
}

namespace {
// Keeps a row's items together: the next one goes on a new line when it would not fit.
void same_line_if(float width) {
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
}
}  // namespace

// draw_header() in a short tile: one button unfolds the settings; folded (true), the compute button or the
// progress, the branches' legend and a range error stand beside it.
bool BifurcationPanel::draw_folded(const BifurcationContext& c, std::string& toast) {
    const float fs = ImGui::GetFontSize();
    if (ImGui::SmallButton(settings_open_ ? "settings ^" : "settings v")) settings_open_ = !settings_open_;
    tooltip("The diagram's settings (parameter, protocol, steps, range), folded in a short tile.");
    if (!settings_open_) {
        ImGui::SameLine();
        if (job_.running()) {
            if (ImGui::SmallButton("Cancel")) job_.cancel();
            ImGui::SameLine();
            ImGui::ProgressBar(static_cast<float>(job_.progress()),
                               ImVec2(std::max(fs * 4.0f, ImGui::GetContentRegionAvail().x - fs * 0.5f), ImGui::GetTextLineHeight()));
        } else {
            char label[48];
            std::snprintf(label, sizeof label, "Compute %s", c.model.c_str());
            ImGui::BeginDisabled(!range_error_.empty());
            if (ImGui::SmallButton(label)) toast = start(c);
            ImGui::EndDisabled();
            tooltip("B: runs on a worker thread and fills in column by column; the animation goes on.");
        }
        if (c.overlay_legend && c.branches && !show_v_ && over_ == SweepParam::Omega) {
            ImGui::SameLine();
            c.overlay_legend(true);
        }
        if (!range_error_.empty()) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", range_error_.c_str());
        return true;
    }
    return false;
}

// The swept range: typed (xI in mm), or dragged on the diagram with the right mouse button; the two
// fields and the reset button stay on one line.
void BifurcationPanel::draw_range_fields(const BifurcationContext& c) {
    const float fs = ImGui::GetFontSize();
    const OverAxis oax = over_axis(over_);
    const char* reset = over_ == SweepParam::Omega ? "0-25" : "reset";
    same_line_if(fs * 9.6f + button_width(reset) + fs * 0.2f);
    bool edited = false;
    double lo_shown = oax.scale * lo_edit_, hi_shown = oax.scale * hi_edit_;
    const char* num_fmt = over_ == SweepParam::M0e ? "%.4f" : "%.2f";
    ImGui::SetNextItemWidth(fs * 4.6f);
    edited |= ImGui::InputDouble("##wlo", &lo_shown, 0, 0, num_fmt);
    char tip_lo[200];
    if (over_ == SweepParam::Omega)
        std::snprintf(tip_lo, sizeof tip_lo, "ω min [rad/s] of the next diagram (0 ≤ min < max ≤ 30). Or drag a box on "
                      "the diagram with the right mouse button: that range is computed at once.");
    else
        std::snprintf(tip_lo, sizeof tip_lo, "%s min [%s] of the next diagram. Or drag a box on the diagram with the "
                      "right mouse button: that range is computed at once.", oax.symbol, over_unit(over_));
    tooltip(tip_lo);
    ImGui::SameLine(0, fs * 0.2f);
    ImGui::SetNextItemWidth(fs * 4.6f);
    edited |= ImGui::InputDouble("##whi", &hi_shown, 0, 0, num_fmt);
    char tip_hi[96];
    std::snprintf(tip_hi, sizeof tip_hi, "%s max [%s] of the next diagram%s", oax.symbol, over_unit(over_),
                  over_ == SweepParam::Omega ? " (EF: where the ramp ends)." : ".");
    tooltip(tip_hi);
    if (edited) {
        lo_edit_ = lo_shown / oax.scale;
        hi_edit_ = hi_shown / oax.scale;
        if (over_ == SweepParam::Omega) range_error_ = check_omega_range(lo_edit_, hi_edit_);
        else range_error_ = c.params ? check_sweep(*c.params, param_sweep(request(c, lo_edit_, hi_edit_))) : "";
    }
    ImGui::SameLine(0, fs * 0.2f);
    if (ImGui::SmallButton(reset)) {
        const Range r = BifurcationPanel{}.kept_[static_cast<int>(over_)];   // the panel's defaults
        lo_edit_ = r.lo;
        hi_edit_ = r.hi;
        range_error_.clear();
    }
    tooltip(over_ == SweepParam::Omega ? "The paper's range, ω from 0 to 25 rad/s." : "The default range of this parameter.");
}

// Cancel and the progress while a diagram is computed, else the compute button.
void BifurcationPanel::draw_compute(const BifurcationContext& c, std::string& toast) {
    const float fs = ImGui::GetFontSize();
    if (job_.running()) {
        same_line_if(fs * 10.0f);
        if (ImGui::Button("Cancel")) job_.cancel();
        ImGui::SameLine();
        char over[48];
        if (shown_req_.protocol == BifProtocol::Ef) std::snprintf(over, sizeof over, "%.0f%%", 100.0 * job_.progress());
        else std::snprintf(over, sizeof over, "%d / %d %s", levels_done_, shown_req_.steps, over_axis(shown_req_.over).symbol);
        ImGui::ProgressBar(static_cast<float>(job_.progress()), ImVec2(std::max(fs * 5.0f, ImGui::GetContentRegionAvail().x - fs * 5.5f), 0), over);
    } else {
        char label[48];
        std::snprintf(label, sizeof label, "Compute %s", c.model.c_str());
        same_line_if(ImGui::CalcTextSize(label).x + fs * 1.2f);
        ImGui::BeginDisabled(!range_error_.empty());
        if (ImGui::Button(label)) toast = start(c);
        ImGui::EndDisabled();
        tooltip("B: runs on a worker thread and fills in column by column; the animation goes on.");
    }
}

// The lambda strip's checkbox: lambda_max(omega) belongs under a diagram over omega.
void BifurcationPanel::draw_strip_toggle(const BifurcationContext& c) {
    const bool strip_ok = (have_ ? shown_req_.over : over_) == SweepParam::Omega;
    ImGui::BeginDisabled(!strip_ok);
    if (ImGui::Checkbox("λ strip", &lyap_on_)) {
        if (lyap_on_ && (lyap_.empty() || lyap_model_ != (have_ ? shown_.model : c.model))) start_strip(c);
        if (!lyap_on_) lyap_job_.cancel();
    }
    ImGui::EndDisabled();
    char tip[400];
    std::snprintf(tip, sizeof tip,
                  "The largest Lyapunov exponent λmax(ω) along the same CF sweep, in a strip under the diagram "
                  "(positive: chaos; negative: a periodic orbit, however long). Slow: %d ω of 20 + 40 periods take "
                  "about 2 s with a rigid bumper (G, H) and several minutes with a compliant one (C, C1).%s",
                  lyap_steps_, strip_ok ? "" : " Over ω only: this diagram is over another parameter.");
    if (strip_ok) tooltip(tip);
    else if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", tip);
}

void BifurcationPanel::draw_header(const BifurcationContext& c, std::string& toast) {
    const float fs = ImGui::GetFontSize();
    // A short tile (analysis tiles open, a large UI scale): the settings fold into one button, so the
    // diagram keeps the height (a row of controls wrapped over three lines left it 50 px).
    const bool short_tile = ImGui::GetContentRegionAvail().y < fs * 16.0f;
    if (short_tile) {
        if (draw_folded(c, toast)) return;
        ImGui::SameLine();
    }
    {
        // The swept parameter: omega (the paper's diagram), or xI or m0e at the omega the simulation runs.
        static const char* kOver[] = {"over ω", "over xI", "over m0e"};
        int o = static_cast<int>(over_);
        ImGui::SetNextItemWidth(fs * 6.4f);
        if (ImGui::Combo("##bif_over", &o, kOver, 3)) set_over(static_cast<SweepParam>(o));
        tooltip("The parameter on the diagram's horizontal axis. xI (the bumper) or m0e (the unbalance) are moved "
                "step by step at the ω the simulation runs (set it first); CF sweeps only. The continued branches, "
                "the ramp's points, the λ strip and a click that sets ω belong to diagrams over ω.");
        same_line_if(fs * 6.2f);
    }
    const char* protos[] = {"CF up", "CF down", "EF ramp"};
    ImGui::SetNextItemWidth(fs * 6.2f);
    if (c.protocol) ImGui::Combo("##proto", c.protocol, protos, 3);
    tooltip("CF: constant steps of the swept parameter, 20 transient + 70 recorded periods each, every step "
            "starting where the last ended. EF: the experiment's slow ramp of ω (25 rad/s in 2800 s) from rest up "
            "to ω max (over ω only).");
    const bool ef = c.protocol && *c.protocol == 2;
    same_line_if(fs * 6.0f);
    ImGui::BeginDisabled(ef);
    ImGui::SetNextItemWidth(fs * 6.0f);
    if (c.steps) ImGui::SliderInt("##steps", c.steps, 25, 600, "%d steps");
    tooltip("CF: the number of levels over the range (a box dragged on the diagram keeps it: finer columns).");
    ImGui::EndDisabled();
    draw_range_fields(c);
    draw_compute(c, toast);
    same_line_if(fs * 3.2f);
    {
        // x or v at the sections: the same points (the sweep records both), the y axis refitted.
        static const char* kY[] = {"x", "v"};
        int y = show_v_ ? 1 : 0;
        ImGui::SetNextItemWidth(fs * 3.0f);
        if (ImGui::Combo("##bif_y", &y, kY, 2)) set_show_v(y == 1);
        tooltip("The section points' x or v over the swept parameter (the continued branches and the ramp's "
                "points: over x only).");
    }
    same_line_if(fs * 5.5f);
    draw_strip_toggle(c);
    draw_legend();
    if (c.overlay_legend && c.branches && !show_v_ && over_ == SweepParam::Omega) c.overlay_legend(short_tile);
    if (!range_error_.empty()) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", range_error_.c_str());
}

// The running attractor's section points on the line at cur (the live points): a dot per half radius of
// height, those off the view counted in live_.
void BifurcationPanel::draw_live_points(Plot& plot, const BifurcationContext& c, double cur, bool is_stale) {
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const Range vx = plot.x_range();
    live_ = {};
    if (c.live && !is_stale) {
        const History<MapPoint>& h = *c.live;
        const std::size_t n = std::min<std::size_t>(h.size(), 400), first = h.size() - n;
        const float r = std::max(2.5f, 0.2f * ImGui::GetFontSize());
        // All on one vertical line: a dot per half radius of height is all the eye can tell apart (a chaotic
        // map's 400 points would otherwise cost ~20k vertices a frame, a third of the frame under llvmpipe).
        const float step = 0.5f * r;
        std::vector<std::uint8_t> taken(static_cast<std::size_t>(std::max(1.0f, (b.y - a.y) / step)) + 2, 0);
        std::vector<ImVec2> dots;
        const bool omega_in_view = cur >= vx.lo && cur <= vx.hi;
        live_.total = n;
        for (std::size_t i = first; i < h.size(); ++i) {
            const ImVec2 p = plot.to_px(cur, show_v_ ? h[i].v : h[i].x);
            // A point off the view is counted and said, never drawn at an edge as if it were there.
            if (!omega_in_view) {
                ++live_.beyond;
                continue;
            }
            if (p.y < a.y) ++live_.above;
            if (p.y > b.y) ++live_.below;
            if (p.y < a.y || p.y > b.y) continue;
            ++live_.in_view;
            const auto cell = static_cast<std::size_t>(std::clamp((p.y - a.y) / step + 1.0f, 0.0f,
                                                                  static_cast<float>(taken.size() - 1)));
            if (taken[cell]) continue;
            taken[cell] = 1;
            dots.push_back(p);
        }
        // Each dot over a dark rim, the next one's rim over it (drawn into the plot's image: no triangles).
        for (const ImVec2& p : dots) {
            plot.dots(&p, 1, IM_COL32(0, 0, 0, 200), 2.0f * r + 2.4f);
            plot.dots(&p, 1, kLiveColor, 2.0f * r);
        }
    }
}

// The value where the simulation runs, beside its line: at the top, or where no continued branch's point
// lies under it; then how many live points the view does not hold.
void BifurcationPanel::draw_cursor_label(Plot& plot, const BifurcationContext& c, double cur) {
    const Palette& pal = palette();
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const SweepParam over = have_ ? shown_req_.over : over_;
    const bool over_omega = over == SweepParam::Omega;
    const OverAxis oax = over_axis(over);
    const Range vx = plot.x_range(), vy = plot.y_range();
    char buf[48];
    // Beyond the diagram's range (30 rad/s over 0..25) the line is off the plot: the label says
    // where it is, at the edge it lies beyond, inside the plot.
    const bool beyond_hi = cur > vx.hi, beyond_lo = cur < vx.lo;
    std::snprintf(buf, sizeof buf, "%s%s = %.*f%s%s%s", beyond_lo ? "<< " : "", oax.symbol, over == SweepParam::M0e ? 4 : 2,
                  oax.scale * cur, over_omega ? "" : " ", over_omega ? "" : over_unit(over), beyond_hi ? " >>" : "");
    ImVec2 p = plot.to_px(std::clamp(cur, vx.lo, vx.hi), vy.hi);
    p.x = std::clamp(p.x, a.x, b.x);
    // The label sits right of the line, or left of it near the right edge, so it is never cut off.
    bool left = beyond_hi || (!beyond_lo && p.x + ImGui::CalcTextSize(buf).x + 12 > b.x);
    // At the top of the plot, else the other side of the line, else the plot's foot: the first place
    // where no continued branch's point lies under it.
    if (c.branches && !show_v_ && over_omega) {
        const ImVec2 ts = ImGui::CalcTextSize(buf);
        const auto covers = [&](bool on_left, float y) {
            const float lx = on_left ? p.x - 5 - ts.x : p.x + 5;
            if (lx < a.x || lx + ts.x > b.x) return true;   // cut off: no place
            for (const analysis::BifPoint& q : c.branches->points) {
                const ImVec2 m = plot.to_px(q.param, q.y[0]);
                if (m.x > lx - 9 && m.x < lx + ts.x + 9 && m.y > y - 7 && m.y < y + ts.y + 9) return true;
            }
            return false;
        };
        const float foot = b.y - ts.y - 2.0f * ImGui::GetTextLineHeightWithSpacing() - 6;
        const std::pair<bool, float> places[] = {{left, p.y + 3}, {!left, p.y + 3}, {left, foot}, {!left, foot}};
        for (const auto& [l, y] : places)
            if (!covers(l, y)) {
                left = l;
                p.y = y - 3;
                break;
            }
    }
    plate_text(plot.draw(), ImVec2(left ? p.x - 5 : p.x + 5, p.y + 3), buf, pal.title_text, ImVec2(left ? 1.0f : 0.0f, 0));
    {   // the label's plate (--state-json: no legend may cover it)
        const ImVec2 ts = ImGui::CalcTextSize(buf);
        const float lx = left ? p.x - 5 - ts.x : p.x + 5;
        omega_label_ = {lx - 3, p.y + 2, lx + ts.x + 3, p.y + 4 + ts.y};
    }
    // The running attractor's section points the view does not hold: how many, and on which side.
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const auto note = [&](std::size_t count, const char* where, float y) {
        if (count == 0) return;
        char text[64];
        std::snprintf(text, sizeof text, "%zu live point%s %s", count, count == 1 ? "" : "s", where);
        plate_text(plot.draw(), ImVec2(left ? p.x - 5 : p.x + 5, y), text, kLiveColor, ImVec2(left ? 1.0f : 0.0f, 0));
    };
    note(live_.beyond, beyond_hi ? "to the right" : "to the left", p.y + 3 + line);
    note(live_.above, "above the view", p.y + 3 + line);
    note(live_.below, "below the view", b.y - 2.0f * line - 6);
}

// A diagram of another model, omega or bumper position: says whose it is, in one line or, narrow, two.
void BifurcationPanel::draw_stale_note(Plot& plot, const BifurcationContext& c) {
    const Palette& pal = palette();
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const SweepParam over = have_ ? shown_req_.over : over_;
    char what[120], now[160];
    if (shown_.model != c.model) {
        std::snprintf(what, sizeof what, "%s diagram — model is now %s;", shown_.model.c_str(), c.model.c_str());
    } else if (over != SweepParam::Omega && std::abs(shown_req_.omega - c.omega) > 1e-9) {
        std::snprintf(what, sizeof what, "%s diagram at ω = %.2f rad/s — ω is now %.2f;", shown_.model.c_str(),
                      shown_req_.omega, c.omega);
    } else {
        std::snprintf(what, sizeof what, "%s diagram at xI = %.1f mm — xI is now %.1f mm;", shown_.model.c_str(),
                      1e3 * shown_req_.params.xI, 1e3 * c.xI);
    }
    std::snprintf(now, sizeof now, "%s press B to recompute", what);
    const float room = b.x - a.x - 16;
    const ImVec2 at(0.5f * (a.x + b.x), a.y + ImGui::GetFontSize() * 1.6f);
    if (ImGui::CalcTextSize(now).x <= room) {
        plate_text(plot.draw(), at, now, pal.warn, ImVec2(0.5f, 0));
    } else {
        plate_text(plot.draw(), at, what, pal.warn, ImVec2(0.5f, 0));
        plate_text(plot.draw(), ImVec2(at.x, at.y + ImGui::GetTextLineHeightWithSpacing() + 2), "press B to recompute", pal.warn,
              ImVec2(0.5f, 0));
    }
}

// The mouse: a click sets omega (over omega); a box dragged with the right button computes its range.
void BifurcationPanel::handle_mouse(Plot& plot, const BifurcationContext& c, BifurcationAction& act) {
    const Palette& pal = palette();
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const SweepParam over = have_ ? shown_req_.over : over_;
    const bool over_omega = over == SweepParam::Omega;
    const OverAxis oax = over_axis(over);
    const Range vy = plot.y_range();
    const ImGuiIO& io = ImGui::GetIO();
    const SweepLimits lim = sweep_limits(over);
    const double w_mouse = std::clamp(plot.x_at(std::clamp(io.MousePos.x, a.x, b.x)), lim.lo, lim.hi);
    if (plot.hovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
        box_active_ = true;
        box_w0_ = w_mouse;
    }
    if (box_active_) {
        const float x0 = plot.to_px(box_w0_, 0).x, x1 = plot.to_px(w_mouse, 0).x;
        const ImVec2 r0(std::min(x0, x1), a.y), r1(std::max(x0, x1), b.y);
        plot.draw()->AddRectFilled(r0, r1, IM_COL32(90, 230, 255, 40));
        plot.draw()->AddRect(r0, r1, kLiveColor, 0.0f, 0, 1.5f);
        char buf[96];
        std::snprintf(buf, sizeof buf, "%s %.3f - %.3f: release to compute", oax.symbol, oax.scale * std::min(box_w0_, w_mouse),
                      oax.scale * std::max(box_w0_, w_mouse));
        plate_text(plot.draw(), ImVec2(0.5f * (r0.x + r1.x), a.y + ImGui::GetFontSize() * 3.0f), buf, pal.title_text, ImVec2(0.5f, 0));
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
            box_active_ = false;
            if (std::abs(x1 - x0) >= 5.0f) apply_box(c, box_w0_, w_mouse, vy);
        }
    } else if (plot.hovered()) {
        plot.vline(w_mouse, pal.trace, 1.0f, true);
        if (over_omega) {
            ImGui::SetTooltip("ω = %.3f rad/s: click to set it\nright-drag: compute the ω range of the box\n"
                              "wheel: zoom, drag: pan, double-click: whole diagram",
                              w_mouse);
            if (plot.clicked()) act.omega = w_mouse;
        } else {
            ImGui::SetTooltip("%s = %.*f %s (a click sets nothing: %s is set in the controls)\nright-drag: compute the "
                              "%s range of the box\nwheel: zoom, drag: pan, double-click: whole diagram",
                              oax.symbol, over == SweepParam::M0e ? 5 : 3, oax.scale * w_mouse, over_unit(over), oax.symbol,
                              oax.symbol);
        }
    }
}

BifurcationAction BifurcationPanel::draw(const BifurcationContext& c) {
    BifurcationAction act;
    const Palette& pal = palette();
    draw_header(c, act.toast);

    Plot plot;
    Axes ax;
    const SweepParam over = have_ ? shown_req_.over : over_;
    const bool over_omega = over == SweepParam::Omega;
    const OverAxis oax = over_axis(over);
    ax.x_label = oax.label;
    ax.x_scale = oax.scale;
    ax.y_label = show_v_ ? "v at sections [m/s]" : "x at sections [mm]";
    ax.y_label_short = show_v_ ? "v [m/s]" : "x [mm]";
    ax.y_scale = show_v_ ? 1.0 : 1e3;
    if (!zoom_applied_ && have_ && !job_.running() && !shown_.points.empty()) {
        // --bif-zoom: the omega range asked for, the auto-fit's x at sections.
        zoom_applied_ = true;
        Plot::set_user_view("##bif", zoom_x_, fit_y_);
    }
    if (script_box_ && have_ && !job_.running() && !shown_.points.empty()) {
        // --bif-box: once the first diagram is done, what a right-drag over that omega range does.
        script_box_ = false;
        apply_box(c, script_box_x_.lo, script_box_x_.hi, fit_y_);
    }
    ImVec2 avail = ImGui::GetContentRegionAvail();
    const bool strip = lyap_on_ && over_omega;
    const float strip_h = strip ? std::max(ImGui::GetFontSize() * 6.0f, 0.3f * avail.y) : 0.0f;
    avail.y -= strip_h;
    plot_rect_ = {};
    info_rect_ = {};
    if (!plot.begin("##bif", avail, fit_x_, fit_y_with_branches(c), ax)) return act;
    const ImVec2 outer_min = ImGui::GetItemRectMin(), outer_max = ImGui::GetItemRectMax();   // the plot with its axes
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    plot_rect_ = {a.x, a.y, b.x, b.y};
    const Range vx = plot.x_range(), vy = plot.y_range();
    if (vx.lo != view_x_.lo || vx.hi != view_x_.hi || vy.lo != view_y_.lo || vy.hi != view_y_.hi) {
        view_x_ = vx;
        view_y_ = vy;
        dirty_ = true;
    }
    const bool is_stale = stale(c);
    if (have_) {
        update_texture(static_cast<int>(b.x - a.x), static_cast<int>(b.y - a.y));
        // A diagram of another model (or bumper position) stays, dimmed, until B computes the new one.
        if (tex_) plot.image(image_.data(), tex_w_, tex_h_, static_cast<GLuint>(tex_), is_stale ? 90.0f / 255.0f : 1.0f);
        draw_info(plot, ax.x_label, outer_min, outer_max);
        if (shown_.points.empty() && job_.running())
            plate_text(plot.draw(), ImVec2(0.5f * (a.x + b.x), 0.5f * (a.y + b.y)), "computing the first level...",
                  pal.axis_text, ImVec2(0.5f, 0.5f));
    } else {
        const char* hint = "press B (or Compute) for a diagram";
        if (ImGui::CalcTextSize(hint).x + 8 > b.x - a.x) hint = "press B";
        const ImVec2 ts = ImGui::CalcTextSize(hint);
        plot.draw()->AddText(ImVec2(0.5f * (a.x + b.x - ts.x), 0.5f * (a.y + b.y - ts.y)), pal.axis_text, hint);
    }
    // The bumper's x_I is a position: drawn over x only ("none": no bumper); over xI it is the diagonal x = xI.
    if (!show_v_ && (!c.params || c.params->has_bumper())) {
        if (over != SweepParam::XI) plot.hline(c.xI, pal.bumper, 1.0f, true);
        else plot.draw()->AddLine(plot.to_px(vx.lo, vx.lo), plot.to_px(vx.hi, vx.hi), pal.bumper, 1.0f);
    }
    // Where the simulation runs (omega, xI or m0e): a line, its value, and the Poincare map's settled points on it.
    const double cur = over == SweepParam::Omega ? c.omega : over == SweepParam::XI ? c.xI : c.params ? c.params->m0e : 0.0;
    plot.vline(cur, pal.cursor, 2.0f);
    draw_live_points(plot, c, cur, is_stale);
    draw_cursor_label(plot, c, cur);
    if (is_stale) draw_stale_note(plot, c);
    handle_mouse(plot, c, act);
    // The ramp's points and the continued branches are x at the sections over omega: drawn over the diagram of
    // x over omega only.
    if (c.ramp && !show_v_ && over_omega) draw_ramp_points(plot, *c.ramp);
    if (c.overlay && !show_v_ && over_omega) c.overlay(plot);   // continued branches and bifurcation points
    plot.end();
    if (strip) draw_strip(c, vx, act);
    return act;
}

Range BifurcationPanel::fit_y_with_branches(const BifurcationContext& c) const {
    if (!c.branches || show_v_ || (have_ ? shown_req_.over : over_) != SweepParam::Omega) return fit_y_;
    double lo = 1e300, hi = -1e300;
    for (const BranchCurve& cv : c.branches->curves)
        for (std::size_t i = 0; i < cv.param.size() && i < cv.x.size(); ++i)
            if (cv.param[i] >= fit_x_.lo && cv.param[i] <= fit_x_.hi) {
                lo = std::min(lo, cv.x[i]);
                hi = std::max(hi, cv.x[i]);
            }
    if (!(hi >= lo) || (lo >= fit_y_.lo && hi <= fit_y_.hi)) return fit_y_;
    // Branches beyond the points' fit: the fit grows to hold them, padded as the points' fit is.
    const double pad = 0.06 * std::max(std::max(hi, fit_y_.hi) - std::min(lo, fit_y_.lo), 1e-3);
    return {std::min(fit_y_.lo, lo - pad), std::max(fit_y_.hi, hi + pad)};
}

void BifurcationPanel::draw_info(Plot& plot, const char* x_label, ImVec2 outer_min, ImVec2 outer_max) {
    // Below the data, in the x label's row, left of the centred label (or right of it): never over a point.
    // Where neither side has room for even "A1H 10/300", it is left out (the header's progress says it).
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const float fs = ImGui::GetFontSize();
    const float label_w = ImGui::CalcTextSize(x_label).x, mid = 0.5f * (a.x + b.x);
    const float left_room = mid - 0.5f * label_w - fs - (outer_min.x + fs * 0.3f);
    const float right_room = outer_max.x - fs * 0.3f - (mid + 0.5f * label_w + fs);
    const float width = std::max(left_room, right_room);
    info_rect_ = {};
    char info[160];
    const char* cut = shown_.cancelled ? " (cancelled)" : "";
    const OverAxis ax = over_axis(shown_req_.over);
    const auto [lo, hi] = swept_range(shown_req_);
    if (shown_req_.protocol == BifProtocol::Ef)
        std::snprintf(info, sizeof info, "%s  EF ramp to %.3g rad/s%s  %zu points", shown_.model.c_str(), shown_req_.omega_hi,
                      cut, shown_.points.size());
    else if (shown_req_.over == SweepParam::Omega)
        std::snprintf(info, sizeof info, "%s  %s  ω %.3g-%.3g: %d/%d levels%s  %zu points", shown_.model.c_str(),
                      shown_.protocol.c_str(), lo, hi, levels_done_, shown_req_.steps, cut, shown_.points.size());
    else
        std::snprintf(info, sizeof info, "%s  %s  %s %.3g-%.3g %s at ω = %.3g rad/s: %d/%d levels%s  %zu points",
                      shown_.model.c_str(), shown_.protocol.c_str(), ax.symbol, ax.scale * lo, ax.scale * hi,
                      over_unit(shown_req_.over), shown_req_.omega, levels_done_, shown_req_.steps, cut, shown_.points.size());
    if (ImGui::CalcTextSize(info).x > width)   // a narrow tile: the levels and the model only
        std::snprintf(info, sizeof info, "%s  %d/%d%s", shown_.model.c_str(), levels_done_, shown_req_.steps, cut);
    const ImVec2 ts = ImGui::CalcTextSize(info);
    if (ts.x > width) return;
    const bool left = ts.x <= left_room;
    const ImVec2 at(left ? outer_min.x + fs * 0.3f : outer_max.x - fs * 0.3f - ts.x, plot.label_row_y());
    ImDrawList* dl = plot.draw();
    dl->PushClipRect(outer_min, outer_max, false);   // outside the data area's clip
    dl->AddText(at, palette().axis_text, info);
    dl->PopClipRect();
    info_rect_ = {at.x, at.y, at.x + ts.x, at.y + ts.y};
}

void BifurcationPanel::apply_box(const BifurcationContext& c, double w0, double w1, Range view_y) {
    auto req = box_request(request(c, lo_edit_, hi_edit_), w0, w1);
    if (!req) return;
    begin(c, *req);
    // The view follows the new range (a double-click gives it back to the auto-fit: the same range).
    const auto [lo, hi] = swept_range(*req);
    Plot::set_user_view("##bif", {lo, hi}, view_y);
}

}  // namespace impactlab::gui
