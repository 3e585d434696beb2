// The continuation's engine (continuation.cpp): its constants, a converged point and the Continuer, which
// follows branches on the stroboscopic map (continuation.cpp) and, near a rigid grazing, from impact to
// impact (continuation_impacting.cpp).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>
#include <vector>

#include "analysis/tangent.hpp"
#include "impactlab/analysis.hpp"
#include "parallel.hpp"

namespace impactlab::analysis::detail {


using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr double kResidualTol = 1e-9;   // scaled |P^k(y) - y| of a converged point (at rtol <= 1e-10)
constexpr int kMaxCorrector = 10;
// A crossing multiplier must lie this close to +1, -1 or the unit circle at both ends of its bracket.
constexpr double kNearCrossing = 0.5;
// |d mu / ds| (scaled arclength) above this is a jump, not a crossing (a smooth one is O(1..100)).
constexpr double kSteepCrossing = 1e4;
// A multiplier at rtol 1e-10 jitters by up to about 3e-3 (an impacting orbit's): over a bracket refined to
// 1e-8 that alone looks steep, so a jump must also be larger than this.
constexpr double kMultiplierJitter = 0.01;
// The scatter of a multiplier from the tangent tracker at any rtol (A1C's period 1 at 22.147, rtol 1e-12 and
// 1e-13: about 5e-7 about a straight line).
constexpr double kMultiplierFloor = 1e-6;
// A sign change of a test function over a bracket ds_bracket long (scaled) whose crossing multiplier goes from
// m_lo to m_hi is a jump (a grazing's), not a crossing, when it is both large and steep.
inline bool multiplier_jumps(double m_lo, double m_hi, double ds_bracket) {
    const double dm = std::abs(m_hi - m_lo);
    return dm > kMultiplierJitter && dm / std::max(ds_bracket, 1e-300) > kSteepCrossing;
}
// A period map P^k expanding more than this (its largest multiplier) is corrected period by period: a point a
// distance d off the branch has a residual of |mu| d, and P^k is nonlinear on that scale (A1C's period 8
// pressing the bumper, mu = 2.5e4: a Newton step cut the residual only 4-fold, and the branch crawled).
constexpr double kShootExpansion = 1e3;
// Penetration of a compliant bumper below which an orbit is still grazing it [m] (C: a force under 0.3 N).
constexpr double kGrazingLayer = 1e-6;
// A step whose multipliers move more than this is retried shorter: it may have jumped onto another
// segment of the branch (across a fold onto the impacting orbit) and a crossing would go unseen.
constexpr double kMaxMultiplierStep = 0.3;
// A compliant contact deeper than this is past its grazing layer [m] (C's layer: about 1 um).
constexpr double kContactDepth = 1e-5;
// Grazing layers of a compliant contact crossed in depth per branch (a bound against going to and fro).
constexpr int kMaxLayers = 8;
// Rigid impacts slower than this are followed from impact to impact, faster ones on the stroboscopic map,
// whose corrector handles them (A1G's window from 16 rad/s, whose slowest impacts are near 0.1 m/s) [m/s].
constexpr double kHandover = 0.05;
// An impact this slow on an orbit with several impacts a period ends the branch: a grazing ahead [m/s].
constexpr double kSlowImpact = 1e-2;

// A converged point of a branch and what the test functions need.
struct Sol {
    Vec3 u = Vec3::Zero();          // scaled (x / kXScale, v / kVScale, q / q_scale)
    MapResult r;                    // at u, with the monodromy
    Eigen::Matrix<double, 2, 3> J = Eigen::Matrix<double, 2, 3>::Zero();  // scaled d G / d u (G = scaled P^k(y) - y)
    int iterations = 0;
};

// Where a job starts: the first orbit (both ways) or a doubling's switch; a rigid grazing to cross (u: the
// grazing orbit, t[2]: the free branch's direction there); onward from a converged point along t, one way;
// an impacting orbit of the stroboscopic branch whose impacts are slow, followed from impact to impact.
enum class JobMode { Start, Grazing, Onward, SlowImpacts };
// The words a branch begun from impact to impact puts before its far end ("grazing / omega range").
inline const char* job_mode_name(JobMode m) {
    switch (m) {
    case JobMode::Start: return "start";
    case JobMode::Grazing: return "grazing";
    case JobMode::Onward: return "onward";
    case JobMode::SlowImpacts: return "slow impacts";
    }
    return "?";
}

// What following a job gave: a branch to keep, or nothing new (the grazing's impacting branch was already
// followed up to it from another grazing).
enum class Followed { Branch, AlreadyReached };

class Continuer {
public:
    Continuer(const Params& p, const ContinuationSpec& spec, Progress* progress)
        : base_(p), work_(p), spec_(spec), progress_(progress) {
        q_scale_ = spec.param == ContParam::Omega ? 1.0 : spec.param == ContParam::XI ? 1e-3 : 1e-3;
        // The map is known only to about rtol: a corrector asked for less than that never converges.
        res_tol_ = std::max(kResidualTol, 10 * spec.sim.rtol);
    }

