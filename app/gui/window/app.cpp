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
    params_ = make_version(opt.model);
    stiffness_ = index_of_stiffness(params_.stiffness_id);
    impact_ = index_of_impact(params_.impact);
    omega_ = opt.omega;
    xI_ = opt.xI;
    params_.xI = xI_;
    speed_ = opt.speed;
    paused_ = opt.paused;
    x0_ = opt.x0;
    dark_ = !opt.light;
    bif_steps_ = opt.bif_steps;
    if (opt.bifurcation == "cf-down") bif_protocol_ = 1;
    else if (opt.bifurcation == "ef") bif_protocol_ = 2;
    bif_panel_.configure(opt);
    bench_.on = opt.bench_plot;
    show_help_ = opt.show_help;
    show_params_ = opt.show_params;
    details_ = opt.details;
    poincare_.set_clicker(opt.clicker || !opt.orbits.empty());
    // The first screen teaches, unless the run is scripted (any flag that drives it or reads it back).
    show_guide_ = opt.guide || (opt.frames == 0 && !opt.bench_plot && opt.soak <= 0 && opt.session.empty() &&
                                opt.data.empty() && opt.demo == 0);
    if (!opt.strip.empty()) {   // --strip (checked by the options)
        const auto second = opt.strip.size() > 1 ? strip_from_key(opt.strip[1]) : std::nullopt;
        strip_.set_traces(strip_from_key(opt.strip[0]).value_or(StripQuantity::X), second);
    }
    if (!opt.data.empty()) {
        show_data_ = true;
        data_panel_.load(opt.data, true);
    }
    analysis_.configure(opt);   // --plane loads now; --continuation, --basins, --small-plane start at the first frame
    set_plot_backend(opt.plot_backend == "gpu" ? PlotBackend::Gpu
                     : opt.plot_backend == "imgui" ? PlotBackend::DrawList : PlotBackend::Raster);
}

App::~App() { shutdown(); }

double App::now_s() const { return glfwGetTime(); }

std::string App::model_name() const {
    return std::string(stiffness_sets()[static_cast<std::size_t>(stiffness_)].id) +
           impact_models()[static_cast<std::size_t>(impact_)].id;
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

    if (opt_.ui_scale > 0) ui_scale_ = static_cast<float>(opt_.ui_scale);
    else {
        float sx = 1, sy = 1;
        glfwGetWindowContentScale(win_, &sx, &sy);
        ui_scale_ = std::clamp(sx, 1.0f, 3.0f);
    }
    configure_layout();   // --presentation, --hide, --maximise, --magnify (tiles.cpp), before the fonts
    fonts_dirty_ = true;
    rebuild_fonts();

    if (!rig_.init(error)) return false;
    if (std::string perr; !plot_gpu::init(perr))
        std::fprintf(stderr, "impactlab-gui: GPU plot shaders refused, drawing plots with ImDrawList: %s\n", perr.c_str());
    if (std::string perr; !opaque_image::init(perr))
        std::fprintf(stderr, "impactlab-gui: image shader refused, drawing images with ImGui's: %s\n", perr.c_str());

    if (opt_.preset > 0) {
        // --preset N: the engine starts on it (no epoch change, nothing transient from the default omega).
        const Preset p = presets_for(model_name())[static_cast<std::size_t>(opt_.preset - 1)];
        omega_ = p.omega;
        x0_ = p.x0;
        xI_ = 0.0;
        params_.xI = 0.0;
    }
    EngineConfig cfg;
    cfg.model = model_name();
    cfg.omega = omega_;
    cfg.xI = xI_;
    cfg.x0 = x0_;
    cfg.v0 = opt_.preset > 0 ? 0.0 : opt_.v0;
    cfg.phi0 = section_phase_ = opt_.phi0;
    warming_ = opt_.warmup > 0 && !bench_.on;
    if (warming_) {
        speed_ = kMaxSpeed;
        paused_ = false;
    }
    cfg.speed = speed_;
    cfg.paused = (paused_ && !warming_) || bench_.on;
    sim_ = std::make_unique<SimThread>(cfg);
    commands_.attach(sim_.get());
    sim_->start();
    xI_shown_ = xI_;
    if (!opt_.ghost.empty()) ghost_impact_ = index_of_impact(make_version(opt_.ghost).impact);
    if (opt_.twin) set_companion(CompanionMode::Twin);
    else if (!opt_.ghost.empty()) set_companion(CompanionMode::Ghost);
    if (!opt_.browse.empty()) {   // the Load session window, its browser on that folder
        open_session_window(false);
        session_browser_.open_dir(opt_.browse);
    }
    if (!opt_.session.empty() && !load_session_file(opt_.session)) {
        if (opt_.frames > 0) {   // headless: checked before the window opened already
            error = session_error_;
            return false;
        }
        // By hand: the window opens on the Load session dialog, which shows what is wrong with the file.
        const std::string why = session_error_;
        open_session_window(false);
        session_error_ = why;
        std::snprintf(session_path_, sizeof session_path_, "%s", opt_.session.c_str());
    }
    if (!opt_.bifurcation.empty()) start_bifurcation();
    if (opt_.ramp_to >= 0) start_ramp(opt_.ramp_to, opt_.ramp_rate);
    last_frame_time_ = now_s();
    return true;
}

