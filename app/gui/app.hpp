// The visualiser's UI thread: GLFW window, OpenGL 3.3 core context, Dear ImGui, and the panels.
// It owns nothing of the simulation: it sends commands to the SimThread and drains its samples each frame
// into its own histories (History<SimMsg>). Drawing and physics stay apart: the only core calls here are
// the model's registry, the potential V(x) and the force laws for display.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis_panels.hpp"
#include "lyapunov_live.hpp"
#include "bifurcation_job.hpp"
#include "data_panel.hpp"
#include "history.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "options.hpp"
#include "plot2d.hpp"
#include "poincare_map.hpp"
#include "presets.hpp"
#include "rig_view.hpp"
#include "sim_thread.hpp"
#include "view_fit.hpp"

struct GLFWwindow;

namespace impactlab::gui {

class App {
public:
    explicit App(const Options& opt);
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;
    // Runs until the window closes (or --frames / --bench-plot is done). Returns the exit code.
    int run();

private:
    // app.cpp: life cycle, frame, input, actions
    bool init(std::string& error);
    void shutdown();
    void rebuild_fonts();
    void frame();
    void drain_samples();
    void poll_bifurcation();
    void handle_keys();
    void set_omega(double w);
    void set_xi(double xI);
    void set_model(int stiffness, int impact);
    void set_paused(bool p);
    void step_period();
    void reset();
    void set_speed(double s);
    void apply_preset(const Preset& p);
    void clear_poincare();   // the user's "clear": the map settles afresh from the next point
    bool write_state_json(const std::string& path);   // --state-json: what the panels show, as JSON
    void start_bifurcation();
    void screenshot(const std::string& path);
    std::string screenshot_name() const;
    void export_csv();
    void toast(const std::string& msg);
    std::string model_name() const;
    double now_s() const;
    int soak();   // --soak: model switches at 100x with an RSS report
    void fill_bench_data(int points);
    void feed_bench_frame();   // appends one frame's worth of new samples (bench mode)

    // panels.cpp: one function per window
    void layout_and_draw();
    void draw_menu();
    void draw_controls();
    void draw_rig();
    void draw_phase();
    void draw_poincare();
    void draw_potential();
    void draw_strip();
    void draw_bifurcation();
    void draw_status();
    void draw_help();
    void draw_toast();
    DataPanelContext data_context() const;
    AnalysisContext analysis_context() const;           // analysis_hooks.cpp
    void apply_analysis(const AnalysisAction& a);       // analysis_hooks.cpp: a click's commands
    void update_density_texture(int w, int h);
    std::size_t trail_first() const;   // the first sample of the phase portrait's trail
    template <class F>
    void timed(int slot, F&& draw);
    static constexpr const char* kPanelNames[7] = {"controls", "rig", "bifurcation", "phase", "poincare", "potential", "x(t)"};
    double panel_s_[7] = {};

    Options opt_;
    GLFWwindow* win_ = nullptr;
    std::unique_ptr<SimThread> sim_;
    BifurcationJob bif_;
    DataPanel data_panel_;             // "Measured data": load, fit, effects on and off
    bool show_data_ = false;
    LiveLyapunov lyapunov_live_;       // lambda_max at the running omega (issue 9)
    AnalysisPanels analysis_;          // continued branches, parameter plane, basins (issues 9, 10)
    RigView rig_;
    bool imgui_ready_ = false;
    bool glfw_ready_ = false;

    // What the user asked for (the sim thread follows within a few milliseconds).
    int stiffness_ = 0, impact_ = 3;   // indices into stiffness_sets() / impact_models()
    double omega_ = 9.0, xI_ = 0.0, speed_ = 1.0, x0_ = -0.011;
    bool paused_ = false;
    Params params_;                    // the UI's copy, for V(x) and the display of forces

    // What the simulation published.
    History<SimMsg> traj_{std::size_t{1} << 19};   // 9 min at 1x, 5 s at 100x
    History<SimMsg> sections_{std::size_t{1} << 18};   // every section point of the epoch (CSV, x(t) dots)
    PoincareMap pc_map_;                               // what the Poincare map shows: settled points only
    SectionFeeder pc_feed_;
    SimMsg last_{};
    bool have_last_ = false;
    std::uint32_t epoch_ = 0;
    std::uint64_t samples_seen_ = 0, impacts_seen_ = 0;
    double frame_max_force_ = 0;
    double flash_ = 0;
    ImpactLabel impact_label_;         // the rig's "F = ..." label: during a contact and shortly after
    double phi_prev_ = 0;

    // Bifurcation diagram.
    std::optional<Diagram> diagram_;
    int bif_protocol_ = 0, bif_steps_ = 300;
    unsigned bif_tex_ = 0;
    int bif_tex_w_ = 0, bif_tex_h_ = 0;
    bool bif_dirty_ = true;
    Range bif_x_{0, 25}, bif_y_{-0.02, 0.005};
    Range bif_view_x_, bif_view_y_;   // what the diagram shows (the user's zoom or bif_x_, bif_y_): the image's ranges
    double bif_started_ = 0;
    bool bif_zoom_applied_ = false;    // --bif-zoom, once the first diagram is there

    // View.
    bool dark_ = true;
    float ui_scale_ = 1.0f;
    bool fonts_dirty_ = true;
    bool show_help_ = false;
    float trail_periods_ = 8.0f;
    float strip_window_ = 6.0f;
    AutoRange phase_x_, phase_v_, pc_x_, pc_v_, strip_y_, potential_y_;
    WindowExtent energy_extent_;       // the energy over the phase portrait's trail (the potential's y range)
    double trail_e_max_ = 0;           // [J] its largest value at the last frame (--state-json)
    std::vector<double> potential_x_, potential_v_;   // V(x) of the current stiffness
    std::string potential_for_;
    double last_frame_time_ = 0, fps_ = 0, frame_dt_ = 1.0 / 60;

    // Screenshot / toast / modes.
    std::string pending_shot_;
    std::string toast_;
    double toast_until_ = 0;
    long frame_count_ = 0;
    long counted_frames_ = 0;
    bool switched_ = false;
    bool bench_mode_ = false;
    bool warming_ = false;   // --warmup: at 100x until the sim time reaches opt_.warmup
    // --bench-plot: the plots show the newest bench_window_ samples (0: the normal trail and strip), and a
    // headless engine appends what the live app would receive at 100x real time every frame.
    std::size_t bench_window_ = 0;
    // Auto-fit extents of the plots' windows, kept incrementally (100k points would cost a pass a frame).
    WindowExtent phase_x_extent_, phase_v_extent_, pc_x_extent_, pc_v_extent_, strip_x_extent_;
    std::uint64_t pc_fit_generation_ = ~std::uint64_t{0};   // the map's generation the fit last snapped to
    std::vector<std::uint32_t> pc_buckets_[16];              // per frame: map points by age band and impacts
    std::unique_ptr<SimEngine> bench_engine_;
    std::unique_ptr<MsgSink> bench_sink_;
    double bench_build_s_ = 0, bench_render_s_ = 0;
    int exit_code_ = 0;
};

}  // namespace impactlab::gui
