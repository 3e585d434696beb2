#include "views/analysis_panels.hpp"

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

#include "gl_util.hpp"
#include "theme.hpp"
#include "widgets.hpp"

namespace impactlab::gui {

namespace {

// ---- colours ---------------------------------------------------------------------------------------------

struct Rgb {
    unsigned char r, g, b;
};
ImU32 col(Rgb c, float a = 1.0f) { return IM_COL32(c.r, c.g, c.b, static_cast<int>(255 * a)); }

// Period classes of a plane (the scan's `period`: 1..16 section values, 0 for more: chaos or a long period).
Rgb period_rgb(int k) {
    switch (k) {
        case 1: return {66, 120, 205};
        case 2: return {72, 178, 92};
        case 3: return {222, 196, 62};
        case 4: return {238, 136, 44};
        case 5: return {150, 96, 210};
        case 6: return {64, 196, 196};
        case 7:
        case 8: return {226, 100, 168};
        case 0: return {196, 36, 36};
        default: return {150, 150, 150};   // 9..16
    }
}
const char* period_name(int k) {
    static char buf[24];
    if (k == 0) return "chaos / > 16";
    if (k >= 9) return "period 9-16";
    if (k == 7 || k == 8) return "period 7-8";
    std::snprintf(buf, sizeof buf, "period %d", k);
    return buf;
}
int period_class(int k) { return k >= 9 ? 9 : k == 8 ? 7 : k; }

// A continuous measure (impacts, lyapunov, x range): dark blue to yellow, t in [0, 1].
Rgb ramp_rgb(double t) {
    static const Rgb stops[] = {{48, 18, 92}, {40, 96, 160}, {32, 160, 140}, {120, 200, 80}, {250, 230, 40}};
    t = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(static_cast<int>(t), 3);
    const double f = t - i;
    auto mix = [f](unsigned char a, unsigned char b) { return static_cast<unsigned char>(a + (b - a) * f); };
    return {mix(stops[i].r, stops[i + 1].r), mix(stops[i].g, stops[i + 1].g), mix(stops[i].b, stops[i + 1].b)};
}

// Attractors of a basin map: the label's colour.
Rgb label_rgb(int id) {
    static const Rgb c[] = {{66, 120, 205}, {238, 136, 44}, {72, 178, 92}, {196, 56, 56}, {150, 96, 210},
                            {64, 196, 196}, {222, 196, 62}, {226, 100, 168}, {130, 90, 60}, {160, 160, 160}};
    return c[static_cast<std::size_t>(id) % (sizeof c / sizeof c[0])];
}

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

// A legend swatch and its text on one line.
void swatch(Rgb c, const char* text) {
    const float h = ImGui::GetTextLineHeight();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + h, p.y + h - 1), col(c));
    ImGui::Dummy(ImVec2(h, h));
    ImGui::SameLine();
    ImGui::TextUnformatted(text);
}

double axis_scale(const std::string& name) { return name == "xI" ? 1e3 : 1.0; }
const char* axis_label(const std::string& name) {
    if (name == "omega") return "omega [rad/s]";
    if (name == "xI") return "xI [mm]";
    return "m0e [kg m]";
}

bool key(int k) { return ImGui::IsKeyPressed(k, false); }

}  // namespace

// ---- set-up and jobs -------------------------------------------------------------------------------------

void AnalysisPanels::configure(const Options& opt) {
    want_cont_ = opt.continuation;
    want_basins_ = opt.basins;
    want_plane_ = opt.small_plane;
    show_basins_ = opt.basins;
    show_plane_ = opt.small_plane || !opt.plane.empty();
    if (!opt.plane.empty()) {
        const std::string err = load_plane(opt.plane);
        if (!err.empty() && startup_error_.empty()) startup_error_ = err;
    }
}

std::string AnalysisPanels::load_plane(const std::string& path) {
    std::snprintf(plane_path_, sizeof plane_path_, "%s", path.c_str());
    try {
        plane_ = load_plane_csv(path);
        plane_error_.clear();
        plane_dirty_ = true;
        plane_measure_ = std::max(plane_->measure_index("period"), 0);
    } catch (const PlaneError& e) {
        plane_error_ = e.what();
    }
    return plane_error_;
}

