#include "app.hpp"
#include "sim/param_edit.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <stb_image.h>   // libstb exports the implementation

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <numbers>

#include "render/gl_util.hpp"
#include "program_assets.hpp"
#include "render/opaque_image.hpp"
#include "render/plot2d.hpp"
#include "render/plot_gpu.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/input_file.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {

// M steps through the bumper laws (C, C1, G, H) and skips "none": a model without a bumper is chosen in the
// combo, not met by surprise while cycling.
int next_impact_law(int current) {
    const auto& laws = impact_models();
    const int n = static_cast<int>(laws.size());
    for (int i = 1; i <= n; ++i) {
        const int j = (current + i) % n;
        if (laws[static_cast<std::size_t>(j)].kind != ImpactKind::None) return j;
    }
    return current;
}

// Keys pressed during the events of a frame. GLFW reports a tap shorter than a frame as a press and a
// release in one poll, which leave ImGui's key state up again before it looks (the key lost): held down
// for one frame instead (App::frame). ImGui's backend chains to this callback. UI thread.
std::vector<int> g_pressed, g_held;
void on_key(GLFWwindow*, int key, int, int action, int) {
    if (action == GLFW_PRESS && key >= 0 && key < 512) g_pressed.push_back(key);
}

// Files dropped on the window (GLFW, also the page's canvas) or picked in the page, for the next frame.
// UI thread.
std::vector<std::string> g_handed;
void on_drop(GLFWwindow*, int count, const char** paths) {
    for (int i = 0; i < count; ++i) g_handed.emplace_back(paths[i]);
}

void glfw_error(int code, const char* text) { std::fprintf(stderr, "impactlab-gui: GLFW error %d: %s\n", code, text); }

int index_of_stiffness(const std::string& id) {
    const auto& all = stiffness_sets();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (id == all[i].id) return static_cast<int>(i);
    return 0;
}

int index_of_impact(const ImpactModel* m) {
    const auto& all = impact_models();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (&all[i] == m || (m && std::string(all[i].id) == m->id)) return static_cast<int>(i);
    return 0;
}

std::string timestamp() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&t));
    return buf;
}

}  // namespace

App::App(const Options& opt) : opt_(opt) {
    use_program_fonts();   // core's figures (the fit's report) draw text with the font found beside the program
    run_.params = make_version(opt.model);
    run_.stiffness = index_of_stiffness(run_.params.stiffness_id);
    run_.impact = index_of_impact(run_.params.impact);
    run_.omega = opt.omega;
    run_.xI = opt.xI;
    run_.params.xI = run_.xI;
    run_.speed = opt.speed;
    run_.paused = opt.paused;
    run_.x0 = opt.x0;
    view_.dark = !opt.light;
    bif_.steps = opt.bif_steps;
    if (opt.bifurcation == "cf-down") bif_.protocol = 1;
    else if (opt.bifurcation == "ef") bif_.protocol = 2;
    bif_.panel.configure(opt);
    bench_.on = opt.bench_plot;
    view_.show_help = opt.show_help;
    view_.show_params = opt.show_params;
    view_.details = opt.details;
    poincare_.set_clicker(opt.clicker || !opt.orbits.empty());
    // The first screen teaches, unless the run is scripted (any flag that drives it or reads it back).
    demos_.show = opt.guide || (opt.frames == 0 && !opt.bench_plot && opt.soak <= 0 && opt.session.empty() &&
                                opt.data.empty() && opt.demo == 0);
    if (!opt.strip.empty()) {   // --strip (checked by the options)
        const auto second = opt.strip.size() > 1 ? strip_from_key(opt.strip[1]) : std::nullopt;
        strip_.set_traces(strip_from_key(opt.strip[0]).value_or(StripQuantity::X), second);
    }
    if (!opt.data.empty()) {
        view_.show_data = true;
        data_panel_.load(opt.data, true);
    }
    analysis_.configure(opt);   // --plane loads now; --continuation, --basins, --small-plane start at the first frame
    set_plot_backend(opt.plot_backend == "gpu" ? PlotBackend::Gpu
                     : opt.plot_backend == "imgui" ? PlotBackend::DrawList : PlotBackend::Raster);
}

