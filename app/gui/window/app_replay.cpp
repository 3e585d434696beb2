// Replay and clip export: the App's side of replay.hpp and clip_writer.hpp.
// While replaying, the simulation is paused and every panel draws traj_, sections_ and last_ as they were at
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

const PoincareMap& App::shown_map() const { return replay_.active() ? replay_map_ : pc_map_; }

bool App::enter_replay() {
    if (replay_.active()) return true;
    if (!replay_.enter(traj_, paused_)) {
        toast("replay: nothing recorded yet");
        return false;
    }
    if (!paused_) set_paused(true);
    impact_label_.reset();   // the live label would speak of a later instant
    return true;
}

void App::leave_replay() {
    if (clip_frame_ >= 0) {
        clip_.abort();
        clip_frame_ = -1;
        toast("clip export cancelled");
    }
    if (!replay_.active()) return;
    const bool was_paused = replay_.leave();
    if (!was_paused && paused_) set_paused(false);
}

void App::continue_from_replay() {
    if (!replay_.active() || traj_.empty()) return;
    const SimMsg m = traj_[sample_at(traj_, replay_.cursor())];
    const bool was_paused = replay_.leave();   // the run goes on from here, paused or not as before replay
    // The old future goes; the history keeps the past up to the instant continued from.
    traj_.drop_newest(traj_.size() - 1 - sample_at(traj_, m.t));
    sections_.drop_newest(sections_.size() - sections_.lower_bound(std::nextafter(m.t, INFINITY),
                                                                   [](const SimMsg& s) { return s.t; }));
    last_ = m;
    restart_sim(m.x, m.v, m.t, m.phi, m.omega, false);
    if (!was_paused) set_paused(false);
    toast("continuing from t = " + std::to_string(m.t).substr(0, 8) + " s");
}

void App::restart_sim(double x, double v, double t, double phi, double omega, bool clear_history) {
    // Restart first (its sample is at t with the new x, v), then the omega of that instant, which only
    // bumps the epoch at the same t: no sample of the old state lands after the restart.
    send(SimCommand::restart(x, v, t, phi));
    if (std::abs(omega - omega_) > 1e-12) set_omega(omega);
    restart_.pending = true;
    restart_.t = t;
    restart_.epoch = epoch_;
    restart_.clear = clear_history;
    restart_.since = now_s();
}

bool App::skip_until_restart(const SimMsg& m) {
    if (!restart_.pending) return false;
    // Records of the old run still in the ring are dropped until the restart's own sample (at exactly
    // its t, a newer epoch); a command the engine refused would leave us waiting, so give up after 2 s.
    const bool arrived = m.kind == MsgKind::Sample && m.t == restart_.t && m.epoch != restart_.epoch;
    if (!arrived && now_s() - restart_.since < 2.0) return true;
    restart_.pending = false;
    if (!arrived) return false;
    if (restart_.clear) {
        traj_.clear();
        sections_.clear();
        have_last_ = false;
    } else {
        traj_.drop_newest(traj_.size() - traj_.lower_bound(m.t, [](const SimMsg& s) { return s.t; }));
        if (!traj_.empty()) last_ = traj_.back();
    }
    impact_label_.reset();
    return false;
}

void App::begin_replay_frame() {
    if (!replay_.active()) return;
    if (clip_frame_ >= 0) replay_.seek(clip_plan_.time_of(clip_frame_));
    const std::size_t i = replay_.update(traj_, clip_frame_ >= 0 ? 0.0 : frame_dt_);
    if (!replay_.active()) {   // the history was cleared under it (a reset, a preset)
        leave_replay();
        return;
    }
    replay_live_.last = last_;
    replay_live_.phi_prev = phi_prev_;
    replay_live_.max_force = frame_max_force_;
    const SimMsg m = traj_[i];
    replay_map_.replay(pc_map_, m.t);   // the Poincare map as it stood then (fed forward, rebuilt going back)
    last_ = m;
    phi_prev_ = i > 0 ? traj_[i - 1].phi : m.phi;
    frame_max_force_ = m.force;
    traj_.rewind_to(i + 1);
    sections_.rewind_to(sections_.lower_bound(std::nextafter(m.t, INFINITY), [](const SimMsg& s) { return s.t; }));
    replay_live_.rewound = true;
}

