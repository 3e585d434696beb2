// The window's chrome around the tiles: the main menu bar, the status bar, the help window and the toast.
// The tiles are tiles.cpp's, the controls column controls.cpp's, the views app/gui/views/. UI thread.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "window/app.hpp"
#include "views/contact_label.hpp"
#include "views/energy_bar.hpp"
#include "render/gl_util.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/sweep.hpp"
#include "render/theme.hpp"
#include "views/view_fit.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

void App::draw_menu() {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Screenshot (PNG)", "F12")) screenshot(screenshot_name());
        if (ImGui::MenuItem("Export trajectory + sections (CSV)", "Ctrl+E")) export_csv();
        if (ImGui::MenuItem("Export clip (PNG frames, video)...")) clip_.window = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Save session...", "Ctrl+S")) open_session_window(true);
        if (ImGui::MenuItem("Load session...", "Ctrl+O")) open_session_window(false);
        ImGui::Separator();
        if (ImGui::MenuItem("Measured data (load, fit, effects)...", nullptr, view_.show_data)) view_.show_data = !view_.show_data;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) glfwSetWindowShouldClose(win_, 1);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Simulation")) {
        if (ImGui::MenuItem(run_.paused ? "Play" : "Pause", "Space")) set_paused(!run_.paused);
        if (ImGui::MenuItem("Step one forcing period", "N")) step_period();
        if (ImGui::MenuItem("Reset (t = 0, from x0 at rest)", "R")) reset();
        ImGui::Separator();
        if (ImGui::MenuItem("Faster x2", "]")) set_speed(run_.speed * 2);
        if (ImGui::MenuItem("Slower /2", "[")) set_speed(run_.speed / 2);
        if (ImGui::MenuItem("Real time (1x)")) set_speed(1.0);
        ImGui::Separator();
        if (ImGui::MenuItem("Clear Poincare map", "C")) clear_poincare();
        ImGui::Separator();
        if (ImGui::MenuItem("Replay the last minutes", "Shift+R", replay_.player.active())) {
            if (replay_.player.active()) replay_.request = ReplayRequest::Leave;
            else enter_replay();
        }
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        draw_view_menu_panels();   // tiles.cpp: presentation, panels, maximise, magnification
        ImGui::Separator();
        if (ImGui::MenuItem("Parameters (m, c, k, ..., the impact law's)...", "F4", view_.show_params)) view_.show_params = !view_.show_params;
        if (ImGui::MenuItem("Details in the status bar (epoch, samples, dropped)", nullptr, view_.details)) view_.details = !view_.details;
        if (ImGui::MenuItem("Dark theme", "T", view_.dark)) {
            view_.dark = !view_.dark;
            apply_theme(view_.dark, view_.ui_scale);
            bif_.dirty = true;
        }
        if (ImGui::BeginMenu("UI scale")) {
            for (float s : {0.75f, 1.0f, 1.25f, 1.5f, 2.0f, 2.5f, 3.0f}) {
                char label[16];
                std::snprintf(label, sizeof label, "%.0f%%", s * 100);
                if (ImGui::MenuItem(label, nullptr, std::abs(view_.ui_scale - s) < 0.01f)) {
                    view_.ui_scale = s;
                    view_.fonts_dirty = true;
                }
            }
            ImGui::EndMenu();
        }
        ImGui::EndMenu();
    }
    apply_analysis(analysis_.menu(analysis_context()));
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("What to try (five demonstrations)...", nullptr, demos_.show)) demos_.show = !demos_.show;
        if (ImGui::MenuItem("Keyboard shortcuts", "F1")) view_.show_help = true;
        ImGui::EndMenu();
    }
    // Right side: model, omega, fps.
    char right[96];
    std::snprintf(right, sizeof right, "%s   ω %.2f rad/s   %.0f fps", model_name().c_str(), run_.omega, frames_.fps);
    const float w = ImGui::CalcTextSize(right).x;
    ImGui::SameLine(ImGui::GetWindowWidth() - w - 14.0f * view_.ui_scale);
    ImGui::TextDisabled("%s", right);
    ImGui::EndMainMenuBar();
}