App::~App() { shutdown(); }

double App::now_s() const { return glfwGetTime(); }

std::string App::model_name() const {
    return std::string(stiffness_sets()[static_cast<std::size_t>(run_.stiffness)].id) +
           impact_models()[static_cast<std::size_t>(run_.impact)].id;
}

bool App::init(std::string& error) {
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit()) {
        error = "cannot initialise GLFW (no display? run under xvfb-run for headless use)";
        return false;
    }
    glfw_ready_ = true;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 0);
    // Nothing draws with depth or stencil; without those buffers llvmpipe renders each tile faster.
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    win_ = glfwCreateWindow(opt_.width, opt_.height, "impactlab - forced impact oscillator", nullptr, nullptr);
    if (!win_) {
        error = "cannot create an OpenGL 3.3 core window";
        return false;
    }
    glfwMakeContextCurrent(win_);
    // Window icon (assets/icons; a missing file only costs the icon).
    int iw = 0, ih = 0, in = 0;
    if (unsigned char* icon = stbi_load(asset_path("icons/impactlab-64.png").c_str(), &iw, &ih, &in, 4)) {
        const GLFWimage img{iw, ih, icon};
        glfwSetWindowIcon(win_, 1, &img);
        stbi_image_free(icon);
    }
    // Headless runs (frames, benchmarks) measure and finish as fast as they can; people get vsync.
    glfwSwapInterval(opt_.frames > 0 || opt_.bench_plot ? 0 : 1);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;   // the layout is computed, nothing to remember
    glfwSetKeyCallback(win_, on_key);   // before the backend, which chains to it
    glfwSetDropCallback(win_, on_drop);
    ImGui_ImplGlfw_InitForOpenGL(win_, true);
#ifdef __EMSCRIPTEN__
    ImGui_ImplOpenGL3_Init("#version 300 es");   // WebGL2
#else
    ImGui_ImplOpenGL3_Init("#version 330 core");
#endif
    imgui_ready_ = true;

    if (opt_.ui_scale > 0) view_.ui_scale = static_cast<float>(opt_.ui_scale);
    else {
        float sx = 1, sy = 1;
        glfwGetWindowContentScale(win_, &sx, &sy);
        view_.ui_scale = std::clamp(sx, 1.0f, 3.0f);
    }
    configure_layout();   // --presentation, --hide, --maximise, --magnify (tiles.cpp), before the fonts
    view_.fonts_dirty = true;
    rebuild_fonts();

    if (!rig_.init(error)) return false;
    if (std::string perr; !plot_gpu::init(perr))
        std::fprintf(stderr, "impactlab-gui: GPU plot shaders refused, drawing plots with ImDrawList: %s\n", perr.c_str());
    if (std::string perr; !opaque_image::init(perr))
        std::fprintf(stderr, "impactlab-gui: image shader refused, drawing images with ImGui's: %s\n", perr.c_str());

    if (opt_.preset > 0) {
        // --preset N: the engine starts on it (no epoch change, nothing transient from the default omega).
        const Preset p = presets_for(model_name())[static_cast<std::size_t>(opt_.preset - 1)];
        run_.omega = p.omega;
        run_.x0 = p.x0;
        run_.xI = 0.0;
        run_.params.xI = 0.0;
    }
    EngineConfig cfg;
    cfg.model = model_name();
    cfg.omega = run_.omega;
    cfg.xI = run_.xI;
    cfg.x0 = run_.x0;
    cfg.v0 = opt_.preset > 0 ? 0.0 : opt_.v0;
    cfg.phi0 = view_.section_phase = opt_.phi0;
    script_.warming = opt_.warmup > 0 && !bench_.on;
    if (script_.warming) {
        run_.speed = kMaxSpeed;
        run_.paused = false;
    }
    cfg.speed = run_.speed;
    cfg.paused = (run_.paused && !script_.warming) || bench_.on;
    sim_ = std::make_unique<SimThread>(cfg);
    commands_.attach(sim_.get());
    sim_->start();
    feed_.xI_shown = run_.xI;
    if (!opt_.ghost.empty()) companion_.ghost_impact = index_of_impact(make_version(opt_.ghost).impact);
    if (opt_.twin) set_companion(CompanionMode::Twin);
    else if (!opt_.ghost.empty()) set_companion(CompanionMode::Ghost);
    if (!opt_.browse.empty()) {   // the Load session window, its browser on that folder
        open_session_window(false);
        session_.browser.open_dir(opt_.browse);
    }
    if (!opt_.session.empty() && !load_session_file(opt_.session)) {
        if (opt_.frames > 0) {   // headless: checked before the window opened already
            error = session_.error;
            return false;
        }
        // By hand: the window opens on the Load session dialog, which shows what is wrong with the file.
        const std::string why = session_.error;
        open_session_window(false);
        session_.error = why;
        std::snprintf(session_.path, sizeof session_.path, "%s", opt_.session.c_str());
    }
    if (!opt_.bifurcation.empty()) start_bifurcation();
    if (opt_.ramp_to >= 0) start_ramp(opt_.ramp_to, opt_.ramp_rate);
    frames_.last_time = now_s();
    return true;
}