void App::end_replay_frame() {
    if (replay_live_.rewound) {
        traj_.reveal();
        sections_.reveal();
        last_ = replay_live_.last;
        phi_prev_ = replay_live_.phi_prev;
        frame_max_force_ = replay_live_.max_force;
        replay_live_.rewound = false;
    }
    // What the replay bar asked for while the histories were rewound.
    const ReplayRequest req = replay_request_;
    replay_request_ = ReplayRequest::None;
    if (req == ReplayRequest::Leave) leave_replay();
    else if (req == ReplayRequest::Continue) continue_from_replay();
    else if (req == ReplayRequest::Clip) {
        std::string err;
        if (start_clip(clip_dir_, clip_seconds_, err)) {
            clip_window_ = false;
            clip_error_.clear();
        } else {
            clip_error_ = err;   // shown in the window, which stays open
            toast(err);
        }
    }
}

void App::handle_replay_keys() {
    auto pressed = [](int key, bool repeat = false) { return ImGui::IsKeyPressed(key, repeat); };
    const bool shift = ImGui::GetIO().KeyShift;
    if (!replay_.active()) {
        if (shift && pressed(GLFW_KEY_R)) enter_replay();
        return;
    }
    if (clip_frame_ >= 0) {   // exporting: only Escape (cancel)
        if (pressed(GLFW_KEY_ESCAPE)) leave_replay();
        return;
    }
    const double period = kTwoPi / std::max(omega_, 0.5);
    if (pressed(GLFW_KEY_SPACE)) replay_.set_playing(!replay_.playing());
    if (pressed(GLFW_KEY_LEFT, true)) replay_.step(-(shift ? 10.0 : 1.0) * period);
    if (pressed(GLFW_KEY_RIGHT, true)) replay_.step((shift ? 10.0 : 1.0) * period);
    if (pressed(GLFW_KEY_COMMA, true)) replay_.step(-sim_sample_dt());
    if (pressed(GLFW_KEY_PERIOD, true)) replay_.step(sim_sample_dt());
    if (pressed(GLFW_KEY_ESCAPE) || (shift && pressed(GLFW_KEY_R))) replay_request_ = ReplayRequest::Leave;
    if (pressed(GLFW_KEY_ENTER)) replay_request_ = ReplayRequest::Continue;
}

double App::sim_sample_dt() const { return SimEngine::sample_dt_for(speed_); }

void App::draw_replay_bar() {
    const Palette& pal = palette();
    const HeldSpan held = held_span(traj_);   // rewound: ends at the cursor; the live end is live_end_t
    const double live_end = replay_live_.last.t;
    const double first = traj_.empty() ? 0.0 : traj_[0].t;
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "REPLAY");
    ImGui::SameLine();
    if (clip_frame_ >= 0) {
        ImGui::Text("exporting clip: frame %d / %d  (t = %.3f s)", clip_frame_ + 1, clip_plan_.frames, replay_.cursor());
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel (Esc)")) replay_request_ = ReplayRequest::Leave;
        return;
    }
    if (ImGui::SmallButton("Live (Esc)")) replay_request_ = ReplayRequest::Leave;
    ImGui::SameLine();
    if (ImGui::SmallButton(replay_.playing() ? "Pause" : "Play")) replay_.set_playing(!replay_.playing());
    ImGui::SameLine();
    const bool slow = replay_.rate() < 0.5;
    if (ImGui::SmallButton(slow ? "0.25x" : "1x")) replay_.set_rate(slow ? 1.0 : 0.25);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Playback speed in replay: 1x or 0.25x real time");
    ImGui::SameLine();
    const float right_w = ImGui::CalcTextSize("Continue from here (Enter)  Export clip...").x + 5 * ImGui::GetStyle().ItemSpacing.x;
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - right_w));
    // The slider runs over what the history holds, in seconds before the live end.
    float back = static_cast<float>(replay_.cursor() - live_end);
    const float lo = static_cast<float>(std::min(first - live_end, -1e-3)), hi = 0.0f;
    char fmt[64];
    std::snprintf(fmt, sizeof fmt, "t = %.3f s  (%%+.2f s)", held.last);
    if (ImGui::SliderFloat("##replay_t", &back, lo, hi, fmt)) {
        replay_.seek(live_end + back);
        replay_.set_playing(false);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Drag through the last %.0f s the history holds (Left/Right: one forcing period, Shift: "
                          "ten; , and . one sample; Space plays).", live_end - first);
    ImGui::SameLine();
    if (ImGui::SmallButton("Continue from here (Enter)")) replay_request_ = ReplayRequest::Continue;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Restart the simulation from this instant (x, v, t, φ, ω); the recorded future is dropped.");
    ImGui::SameLine();
    if (ImGui::SmallButton("Export clip...")) clip_window_ = true;
}

