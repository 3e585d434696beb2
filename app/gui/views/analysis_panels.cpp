#include "analysis_panels.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_util.hpp"
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

// ---- colours ---------------------------------------------------------------------------------------------

// Branches by period: 1, 2, 4, 8 (others cycle).
ImU32 branch_color(int period) {
    switch (period) {
        case 1: return IM_COL32(255, 160, 40, 255);
        case 2: return IM_COL32(80, 200, 255, 255);
        case 4: return IM_COL32(210, 120, 255, 255);
        default: return IM_COL32(120, 235, 120, 255);
    }
}
ImU32 bif_color(analysis::BifKind k) {
    switch (k) {
        case analysis::BifKind::Fold: return IM_COL32(255, 230, 60, 255);
        case analysis::BifKind::PeriodDoubling: return IM_COL32(255, 70, 200, 255);
        case analysis::BifKind::NeimarkSacker: return IM_COL32(60, 240, 240, 255);
        case analysis::BifKind::Grazing: return IM_COL32(255, 255, 255, 255);
    }
    return IM_COL32_WHITE;
}
const char* bif_label(analysis::BifKind k) {
    switch (k) {
        case analysis::BifKind::Fold: return "fold";
        case analysis::BifKind::PeriodDoubling: return "period doubling";
        case analysis::BifKind::NeimarkSacker: return "Neimark-Sacker";
        case analysis::BifKind::Grazing: return "grazing";
    }
    return "?";
}

// The symbol of a bifurcation point: square (fold), triangle (period doubling), diamond (Neimark-Sacker),
// ring (grazing); r is its half size in pixels.
void bif_marker(ImDrawList* dl, ImVec2 p, analysis::BifKind k, float r) {
    const ImU32 c = bif_color(k), edge = IM_COL32(0, 0, 0, 200);
    switch (k) {
        case analysis::BifKind::Fold:
            dl->AddRectFilled(ImVec2(p.x - r, p.y - r), ImVec2(p.x + r, p.y + r), c);
            dl->AddRect(ImVec2(p.x - r, p.y - r), ImVec2(p.x + r, p.y + r), edge);
            break;
        case analysis::BifKind::PeriodDoubling:
            dl->AddTriangleFilled(ImVec2(p.x, p.y - 1.2f * r), ImVec2(p.x - r, p.y + 0.8f * r), ImVec2(p.x + r, p.y + 0.8f * r), c);
            dl->AddTriangle(ImVec2(p.x, p.y - 1.2f * r), ImVec2(p.x - r, p.y + 0.8f * r), ImVec2(p.x + r, p.y + 0.8f * r), edge);
            break;
        case analysis::BifKind::NeimarkSacker:
            dl->AddQuadFilled(ImVec2(p.x, p.y - r * 1.3f), ImVec2(p.x + r, p.y), ImVec2(p.x, p.y + r * 1.3f), ImVec2(p.x - r, p.y), c);
            break;
        case analysis::BifKind::Grazing:
            dl->AddCircle(p, r, edge, 12, 3.5f);
            dl->AddCircle(p, r, c, 12, 2.0f);
            break;
    }
}

// A polyline, dashed where `dashed` is set for the segment's start point; the dash phase runs on along the
// curve so short segments still show gaps.
void draw_branch(ImDrawList* dl, const std::vector<ImVec2>& pts, const std::vector<char>& dashed, ImU32 c, float w) {
    const float on = 6.0f, period = 10.0f;
    float phase = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const ImVec2 a = pts[i], b = pts[i + 1];
        const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
        if (!dashed[i]) {
            dl->AddLine(a, b, c, w);
            phase = 0;
            continue;
        }
        if (len > 4000.0f) continue;   // an unstable branch leaving the view: nothing to dash off-screen
        float s = 0;
        while (s < len) {
            const float in = std::fmod(phase + s, period);
            const float step = std::min(in < on ? on - in : period - in, len - s);
            if (in < on) {
                const float t0 = s / len, t1 = (s + step) / len;
                dl->AddLine(ImVec2(a.x + dx * t0, a.y + dy * t0), ImVec2(a.x + dx * t1, a.y + dy * t1), c, w * 0.8f);
            }
            s += step + 1e-4f;
        }
        phase = std::fmod(phase + len, period);
    }
}

