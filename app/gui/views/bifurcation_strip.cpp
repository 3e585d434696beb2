// The bifurcation view's parts beside the diagram itself: the strip of lambda_max(omega) under it (its job,
// its plot on the diagram's omega axis) and the density colours' legend in the header. UI thread only.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/sim_engine.hpp"   // kMaxOmega
#include "render/theme.hpp"
#include "views/bifurcation_panel.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

ImU32 density_u32(float t) {
    unsigned char c[4];
    density_color(palette().dark, t, c);
    return IM_COL32(c[0], c[1], c[2], c[3]);
}

// The Lyapunov strip: chaos (lambda > 0), periodic orbits (lambda < 0), and a band around zero where the
// estimate of 40 periods cannot tell (a cart creeping off the hilltop: about 1e-3 1/s).
constexpr ImU32 kChaosColor = IM_COL32(240, 80, 70, 255), kOrderColor = IM_COL32(80, 150, 255, 255),
                kZeroColor = IM_COL32(170, 170, 170, 255);
constexpr double kLambdaZero = 0.02;   // [1/s]
ImU32 lambda_color(double l) { return l > kLambdaZero ? kChaosColor : l < -kLambdaZero ? kOrderColor : kZeroColor; }
const char* lambda_word(double l) {
    return l > kLambdaZero ? "chaos" : l < -kLambdaZero ? "periodic" : "about zero: neither settles nor separates";
}

}  // namespace

void BifurcationPanel::start_strip(const BifurcationContext& c) {
    LyapunovStripRequest r;
    r.params = have_ ? shown_req_.params : *c.params;
    // The diagram's sweep: the same direction and omega range (the EF ramp's range swept up).
    r.direction = have_ && shown_req_.protocol == BifProtocol::CfDown ? SweepDirection::Down : SweepDirection::Up;
    r.omega_lo = have_ ? shown_req_.omega_lo : lo_edit_;
    r.omega_hi = have_ ? shown_req_.omega_hi : hi_edit_;
    r.steps = lyap_steps_;
    lyap_req_ = r;
    lyap_.clear();
    lyap_done_ = 0;
    lyap_model_ = have_ ? shown_.model : c.model;
    lyap_job_.start(r);
}

void BifurcationPanel::draw_legend() const {
    // The density colours in the header, from one point in a pixel to the densest pixel, on the image's log
    // scale (the colour of n points is log(1 + n) / log(1 + max)), so it never covers the diagram.
    if (!have_ || shown_.points.empty() || max_count_ <= 0) return;
    const Palette& pal = palette();
    const float fs = ImGui::GetFontSize();
    char top[32];
    std::snprintf(top, sizeof top, "%.0f", static_cast<double>(max_count_));
    const float bar_w = fs * 5.0f, bar_h = fs * 0.75f;
    const float need = ImGui::CalcTextSize("1").x + bar_w + ImGui::CalcTextSize(top).x + ImGui::CalcTextSize(" points/pixel").x + fs;
    ImGui::SameLine(0, fs * 0.8f);
    if (ImGui::GetContentRegionAvail().x < need) ImGui::NewLine();
    ImGui::TextUnformatted("1");
    ImGui::SameLine(0, fs * 0.25f);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float y0 = p.y + 0.5f * (ImGui::GetTextLineHeight() - bar_h);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    constexpr int kBands = 24;
    for (int i = 0; i < kBands; ++i) {
        const float t0 = static_cast<float>(i) / kBands, t1 = static_cast<float>(i + 1) / kBands;
        const ImU32 c0 = density_u32(t0), c1 = density_u32(t1);
        dl->AddRectFilledMultiColor(ImVec2(p.x + t0 * bar_w, y0), ImVec2(p.x + t1 * bar_w, y0 + bar_h), c0, c1, c1, c0);
    }
    dl->AddRect(ImVec2(p.x - 0.5f, y0 - 0.5f), ImVec2(p.x + bar_w + 0.5f, y0 + bar_h + 0.5f), pal.plot_frame);
    ImGui::Dummy(ImVec2(bar_w, ImGui::GetTextLineHeight()));
    if (ImGui::IsItemHovered()) {
        const double mid = std::expm1(0.5 * std::log1p(static_cast<double>(max_count_)));
        ImGui::SetTooltip("Colour: section points falling in one pixel of the image, on a log scale "
                          "(1 point: darkest, %.0f: the middle, %.0f: the densest pixel of this view).",
                          mid, static_cast<double>(max_count_));
    }
    ImGui::SameLine(0, fs * 0.25f);
    ImGui::Text("%s points/pixel", top);
    const int unsettled = not_settled();
    if (unsettled == 0) return;
    // The grey levels: what they are, in the header beside the scale (never over the diagram).
    char grey[48];
    std::snprintf(grey, sizeof grey, "not settled: %d", unsettled);
    ImGui::SameLine(0, fs * 0.8f);
    if (ImGui::GetContentRegionAvail().x < bar_h + fs * 0.3f + ImGui::CalcTextSize(grey).x) ImGui::NewLine();
    const ImVec2 q = ImGui::GetCursorScreenPos();
    unsigned char rgba[4];
    not_settled_color(pal.dark, 0.6f, rgba);
    const float gy = q.y + 0.5f * (ImGui::GetTextLineHeight() - bar_h);
    dl->AddRectFilled(ImVec2(q.x, gy), ImVec2(q.x + bar_h, gy + bar_h), IM_COL32(rgba[0], rgba[1], rgba[2], rgba[3]));
    ImGui::Dummy(ImVec2(bar_h, ImGui::GetTextLineHeight()));
    ImGui::SameLine(0, fs * 0.3f);
    ImGui::TextUnformatted(grey);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Grey: %d levels whose section points did not recur with a period up to %d within %d more "
                          "records (the map's own test, as impactlab bifurcation --settle): chaos, or a transient "
                          "longer than that. A finite run cannot tell the two apart.",
                          unsettled, kDiagramMaxPeriod, shown_req_.settle);
}