void App::shutdown() {
    if (sim_) sim_->stop();
    if (imgui_ready_) {
        bif_.panel.release_gl();
        rig_.shutdown();
        analysis_.release_gl();
        plot_gpu::shutdown();
        release_plot_canvases();
        opaque_image::shutdown();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        imgui_ready_ = false;
    }
    if (win_) {
        glfwDestroyWindow(win_);
        win_ = nullptr;
    }
    if (glfw_ready_) {
        glfwTerminate();
        glfw_ready_ = false;
    }
}

void App::rebuild_fonts() {
    if (!view_.fonts_dirty) return;
    view_.fonts_dirty = false;
    ImGuiIO& io = ImGui::GetIO();
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.OversampleH = 2;
    cfg.OversampleV = 1;
    // Latin-1, Greek (ω, φ, π, κ, λ) and a few signs (², –, ·, →, −, ≤, ≥, ■): the panels speak the paper's symbols.
    static const ImWchar kRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x2027, 0x2190, 0x2193,
                                      0x2212, 0x2212, 0x2264, 0x2265, 0x25A0, 0x25CF, 0};
    cfg.GlyphRanges = kRanges;
    const float size = std::round(14.5f * view_.ui_scale);
    const std::string font = asset_path("fonts/DejaVuSans.ttf");   // share/impactlab when installed
    if (font.empty() || !io.Fonts->AddFontFromFileTTF(font.c_str(), size, &cfg)) {
        std::fprintf(stderr, "impactlab-gui: font fonts/DejaVuSans.ttf not found, using ImGui's default\n");
        ImFontConfig d;
        d.SizePixels = 13.0f * view_.ui_scale;
        io.Fonts->AddFontDefault(&d);
    }
    io.Fonts->Build();
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
    apply_theme(view_.dark, view_.ui_scale);
    bif_.dirty = true;
}

void App::toast(const std::string& msg) {
    toast_.show(msg, now_s());
    std::fprintf(stderr, "impactlab-gui: %s\n", msg.c_str());
}

// ---- actions: each one updates the UI's intent and sends a command -------------------------------------

void App::send(const SimCommand& c) {
    if (!commands_.send(c))
        toast(std::to_string(commands_.lost()) + " command(s) to the simulation lost: it has not taken any for a while");
}

void App::set_omega(double w) {
    ramp_.live.stop();   // the engine ends a ramp on any set omega
    run_.omega = std::clamp(w, 0.0, kMaxOmega);
    send(SimCommand::omega(run_.omega));
}

void App::set_xi(double xI) {
    run_.xI = std::clamp(xI, -kMaxAbsXI, kMaxAbsXI);
    run_.params.xI = run_.xI;
    send(SimCommand::xi(run_.xI));
}

void App::set_model(int stiffness, int impact) {
    run_.stiffness = std::clamp(stiffness, 0, static_cast<int>(stiffness_sets().size()) - 1);
    run_.impact = std::clamp(impact, 0, static_cast<int>(impact_models().size()) - 1);
    // The same version keeps its edited parameters, as the engine does (a preset of the running model).
    if (run_.params.name != model_name()) {
        run_.params = make_version(model_name());
        run_.params.xI = run_.xI;
        ++run_.params_rev;
    }
    send(SimCommand::set_model(model_name()));
}

