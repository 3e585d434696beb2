// The bifurcation diagram and its Lyapunov strip computed on worker threads (the core's run_cf_sweep /
// run_ef_ramp and analysis::lyapunov_sweep) with progress and cancel through impactlab::Progress. They fill
// progressively: the worker publishes each finished omega level (the EF ramp: chunks of section points) to
// a Feed, whole, and the UI takes what arrived every frame; the finished result is handed over whole at the
// end and equals the chunks put together. GL-free.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/analysis_jobs.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::gui {

enum class BifProtocol { CfUp, CfDown, Ef };
const char* bif_protocol_name(BifProtocol p);

struct BifRequest {
    Params params;
    BifProtocol protocol = BifProtocol::CfUp;
    int steps = 300;           // CF: number of omega levels
    int transient = 20;        // CF: periods discarded at each omega
    int record = 70;           // CF: periods recorded
    // CF: omega_j = omega_lo + (omega_hi - omega_lo) j / steps, j = 1..steps [rad/s] (the paper's 25 j / 300
    // for [0, 25]: never omega = 0, where a period is infinite). EF: the ramp from rest to omega_hi.
    double omega_lo = 0.0, omega_hi = 25.0;
    double ef_rate = 25.0 / 2800.0;   // EF: d omega / dt [rad/s^2] (the paper's 25 rad/s in 2800 s)
    // CF over xI [m] or m0e [kg m] instead of omega: `steps` levels from lo to hi (both included, as the CLI's
    // --range) at the fixed omega [rad/s]; omega_lo, omega_hi are then unused.
    SweepParam over = SweepParam::Omega;
    double lo = 0, hi = 0;
    double omega = 0;
    // CF: each level judged by the map's own test, with up to `settle` more records where it has not settled
    // (run_cf_levels, as the CLI's --settle); levels still unsettled are drawn grey. 0: not judged.
    int settle = 10;
};
// The CF sweep a request runs (its omega levels as cf_spec's; those of xI or m0e from lo to hi).
ParamSweep param_sweep(const BifRequest& r);
// The request's range of its swept parameter, in SI units: [omega_lo, omega_hi] (EF: from 0), or [lo, hi].
std::pair<double, double> swept_range(const BifRequest& r);

// The core's specs for a request (what the job runs, and what a test compares with).
CfSpec cf_spec(const BifRequest& r);
EfSpec ef_spec(const BifRequest& r);

// "" when 0 <= lo < hi <= kMaxOmega [rad/s]; otherwise what is wrong, in words for the panel.
std::string check_omega_range(double lo, double hi);
// The smallest omega span a box may ask for [rad/s]: narrower drags are clicks or slips.
inline constexpr double kMinBoxSpan = 0.02;
// The range a diagram of `over` may span in the GUI [SI units]: omega in [0, kMaxOmega], xI within the
// rail's travel, m0e in (0, 10] (its lower end: the smallest unbalance that still forces the cart), and the
// smallest span a box may ask for.
struct SweepLimits { double lo, hi, min_box; };
SweepLimits sweep_limits(SweepParam over);
// A box dragged on the diagram between w0 and w1 of its swept parameter (either order, clamped to
// sweep_limits): the same request (model, protocol, steps, periods, fixed omega) over the box's range.
// nullopt if narrower than the limits' min_box.
std::optional<BifRequest> box_request(const BifRequest& base, double w0, double w1);

// Results published by a worker as it goes and taken by the UI as they come. The worker builds each chunk
// in its own vector and appends it here whole under the mutex, so the UI never sees half a level.
template <class T>
class Feed {
public:
    // Worker thread. Appends `chunk` (then empties it) and records how many levels are done.
    void publish(std::vector<T>& chunk, int levels_done) {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.insert(pending_.end(), chunk.begin(), chunk.end());
        levels_ = levels_done;
        chunk.clear();
    }
    // UI thread. Appends what arrived since the last call to `out`; returns the levels done so far.
    int take(std::vector<T>& out) {
        std::lock_guard<std::mutex> lock(mutex_);
        out.insert(out.end(), pending_.begin(), pending_.end());
        pending_.clear();
        return levels_;
    }

private:
    std::mutex mutex_;
    std::vector<T> pending_;
    int levels_ = 0;
};