void BifurcationPanel::draw_strip(const BifurcationContext& c, Range view_x, BifurcationAction& act) {
    const Palette& pal = palette();
    // The auto-fit: zero and the exponents found; a resting cart's very negative values are cut at -4 1/s.
    double lo = -0.5, hi = 0.5;
    for (const auto& q : lyap_) {
        if (!std::isfinite(q.lambda_max)) continue;
        lo = std::min(lo, std::max(q.lambda_max, -4.0));
        hi = std::max(hi, q.lambda_max);
    }
    const double pad = 0.08 * (hi - lo);
    const Range fit_y{lo - pad, hi + pad};
    // The strip shares the diagram's omega axis: it is drawn over the diagram's view, and a zoom or pan on
    // the strip is handed to the diagram (both show it from the next frame) while lambda's axis keeps the
    // user's zoom; a double-click on the strip gives both back to their auto-fits.
    const Range y_in = lyap_y_user_ ? lyap_view_y_ : fit_y;
    Plot plot;
    Axes ax;
    ax.x_label = "ω [rad/s]";
    ax.y_label = "λmax [1/s]";
    if (!plot.begin("##lyap", ImGui::GetContentRegionAvail(), view_x, y_in, ax)) return;
    const Range vx = plot.x_range(), vy = plot.y_range();
    if (plot.zoomed()) {
        if (vx.lo != view_x.lo || vx.hi != view_x.hi) Plot::set_user_view("##bif", vx, view_y_);
        if (vy.lo != y_in.lo || vy.hi != y_in.hi) {
            lyap_y_user_ = true;
            lyap_view_y_ = vy;
        }
        Plot::clear_user_view("##lyap");
    }
    if (plot.hovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
        lyap_y_user_ = false;
        Plot::clear_user_view("##bif");
    }
    const ImVec2 a = plot.area_min();
    plot.hline(0.0, pal.axis_text, 1.0f, true);
    plot.text(vx.lo, 0.0, " λ = 0", pal.axis_text, ImVec2(0, 1.0f));
    const bool is_stale = lyap_model_ != c.model || std::abs(lyap_req_.params.xI - c.xI) > 1e-9;
    if (!lyap_.empty()) {
        plot.series(lyap_.size(), [&](std::size_t i) {
            struct P { double x, y; };
            return P{lyap_[i].omega, std::max(lyap_[i].lambda_max, vy.lo)};
        }, is_stale ? pal.grid : pal.trace2, 1.2f);
        for (const auto& q : lyap_) {
            const ImVec2 p = plot.to_px(q.omega, std::max(q.lambda_max, vy.lo));
            ImU32 col = lambda_color(q.lambda_max);
            if (is_stale) col = (col & 0x00FFFFFFu) | (90u << 24);
            plot.draw()->AddCircleFilled(p, 2.6f, col, 8);
        }
    }
    char info[200];
    if (lyap_job_.running())
        std::snprintf(info, sizeof info, "%s λmax: %d / %d ω (%d + %d periods each) computing...", lyap_model_.c_str(),
                      lyap_done_, lyap_req_.steps, lyap_req_.transient, lyap_req_.record);
    else if (lyap_.empty())
        std::snprintf(info, sizeof info, "λmax: none yet (tick λ again, or B, to compute)");
    else
        std::snprintf(info, sizeof info, "%s λmax at %zu ω%s  (red: > 0, chaos; blue: < 0, periodic; grey: about 0)", lyap_model_.c_str(),
                      lyap_.size(), is_stale ? " — another model or xI: press B" : "");
    plate_text(plot.draw(), ImVec2(a.x + 6, a.y + 4), info, is_stale ? pal.warn : pal.axis_text);
    plot.vline(c.omega, pal.cursor, 1.5f);
    if (plot.hovered()) {
        const double w = std::clamp(plot.x_at(ImGui::GetIO().MousePos.x), 0.0, kMaxOmega);
        // The nearest computed omega, named.
        const analysis::LyapunovPoint* near = nullptr;
        for (const auto& q : lyap_)
            if (!near || std::abs(q.omega - w) < std::abs(near->omega - w)) near = &q;
        if (near && std::abs(plot.to_px(near->omega, 0).x - ImGui::GetIO().MousePos.x) < 8)
            ImGui::SetTooltip("ω = %.3f rad/s: λmax = %+.3f 1/s (%s, %d section values)", near->omega, near->lambda_max,
                              lambda_word(near->lambda_max), near->period);
        else ImGui::SetTooltip("ω = %.3f rad/s (click to set)", w);
        if (plot.clicked()) act.omega = w;
    }
    plot.end();
}

}  // namespace impactlab::gui
