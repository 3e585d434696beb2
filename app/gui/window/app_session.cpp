// Session files: the App's side of session.hpp. current_session() gathers what the window shows;
// apply_session() sets it through the same actions as the controls (commands to the simulation thread) and
// restarts the run from the saved state. A file is validated whole before anything changes. UI thread only.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "window/app.hpp"
#include "sim/param_edit.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
constexpr const char* kProtocols[] = {"cf-up", "cf-down", "ef"};
constexpr const char* kSessionName = "impactlab-session.json";   // a session saved into a folder
}  // namespace

Session App::current_session() const {
    Session s;
    s.model = model_name();
    s.omega = run_.omega;
    s.xI = run_.xI;
    s.speed = run_.speed;
    // Replaying: the instant shown, paused (as the simulation is); live: the newest state.
    const bool replaying = replay_.player.active() && !feed_.traj.empty();
    const SimMsg m = replaying ? feed_.traj[sample_at(feed_.traj, replay_.player.cursor())] : feed_.last;
    s.paused = run_.paused || replaying;
    if (feed_.have_last || replaying) {
        s.t = m.t;
        s.x = m.x;
        s.v = m.v;
        s.phi = m.phi;
    } else {
        s.x = run_.x0;
    }
    s.dark = view_.dark;
    s.ui_scale = layout_.mode == LayoutMode::Presentation ? layout_.normal_scale : view_.ui_scale;   // presenting raised it
    s.presentation = layout_.mode == LayoutMode::Presentation;
    if (!layout_.controls_visible) s.hidden.push_back("controls");
    for (int i = 0; i < kPanelCount; ++i)   // the analysis tiles are not saved (nor their results)
        if (!layout_.panel_visible[static_cast<std::size_t>(i)] && !on_demand(static_cast<PanelId>(i)))
            s.hidden.push_back(panel_key(static_cast<PanelId>(i)));
    s.maximised = layout_.maximised ? panel_key(*layout_.maximised) : "";
    s.presentation_plot = panel_key(layout_.featured);
    s.magnify = layout_.magnify[0];
    s.magnify_presentation = layout_.magnify[1];
    s.trail_periods = view_.trail_periods;
    s.strip_window = view_.strip_window;
    s.poincare_phi0 = view_.section_phase;
    for (const Plot::NamedView& v : Plot::user_views()) s.views.push_back({v.id, v.x.lo, v.x.hi, v.y.lo, v.y.hi});
    s.show_data = view_.show_data;
    s.show_help = view_.show_help;
    s.bif_protocol = kProtocols[std::clamp(bif_.protocol, 0, 2)];
    s.bif_steps = bif_.steps;
    s.data = data_panel_.loaded_path();
    s.companion = companion_.mode == CompanionMode::Twin ? "twin" : companion_.mode == CompanionMode::Ghost ? "ghost" : "off";
    s.ghost_impact = impact_models()[static_cast<std::size_t>(companion_.ghost_impact)].id;
    for (const EditableParam& e : editable_params(run_.params))
        if (e.value != e.paper) s.params.emplace_back(e.key, e.value);
    s.strip = {strip_key(strip_.first())};
    if (const auto q = strip_.second()) s.strip.push_back(strip_key(*q));
    s.clicker = poincare_.clicker();
    for (const ClickedOrbit& o : poincare_.orbits()) s.orbits.push_back({o.x0, o.v0, o.pts});
    return s;
}