bool App::set_param(const std::string& key, double value) {
    std::string error;
    const bool ok = gui::set_param(run_.params, key, value, error);
    params_panel_.set_error(ok ? std::string() : key + ": " + error);
    if (!ok) return false;
    ++run_.params_rev;
    send(SimCommand::set_param(key, value));
    return true;
}

void App::reset_params() {
    run_.params = make_version(model_name());
    run_.params.xI = run_.xI;
    ++run_.params_rev;
    params_panel_.set_error("");
    send(SimCommand::reset_params());
}

void App::run_demo(int k) {
    demos_.last = k;
    if (companion_.mode != CompanionMode::Off && k != 3) set_companion(CompanionMode::Off);
    switch (k) {
        case 1:   // period doubling: the first doubling of A1H at 10.86 rad/s, crossed in about 30 s of wall time
            set_version("A1H");
            set_omega(Demos::kDemo1From);
            set_demo_speed(20.0);
            start_ramp(Demos::kDemo1To, Demos::kDemo1Rate);
            break;
        case 2:   // the road to chaos: the live ramp over the diagram
            set_version("A1H");
            set_omega(9.0);
            set_demo_speed(50.0);
            start_bifurcation();
            start_ramp(16.0, 0.05);
            break;
        case 3: {   // the impact model: a ghost under G beside A1C in chaos
            set_version("A1C");
            apply_preset(presets_for("A1C")[2]);
            const auto& laws = impact_models();
            for (std::size_t i = 0; i < laws.size(); ++i)
                if (std::string(laws[i].id) == "G") companion_.ghost_impact = static_cast<int>(i);
            set_companion(CompanionMode::Ghost);
            break;
        }
        case 4:   // the energy budget, in chaos: its balance is in the State group
            set_version("A1H");
            apply_preset(presets_for("A1H")[2]);
            layout_.controls_focus = 2;
            break;
        case 5:   // basins: A1G's two attractors at 13 rad/s
            set_version("A1G");
            set_omega(13.0);
            analysis_.basins.start(analysis_context());
            set_panel_visible(PanelId::Basins, true);
            break;
        default: demos_.last = 0; return;
    }
    toast(std::string(guide_demo(k).title) + ": " + guide_demo(k).look_for);
}

void App::set_demo_speed(double s) {
    // --warmup runs at 100x first: the demo's speed then follows it (a test reads a later moment of the demo).
    demos_.speed = s;
    if (!script_.warming) set_speed(s);
}

void App::set_version(const std::string& name) {
    const Params p = make_version(name);
    set_model(index_of_stiffness(p.stiffness_id), index_of_impact(p.impact));
}

void App::set_paused(bool p) {
    run_.paused = p;
    send(SimCommand::paused(p));
}

void App::step_period() {
    run_.paused = true;
    send(SimCommand::step_period());
}

void App::reset() {
    ramp_.live.stop();   // Reset restarts the drive at the omega reached
    send(SimCommand::reset(run_.x0, 0.0));
}

void App::set_speed(double s) {
    run_.speed = std::clamp(s, kMinSpeed, kMaxSpeed);
    send(SimCommand::speed(run_.speed));
}

void App::apply_preset(const Preset& p) {
    if (run_.xI != 0.0) set_xi(0.0);
    run_.omega = p.omega;
    run_.x0 = p.x0;
    ramp_.live.stop();
    send(SimCommand::omega(run_.omega));
    send(SimCommand::reset(run_.x0, 0.0));
    if (run_.paused) set_paused(false);
    toast(model_name() + ": " + p.label + " (ω = " + std::to_string(p.omega).substr(0, 5) + " rad/s)");
}

void App::clear_poincare() {
    feed_.sections.clear();
    feed_.pc_map.reset();
    feed_.pc_feed.reset();
}

void App::screenshot(const std::string& path) { frames_.pending_shot = path; }

void App::open_user_file(const std::string& path) { g_handed.push_back(path); }

