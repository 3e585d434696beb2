// Replay and clip export: the App's side of replay.hpp and clip_writer.hpp.
// While replaying, the simulation is paused and every panel draws feed_.traj, feed_.sections and feed_.last as they were at
// the cursor: begin_replay_frame() rewinds the histories to it (History::rewind_to keeps indices and
// sequence numbers, so the incremental plots stay valid) and end_replay_frame() gives the live ones back,
// so no panel needs to know about replay. UI thread only.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "window/app.hpp"
#include "render/gl_util.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
std::string clip_name(const std::string& model) {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&t));
    return "impactlab-clip-" + model + "-" + buf;
}
}  // namespace

bool App::enter_replay() {
    if (replay_.player.active()) return true;
    if (!replay_.player.enter(feed_.traj, run_.paused)) {
        toast("replay: nothing recorded yet");
        return false;
    }
    if (!run_.paused) set_paused(true);
    feed_.impact_label.reset();   // the live label would speak of a later instant
    return true;
}

void App::leave_replay() {
    if (clip_.frame >= 0) {
        clip_.writer.abort();
        clip_.frame = -1;
        toast("clip export cancelled");
    }
    if (!replay_.player.active()) return;
    const bool was_paused = replay_.player.leave();
    if (!was_paused && run_.paused) set_paused(false);
}

void App::continue_from_replay() {
    if (!replay_.player.active() || feed_.traj.empty()) return;
    const SimMsg m = feed_.traj[sample_at(feed_.traj, replay_.player.cursor())];
    const bool was_paused = replay_.player.leave();   // the run goes on from here, paused or not as before replay
    // The old future goes; the history keeps the past up to the instant continued from.
    feed_.traj.drop_newest(feed_.traj.size() - 1 - sample_at(feed_.traj, m.t));
    feed_.sections.drop_newest(feed_.sections.size() - feed_.sections.lower_bound(std::nextafter(m.t, INFINITY),
                                                                   [](const SimMsg& s) { return s.t; }));
    feed_.last = m;
    restart_sim(m.x, m.v, m.t, m.phi, m.omega, false);
    if (!was_paused) set_paused(false);
    toast("continuing from t = " + std::to_string(m.t).substr(0, 8) + " s");
}

void App::restart_sim(double x, double v, double t, double phi, double omega, bool clear_history) {
    // Restart first (its sample is at t with the new x, v), then the omega of that instant, which only
    // bumps the epoch at the same t: no sample of the old state lands after the restart.
    send(SimCommand::restart(x, v, t, phi));
    if (std::abs(omega - run_.omega) > 1e-12) set_omega(omega);
    feed_.restart.pending = true;
    feed_.restart.t = t;
    feed_.restart.epoch = feed_.epoch;
    feed_.restart.clear = clear_history;
    feed_.restart.since = now_s();
}

bool App::skip_until_restart(const SimMsg& m) {
    if (!feed_.restart.pending) return false;
    // Records of the old run still in the ring are dropped until the restart's own sample (at exactly
    // its t, a newer epoch); a command the engine refused would leave us waiting, so give up after 2 s.
    const bool arrived = m.kind == MsgKind::Sample && m.t == feed_.restart.t && m.epoch != feed_.restart.epoch;
    if (!arrived && now_s() - feed_.restart.since < 2.0) return true;
    feed_.restart.pending = false;
    if (!arrived) return false;
    if (feed_.restart.clear) {
        feed_.traj.clear();
        feed_.sections.clear();
        feed_.have_last = false;
    } else {
        feed_.traj.drop_newest(feed_.traj.size() - feed_.traj.lower_bound(m.t, [](const SimMsg& s) { return s.t; }));
        if (!feed_.traj.empty()) feed_.last = feed_.traj.back();
    }
    feed_.impact_label.reset();
    return false;
}

