// Bifurcation diagrams: the CF sweep (up or down) and the EF ramp of MODEL.md, for any model version.
// A long job runs on whatever thread calls it; it reports progress through atomics, can be cancelled,
// and returns a finished Diagram whole.
#pragma once

#include <atomic>
#include <cmath>
#include <utility>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab {

// Shared between the job (writer) and a UI or progress bar (reader).
struct Progress {
    std::atomic<double> fraction{0.0};   // written by the job thread
    std::atomic<bool> cancel{false};     // written by any thread, read by the job thread
};

// The parameter a CF diagram sweeps: the forcing frequency (the paper's diagram), or the bumper position or
// the unbalance at a fixed omega, each moved quasi-statically from level to level.
enum class SweepParam { Omega, XI, M0e };
const char* sweep_param_name(SweepParam s);   // "omega", "xI", "m0e": the CSV column and the flags' word
const char* sweep_param_unit(SweepParam s);   // its SI unit: "rad/s", "m", "kg m"
std::optional<SweepParam> parse_sweep_param(const std::string& name);   // the name above; nullopt otherwise
// How a plot's axis shows it: xI in mm (the bumper moves by millimetres), omega and m0e in SI units;
// value shown = scale * value in SI units.
struct SweepParamAxis { const char* unit; double scale; };
SweepParamAxis sweep_param_axis(SweepParam s);

// A section point of the diagram. `omega` is the value of the swept parameter at the point's level: omega
// [rad/s] for the paper's diagram and the EF ramp (omega(t)), xI [m] or m0e [kg m] when Diagram::over says so.
struct DiagramPoint { double omega, x, v; };

// A level of a CF diagram judged by the map's own test (settle_level): its period k or kLevelNotSettled
// (0: not judged, a sweep without a settle budget); its points are points[first, first + count).
inline constexpr int kLevelNotSettled = -1;
struct DiagramLevel {
    double at = 0;               // the swept parameter's value
    int period = 0;
    std::size_t first = 0, count = 0;
};

struct Diagram {
    std::string model;
    std::string protocol;                // "cf-up", "cf-down", "ef"
    SweepParam over = SweepParam::Omega; // what the points' first coordinate is
    double omega = 0;                    // [rad/s] the fixed forcing frequency of an xI or m0e sweep
    std::vector<DiagramPoint> points;
    std::vector<DiagramLevel> levels;    // with a settle budget (run_cf_levels): every level, judged
    bool cancelled = false;
    double simulated_seconds = 0;
    std::uint64_t steps = 0, impacts = 0;
};

enum class SweepDirection { Up, Down };

struct CfSpec {
    double omega_min = 25.0 / 300.0;     // omega_j = omega_min + (j-1) (omega_max - omega_min)/(steps-1)
    double omega_max = 25.0;
    int steps = 300;
    int transient = 20;                  // periods discarded at each omega
    int record = 70;                     // periods recorded at each omega
    SweepDirection direction = SweepDirection::Up;
};

struct EfSpec {
    double omega_max = 25.1;             // [rad/s] reached at t_ramp
    double t_ramp = 2800.0;              // [s]
};

// One level of a CF-style sweep: the forcing frequency and the parameters a parameter plane varies.
struct CfLevel { double omega, xI, m0e; };
double level_value(const CfLevel& lv, SweepParam s);   // lv.omega, lv.xI or lv.m0e
double& level_value(CfLevel& lv, SweepParam s);

// A CF sweep of one parameter from lo to hi (in its SI units) over `steps` levels: value_j = lo + (hi - lo)
// j / (steps - 1), j = 0..steps-1 (reversed going down); the other two are the model's, and omega is `omega`
// when the sweep is of xI or m0e.
struct ParamSweep {
    SweepParam over = SweepParam::Omega;
    double lo = 25.0 / 300.0, hi = 25.0;
    int steps = 300;
    SweepDirection direction = SweepDirection::Up;
    double omega = 0;                    // [rad/s] the fixed forcing frequency of an xI or m0e sweep
};
// The levels run_cf_levels takes for `s`, in sweep order.
std::vector<CfLevel> sweep_levels(const Params& p, const ParamSweep& s);
// "" when s can be swept for model p, else what is wrong, naming the parameter and its range: omega in
// (0, 1000] rad/s; xI within the rail's travel (param_ranges) and only with a bumper; m0e in (0, 10] kg m
// (an unbalance of zero forces nothing); an xI or m0e sweep's fixed omega in (0, 1000] rad/s; lo <= hi; steps >= 1.
std::string check_sweep(const Params& p, const ParamSweep& s);
// Watches a CF-style sweep beside its section collector (the scan's measures): every piece, impact and
// section of every level in time order, plus where each level begins and ends. Simulating thread.
class LevelObserver : public Observer {
public:
    virtual void begin_level(std::size_t /*j*/, const CfLevel&) {}
    // The level as the diagram keeps it: its verdict (period 0 without a settle budget) and its points, the
    // record that settled, which may come after the sections this observer saw.
    virtual void kept(std::size_t /*j*/, const DiagramLevel& /*level*/, const DiagramPoint* /*points*/) {}
    virtual void end_level(std::size_t /*j*/, const Params& /*p*/, const State& /*s*/) {}
};
// The CF loop itself: from rest at x = 0, each level sets its omega (phi continuous, restarted at a section
// instant), its m0e and its bumper position (moved quasi-statically, Simulator::move_bumper) and runs
// transient + record periods from the previous level's final state; the diagram holds the recorded section
// points, with each level's value of `over` (omega unless said). run_cf_sweep is this with xI and m0e fixed.
// With settle_budget > 0 each level is judged by settle_level (periods up to kDiagramMaxPeriod, no chaos
// verdict: a long chaotic transient looks like chaos, A1H at 18 rad/s and xI = 2.63 mm settles on a period 18
// after about 3000 periods) from its end state (a copy: the next level starts where this one ended, as the
// protocol says); its points are the record that settled (or the last one run) and Diagram::levels says what
// each level is: a period, or kLevelNotSettled (chaos, or a transient longer than the budget).
inline constexpr int kDiagramMaxPeriod = 32;
Diagram run_cf_levels(const Params& p, const std::vector<CfLevel>& levels, int transient, int record,
                      Progress* progress = nullptr, const Tolerances& tol = {}, LevelObserver* extra = nullptr,
                      SweepParam over = SweepParam::Omega, int settle_budget = 0);
