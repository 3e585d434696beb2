// The bifurcation diagram's view, with the Lyapunov curve under it: the density image of the
// section points over omega (or over xI or m0e at the running omega), filling column by column while its
// worker runs (BifurcationJob); the range typed in or dragged as a box (right mouse button) on the diagram;
// the live section points of the running attractor over it; a note when the model or a parameter held fixed
// has changed since; a legend of the density colours; and, over omega, an optional strip of
// lambda_max(omega) under it on the same omega axis (LyapunovStripJob; bifurcation_strip.cpp).
// The app hands it what it shows (BifurcationContext) and applies what a click asks for (BifurcationAction);
// nothing here talks to the simulation thread. UI thread only.
#pragma once

#include <array>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analysis_jobs.hpp"
#include "analysis/bifurcation_job.hpp"
#include "sim/history.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "sim/omega_ramp.hpp"
#include "window/options.hpp"
#include "render/plot2d.hpp"
#include "views/poincare_map.hpp"

namespace impactlab::gui {

struct BifurcationContext {
    const Params* params = nullptr;          // the UI's copy of the model, with the current xI
    std::string model;                       // its name ("A1H")
    double omega = 0, xI = 0;                // what the simulation runs at [rad/s], [m]
    const History<MapPoint>* live = nullptr; // the Poincare map's settled section points at omega (or null)
    int* protocol = nullptr;                 // the app's settings, which sessions save: 0 CF up, 1 CF down, 2 EF
    int* steps = nullptr;                    // CF omega levels
    const OmegaRamp* ramp = nullptr;         // the live omega ramp: the section points it passed, in green
    std::function<void(Plot&)> overlay;      // drawn last inside the diagram (the continued branches)
    std::function<void(bool)> overlay_legend;   // its legend above the diagram (outside it); true: compact
    const ContinuationOverlay* branches = nullptr;   // what `overlay` draws (or null): the y fit includes it
};

// What a click asked for: the app applies it.
struct BifurcationAction {
    std::optional<double> omega;
    std::string toast;
};

// The running attractor's section points at the last frame: how many the diagram drew on the omega line and
// how many lay off its view (omega beyond the omega axis, or x above or below the y axis).
struct LivePoints {
    std::size_t total = 0, in_view = 0, beyond = 0, above = 0, below = 0;
};

// What the panel shows, for --state-json.
struct BifurcationState {
    bool have = false;                    // a diagram is shown (computing or done)
    std::string model, protocol;          // of the diagram shown
    SweepParam over = SweepParam::Omega;  // the parameter on its horizontal axis
    double omega_lo = 0, omega_hi = 0;    // its omega range [rad/s] (a diagram over omega)
    double lo = 0, hi = 0;                // its range of `over` [rad/s, m or kg m]
    double omega = 0;                     // [rad/s] the fixed omega of a diagram over xI or m0e
    // Each level's value of `over`, with the least and greatest x of its section points [m] and its verdict
    // (the period, kLevelNotSettled, or 0 where not judged), in sweep order.
    struct Level { double at, x_min, x_max; int period; };
    std::vector<Level> level_x;
    int settle = 0;                       // the settle budget the diagram was computed with (records)
    int not_settled = 0;                  // its levels judged kLevelNotSettled (drawn grey)
    int steps = 0, levels_done = 0;       // CF levels asked for and finished (EF: 0, 0)
    std::size_t points = 0;
    bool running = false, cancelled = false, stale = false;
    double progress = 0;
    Range view_omega;                     // the horizontal range on screen (of `over`)
    bool y_is_v = false;                  // the quantity over omega: v (else x) at the sections
    Range view_y;                         // its range on screen [m] or [m/s]
    std::string range_error;              // the range inputs' complaint ("" when valid)
    bool lyap_on = false, lyap_running = false;
    int lyap_steps = 0, lyap_done = 0, lyap_positive = 0;   // omegas asked, done, with lambda_max > 0
    LivePoints live;
};

class BifurcationPanel {
public:
    BifurcationPanel() = default;
    BifurcationPanel(const BifurcationPanel&) = delete;
    BifurcationPanel& operator=(const BifurcationPanel&) = delete;

