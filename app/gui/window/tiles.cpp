// The visualiser's tiles on the main viewport: App::layout_and_draw asks layout.cpp
// for rectangles and draws each panel in its tile; a tile with several panels shows them as tabs. Each
// tile's title bar has hide and maximise buttons (a double-click on the title maximises too); presentation
// mode is the rig and one plot under a slim bar of controls. UI thread only.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "window/app.hpp"
#include "render/plot2d.hpp"
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

constexpr ImGuiWindowFlags kTileFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                        ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;

bool begin_tile_at(const char* name, const Rect& r, ImGuiWindowFlags extra = 0) {
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y));
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h));
    // No background fill: App::frame clears the window to WindowBg (cheap under llvmpipe, see panels.cpp).
    ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(0, 0, 0, 0));
    const bool open = ImGui::Begin(name, nullptr, kTileFlags | extra);
    ImGui::PopStyleColor();
    return open;
}

// Titles, longest first: the tile shows the longest that fits beside its buttons (the view table's, and
// the rig's magnification where it is not x1).
// A title's "φ = 2πn" with the section's phase in it ("φ = 1.57 + 2πn") when it is not 0.
std::string with_section_phase(std::string title, double phi0) {
    static const std::string strobe = "φ = 2πn";
    const std::size_t at = title.find(strobe);
    if (at == std::string::npos || phi0 == 0.0 || phi0 == kTwoPi) return title;
    char buf[48];
    std::snprintf(buf, sizeof buf, "φ = %.2f + 2πn", phi0);
    return title.replace(at, strobe.size(), buf);
}

std::vector<std::string> titles_of(PanelId p, double magnify, double phi0 = 0.0) {
    if (p == PanelId::Rig && magnify > 1.001) {
        char g[16];
        std::snprintf(g, sizeof g, "%.3g", magnify);
        return {std::string("Rig (top view, to scale; displacement ×") + g + ")", std::string("Rig (displacement ×") + g + ")",
                std::string("Rig ×") + g};
    }
    std::vector<std::string> out;
    for (const char* t : view_info(p).titles)
        if (t) out.push_back(with_section_phase(t, phi0));
    return out;
}

// The tab's label: the shortest title.
std::string tab_label(PanelId p) { return titles_of(p, 1.0).back(); }

}  // namespace

double App::magnification() const { return layout_.magnify[layout_.mode == LayoutMode::Presentation ? 1 : 0]; }

void App::set_magnification(double g) {
    layout_.magnify[layout_.mode == LayoutMode::Presentation ? 1 : 0] = std::clamp(g, RigMagnify::kMin, RigMagnify::kMax);
}

void App::set_presentation(bool on) {
    const LayoutMode m = on ? LayoutMode::Presentation : LayoutMode::Normal;
    if (m == layout_.mode) return;
    layout_.mode = m;
    layout_.maximised.reset();
    // Large fonts in front of a class: at least 1.5 while presenting, the user's scale back afterwards.
    if (on) {
        layout_.normal_scale = view_.ui_scale;
        view_.ui_scale = std::max(view_.ui_scale, 1.5f);
    } else {
        view_.ui_scale = layout_.normal_scale;
    }
    view_.fonts_dirty = true;
}

// UI thread, at init (after the UI scale is known: presentation mode raises it).
void App::configure_layout() {
    for (const std::string& h : opt_.hide) {
        if (h == "controls") layout_.controls_visible = false;
        else if (const auto p = panel_from_key(h)) layout_.panel_visible[static_cast<std::size_t>(*p)] = false;
    }
    if (const auto p = panel_from_key(opt_.presentation_plot)) layout_.featured = *p;
    if (opt_.presentation) set_presentation(true);
    if (opt_.magnify > 0) set_magnification(opt_.magnify);   // the starting mode's
    if (const auto p = panel_from_key(opt_.maximise)) layout_.maximised = *p;
    // The analysis tiles open with what the command line asks of them.
    if (!opt_.plane.empty() || opt_.small_plane) set_panel_visible(PanelId::Plane, true);
    if (opt_.basins) set_panel_visible(PanelId::Basins, true);
}