void App::begin_replay_frame() {
    if (!replay_.player.active()) return;
    if (clip_.frame >= 0) replay_.player.seek(clip_.plan.time_of(clip_.frame));
    const std::size_t i = replay_.player.update(feed_.traj, clip_.frame >= 0 ? 0.0 : frames_.dt);
    if (!replay_.player.active()) {   // the history was cleared under it (a reset, a preset)
        leave_replay();
        return;
    }
    replay_.live.last = feed_.last;
    replay_.live.phi_prev = feed_.phi_prev;
    replay_.live.max_force = feed_.frame_max_force;
    const SimMsg m = feed_.traj[i];
    replay_.map.replay(feed_.pc_map, m.t);   // the Poincare map as it stood then (fed forward, rebuilt going back)
    feed_.last = m;
    feed_.phi_prev = i > 0 ? feed_.traj[i - 1].phi : m.phi;
    feed_.frame_max_force = m.force;
    feed_.traj.rewind_to(i + 1);
    feed_.sections.rewind_to(feed_.sections.lower_bound(std::nextafter(m.t, INFINITY), [](const SimMsg& s) { return s.t; }));
    replay_.live.rewound = true;
}

void App::end_replay_frame() {
    if (replay_.live.rewound) {
        feed_.traj.reveal();
        feed_.sections.reveal();
        feed_.last = replay_.live.last;
        feed_.phi_prev = replay_.live.phi_prev;
        feed_.frame_max_force = replay_.live.max_force;
        replay_.live.rewound = false;
    }
    // What the replay bar asked for while the histories were rewound.
    const ReplayRequest req = replay_.request;
    replay_.request = ReplayRequest::None;
    if (req == ReplayRequest::Leave) leave_replay();
    else if (req == ReplayRequest::Continue) continue_from_replay();
    else if (req == ReplayRequest::Clip) {
        std::string err;
        if (start_clip(clip_.dir, clip_.seconds, err)) {
            clip_.window = false;
            clip_.error.clear();
        } else {
            clip_.error = err;   // shown in the window, which stays open
            toast(err);
        }
    }
}

void App::handle_replay_keys() {
    auto pressed = [](int key, bool repeat = false) { return ImGui::IsKeyPressed(key, repeat); };
    const bool shift = ImGui::GetIO().KeyShift;
    if (!replay_.player.active()) {
        if (shift && pressed(GLFW_KEY_R)) enter_replay();
        return;
    }
    if (clip_.frame >= 0) {   // exporting: only Escape (cancel)
        if (pressed(GLFW_KEY_ESCAPE)) leave_replay();
        return;
    }
    const double period = kTwoPi / std::max(run_.omega, 0.5);
    if (pressed(GLFW_KEY_SPACE)) replay_.player.set_playing(!replay_.player.playing());
    if (pressed(GLFW_KEY_LEFT, true)) replay_.player.step(-(shift ? 10.0 : 1.0) * period);
    if (pressed(GLFW_KEY_RIGHT, true)) replay_.player.step((shift ? 10.0 : 1.0) * period);
    if (pressed(GLFW_KEY_COMMA, true)) replay_.player.step(-sim_sample_dt());
    if (pressed(GLFW_KEY_PERIOD, true)) replay_.player.step(sim_sample_dt());
    if (pressed(GLFW_KEY_ESCAPE) || (shift && pressed(GLFW_KEY_R))) replay_.request = ReplayRequest::Leave;
    if (pressed(GLFW_KEY_ENTER)) replay_.request = ReplayRequest::Continue;
}

double App::sim_sample_dt() const { return SimEngine::sample_dt_for(run_.speed); }

