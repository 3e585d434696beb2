// Beyond the sweep: periodic orbits as fixed points of the k-th Poincare map with their monodromy
// and Floquet multipliers, pseudo-arclength continuation with bifurcation detection, Lyapunov exponents of
// the hybrid flow, and basins of attraction.
//
// Every trajectory is the core Simulator's. The monodromy comes from the variational equation
// d(Phi)/dt = A(t) Phi integrated along the Simulator's accepted pieces (A is the Jacobian of Eq. (1) at the
// piece's dense output; only this linear 2x2 equation is integrated here, the rig's state never is), with
// the saltation matrix of the impact law at every rigid impact, sticking and permanent contact. Long jobs
// report through a Progress (sweep.hpp) and stop when its cancel flag is set. SI units throughout.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/simulator.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::analysis {

// Scales that make (x, v) dimensionless for norms, tolerances and the arclength (the cart moves over ~1 cm
// at ~0.1 m/s): x / kXScale, v / kVScale.
inline constexpr double kXScale = 1e-2;   // [m]
inline constexpr double kVScale = 1e-1;   // [m/s]
double scaled_norm(const Vec2& dy);       // max(|dx| / kXScale, |dv| / kVScale)

// Tolerances of the simulator for analysis: tighter than a sweep's, since Newton and finite differences
// need the map smooth to well below the orbit tolerance.
Tolerances analysis_tolerances(double rtol = 1e-10);

// ---- The Poincare map and its derivative ------------------------------------------------------------------

// One application of the k-th stroboscopic map at constant omega: from (x, v) at t = 0, phi = 0 to the state
// at phi = 2 pi k, with what happened on the way.
struct MapResult {
    Vec2 y = Vec2::Zero();               // (x, v) at phi = 2 pi k (the bumper point (xI, 0) when held there)
    Mat2 M = Mat2::Identity();           // d y / d y0 (tangent + saltation), if asked for
    std::vector<Vec2> sections;          // (x, v) at phi = 2 pi i, i = 1..k (the last equals y)
    int impacts = 0;                     // rigid impacts, or compliant contacts entered, during the k periods
    double max_x = -1e300;               // largest x reached [m]
    double min_impact_speed = 1e300;     // smallest v- of a rigid impact [m/s] (1e300 without one)
    bool held = false;                   // y is held at the bumper (regime II or III at the end)
    bool contact = false;                // permanent contact (regime III) occurred
    std::uint64_t steps = 0;
};

MapResult poincare_map(const Params& p, double omega, const Vec2& y0, int k, bool tangent, const Tolerances& tol);
// The same derivative by central finite differences of the map (relative step h in scaled units): the check
// of the variational equations and the saltation matrices.
Mat2 monodromy_fd(const Params& p, double omega, const Vec2& y0, int k, const Tolerances& tol, double h = 1e-6);

// ---- Periodic orbits --------------------------------------------------------------------------------------

struct Floquet {
    std::array<std::complex<double>, 2> mu{};   // multipliers, |mu[0]| >= |mu[1]|
    bool stable = false;                        // both inside the unit circle
};
Floquet floquet(const Mat2& M);

struct OrbitOptions {
    int period = 1;              // k: the orbit repeats after k forcing periods
    int max_iterations = 40;
    double tol = 1e-9;           // on the scaled residual |P^k(y) - y|
    Tolerances sim = analysis_tolerances();
};

struct Orbit {
    bool converged = false;
    int iterations = 0;
    double omega = 0;            // [rad/s]
    int period = 1;
    Vec2 y = Vec2::Zero();       // section point at phi = 0 (x [m], v [m/s])
    Mat2 M = Mat2::Identity();   // monodromy of the k-th map
    Floquet floquet;
    double residual = 0;         // scaled |P^k(y) - y|
    int impacts = 0;             // per k periods
    double max_x = 0;            // [m]
    double min_impact_speed = 1e300;
    std::vector<Vec2> sections;  // the k section points of the orbit, starting after y
    std::string message;         // why it did not converge
};

// Newton on P^k(y) - y = 0 from `guess`, with the monodromy as Jacobian (damped when a full step does not
// lower the residual). An orbit that turns out to have a smaller period than asked stays as found.
Orbit find_orbit(const Params& p, double omega, const Vec2& guess, const OrbitOptions& opt = {});
// The section point after `periods` forcing periods from y0 (a start for Newton that sits on an attractor).
Vec2 settle(const Params& p, double omega, const Vec2& y0, int periods, const Tolerances& tol);
// The bottom of the left well (x < 0, where F_SA = 0), the usual start of a search [m].
double left_well(const Params& p);

