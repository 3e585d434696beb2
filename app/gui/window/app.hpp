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

#include "analysis/lyapunov_live.hpp"
#include "files/clip_export.hpp"
#include "files/session.hpp"
#include "files/session_window.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "render/plot2d.hpp"
#include "sim/command_link.hpp"
#include "sim/live_feed.hpp"
#include "sim/presets.hpp"
#include "sim/sim_thread.hpp"
#include "sim/state_pick.hpp"
#include "views/analysis_panels.hpp"
#include "views/data_panel.hpp"
#include "views/params_panel.hpp"
#include "views/phase_panel.hpp"
#include "views/poincare_panel.hpp"
#include "views/potential_panel.hpp"
#include "views/rig_panel.hpp"
#include "views/strip_panel.hpp"
#include "views/view.hpp"
#include "views/view_fit.hpp"
#include "window/bench_plot.hpp"
#include "window/diagram_tile.hpp"
#include "window/companion.hpp"
#include "window/demos.hpp"
#include "window/frame_stats.hpp"
#include "window/layout.hpp"
#include "window/layout_state.hpp"
#include "window/options.hpp"
#include "window/ramp_control.hpp"
#include "window/replay_controller.hpp"
#include "window/run_request.hpp"
#include "window/script_state.hpp"
#include "window/toast.hpp"
#include "window/view_settings.hpp"

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
    void apply_scripted_keys();        // frame()'s pieces: --tap, --press and taps held for this frame,
    void run_frame_script();           // the first frame's scripted changes and the end of --warmup,
    void render(int& fw, int& fh);     // the frame rendered (its framebuffer's size out) and a screenshot saved
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
    void set_demo_speed(double s);
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
    bool bench_frame();        // one of them (a page's animation frame); false once the report is printed
    void report_bench();
    int soak();                // --soak: model switches at 100x with an RSS report
    bool script_step();        // a counted --frames frame: the script's changes; false when the run is over
    void script_mouse();       // --double-click: the scripted mouse of this frame (before ImGui::NewFrame)
    void fill_bench_data(int points);
    void feed_bench_frame();   // appends one frame's worth of new samples (bench mode)

    // panels.cpp: the menu, the status bar, help, the toast; tiles.cpp: the layout drawn
    void layout_and_draw();
    bool nothing_shown() const { return layout_.frame.controls.empty() && layout_.frame.tiles.empty() && layout_.frame.bar.empty(); }
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
    // The map the panels show: the live one, or while replaying the one at the cursor.
    const PoincareMap& shown_map() const { return replay_.shown_map(feed_.pc_map); }
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

    // The window and its link to the simulation thread.
    Options opt_;
    GLFWwindow* win_ = nullptr;
    bool glfw_ready_ = false;
    bool imgui_ready_ = false;
    std::unique_ptr<SimThread> sim_;
    CommandLink commands_;             // what the UI sends sim_, and what waits for room in its ring
    RunRequest run_;                   // what the user asked for (the sim thread follows within milliseconds)
    LiveFeed feed_;                    // what the simulation published
    // The layout and the display settings (tiles.cpp, controls.cpp).
    LayoutState layout_;
    ViewSettings view_;
    FrameStats frames_;
    Toast toast_;
    // The views (views/) and the floating panels.
    RigPanel rig_;
    PhasePanel phase_;
    PoincarePanel poincare_;
    PotentialPanel potential_;
    StripPanel strip_;
    DiagramTile bif_;                  // the diagram, its range, live points and the Lyapunov strip
    AnalysisPanels analysis_;          // continued branches, parameter plane, basins
    DataPanel data_panel_;             // "Measured data": load, fit, effects on and off
    ParamsPanel params_panel_;         // m, c, k, T, m0e, eps and the impact law's, live
    Demos demos_;                      // "What to try"
    // What the UI adds to the run: the omega ramp, lambda_max live, the companion cart.
    RampControl ramp_;
    LiveLyapunov lyapunov_live_;       // lambda_max at the running omega
    Companion companion_;
    // Replay, clips, sessions (app_replay.cpp, app_session.cpp); the scripted runs (harness.cpp).
    ReplayController replay_;
    ClipExport clip_;
    SessionWindow session_;
    ScriptState script_;
    BenchPlot bench_;
};

}  // namespace impactlab::gui
