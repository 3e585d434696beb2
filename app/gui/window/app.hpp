// The visualiser's UI thread: GLFW window, OpenGL 3.3 core context, Dear ImGui, and the panels.
// It owns nothing of the simulation: it sends commands to the SimThread and drains its samples each frame
// into its own histories (History<SimMsg>). Drawing and physics stay apart: the only core calls here are
// the model's registry, the potential V(x) and the force laws for display.
#pragma once

#include <array>
#include <nlohmann/json_fwd.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "views/analysis_panels.hpp"
#include "analysis/lyapunov_live.hpp"
#include "sim/omega_ramp.hpp"
#include "views/bifurcation_panel.hpp"
#include "files/clip_writer.hpp"
#include "sim/command_link.hpp"
#include "sim/companion_track.hpp"
#include "views/data_panel.hpp"
#include "sim/history.hpp"
#include "window/layout.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "window/options.hpp"
#include "render/plot2d.hpp"
#include "views/poincare_map.hpp"
#include "sim/presets.hpp"
#include "sim/replay.hpp"
#include "views/file_browser.hpp"
#include "views/guide_panel.hpp"
#include "views/params_panel.hpp"
#include "views/phase_panel.hpp"
#include "views/poincare_panel.hpp"
#include "views/potential_panel.hpp"
#include "views/rig_panel.hpp"
#include "views/strip_panel.hpp"
#include "views/view.hpp"
#include "files/session.hpp"
#include "sim/sim_thread.hpp"
#include "sim/state_pick.hpp"
#include "views/view_fit.hpp"

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
    // run()'s frame loop in pieces, for a host that owns the loop (a browser: app/web/web_main.cpp): open()
    // once, then loop_once() every frame while it returns true (false: --frames are done), then finish().
    bool open(std::string& error) { return init(error); }
    bool loop_once();
    int finish();   // the summary line, --state-json and the other files asked for; the exit code
    // A file handed in from outside the program (dropped on the window, or picked in the browser page):
    // taken up at the next frame, a session (.json) loaded as "Load session" would, any other file opened
    // in the measured-data window. UI thread.
    void open_user_file(const std::string& path);