void App::toggle_maximised(PanelId p) {
    if (layout_.maximised == p) layout_.maximised.reset();
    else layout_.maximised = p;
}

void App::draw_panel(PanelId p) {
    const int slot = 1 + static_cast<int>(p);   // bench_.panel_s: the controls first
    const auto t0 = std::chrono::steady_clock::now();
    switch (p) {
        case PanelId::Rig: apply_view(rig_.draw(view_context())); break;
        case PanelId::Bifurcation: draw_bifurcation(); break;
        case PanelId::Phase: apply_view(phase_.draw(view_context())); break;
        case PanelId::Poincare: apply_view(poincare_.draw(view_context(), phase_.view_x(), phase_.view_v())); break;
        case PanelId::Potential: apply_view(potential_.draw(view_context())); break;
        case PanelId::Strip: apply_view(strip_.draw(view_context())); break;
        case PanelId::Plane: apply_analysis(analysis_.plane.draw(analysis_context())); break;
        case PanelId::Basins: apply_analysis(analysis_.basins.draw(analysis_context())); break;
    }
    if (bench_.on)
        bench_.panel_s[static_cast<std::size_t>(slot)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One tile: its title (the longest that fits), the hide and maximise buttons drawn over the title bar,
// tabs when it holds several panels.
void App::draw_tile(const Tile& tile) {
    const std::size_t key = static_cast<std::size_t>(tile.panels.front());
    PanelId active = layout_.tile_tab[key];
    if (std::find(tile.panels.begin(), tile.panels.end(), active) == tile.panels.end()) active = tile.panels.front();
    const float frame_h = ImGui::GetFrameHeight();
    const bool presenting = layout_.mode == LayoutMode::Presentation;
    // Buttons: maximise (or restore) and, outside presentation mode, hide.
    const int buttons = presenting ? 1 : 2;
    const float button_w = frame_h, buttons_w = static_cast<float>(buttons) * button_w + 4.0f * view_.ui_scale;
    const float room = tile.rect.w - buttons_w - 2.0f * ImGui::GetStyle().FramePadding.x - 4.0f * view_.ui_scale;
    std::string title;
    std::vector<std::string> titles = titles_of(active, magnification(), view_.section_phase);
    if (active == PanelId::Strip && (strip_.first() != StripQuantity::X || strip_.second()))   // other traces
        titles = {with_section_phase("Time strip        dots: Poincaré sections (φ = 2πn)    right-click: the traces",
                                     view_.section_phase),
                  "Time strip"};
    for (const std::string& t : titles) {
        title = t;
        if (ImGui::CalcTextSize(t.c_str()).x <= room) break;
    }
    const std::string id = title + "###tile_" + panel_key(tile.panels.front());
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(4.0f * view_.ui_scale, 4.0f * view_.ui_scale));
    // The wheel zooms these plots; it must not scroll their tile too.
    const bool rigish = active == PanelId::Rig || active == PanelId::Bifurcation || active == PanelId::Plane ||
                        active == PanelId::Basins;
    const bool open = begin_tile_at(id.c_str(), tile.rect,
                                    ImGuiWindowFlags_NoScrollbar | (rigish ? ImGuiWindowFlags_NoScrollWithMouse : 0));
    ImGui::PopStyleVar();
    if (open) {
        // Title bar: [maximise/restore] [hide], at its right end (ImGui clips the title before them).
        const ImVec2 wp = ImGui::GetWindowPos();
        const ImVec2 t0(wp.x, wp.y), t1(wp.x + tile.rect.w, wp.y + frame_h);
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->PushClipRect(t0, t1, false);
        const Palette& pal = palette();
        const bool window_hovered = ImGui::IsWindowHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem);
        bool over_button = false;
        for (int b = 0; b < buttons; ++b) {
            const float x1 = t1.x - 4.0f * view_.ui_scale - static_cast<float>(b) * button_w, x0 = x1 - button_w;
            const ImVec2 b0(x0 + 2, t0.y + 2), b1(x1 - 2, t1.y - 2);
            const bool hover = window_hovered && ImGui::IsMouseHoveringRect(b0, b1);
            over_button = over_button || hover;
            if (hover) dl->AddRectFilled(b0, b1, ImGui::GetColorU32(ImGuiCol_ButtonHovered), 3.0f);
            const ImU32 col = hover ? pal.title_text : pal.axis_text;
            const float m = std::round(0.28f * (b1.y - b0.y));
            const ImVec2 mid(0.5f * (b0.x + b1.x), 0.5f * (b0.y + b1.y));
            const bool is_hide = !presenting && b == 0;
            if (is_hide) {   // a cross
                dl->AddLine(ImVec2(mid.x - m, mid.y - m), ImVec2(mid.x + m, mid.y + m), col, 1.5f * view_.ui_scale);
                dl->AddLine(ImVec2(mid.x - m, mid.y + m), ImVec2(mid.x + m, mid.y - m), col, 1.5f * view_.ui_scale);
            } else if (layout_.maximised == active) {   // restore: two frames
                dl->AddRect(ImVec2(mid.x - m + 3, mid.y - m), ImVec2(mid.x + m, mid.y + m - 3), col, 0, 0, 1.2f * view_.ui_scale);
                dl->AddRectFilled(ImVec2(mid.x - m, mid.y - m + 3), ImVec2(mid.x + m - 3, mid.y + m),
                                  ImGui::GetColorU32(ImGuiCol_TitleBgActive));
                dl->AddRect(ImVec2(mid.x - m, mid.y - m + 3), ImVec2(mid.x + m - 3, mid.y + m), col, 0, 0, 1.2f * view_.ui_scale);
            } else {   // maximise: one frame
                dl->AddRect(ImVec2(mid.x - m, mid.y - m), ImVec2(mid.x + m, mid.y + m), col, 0, 0, 1.4f * view_.ui_scale);
            }
            if (hover) {
                ImGui::SetTooltip("%s", is_hide ? "hide this panel (View > Panels shows it again)"
                                                : layout_.maximised == active ? "restore the layout (Z or Esc)"
                                                                       : "maximise (Z over a panel, or double-click its title)");
                if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                    if (is_hide) set_panel_visible(active, false);
                    else toggle_maximised(active);
                }
            }
        }
        if (!over_button && window_hovered && ImGui::IsMouseHoveringRect(t0, t1) && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left))
            toggle_maximised(active);
        dl->PopClipRect();
        if (window_hovered) layout_.hovered_panel = active;

        if (tile.panels.size() == 1) {
            draw_panel(active);
        } else if (ImGui::BeginTabBar("##tabs", ImGuiTabBarFlags_FittingPolicyScroll)) {
            const bool focus = layout_.focus_tab && std::find(tile.panels.begin(), tile.panels.end(), *layout_.focus_tab) != tile.panels.end();
            for (PanelId p : tile.panels) {
                const ImGuiTabItemFlags flags = focus && p == *layout_.focus_tab ? ImGuiTabItemFlags_SetSelected : 0;
                if (ImGui::BeginTabItem((tab_label(p) + "###" + panel_key(p)).c_str(), nullptr, flags)) {
                    layout_.tile_tab[key] = p;
                    draw_panel(p);
                    ImGui::EndTabItem();
                }
            }
            ImGui::EndTabBar();
            if (focus) layout_.focus_tab.reset();
        }
    }
    ImGui::End();
}