void App::draw_status() {
    if (replay_.player.active()) {   // the bar becomes the replay's timeline (app_replay.cpp)
        draw_replay_bar();
        return;
    }
    const SimStatus st = sim_->status();
    const Palette& pal = palette();
    ImGui::Text("t = %.2f s", feed_.last.t);
    ImGui::SameLine(0, 18);
    ImGui::TextDisabled("|");
    ImGui::SameLine(0, 18);
    if (script_.warming) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "warming up at 100x to t = %.0f s", opt_.warmup);
    else if (st.paused) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "paused");
    else if (st.lagging)
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "speed %.2fx asked, %.2fx achieved (model too slow)",
                           run_.speed, st.achieved_speed);
    else ImGui::Text("speed %.2fx (achieved %.2fx)", run_.speed, st.achieved_speed);
    if (commands_.waiting() > 0 || commands_.lost() > 0) {   // the simulation thread is not taking commands
        ImGui::SameLine(0, 18);
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "commands: %zu waiting, %llu lost", commands_.waiting(),
                           static_cast<unsigned long long>(commands_.lost()));
    }
    const char* help = "F1: shortcuts";
    const char* replay = "Replay";
    // The fields after the speed only where they fit before the buttons on the right (a large UI scale or a
    // narrow window drops the least useful first: the regime stays, then the samples, then the epoch).
    const float right_w = ImGui::CalcTextSize(help).x + ImGui::CalcTextSize(replay).x + 2 * ImGui::GetStyle().FramePadding.x +
                          48.0f * view_.ui_scale;
    char epoch[32], samples[64];
    std::snprintf(epoch, sizeof epoch, "epoch %u", feed_.epoch);
    std::snprintf(samples, sizeof samples, "samples %.2fM, dropped %llu", static_cast<double>(feed_.samples_seen) / 1e6,
                  static_cast<unsigned long long>(st.dropped));
    const char* regime = contact_label(run_.params, feed_.last.regime, feed_.last.force);
    const float sep = ImGui::CalcTextSize("|").x + 36.0f;
    float room = ImGui::GetWindowWidth() - right_w - (ImGui::GetItemRectMax().x - ImGui::GetWindowPos().x);
    // The epoch and the ring's counts are the simulation's bookkeeping: shown with View > Details only.
    const char* fields[3] = {view_.details ? epoch : "", view_.details ? samples : "", regime};
    for (const char* field : fields)
        if (*field) room -= sep + ImGui::CalcTextSize(field).x;
    bool drop[3] = {};
    for (int i = 0; i < 3 && room < 0; ++i) {
        if (!*fields[i]) continue;
        drop[i] = true;
        room += sep + ImGui::CalcTextSize(fields[i]).x;
    }
    for (int i = 0; i < 3; ++i) {
        if (drop[i] || !*fields[i]) continue;
        const char* field = fields[i];
        ImGui::SameLine(0, 18);
        ImGui::TextDisabled("|");
        ImGui::SameLine(0, 18);
        ImGui::TextUnformatted(field);
    }
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(help).x - ImGui::CalcTextSize(replay).x -
                    ImGui::GetStyle().FramePadding.x * 2 - 30.0f * view_.ui_scale);
    if (ImGui::SmallButton(replay)) enter_replay();
    tooltip("Shift+R: scrub back through the last minutes (the simulation pauses)");
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(help).x - 12.0f * view_.ui_scale);
    ImGui::TextDisabled("%s", help);
}

void App::draw_help() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Keyboard shortcuts", &view_.show_help,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        static const char* keys[][2] = {
            {"Space", "play / pause"},
            {"N  or  .", "step one forcing period (to the next Poincare section)"},
            {"R", "reset: t = 0, cart at rest in the left well"},
            {"Left / Right", "ω -/+ 0.1 rad/s (Shift: 1 rad/s)"},
            {"Up / Down", "bumper x_I +/- 0.5 mm (Shift: 2 mm)"},
            {"[  /  ]", "speed / 2, x 2 (0.01x .. 100x)"},
            {"M", "next impact model (C, C1, G, H), live"},
            {"K", "next stiffness (A1, A3), live"},
            {"1 .. 4", "presets: period 1, period 2, chaos, periodic window"},
            {"B", "compute (or cancel) the bifurcation diagram"},
            {"O", "continue the periodic orbits over the diagram's ω range (or cancel)"},
            {"F2, F3", "parameter plane (ω, x_I), basins of attraction at ω"},
            {"F4", "parameters of the running model (m, c, k, T, m0e, eps, the impact law's)"},
            {"click diagram", "set ω there"},
            {"click phase / well", "start the cart from that (x, v) / that x at rest"},
            {"drag the cart", "hold it at the mouse; let go: from there at rest"},
            {"right-drag diagram", "compute the ω range of the box (column by column)"},
            {"C", "clear the Poincare map"},
            {"T", "dark / light theme"},
            {"P", "presentation mode: the rig and one plot, large (V: the next plot)"},
            {"Z", "maximise the panel under the mouse, or restore"},
            {"Esc", "restore a maximised panel, leave presentation mode"},
            {"Ctrl + / Ctrl -", "UI scale"},
            {"F12", "screenshot (PNG)"},
            {"Ctrl+S, Ctrl+O", "save, load a session (JSON)"},
            {"Shift+R", "replay: scrub back (Space play, Left/Right a period, , . a sample,"},
            {"", "  Enter continue from there, Esc back to live)"},
            {"Ctrl+E", "export trajectory and sections (CSV)"},
            {"F1, H", "this window"},
            {"Ctrl+Q", "quit"},
        };
        if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const auto& k : keys) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                ImGui::TextColored(ImGui::GetStyle().Colors[ImGuiCol_SliderGrab], "%s", k[0]);
                ImGui::TableSetColumnIndex(1);
                ImGui::TextUnformatted(k[1]);
            }
            ImGui::EndTable();
        }
        ImGui::Spacing();
        ImGui::TextDisabled("impactlab %s  -  Dear ImGui %s", IMPACTLAB_VERSION, IMGUI_VERSION);
    }
    ImGui::End();
}

void App::draw_toast() {
    if (!toast_.visible(now_s()) || opt_.frames > 0) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float pad = 14.0f * view_.ui_scale;
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - pad, vp->Pos.y + vp->Size.y - pad - ImGui::GetFrameHeight() * 1.5f),
                            ImGuiCond_Always, ImVec2(1, 1));
    ImGui::SetNextWindowBgAlpha(0.92f);
    if (ImGui::Begin("##toast", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav))
        ImGui::TextUnformatted(toast_.text.c_str());
    ImGui::End();
}

}  // namespace impactlab::gui
