// The rig, drawn to scale (RigView renders it on the GPU from a draw-list callback), with its labels placed
// in order of importance where they fit, the companion's outline, and the cart dragged with the mouse.
#include "rig_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>

#include "views/contact_label.hpp"
#include "impactlab/drive.hpp"
#include "impactlab/forces.hpp"
#include "window/layout.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
// The labels over the rig's image. They go in order of importance, each at the first of its spots that lies
// inside the image and clear of those placed before (LabelPlacer): none overprints another, none is cut at
// the edge, at any UI scale, tile size, x_I or magnification; what finds no room is left out.
class RigLabels {
public:
    struct Spot {
        ImVec2 p, align;   // the point, and where on the text's box it sits (0..1 in x and y)
    };
    RigLabels(const RigView& rig, ImVec2 p0, float fbs, int w, int h, const Palette& pal)
        : rig_(rig), p0_(p0), fbs_(fbs), labels_({p0.x, p0.y, static_cast<float>(w), static_cast<float>(h)}),
          plate_bg_(pal.dark ? IM_COL32(10, 12, 16, 150) : IM_COL32(255, 255, 255, 170)) {}
    ImDrawList* dl() const { return dl_; }
    // Screen position of a point of the drawing (x already magnified: mag.draw_x, mag.bumper_face).
    ImVec2 at(double x, double y) const {
        const ImVec2 q = rig_.to_image(x, y);
        return ImVec2(p0_.x + q.x / fbs_, p0_.y + q.y / fbs_);
    }
    bool put(const char* s, ImU32 col, std::initializer_list<Spot> spots, bool plate = true) {
        const ImVec2 ts = ImGui::CalcTextSize(s);
        for (const Spot& sp : spots) {
            const Rect r{std::round(sp.p.x - ts.x * sp.align.x) - 3, std::round(sp.p.y - ts.y * sp.align.y) - 1, ts.x + 6,
                         ts.y + 2};
            if (!labels_.place(r)) continue;
            if (plate) dl_->AddRectFilled(ImVec2(r.x, r.y), ImVec2(r.right(), r.bottom()), plate_bg_, 3.0f);
            dl_->AddText(ImVec2(r.x + 3, r.y + 1), col, s);
            return true;
        }
        return false;
    }
    bool place(const Rect& r) { return labels_.place(r); }
    // A part of the drawing no label may cover.
    void reserve(double x0, double y0, double x1, double y1) {
        const ImVec2 a = at(x0, y0), b = at(x1, y1);
        labels_.reserve({std::min(a.x, b.x), std::min(a.y, b.y), std::abs(b.x - a.x), std::abs(b.y - a.y)});
    }

private:
    const RigView& rig_;
    ImVec2 p0_;
    float fbs_;
    LabelPlacer labels_;
    ImU32 plate_bg_;
    ImDrawList* dl_ = ImGui::GetWindowDrawList();
};

// The regime badge, PAUSED, and the magnification (where every eye goes first: beside the badge or under it).
// The badge: a compliant bumper has no regimes II/III (contact is free flight with F_I > 0); the same words
// as the status bar, from the same sample (contact_label.hpp).
void put_badges(RigLabels& L, const ViewContext& ctx, const RigMagnify& mag, ImVec2 p0, int w, int h, float edge) {
    const Params& p = *ctx.params;
    const Palette& pal = palette();
    const float fs = ImGui::GetFontSize();
    char buf[128];
    const char* badge = contact_label(p, ctx.last.regime, ctx.last.force);
    const ImU32 badge_col = in_contact(p, ctx.last.regime, ctx.last.force) ? pal.bumper : pal.energy;
    const ImVec2 bp(p0.x + edge, p0.y + fs * 0.5f);
    L.put(badge, badge_col, {{bp, {0, 0}}});
    if (ctx.paused) L.put(ctx.sim_paused ? "PAUSED" : "STEPPING", pal.warn, {{ImVec2(p0.x + w - edge, bp.y), {1, 0}}}, false);
    if (mag.gain > 1.001) {
        std::snprintf(buf, sizeof buf, "displacement ×%.3g (drawing only)", mag.gain);
        const float bw = ImGui::CalcTextSize(badge).x;
        if (!L.put(buf, pal.warn, {{ImVec2(bp.x + bw + fs, bp.y), {0, 0}}, {ImVec2(bp.x, bp.y + 1.6f * fs), {0, 0}}})) {
            std::snprintf(buf, sizeof buf, "displacement ×%.3g", mag.gain);
            L.put(buf, pal.warn, {{ImVec2(bp.x + bw + fs, bp.y), {0, 0}}, {ImVec2(bp.x, bp.y + 1.6f * fs), {0, 0}},
                                  {ImVec2(p0.x + w - edge, p0.y + h - fs * 2.2f), {1, 1}}});
        }
    }
}