// The controls column: its three groups stacked, or as tabs when the column is too short for them (the
// layout decides from the groups' heights, measured whenever all three are drawn).
void App::draw_controls() {
    struct Group {
        const char* name;
        void (App::*draw)();
    };
    static constexpr Group kGroups[3] = {{"Run", &App::draw_controls_run}, {"View", &App::draw_controls_view},
                                         {"State", &App::draw_controls_state}};
    static constexpr int kTabOrder[3] = {0, 2, 1};   // Run, State, View
    if (layout_.controls_measured_scale != view_.ui_scale) {   // new fonts: measure every section stacked again
        layout_.controls_measured_scale = view_.ui_scale;
        for (float& h : layout_.controls_group_h) h = 0;
        layout_.controls_need_h = 0;
        return;   // this frame's layout was made with the old heights
    }
    auto measured = [&](int i) {
        const float y0 = ImGui::GetCursorPosY();
        (this->*kGroups[i].draw)();
        layout_.controls_group_h[static_cast<std::size_t>(i)] = ImGui::GetCursorPosY() - y0;
    };
    if (!layout_.frame.controls_tabbed) {
        for (int i = 0; i < 3; ++i) measured(i);
        layout_.controls_tab = -1;   // every group shows (a focus asked for waits: the first frames measure untabbed)
    } else if (ImGui::BeginTabBar("##controls_tabs")) {
        for (int i : kTabOrder) {
            // A demonstration may name a group (demo 4: the energy balance under State): it comes to the front.
            const ImGuiTabItemFlags flags = layout_.controls_focus == i ? ImGuiTabItemFlags_SetSelected : 0;
            if (ImGui::BeginTabItem(kGroups[i].name, nullptr, flags)) {
                layout_.controls_tab = i;
                measured(i);
                ImGui::EndTabItem();
            }
        }
        ImGui::EndTabBar();
        layout_.controls_focus = -1;
    }
    float need = 0;
    bool all = true;
    for (float h : layout_.controls_group_h) {
        need += h;
        all = all && h > 0;
    }
    // The column's chrome: its title bar and padding.
    layout_.controls_need_h = all ? need + ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().WindowPadding.y : 0.0f;
}