void App::draw_clip_window() {
    if (!clip_window_) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Export clip", &clip_window_,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        ImGui::TextUnformatted(replay_.active() ? "The seconds before the replayed instant, as shown (the whole window)."
                                                : "The last seconds of the run, as shown (the whole window).");
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 22);
        ImGui::InputText("folder", clip_dir_, sizeof clip_dir_);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 22);
        ImGui::SliderFloat("seconds", &clip_seconds_, 0.5f, 60.0f, "%.1f s of simulated time", ImGuiSliderFlags_Logarithmic);
        const bool ffmpeg = !find_on_path("ffmpeg").empty();
        ImGui::TextDisabled("%.0f fps, PNG frames%s; played at %.2gx", kClipFps, ffmpeg ? " and clip.mp4 (ffmpeg)" : " (no ffmpeg: no video)",
                            replay_.active() ? replay_.rate() : 1.0);
        if (ImGui::Button("Export")) replay_request_ = ReplayRequest::Clip;
        ImGui::SameLine();
        if (ImGui::Button("Close")) clip_window_ = false;
        if (!clip_error_.empty()) {
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32);
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", clip_error_.c_str());
            ImGui::PopTextWrapPos();
        }
    }
    ImGui::End();
}

bool App::start_clip(const std::string& dir, double seconds, std::string& error) {
    if (clip_frame_ >= 0) {
        error = "clip export: one is in progress";
        return false;
    }
    const bool from_live = !replay_.active();
    if (from_live && !enter_replay()) {
        error = "clip export: nothing recorded yet";
        return false;
    }
    try {
        clip_plan_ = plan_clip(traj_, replay_.cursor(), seconds, kClipFps, replay_.rate());
    } catch (const std::exception& e) {
        if (from_live) leave_replay();
        error = std::string("clip export: ") + e.what();
        return false;
    }
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win_, &fw, &fh);
    if (!clip_.begin(dir, clip_name(model_name()), fw, fh, kClipFps, true, error)) {
        if (from_live) leave_replay();
        return false;
    }
    clip_from_live_ = from_live;
    clip_frame_ = 0;
    replay_.set_playing(false);
    return true;
}

void App::capture_clip_frame(int fw, int fh) {
    if (clip_frame_ < 0) return;
    std::string err;
    bool ok = true;
    if (fw != clip_.width() || fh != clip_.height()) {
        err = "clip export: the window changed size during the clip";
        clip_.abort();
        ok = false;
    } else {
        const std::vector<unsigned char> px = read_framebuffer_rgb(fw, fh);
        ok = clip_.add_frame(px.data(), err);
    }
    if (ok && ++clip_frame_ < clip_plan_.frames) return;
    clip_frame_ = -1;
    std::string summary;
    if (ok && clip_.finish(summary, err)) {
        toast(summary);
        clip_summary_ = summary;
    } else {
        toast(err);
        clip_error_ = err;
    }
    if (clip_from_live_) leave_replay();
}

}  // namespace impactlab::gui