bool key(int k) { return ImGui::IsKeyPressed(k, false); }

}  // namespace

// ---- set-up and jobs -------------------------------------------------------------------------------------

void AnalysisPanels::configure(const Options& opt) {
    want_cont_ = opt.continuation;
    want_here_ = opt.continue_here;
    basins.configure(opt);
    if (const std::string err = plane.configure(opt); !err.empty() && startup_error_.empty()) startup_error_ = err;
}

void AnalysisPanels::start_continuation(const AnalysisContext& c) {
    const Params p = *c.params;
    const double lo = c.diagram_omega.lo, hi = c.diagram_omega.hi;
    cont_job_.start([p, lo, hi](Progress& prog) { return compute_continuation(p, lo, hi, prog); });
}

std::string AnalysisPanels::start_continuation_here(const AnalysisContext& c) {
    if (!c.orbit)
        return c.chaotic ? "continuation: the running attractor is chaotic: no periodic orbit to continue"
                         : "continuation: the Poincare map has not settled on a periodic orbit yet";
    const Params p = *c.params;
    const double lo = c.diagram_omega.lo, hi = c.diagram_omega.hi, w = c.omega;
    const AnalysisContext::Orbit o = *c.orbit;
    cont_job_.start([=](Progress& prog) { return compute_continuation_from(p, lo, hi, w, o.x, o.v, o.period, prog); });
    return "";
}

bool AnalysisPanels::busy() const { return want_cont_ || want_here_ || cont_job_.running() || plane.busy() || basins.busy(); }

void AnalysisPanels::release_gl() {
    plane.release_gl();
    basins.release_gl();
}

// ---- menu, keys ------------------------------------------------------------------------------------------

AnalysisAction AnalysisPanels::menu(const AnalysisContext& c) {
    AnalysisAction act;
    if (!ImGui::BeginMenu("Analysis")) return act;
    if (cont_job_.running()) {
        if (ImGui::MenuItem("Cancel the continuation", "O")) cont_job_.cancel();
    } else {
        if (ImGui::MenuItem("Continue the period-1 branch (over the diagram)", "O")) start_continuation(c);
        char label[96];
        if (c.orbit) std::snprintf(label, sizeof label, "Continue from the running orbit (period %d at ω = %.2f)", c.orbit->period, c.omega);
        else std::snprintf(label, sizeof label, "Continue from the running orbit (once the map settles)");
        if (ImGui::MenuItem(label, "Shift+O", false, c.orbit.has_value())) act.toast = start_continuation_here(c);
    }
    if (overlay_ && ImGui::MenuItem("Hide the continued branches")) overlay_.reset();
    ImGui::Separator();
    if (ImGui::MenuItem("Parameter plane", "F2", c.plane_open)) act.toggle_plane = true;
    if (ImGui::MenuItem("Basins of attraction", "F3", c.basins_open)) act.toggle_basins = true;
    ImGui::EndMenu();
    return act;
}