void App::set_panel_visible(PanelId p, bool on) {
    layout_.panel_visible[static_cast<std::size_t>(p)] = on;
    if (!on && layout_.maximised == p) layout_.maximised.reset();
    // An analysis tile opened where the layout has no room makes a tab: it comes to the front, or F2 would
    // seem to do nothing.
    if (on && on_demand(p)) layout_.focus_tab = p;
}

LayoutRequest App::layout_request(const Rect& area) const {
    LayoutRequest r;
    r.area = area;
    r.scale = view_.ui_scale;
    r.frame_h = ImGui::GetFrameHeight();
    r.mode = layout_.mode;
    r.controls_visible = layout_.controls_visible;
    r.controls_need_h = layout_.controls_need_h;
    r.visible = layout_.panel_visible;
    r.maximised = layout_.maximised;
    r.featured = layout_.featured;
    return r;
}

void App::layout_and_draw() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const bool presenting = layout_.mode == LayoutMode::Presentation;
    // Presentation mode: no menu and no status bar (the slim bar has what a lecture needs; P leaves).
    float menu_h = 0, status_h = 0;
    if (!presenting) {
        draw_menu();
        menu_h = ImGui::GetFrameHeight();
        status_h = std::round(ImGui::GetFrameHeight() + 6.0f * view_.ui_scale);
    }
    const Rect area{vp->Pos.x, vp->Pos.y + menu_h, vp->Size.x, vp->Size.y - menu_h - status_h};
    layout_.frame = compute_layout(layout_request(area));
    layout_.hovered_panel.reset();

    set_plot_backdrops_by_clear(true);   // the tiles draw no background: frame() clears under their plots
    if (!layout_.frame.controls.empty()) {
        if (begin_tile_at("Controls###controls", layout_.frame.controls)) {
            const auto t0 = std::chrono::steady_clock::now();
            draw_controls();
            if (bench_.on) bench_.panel_s[0] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        ImGui::End();
    }
    if (!layout_.frame.bar.empty()) {
        ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f * view_.ui_scale, 4.5f * view_.ui_scale));
        if (begin_tile_at("##presentation_bar", layout_.frame.bar, ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar))
            draw_presentation_bar();
        ImGui::End();
        ImGui::PopStyleVar();
    }
    for (const Tile& t : layout_.frame.tiles) draw_tile(t);
    set_plot_backdrops_by_clear(false);   // floating windows (data panel) draw their own
    if (nothing_shown()) {
        // Every panel hidden: a blank window would look broken, so say how to get them back.
        const char* hint = "Every panel is hidden.  View > Panels shows them again.";
        const ImVec2 ts = ImGui::CalcTextSize(hint);
        ImGui::GetBackgroundDrawList()->AddText(ImVec2(area.x + 0.5f * (area.w - ts.x), area.y + 0.5f * (area.h - ts.y)),
                                                palette().axis_text, hint);
    }

    if (!presenting) {
        ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f * view_.ui_scale, 3.0f * view_.ui_scale));
        if (begin_tile_at("##status", {vp->Pos.x, vp->Pos.y + vp->Size.y - status_h, vp->Size.x, status_h},
                          ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar))
            draw_status();
        ImGui::End();
        ImGui::PopStyleVar();
    }

    data_panel_.poll(data_context());
    if (view_.show_data) data_panel_.draw(&view_.show_data, data_context());
    if (demos_.show)
        if (const GuideAction ga = demos_.panel.draw(&demos_.show, demos_.last); ga.demo) {
            run_demo(ga.demo);
            demos_.panel.move_aside();
        }
    if (view_.show_params) {
        const ParamsAction pa = params_panel_.draw(&view_.show_params, {&run_.params, model_name(), view_.ui_scale});
        if (pa.set) set_param(pa.set->first, pa.set->second);
        if (pa.reset) reset_params();
    }
    apply_analysis(analysis_.poll(analysis_context()));
    if (view_.show_help) draw_help();
    draw_toast();
}