void App::open_handed_files() {
    std::vector<std::string> files;
    files.swap(g_handed);
    for (const std::string& path : files) {
        std::string ext = std::filesystem::path(path).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext == ".json") {   // a session; a file of another kind is refused by the loader, which says why
            load_session_file(path);
            continue;
        }
        view_.show_data = true;   // the record's window, where its load and any error show
        data_panel_.load(path, false);
        toast("opening " + utf8_escaped(path) + " as a measured record");
    }
}

std::string App::screenshot_name() const { return "impactlab-" + model_name() + "-" + timestamp() + ".png"; }

void App::export_csv() {
    const std::string base = "impactlab-" + model_name() + "-" + timestamp();
    const bool a = write_trajectory_csv(base + "-trajectory.csv", feed_.traj, model_name());
    const bool b = write_sections_csv(base + "-sections.csv", feed_.sections, model_name());
    if (a && b) toast("exported " + base + "-trajectory.csv (" + std::to_string(feed_.traj.size()) + " samples) and -sections.csv (" +
                      std::to_string(feed_.sections.size()) + " points)");
    else toast("export failed: cannot write " + base + "-*.csv in the current folder");
}

// ---- per frame -------------------------------------------------------------------------------------------

void App::drain_samples() {
    feed_.frame_max_force = 0;
    const double phi_before = feed_.have_last ? feed_.last.phi : 0.0;
    const double wall = now_s();
#ifdef __EMSCRIPTEN__
    sim_->pump();   // a browser page has no threads: the engine's slice runs here, before the drain
#endif
    sim_->samples().drain([&](const SimMsg& m) {
        if (m.source != 0) {   // the companion cart: its own track, compared with the cart's samples
            if (companion_.mode != CompanionMode::Off) companion_.track.on_msg(m, feed_.traj);
            return;
        }
        if (skip_until_restart(m)) return;   // a replay's "continue" or a session: the old run's leftovers
        if (m.epoch != feed_.epoch) {
            // The dynamics changed: the Poincare map of the old attractor no longer applies, and the new
            // one is transient until the map has settled again.
            feed_.sections.clear();
            feed_.pc_map.reset();
            feed_.pc_feed.reset();
            feed_.impacts_seen = 0;
            feed_.have_grazing = false;
            if (feed_.have_last && m.t < feed_.last.t) {   // a reset: time starts over
                feed_.traj.clear();
                feed_.impact_label.reset();
            }
            feed_.epoch = m.epoch;
        }
        feed_.pc_feed.on_msg(m, feed_.pc_map);
        if (ramp_.live.active()) {
            if (m.kind == MsgKind::Sample && m.source == 0) run_.omega = m.omega;   // the slider follows the ramp
            if (ramp_.live.on_msg(m))
                toast("ramp done: ω = " + std::to_string(ramp_.live.target()).substr(0, 5) + " rad/s, " +
                      std::to_string(ramp_.live.points().size()) + " section points on the diagram");
        }
        switch (m.kind) {
            case MsgKind::Sample:
                feed_.traj.push(m);
                feed_.last = m;
                feed_.have_last = true;
                ++feed_.samples_seen;
                feed_.frame_max_force = std::max(feed_.frame_max_force, m.force);
                feed_.impact_label.sample(m.t, wall, m.force);
                break;
            case MsgKind::Section:
                feed_.sections.push(m);
                break;
            case MsgKind::Impact:
                ++feed_.impacts_seen;
                feed_.impact_label.impact(m.t, wall, m.force);
                feed_.flash = std::max(feed_.flash, std::clamp(m.force / 0.25, 0.25, 1.0));
                break;
            case MsgKind::Grazing:
                feed_.grazing = m;
                feed_.have_grazing = true;
                break;
        }
    });
    feed_.phi_prev = phi_before;
}