// The impact label at the bumper's face, the cart's x beside the ruler, the bumper's x_I under it.
void put_contact_labels(RigLabels& L, const ViewContext& ctx, const RigMagnify& mag, ImVec2 p0, int w) {
    const Params& p = *ctx.params;
    const Palette& pal = palette();
    char buf[128];
    const double face = mag.bumper_face(ctx.xI_shown);
    const double bumper_top = rig::kBumperY + rig::kBumperHalfH + 0.0025, bumper_low = rig::kBumperY - rig::kBumperHalfH - 0.003;
    // The impact label speaks of the displayed instant: the force now while in contact, then the last
    // contact's v- or peak force, fading, for at most half a forcing period of simulated time.
    const bool touching = in_contact(p, ctx.last.regime, ctx.last.force);
    const double label_alpha =
        ctx.impact_label->alpha(touching, ctx.last.t, ctx.now, kTwoPi / std::max(ctx.omega, 0.5), ctx.speed);
    if (label_alpha > 0.02) {
        if (touching) std::snprintf(buf, sizeof buf, "F = %.1f N", std::max(0.0, ctx.last.force));
        else if (ctx.impact_label->was_impact()) std::snprintf(buf, sizeof buf, "impact  v- = %.3f m/s", ctx.impact_label->v_minus());
        else std::snprintf(buf, sizeof buf, "contact  peak F = %.1f N", ctx.impact_label->peak_force());
        const double heat = touching ? std::min(1.0, ctx.last.force / 100) : 0.0;
        const ImU32 col = heat_color(static_cast<float>(0.5 + 0.5 * std::max(ctx.flash, heat)), static_cast<float>(label_alpha));
        const ImVec2 q = L.at(face + 0.004, bumper_top);
        L.put(buf, col, {{q, {0, 1}}, {ImVec2(p0.x + w - 4, q.y), {1, 1}}, {L.at(face - 0.004, bumper_top), {1, 1}}});
    }
    // The cart's x beside the ruler (whose millimetres are magnified with the displacement).
    std::snprintf(buf, sizeof buf, "x = %+.2f mm", ctx.last.x * 1e3);
    const double ruler_end = 0.025 * mag.gain;
    L.put(buf, pal.title_text, {{L.at(ruler_end + 0.004, rig::kRulerY + 0.0025), {0, 0.5f}},
                                {L.at(-ruler_end - 0.004, rig::kRulerY + 0.0025), {1, 0.5f}},
                                {L.at(0.0, rig::kRulerY - 0.004), {0.5f, 0}}});
    // The bumper: under it, right of its face; at a large x_I against the image's right edge, or shorter.
    if (p.has_bumper()) {
        std::snprintf(buf, sizeof buf, "bumper  x_I = %+.1f mm", ctx.xI_shown * 1e3);
        const ImVec2 q = L.at(face + 0.004, bumper_low), q_left = L.at(face - 0.004, bumper_low);
        if (!L.put(buf, pal.axis_text, {{q, {0, 0}}, {ImVec2(p0.x + w - 4, q.y), {1, 0}}, {q_left, {1, 0}}})) {
            std::snprintf(buf, sizeof buf, "x_I = %+.1f mm", ctx.xI_shown * 1e3);
            L.put(buf, pal.axis_text, {{q, {0, 0}}, {ImVec2(p0.x + w - 4, q.y), {1, 0}}, {q_left, {1, 0}}});
        }
    }
}