void App::shutdown() {
    if (sim_) sim_->stop();
    if (imgui_ready_) {
        bif_panel_.release_gl();
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
    if (!fonts_dirty_) return;
    fonts_dirty_ = false;
    ImGuiIO& io = ImGui::GetIO();
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.OversampleH = 2;
    cfg.OversampleV = 1;
    // Latin-1, Greek (ω, φ, π, κ, λ) and a few signs (², –, ·, →, −, ≤, ≥, ■): the panels speak the paper's symbols.
    static const ImWchar kRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x2027, 0x2190, 0x2193,
                                      0x2212, 0x2212, 0x2264, 0x2265, 0x25A0, 0x25CF, 0};
    cfg.GlyphRanges = kRanges;
    const float size = std::round(14.5f * ui_scale_);
    const std::string font = asset_path("fonts/DejaVuSans.ttf");   // share/impactlab when installed
    if (font.empty() || !io.Fonts->AddFontFromFileTTF(font.c_str(), size, &cfg)) {
        std::fprintf(stderr, "impactlab-gui: font fonts/DejaVuSans.ttf not found, using ImGui's default\n");
        ImFontConfig d;
        d.SizePixels = 13.0f * ui_scale_;
        io.Fonts->AddFontDefault(&d);
    }
    io.Fonts->Build();
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
    apply_theme(dark_, ui_scale_);
    bif_dirty_ = true;
}

void App::toast(const std::string& msg) {
    toast_ = msg;
    toast_until_ = now_s() + 4.0;
    std::fprintf(stderr, "impactlab-gui: %s\n", msg.c_str());
}

// ---- actions: each one updates the UI's intent and sends a command -------------------------------------

void App::send(const SimCommand& c) {
    if (!commands_.send(c))
        toast(std::to_string(commands_.lost()) + " command(s) to the simulation lost: it has not taken any for a while");
}

void App::set_omega(double w) {
    ramp_.stop();   // the engine ends a ramp on any set omega
    omega_ = std::clamp(w, 0.0, kMaxOmega);
    send(SimCommand::omega(omega_));
}

void App::set_xi(double xI) {
    xI_ = std::clamp(xI, -kMaxAbsXI, kMaxAbsXI);
    params_.xI = xI_;
    send(SimCommand::xi(xI_));
}

void App::set_model(int stiffness, int impact) {
    stiffness_ = std::clamp(stiffness, 0, static_cast<int>(stiffness_sets().size()) - 1);
    impact_ = std::clamp(impact, 0, static_cast<int>(impact_models().size()) - 1);
    // The same version keeps its edited parameters, as the engine does (a preset of the running model).
    if (params_.name != model_name()) {
        params_ = make_version(model_name());
        params_.xI = xI_;
        ++params_rev_;
    }
    send(SimCommand::set_model(model_name()));
}