// ---- Impacting orbits from impact to impact (rigid bumpers) ----------------------------------------------

// A period-k orbit with one rigid impact per k forcing periods, written from impact to impact: the cart hits
// xI at phase theta with speed v- >= 0, is held for T_imp(v-), leaves with v+ = -kappa(v-) v- and flies (on the
// rig without the bumper) until phase theta + 2 pi k. The residual is zero when it arrives at xI with v- again.
// Unlike the stroboscopic map, whose derivative grows as 1/v- near a grazing, these equations are smooth
// through v- = 0: the grazing orbit is the solution with v- = 0.
struct ImpactShot {
    Vec2 residual = Vec2::Zero();        // scaled ((x_end - xI) / kXScale, (v_end - v-) / kVScale)
    Mat2 J = Mat2::Zero();               // d residual / d (theta [rad], v- / kVScale), if asked for
    Vec2 section = Vec2::Zero();         // (x, v) at the first phi = 2 pi n after the release
    double section_phase = 0;            // that 2 pi n [rad]
};
ImpactShot impact_shot(const Params& p, double omega, double theta, double v_minus, int k, bool jacobian,
                       const Tolerances& tol);
struct ImpactOrbit {
    bool converged = false;
    int iterations = 0;
    double theta = 0, v_minus = 0;       // impact phase [rad] and speed [m/s]
    double residual = 0;                 // scaled
    Vec2 section = Vec2::Zero();         // a section point of the orbit (P^k fixes it when the orbit is admissible)
};
// Newton on the two equations at fixed parameters, from (theta, v-).
ImpactOrbit find_impact_orbit(const Params& p, double omega, double theta, double v_minus, int k,
                              const Tolerances& tol = analysis_tolerances(), int max_iterations = 20);
// The phase omega t [rad] at which the orbit through section point y reaches its largest x over k periods
// on the rig without the bumper (the grazing orbit's touch), and that x (if x_max is given).
double peak_phase(const Params& p, double omega, const Vec2& y, int k, const Tolerances& tol, double* x_max = nullptr);
// The first rigid impact within k periods from section point y: its phase omega t [rad] and v- [m/s]; false
// without one.
bool first_impact(const Params& p, double omega, const Vec2& y, int k, const Tolerances& tol, double& theta,
                  double& v_minus);

// ---- Continuation -----------------------------------------------------------------------------------------

// The parameter a branch is continued in: the one a CF sweep or a scan axis moves (sweep_param_name names it).
using ContParam = SweepParam;

enum class BifKind : std::uint8_t { Fold, PeriodDoubling, NeimarkSacker, Grazing };
const char* bif_kind_name(BifKind k);       // "fold", "period_doubling", "neimark_sacker", "grazing"

struct BranchPoint {
    double param = 0;            // the continued parameter's value (omega [rad/s], xI [m] or m0e [kg m])
    Vec2 y = Vec2::Zero();       // section point
    int period = 1;
    bool stable = false;
    Floquet floquet;
    int impacts = 0;
    double max_x = 0;
    std::vector<Vec2> sections;  // the k section points of the orbit, y first (a period-k diagram draws all k)
};
struct Branch {
    int id = 0;
    int period = 1;
    int parent = -1;             // the branch it was switched from at a period doubling (-1: the first)
    std::vector<BranchPoint> points;   // ordered along the arclength
    std::string end;             // why it ended at each end ("omega range", "Newton failed", ...)
};
struct BifPoint {
    BifKind kind;
    double param = 0;
    Vec2 y = Vec2::Zero();
    int period = 1;
    int branch = 0;
    double precision = 0;        // uncertainty of param: the final bracket or, if larger, how far a crossing
                                 // still moves between the integrator at rtol/10 and rtol/100
    // A rigid grazing that the continuation crossed onto the impacting branch (G, H): "persistence" when the
    // impacting orbits lie on the far side (the branch goes through), "nonsmooth fold" when they lie on the
    // free orbits' side (the two meet there and end). The impacting orbit's largest |multiplier| and impact
    // speed scale as d^mu_exponent and d^speed_exponent in the distance d = |param - grazing| (fitted over the
    // orbits with impacts of 1e-4 .. 1e-3 m/s). Nordmark's map, x' = A x + b sqrt(penetration) + mu c, has
    // impacting fixed points whose sqrt(penetration), hence v-, grows linearly in d, and a derivative that grows
    // as 1/sqrt(penetration): -1 and +1.
    std::string scenario;
    double mu_exponent = NAN, speed_exponent = NAN;
};

