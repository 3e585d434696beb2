// The scripted harness: what the tests and the benchmarks drive without a hand on the mouse. --bench-plot
// (synthetic data fed a frame's worth at a time, the frames timed), --soak (model switches at 100x with
// the resident memory reported), and a --frames run's script (--then-preset, --then-xI, --then-omega,
// --switch-model half-way; --clip-out, --replay-back and --screenshot at the end). The live app never
// enters this file's code. UI thread.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "window/app.hpp"
#include "render/gl_util.hpp"
#include "render/plot_gpu.hpp"

namespace impactlab::gui {

namespace {
// Bench mode: the headless engine's samples go straight into the UI's history, as if drained from the ring.
struct HistorySink final : MsgSink {
    History<SimMsg>* traj = nullptr;
    std::vector<SimMsg>* ahead = nullptr;   // set: samples computed ahead go here instead
    void put(const SimMsg& m) override {   // UI thread (the bench engine runs there)
        if (m.kind != MsgKind::Sample) return;
        if (ahead) ahead->push_back(m);
        else traj->push(m);
    }
};
}  // namespace

void App::fill_bench_data(int points) {
    // Real trajectory for the phase portrait and x(t): the engine, headless, at omega = 18 (chaos), at
    // 100x real time (1 ms samples) as in the live app.
    auto sink = std::make_unique<HistorySink>();
    HistorySink* hs = sink.get();
    sink->traj = &feed_.traj;
    EngineConfig cfg;
    cfg.model = model_name();
    cfg.omega = 18.0;
    cfg.speed = 100.0;
    bench_.engine = std::make_unique<SimEngine>(cfg, sink.get());
    bench_.sink = std::move(sink);
    feed_.traj.clear();
    bench_.engine->advance_to(points * bench_.engine->sample_dt() * 1.0001);
    feed_.last = feed_.traj.back();
    // The frames' new samples are computed now: the app runs the simulation on its own thread, and the
    // benchmark times the UI thread's frames only. feed_bench_frame() hands them over a frame's worth at a time.
    bench_.feed.clear();
    bench_.fed = 0;
    hs->ahead = &bench_.feed;
    bench_.engine->advance_to(feed_.last.t + BenchPlot::kFrames * 100.0 / 60.0 + 1.0);
    hs->ahead = nullptr;
    feed_.have_last = true;
    run_.omega = 18.0;
    // Synthetic section points and diagram (shapes like the real ones; the draw cost is what is measured).
    // The map's points carry 0, 1 or 2 impacts in turn, so the bench draws every colour.
    feed_.sections.clear();
    feed_.pc_map.reset();
    double a = 0.1, b = 0.2;
    for (int i = 0; i < points; ++i) {   // a Henon map, scaled into the left well
        const double na = 1.0 - 1.4 * a * a + b;
        b = 0.3 * a;
        a = na;
        SimMsg m;
        m.kind = MsgKind::Section;
        m.x = -0.010 + 0.005 * a;
        m.v = 0.12 * b / 0.4;
        m.t = i;
        feed_.sections.push(m);
        feed_.pc_map.push({m.t, m.x, m.v, i % 3, 0.02, 0.2});
    }
    Diagram d;
    d.model = model_name();
    d.protocol = "bench";
    for (int i = 0; i < points; ++i) {   // a logistic-map cascade over omega
        const double w = 25.0 * (i / 70) / (points / 70.0);
        double r = 2.8 + 1.2 * w / 25.0, x = 0.4;
        for (int k = 0; k < 60 + i % 70; ++k) x = r * x * (1 - x);
        d.points.push_back({w, -0.018 + 0.014 * x, 0.0});
    }
    bif_.panel.show_bench(std::move(d), {0, 25}, {-0.019, -0.003});
    bench_.window = static_cast<std::size_t>(points);
}

void App::feed_bench_frame() {
    // One 60 Hz frame at 100x real time: 1/60 s x 100 = 1.67 s of simulation, 1,667 samples of 1 ms.
    const double t = feed_.last.t + 100.0 / 60.0;
    while (bench_.fed < bench_.feed.size() && bench_.feed[bench_.fed].t <= t) feed_.traj.push(bench_.feed[bench_.fed++]);
    feed_.last = feed_.traj.back();
}

int App::run_bench() {
    while (bench_frame())
        if (glfwWindowShouldClose(win_)) return 0;
    return 0;
}

// The frames one at a time, so a browser page runs them as its animation frames (the desktop's run_bench
// loops over them).
bool App::bench_frame() {
    constexpr int kWarm = BenchPlot::kWarm, kFrames = BenchPlot::kFrames - kWarm;
    const int i = bench_.frame++;
    if (i == 0) fill_bench_data(opt_.bench_points);
    if (i == kWarm) {
        Plot::reset_stats();
        bench_.events_s = bench_.build_s = bench_.wait_s = bench_.submit_s = 0;
        for (double& p : bench_.panel_s) p = 0;
        bench_.timed_s = now_s();
    }
    if (i == kWarm + kFrames) {   // the last timed frame is shown by this swap
        glfwSwapBuffers(win_);
        frames_.pending = false;
        bench_.timed_s = now_s() - bench_.timed_s;
        report_bench();
        return false;
    }
    feed_bench_frame();
    if (i + 1 == kWarm && !opt_.screenshot.empty()) screenshot(opt_.screenshot);   // an untimed frame
    frame();
    if (i >= kWarm)
        bench_.verts = std::max(bench_.verts, static_cast<std::size_t>(ImGui::GetDrawData()->TotalVtxCount) + plot_gpu::queued_points());
    return true;
}

void App::report_bench() {
    constexpr int kFrames = BenchPlot::kFrames - BenchPlot::kWarm;
    const double s = bench_.timed_s;
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win_, &fw, &fh);
    std::printf("plot benchmark (%s backend): %dx%d, %d points on each plot (phase portrait, x(t), Poincare map, "
                "bifurcation), 1,667 new samples a frame (100x real time): %.1f fps (%.2f ms/frame, %zu vertices/frame, renderer: %s)\n",
                opt_.plot_backend.c_str(), fw, fh, opt_.bench_points, kFrames / s, 1e3 * s / kFrames, bench_.verts,
                reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    std::printf("plot benchmark: per frame %.2f ms polling events, %.2f ms building the UI (ImGui, the plots' "
                "images, rig geometry), %.2f ms waiting for the previous frame's rendering (the rest of it overlaps "
                "the building), %.2f ms submitting (uploads, GL calls); panels [ms]:",
                1e3 * bench_.events_s / kFrames, 1e3 * bench_.build_s / kFrames, 1e3 * bench_.wait_s / kFrames,
                1e3 * bench_.submit_s / kFrames);
    std::printf(" controls %.2f", 1e3 * bench_.panel_s[0] / kFrames);
    for (const ViewInfo& v : kViews) std::printf(" %s %.2f", v.key, 1e3 * bench_.panel_s[1 + static_cast<int>(v.id)] / kFrames);
    std::printf("; %zu points reached the renderer per frame after decimation\n", Plot::emitted_vertices() / kFrames);
}

void App::script_mouse() {
    // --double-click: press, release, press, release on four frames at one point, timed as at 60 fps (a
    // loaded machine's slow frames must not split the gesture into two single clicks).
    for (std::size_t k = 0; k < opt_.double_clicks.size(); ++k) {
        const long f = frames_.count - 10 - 8 * static_cast<long>(k);
        if (f < 0 || f > 4) continue;
        ImGuiIO& io = ImGui::GetIO();
        if (f == 0) {
            const FileBrowser::Row* r = session_.browser.row(opt_.double_clicks[k]);
            if (!r) {
                std::fprintf(stderr, "impactlab-gui: error: --double-click: no row '%s' in the session browser\n",
                             opt_.double_clicks[k].c_str());
                script_.exit_code = 1;
                continue;
            }
            script_.click_at = ImVec2(0.5f * (r->x0 + r->x1), 0.5f * (r->y0 + r->y1));
        }
        io.MousePos = script_.click_at;
        io.MouseDown[0] = f == 0 || f == 2;
        io.DeltaTime = 1.0f / 60.0f;
    }
}

bool App::script_step() {
    // --orbit: the clicks, one at each of the first n of n + 1 equal parts of the run.
    const long parts = static_cast<long>(opt_.orbits.size()) + 1;
    for (long k = 1; k < parts; ++k)
        if (frames_.counted == k * opt_.frames / parts)
            start_orbit(opt_.orbits[static_cast<std::size_t>(k - 1)].first, opt_.orbits[static_cast<std::size_t>(k - 1)].second);
    // With --data the fit is for the start model, and --preset or --state-json look at one model: no
    // switch unless one is asked for.
    const bool keep_model = !opt_.data.empty() || opt_.preset > 0 || !opt_.state_json.empty() || !opt_.session.empty() ||
                            !opt_.save_session.empty();
    if (!script_.switched && frames_.counted >= opt_.frames / 2 && opt_.then_preset > 0) {
        script_.switched = true;   // --then-preset: what pressing key N does
        apply_preset(presets_for(model_name())[static_cast<std::size_t>(opt_.then_preset - 1)]);
    }
    if (!script_.switched && frames_.counted >= opt_.frames / 2 && opt_.then_xi) {
        script_.switched = true;   // --then-xI: what dragging the x_I slider there does
        set_xi(opt_.then_xI);
    }
    if (!script_.switched && frames_.counted >= opt_.frames / 2 && opt_.then_phase) {
        script_.switched = true;   // --then-phi0: what moving the Poincare view's phase slider there does
        set_section_phase(opt_.then_phi0);
    }
    if (!script_.switched && frames_.counted >= opt_.frames / 2 && opt_.then_w) {
        script_.switched = true;   // --then-omega: what the arrow keys do, live (no reset)
        set_omega(opt_.then_omega);
    }
    if (!script_.switched && frames_.counted >= opt_.frames / 2 && (!keep_model || !opt_.switch_model.empty())) {
        script_.switched = true;
        // Switch the model once, live: to --switch-model, or H <-> G with the same stiffness.
        std::string target = opt_.switch_model;
        if (target.empty()) {
            const std::string imp = impact_models()[static_cast<std::size_t>(run_.impact)].id;
            target = std::string(stiffness_sets()[static_cast<std::size_t>(run_.stiffness)].id) + (imp == "H" ? "G" : "H");
        }
        set_version(target);
    }
    if (frames_.counted >= opt_.frames) {
        if (!opt_.clip_out.empty() && !clip_.started) {   // --clip-out: the last seconds, a frame each
            clip_.started = true;
            if (std::string err; !start_clip(opt_.clip_out, opt_.clip_seconds, err)) {
                std::fprintf(stderr, "impactlab-gui: error: --clip-out: %s\n", err.c_str());
                script_.exit_code = 1;
            }
            return true;
        }
        if (clip_.frame >= 0) return true;
        if (opt_.replay_back > 0 && !script_.replay_back_done) {   // --replay-back: the last frame shows the past
            script_.replay_back_done = true;
            if (enter_replay()) replay_.player.seek(replay_.player.cursor() - opt_.replay_back);
            if (opt_.replay_continue) {   // then Enter, and 60 more frames of the continued run
                replay_.request = ReplayRequest::Continue;
                frames_.counted -= 60;
            }
            return true;
        }
        if (!opt_.screenshot.empty()) {
            screenshot(opt_.screenshot);
            frame();   // renders once more and reads that frame back
        }
        return false;
    }
    return true;
}

namespace {
// Resident set size of this process [MB] (Linux /proc; 0 where unknown).
double rss_mb() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    long pages = 0, resident = 0;
    const int n = std::fscanf(f, "%ld %ld", &pages, &resident);
    std::fclose(f);
    return n == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0 : 0.0;
}
}  // namespace