void AnalysisPanels::start_continuation(const AnalysisContext& c) {
    const Params p = *c.params;
    const double lo = c.diagram_omega.lo, hi = c.diagram_omega.hi;
    cont_job_.start([p, lo, hi](Progress& prog) { return compute_continuation(p, lo, hi, prog); });
}

void AnalysisPanels::start_plane(const AnalysisContext& c) {
    const Params p = *c.params;
    PlaneRequest req = plane_req_;
    req.omega_lo = std::max(c.diagram_omega.lo, 0.1);
    req.omega_hi = std::max(c.diagram_omega.hi, req.omega_lo + 1.0);
    const std::string model = c.model;
    plane_job_.start([p, req, model](Progress& prog) { return compute_plane(p, model, req, prog); });
    show_plane_ = true;
}

void AnalysisPanels::start_basins(const AnalysisContext& c) {
    const Params p = *c.params;
    const analysis::BasinSpec spec = basin_request(p, c.omega, basin_grid_, 2);
    basin_job_.start([p, spec](Progress& prog) { return analysis::compute_basins(p, spec, &prog); });
    basins_model_ = c.model;
    show_basins_ = true;
}

bool AnalysisPanels::busy() const {
    return want_cont_ || want_plane_ || want_basins_ || cont_job_.running() || plane_job_.running() || basin_job_.running();
}

void AnalysisPanels::release_gl() {
    for (unsigned* t : {&plane_tex_, &basin_tex_}) {
        if (*t) {
            const GLuint id = *t;
            glDeleteTextures(1, &id);
            *t = 0;
        }
    }
}

void AnalysisPanels::poll(AnalysisAction& act) {
    auto report = [&](const std::string& what, const std::string& err) {
        if (err.empty()) return;
        act.toast = what + " failed: " + err;
        if (startup_error_.empty()) startup_error_ = act.toast;
    };
    report("continuation", cont_job_.take_error());
    report("plane", plane_job_.take_error());
    report("basins", basin_job_.take_error());
    if (auto r = cont_job_.take_result()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "continuation %s: %zu curves, %zu bifurcation points in %.1f s%s", r->model.c_str(),
                      r->curves.size(), r->points.size(), r->seconds, r->cancelled ? " (cancelled, partial)" : "");
        act.toast = buf;
        overlay_ = std::move(*r);
    }
    if (auto r = plane_job_.take_result()) {
        plane_ = std::move(*r);
        plane_error_.clear();
        plane_dirty_ = true;
        plane_measure_ = std::max(plane_->measure_index("period"), 0);
        act.toast = "plane " + plane_->source + ": " + std::to_string(plane_->nx()) + " x " + std::to_string(plane_->ny());
    }
    if (auto r = basin_job_.take_result()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "basins at omega = %.3f: %zu attractors in %.1f s%s", r->spec.omega, r->attractors.size(),
                      r->seconds, r->cancelled ? " (cancelled, partial)" : "");
        act.toast = buf;
        basins_ = std::move(*r);
        basin_dirty_ = true;
    }
}

// ---- menu, keys, windows ---------------------------------------------------------------------------------

void AnalysisPanels::menu(const AnalysisContext& c) {
    if (!ImGui::BeginMenu("Analysis")) return;
    if (cont_job_.running()) {
        if (ImGui::MenuItem("Cancel the continuation", "O")) cont_job_.cancel();
    } else if (ImGui::MenuItem("Continue the period-1 branch (over the diagram)", "O")) {
        start_continuation(c);
    }
    if (overlay_ && ImGui::MenuItem("Hide the continued branches")) overlay_.reset();
    ImGui::Separator();
    if (ImGui::MenuItem("Parameter plane...", "F2", show_plane_)) show_plane_ = !show_plane_;
    if (ImGui::MenuItem("Basins of attraction...", "F3", show_basins_)) show_basins_ = !show_basins_;
    ImGui::EndMenu();
}