// The legend: a scale bar (the rig's size; the displacement is magnified on top of it) and the forcing.
void put_legend(RigLabels& L, const ViewContext& ctx, float ten_mm, ImVec2 p0, int w, int h, float edge) {
    const Palette& pal = palette();
    const float fs = ImGui::GetFontSize();
    char buf[128];
    const ImVec2 lg(p0.x + edge, p0.y + h - fs * 0.8f);
    const ImVec2 tl = ImGui::CalcTextSize("10 mm");
    if (L.place({lg.x - 2, lg.y - fs * 0.6f, ten_mm + 8 + tl.x, fs * 1.2f})) {
        ImDrawList* dl = L.dl();
        dl->AddLine(ImVec2(lg.x, lg.y), ImVec2(lg.x + ten_mm, lg.y), pal.title_text, 2.0f);
        dl->AddLine(ImVec2(lg.x, lg.y - 4), ImVec2(lg.x, lg.y + 4), pal.title_text, 1.5f);
        dl->AddLine(ImVec2(lg.x + ten_mm, lg.y - 4), ImVec2(lg.x + ten_mm, lg.y + 4), pal.title_text, 1.5f);
        dl->AddText(ImVec2(lg.x + ten_mm + 6, lg.y - fs * 0.55f), pal.axis_text, "10 mm");
    }
    const double om = ctx.last.omega;
    const double m0e = ctx.params->m0e;
    std::snprintf(buf, sizeof buf, "unbalance  m0e ω² = %.2f N", m0e * om * om);
    const ImVec2 ub(p0.x + w - edge, lg.y - fs * 0.55f);
    if (!L.put(buf, pal.axis_text, {{ub, {1, 0}}})) {
        std::snprintf(buf, sizeof buf, "m0e ω² = %.2f N", m0e * om * om);
        L.put(buf, pal.axis_text, {{ub, {1, 0}}});
    }
}

// The parts: the magnets' force, the springs, the ruler's numbers (at the magnified millimetres).
void put_part_labels(RigLabels& L, const ViewContext& ctx, const RigMagnify& mag, double magnet_force) {
    const ImU32 dim = palette().axis_text;
    char buf[128];
    // The magnets' force on the cart as a direction and a size: a signed "repel: -12.58 N" read as attraction.
    const char* towards = magnet_force < 0 ? "←" : "→";
    std::snprintf(buf, sizeof buf, "magnets push the cart %s %.2f N", towards, std::abs(magnet_force));
    if (!L.put(buf, dim, {{L.at(-0.014, rig::kMagnetFixedY - 0.001), {1, 0.5f}}})) {
        std::snprintf(buf, sizeof buf, "magnets %s %.2f N", towards, std::abs(magnet_force));
        L.put(buf, dim, {{L.at(-0.014, rig::kMagnetFixedY - 0.001), {1, 0.5f}}});
    }
    std::snprintf(buf, sizeof buf, "springs  k = %.0f N/m", ctx.params->k);
    L.put(buf, dim, {{L.at(-mag.wall_x() + 0.012, rig::kSpringY + 0.0115), {0, 1}}});
    for (int mm = -20; mm <= 20; mm += 20) {
        std::snprintf(buf, sizeof buf, "%d", mm);
        L.put(buf, dim, {{L.at(mm * 1e-3 * mag.gain, rig::kRulerY + 0.0058), {0.5f, 1}}}, false);
    }
}
}  // namespace