struct ContinuationSpec {
    ContParam param = ContParam::Omega;
    double omega = 10;           // fixed omega when another parameter is continued [rad/s]
    double lo = 5, hi = 25;      // parameter range
    double start = NAN;          // parameter value of the first orbit (NaN: lo)
    Vec2 guess = Vec2(NAN, NAN); // its start (NaN: settle from the left well's bottom)
    int period = 1;
    int max_period = 8;          // period-doubled branches followed up to this period
    int max_branches = 12;
    int max_points = 800;        // per branch
    double ds = 0.02, ds_min = 1e-6, ds_max = 0.25;   // arclength in scaled units (x/1 cm, v/0.1 m/s, param/scale)
    double locate_tol = 1e-7;    // bifurcation points located to this width in the parameter
    Tolerances sim = analysis_tolerances();
};
struct ContinuationResult {
    std::vector<Branch> branches;
    std::vector<BifPoint> points;
    bool cancelled = false;
    double seconds = 0;          // wall time
    std::uint64_t map_evaluations = 0;
};
ContinuationResult continue_orbits(const Params& p, const ContinuationSpec& spec, Progress* progress = nullptr);

// A period-doubling cascade read off a continuation: the doublings of the chain of switched branches
// (period k -> 2k -> 4k ...), each on the branch switched onto at the one before, and Feigenbaum's ratios
// delta_j = (q_j - q_{j-1}) / (q_{j+1} - q_j) of consecutive ones (4.6692... in the limit): a check of how
// accurately the doublings are located. The longest chain is returned, ordered by period.
struct Cascade {
    std::vector<const BifPoint*> doublings;   // into the result's points
    std::vector<double> ratios;               // doublings.size() - 2 of them
};
inline constexpr double kFeigenbaumDelta = 4.669201609102990;
Cascade find_cascade(const ContinuationResult& r);

// ---- Two-parameter curves ---------------------------------------------------------------------------------

// A period doubling followed in two parameters: omega and `second` (xI or m0e). At each value of the second
// parameter, stepped by `step` from the model's own value to each end of [lo, hi], the doubling's omega is
// found again by a secant on the multiplier nearest -1 of the period-k orbit (Newton from the previous
// point's orbit, both extrapolated from the last two points). The curve ends where the orbit or the secant
// is lost (the multiplier turns complex, or the orbit is no longer found). The three curves take a Progress:
// its fraction is the share of [lo, hi] covered, and its cancel is seen before every step (the curve comes
// back marked cancelled).
struct CurvePoint {
    double omega = 0;            // [rad/s]
    double q = 0;                // the second parameter [m] or [kg m]
    Vec2 y = Vec2::Zero();       // the period-k orbit's section point there
};
// Why a curve stopped on one side of its start: the second parameter's range, the point lost (at q), a
// cancel, or the end of a plane's axis where the start already lay (curve_over_plane says so).
enum class CurveStop { Range, Lost, Cancelled, AxisEnd };
struct CurveEnd {
    CurveStop stop = CurveStop::Cancelled;
    double q = 0;                     // where the point was lost [the second parameter's unit]
    std::string why;                  // a lost point: what the last point found was near ("" if nothing known)
};
struct BifCurve {
    BifKind kind = BifKind::PeriodDoubling;
    ContParam second = ContParam::XI;
    int period = 1;
    std::vector<CurvePoint> points;   // ordered by q
    CurveEnd below, above;            // why it ended towards lower and higher q
    std::string end;                  // both in words, curve_ends_name ("cancelled" where a cancel stopped it)
    bool cancelled = false;           // stopped by a cancel: the points are only those found before it
};
// One end in words: "xI range", "doubling lost near xI = 0.001000", "cancelled", "at the axis' end".
std::string curve_end_name(const BifCurve& c, const CurveEnd& e);
// Both, "below / above".
std::string curve_ends_name(const BifCurve& c);
BifCurve continue_doubling_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                                 double lo, double hi, double step, const Tolerances& sim = analysis_tolerances(),
                                 Progress* progress = nullptr);

// A grazing followed in two parameters the same way: at each value of the second parameter the omega where
// the period-k orbit of the rig without its bumper reaches xI with its largest x (a secant on that x minus xI,
// which is smooth through the grazing). (omega0, y0): a grazing and its orbit's section point, as continue
// reports it. The curve ends where that orbit is lost.
BifCurve continue_grazing_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                                double lo, double hi, double step, const Tolerances& sim = analysis_tolerances(),
                                Progress* progress = nullptr);