AnalysisAction AnalysisPanels::poll(const AnalysisContext& c) {
    AnalysisAction act;
    // Asked for on the command line: begun at the first frame, when the context exists.
    if (std::exchange(want_cont_, false)) start_continuation(c);
    // A map on its way to a periodic orbit may call its transient chaos first: chaos is the answer once it
    // has lasted 60 s of simulated time (about a hundred forcing periods); 20000 frames at most in all.
    if (!c.chaotic) here_chaos_since_ = -1;
    else if (here_chaos_since_ < 0) here_chaos_since_ = c.sim_time;
    const bool chaos_lasts = here_chaos_since_ >= 0 && c.sim_time - here_chaos_since_ > 60.0;
    if (want_here_ && (c.orbit || chaos_lasts || ++here_wait_ > 20000)) {
        want_here_ = false;
        if (std::string err = start_continuation_here(c); !err.empty()) {
            act.toast = err;
            if (startup_error_.empty()) startup_error_ = "--continue-here: " + err;
        }
    }
    if (const std::string err = cont_job_.take_error(); !err.empty()) {
        act.toast = "continuation failed: " + err;
        if (startup_error_.empty()) startup_error_ = act.toast;
    }
    if (auto r = cont_job_.take_result()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "continuation %s: %zu curves, %zu bifurcation points in %.1f s%s", r->model.c_str(),
                      r->curves.size(), r->points.size(), r->seconds, r->cancelled ? " (cancelled, partial)" : "");
        act.toast = buf;
        overlay_ = std::move(*r);
    }
    act.merge(plane.poll(c, startup_error_));
    act.merge(basins.poll(c, startup_error_));
    live_model_ = c.model;
    live_xI_ = c.xI;
    // Ctrl+O is Load session: a chord is not also its letter.
    if (!ImGui::GetIO().WantTextInput && !ImGui::GetIO().KeyCtrl) {
        if (key(GLFW_KEY_O)) {
            if (cont_job_.running()) cont_job_.cancel();
            else if (ImGui::GetIO().KeyShift) act.toast = start_continuation_here(c);
            else start_continuation(c);
        }
        if (key(GLFW_KEY_F2)) act.toggle_plane = true;
        if (key(GLFW_KEY_F3)) act.toggle_basins = true;
    }
    return act;
}

void AnalysisPanels::overlay_diagram(Plot& plot) const {
    ImDrawList* dl = plot.draw();
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    const float s = ImGui::GetFontSize() / 14.5f;
    if (cont_job_.running()) {
        char buf[80];
        std::snprintf(buf, sizeof buf, "continuing the branches... %.0f%%  (O cancels)", 100.0 * cont_job_.progress());
        plate_text(dl, ImVec2(a.x + 6, a.y + 6), buf, palette().axis_text);
    }
    if (!overlay_) return;
    if (overlay_->model != live_model_ || std::abs(overlay_->xI - live_xI_) > 1e-12) {
        // Computed for another model or bumper: still shown (to compare), and said so.
        char buf[96];
        std::snprintf(buf, sizeof buf, "branches of %s at xI = %.1f mm (O recomputes)", overlay_->model.c_str(), 1e3 * overlay_->xI);
        plate_text(dl, ImVec2(a.x + 6, a.y + 6 + (cont_job_.running() ? ImGui::GetTextLineHeight() + 4 : 0.0f)), buf, palette().warn);
    }
    std::vector<ImVec2> pts;
    std::vector<char> dashed;
    for (const BranchCurve& cv : overlay_->curves) {
        pts.clear();
        dashed.clear();
        for (std::size_t i = 0; i < cv.param.size(); ++i) {
            pts.push_back(plot.to_px(cv.param[i], cv.x[i]));
            // A segment is dashed unless both ends are stable (the change of stability sits between them).
            dashed.push_back(!(cv.stable[i] && (i + 1 >= cv.param.size() || cv.stable[i + 1])));
        }
        draw_branch(dl, pts, dashed, branch_color(cv.period), 2.0f * s);
    }
    // The bifurcation points, and the one nearest the mouse named.
    const ImVec2 m = ImGui::GetIO().MousePos;
    const analysis::BifPoint* near = nullptr;
    float best = 8.0f * s * 8.0f * s;
    markers_.clear();
    for (const analysis::BifPoint& q : overlay_->points) {
        const ImVec2 p = plot.to_px(q.param, q.y[0]);
        if (p.x >= a.x && p.x <= b.x && p.y >= a.y && p.y <= b.y) markers_.push_back({p.x, p.y});
        bif_marker(dl, p, q.kind, 5.0f * s);
        const float d2 = (p.x - m.x) * (p.x - m.x) + (p.y - m.y) * (p.y - m.y);
        if (plot.hovered() && d2 < best) {
            best = d2;
            near = &q;
        }
    }
    if (near)
        ImGui::SetTooltip("%s at ω = %.7g rad/s (± %.0e)\nperiod %d, x = %.3f mm, v = %.1f mm/s",
                          bif_label(near->kind), near->param, near->precision, near->period, 1e3 * near->y[0], 1e3 * near->y[1]);
}