ViewAction RigPanel::draw(const ViewContext& ctx) {
    const Params& p = *ctx.params;
    const Palette& pal = palette();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const int w = std::max(16, static_cast<int>(avail.x)), h = std::max(16, static_cast<int>(avail.y));
    RigState st;
    st.x = ctx.last.x;
    st.v = ctx.last.v;
    st.phi = ctx.last.phi;
    st.phi_span = ctx.have_last ? ctx.last.phi - ctx.phi_prev : 0.0;
    st.xI = ctx.xI_shown;   // where the simulation has it: it travels to the slider's x_I, pushing the cart
    st.bumper_force = std::max(ctx.frame_max_force, ctx.last.force);
    st.bumper = p.has_bumper();
    st.flash = ctx.flash;
    st.magnet_force = -(spring_magnet(p, ctx.last.x).F - p.k * ctx.last.x);
    st.spring_force = -p.k * ctx.last.x;
    st.in_contact = in_contact(p, ctx.last.regime, ctx.last.force);
    st.magnify = ctx.magnify;   // the drawing only (layout.hpp: RigMagnify)
    // Rendered at the framebuffer's resolution (sharp on high-DPI screens), shown at display size.
    const float fbs = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
    rig_.prepare(static_cast<int>(w * fbs), static_cast<int>(h * fbs), st, pal);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(static_cast<float>(w), static_cast<float>(h)));   // the item the mouse hovers
    rig_.add_to(ImGui::GetWindowDrawList(), p0);
    ViewAction act = mouse(ctx, p0, fbs);   // drag the cart

    RigLabels labels(rig_, p0, fbs, w, h, pal);
    const RigMagnify& mag = rig_.magnify();
    {   // The ruler and the end walls are no place for a label either: their boxes are taken first.
        const double wall_x = mag.wall_x(), ruler = 0.025 * mag.gain;
        labels.reserve(-ruler, rig::kRulerY - 0.001, ruler, rig::kRulerY + 0.0052);   // the ticks (numbers sit above)
        labels.reserve(wall_x - 0.003, -0.065, wall_x + 0.013, 0.045);
        labels.reserve(-wall_x - 0.013, -0.065, -wall_x + 0.003, 0.045);
    }
    const float edge = ImGui::GetFontSize() * 0.6f;
    put_badges(labels, ctx, mag, p0, w, h, edge);
    put_contact_labels(labels, ctx, mag, p0, w);
    put_legend(labels, ctx, 0.010f * rig_.px_per_m() / fbs, p0, w, h, edge);
    put_part_labels(labels, ctx, mag, st.magnet_force);
    // The companion cart: a translucent outline where the twin or the ghost is.
    if (ctx.companion_shown()) {
        ImDrawList* dl = labels.dl();
        const double xc = rig_.magnify().draw_x(ctx.companion->last().x);   // drawn as the cart is
        const ImVec2 a = labels.at(xc - rig::kCartHalfW, rig::kCartHalfH), b = labels.at(xc + rig::kCartHalfW, -rig::kCartHalfH);
        dl->AddRectFilled(a, b, companion_color(0.22f), 6.0f);
        dl->AddRect(a, b, companion_color(0.9f), 6.0f, 0, 2.0f);
        dl->AddText(ImVec2(a.x + 4, b.y - ImGui::GetFontSize() - 2), companion_color(1.0f), ctx.companion_name.c_str());
    }
    return act;
}

ViewAction RigPanel::mouse(const ViewContext& ctx, ImVec2 image_min, float fbs) {
    ViewAction act;
    // The rig image's mapping, from two points of RigView::to_image (framebuffer pixels): m -> screen.
    const ImVec2 o = rig_.to_image(0.0, 0.0), e = rig_.to_image(0.01, 0.01);
    const double ppm_x = (e.x - o.x) / 0.01, ppm_y = (o.y - e.y) / 0.01;
    if (!(ppm_x > 0) || !(ppm_y > 0)) return act;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const double mx = ((mouse.x - image_min.x) * fbs - o.x) / ppm_x;
    const double my = -((mouse.y - image_min.y) * fbs - o.y) / ppm_y;
    const bool hovered = ImGui::IsItemHovered();
    // mx is in the drawing, whose displacements may be magnified (tiles.cpp, RigMagnify): the cart is drawn
    // at draw_x(x), and a drawn distance is gain times the true one.
    const RigMagnify& mag = rig_.magnify();
    const bool on_cart =
        hovered && std::abs(mx - mag.draw_x(ctx.last.x)) <= rig::kCartHalfW && std::abs(my) <= rig::kCartHalfH;
    if (!dragging_ && on_cart) {
        ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Left))
            ImGui::SetTooltip("drag the cart: the simulation holds it at the mouse;\nlet go to start from there at rest");
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
            dragging_ = true;
            drag_grab_ = ctx.last.x - mx / mag.gain;
            drag_x_ = std::nan("");   // the first frame sends the hold
        }
    }
    if (!dragging_) return act;
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
    const PickedState s = pick_state(mx / mag.gain + drag_grab_, 0.0, ctx.xI, ctx.params->has_bumper());
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        if (!(std::abs(s.x - drag_x_) <= 1e-6)) {   // moved (each hold restarts the companion too)
            drag_x_ = s.x;
            act.hold = drag_x_;
        }
        ImGui::SetTooltip("x = %+.2f mm%s", drag_x_ * 1e3, s.note.empty() ? "" : "  (at the bumper)");
    } else {   // let go: from there at rest (a toast says so if the bumper or the rail stopped the hand)
        dragging_ = false;
        act.set_state = std::make_pair(mx / mag.gain + drag_grab_, 0.0);
    }
    return act;
}

}  // namespace impactlab::gui