// The CF diagram of a ParamSweep: run_cf_levels over sweep_levels, its points carrying s.over's value.
Diagram run_cf_param_sweep(const Params& p, const ParamSweep& s, int transient, int record, Progress* progress = nullptr,
                           const Tolerances& tol = {}, LevelObserver* extra = nullptr, int settle_budget = 0);

// Whether a level's record has settled, by the map's own test: its x values on the section recur in order
// with a period k <= max_period, every point k sections later within 1e-5 m, and the step from one section to
// the next no longer shrinking (an alternation dying out near a multiplier of -1 is no period 2). Otherwise the
// level runs on from s (at a section instant, phase 0), a record of the same length at a time, up to `budget`
// more: k once one settles; with chaos_verdict, 0 (chaos) when there are more than max_period values and the
// next record comes no closer to recurring than half the last (a chaotic transient reads so too); otherwise
// kLevelNotSettled when the budget runs out. `record` is left as the last record looked at. Simulating thread.
int settle_level(const Params& p, double omega, State s, std::vector<SectionPoint>& record, int max_period, int budget,
                 const Tolerances& tol, bool chaos_verdict = true);
// Starts at rest at x = 0 (made consistent with the bumper), as MODEL.md prescribes. `extra` as run_cf_levels's.
Diagram run_cf_sweep(const Params& p, const CfSpec& spec, Progress* progress = nullptr, const Tolerances& tol = {},
                     LevelObserver* extra = nullptr);
// `extra` (optional) sees every piece, impact and section of the ramp in time order (a GUI's progressive fill).
Diagram run_ef_ramp(const Params& p, const EfSpec& spec, Progress* progress = nullptr, const Tolerances& tol = {},
                    Observer* extra = nullptr);

// Poincare section at constant omega, the drive's phase 0 at state.t: `transient` periods discarded, then
// `periods` points recorded at phi = phi0 + 2 pi k (Simulator::set_section_phase: 0 <= phi0 <= 2 pi, else
// std::invalid_argument), n = 1 + transient, ...; the state is left at the last of them.
std::vector<SectionPoint> poincare_section(const Params& p, double omega, int periods, int transient, State& state,
                                           const Tolerances& tol = {}, Progress* progress = nullptr,
                                           double phi0 = 0.0);

// One run of `duration` seconds from state s (made consistent with p and d first) under drive d, its trajectory
// sampled every dt from t = 0 into `sink`; advanced in 200 equal slices, so the progress moves and a cancel is
// seen within a slice (the CLI's simulate and the Python module share the slicing, hence every sample).
// Returns false when progress->cancel stopped it.
bool simulate_sampled(const Params& p, const Drive& d, State& s, double duration, double dt, const Tolerances& tol,
                      Progress* progress, const std::function<void(const Sample&)>& sink);

// Distinct values among the recorded section points at one omega (period detection, tests, README):
// the number of clusters of x closer than `tol` [m]; returns record+1 if it exceeds max_period.
int count_period(const std::vector<double>& xs, double tol, int max_period = 16);

// The transitions of Fig. 3 read off a CF diagram (omega increasing or decreasing through the points):
// where the cart leaves x ~ 0, where period 2 first appears, where chaos starts and ends, the periodic
// windows inside the chaos, and the return to period 1. NaN where a transition does not occur.
struct Transitions {
    double jump = NAN;                       // first omega with |x| > 5 mm on the section (if it starts near 0)
    double period_doubling = NAN;            // first omega after the jump with period 2
    double chaos_start = NAN;                // first omega of a run of >= 5 levels with > 8 distinct section values
    double chaos_end = NAN;                  // last omega of the last such run
    double period1_return = NAN;             // first period-1 omega after chaos_end
    std::vector<std::pair<double, double>> windows;   // periodic (period <= 4) runs of >= 4 omegas inside the chaos
    std::vector<int> periods;                // period per omega (record+1 means more than 16: chaos)
    std::vector<double> omegas;
};
Transitions find_transitions(const Diagram& d, double cluster_tol = 1e-5);

// omega,x,v rows with a header (xI,x,v or m0e,x,v for those sweeps); the format the CLI writes and the GUI exports.
void write_diagram_csv(const Diagram& d, std::ostream& out);

}  // namespace impactlab