void App::draw_replay_bar() {
    const Palette& pal = palette();
    const HeldSpan held = held_span(feed_.traj);   // rewound: ends at the cursor; the live end is live_end_t
    const double live_end = replay_.live.last.t;
    const double first = feed_.traj.empty() ? 0.0 : feed_.traj[0].t;
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "REPLAY");
    ImGui::SameLine();
    if (clip_.frame >= 0) {
        ImGui::Text("exporting clip: frame %d / %d  (t = %.3f s)", clip_.frame + 1, clip_.plan.frames, replay_.player.cursor());
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel (Esc)")) replay_.request = ReplayRequest::Leave;
        return;
    }
    if (ImGui::SmallButton("Live (Esc)")) replay_.request = ReplayRequest::Leave;
    ImGui::SameLine();
    if (ImGui::SmallButton(replay_.player.playing() ? "Pause" : "Play")) replay_.player.set_playing(!replay_.player.playing());
    ImGui::SameLine();
    const bool slow = replay_.player.rate() < 0.5;
    if (ImGui::SmallButton(slow ? "0.25x" : "1x")) replay_.player.set_rate(slow ? 1.0 : 0.25);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Playback speed in replay: 1x or 0.25x real time");
    ImGui::SameLine();
    const float right_w = ImGui::CalcTextSize("Continue from here (Enter)  Export clip...").x + 5 * ImGui::GetStyle().ItemSpacing.x;
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - right_w));
    // The slider runs over what the history holds, in seconds before the live end.
    float back = static_cast<float>(replay_.player.cursor() - live_end);
    const float lo = static_cast<float>(std::min(first - live_end, -1e-3)), hi = 0.0f;
    char fmt[64];
    std::snprintf(fmt, sizeof fmt, "t = %.3f s  (%%+.2f s)", held.last);
    if (ImGui::SliderFloat("##replay_t", &back, lo, hi, fmt)) {
        replay_.player.seek(live_end + back);
        replay_.player.set_playing(false);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Drag through the last %.0f s the history holds (Left/Right: one forcing period, Shift: "
                          "ten; , and . one sample; Space plays).", live_end - first);
    ImGui::SameLine();
    if (ImGui::SmallButton("Continue from here (Enter)")) replay_.request = ReplayRequest::Continue;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Restart the simulation from this instant (x, v, t, φ, ω); the recorded future is dropped.");
    ImGui::SameLine();
    if (ImGui::SmallButton("Export clip...")) clip_.window = true;
}

void App::draw_clip_window() {
    if (!clip_.window) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Export clip", &clip_.window,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        ImGui::TextUnformatted(replay_.player.active() ? "The seconds before the replayed instant, as shown (the whole window)."
                                                : "The last seconds of the run, as shown (the whole window).");
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 22);
        ImGui::InputText("folder", clip_.dir, sizeof clip_.dir);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 22);
        ImGui::SliderFloat("seconds", &clip_.seconds, 0.5f, 60.0f, "%.1f s of simulated time", ImGuiSliderFlags_Logarithmic);
        const bool ffmpeg = !find_on_path("ffmpeg").empty();
        ImGui::TextDisabled("%.0f fps, PNG frames%s; played at %.2gx", ClipExport::kFps, ffmpeg ? " and clip.mp4 (ffmpeg)" : " (no ffmpeg: no video)",
                            replay_.player.active() ? replay_.player.rate() : 1.0);
        if (ImGui::Button("Export")) replay_.request = ReplayRequest::Clip;
        ImGui::SameLine();
        if (ImGui::Button("Close")) clip_.window = false;
        if (!clip_.error.empty()) {
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32);
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", clip_.error.c_str());
            ImGui::PopTextWrapPos();
        }
    }
    ImGui::End();
}

bool App::start_clip(const std::string& dir, double seconds, std::string& error) {
    if (clip_.frame >= 0) {
        error = "clip export: one is in progress";
        return false;
    }
    const bool from_live = !replay_.player.active();
    if (from_live && !enter_replay()) {
        error = "clip export: nothing recorded yet";
        return false;
    }
    try {
        clip_.plan = plan_clip(feed_.traj, replay_.player.cursor(), seconds, ClipExport::kFps, replay_.player.rate());
    } catch (const std::exception& e) {
        if (from_live) leave_replay();
        error = std::string("clip export: ") + e.what();
        return false;
    }
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win_, &fw, &fh);
    if (!clip_.writer.begin(dir, clip_name(model_name()), fw, fh, ClipExport::kFps, true, error)) {
        if (from_live) leave_replay();
        return false;
    }
    clip_.from_live = from_live;
    clip_.frame = 0;
    replay_.player.set_playing(false);
    return true;
}

void App::capture_clip_frame(int fw, int fh) {
    if (clip_.frame < 0) return;
    std::string err;
    bool ok = true;
    if (fw != clip_.writer.width() || fh != clip_.writer.height()) {
        err = "clip export: the window changed size during the clip";
        clip_.writer.abort();
        ok = false;
    } else {
        const std::vector<unsigned char> px = read_framebuffer_rgb(fw, fh);
        ok = clip_.writer.add_frame(px.data(), err);
    }
    if (ok && ++clip_.frame < clip_.plan.frames) return;
    clip_.frame = -1;
    std::string summary;
    if (ok && clip_.writer.finish(summary, err)) {
        toast(summary);
        clip_.summary = summary;
    } else {
        toast(err);
        clip_.error = err;
    }
    if (clip_.from_live) leave_replay();
}

}  // namespace impactlab::gui