void App::handle_keys() {
    ImGuiIO& io = ImGui::GetIO();
    auto pressed = [](int key, bool repeat = false) { return ImGui::IsKeyPressed(key, repeat); };
    const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
    // Ctrl+S and Ctrl+O type nothing: they also work from a text field (the session window's own path).
    if (ctrl && pressed(GLFW_KEY_S)) open_session_window(true);
    if (ctrl && pressed(GLFW_KEY_O)) open_session_window(false);
    if (io.WantTextInput) return;
    // Replay (Shift+R) has its own Space, Left/Right, , . Enter and Esc (app_replay.cpp).
    const bool replaying = replay_.player.active();
    handle_replay_keys();
    if (!replaying) handle_layout_keys();   // P presentation, V its plot, Z maximise, Esc restore (tiles.cpp)
    if (!replaying) {
        if (pressed(GLFW_KEY_SPACE)) set_paused(!run_.paused);
        if (pressed(GLFW_KEY_N, true) || pressed(GLFW_KEY_PERIOD, true)) step_period();
        if (pressed(GLFW_KEY_R) && !ctrl && !shift) reset();
        if (pressed(GLFW_KEY_RIGHT, true)) set_omega(run_.omega + (shift ? 1.0 : 0.1));
        if (pressed(GLFW_KEY_LEFT, true)) set_omega(run_.omega - (shift ? 1.0 : 0.1));
    }
    if (pressed(GLFW_KEY_UP, true)) set_xi(run_.xI + (shift ? 2e-3 : 5e-4));
    if (pressed(GLFW_KEY_DOWN, true)) set_xi(run_.xI - (shift ? 2e-3 : 5e-4));
    if (pressed(GLFW_KEY_RIGHT_BRACKET, true) || (!ctrl && pressed(GLFW_KEY_KP_ADD, true))) set_speed(run_.speed * 2.0);
    if (pressed(GLFW_KEY_LEFT_BRACKET, true) || (!ctrl && pressed(GLFW_KEY_KP_SUBTRACT, true))) set_speed(run_.speed / 2.0);
    if (pressed(GLFW_KEY_M) && !ctrl) set_model(run_.stiffness, next_impact_law(run_.impact));
    if (pressed(GLFW_KEY_K) && !ctrl) set_model((run_.stiffness + 1) % static_cast<int>(stiffness_sets().size()), run_.impact);
    if (pressed(GLFW_KEY_C) && !ctrl) clear_poincare();
    if (pressed(GLFW_KEY_B) && !ctrl) {
        if (const std::string msg = bif_.panel.toggle(bifurcation_context()); !msg.empty()) toast(msg);
    }
    if (pressed(GLFW_KEY_T) && !ctrl) {
        view_.dark = !view_.dark;
        apply_theme(view_.dark, view_.ui_scale);
        bif_.dirty = true;
    }
    if (pressed(GLFW_KEY_F1) || (pressed(GLFW_KEY_SLASH) && shift)) view_.show_help = !view_.show_help;
    if (pressed(GLFW_KEY_H) && !ctrl) view_.show_help = !view_.show_help;
    if (pressed(GLFW_KEY_F12)) screenshot(screenshot_name());
    if (pressed(GLFW_KEY_F4)) view_.show_params = !view_.show_params;
    if (ctrl && pressed(GLFW_KEY_E)) export_csv();
    if (ctrl && (pressed(GLFW_KEY_EQUAL) || pressed(GLFW_KEY_KP_ADD))) {
        view_.ui_scale = std::min(3.0f, view_.ui_scale + 0.25f);
        view_.fonts_dirty = true;
    }
    if (ctrl && (pressed(GLFW_KEY_MINUS) || pressed(GLFW_KEY_KP_SUBTRACT))) {
        view_.ui_scale = std::max(0.5f, view_.ui_scale - 0.25f);
        view_.fonts_dirty = true;
    }
    if (ctrl && pressed(GLFW_KEY_Q)) glfwSetWindowShouldClose(win_, GLFW_TRUE);
    for (int i = 0; i < 4; ++i) {
        if (pressed(GLFW_KEY_1 + i)) {
            const auto list = presets_for(model_name());
            if (static_cast<std::size_t>(i) < list.size()) apply_preset(list[static_cast<std::size_t>(i)]);
        }
    }
}