bool App::set_param(const std::string& key, double value) {
    std::string error;
    const bool ok = gui::set_param(params_, key, value, error);
    params_panel_.set_error(ok ? std::string() : key + ": " + error);
    if (!ok) return false;
    ++params_rev_;
    send(SimCommand::set_param(key, value));
    return true;
}

void App::reset_params() {
    params_ = make_version(model_name());
    params_.xI = xI_;
    ++params_rev_;
    params_panel_.set_error("");
    send(SimCommand::reset_params());
}

void App::run_demo(int k) {
    demo_ = k;
    if (companion_mode_ != CompanionMode::Off && k != 3) set_companion(CompanionMode::Off);
    switch (k) {
        case 1:   // period doubling: the first doubling of A1H at 10.86 rad/s, crossed in about 30 s of wall time
            set_version("A1H");
            set_omega(kDemo1From);
            set_demo_speed(20.0);
            start_ramp(kDemo1To, kDemo1Rate);
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
                if (std::string(laws[i].id) == "G") ghost_impact_ = static_cast<int>(i);
            set_companion(CompanionMode::Ghost);
            break;
        }
        case 4:   // the energy budget, in chaos: its balance is in the State group
            set_version("A1H");
            apply_preset(presets_for("A1H")[2]);
            controls_focus_ = 2;
            break;
        case 5:   // basins: A1G's two attractors at 13 rad/s
            set_version("A1G");
            set_omega(13.0);
            analysis_.basins.start(analysis_context());
            set_panel_visible(PanelId::Basins, true);
            break;
        default: demo_ = 0; return;
    }
    toast(std::string(guide_demo(k).title) + ": " + guide_demo(k).look_for);
}

void App::set_demo_speed(double s) {
    // --warmup runs at 100x first: the demo's speed then follows it (a test reads a later moment of the demo).
    demo_speed_ = s;
    if (!warming_) set_speed(s);
}

void App::set_version(const std::string& name) {
    const Params p = make_version(name);
    set_model(index_of_stiffness(p.stiffness_id), index_of_impact(p.impact));
}

void App::set_paused(bool p) {
    paused_ = p;
    send(SimCommand::paused(p));
}

void App::step_period() {
    paused_ = true;
    send(SimCommand::step_period());
}

void App::reset() {
    ramp_.stop();   // Reset restarts the drive at the omega reached
    send(SimCommand::reset(x0_, 0.0));
}

void App::set_speed(double s) {
    speed_ = std::clamp(s, kMinSpeed, kMaxSpeed);
    send(SimCommand::speed(speed_));
}

void App::apply_preset(const Preset& p) {
    if (xI_ != 0.0) set_xi(0.0);
    omega_ = p.omega;
    x0_ = p.x0;
    ramp_.stop();
    send(SimCommand::omega(omega_));
    send(SimCommand::reset(x0_, 0.0));
    if (paused_) set_paused(false);
    toast(model_name() + ": " + p.label + " (ω = " + std::to_string(p.omega).substr(0, 5) + " rad/s)");
}

void App::clear_poincare() {
    sections_.clear();
    pc_map_.reset();
    pc_feed_.reset();
}

void App::screenshot(const std::string& path) { pending_shot_ = path; }

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
        show_data_ = true;   // the record's window, where its load and any error show
        data_panel_.load(path, false);
        toast("opening " + utf8_escaped(path) + " as a measured record");
    }
}

std::string App::screenshot_name() const { return "impactlab-" + model_name() + "-" + timestamp() + ".png"; }

void App::export_csv() {
    const std::string base = "impactlab-" + model_name() + "-" + timestamp();
    const bool a = write_trajectory_csv(base + "-trajectory.csv", traj_, model_name());
    const bool b = write_sections_csv(base + "-sections.csv", sections_, model_name());
    if (a && b) toast("exported " + base + "-trajectory.csv (" + std::to_string(traj_.size()) + " samples) and -sections.csv (" +
                      std::to_string(sections_.size()) + " points)");
    else toast("export failed: cannot write " + base + "-*.csv in the current folder");
}