AnalysisAction AnalysisPanels::draw(const AnalysisContext& c) {
    AnalysisAction act;
    // Asked for on the command line: begun at the first frame, when the context exists.
    if (std::exchange(want_cont_, false)) start_continuation(c);
    if (std::exchange(want_plane_, false)) start_plane(c);
    if (std::exchange(want_basins_, false)) start_basins(c);
    poll(act);
    live_model_ = c.model;
    live_xI_ = c.xI;
    // Ctrl+O is Load session: a chord is not also its letter.
    if (!ImGui::GetIO().WantTextInput && !ImGui::GetIO().KeyCtrl) {
        if (key(GLFW_KEY_O)) {
            if (cont_job_.running()) cont_job_.cancel();
            else start_continuation(c);
        }
        if (key(GLFW_KEY_F2)) show_plane_ = !show_plane_;
        if (key(GLFW_KEY_F3)) show_basins_ = !show_basins_;
    }
    if (show_plane_) draw_plane_window(c, act);
    if (show_basins_) draw_basins_window(c, act);
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
    for (const analysis::BifPoint& q : overlay_->points) {
        const ImVec2 p = plot.to_px(q.param, q.y[0]);
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
    // Legend (top right): the line styles (in a neutral colour: the colour is the period), a colour per
    // period shown, and the symbols of the kinds found.
    struct Row {
        std::string text;
        int style;   // 0 solid, 1 dashed, 2 a period's colour, 3 a marker
        int arg;     // the period, or the kind
    };
    std::vector<Row> rows{{"stable", 0, 0}, {"unstable", 1, 0}};
    for (int k = 1; k <= 64; k *= 2)
        for (const BranchCurve& cv : overlay_->curves)
            if (cv.period == k) {
                rows.push_back({"period " + std::to_string(k), 2, k});
                break;
            }
    static const char* kKinds[] = {"fold", "period doubling", "Neimark-Sacker", "grazing"};
    for (int kind = 0; kind < 4; ++kind)
        for (const analysis::BifPoint& q : overlay_->points)
            if (static_cast<int>(q.kind) == kind) {
                rows.push_back({kKinds[kind], 3, kind});
                break;
            }
    const float lh = ImGui::GetTextLineHeight();
    float w = 0;
    for (const Row& r : rows) w = std::max(w, ImGui::CalcTextSize(r.text.c_str()).x);
    const float x0 = b.x - w - 34 * s - 6, y0 = a.y + 6;
    const ImU32 bg = palette().dark ? IM_COL32(10, 12, 16, 190) : IM_COL32(255, 255, 255, 200);
    dl->AddRectFilled(ImVec2(x0 - 4, y0 - 2), ImVec2(b.x - 4, y0 + static_cast<float>(rows.size()) * lh + 2), bg, 3.0f);
    float y = y0 + 0.5f * lh;
    const ImU32 neutral = palette().axis_text;
    for (const Row& r : rows) {
        const ImVec2 l0(x0 + 2, y), l1(x0 + 24 * s, y);
        if (r.style == 0) dl->AddLine(l0, l1, neutral, 2.0f * s);
        else if (r.style == 1) draw_branch(dl, {l0, l1}, {1}, neutral, 2.0f * s);
        else if (r.style == 2) dl->AddLine(l0, l1, branch_color(r.arg), 3.0f * s);
        else bif_marker(dl, ImVec2(x0 + 13 * s, y), static_cast<analysis::BifKind>(r.arg), 4.5f * s);
        dl->AddText(ImVec2(x0 + 30 * s, y - 0.5f * lh), neutral, r.text.c_str());
        y += lh;
    }
}

void AnalysisPanels::draw_plane_window(const AnalysisContext& c, AnalysisAction& act) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    // First placed in the lower left, clear of the window's centre (where a headless pointer rests).
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.02f, vp->Pos.y + vp->Size.y * 0.53f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(std::min(560 * c.ui_scale, vp->Size.x * 0.45f), std::min(440 * c.ui_scale, vp->Size.y * 0.45f)),
                             ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Parameter plane", &show_plane_)) {
        ImGui::End();
        return;
    }
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 16);
    const bool enter = ImGui::InputTextWithHint("##planepath", "plane.csv (impactlab scan --out)", plane_path_, sizeof plane_path_,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if (ImGui::Button("Load") || enter) {
        const std::string err = load_plane(plane_path_);
        act.toast = err.empty() ? std::string("plane loaded: ") + plane_path_ : err;
    }
    ImGui::SameLine();
    if (plane_job_.running()) {
        if (ImGui::Button("Cancel")) plane_job_.cancel();
        ImGui::SameLine();
        ImGui::ProgressBar(static_cast<float>(plane_job_.progress()), ImVec2(-1, 0));
    } else {
        char label[48];
        std::snprintf(label, sizeof label, "Compute %dx%d", plane_req_.nx, plane_req_.ny);
        if (ImGui::Button(label)) start_plane(c);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("(ω over the diagram's range) x (x_I from -10 to 10 mm) for %s on a worker:\n"
                              "each row a CF sweep along ω, as impactlab scan", c.model.c_str());
    }
    if (!plane_error_.empty()) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", plane_error_.c_str());
    if (!plane_) {
        ImGui::TextDisabled("No plane: load a scan CSV (impactlab scan ... --out plane.csv) or compute one.");
        ImGui::End();
        return;
    }
    PlaneData& pl = *plane_;
    // Measure and legend on the right, the map on the left.
    const float legend_w = ImGui::GetFontSize() * 9.5f;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    ImGui::BeginGroup();
    const std::vector<double>& vals = pl.values[static_cast<std::size_t>(plane_measure_)];
    const bool classes = pl.measures[static_cast<std::size_t>(plane_measure_)] == "period";
    double vmin = 1e300, vmax = -1e300;
    for (double v : vals)
        if (std::isfinite(v)) vmin = std::min(vmin, v), vmax = std::max(vmax, v);
    if (plane_dirty_ || !plane_tex_) {
        const int nx = pl.nx(), ny = pl.ny();
        std::vector<unsigned char> rgba(static_cast<std::size_t>(nx) * ny * 4, 0);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const double v = vals[static_cast<std::size_t>(j) * nx + i];
                if (!std::isfinite(v)) continue;   // not computed: transparent
                const Rgb cc = classes ? period_rgb(static_cast<int>(std::lround(v)))
                                       : ramp_rgb(vmax > vmin ? (v - vmin) / (vmax - vmin) : 0.5);
                unsigned char* px = &rgba[(static_cast<std::size_t>(ny - 1 - j) * nx + i) * 4];   // top row: the last y
                px[0] = cc.r, px[1] = cc.g, px[2] = cc.b, px[3] = 255;
            }
        plane_tex_ = upload_rgba_texture(static_cast<GLuint>(plane_tex_), nx, ny, rgba.data());
        plane_dirty_ = false;
    }
    const PlaneExtent e = plane_extent(pl);
    Axes ax;
    ax.x_label = axis_label(pl.x_name);
    ax.y_label = axis_label(pl.y_name);
    ax.x_scale = axis_scale(pl.x_name);
    ax.y_scale = axis_scale(pl.y_name);
    Plot plot;
    if (plot.begin("##plane", ImVec2(std::max(avail.x - legend_w, 50.0f), avail.y), {e.x_lo, e.x_hi}, {e.y_lo, e.y_hi}, ax)) {
        ImDrawList* dl = plot.draw();
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(plane_tex_)), plot.to_px(e.x_lo, e.y_hi),
                     plot.to_px(e.x_hi, e.y_lo));
        const Palette& pal = palette();
        // Where the bifurcation diagram lies on the plane.
        if (auto cut = diagram_cut(pl, c.diagram_omega.lo, c.diagram_omega.hi, c.xI, c.params->m0e)) {
            const ImVec2 p0 = plot.to_px(cut->x0, cut->y0), p1 = plot.to_px(cut->x1, cut->y1);
            dl->AddLine(p0, p1, IM_COL32(0, 0, 0, 200), 5.0f);
            dl->AddLine(p0, p1, IM_COL32(255, 255, 255, 255), 2.5f);
            const double wx = pl.x_name == "omega" ? c.omega : pl.x_name == "xI" ? c.xI : c.params->m0e;
            const double wy = pl.y_name == "omega" ? c.omega : pl.y_name == "xI" ? c.xI : c.params->m0e;
            const ImVec2 cur = plot.to_px(wx, wy);
            dl->AddCircleFilled(cur, 5.0f, IM_COL32(0, 0, 0, 220));
            dl->AddCircleFilled(cur, 3.5f, pal.cursor);
            plate_text(dl, ImVec2(std::min(p1.x, plot.area_max().x) - ImGui::CalcTextSize("bifurcation diagram").x - 6, p1.y + 4),
                  "bifurcation diagram", pal.axis_text);
        }
        const ImVec2 a = plot.area_min(), b = plot.area_max();
        const ImVec2 m = ImGui::GetIO().MousePos;
        if (plot.hovered()) {
            const auto cell = plane_pick(pl, (m.x - a.x) / (b.x - a.x), (b.y - m.y) / (b.y - a.y));
            if (cell) {
                const double v = vals[static_cast<std::size_t>(cell->j) * pl.nx() + cell->i];
                // A period is named as the map's legend names it ("chaos / > 16" for 0), not as a number.
                const std::string& measure = pl.measures[static_cast<std::size_t>(plane_measure_)];
                char value[48];
                if (measure == "period" && std::isfinite(v)) std::snprintf(value, sizeof value, "%s", period_name(static_cast<int>(v)));
                else std::snprintf(value, sizeof value, "%s = %.4g", measure.c_str(), v);
                ImGui::SetTooltip("%s = %.4g, %s = %.4g\n%s\n(click: run there)", pl.x_name.c_str(), cell->x * axis_scale(pl.x_name),
                                  pl.y_name.c_str(), cell->y * axis_scale(pl.y_name), value);
                if (plot.clicked()) {
                    const PlaneClick click = plane_click(pl, *cell);
                    act.omega = click.omega;
                    act.xI = click.xI;
                    if (!click.ignored.empty()) act.toast = click.ignored + " is not a live parameter: only the other axis was set";
                }
            }
        }
        plate_text(dl, ImVec2(a.x + 4, b.y - ImGui::GetTextLineHeight() - 4), pl.source.c_str(), pal.axis_text);
        plot.end();
    }
    ImGui::EndGroup();
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::SetNextItemWidth(legend_w - ImGui::GetStyle().ItemSpacing.x);
    std::vector<const char*> names;
    for (const auto& s : pl.measures) names.push_back(s.c_str());
    if (ImGui::Combo("##measure", &plane_measure_, names.data(), static_cast<int>(names.size()))) plane_dirty_ = true;
    ImGui::Text("%d x %d points", pl.nx(), pl.ny());
    if (classes) {
        bool present[10] = {};
        for (double v : vals)
            if (std::isfinite(v)) present[std::clamp(period_class(static_cast<int>(std::lround(v))), 0, 9)] = true;
        for (int k : {1, 2, 3, 4, 5, 6, 7, 9, 0})
            if (present[k]) swatch(period_rgb(k), period_name(k));
    } else if (vmax >= vmin) {
        for (int k = 4; k >= 0; --k) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.4g", vmin + (vmax - vmin) * k / 4.0);
            swatch(ramp_rgb(k / 4.0), buf);
        }
    }
    ImGui::Spacing();
    ImGui::TextDisabled("line: the diagram");
    ImGui::TextDisabled("dot: running now");
    ImGui::EndGroup();
    ImGui::End();
}