// frame(), after the backend's new frame: the keys the scripted runs and the taps hold for this frame.
void App::apply_scripted_keys() {
    // A tap released within the poll it was pressed in: down for this frame, up at the next.
    {
        ImGuiIO& io = ImGui::GetIO();
        for (const int key : g_held)
            if (std::find(g_pressed.begin(), g_pressed.end(), key) == g_pressed.end()) io.KeysDown[key] = false;
        g_held.clear();
        for (const int key : g_pressed)
            if (!io.KeysDown[key]) {
                io.KeysDown[key] = true;
                g_held.push_back(key);
            }
        g_pressed.clear();
    }
    if (!opt_.press.empty() && (frames_.count == 3 || frames_.count == 4)) {
        // --press: down at frame 3, up at frame 4, as the GLFW backend's key callback sets them.
        ImGuiIO& io = ImGui::GetIO();
        const bool ctrl = opt_.press.rfind("ctrl+", 0) == 0;
        const int key = GLFW_KEY_A + (opt_.press.back() - 'a');
        const bool down = frames_.count == 3;
        io.KeysDown[key] = down;
        io.KeysDown[GLFW_KEY_LEFT_CONTROL] = down && ctrl;
        io.KeyCtrl = down && ctrl;
    }
}

// frame(), once the samples are drained: the first frame's scripted changes (--set-state, --param, --demo),
// and the end of --warmup.
void App::run_frame_script() {
    if (opt_.set_state && frames_.count == 1) set_state(opt_.set_x, opt_.set_v);   // --set-state, as a click
    if (frames_.count == 1)
        for (const auto& [key, value] : opt_.params) set_param(key, value);   // --param, as typed in the panel
    if (frames_.count == 1 && opt_.demo > 0) {   // --demo, as its button
        run_demo(opt_.demo);
        demos_.panel.move_aside();
    }
    if (script_.warming && feed_.have_last && feed_.last.t >= opt_.warmup) {
        script_.warming = false;
        set_speed(demos_.speed > 0 ? demos_.speed : opt_.speed);   // a demo's own speed, once warmed up
        if (opt_.paused) set_paused(true);
    }
}

// frame(), once the previous frame is shown: this one rendered into the back buffer (fw x fh pixels), and
// the screenshot asked for saved from it.
void App::render(int& fw, int& fh) {
    glfwGetFramebufferSize(win_, &fw, &fh);
    glViewport(0, 0, fw, fh);
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1.0f);   // the tiles' background (they draw none themselves)
    glClear(GL_COLOR_BUFFER_BIT);
    // The tiles' plot areas: scissored clears, which cost next to nothing, instead of blended rectangles.
    const ImVec2 fbs = ImGui::GetIO().DisplayFramebufferScale;
    glEnable(GL_SCISSOR_TEST);
    for (const PlotBackdrop& b : take_plot_backdrops()) {
        const ImVec4 c = ImGui::ColorConvertU32ToFloat4(b.color);
        const int x0 = static_cast<int>(std::lround(b.min.x * fbs.x)), x1 = static_cast<int>(std::lround(b.max.x * fbs.x));
        const int y0 = static_cast<int>(std::lround(b.min.y * fbs.y)), y1 = static_cast<int>(std::lround(b.max.y * fbs.y));
        glScissor(x0, fh - y1, x1 - x0, y1 - y0);
        glClearColor(c.x, c.y, c.z, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glDisable(GL_SCISSOR_TEST);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!frames_.pending_shot.empty()) {
        glReadBuffer(GL_BACK);
        std::string err;
        if (save_framebuffer_png(frames_.pending_shot, fw, fh, err)) toast("screenshot saved: " + frames_.pending_shot);
        else {
            toast("screenshot failed: " + err);
            if (opt_.frames > 0) script_.exit_code = 1;
        }
        frames_.pending_shot.clear();
    }
}