void App::apply_session(const Session& s) {
    leave_replay();
    const Params p = make_version(s.model);   // valid: session_from_json checked it
    int stiffness = 0, impact = 0;
    for (std::size_t i = 0; i < stiffness_sets().size(); ++i)
        if (p.stiffness_id == stiffness_sets()[i].id) stiffness = static_cast<int>(i);
    for (std::size_t i = 0; i < impact_models().size(); ++i)
        if (p.impact && std::string(impact_models()[i].id) == p.impact->id) impact = static_cast<int>(i);
    set_model(stiffness, impact);
    set_xi(s.xI);
    // The session's edits on the version's own values (checked when the file was read).
    if (params_edited(run_.params) || !s.params.empty()) reset_params();
    for (const auto& [key, value] : s.params) set_param(key, value);
    set_omega(s.omega);
    set_speed(s.speed);
    set_section_phase(s.poincare_phi0);   // before the restart: its sections are at the session's phase
    // The run goes on from the saved instant; what the history held belongs to another run.
    restart_sim(s.x, s.v, s.t, s.phi, s.omega, true);
    set_paused(s.paused);
    for (std::size_t i = 0; i < impact_models().size(); ++i)
        if (s.ghost_impact == impact_models()[i].id) companion_.ghost_impact = static_cast<int>(i);
    const CompanionMode mode = s.companion == "twin"    ? CompanionMode::Twin
                               : s.companion == "ghost" ? CompanionMode::Ghost
                                                        : CompanionMode::Off;
    if (mode != companion_.mode || mode == CompanionMode::Ghost) set_companion(mode);
    if (view_.dark != s.dark) {
        view_.dark = s.dark;
        apply_theme(view_.dark, view_.ui_scale);
        bif_.dirty = true;
    }
    set_presentation(false);   // back to the user's scale before the session's
    if (view_.ui_scale != static_cast<float>(s.ui_scale)) {
        view_.ui_scale = static_cast<float>(s.ui_scale);
        view_.fonts_dirty = true;
    }
    layout_.controls_visible = true;
    for (int i = 0; i < kPanelCount; ++i)
        if (!on_demand(static_cast<PanelId>(i))) layout_.panel_visible[static_cast<std::size_t>(i)] = true;
    for (const std::string& h : s.hidden) {
        if (h == "controls") layout_.controls_visible = false;
        else if (const auto panel = panel_from_key(h)) layout_.panel_visible[static_cast<std::size_t>(*panel)] = false;
    }
    if (const auto plot = panel_from_key(s.presentation_plot)) layout_.featured = *plot;
    layout_.magnify[0] = s.magnify;
    layout_.magnify[1] = s.magnify_presentation;
    set_presentation(s.presentation);   // raises the scale to 1.5 at least, and clears a maximised panel
    layout_.maximised.reset();
    if (const auto panel = panel_from_key(s.maximised)) layout_.maximised = *panel;
    view_.trail_periods = static_cast<float>(s.trail_periods);
    view_.strip_window = static_cast<float>(s.strip_window);
    std::vector<Plot::NamedView> views;
    for (const SessionView& v : s.views) views.push_back({v.id, {v.x_lo, v.x_hi}, {v.y_lo, v.y_hi}});
    Plot::restore_user_views(views);
    view_.show_data = s.show_data || !s.data.empty();
    view_.show_help = s.show_help;
    for (int i = 0; i < 3; ++i)
        if (s.bif_protocol == kProtocols[i]) bif_.protocol = i;
    bif_.steps = s.bif_steps;
    if (!s.data.empty() && s.data != data_panel_.loaded_path()) data_panel_.load(s.data, false);
    const auto first = strip_from_key(s.strip.empty() ? "x" : s.strip[0]);
    strip_.set_traces(first.value_or(StripQuantity::X), s.strip.size() > 1 ? strip_from_key(s.strip[1]) : std::nullopt);
    // After the restart above: the orbits are shown as saved, not fed by the new run.
    std::vector<ClickedOrbit> orbits;
    for (const SessionOrbit& o : s.orbits) {
        ClickedOrbit c;
        c.x0 = o.x0;
        c.v0 = o.v0;
        c.pts = o.points;
        orbits.push_back(std::move(c));
    }
    poincare_.restore_orbits(std::move(orbits));
    poincare_.set_clicker(s.clicker);
}

bool App::save_session_file(const std::string& path) {
    try {
        save_session(current_session(), path);
    } catch (const SessionError& e) {
        session_.error = e.what();
        toast(std::string("session not saved: ") + e.what());
        return false;
    }
    session_.error.clear();
    toast("session saved: " + path);
    return true;
}

bool App::load_session_file(const std::string& path) {
    Session s;
    try {
        s = load_session(path, current_session());
    } catch (const SessionError& e) {
        // Nothing was applied: the program goes on as it was.
        session_.error = e.what();
        toast(std::string("session not loaded: ") + e.what());
        return false;
    }
    session_.error.clear();
    apply_session(s);
    toast("session loaded: " + path);
    return true;
}

void App::open_session_window(bool save) {
    session_.open = true;
    session_.saving = save;
    session_.error.clear();
    session_.overwrite_pending.clear();
}

void App::draw_session_window() {
    if (!session_.open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    const char* title = session_.saving ? "Save session###session" : "Load session###session";
    if (ImGui::Begin(title, &session_.open,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        ImGui::TextUnformatted(session_.saving
                                   ? "Model, ω, x_I, speed, the state (x, v, t, φ), theme, UI scale, zoomed views,\n"
                                     "open windows, trail, the diagram's settings and the data file, as JSON."
                                   : "Loads a session file; a bad file changes nothing and says why.");
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 24);
        const bool enter = ImGui::InputText("file", session_.path, sizeof session_.path, ImGuiInputTextFlags_EnterReturnsTrue);
        // The session files beside the path: a click picks one, a double-click also saves or loads it.
        const bool picked = session_.browser.draw("##session_files", session_.path, sizeof session_.path);
        // Saving over a file asks first (a double-click on a row says "save", not "overwrite").
        if (!session_.overwrite_pending.empty() && session_.overwrite_pending != save_target(session_.path, kSessionName)) session_.overwrite_pending.clear();
        if (session_.saving && !session_.overwrite_pending.empty()) {
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s exists. Overwrite it?", session_.overwrite_pending.c_str());
            if (ImGui::Button("Overwrite")) session_.request = 3;
            ImGui::SameLine();
            if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) session_.overwrite_pending.clear();
        } else {
            if (ImGui::Button(session_.saving ? "Save" : "Load") || enter || picked) session_.request = session_.saving ? 1 : 2;
            ImGui::SameLine();
            if (ImGui::Button("Close")) session_.open = false;
        }
        if (!session_.error.empty()) {
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32);
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", session_.error.c_str());
            ImGui::PopTextWrapPos();
        }
    }
    ImGui::End();
}

void App::handle_session_request() {
    // After the panels drew (the histories are live again): what the session window asked for.
    const int req = session_.request;
    session_.request = 0;
    if (req == 1 || req == 3) {
        // A folder typed or entered means a file in it; an existing file is written only once confirmed.
        const std::string target = save_target(session_.path, kSessionName);
        std::snprintf(session_.path, sizeof session_.path, "%s", target.c_str());
        std::error_code ec;
        if (req == 1 && std::filesystem::exists(target, ec)) {
            session_.overwrite_pending = target;
            return;
        }
        session_.overwrite_pending.clear();
        if (save_session_file(target)) session_.open = false;
    }
    if (req == 2 && load_session_file(session_.path)) session_.open = false;
}

}  // namespace impactlab::gui