void AnalysisPanels::draw_basins_window(const AnalysisContext& c, AnalysisAction& act) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.53f, vp->Pos.y + vp->Size.y * 0.53f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(std::min(600 * c.ui_scale, vp->Size.x * 0.45f), std::min(440 * c.ui_scale, vp->Size.y * 0.45f)),
                             ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Basins of attraction", &show_basins_)) {
        ImGui::End();
        return;
    }
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7);
    ImGui::SliderInt("##grid", &basin_grid_, 20, 200, "grid %d");
    ImGui::SameLine();
    if (basin_job_.running()) {
        if (ImGui::Button("Cancel")) basin_job_.cancel();
        ImGui::SameLine();
        ImGui::ProgressBar(static_cast<float>(basin_job_.progress()), ImVec2(-1, 0));
    } else {
        char label[64];
        std::snprintf(label, sizeof label, "Compute at omega = %.2f", c.omega);
        if (ImGui::Button(label)) start_basins(c);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Every (x0, v0) of the grid at φ = 0 run to its attractor on a worker (2 threads).");
    }
    if (!basins_) {
        ImGui::TextDisabled("No basins yet: compute them at the current ω.");
        ImGui::End();
        return;
    }
    const analysis::BasinResult& r = *basins_;
    const analysis::BasinSpec& sp = r.spec;
    if (basin_dirty_ || !basin_tex_) {
        std::vector<unsigned char> rgba(static_cast<std::size_t>(sp.nx) * sp.nv * 4, 0);
        for (int j = 0; j < sp.nv; ++j)
            for (int i = 0; i < sp.nx; ++i) {
                const int l = r.label[static_cast<std::size_t>(j) * sp.nx + i];
                if (l < 0) continue;
                const Rgb cc = label_rgb(l);
                unsigned char* px = &rgba[(static_cast<std::size_t>(sp.nv - 1 - j) * sp.nx + i) * 4];
                px[0] = cc.r, px[1] = cc.g, px[2] = cc.b, px[3] = 255;
            }
        basin_tex_ = upload_rgba_texture(static_cast<GLuint>(basin_tex_), sp.nx, sp.nv, rgba.data());
        basin_dirty_ = false;
    }
    const float legend_w = ImGui::GetFontSize() * 12.5f;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    Axes ax;
    ax.x_label = "x0 [mm]";
    ax.y_label = "v0 [mm/s]";
    ax.x_scale = ax.y_scale = 1e3;
    Plot plot;
    if (plot.begin("##basins", ImVec2(std::max(avail.x - legend_w, 50.0f), avail.y), {sp.x_min, sp.x_max}, {sp.v_min, sp.v_max}, ax)) {
        ImDrawList* dl = plot.draw();
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(basin_tex_)), plot.to_px(sp.x_min, sp.v_max),
                     plot.to_px(sp.x_max, sp.v_min));
        // Each attractor's section points, ringed so they show on their own basin's colour.
        for (const analysis::Attractor& at : r.attractors)
            for (std::size_t k = 0; k < at.points.size() && k < 64; ++k) {
                const ImVec2 p = plot.to_px(at.points[k][0], at.points[k][1]);
                dl->AddCircleFilled(p, 4.0f, IM_COL32(0, 0, 0, 230));
                dl->AddCircleFilled(p, 2.5f, IM_COL32(255, 255, 255, 255));
            }
        const ImVec2 a = plot.area_min(), b = plot.area_max(), m = ImGui::GetIO().MousePos;
        if (plot.hovered()) {
            const int i = std::clamp(static_cast<int>((m.x - a.x) / (b.x - a.x) * sp.nx), 0, sp.nx - 1);
            const int j = std::clamp(static_cast<int>((b.y - m.y) / (b.y - a.y) * sp.nv), 0, sp.nv - 1);
            const int l = r.label[static_cast<std::size_t>(j) * sp.nx + i];
            ImGui::SetTooltip("x0 = %.2f mm, v0 = %.1f mm/s: attractor %d\n(click: start the simulation here at ω = %.3f)",
                              1e3 * r.x0(i), 1e3 * r.v0(j), l, sp.omega);
            if (plot.clicked()) {
                act.reset = std::make_pair(r.x0(i), r.v0(j));
                if (std::abs(c.omega - sp.omega) > 1e-12) act.omega = sp.omega;
            }
        }
        char info[96];
        std::snprintf(info, sizeof info, "%s  omega = %.3f rad/s  %d x %d  %.1f s", basins_model_.c_str(), sp.omega, sp.nx, sp.nv, r.seconds);
        plate_text(dl, ImVec2(a.x + 4, b.y - ImGui::GetTextLineHeight() - 4), info, palette().axis_text);
        plot.end();
    }
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted("attractors (cells)");
    for (const analysis::Attractor& at : r.attractors) {
        char buf[96];
        const char* well = at.well < 0 ? "left" : at.well > 0 ? "right" : "centre";
        if (at.kind == analysis::AttractorKind::Periodic)
            std::snprintf(buf, sizeof buf, "%d: period %d, %s (%zu)", at.id, at.period, well, at.cells);
        else
            std::snprintf(buf, sizeof buf, "%d: %s, %s (%zu)", at.id, analysis::attractor_kind_name(at.kind), well, at.cells);
        swatch(label_rgb(at.id), buf);
    }
    ImGui::Spacing();
    ImGui::TextDisabled("dots: section points");
    ImGui::TextDisabled("click: run from there");
    ImGui::EndGroup();
    ImGui::End();
}

}  // namespace impactlab::gui