// A fold (a multiplier at +1) followed the same way: at each value of the second parameter, Newton on the
// extended system P^k(y) = y, det(M - I) = 0 in (x, v, omega), from the last two points extrapolated.
BifCurve continue_fold_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                             double lo, double hi, double step, const Tolerances& sim = analysis_tolerances(),
                             Progress* progress = nullptr);

// The curve of `kind` (PeriodDoubling, Grazing or Fold; throws std::invalid_argument for another) from its
// known point: continue_doubling_curve, continue_grazing_curve or continue_fold_curve.
BifCurve continue_curve(BifKind kind, const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                        double lo, double hi, double step, const Tolerances& sim = analysis_tolerances(),
                        Progress* progress = nullptr);

// One curve of a branch in a bifurcation diagram's coordinates: a period-k branch gives k curves, one per
// section point of its orbit (a diagram shows all k of them at each parameter value).
struct BranchCurve {
    int branch = 0, period = 1;
    std::vector<double> param, x;   // the continued parameter, the section point's x [m]
    std::vector<char> stable;       // per point
};
// The curves of every branch, branch by branch and section point by section point; curves without points
// are left out.
std::vector<BranchCurve> branch_curves(const ContinuationResult& r);

// ---- Lyapunov exponents -----------------------------------------------------------------------------------

struct LyapunovResult {
    double lambda_max = 0;       // [1/s]
    double lambda_min = 0;       // the second exponent [1/s] (lambda_max + lambda_min = mean phase-volume rate)
    double seconds = 0;          // simulated time averaged over [s]
    std::vector<Vec2> sections;  // the recorded section points (the sweep's classification uses them)
    std::vector<double> growth;  // per period: log of the largest direction's stretch (lambda_max's share)
    bool cancelled = false;
};
// Benettin: tangent (with saltation) over `periods` forcing periods after `transient`, re-orthonormalised
// (QR) once per period. State s is advanced (a sweep carries it on); the drive starts at s.t with phi = 0.
LyapunovResult lyapunov(const Params& p, double omega, State& s, int transient, int periods,
                        const Tolerances& tol = {}, Progress* progress = nullptr);
// The check: two trajectories d0 apart (scaled), the distance renormalised once per period; growth (optional)
// receives each period's log(distance / d0).
double lyapunov_two_trajectory(const Params& p, double omega, State s, int transient, int periods,
                               const Tolerances& tol = {}, double d0 = 1e-7, std::vector<double>* growth = nullptr);

// Both estimates of lambda_max over the same trajectory (from s, at tol) with their scatter: the periods cut
// into `blocks` consecutive blocks, each block's estimate, and the standard error of the mean over blocks.
// On a chaotic attractor the two runs' reference trajectories part after some dozens of periods, so their
// blocks are independent samples: the difference is judged against both standard errors. The two-trajectory
// estimate is also run at d0 / 10, so that a difference from the finite separation shows as a move with d0.
struct LyapunovCheck {
    double benettin = 0, benettin_se = 0;          // [1/s]
    double two = 0, two_se = 0;                    // two trajectories d0 apart [1/s]
    double two_small = 0;                          // the same at d0 / 10 [1/s]
    double diff = 0, diff_se = 0;                  // two - benettin, and its standard error [1/s]
    double d0 = 1e-6;
    int blocks = 10;
    bool agree = false;                            // |diff| <= 3 diff_se (within the scatter)
    std::string why;                               // a sentence: agree, or what the difference follows
};
LyapunovCheck lyapunov_check(const Params& p, double omega, const State& s, int transient, int periods,
                             const Tolerances& tol, double d0 = 1e-6, int blocks = 10);

struct LyapunovPoint { double omega, lambda_max, lambda_min; int period; };
// Along a CF sweep (each omega from the previous state, as run_cf_sweep): spec.transient periods dropped,
// spec.record periods averaged; period = count_period of the recorded section points (as the sweep counts).
// on_point (optional) receives each omega's point as soon as it is done, on the calling thread (a GUI's
// progressive fill); a cancelled sweep returns the points done so far.
std::vector<LyapunovPoint> lyapunov_sweep(const Params& p, const CfSpec& spec, Progress* progress = nullptr,
                                          const Tolerances& tol = {},
                                          const std::function<void(const LyapunovPoint&)>& on_point = {});

// ---- Basins of attraction ---------------------------------------------------------------------------------