    // --bif-range, --bif-box, --bif-zoom, --bif-lyapunov, --lyap-steps, --bif-nowait.
    void configure(const Options& opt);
    // A new diagram over the range in the inputs (key B, Compute); refused with a toast when the range is
    // not valid. With the strip on, its Lyapunov curve restarts too.
    std::string start(const BifurcationContext& c);
    // B: start, or cancel what runs.
    std::string toggle(const BifurcationContext& c);
    // Every frame, drawn or not: takes what the workers published. Returns a message for a toast ("" none).
    std::string poll(const BifurcationContext& c);
    // Inside the diagram's tile.
    BifurcationAction draw(const BifurcationContext& c);
    // Headless runs (--frames) wait while this is true: a diagram asked for at start still computing (not
    // with --bif-nowait), or the strip asked for at start still computing.
    bool busy() const;
    double progress() const { return job_.progress(); }
    // The running omega's label as last drawn (screen pixels x0, y0, x1, y1; zeros before).
    const std::array<float, 4>& omega_label() const { return omega_label_; }
    // The diagram's data area as last drawn (screen pixels x0, y0, x1, y1; zeros when not drawn).
    const std::array<float, 4>& plot_rect() const { return plot_rect_; }
    const std::array<float, 4>& info_rect() const { return info_rect_; }
    // The diagram's omega axis (the auto-fit, not the zoom): what the continuation follows. A diagram over
    // xI or m0e gives the omega range last typed for one over omega.
    Range omega_axis() const { return shown_req_.over == SweepParam::Omega ? fit_x_ : kept_[0]; }
    BifurcationState state(const BifurcationContext& c) const;
    // The look changed (theme, fonts): the image is drawn again.
    void mark_dirty() { dirty_ = true; }
    // --bench-plot: a synthetic diagram shown as a computed one.
    void show_bench(Diagram d, Range x, Range y);
    void release_gl();   // before the GL context goes

private:
    BifRequest request(const BifurcationContext& c, double lo, double hi) const;
    // The parameter the next diagram sweeps (the view's combo): its range inputs swap with it.
    void set_over(SweepParam over);
    // The y fit, widened to hold the continued branches drawn over it (those within the omega axis).
    Range fit_y_with_branches(const BifurcationContext& c) const;
    // Says what the diagram shown is: the model, protocol, range and levels (narrow: levels and model).
    void draw_info(Plot& plot, const char* x_label, ImVec2 outer_min, ImVec2 outer_max);
    void begin(const BifurcationContext& c, const BifRequest& req);
    void start_strip(const BifurcationContext& c);
    void grow_fit(std::size_t from);
    void snap_fit();
    // x or v at the sections over omega; the y fit and the view follow.
    void set_show_v(bool v);
    double y_of(const DiagramPoint& p) const { return show_v_ ? p.v : p.x; }
    void update_texture(int w, int h);
    void draw_header(const BifurcationContext& c, std::string& toast);
    // draw()'s layers over the plot: the live points on the running value's line, its label, a stale
    // diagram's note, the mouse (a click, a box).
    void draw_live_points(Plot& plot, const BifurcationContext& c, double cur, bool is_stale);
    void draw_cursor_label(Plot& plot, const BifurcationContext& c, double cur);
    void draw_stale_note(Plot& plot, const BifurcationContext& c);
    void handle_mouse(Plot& plot, const BifurcationContext& c, BifurcationAction& act);
    // draw_header()'s pieces: folded in a short tile (true: nothing more to draw), the range's fields, the
    // compute button or the progress, the lambda strip's checkbox.
    bool draw_folded(const BifurcationContext& c, std::string& toast);
    void draw_range_fields(const BifurcationContext& c);
    void draw_compute(const BifurcationContext& c, std::string& toast);
    void draw_strip_toggle(const BifurcationContext& c);
    void draw_legend() const;   // the density colours, in the header
    int not_settled() const;    // levels of the diagram shown judged not settled (drawn grey)
    // A box dragged (or scripted) from omega w0 to w1: its range computed, and the view set to it.
    void apply_box(const BifurcationContext& c, double w0, double w1, Range view_y);
    void draw_strip(const BifurcationContext& c, Range view_x, BifurcationAction& act);
    bool stale(const BifurcationContext& c) const;

    BifurcationJob job_;
    Diagram shown_;                  // the points so far (or all) of the diagram shown
    BifRequest shown_req_;           // what it was asked for (range, steps, protocol, model, xI)
    bool have_ = false;              // anything to show
    int levels_done_ = 0;
    double started_ = 0;             // [s] wall clock, for the toast
    Range fit_x_{0, 25}, fit_y_{-0.02, 0.005};   // the auto-fit: the request's omega range, the points' x
    bool fit_y_empty_ = true;

    double lo_edit_ = 0, hi_edit_ = 25;           // the range inputs, of over_ [SI units: rad/s, m, kg m]
    SweepParam over_ = SweepParam::Omega;         // the parameter the next diagram sweeps
    Range kept_[3] = {{0, 25}, {-0.01, 0.01}, {0.01, 0.04}};   // each parameter's range inputs, kept on a switch
    std::string range_error_;

    // The density image, for the view shown.
    unsigned tex_ = 0;
    int tex_w_ = 0, tex_h_ = 0;
    std::vector<unsigned char> image_;   // the texture's pixels (composited into the plot's own image)
    bool dirty_ = true;
    bool dark_ = true;               // the theme the image was drawn for
    Range view_x_, view_y_;
    float max_count_ = 0;            // points in the densest pixel (the legend's top)
    int settle_ = 10;                // --bif-settle: the next diagram's settle budget

    LivePoints live_;                // at the last frame

    // The box being dragged with the right mouse button [rad/s].
    bool box_active_ = false;
    double box_w0_ = 0;

    // Start-up (options).
    bool want_start_ = false, nowait_ = false, zoom_applied_ = true;
    Range zoom_x_;
    bool script_box_ = false;        // --bif-box: a box to apply once the first diagram is done
    Range script_box_x_;

    // The Lyapunov strip.
    bool lyap_on_ = false, lyap_want_ = false;
    bool show_v_ = false;   // the diagram plots v at the sections (else x)
    int lyap_steps_ = 60;
    LyapunovStripJob lyap_job_;
    LyapunovStripRequest lyap_req_;
    std::vector<analysis::LyapunovPoint> lyap_;
    std::string lyap_model_;
    int lyap_done_ = 0;
    bool lyap_y_user_ = false;
    Range lyap_view_y_{-1, 1};
    std::array<float, 4> omega_label_{};   // the running omega's label (omega_label())
    std::array<float, 4> plot_rect_{};     // the data area (plot_rect())
    std::array<float, 4> info_rect_{};     // the diagram's info line, below the data (info_rect(); zeros: not drawn)
    bool settings_open_ = false;           // a short tile's folded settings, unfolded
};

}  // namespace impactlab::gui