// Presentation mode's slim bar: play, ω and x_I, the presets, the magnification, which plot, exit. One row
// where the width holds it, else two (layout_.frame.bar_lines).
void App::draw_presentation_bar() {
    const float fs = ImGui::GetFontSize();
    const float sp = ImGui::GetStyle().ItemSpacing.x;
    const float full = ImGui::GetContentRegionAvail().x;
    if (ImGui::Button(run_.paused ? "Play" : "Pause", ImVec2(4.2f * fs, 0))) set_paused(!run_.paused);
    ImGui::SameLine();
    // Line 1: the two sliders share what is left of the row (of the first half when one row holds all).
    const float row = layout_.frame.bar_lines > 1 ? full : 0.52f * full;
    const float slider_w = std::max(6.0f * fs, 0.5f * (row - 4.2f * fs - 3.0f * sp));
    float w = static_cast<float>(run_.omega);
    ImGui::SetNextItemWidth(slider_w);
    if (ImGui::SliderFloat("##p_omega", &w, 0.0f, 30.0f, "ω = %.2f rad/s")) set_omega(w);
    ImGui::SameLine();
    float xi_mm = static_cast<float>(run_.xI * 1e3);
    ImGui::SetNextItemWidth(slider_w);
    if (ImGui::SliderFloat("##p_xI", &xi_mm, -20.0f, 20.0f, "x_I = %.1f mm")) set_xi(xi_mm * 1e-3);
    if (layout_.frame.bar_lines == 1) ImGui::SameLine(0, 2.0f * sp);
    // Line 2 (or the second half): presets, magnification, the plot, exit.
    const auto list = presets_for(model_name());
    const char* exit_label = "Exit (P)";
    const float exit_w = button_width(exit_label);
    // The presets' full names when the row holds them beside the magnification, the plot picker and Exit;
    // their numbers alone otherwise (a projector's 1024 px at UI scale 2), named in their tooltips.
    float full_w = 7.5f * fs + 5.0f * fs + exit_w + 3.0f * sp;
    for (std::size_t i = 0; i < list.size(); ++i) full_w += button_width((std::to_string(i + 1) + " " + list[i].label).c_str()) + sp;
    const bool short_presets = full_w > ImGui::GetContentRegionAvail().x;
    for (std::size_t i = 0; i < list.size(); ++i) {
        char label[64];
        if (short_presets) std::snprintf(label, sizeof label, "%zu###p_preset%zu", i + 1, i);
        else std::snprintf(label, sizeof label, "%zu %s###p_preset%zu", i + 1, list[i].label, i);
        if (ImGui::Button(label)) apply_preset(list[i]);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("key %zu, %s: %s", i + 1, list[i].label, list[i].note);
        ImGui::SameLine();
    }
    float g = static_cast<float>(magnification());
    ImGui::SetNextItemWidth(7.5f * fs);
    if (ImGui::SliderFloat("##p_magnify", &g, 1.0f, 10.0f, "disp. ×%.1f")) set_magnification(g);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the rig's displacement magnification (the drawing only)");
    ImGui::SameLine();
    const float combo_w = std::max(5.0f * fs, ImGui::GetContentRegionAvail().x - exit_w - sp);
    ImGui::SetNextItemWidth(std::min(combo_w, 9.0f * fs));
    if (ImGui::BeginCombo("##p_plot", tab_label(layout_.featured).c_str())) {
        for (PanelId p : presentation_plots())
            if (ImGui::Selectable(tab_label(p).c_str(), p == layout_.featured)) layout_.featured = p;
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the plot beside the rig (V: the next one)");
    ImGui::SameLine(std::max(ImGui::GetCursorPosX(), ImGui::GetWindowContentRegionMax().x - exit_w));
    if (ImGui::Button(exit_label)) set_presentation(false);
}

// View > Panels, Maximise, Presentation (the menu is in panels.cpp's draw_menu).
void App::draw_view_menu_panels() {
    if (ImGui::MenuItem("Presentation mode", "P", layout_.mode == LayoutMode::Presentation)) set_presentation(layout_.mode != LayoutMode::Presentation);
    if (ImGui::BeginMenu("Presentation plot")) {
        for (PanelId p : presentation_plots())
            if (ImGui::MenuItem(tab_label(p).c_str(), nullptr, layout_.featured == p)) layout_.featured = p;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Panels")) {
        ImGui::MenuItem("Controls", nullptr, &layout_.controls_visible);
        for (int i = 0; i < kPanelCount; ++i) {
            const PanelId p = static_cast<PanelId>(i);
            if (ImGui::MenuItem(titles_of(p, 1.0).front().c_str(), nullptr, layout_.panel_visible[static_cast<std::size_t>(i)]))
                set_panel_visible(p, !layout_.panel_visible[static_cast<std::size_t>(i)]);
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Show all")) {
            for (int i = 0; i < kPanelCount; ++i)   // the analysis tiles stay open or closed
                if (!on_demand(static_cast<PanelId>(i))) layout_.panel_visible[static_cast<std::size_t>(i)] = true;
            layout_.controls_visible = true;
        }
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Maximise")) {
        for (int i = 0; i < kPanelCount; ++i) {
            const PanelId p = static_cast<PanelId>(i);
            if (ImGui::MenuItem(titles_of(p, 1.0).front().c_str(), nullptr, layout_.maximised == p)) {
                set_panel_visible(p, true);
                toggle_maximised(p);
            }
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Restore", "Esc", false, layout_.maximised.has_value())) layout_.maximised.reset();
        ImGui::EndMenu();
    }
    float g = static_cast<float>(magnification());
    ImGui::SetNextItemWidth(8.0f * ImGui::GetFontSize());
    if (ImGui::SliderFloat("##menu_magnify", &g, 1.0f, 10.0f, "rig displacement ×%.1f")) set_magnification(g);
}

// What --state-json reports of the layout (UI thread, after the last frame): the mode, the UI scale (and
// the user's, which presentation mode raised), the panels shown, hidden and maximised, the tiles as drawn
// (rectangles [x, y, w, h] in pixels, a tile's panels in tab order) and the rig's magnification.
nlohmann::json App::layout_json() const {
    using nlohmann::json;
    json j;
    j["mode"] = layout_.mode == LayoutMode::Presentation ? "presentation" : "normal";
    j["ui_scale"] = view_.ui_scale;
    j["ui_scale_normal"] = layout_.mode == LayoutMode::Presentation ? layout_.normal_scale : view_.ui_scale;
    j["font_px"] = ImGui::GetFontSize();
    j["magnification"] = magnification();
    j["presentation_plot"] = panel_key(layout_.featured);
    j["maximised"] = layout_.maximised ? json(panel_key(*layout_.maximised)) : json(nullptr);
    json shown = json::array(), hidden = json::array();
    if (!layout_.frame.controls.empty()) shown.push_back("controls");
    else if (!layout_.controls_visible) hidden.push_back("controls");
    for (const Tile& t : layout_.frame.tiles)
        for (PanelId p : t.panels) shown.push_back(panel_key(p));
    for (int i = 0; i < kPanelCount; ++i)   // a closed analysis tile is not a hidden one
        if (!layout_.panel_visible[static_cast<std::size_t>(i)] && !on_demand(static_cast<PanelId>(i)))
            hidden.push_back(panel_key(static_cast<PanelId>(i)));
    j["visible_panels"] = std::move(shown);
    j["hidden_panels"] = std::move(hidden);
    j["nothing_shown_hint"] = nothing_shown();   // every panel hidden: the window says how to show them
    auto rect = [](const Rect& r) { return json::array({r.x, r.y, r.w, r.h}); };
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    j["viewport"] = json::array({vp->Pos.x, vp->Pos.y, vp->Size.x, vp->Size.y});
    j["controls"] = layout_.frame.controls.empty() ? json(nullptr) : rect(layout_.frame.controls);
    j["controls_tabbed"] = layout_.frame.controls_tabbed;
    j["bar"] = layout_.frame.bar.empty() ? json(nullptr) : rect(layout_.frame.bar);
    json tiles = json::array();
    for (const Tile& t : layout_.frame.tiles) {
        json panels = json::array();
        for (PanelId p : t.panels) panels.push_back(panel_key(p));
        tiles.push_back({{"rect", rect(t.rect)}, {"panels", std::move(panels)}});
    }
    j["tiles"] = std::move(tiles);
    return j;
}

// Keys of the layout (App::handle_keys calls this): P presentation, V its next plot, Z maximise the panel
// under the mouse (or restore), Esc restore / leave presentation.
void App::handle_layout_keys() {
    auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
    const ImGuiIO& io = ImGui::GetIO();
    if (io.KeyCtrl || io.KeyAlt) return;
    if (pressed(GLFW_KEY_P)) set_presentation(layout_.mode != LayoutMode::Presentation);
    if (pressed(GLFW_KEY_V) && layout_.mode == LayoutMode::Presentation) {
        const auto& all = presentation_plots();
        const auto it = std::find(all.begin(), all.end(), layout_.featured);
        layout_.featured = it == all.end() || it + 1 == all.end() ? all.front() : *(it + 1);
    }
    if (pressed(GLFW_KEY_Z)) {
        if (layout_.maximised) layout_.maximised.reset();
        else if (layout_.hovered_panel) layout_.maximised = *layout_.hovered_panel;
    }
    if (pressed(GLFW_KEY_ESCAPE)) {
        if (layout_.maximised) layout_.maximised.reset();
        else if (layout_.mode == LayoutMode::Presentation) set_presentation(false);
    }
}

}  // namespace impactlab::gui