void AnalysisPanels::overlay_legend(bool compact) const {
    // A row above the diagram, outside its plot (it never covers a branch, a point or a label): the line
    // styles in a neutral colour (the colour is the period), a colour per period shown, the symbols found.
    // Compact (a short tile): one word, "key", that shows the row when hovered.
    legend_ = {};
    if (!overlay_) return;
    if (compact) {
        ImGui::TextDisabled("key");
        const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
        if (ImGui::IsItemHovered()) {
            ImGui::BeginTooltip();
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 22.0f);
            overlay_legend(false);
            ImGui::PopTextWrapPos();
            ImGui::EndTooltip();
        }
        legend_ = {a.x, a.y, b.x, b.y};
        return;
    }
    const float s = ImGui::GetFontSize() / 14.5f, lh = ImGui::GetTextLineHeight();
    const ImU32 neutral = palette().axis_text;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    bool first = true;
    // One entry: its sample drawn in a box of 22 s pixels, then its text, wrapped as a unit.
    const auto entry = [&](const char* text, const auto& sample) {
        const float w = 24 * s + ImGui::CalcTextSize(text).x;
        if (!first) same_line_or_wrap(w);
        first = false;
        const ImVec2 p = ImGui::GetCursorScreenPos();
        sample(dl, ImVec2(p.x + 1, p.y + 0.5f * lh), ImVec2(p.x + 20 * s, p.y + 0.5f * lh));
        dl->AddText(ImVec2(p.x + 24 * s, p.y), neutral, text);
        ImGui::Dummy(ImVec2(w, lh));
        x0 = std::min(x0, p.x);
        y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x + w);
        y1 = std::max(y1, p.y + lh);
    };
    entry("stable", [&](ImDrawList* d, ImVec2 a, ImVec2 b) { d->AddLine(a, b, neutral, 2.0f * s); });
    entry("unstable", [&](ImDrawList* d, ImVec2 a, ImVec2 b) { draw_branch(d, {a, b}, {1}, neutral, 2.0f * s); });
    // The periods as one entry: "period" and each period shown, in its colour.
    std::vector<int> periods;
    for (int k = 1; k <= 64; k *= 2)
        for (const BranchCurve& cv : overlay_->curves)
            if (cv.period == k) {
                periods.push_back(k);
                break;
            }
    if (!periods.empty()) {
        std::string all = "period";
        for (const int k : periods) {
            all += ' ';
            all += std::to_string(k);
        }
        const float w = ImGui::CalcTextSize(all.c_str()).x;
        same_line_or_wrap(w);
        const ImVec2 p = ImGui::GetCursorScreenPos();
        dl->AddText(p, neutral, "period");
        float x = p.x + ImGui::CalcTextSize("period").x;
        for (const int k : periods) {
            std::string t(1, ' ');
            t += std::to_string(k);
            dl->AddText(ImVec2(x, p.y), branch_color(k), t.c_str());
            x += ImGui::CalcTextSize(t.c_str()).x;
        }
        ImGui::Dummy(ImVec2(w, lh));
        x1 = std::max(x1, p.x + w);
        y1 = std::max(y1, p.y + lh);
    }
    static const char* kKinds[] = {"fold", "doubling", "Neimark-Sacker", "grazing"};
    for (int kind = 0; kind < 4; ++kind)
        for (const analysis::BifPoint& q : overlay_->points)
            if (static_cast<int>(q.kind) == kind) {
                entry(kKinds[kind], [&](ImDrawList* d, ImVec2 a, ImVec2 b) {
                    bif_marker(d, ImVec2(0.5f * (a.x + b.x), a.y), static_cast<analysis::BifKind>(kind), 4.5f * s);
                });
                break;
            }
    legend_ = {x0, y0, x1, y1};
}

}  // namespace impactlab::gui