// ---- per frame -------------------------------------------------------------------------------------------

void App::drain_samples() {
    frame_max_force_ = 0;
    const double phi_before = have_last_ ? last_.phi : 0.0;
    const double wall = now_s();
#ifdef __EMSCRIPTEN__
    sim_->pump();   // a browser page has no threads: the engine's slice runs here, before the drain
#endif
    sim_->samples().drain([&](const SimMsg& m) {
        if (m.source != 0) {   // the companion cart: its own track, compared with the cart's samples
            if (companion_mode_ != CompanionMode::Off) companion_.on_msg(m, traj_);
            return;
        }
        if (skip_until_restart(m)) return;   // a replay's "continue" or a session: the old run's leftovers
        if (m.epoch != epoch_) {
            // The dynamics changed: the Poincare map of the old attractor no longer applies, and the new
            // one is transient until the map has settled again.
            sections_.clear();
            pc_map_.reset();
            pc_feed_.reset();
            impacts_seen_ = 0;
            have_grazing_ = false;
            if (have_last_ && m.t < last_.t) {   // a reset: time starts over
                traj_.clear();
                impact_label_.reset();
            }
            epoch_ = m.epoch;
        }
        pc_feed_.on_msg(m, pc_map_);
        if (ramp_.active()) {
            if (m.kind == MsgKind::Sample && m.source == 0) omega_ = m.omega;   // the slider follows the ramp
            if (ramp_.on_msg(m))
                toast("ramp done: ω = " + std::to_string(ramp_.target()).substr(0, 5) + " rad/s, " +
                      std::to_string(ramp_.points().size()) + " section points on the diagram");
        }
        switch (m.kind) {
            case MsgKind::Sample:
                traj_.push(m);
                last_ = m;
                have_last_ = true;
                ++samples_seen_;
                frame_max_force_ = std::max(frame_max_force_, m.force);
                impact_label_.sample(m.t, wall, m.force);
                break;
            case MsgKind::Section:
                sections_.push(m);
                break;
            case MsgKind::Impact:
                ++impacts_seen_;
                impact_label_.impact(m.t, wall, m.force);
                flash_ = std::max(flash_, std::clamp(m.force / 0.25, 0.25, 1.0));
                break;
            case MsgKind::Grazing:
                grazing_ = m;
                have_grazing_ = true;
                break;
        }
    });
    phi_prev_ = phi_before;
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
    const bool replaying = replay_.active();
    handle_replay_keys();
    if (!replaying) handle_layout_keys();   // P presentation, V its plot, Z maximise, Esc restore (tiles.cpp)
    if (!replaying) {
        if (pressed(GLFW_KEY_SPACE)) set_paused(!paused_);
        if (pressed(GLFW_KEY_N, true) || pressed(GLFW_KEY_PERIOD, true)) step_period();
        if (pressed(GLFW_KEY_R) && !ctrl && !shift) reset();
        if (pressed(GLFW_KEY_RIGHT, true)) set_omega(omega_ + (shift ? 1.0 : 0.1));
        if (pressed(GLFW_KEY_LEFT, true)) set_omega(omega_ - (shift ? 1.0 : 0.1));
    }
    if (pressed(GLFW_KEY_UP, true)) set_xi(xI_ + (shift ? 2e-3 : 5e-4));
    if (pressed(GLFW_KEY_DOWN, true)) set_xi(xI_ - (shift ? 2e-3 : 5e-4));
    if (pressed(GLFW_KEY_RIGHT_BRACKET, true) || (!ctrl && pressed(GLFW_KEY_KP_ADD, true))) set_speed(speed_ * 2.0);
    if (pressed(GLFW_KEY_LEFT_BRACKET, true) || (!ctrl && pressed(GLFW_KEY_KP_SUBTRACT, true))) set_speed(speed_ / 2.0);
    if (pressed(GLFW_KEY_M) && !ctrl) set_model(stiffness_, next_impact_law(impact_));
    if (pressed(GLFW_KEY_K) && !ctrl) set_model((stiffness_ + 1) % static_cast<int>(stiffness_sets().size()), impact_);
    if (pressed(GLFW_KEY_C) && !ctrl) clear_poincare();
    if (pressed(GLFW_KEY_B) && !ctrl) {
        if (const std::string msg = bif_panel_.toggle(bifurcation_context()); !msg.empty()) toast(msg);
    }
    if (pressed(GLFW_KEY_T) && !ctrl) {
        dark_ = !dark_;
        apply_theme(dark_, ui_scale_);
        bif_dirty_ = true;
    }
    if (pressed(GLFW_KEY_F1) || (pressed(GLFW_KEY_SLASH) && shift)) show_help_ = !show_help_;
    if (pressed(GLFW_KEY_H) && !ctrl) show_help_ = !show_help_;
    if (pressed(GLFW_KEY_F12)) screenshot(screenshot_name());
    if (pressed(GLFW_KEY_F4)) show_params_ = !show_params_;
    if (ctrl && pressed(GLFW_KEY_E)) export_csv();
    if (ctrl && (pressed(GLFW_KEY_EQUAL) || pressed(GLFW_KEY_KP_ADD))) {
        ui_scale_ = std::min(3.0f, ui_scale_ + 0.25f);
        fonts_dirty_ = true;
    }
    if (ctrl && (pressed(GLFW_KEY_MINUS) || pressed(GLFW_KEY_KP_SUBTRACT))) {
        ui_scale_ = std::max(0.5f, ui_scale_ - 0.25f);
        fonts_dirty_ = true;
    }
    if (ctrl && pressed(GLFW_KEY_Q)) glfwSetWindowShouldClose(win_, GLFW_TRUE);
    for (int i = 0; i < 4; ++i) {
        if (pressed(GLFW_KEY_1 + i)) {
            const auto list = presets_for(model_name());
            if (static_cast<std::size_t>(i) < list.size()) apply_preset(list[static_cast<std::size_t>(i)]);
        }
    }
}