enum class AttractorKind : std::uint8_t { Periodic, Chaos, Resting, Failed };
inline Tolerances basin_tolerances() {
    Tolerances t;
    t.rtol = 1e-6;
    return t;
}
// "period", "chaos" (no recurrence up to max_period: chaotic or a longer period), "resting" (held at the
// bumper in regime III through whole periods), "failed" (the simulator stalled).
const char* attractor_kind_name(AttractorKind k);

struct BasinSpec {
    double omega = 13;                        // [rad/s], constant; every cell starts at t = 0, phi = 0
    double x_min = -0.03, x_max = 0.0;        // [m] grid of cell centres x0_i = x_min + (i + 1/2) dx
    double v_min = -0.3, v_max = 0.3;         // [m/s]
    int nx = 200, nv = 200;
    // A cell runs at most transient + periods forcing periods; it stops as soon as its section points recur
    // (period k: |y_j - y_{j-k}| < recur_tol for `confirm` whole cycles, and at least 4 points). One that
    // never recurs keeps its last `periods` section points as a chaotic attractor, unless these repeat within
    // match_tol over the whole window (a slowly converging cycle). A1G at omega 13: every periodic cell has
    // recurred within 60 periods (300 give the same labels).
    int transient = 60;
    int periods = 40;
    int max_period = 16;
    int confirm = 3;
    double recur_tol = 1e-5;                  // scaled (x / 1 cm, v / 0.1 m/s): early stop of a cell
    double match_tol = 1e-3;                  // scaled: two cycles are the same orbit (and the late check)
    double chaos_tol = 0.2;                   // scaled: median nearest-neighbour distance of two chaotic sets
    int threads = 0;                          // 0: std::thread::hardware_concurrency()
    // rtol 1e-6: a basin needs the attractor, not digits (A1G, omega 13, 50 x 50: the same labels as 1e-8
    // for 0.62 of the time; the section noise stays below recur_tol).
    Tolerances sim = basin_tolerances();
};

// Where one start ends: its attractor as section points at phi = 2 pi i.
struct CellOutcome {
    AttractorKind kind = AttractorKind::Chaos;
    int period = 0;                           // k (Periodic, Resting); 0 otherwise
    int periods_run = 0;                      // forcing periods simulated
    std::vector<Vec2> points;                 // one cycle (k points), or the last `periods` points (chaos)
};
// Runs (x0, v0) at t = 0, phi = 0 through the Simulator until its section points recur or the budget ends.
CellOutcome run_to_attractor(const Params& p, const BasinSpec& spec, const Vec2& y0);

struct Attractor {
    int id = 0;                               // the label; ids follow the first grid cell (row-major) reaching it
    AttractorKind kind = AttractorKind::Chaos;
    int period = 0;
    int well = 0;                             // sign of the mean section x: -1 left, +1 right, 0 at x = 0
    std::vector<Vec2> points;                 // the first cell's outcome points
    Vec2 representative = Vec2::Zero();       // the point of smallest x (a cycle's canonical point)
    std::size_t first_cell = 0, cells = 0;
    double mean_periods = 0;                  // mean forcing periods its cells ran
};
struct BasinResult {
    BasinSpec spec;
    std::vector<int> label;                   // nv rows of nx: label[j * nx + i] at (x0_i, v0_j); -1 not run
    std::vector<Attractor> attractors;
    bool cancelled = false;
    double seconds = 0;                       // wall time
    std::uint64_t periods_run = 0;            // forcing periods simulated over all cells
    int threads = 1;
    double x0(int i) const { return spec.x_min + (i + 0.5) * (spec.x_max - spec.x_min) / spec.nx; }
    double v0(int j) const { return spec.v_min + (j + 0.5) * (spec.v_max - spec.v_min) / spec.nv; }
};
// The grid on a pool of spec.threads threads (rows handed out one at a time). Every 4th cell in x and v runs
// first; every other cell also stops once two consecutive section points follow one of their trajectories
// (within 1e-3 scaled), and takes its outcome. Labels are assigned after all cells are done, in cell order,
// so the result is identical for any thread count. Throws
// std::invalid_argument for an empty grid or an inverted range.
BasinResult compute_basins(const Params& p, const BasinSpec& spec, Progress* progress = nullptr);
// Whether two outcomes are the same attractor (the matching compute_basins uses).
bool same_attractor(const CellOutcome& a, const CellOutcome& b, const BasinSpec& spec);
// The window of starts shown by default: x0 in [-0.03, xI] (a bumper beyond 3 cm, or none: [-0.03, 0.03],
// and at least 3 cm wide below the bumper), v0 in [-0.3, 0.3] m/s.
void set_default_window(const Params& p, BasinSpec& spec);

}  // namespace impactlab::analysis