int App::soak() {
    // Every version in turn, 3 s each, at 100x: what a class sees when the teacher flips through the models.
    std::vector<std::string> versions;
    for (const auto& st : stiffness_sets())
        for (const auto& im : impact_models())
            if (im.kind != ImpactKind::None) versions.push_back(std::string(st.id) + im.id);
    set_speed(kMaxSpeed);
    const double t0 = now_s();
    double next_switch = t0 + 3.0, next_report = t0 + 10.0, rss_ref = -1;
    std::size_t k = 0;
    long frames_at_report = frames_.count;
    double worst_growth = 0;
    std::printf("soak: %.0f s at %gx, switching through %zu versions every 3 s\n", opt_.soak, kMaxSpeed, versions.size());
    while (!glfwWindowShouldClose(win_)) {
        frame();
        const double now = now_s();
        if (now >= next_switch) {
            set_version(versions[++k % versions.size()]);
            next_switch += 3.0;
        }
        if (now >= next_report || now - t0 >= opt_.soak) {
            const SimStatus st = sim_->status();
            const double rss = rss_mb();
            if (rss_ref < 0 && now - t0 >= 0.25 * opt_.soak) rss_ref = rss;   // after the caches and pools filled
            if (rss_ref >= 0) worst_growth = std::max(worst_growth, rss - rss_ref);
            std::printf("soak: t=%6.0f s rss=%7.1f MB dropped=%llu samples=%llu sim_time=%.0f s fps=%.1f model=%s\n", now - t0, rss,
                        static_cast<unsigned long long>(st.dropped), static_cast<unsigned long long>(feed_.samples_seen),
                        feed_.have_last ? feed_.last.t : st.sim_time, static_cast<double>(frames_.count - frames_at_report) / 10.0,
                        model_name().c_str());
            std::fflush(stdout);
            frames_at_report = frames_.count;
            next_report += 10.0;
            if (now - t0 >= opt_.soak) break;
        }
    }
    std::printf("soak: RSS grew by %.1f MB after the first quarter (limit 16 MB)\n", worst_growth);
    return worst_growth > 16.0 ? 1 : 0;
}

}  // namespace impactlab::gui