private:
    // app.cpp: life cycle, frame, input, actions
    bool init(std::string& error);
    void shutdown();
    void rebuild_fonts();
    void frame();
    void drain_samples();
    void poll_bifurcation();
    void handle_keys();
    void open_handed_files();   // what open_user_file and the window's drops queued
    // Every command to the simulation thread goes through here: one the ring refuses is resent at the next
    // frame (commands_), and one given up is told in a toast.
    void send(const SimCommand& c);
    void set_omega(double w);
    void start_ramp(double target, double rate);   // routing.cpp: the live omega ramp
    void draw_ramp_controls();                      // controls.cpp: its row under the omega slider
    void set_xi(double xI);
    void set_model(int stiffness, int impact);
    void set_version(const std::string& name);   // "A1G": set_model by the version's name
    // The parameters panel's edits (views/params_panel.hpp): checked, then sent; a toast-free refusal shows
    // in the panel. reset_params: the version's own values.
    bool set_param(const std::string& key, double value);
    void reset_params();
    void run_demo(int k);   // "What to try": demonstration k (1-5) set up
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
    // harness.cpp: the scripted runs (tests, benchmarks); the live app never calls these.
    int run_bench();           // --bench-plot: the timed frames and their report
    int soak();                // --soak: model switches at 100x with an RSS report
    bool script_step();        // a counted --frames frame: the script's changes; false when the run is over
    void script_mouse();       // --double-click: the scripted mouse of this frame (before ImGui::NewFrame)
    void fill_bench_data(int points);
    void feed_bench_frame();   // appends one frame's worth of new samples (bench mode)

    // panels.cpp: the menu, the status bar, help, the toast; tiles.cpp: the layout drawn
    void layout_and_draw();
    bool nothing_shown() const { return layout_.controls.empty() && layout_.tiles.empty() && layout_.bar.empty(); }
    void draw_menu();
    void draw_controls();         // tiles.cpp: the three groups below (controls.cpp), stacked or as tabs
    void draw_controls_run();     // model, forcing and bumper, run, presets
    void draw_controls_view();    // display settings
    void draw_controls_state();   // state, forces, energy
    // routing.cpp: the views (views/) get a context from the shared history and the App's settings, and what
    // a click asks for is routed to the simulation thread here.
    ViewContext view_context() const;
    void apply_view(const ViewAction& a);
    void start_orbit(double x, double v);          // the Poincare clicker: a new orbit (--orbit as a click)
    void restart_at_section(double x, double v);   // the cart from (x, v) at the next section
    void set_section_phase(double phi0);            // the Poincare section at phi = phi0 + 2 pi k [rad]
    void draw_bifurcation();
    void draw_status();
    void draw_help();
    void draw_toast();
    // routing.cpp: the mouse sets the state, the companion cart; controls.cpp: their rows, the grazing monitor
    void set_state(double x, double v);                 // checked (rail, bumper; a toast says why it moved)
    void set_companion(CompanionMode mode);
    void draw_companion_controls();                     // Controls: the companion's mode and ghost law
    void draw_grazing();                                // State: distance to the bumper, impact velocity
    // app_replay.cpp: replay of the recent past and clip export
    bool enter_replay();                                // pauses the simulation; false if nothing is recorded
    void leave_replay();                                // back to live (the simulation as it was before)
    void continue_from_replay();                        // the run restarts from the replayed instant
    // Restarts the simulation at (x, v, t, phi) with omega; clear_history: a new run (a session), else the
    // history keeps what came before t.
    void restart_sim(double x, double v, double t, double phi, double omega, bool clear_history);
    bool skip_until_restart(const SimMsg& m);           // drain_samples: drops the old run's stale records
    void begin_replay_frame();                          // frame(), before the panels: rewinds to the cursor
    void end_replay_frame();                            // after them: the live histories back, then requests
    void handle_replay_keys();
    double sim_sample_dt() const;
    void draw_replay_bar();                             // the status bar while replaying
    void draw_clip_window();
    bool start_clip(const std::string& dir, double seconds, std::string& error);
    void capture_clip_frame(int fw, int fh);            // frame(), after rendering: one frame of the clip
    // app_session.cpp: session files
    Session current_session() const;
    void apply_session(const Session& s);
    bool save_session_file(const std::string& path);
    bool load_session_file(const std::string& path);    // a bad file changes nothing (a toast says why)
    void open_session_window(bool save);
    void draw_session_window();
    void handle_session_request();
    DataPanelContext data_context() const;
    AnalysisContext analysis_context() const;           // routing.cpp
    void apply_analysis(const AnalysisAction& a);       // routing.cpp: a click's commands
    BifurcationContext bifurcation_context();           // routing.cpp
    std::size_t trail_first() const;   // the first sample of the phase portrait's trail
    // tiles.cpp: the layout (layout.hpp) drawn: tiles, tabs, hide and maximise, presentation mode
    void draw_tile(const Tile& tile);
    void draw_panel(PanelId p);
    void draw_presentation_bar();
    void draw_view_menu_panels();
    void handle_layout_keys();
    void configure_layout();   // from the options, at init
    nlohmann::json layout_json() const;   // for --state-json
    void set_presentation(bool on);
    void set_panel_visible(PanelId p, bool on);
    void toggle_maximised(PanelId p);
    double magnification() const;   // the rig's displacement magnification in the current mode
    void set_magnification(double g);
    LayoutRequest layout_request(const Rect& area) const;

    Options opt_;
    GLFWwindow* win_ = nullptr;
    std::unique_ptr<SimThread> sim_;
    CommandLink commands_;             // what the UI sends sim_, and what waits for room in its ring
    BifurcationPanel bif_panel_;       // the diagram, its range, live points and the Lyapunov strip
    DataPanel data_panel_;             // "Measured data": load, fit, effects on and off
    bool show_data_ = false;
    OmegaRamp ramp_;                   // the live omega ramp and the section points it passed
    float ramp_target_ = 25.0f, ramp_rate_ = 0.05f;   // its inputs [rad/s], [rad/s per s]
    double energy_floor_ = 0;          // [J] the well's floor V_min of params_ (the energy bar's zero)
    int energy_floor_rev_ = -1;        // the params_rev_ it was computed for
    LiveLyapunov lyapunov_live_;       // lambda_max at the running omega
    CompanionTrack companion_;         // the twin or the ghost (source 1 records)
    CompanionMode companion_mode_ = CompanionMode::Off;
    int ghost_impact_ = 2;             // the ghost's impact law, an index into impact_models()
    SimMsg grazing_{};                 // the cart's grazing monitor, last whole period (MsgKind::Grazing)
    bool have_grazing_ = false;
    double xI_shown_ = 0;              // [m] the bumper where the simulation has it (travelling to xI_)
    AnalysisPanels analysis_;          // continued branches, parameter plane, basins
    ParamsPanel params_panel_;         // m, c, k, T, m0e, eps and the impact law's, live
    GuidePanel guide_;                 // "What to try": five demonstrations
    bool show_guide_ = false;
    int demo_ = 0;                     // the last demonstration run (1-5), 0 none
    double demo_speed_ = 0;
    int controls_focus_ = -1;          // the controls' group (0 Run, 1 View, 2 State) to bring to the front
    int controls_tab_ = -1;            // the group shown when the controls are tabbed (-1: not tabbed)            // the speed the last demonstration asked for (0: none)
    // Demonstration 1: A1H's first doubling (10.8613 rad/s) crossed slowly, 0.6 rad/s over 600 s of
    // simulation, 30 s of wall time at 20x, the split reached about 13 s in.
    static constexpr double kDemo1From = 10.6, kDemo1To = 11.2, kDemo1Rate = 1e-3;
    void set_demo_speed(double s);
    bool details_ = false;             // the status bar's technical fields
    bool show_params_ = false;
    int params_rev_ = 0;               // bumped at every change of params_ (the potential, the energy floor)
    RigPanel rig_;
    PhasePanel phase_;
    PoincarePanel poincare_;
    PotentialPanel potential_;
    StripPanel strip_;
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
    PoincareMap replay_map_;                           // replaying: pc_map_ as it stood at the cursor
    // The map the panels show: the live one, or while replaying the one at the cursor (app_replay.cpp).
    const PoincareMap& shown_map() const;
    SectionFeeder pc_feed_;
    SimMsg last_{};
    bool have_last_ = false;
    std::uint32_t epoch_ = 0;
    std::uint64_t samples_seen_ = 0, impacts_seen_ = 0;
    double frame_max_force_ = 0;
    double flash_ = 0;
    ImpactLabel impact_label_;         // the rig's "F = ..." label: during a contact and shortly after
    double phi_prev_ = 0;

    // Bifurcation diagram: the settings sessions save (the panel edits them), and "the look changed".
    int bif_protocol_ = 0, bif_steps_ = 300;
    bool bif_dirty_ = true;

    // View.
    bool dark_ = true;
    float ui_scale_ = 1.0f;
    // The layout (tiles.cpp). Presentation mode raises ui_scale_ to 1.5 at least; normal_scale_ is the
    // user's scale to go back to.
    LayoutMode mode_ = LayoutMode::Normal;
    float normal_scale_ = 1.0f;
    std::array<bool, kPanelCount> panel_visible_ = default_visible();   // on-demand panels: open
    bool controls_visible_ = true;
    std::optional<PanelId> maximised_;
    std::optional<PanelId> hovered_panel_;         // the panel under the mouse at the last frame (key Z)
    std::optional<PanelId> focus_tab_;             // an analysis tile just opened: its tab comes to the front
    PanelId featured_ = PanelId::Phase;             // presentation mode's plot
    std::array<PanelId, kPanelCount> tile_tab_{};   // the active tab of the tile whose first panel is the index
    double magnify_[2] = {1.0, 3.0};                // the rig's displacement magnification: normal, presentation
    float controls_group_h_[3] = {};                // [px] the controls' groups as last drawn
    float controls_need_h_ = 0;                     // [px] all of them stacked (0: not all measured yet)
    float controls_measured_scale_ = 0;             // the UI scale they were measured at
    Layout layout_;                                 // this frame's
    bool fonts_dirty_ = true;
    bool show_help_ = false;
    float trail_periods_ = 8.0f;
    double section_phase_ = 0;   // [rad] the Poincare section's phase phi0, as last sent
    float strip_window_ = 6.0f;
    double last_frame_time_ = 0, fps_ = 0, frame_dt_ = 1.0 / 60;
    double fps_since_ = 0;   // [s] wall time the frames counted in fps_frames_ began
    int fps_frames_ = 0;

    // Screenshot / toast / modes.
    std::string pending_shot_;
    std::string toast_;
    double toast_until_ = 0;
    long frame_count_ = 0;
    long counted_frames_ = 0;
    bool switched_ = false;
    bool warming_ = false;   // --warmup: at 100x until the sim time reaches opt_.warmup
    // --bench-plot (harness.cpp): the plots show the newest `window` samples (0: the normal trail and
    // strip), and a headless engine appends what the live app would receive at 100x real time every frame.
    static constexpr int kBenchFrames = 220;   // 20 warm-up frames and 200 timed
    struct Bench {
        bool on = false;
        std::size_t window = 0;
        std::unique_ptr<SimEngine> engine;
        std::unique_ptr<MsgSink> sink;
        std::vector<SimMsg> feed;              // the timed frames' samples, computed before
        std::size_t fed = 0;
        double events_s = 0, build_s = 0, wait_s = 0, submit_s = 0;
        double panel_s[1 + kPanelCount] = {};  // the controls, then each view (the view table's order)
    } bench_;
    bool frame_pending_ = false;               // a frame is submitted and waits for the next one's swap
    int exit_code_ = 0;

    // Replay and clip export (app_replay.cpp).
    enum class ReplayRequest { None, Leave, Continue, Clip };   // asked while the histories are rewound
    static constexpr double kClipFps = 30.0;
    Replay replay_;
    ReplayRequest replay_request_ = ReplayRequest::None;
    struct {
        SimMsg last{};
        double phi_prev = 0, max_force = 0;
        bool rewound = false;   // traj_, sections_ and last_ show the cursor's instant
    } replay_live_;
    struct {
        bool pending = false, clear = false;
        double t = 0, since = 0;
        std::uint32_t epoch = 0;
    } restart_;                 // a Restart sent, its sample not yet drained
    ClipWriter clip_;
    ClipPlan clip_plan_;
    int clip_frame_ = -1;       // the clip frame being rendered (-1: no export)
    bool clip_from_live_ = false, clip_window_ = false, clip_started_ = false, replay_back_done_ = false;
    char clip_dir_[512] = ".";
    float clip_seconds_ = 5.0f;
    std::string clip_summary_, clip_error_;
    // Session files (app_session.cpp).
    bool session_window_ = false, session_saving_ = true;
    int session_request_ = 0;   // 1 save, 2 load, 3 save over the existing file (after the panels drew)
    std::string overwrite_pending_;   // the existing file a save would replace, asked about ("" none)
    ImVec2 click_at_{};               // --double-click: where the mouse is held (harness.cpp)
    char session_path_[512] = "impactlab-session.json";
    FileBrowser session_browser_{{".json"}, "impactlab-session.json"};   // the session window's list of the folder's .json files
    std::string session_error_;
};

}  // namespace impactlab::gui