    ContinuationResult run();

private:
    struct Job { int period; int parent; Vec3 u; Vec3 t; bool both_ways; JobMode mode = JobMode::Start; };

    double q_of(const Vec3& u) const { return u[2] * q_scale_; }
    Vec2 y_of(const Vec3& u) const { return Vec2(u[0] * kXScale, u[1] * kVScale); }
    Vec3 u_of(const Vec2& y, double q) const { return Vec3(y[0] / kXScale, y[1] / kVScale, q / q_scale_); }

    // Puts the parameter value q into w; returns the omega to run at.
    double apply_to(Params& w, double q) const {
        if (spec_.param == ContParam::Omega) return q;
        if (spec_.param == ContParam::XI) w.xI = q;
        else w.m0e = q;
        return spec_.omega;
    }
    double apply(double q) { return apply_to(work_, q); }

    // The distance (scaled) from c to the segment a..b.
    static double segment_distance(const Vec3& c, const Vec3& a, const Vec3& b) {
        const double len2 = (b - a).squaredNorm();
        const double f = len2 > 0 ? std::clamp((c - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
        return (a + f * (b - a) - c).norm();
    }

    MapResult map(const Vec3& u, int k, bool tangent) {
        const double omega = apply(q_of(u));
        ++evaluations_;
        return poincare_map(work_, omega, y_of(u), k, tangent, spec_.sim);
    }

    // The maps at several points side by side (a corrector's point with its monodromy and its finite-difference
    // neighbours): each on its own copy of the parameters, so each result is the one map() would give, in any
    // order and on any number of threads.
    // phis: where given, the monodromy at each section (period_map).
    struct MapAt { Vec3 u; bool tangent; std::vector<Mat2>* phis = nullptr; };
    std::vector<MapResult> maps(const std::vector<MapAt>& at, int k) {
        std::vector<MapResult> out(at.size());
        const Params base = work_;
        ::impactlab::detail::for_each_index(at.size(), [&](std::size_t i) {
            Params w = base;
            const double omega = apply_to(w, q_of(at[i].u));
            out[i] = period_map(w, omega, y_of(at[i].u), k, at[i].tangent, spec_.sim, at[i].phis);
        });
        evaluations_ += at.size();
        return out;
    }

    // A state and a monodromy in the scaled variables (x / kXScale, v / kVScale).
    static Vec2 scaled(const Vec2& y) { return Vec2(y[0] / kXScale, y[1] / kVScale); }
    static Mat2 scaled(const Mat2& M) {
        Mat2 S;
        S(0, 0) = M(0, 0);
        S(0, 1) = M(0, 1) * kVScale / kXScale;
        S(1, 0) = M(1, 0) * kXScale / kVScale;
        S(1, 1) = M(1, 1);
        return S;
    }

    Vec2 residual(const MapResult& r, const Vec3& u) const { return scaled(r.y) - u.head<2>(); }

    // How long an impact at zero speed holds the cart [s]: 0 for G (the map is continuous at a grazing),
    // T_imp(0) for H.
    double dwell_at_rest() const { return work_.rigid() ? work_.impact->duration(work_.ip.data(), 0.0) : 0.0; }

    // An orbit pressing a compliant bumper deeper than its grazing layer.
    bool deep_contact(const Sol& s) const {
        return work_.compliant() && s.r.max_x - work_.xI > kContactDepth;
    }

    // Scaled d G / d u (r: the map at u, with its monodromy); d P / d q by a forward difference, rq being the map
    // at u + kDq in the parameter (the tangent in the parameter would need the section time's dependence on
    // omega and the law's on xI).
    static constexpr double kDq = 1e-6;
    static Vec3 shifted_q(const Vec3& u) { return Vec3(u[0], u[1], u[2] + kDq); }
    static Eigen::Matrix<double, 2, 3> jacobian(const MapResult& r, const MapResult& rq) {
        return jacobian(scaled(r.M), Vec2((rq.y[0] - r.y[0]) / kXScale / kDq, (rq.y[1] - r.y[1]) / kVScale / kDq));
    }
    // The same from the scaled monodromy M and d P / d q (scaled).
    static Eigen::Matrix<double, 2, 3> jacobian(const Mat2& M, const Vec2& dq) {
        Eigen::Matrix<double, 2, 3> J;
        J.leftCols<2>() = M - Mat2::Identity();
        J.col(2) = dq;
        return J;
    }

    // A converged corrector's point handed out.
    static bool take(Sol& out, const Vec3& u, MapResult& r, const Eigen::Matrix<double, 2, 3>& J, int it) {
        out.u = u;
        out.r = std::move(r);
        out.J = J;
        out.iterations = it;
        return true;
    }

    // Newton on G(u) = 0 and n . (u - u_pred) = 0.
    bool correct(const Vec3& u_pred, const Vec3& n, int k, Sol& out) {
        Vec3 u = u_pred;
        for (int it = 0; it <= kMaxCorrector; ++it) {
            // A step past omega = 0 (a range that starts near it) has no forcing period: a failed step, which
            // the step control shortens until the point lands in (0, lo) and the branch ends at the range.
            if (spec_.param == ContParam::Omega && !(q_of(u) > 0)) return false;
            std::vector<Mat2> phis;
            std::vector<MapResult> rs = maps({{u, true, it == 0 && k >= 2 ? &phis : nullptr}, {shifted_q(u), false}}, k);
            MapResult r = std::move(rs[0]);
            const Vec2 G = residual(r, u);
            if (!G.allFinite()) return false;
            const Eigen::Matrix<double, 2, 3> J = jacobian(r, rs[1]);
            const double h = n.dot(u - u_pred);
            if (G.cwiseAbs().maxCoeff() < res_tol_ && std::abs(h) < 1e-9) return take(out, u, r, J, it);
            if (it == kMaxCorrector) break;
            Mat3 A;
            A.topRows<2>() = J;
            A.row(2) = n.transpose();
            const Vec3 rhs(G[0], G[1], h);
            const Vec3 du = A.fullPivLu().solve(-rhs);
            if (!du.allFinite() || du.norm() > 1.0) return false;   // left the neighbourhood of the branch
            if (it == 0 && k >= 2 && std::abs(floquet(r.M).mu[0]) > kShootExpansion)
                return correct_by_periods(u_pred, n, k, u, du, r, rs[1], phis, out);
            // At the map's noise floor (a long period: its residual's noise passes res_tol) the residual no
            // longer falls, yet a Newton step below the tolerance puts the branch's point within it of u (as
            // find_orbit accepts it). Without this, whether a step converges follows the last bits of libm.
            if (it >= 2 && du.norm() < res_tol_ && G.cwiseAbs().maxCoeff() < 100 * res_tol_ && std::abs(h) < 1e-9)
                return take(out, u, r, J, it);
            u += du;
        }
        return false;
    }

    // Newton on the k one-period maps at once (multiple shooting): unknowns z_0 .. z_{k-1} (scaled section
    // points) and q, equations P(z_i) = z_{i+1 mod k} and n . (u - u_pred) = 0, u = (z_0, q). Started from
    // the first Newton step du of the whole map at u (r, rq: P^k at u and at u shifted in q; phis: its
    // monodromy at each section), carried along the orbit by the linearised map. Each period's map is
    // evaluated on its own, on all cores.
    bool correct_by_periods(const Vec3& u_pred, const Vec3& n, int k, const Vec3& u, const Vec3& du,
                            const MapResult& r, const MapResult& rq, const std::vector<Mat2>& phis, Sol& out);

    static Vec3 tangent_of(const Sol& s, const Vec3& prev) {
        Vec3 t = Vec3(s.J.row(0).transpose()).cross(Vec3(s.J.row(1).transpose()));
        if (t.norm() == 0 || !t.allFinite()) return prev;
        t.normalize();
        if (t.dot(prev) < 0) t = -t;
        return t;
    }

    // Test functions: each changes sign at its bifurcation.
    double test(BifKind kind, const Sol& s) const {
        const Mat2& M = s.r.M;
        switch (kind) {
            case BifKind::Fold: return (M - Mat2::Identity()).determinant();
            case BifKind::PeriodDoubling: return (M + Mat2::Identity()).determinant();
            case BifKind::NeimarkSacker: return M.determinant() - 1.0;
            case BifKind::Grazing:
                if (!base_.has_bumper()) return -1.0;
                if (!work_.has_bumper()) return (s.r.max_x - work_.xI) / kXScale;   // locating a rigid grazing
                if (work_.rigid() && s.r.impacts > 0) return s.r.min_impact_speed / kVScale;
                return (s.r.max_x - work_.xI) / kXScale;
        }
        return 0;
    }
    // Scaled distance between the section point and the one k/2 periods later (0: the orbit has period k/2).
    double half_gap(const Sol& s, int k) const {
        if (s.r.sections.size() < static_cast<std::size_t>(k)) return 1.0;
        return scaled_norm(s.r.sections[static_cast<std::size_t>(k / 2 - 1)] - y_of(s.u));
    }
    static bool complex_pair(const Mat2& M) {
        const double tr = M.trace(), det = M.determinant();
        return 0.25 * tr * tr - det < 0;
    }
    // The multiplier a kind is about: the real one nearest +1 (fold) or -1 (period doubling), the modulus
    // of a complex pair (Neimark-Sacker, which crosses |mu| = 1). NaN when the multipliers are not of that
    // sort (complex for a fold or a doubling, real for Neimark-Sacker).
    static double crossing_multiplier(BifKind kind, const Mat2& M) {
        const Floquet f = floquet(M);
        if (kind == BifKind::NeimarkSacker) return complex_pair(M) ? std::abs(f.mu[0]) : NAN;
        if (complex_pair(M)) return NAN;
        const double c = kind == BifKind::Fold ? 1.0 : -1.0;
        const double a = f.mu[0].real(), b = f.mu[1].real();
        return std::abs(a - c) < std::abs(b - c) ? a : b;
    }
    // The crossing multiplier of the orbit at parameter q near y, found with the integrator's rtol scaled by
    // `factor`: the orbit moves with the integrator's error too, and the multiplier is steep in it (A1C at
    // the first doubling: 3e3 per metre of x). NaN if that run stalls or does not converge.
    double crossing_at(BifKind kind, double q, const Vec2& y, int k, double factor) {
        OrbitOptions oo;
        oo.period = k;
        oo.sim = spec_.sim;
        oo.sim.rtol = std::max(oo.sim.rtol * factor, 1e-13);
        oo.max_iterations = 8;
        const double omega = apply(q);
        ++evaluations_;
        try {
            const Orbit o = find_orbit(work_, omega, y, oo);
            return o.converged && scaled_norm(o.y - y) < 1e-2 ? crossing_multiplier(kind, o.M) : NAN;
        } catch (const std::exception&) {
            return NAN;
        }
    }
    // The largest change of a multiplier between two points (matched the closer way round), relative to the
    // larger multiplier where that exceeds 1: an unstable orbit of a cascade (mu = -20 .. -1000) moves its
    // multiplier by more than kMaxMultiplierStep in any step worth taking, while a jump onto another segment
    // (-1 to -13) stays large relative to it.
    static double multiplier_change(const Mat2& A, const Mat2& B) {
        const Floquet a = floquet(A), b = floquet(B);
        const double same = std::max(std::abs(a.mu[0] - b.mu[0]), std::abs(a.mu[1] - b.mu[1]));
        const double swapped = std::max(std::abs(a.mu[0] - b.mu[1]), std::abs(a.mu[1] - b.mu[0]));
        const double scale = std::max({1.0, std::abs(a.mu[0]), std::abs(b.mu[0])});
        return std::min(same, swapped) / scale;
    }

    BranchPoint point_of(const Sol& s, int k) const {
        BranchPoint b;
        b.param = q_of(s.u);
        b.y = y_of(s.u);
        b.period = k;
        b.floquet = floquet(s.r.M);
        b.stable = b.floquet.stable;
        b.impacts = s.r.impacts;
        b.max_x = s.r.max_x;
        b.sections.push_back(b.y);
        for (std::size_t i = 0; i + 1 < s.r.sections.size(); ++i) b.sections.push_back(s.r.sections[i]);
        return b;
    }

    // Natural-parameter restart past a corrector failure on a near-neutral orbit (see follow()); on success
    // cur, t and ds are the restarted point, its tangent and the initial step, and the jump is noted.
    bool restart(Sol& cur, Vec3& t, int k, double& ds, std::string& skipped) {
        const Floquet f = floquet(cur.r.M);
        if (std::abs(f.mu[0].imag()) > 0 || f.mu[0].real() < 0.99) return false;
        const double dir = t[2] >= 0 ? 1.0 : -1.0;
        for (double jump : {0.01, 0.03, 0.1}) {
            Vec3 u = cur.u;
            u[2] += dir * jump;
            const double q = q_of(u);
            if (q < std::min(spec_.lo, spec_.hi) || q > std::max(spec_.lo, spec_.hi)) return false;
            OrbitOptions oo;
            oo.period = k;
            oo.sim = spec_.sim;
            const double omega = apply(q);
            ++evaluations_;
            const Orbit o = find_orbit(work_, omega, y_of(cur.u), oo);
            if (!o.converged || scaled_norm(o.y - y_of(cur.u)) > 0.1) continue;   // not the same branch
            Sol next;
            const Vec3 n(0, 0, 1);
            if (!correct(u_of(o.y, q), n, k, next)) continue;
            char buf[96];
            std::snprintf(buf, sizeof buf, "%s%.6g..%.6g", skipped.empty() ? "" : ", ", std::min(q_of(cur.u), q),
                          std::max(q_of(cur.u), q));
            skipped += buf;
            cur = std::move(next);
            t = tangent_of(cur, Vec3(0, 0, dir));
            ds = spec_.ds;
            return true;
        }
        return false;
    }

    // Bisection along the step from a (with tangent t) to the point at arclength ds.
    // off_bumper: a grazing the corrector cannot cross is located on the bumperless orbit (rigid bumpers,
    // and compliant ones too stiff for it, as C1's).
    void locate(BifKind kind, const Sol& a, const Vec3& t, double ds, const Sol& b, int k, int branch,
                bool off_bumper = false);
    // A located point between lo and hi (test values f_lo, f_hi; the bracket's width as its precision) kept
    // unless it is not the crossing its kind names or was met before; a doubling's branch is queued.
    void record(BifKind kind, const Sol& lo, const Sol& hi, double f_lo, double f_hi, int k, int branch);
    // Whether the bracket lo..hi of a fold, doubling or Neimark-Sacker holds a crossing of the multiplier it
    // names (not a jump, not a grazing's); for a doubling or Neimark-Sacker the point's shift and precision
    // from the orbit found again at a tighter tolerance.
    bool true_crossing(BifKind kind, const Sol& lo, const Sol& hi, const Sol& best, int k, double& precision, double& shift);
    // The crossing moved to where the multiplier at rtol / 100 crosses (a doubling or Neimark-Sacker), with
    // the precision that allows; a fold or a grazing stays where the bracket put it.
    void refine_crossing(BifKind kind, const Sol& lo, const Sol& hi, const Sol& best, int k, double& precision, double& shift);
    // A doubling's job whose period-2k orbit an earlier branch already passes through (the far end of a
    // bubble, or a loop through both doublings): any of the k section points may be where it lands.
    bool covered(const Job& job) const;
    // A period doubling located at best: the period-2k branch queued as a job.
    void switch_to_doubled(const Sol& best, int k, int branch);
    void follow(const Job& job, Branch& br);
    // Why a branch ends where the corrector fails at every step down to ds_min from cur: the numerical
    // limit, or the grazing it ran into, located on the bumperless orbit (a rigid grazing's impacting branch
    // is queued as a job).
    std::string corrector_limit(const Sol& cur, const Vec3& t, double ds, int k, int branch);
    // The impacting branch from a located rigid grazing g queued as a job, the way t was going in the parameter.
    void queue_grazing(const BifPoint& g, const Vec3& t, int k, int branch) {
        jobs_.push_back({k, branch, u_of(g.y, g.param), Vec3(0, 0, t[2] >= 0 ? 1.0 : -1.0), false, JobMode::Grazing});
    }
    // The end of a branch whose step from cur to next crossed H's jump at a grazing (the impacting side's branch
    // queued from the located grazing when the branch was free).
    std::string dwell_jump_end(const Sol& cur, const Vec3& t, const Sol& next, int k, int branch);
    // The test functions' sign changes over the step from cur to next, each located; a rigid grazing that the
    // corrector itself stepped across gets its scenario and exponents.
    void locate_crossings(const Sol& cur, const Vec3& t, double ds, const Sol& next, int k, int branch);
    // The step from a to b passes within 1e-3 (scaled) of one of pj's section points: the same orbit again.
    bool passes_by(const BranchPoint& pj, const Vec3& a, const Vec3& b) const;
    // A corrector that failed at a short step on a long period (at_limit: at the shortest step, on an orbit
    // deep in a compliant contact): the map sharpened and cur corrected on it; false where that does not
    // apply (or was done twice).
    bool sharpen(Sol& cur, const Vec3& t, int k, double& ds, int& sharpened, bool at_limit = false);
    // A step from cur to next that is to be taken again shorter (ds shortened): a grazing ahead, a corrector
    // that wandered or multipliers that jumped, or once a step past the range's end (clipped).
    bool shorten(const Sol& cur, const Vec3& t, const Sol& next, bool first, bool& clipped, double& ds) const;
    // The share of the range a forward branch has covered at q, never backwards.
    void report_progress(double q);
    // On from next (slow rigid impacts) from impact to impact: its points appended to pts; returns the end.
    std::string hand_over(const Job& job, const Sol& next, const Vec3& t, int branch, std::vector<BranchPoint>& pts);
    // From a rigid grazing onto the impacting branch, written from impact to impact (impact_shot) while the
    // impacts are slow, then on with the stroboscopic map (follow, onward).
    Followed follow_impacting(const Job& job, Branch& br);
    // The start from an impacting orbit of the stroboscopic branch whose impacts are slow (job.u): z, t and
    // section, or false with the reason in failure.
    bool slow_impacts_start(const Job& job, Vec3& z, Vec3& t, Vec2& section, std::string& failure);
    // Why the impacting branch ends where the corrector fails at every step down to ds_min from z.
    std::string impacting_limit(const Vec3& z, const Vec3& t, double ds, int k);
    // The impacts end on the step from z to zn (v- through zero): the grazing located, kept once and noted as
    // reached; returns the branch's end.
    std::string impacts_end(const Vec3& z, const Vec3& t, double ds, const Vec3& zn, const Vec2& sec, int k, int branch);
    // The exponents of a crossed grazing (BifPoint::mu_exponent, speed_exponent) from the impacting orbits
    // near it; z, t: the grazing orbit from impact to impact and the impacting branch's tangent there.
    void measure_scaling(BifPoint& gp, const Vec3& z, const Vec3& t, int k);
    // The grazing orbit at (q_g, y_g) from impact to impact (z) and the impacting branch's tangent there (t).
    // With a dwell at rest (H, dwell = true) the impacting branch's first orbit instead: the one that arrives at
    // xI at rest, dwells T_imp(0) and closes, found with the parameter free.
    bool grazing_start(double q_g, const Vec2& y_g, int k, Vec3& z, Vec3& t, Vec2& section, bool dwell = false);
    // The scenario of such a grazing: the dwell, and the jump from the grazing orbit to that first orbit.
    void describe_dwell(BifPoint& gp, const Vec3& z, const Vec2& section, int k);
    // Its scenario (persistence or nonsmooth fold) and exponents.
    void describe_grazing(BifPoint& gp, double free_dir, const Vec3& z, const Vec3& t, int k);
    // A fold, doubling or Neimark-Sacker between two impact-to-impact points (z + s t, s in [0, ds]), located
    // by bisection on the test function of the stroboscopic monodromy; a and b are the two ends' orbits.
    void locate_impacting(BifKind kind, const Vec3& z, const Vec3& t, double ds, const Sol& a, const Sol& b, int k,
                          int branch);
    // The impact-to-impact equations at z = (theta, v- / kVScale, q / q_scale), with d/dz (q by a forward
    // difference). False if the flight stalls.
    bool shot(const Vec3& z, int k, Vec2& G, Eigen::Matrix<double, 2, 3>& J, Vec2& section);
    bool correct_impacting(const Vec3& z_pred, const Vec3& n, int k, Vec3& z, Eigen::Matrix<double, 2, 3>& J, Vec2& section);

    // ---- A compliant contact's grazing layer (continuation_contact.cpp) ----
    // Newton on G(u) = 0 and (largest x - xI) = depth: the branch written with the contact's depth as its
    // parameter, which steps through the layer where the branch turns within nanometres of the touch.
    bool correct_depth(const Vec3& u_pred, double depth, int k, Sol& out);
    // From cur (where the arclength corrector failed within the layer) on in depth, the way the branch was
    // going, until the contact is microns deep or the orbit clear of it: the points appended to pts and arc,
    // the crossings on the way located, cur and t the last point and its tangent. False if the layer was not
    // crossed (cur is then the last point reached).
    bool cross_contact_layer(Sol& cur, Vec3& t, int k, int branch, std::vector<BranchPoint>& pts,
                             std::vector<double>& arc);
    // A fold, doubling or Neimark-Sacker between two depth points (depths scale sinh(sa), scale sinh(sb)),
    // located by bisection.
    void locate_depth(BifKind kind, const Sol& a, double sa, const Sol& b, double sb, double scale, int k, int branch);

    bool cancelled() const { return progress_ && progress_->cancel.load(std::memory_order_relaxed); }

    const Params& base_;
    Params work_;
    ContinuationSpec spec_;
    Progress* progress_;
    double q_scale_ = 1;
    double res_tol_ = kResidualTol;
    std::uint64_t evaluations_ = 0;
    ContinuationResult result_;
    std::deque<Job> jobs_;
    double branch_fraction_ = 0;
    int last_located_ = -1;   // index in result_.points of what locate() last found (new or met again)
    int handoffs_ = 0;   // stroboscopic -> impact to impact switches in this run (bounded against a ping-pong)
    std::vector<double> reached_;   // grazings reached from the impacting side (where the impacts end)
};

}  // namespace impactlab::analysis::detail