void App::frame() {
    const double t_events = now_s();
    glfwPollEvents();
    if (opt_.tap && frame_count_ == 3) {   // --tap: a press and its release in one poll, through the backend
        const int key = GLFW_KEY_A + (opt_.tap - 'a');
        ImGui_ImplGlfw_KeyCallback(win_, key, 0, GLFW_PRESS, 0);
        ImGui_ImplGlfw_KeyCallback(win_, key, 0, GLFW_RELEASE, 0);
    }
    rebuild_fonts();
    const double t = now_s();
    frame_dt_ = std::clamp(t - last_frame_time_, 1e-4, 0.25);
    last_frame_time_ = t;
    // Frames counted over half a second of wall time: an average of 1/dt would follow a burst of frames
    // shown back to back (a swap deferred, a resize) up to 1000 fps and more.
    ++fps_frames_;
    if (fps_since_ <= 0) fps_since_ = t;
    if (t - fps_since_ >= 0.5 || (fps_ <= 0 && fps_frames_ >= 3 && t > fps_since_)) {
        fps_ = fps_frames_ / (t - fps_since_);
        fps_frames_ = 0;
        fps_since_ = t;
    }
    flash_ *= std::exp(-frame_dt_ / 0.22);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    {   // a tap released within the poll it was pressed in: down for this frame, up at the next
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
    if (!opt_.press.empty() && (frame_count_ == 3 || frame_count_ == 4)) {
        // --press: down at frame 3, up at frame 4, as the GLFW backend's key callback sets them.
        ImGuiIO& io = ImGui::GetIO();
        const bool ctrl = opt_.press.rfind("ctrl+", 0) == 0;
        const int key = GLFW_KEY_A + (opt_.press.back() - 'a');
        const bool down = frame_count_ == 3;
        io.KeysDown[key] = down;
        io.KeysDown[GLFW_KEY_LEFT_CONTROL] = down && ctrl;
        io.KeyCtrl = down && ctrl;
    }
    script_mouse();
    ImGui::NewFrame();
    plot_gpu::begin_frame();
    opaque_image::begin_frame();
    commands_.flush();   // what the ring refused last frame, before this frame's own commands
    if (!bench_.on) drain_samples();
    xI_shown_ = sim_->status().xI;
    if (opt_.set_state && frame_count_ == 1) set_state(opt_.set_x, opt_.set_v);   // --set-state, as a click
    if (frame_count_ == 1)
        for (const auto& [key, value] : opt_.params) set_param(key, value);   // --param, as typed in the panel
    if (frame_count_ == 1 && opt_.demo > 0) {   // --demo, as its button
        run_demo(opt_.demo);
        guide_.move_aside();
    }
    if (warming_ && have_last_ && last_.t >= opt_.warmup) {
        warming_ = false;
        set_speed(demo_speed_ > 0 ? demo_speed_ : opt_.speed);   // a demo's own speed, once warmed up
        if (opt_.paused) set_paused(true);
    }
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
    if (frame_pending_) glfwSwapBuffers(win_);
    frame_pending_ = false;
    const double t_shown = now_s();
    flush_canvas_uploads();   // the plots' images, now that the rig's has had the build's time to render
    plot_gpu::upload();

    int fw = 0, fh = 0;
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
    if (!pending_shot_.empty()) {
        glReadBuffer(GL_BACK);
        std::string err;
        if (save_framebuffer_png(pending_shot_, fw, fh, err)) toast("screenshot saved: " + pending_shot_);
        else {
            toast("screenshot failed: " + err);
            if (opt_.frames > 0) exit_code_ = 1;
        }
        pending_shot_.clear();
    }
    capture_clip_frame(fw, fh);   // exporting a clip: this frame
    glFlush();   // rendering starts now; the next frame's swap shows it
    frame_pending_ = true;
    if (bench_.on) {
        bench_.events_s += t - t_events;
        bench_.build_s += t_built - t;
        bench_.wait_s += t_shown - t_built;
        bench_.submit_s += now_s() - t_shown;
    }
    ++frame_count_;
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
    frame();
    if (opt_.frames <= 0) return true;
    // Headless run: with a diagram requested, the frames are counted once it is done.
    const bool waiting = bif_panel_.busy() || warming_ ||
                         (!opt_.data.empty() && data_panel_.busy()) || analysis_.busy();
    if (waiting) {
        if (frame_count_ % 600 == 0 && frame_count_ > 0)
            std::fprintf(stderr, "impactlab-gui: waiting for the bifurcation diagram (%.0f%%)\n", 100 * bif_panel_.progress());
        return true;
    }
    ++counted_frames_;
    return script_step();
}

int App::finish() {
    const SimStatus st = sim_->status();
    const double t_reached = have_last_ ? last_.t : st.sim_time;
    std::printf("impactlab-gui: frames=%ld model=%s sim_time=%.6f samples=%llu dropped=%llu epoch=%u\n", frame_count_,
                model_name().c_str(), t_reached, static_cast<unsigned long long>(samples_seen_),
                static_cast<unsigned long long>(st.dropped), epoch_);
    std::fflush(stdout);
    if (opt_.frames > 0 && !opt_.data.empty()) {
        if (const std::string& err = data_panel_.error(); !err.empty()) {
            std::fprintf(stderr, "impactlab-gui: error: --data %s: %s\n", opt_.data.c_str(), err.c_str());
            exit_code_ = 1;
        }
    }
    if (opt_.frames > 0 && !analysis_.startup_error().empty()) {   // a bad --plane file, a failed job
        std::fprintf(stderr, "impactlab-gui: error: %s\n", analysis_.startup_error().c_str());
        exit_code_ = 1;
    }
    if (!opt_.state_json.empty() && !write_state_json(opt_.state_json)) exit_code_ = 1;
    if (!clip_error_.empty()) exit_code_ = 1;
    if (!opt_.save_session.empty() && !save_session_file(opt_.save_session)) {
        std::fprintf(stderr, "impactlab-gui: error: --save-session: %s\n", session_error_.c_str());
        exit_code_ = 1;
    }
    return exit_code_;
}

}  // namespace impactlab::gui