// A LevelObserver that publishes each finished CF level as the diagram keeps it: its section points (the
// record that settled, with the level's value of the swept parameter) to one Feed, then its verdict to the
// other. Simulating thread.
class LevelPublisher : public LevelObserver {
public:
    LevelPublisher(Feed<DiagramPoint>& points, Feed<DiagramLevel>& levels) : points_(points), levels_(levels) {}
    void kept(std::size_t j, const DiagramLevel& level, const DiagramPoint* pts) override {
        chunk_.assign(pts, pts + level.count);
        points_.publish(chunk_, static_cast<int>(j + 1));
        if (level.period == 0) return;   // not judged (no settle budget): the diagram keeps no level either
        level_.assign(1, level);
        levels_.publish(level_, static_cast<int>(j + 1));
    }

private:
    Feed<DiagramPoint>& points_;
    Feed<DiagramLevel>& levels_;
    std::vector<DiagramPoint> chunk_;
    std::vector<DiagramLevel> level_;
};

// The diagram on a worker, filling progressively. UI thread, except where said.
class BifurcationJob {
public:
    // Cancels any job in progress (its result dropped) and starts `req`.
    void start(const BifRequest& req);
    void cancel() { job_.cancel(); }
    bool running() const { return job_.running(); }   // any thread
    double progress() const { return job_.progress(); }
    // Appends the points published since the last call (whole levels; EF: chunks) to `out`; returns the
    // levels done (CF) or 0 (EF). A level's verdict (CF) comes after its points: into `levels` if given.
    int take_new(std::vector<DiagramPoint>& out, std::vector<DiagramLevel>* levels = nullptr) {
        if (levels && level_feed_) level_feed_->take(*levels);
        return feed_ ? feed_->take(out) : 0;
    }
    // The finished diagram, once: it holds exactly the points published, in order.
    std::optional<Diagram> take_result() { return job_.take_result(); }
    std::string take_error() { return job_.take_error(); }
    void wait() { job_.wait(); }   // tests

private:
    std::shared_ptr<Feed<DiagramPoint>> feed_;   // shared with the worker: a new job gets new ones
    std::shared_ptr<Feed<DiagramLevel>> level_feed_;
    Job<Diagram> job_;
};

// The largest Lyapunov exponent along the diagram's CF sweep (analysis::lyapunov_sweep), published per
// omega. Fewer omegas and periods than the diagram by default: a compliant bumper (C, C1) costs about 5 s of
// CPU per omega at 60 periods, the rigid ones (G, H) about 1/30 of that.
struct LyapunovStripRequest {
    Params params;
    SweepDirection direction = SweepDirection::Up;
    double omega_lo = 0.0, omega_hi = 25.0;   // as BifRequest: omega_j = lo + (hi - lo) j / steps
    int steps = 60;
    int transient = 20, record = 40;
};
CfSpec cf_spec(const LyapunovStripRequest& r);

class LyapunovStripJob {
public:
    void start(const LyapunovStripRequest& req);
    void cancel() { job_.cancel(); }
    bool running() const { return job_.running(); }
    double progress() const { return job_.progress(); }
    int take_new(std::vector<analysis::LyapunovPoint>& out) { return feed_ ? feed_->take(out) : 0; }
    std::optional<std::vector<analysis::LyapunovPoint>> take_result() { return job_.take_result(); }
    std::string take_error() { return job_.take_error(); }
    void wait() { job_.wait(); }

private:
    std::shared_ptr<Feed<analysis::LyapunovPoint>> feed_;
    Job<std::vector<analysis::LyapunovPoint>> job_;
};

}  // namespace impactlab::gui