void App::frame() {
    const double t_events = now_s();
    glfwPollEvents();
    if (opt_.tap && frames_.count == 3) {   // --tap: a press and its release in one poll, through the backend
        const int key = GLFW_KEY_A + (opt_.tap - 'a');
        ImGui_ImplGlfw_KeyCallback(win_, key, 0, GLFW_PRESS, 0);
        ImGui_ImplGlfw_KeyCallback(win_, key, 0, GLFW_RELEASE, 0);
    }
    rebuild_fonts();
    const double t = now_s();
    frames_.tick(t);
    feed_.flash *= std::exp(-frames_.dt / 0.22);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    apply_scripted_keys();
    script_mouse();
    ImGui::NewFrame();
    plot_gpu::begin_frame();
    opaque_image::begin_frame();
    commands_.flush();   // what the ring refused last frame, before this frame's own commands
    if (!bench_.on) drain_samples();
    feed_.xI_shown = sim_->status().xI;
    run_frame_script();
    poll_bifurcation();
    handle_keys();
    begin_replay_frame();   // replaying: the panels draw the cursor's instant
    layout_and_draw();
    draw_clip_window();
    draw_session_window();
    end_replay_frame();
    handle_session_request();
    open_handed_files();
    ImGui::Render();
    const double t_built = now_s();
    // The previous frame is shown only now, once this one is built: under a software renderer its
    // rasterization ran on the driver's threads while this thread built the UI (one frame of latency).
    if (frames_.pending) glfwSwapBuffers(win_);
    frames_.pending = false;
    const double t_shown = now_s();
    flush_canvas_uploads();   // the plots' images, now that the rig's has had the build's time to render
    plot_gpu::upload();

    int fw = 0, fh = 0;
    render(fw, fh);
    capture_clip_frame(fw, fh);   // exporting a clip: this frame
    glFlush();   // rendering starts now; the next frame's swap shows it
    frames_.pending = true;
    if (bench_.on) {
        bench_.events_s += t - t_events;
        bench_.build_s += t_built - t;
        bench_.wait_s += t_shown - t_built;
        bench_.submit_s += now_s() - t_shown;
    }
    ++frames_.count;
}

int App::run() {
    std::string error;
    if (!init(error)) {
        std::fprintf(stderr, "impactlab-gui: error: %s\n", error.c_str());
        return 1;
    }
    if (bench_.on) return run_bench();
    if (opt_.soak > 0) return soak();

    while (!glfwWindowShouldClose(win_) && loop_once()) {}
    return finish();
}

bool App::loop_once() {
    if (bench_.on) return bench_frame();   // a page's --bench-plot (the desktop's runs in run_bench)
    frame();
    if (opt_.frames <= 0) return true;
    // Headless run: with a diagram requested, the frames are counted once it is done.
    const bool waiting = bif_.panel.busy() || script_.warming ||
                         (!opt_.data.empty() && data_panel_.busy()) || analysis_.busy();
    if (waiting) {
        if (frames_.count % 600 == 0 && frames_.count > 0)
            std::fprintf(stderr, "impactlab-gui: waiting for the bifurcation diagram (%.0f%%)\n", 100 * bif_.panel.progress());
        return true;
    }
    ++frames_.counted;
    return script_step();
}

int App::finish() {
    const SimStatus st = sim_->status();
    const double t_reached = feed_.have_last ? feed_.last.t : st.sim_time;
    std::printf("impactlab-gui: frames=%ld model=%s sim_time=%.6f samples=%llu dropped=%llu epoch=%u\n", frames_.count,
                model_name().c_str(), t_reached, static_cast<unsigned long long>(feed_.samples_seen),
                static_cast<unsigned long long>(st.dropped), feed_.epoch);
    std::fflush(stdout);
    if (opt_.frames > 0 && !opt_.data.empty()) {
        if (const std::string& err = data_panel_.error(); !err.empty()) {
            std::fprintf(stderr, "impactlab-gui: error: --data %s: %s\n", opt_.data.c_str(), err.c_str());
            script_.exit_code = 1;
        }
    }
    if (opt_.frames > 0 && !analysis_.startup_error().empty()) {   // a bad --plane file, a failed job
        std::fprintf(stderr, "impactlab-gui: error: %s\n", analysis_.startup_error().c_str());
        script_.exit_code = 1;
    }
    if (!opt_.state_json.empty() && !write_state_json(opt_.state_json)) script_.exit_code = 1;
    if (!clip_.error.empty()) script_.exit_code = 1;
    if (!opt_.save_session.empty() && !save_session_file(opt_.save_session)) {
        std::fprintf(stderr, "impactlab-gui: error: --save-session: %s\n", session_.error.c_str());
        script_.exit_code = 1;
    }
    return script_.exit_code;
}

}  // namespace impactlab::gui
