// Pseudo-arclength continuation of periodic orbits (fixed points of P^k) in omega, xI or m0e, with test
// functions for folds (det(M - I)), period doublings (det(M + I)), Neimark-Sacker (det M - 1 with complex
// multipliers) and grazing (the largest x of the orbit reaching xI, or the smallest impact speed reaching 0),
// each located by bisection along the arclength; at a period doubling the period-2k branch is switched onto.
// A sign change counts only as the multiplier crossing it names (real through +1 or -1, a complex pair through
// the unit circle, at a finite rate, clear of a grazing); a doubling or Neimark-Sacker is then re-located on
// the orbit found again at a tighter tolerance.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>

#include "impactlab/analysis.hpp"

namespace impactlab::analysis {

const char* cont_param_name(ContParam c) {
    switch (c) {
        case ContParam::Omega: return "omega";
        case ContParam::XI: return "xI";
        case ContParam::M0e: return "m0e";
    }
    return "?";
}

const char* bif_kind_name(BifKind k) {
    switch (k) {
        case BifKind::Fold: return "fold";
        case BifKind::PeriodDoubling: return "period_doubling";
        case BifKind::NeimarkSacker: return "neimark_sacker";
        case BifKind::Grazing: return "grazing";
    }
    return "?";
}

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr double kResidualTol = 1e-9;   // scaled |P^k(y) - y| of a converged point (at rtol <= 1e-10)
constexpr int kMaxCorrector = 10;
// A crossing multiplier must lie this close to +1, -1 or the unit circle at both ends of its bracket.
constexpr double kNearCrossing = 0.5;
// |d mu / ds| (scaled arclength) above this is a jump, not a crossing (a smooth one is O(1..100)).
constexpr double kSteepCrossing = 1e4;
// Penetration of a compliant bumper below which an orbit is still grazing it [m] (C: a force under 0.3 N).
constexpr double kGrazingLayer = 1e-6;
// A step whose multipliers move more than this is retried shorter: it may have jumped onto another
// segment of the branch (across a fold onto the impacting orbit) and a crossing would go unseen.
constexpr double kMaxMultiplierStep = 0.3;
// Rigid impacts slower than this are followed from impact to impact, faster ones on the stroboscopic map,
// whose corrector handles them (A1G's window from 16 rad/s, whose slowest impacts are near 0.1 m/s) [m/s].
constexpr double kHandover = 0.05;

// A converged point of a branch and what the test functions need.
struct Sol {
    Vec3 u = Vec3::Zero();          // scaled (x / kXScale, v / kVScale, q / q_scale)
    MapResult r;                    // at u, with the monodromy
    Eigen::Matrix<double, 2, 3> J = Eigen::Matrix<double, 2, 3>::Zero();  // scaled d G / d u (G = scaled P^k(y) - y)
    int iterations = 0;
};

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
    // mode 0: a start (both_ways) or a doubling's switch; 1: a rigid grazing to cross (u: the grazing orbit,
    // t[2]: the free branch's direction there); 2: onward from a converged point along t, one way.
    struct Job { int period; int parent; Vec3 u; Vec3 t; bool both_ways; int mode = 0; };

    double q_of(const Vec3& u) const { return u[2] * q_scale_; }
    Vec2 y_of(const Vec3& u) const { return Vec2(u[0] * kXScale, u[1] * kVScale); }
    Vec3 u_of(const Vec2& y, double q) const { return Vec3(y[0] / kXScale, y[1] / kVScale, q / q_scale_); }

    // Puts the parameter value q into work_; returns the omega to run at.
    double apply(double q) {
        if (spec_.param == ContParam::Omega) return q;
        if (spec_.param == ContParam::XI) work_.xI = q;
        else work_.m0e = q;
        return spec_.omega;
    }

    MapResult map(const Vec3& u, int k, bool tangent) {
        const double omega = apply(q_of(u));
        ++evaluations_;
        return poincare_map(work_, omega, y_of(u), k, tangent, spec_.sim);
    }

    Vec2 residual(const MapResult& r, const Vec3& u) const {
        return Vec2(r.y[0] / kXScale - u[0], r.y[1] / kVScale - u[1]);
    }

    // Newton on G(u) = 0 and n . (u - u_pred) = 0.
    bool correct(const Vec3& u_pred, const Vec3& n, int k, Sol& out) {
        Vec3 u = u_pred;
        for (int it = 0; it <= kMaxCorrector; ++it) {
            // A step past omega = 0 (a range that starts near it) has no forcing period: a failed step, which
            // the step control shortens until the point lands in (0, lo) and the branch ends at the range.
            if (spec_.param == ContParam::Omega && !(q_of(u) > 0)) return false;
            MapResult r = map(u, k, true);
            const Vec2 G = residual(r, u);
            if (!G.allFinite()) return false;
            Eigen::Matrix<double, 2, 3> J;
            J(0, 0) = r.M(0, 0) - 1.0;
            J(0, 1) = r.M(0, 1) * kVScale / kXScale;
            J(1, 0) = r.M(1, 0) * kXScale / kVScale;
            J(1, 1) = r.M(1, 1) - 1.0;
            // d P / d q by a forward difference (one more map; the tangent in the parameter would need the
            // section time's dependence on omega and the law's on xI).
            const double dq = 1e-6;
            Vec3 uq = u;
            uq[2] += dq;
            const MapResult rq = map(uq, k, false);
            J(0, 2) = (rq.y[0] - r.y[0]) / kXScale / dq;
            J(1, 2) = (rq.y[1] - r.y[1]) / kVScale / dq;
            const double h = n.dot(u - u_pred);
            if (G.cwiseAbs().maxCoeff() < res_tol_ && std::abs(h) < 1e-9) {
                out.u = u;
                out.r = std::move(r);
                out.J = J;
                out.iterations = it;
                return true;
            }
            if (it == kMaxCorrector) break;
            Mat3 A;
            A.topRows<2>() = J;
            A.row(2) = n.transpose();
            const Vec3 rhs(G[0], G[1], h);
            const Vec3 du = A.fullPivLu().solve(-rhs);
            if (!du.allFinite() || du.norm() > 1.0) return false;   // left the neighbourhood of the branch
            u += du;
        }
        return false;
    }

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
    // The largest change of a multiplier between two points (matched the closer way round).
    static double multiplier_change(const Mat2& A, const Mat2& B) {
        const Floquet a = floquet(A), b = floquet(B);
        const double same = std::max(std::abs(a.mu[0] - b.mu[0]), std::abs(a.mu[1] - b.mu[1]));
        const double swapped = std::max(std::abs(a.mu[0] - b.mu[1]), std::abs(a.mu[1] - b.mu[0]));
        return std::min(same, swapped);
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
    void follow(const Job& job, Branch& br);
    // From a rigid grazing onto the impacting branch, written from impact to impact (impact_shot) while the
    // impacts are slow, then on with the stroboscopic map (follow, mode 2).
    void follow_impacting(const Job& job, Branch& br);
    // The exponents of a crossed grazing (BifPoint::mu_exponent, speed_exponent) from the impacting orbits
    // near it; z, t: the grazing orbit from impact to impact and the impacting branch's tangent there.
    void measure_scaling(BifPoint& gp, const Vec3& z, const Vec3& t, int k);
    // The grazing orbit at (q_g, y_g) from impact to impact (z) and the impacting branch's tangent there (t).
    bool grazing_start(double q_g, const Vec2& y_g, int k, Vec3& z, Vec3& t, Vec2& section);
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

void Continuer::locate(BifKind kind, const Sol& a, const Vec3& t, double ds, const Sol& b, int k, int branch,
                       bool off_bumper) {
    double s_lo = 0, s_hi = ds, f_lo = test(kind, a), f_hi = test(kind, b);
    Sol lo = a, hi = b;
    // A rigid grazing is located on the orbit without the bumper, whose largest x is smooth in the parameter
    // and equals xI exactly at the grazing (on the impacting side the map's derivative grows without bound
    // and the corrector may fail inside the bracket). The same holds for a compliant bumper: its force is
    // zero up to the touch.
    const ImpactModel* rigid_law = nullptr;
    if (kind == BifKind::Grazing && (work_.rigid() || off_bumper)) {
        rigid_law = work_.impact;
        work_.impact = find_impact("none");
        // Walk along the step (and a little past it) on the bumperless orbit until its largest x passes xI.
        Sol la, lb;
        bool bracketed = false;
        if (correct(a.u, t, k, la)) {
            double s_prev = 0;
            for (double sg = ds / 16; sg <= 2 * ds && !bracketed; sg *= 2) {
                if (!correct(a.u + sg * t, t, k, lb)) break;
                if (((la.r.max_x - work_.xI) > 0) != ((lb.r.max_x - work_.xI) > 0)) {
                    bracketed = true;
                    s_lo = s_prev;
                    s_hi = sg;
                } else {
                    la = lb;
                    s_prev = sg;
                }
            }
        }
        if (bracketed) {
            lo = la;
            hi = lb;
            f_lo = test(kind, lo);
            f_hi = test(kind, hi);
        } else {
            work_.impact = rigid_law;
            rigid_law = nullptr;
        }
    }
    if ((f_lo > 0) == (f_hi > 0)) return;   // nothing bracketed (a rigid grazing the corrector cannot reach)
    for (int it = 0; it < 80 && std::abs(q_of(hi.u) - q_of(lo.u)) > spec_.locate_tol; ++it) {
        // Illinois step on the arclength, kept inside the bracket.
        double s = (f_hi == f_lo) ? 0.5 * (s_lo + s_hi) : s_hi - f_hi * (s_hi - s_lo) / (f_hi - f_lo);
        const double w = s_hi - s_lo;
        s = std::clamp(s, s_lo + 0.02 * w, s_hi - 0.02 * w);
        Sol m;
        if (!correct(a.u + s * t, t, k, m)) break;
        const double fm = test(kind, m);
        if ((fm > 0) == (f_hi > 0)) {
            s_hi = s;
            hi = m;
            f_hi = fm;
            f_lo *= 0.5;
        } else {
            s_lo = s;
            lo = m;
            f_lo = fm;
            f_hi *= 0.5;
        }
    }
    if (rigid_law) work_.impact = rigid_law;
    const Sol& best = std::abs(f_lo) < std::abs(f_hi) ? lo : hi;
    double precision = std::abs(q_of(hi.u) - q_of(lo.u)), shift = 0;
    if (kind != BifKind::Grazing) {
        // A fold, a doubling or a Neimark-Sacker is a multiplier crossing +1, -1 or the unit circle: it
        // must be of that sort on both sides of the bracket, near the value it crosses, and change at a
        // finite rate along the arclength. A sign change of the test function without that is a jump (a
        // grazing's: the impacting orbit's multiplier runs from +1 to -22 within 1e-5 rad/s of it), not a
        // bifurcation of that kind.
        const double c = kind == BifKind::Fold ? 1.0 : -1.0;
        const double target = kind == BifKind::NeimarkSacker ? 1.0 : c;
        const double m_lo = crossing_multiplier(kind, lo.r.M), m_hi = crossing_multiplier(kind, hi.r.M);
        if (!std::isfinite(m_lo) || !std::isfinite(m_hi)) return;
        if (std::abs(m_lo - target) > kNearCrossing || std::abs(m_hi - target) > kNearCrossing) return;
        const double ds_bracket = std::max((hi.u - lo.u).norm(), 1e-300);
        if (std::abs(m_hi - m_lo) / ds_bracket > kSteepCrossing) return;
        // Inside a compliant bumper's grazing layer the crossing is the grazing's, however smooth it looks
        // there (A3C's period 2 at 12.8999, 1e-4 past its grazing: mu = -1.005 with 0.22 um of penetration).
        if (work_.has_bumper() && !work_.rigid() && best.r.max_x > work_.xI && best.r.max_x - work_.xI < kGrazingLayer) return;
        // The bracket is only as good as the monodromy: at rtol 1e-10 the multiplier of A1C near its first
        // doubling jitters by 5e-5 from one omega to the next (the step sequence changes), so a bracket of
        // 1e-7 may sit 6e-5 from the crossing. The orbit is found again at rtol / 100, where the multiplier is
        // smooth, the crossing moved there by a secant, and its error bounded by how far the multiplier
        // still moves from rtol / 10. A fold needs no move: its parameter is stationary in the multiplier.
        if (kind != BifKind::Fold) {
            const double q0 = q_of(best.u), dq = 1e-3 * q_scale_ * (q_of(hi.u) > q_of(lo.u) ? 1 : -1);
            const double m0 = crossing_at(kind, q0, y_of(best.u), k, 0.01);
            const double m1 = crossing_at(kind, q0 + dq, y_of(best.u), k, 0.01);
            const double m_mid = crossing_at(kind, q0, y_of(best.u), k, 0.1);
            if (std::isfinite(m0) && std::isfinite(m1) && std::isfinite(m_mid) && m1 != m0) {
                const double slope = (m1 - m0) / dq;   // d mu / d q at rtol / 100
                shift = -(m0 - target) / slope;
                if (std::abs(shift) > 1e-3 * q_scale_) shift = 0;   // not a smooth crossing there: the bracket stands
                else precision = std::max(std::abs(m0 - m_mid) / std::abs(slope), std::abs(shift) * 0.1);
            }
        }
    }
    BifPoint bp{kind, q_of(best.u) + shift, y_of(best.u), k, branch, precision, {}, NAN, NAN};
    // The same point met again (from the other side of a bubble, on another branch through the same orbit at
    // another of its k phases, or by a failed corrector after its sign change): reported once.
    for (std::size_t qi = 0; qi < result_.points.size(); ++qi) {
        const BifPoint& q = result_.points[qi];
        if (q.kind != kind || q.period != k) continue;
        if (std::abs(q.param - bp.param) > std::max(1e-5 * q_scale_, 3 * (q.precision + bp.precision))) continue;
        bool same = scaled_norm(q.y - bp.y) < 1e-3;
        for (const Vec2& sp : best.r.sections) same = same || scaled_norm(q.y - sp) < 1e-3;
        if (same) {
            last_located_ = static_cast<int>(qi);
            return;
        }
    }
    last_located_ = static_cast<int>(result_.points.size());
    result_.points.push_back(bp);
    if (kind != BifKind::PeriodDoubling || 2 * k > spec_.max_period) return;
    // Switch onto the period-2k branch: it leaves the period-k orbit along the eigenvector of mu = -1.
    Eigen::EigenSolver<Mat2> es(best.r.M);
    int i = std::abs(es.eigenvalues()[0] + 1.0) < std::abs(es.eigenvalues()[1] + 1.0) ? 0 : 1;
    Vec2 e = es.eigenvectors().col(i).real();
    e = Vec2(e[0] / kXScale, e[1] / kVScale);
    if (e.norm() == 0) return;
    e.normalize();
    jobs_.push_back({2 * k, branch, best.u, Vec3(e[0], e[1], 0.0), false, 0});
}

void Continuer::follow(const Job& job, Branch& br) {
    const int k = job.period;
    std::vector<BranchPoint> fwd, bwd;
    std::string end_fwd, end_bwd, skipped;
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    bool closed = false;
    for (int dir = 0; dir < (job.both_ways && !closed ? 2 : 1); ++dir) {
        auto& pts = dir == 0 ? fwd : bwd;
        auto& end = dir == 0 ? end_fwd : end_bwd;
        std::vector<double> arc(pts.size(), 0.0);   // arclength of each point from this direction's start
        Vec3 t = dir == 0 ? job.t : Vec3(-job.t);
        Sol cur;
        double ds = spec_.ds;
        if (job.both_ways || job.mode == 2) {   // the start is a converged point of this branch
            if (!correct(job.u, t, k, cur)) {
                end = "the start did not converge";
                continue;
            }
            if (dir == 0) pts.push_back(point_of(cur, k));
            t = tangent_of(cur, t);
        } else {               // a switch: the start is the period-doubling point, step off along t
            cur.u = job.u;
            cur.r = map(job.u, k, true);
            pts.push_back(point_of(cur, k));
        }
        bool first = !job.both_ways && job.mode != 2;
        bool clipped = false;
        while (true) {
            if (cancelled()) {
                end = "cancelled";
                break;
            }
            if (static_cast<int>(fwd.size() + bwd.size()) >= spec_.max_points) {
                end = "point limit";
                break;
            }
            Sol next;
            if (!correct(cur.u + ds * t, t, k, next)) {
                ds *= 0.5;
                if (ds < spec_.ds_min) {
                    // A cart held by dry friction (a real multiplier within 1 % of +1: the creeping mode)
                    // has a nearly singular M - I, and the corrector fails where the damped Newton of
                    // find_orbit still converges: restart a little further on at fixed q, the same branch.
                    if (restart(cur, t, k, ds, skipped)) continue;
                    end = "Newton failed near " + std::string(cont_param_name(spec_.param)) + " = " +
                          std::to_string(q_of(cur.u));
                    // An orbit about to graze: the impacting side is out of the corrector's reach (a rigid
                    // bumper, or a compliant one as stiff as C1's), the grazing itself is still located on
                    // the bumperless orbit.
                    const double g = test(BifKind::Grazing, cur);
                    if (work_.has_bumper() && g < 0 && g > -0.1) {
                        last_located_ = -1;
                        locate(BifKind::Grazing, cur, t, 0.05, cur, k, br.id, true);
                        if (last_located_ >= 0) {
                            end = work_.rigid() ? "grazing (rigid impacts begin)" : "grazing (the corrector cannot step into the contacts)";
                            // A free orbit touching a rigid bumper: its impacting continuation starts there,
                            // when the law makes the map continuous at the grazing. H's zero-speed impact still
                            // holds the cart for T_imp(0) = 6.2 ms, so its map jumps there: no branch through.
                            const bool continuous_law = work_.rigid() && work_.impact->duration(work_.ip.data(), 0.0) == 0.0;
                            if (work_.rigid() && !continuous_law)
                                end = "grazing (rigid impacts begin; a zero-speed impact still sticks for T_imp(0) > 0, "
                                      "so the map jumps there)";
                            if (continuous_law && cur.r.impacts == 0) {
                                const BifPoint& g0 = result_.points[static_cast<std::size_t>(last_located_)];
                                jobs_.push_back({k, br.id, u_of(g0.y, g0.param), Vec3(0, 0, t[2] >= 0 ? 1.0 : -1.0), false, 1});
                            }
                        }
                    }
                    break;
                }
                continue;
            }
            // A period-2k branch that shrinks back onto its period-k orbit has reached the other period
            // doubling of a bubble: stop there (the period-k branch holds the rest).
            if (k > 1 && job.parent >= 0) {
                const double gap = half_gap(next, k);
                if (gap < 1e-5) {
                    // A collapse from far in one step is a corrector that jumped onto the period-k orbit
                    // (which P^2k also fixes): retry shorter. A gradual one is the bubble's other end.
                    if (!first && half_gap(cur, k) > 100 * std::max(gap, 1e-4) && ds > 10 * spec_.ds_min) {
                        ds *= 0.25;
                        continue;
                    }
                    end = "rejoined the period-" + std::to_string(k / 2) + " branch";
                    break;
                }
            }
            // Approaching a grazing (the test function falls towards 0): shorten the step so that the
            // corrector, whose map loses smoothness there, is not thrown across it.
            if (work_.has_bumper() && !first) {
                const double g0 = test(BifKind::Grazing, cur), g1 = test(BifKind::Grazing, next);
                if (g1 < 0 && g1 > g0 && ds > std::max(4 * std::abs(g1), 20 * spec_.ds_min)) {
                    ds = std::max(2 * std::abs(g1), 10 * spec_.ds_min);
                    continue;
                }
            }
            // A corrector that wandered far from the predictor, or multipliers that moved a lot in one step:
            // the step may have left the branch's segment (the stable period 2 of A1C at 12.78 once landed
            // on the impacting orbit at 12.96, past the fold, with a multiplier of -13). Shorter, down to
            // a crawl: a true jump (a grazing) is then crossed in steps that bracket it.
            if (!first && ds > 16 * spec_.ds_min &&
                ((next.u - (cur.u + ds * t)).norm() > 0.5 * ds || multiplier_change(cur.r.M, next.r.M) > kMaxMultiplierStep)) {
                ds *= 0.5;
                continue;
            }
            // A step past the end of the range: once, shorten it to end there, so that the branch reaches
            // the range's end rather than stopping up to ds_max short of it.
            if (const double qn = q_of(next.u); (qn < lo || qn > hi) && !clipped) {
                clipped = true;
                const double frac = ((qn > hi ? hi : lo) - q_of(cur.u)) / (qn - q_of(cur.u));
                if (frac > 0 && frac < 1 && frac * ds > spec_.ds_min) {
                    ds *= 0.999 * frac;
                    continue;
                }
            }
            // Slow rigid impacts (near a grazing): the stroboscopic map's derivative grows as 1/v-, and its
            // corrector crawls or jumps across; on from impact to impact, where the grazing can be reached.
            if (work_.rigid() && !first && next.r.impacts == 1 && cur.r.impacts == 1 && handoffs_ < 16 &&
                next.r.min_impact_speed < 0.8 * kHandover) {
                pts.push_back(point_of(next, k));
                Branch rest;
                rest.id = br.id;
                Job on{k, job.parent, next.u, t, false, 3};
                ++handoffs_;
                follow_impacting(on, rest);
                pts.insert(pts.end(), rest.points.begin(), rest.points.end());
                end = rest.end;
                break;
            }
            const Vec3 t_next = tangent_of(next, t);
            if (!first) {
                for (BifKind kind : {BifKind::Fold, BifKind::PeriodDoubling, BifKind::NeimarkSacker, BifKind::Grazing}) {
                    const double fa = test(kind, cur), fb = test(kind, next);
                    if (!((fa > 0) != (fb > 0)) || !std::isfinite(fa) || !std::isfinite(fb)) continue;
                    if (kind == BifKind::NeimarkSacker && !(complex_pair(cur.r.M) && complex_pair(next.r.M))) continue;
                    last_located_ = -1;
                    locate(kind, cur, t, ds, next, k, br.id);
                    // A rigid grazing the corrector itself stepped across (a continuous law): its scenario and
                    // exponents, from the grazing orbit.
                    if (kind == BifKind::Grazing && last_located_ >= 0 && work_.rigid() &&
                        work_.impact->duration(work_.ip.data(), 0.0) == 0.0 && (cur.r.impacts == 0) != (next.r.impacts == 0)) {
                        BifPoint& gp = result_.points[static_cast<std::size_t>(last_located_)];
                        Vec3 zg, tg;
                        Vec2 sec;
                        if (gp.scenario.empty() && grazing_start(gp.param, gp.y, k, zg, tg, sec))
                            describe_grazing(gp, cur.r.impacts == 0 ? t[2] : -t[2], zg, tg, k);
                    }
                }
            }
            first = false;
            const double q = q_of(next.u);
            if (q < lo || q > hi) {
                end = std::string(cont_param_name(spec_.param)) + " range";
                break;
            }
            pts.push_back(point_of(next, k));
            arc.push_back((arc.empty() ? 0.0 : arc.back()) + (next.u - cur.u).norm());
            // Back at an earlier orbit of the branch (or at one of its k phases, the same orbit): a closed
            // branch, an isola. Without this it would be followed round again up to the point limit.
            if (pts.size() > 8) {
                const Vec3 a = cur.u, b = next.u;
                const double len2 = (b - a).squaredNorm();
                auto near = [&](const BranchPoint& pj) {
                    for (const Vec2& sp : pj.sections) {
                        const Vec3 c = u_of(sp, pj.param);
                        const double f = len2 > 0 ? std::clamp((c - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
                        if ((a + f * (b - a) - c).norm() < 1e-3) return true;
                    }
                    return false;
                };
                // Only orbits at least 0.5 (scaled arclength) behind: a branch's own last steps are always near.
                for (std::size_t j = 0; j + 8 < pts.size() && !closed; ++j)
                    if (arc.back() - arc[j] > 0.5) closed = near(pts[j]);
                if (!closed && dir == 1 && !fwd.empty() && arc.back() > 0.5) closed = near(fwd.front());
                if (closed) {
                    end = "closed loop (back at an earlier orbit)";
                    break;
                }
            }
            cur = std::move(next);
            t = t_next;
            if (progress_ && dir == 0) {
                const double f = (q - lo) / (hi - lo);
                const double now = std::clamp(branch_fraction_ + f / std::max<double>(1, 1 + jobs_.size()), 0.0, 1.0);
                if (now > progress_->fraction.load(std::memory_order_relaxed))   // never backwards
                    progress_->fraction.store(now, std::memory_order_relaxed);
            }
            // Step control: grow after an easy correction, shrink after a hard one.
            ds = cur.iterations <= 2 ? std::min(ds * 1.5, spec_.ds_max) : cur.iterations >= 5 ? ds * 0.6 : ds;
        }
    }
    br.points.assign(bwd.rbegin(), bwd.rend());
    br.points.insert(br.points.end(), fwd.begin(), fwd.end());
    br.end = job.both_ways && !bwd.empty() ? end_bwd + " / " + end_fwd : job.both_ways && !closed ? end_bwd + " / " + end_fwd : end_fwd;
    if (!skipped.empty()) br.end += " (restarted across " + skipped + ": near-neutral orbit, corrector failed)";
}

bool Continuer::shot(const Vec3& z, int k, Vec2& G, Eigen::Matrix<double, 2, 3>& J, Vec2& section) {
    const double q = q_of(z);
    if (spec_.param == ContParam::Omega && !(q > 0)) return false;
    try {
        const double omega = apply(q);
        ++evaluations_;
        const ImpactShot a = impact_shot(work_, omega, z[0], z[1] * kVScale, k, true, spec_.sim);
        const double dq = 1e-6;
        const double omega_q = apply(q + dq * q_scale_);
        ++evaluations_;
        const ImpactShot b = impact_shot(work_, omega_q, z[0], z[1] * kVScale, k, false, spec_.sim);
        apply(q);
        G = a.residual;
        J.leftCols<2>() = a.J;
        J.col(2) = (b.residual - a.residual) / dq;
        section = a.section;
        return G.allFinite() && J.allFinite();
    } catch (const std::exception&) {
        apply(q);
        return false;
    }
}

bool Continuer::correct_impacting(const Vec3& z_pred, const Vec3& n, int k, Vec3& z, Eigen::Matrix<double, 2, 3>& J,
                                  Vec2& section) {
    z = z_pred;
    for (int it = 0; it <= kMaxCorrector; ++it) {
        Vec2 G;
        if (!shot(z, k, G, J, section)) return false;
        const double h = n.dot(z - z_pred);
        if (G.cwiseAbs().maxCoeff() < res_tol_ && std::abs(h) < 1e-9) return true;
        if (it == kMaxCorrector) break;
        Mat3 A;
        A.topRows<2>() = J;
        A.row(2) = n.transpose();
        const Vec3 dz = A.fullPivLu().solve(-Vec3(G[0], G[1], h));
        if (!dz.allFinite() || dz.norm() > 1.0) return false;
        z += dz;
    }
    return false;
}

void Continuer::follow_impacting(const Job& job, Branch& br) {
    const int k = job.period;
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    Vec3 z, t;
    Eigen::Matrix<double, 2, 3> J;
    Vec2 section;
    if (job.mode == 1) {
        if (!grazing_start(q_of(job.u), y_of(job.u), k, z, t, section)) {
            br.end = "the grazing orbit did not converge from impact to impact";
            return;
        }
        for (BifPoint& b : result_.points)
            if (b.kind == BifKind::Grazing && b.param == q_of(job.u) && b.scenario.empty()) describe_grazing(b, job.t[2], z, t, k);
        // Its impacting branch already followed to here from another grazing: not again.
        for (double qr : reached_)
            if (std::abs(qr - q_of(job.u)) < 1e-5 * q_scale_) {
                br.end = "reached";
                return;
            }
    } else {
        // From an impacting orbit of the stroboscopic branch whose impacts are slow (mode 3).
        double theta = 0, vm = 0;
        if (!first_impact(work_, apply(q_of(job.u)), y_of(job.u), k, spec_.sim, theta, vm) ||
            !correct_impacting(Vec3(theta, vm / kVScale, job.u[2]), Vec3(0, 0, 1), k, z, J, section)) {
            br.end = "the impacting orbit did not converge from impact to impact";
            return;
        }
        t = Vec3(J.row(0).transpose()).cross(Vec3(J.row(1).transpose()));
        if (!(t.norm() > 0) || !t.allFinite()) {
            br.end = "singular impact-to-impact equations";
            return;
        }
        t.normalize();
        if (t[2] * job.t[2] < 0) t = -t;   // the way the stroboscopic branch was going in the parameter
    }
    double ds = 0.01;
    std::string end;
    bool handed = false, have_prev = false;
    Sol prev;
    while (true) {
        if (cancelled()) { end = "cancelled"; break; }
        if (static_cast<int>(br.points.size()) >= spec_.max_points) { end = "point limit"; break; }
        Vec3 zn;
        Vec2 sec;
        Eigen::Matrix<double, 2, 3> Jn;
        if (!correct_impacting(z + ds * t, t, k, zn, Jn, sec)) {
            ds *= 0.5;
            if (ds < spec_.ds_min) {
                end = "Newton failed (impact to impact) near " + std::string(cont_param_name(spec_.param)) + " = " +
                      std::to_string(q_of(z));
                break;
            }
            continue;
        }
        if (zn[1] <= 0 && z[1] > 0) {
            // The impacts end: v- passes zero between z and zn, a grazing, located by a secant on v- along
            // the step (the equations are smooth there).
            double sa = 0, sb = ds, va = z[1], vb = zn[1];
            Vec3 zm = zn;
            Vec2 secm = sec;
            for (int it = 0; it < 60 && std::abs(vb - va) > 0; ++it) {
                const double sm = sb - vb * (sb - sa) / (vb - va);
                Eigen::Matrix<double, 2, 3> Jm;
                if (!correct_impacting(z + sm * t, t, k, zm, Jm, secm)) break;
                sa = sb; va = vb; sb = sm; vb = zm[1];
                if (std::abs(vb) * kVScale < 1e-12) break;
            }
            BifPoint bp{BifKind::Grazing, q_of(zm), secm, k, br.id, std::abs(sb - sa) * q_scale_, {}, NAN, NAN};
            bp.precision = std::max(bp.precision, 1e-9 * q_scale_);
            bool known = false;
            for (const BifPoint& q : result_.points)
                if (q.kind == BifKind::Grazing && std::abs(q.param - bp.param) < 1e-5 * q_scale_) known = true;
            if (!known) result_.points.push_back(bp);
            reached_.push_back(bp.param);
            end = "grazing at " + std::string(cont_param_name(spec_.param)) + " = " + std::to_string(bp.param) +
                  " (the impacts end)";
            break;
        }
        const double q = q_of(zn);
        if (q < lo || q > hi) { end = std::string(cont_param_name(spec_.param)) + " range"; break; }
        // The same orbit on the real map: one impact per k periods and a fixed point of P^k. Otherwise the
        // flight crosses xI in between (a second impact) and the orbit is not the rig's.
        Sol sp;
        sp.u = u_of(sec, q);
        sp.r = map(sp.u, k, true);
        if (sp.r.impacts != 1 || scaled_norm(sp.r.y - sec) > 1e-5) {
            end = "the impacting orbit is no longer admissible near " + std::string(cont_param_name(spec_.param)) +
                  " = " + std::to_string(q) + " (its flight crosses xI)";
            break;
        }
        Vec3 tn = Vec3(Jn.row(0).transpose()).cross(Vec3(Jn.row(1).transpose()));
        if (tn.norm() > 0 && tn.allFinite()) {
            tn.normalize();
            if (tn.dot(t) < 0) tn = -tn;
        } else {
            tn = t;
        }
        if (have_prev)
            for (BifKind kind : {BifKind::Fold, BifKind::PeriodDoubling, BifKind::NeimarkSacker}) {
                const double fa = test(kind, prev), fb = test(kind, sp);
                if (!std::isfinite(fa) || !std::isfinite(fb) || (fa > 0) == (fb > 0)) continue;
                if (kind == BifKind::NeimarkSacker && !(complex_pair(prev.r.M) && complex_pair(sp.r.M))) continue;
                locate_impacting(kind, z, t, ds, prev, sp, k, br.id);
            }
        prev = sp;
        have_prev = true;
        z = zn;
        t = tn;
        section = sec;
        br.points.push_back(point_of(sp, k));
        ds = std::min(ds * 1.5, 0.1);
        // Fast enough for the stroboscopic map (and growing): on with it.
        if (zn[1] * kVScale > kHandover && t[1] > 0) {
            handed = true;
            break;
        }
    }
    if (!handed) {
        br.end = (job.mode == 1 ? "grazing / " : "slow impacts / ") + end;
        return;
    }
    Branch onward;
    onward.id = br.id;
    follow({k, job.parent, u_of(section, q_of(z)), Vec3(0, 0, t[2] >= 0 ? 1.0 : -1.0), false, 2}, onward);
    br.points.insert(br.points.end(), onward.points.begin(), onward.points.end());
    br.end = (job.mode == 1 ? "grazing / " : "slow impacts / ") + onward.end;
}

void Continuer::locate_impacting(BifKind kind, const Vec3& z, const Vec3& t, double ds, const Sol& a, const Sol& b,
                                 int k, int branch) {
    double s_lo = 0, s_hi = ds, f_lo = test(kind, a), f_hi = test(kind, b);
    Sol lo = a, hi = b;
    for (int it = 0; it < 80 && std::abs(q_of(hi.u) - q_of(lo.u)) > spec_.locate_tol; ++it) {
        const double sm = 0.5 * (s_lo + s_hi);
        Vec3 zm;
        Eigen::Matrix<double, 2, 3> Jm;
        Vec2 sec;
        if (!correct_impacting(z + sm * t, t, k, zm, Jm, sec)) break;
        Sol m;
        m.u = u_of(sec, q_of(zm));
        m.r = map(m.u, k, true);
        const double fm = test(kind, m);
        if ((fm > 0) == (f_hi > 0)) { s_hi = sm; hi = m; f_hi = fm; }
        else { s_lo = sm; lo = m; f_lo = fm; }
    }
    // A crossing of the multiplier it names, near +1, -1 or the unit circle on both sides (see locate()).
    const double target = 1.0 * (kind == BifKind::PeriodDoubling ? -1.0 : 1.0);
    const double m_lo = crossing_multiplier(kind, lo.r.M), m_hi = crossing_multiplier(kind, hi.r.M);
    if (!std::isfinite(m_lo) || !std::isfinite(m_hi)) return;
    if (std::abs(m_lo - target) > kNearCrossing || std::abs(m_hi - target) > kNearCrossing) return;
    const Sol& best = std::abs(f_lo) < std::abs(f_hi) ? lo : hi;
    BifPoint bp{kind, q_of(best.u), y_of(best.u), k, branch, std::abs(q_of(hi.u) - q_of(lo.u)), {}, NAN, NAN};
    for (const BifPoint& q : result_.points)
        if (q.kind == kind && q.period == k && std::abs(q.param - bp.param) < std::max(1e-5 * q_scale_, 3 * (q.precision + bp.precision)))
            return;
    result_.points.push_back(bp);
}

bool Continuer::grazing_start(double q_g, const Vec2& y_g, int k, Vec3& z, Vec3& t, Vec2& section) {
    // The grazing orbit written from impact to impact touches xI at the peak of the bumperless orbit, v- = 0.
    Eigen::Matrix<double, 2, 3> J;
    const double theta_g = peak_phase(work_, apply(q_g), y_g, k, spec_.sim);
    if (!correct_impacting(Vec3(theta_g, 0.0, q_g / q_scale_), Vec3(0, 0, 1), k, z, J, section)) return false;
    t = Vec3(J.row(0).transpose()).cross(Vec3(J.row(1).transpose()));
    if (!(t.norm() > 0) || !t.allFinite()) return false;
    t.normalize();
    if (t[1] < 0) t = -t;   // onto the impacting side: v- grows
    return true;
}

void Continuer::describe_grazing(BifPoint& gp, double free_dir, const Vec3& z, const Vec3& t, int k) {
    // The free orbits' side: where the bumperless orbit stays below xI, 1e-4 (scaled) either side of the
    // grazing. The way the branch was going (free_dir) is the fallback: it is not reliable, since a corrector
    // that steps across a nonsmooth fold turns back in the parameter there.
    double free_side = free_dir >= 0 ? -1.0 : 1.0;
    const ImpactModel* law = work_.impact;
    work_.impact = find_impact("none");
    int below = 0;
    double side_below = 0;
    for (double sgn : {-1.0, 1.0}) {
        const double q = gp.param + sgn * 1e-4 * q_scale_;
        OrbitOptions oo;
        oo.period = k;
        oo.sim = spec_.sim;
        const double omega = apply(q);
        const Orbit o = find_orbit(work_, omega, gp.y, oo);
        double x_max = 0;
        if (!o.converged) continue;
        peak_phase(work_, omega, o.y, k, spec_.sim, &x_max);
        if (x_max < work_.xI) {
            ++below;
            side_below = sgn;
        }
    }
    work_.impact = law;
    apply(gp.param);
    if (below == 1) free_side = side_below;
    gp.scenario = (t[2] >= 0) == (free_side >= 0) ? "nonsmooth fold" : "persistence";
    measure_scaling(gp, z, t, k);
}

void Continuer::measure_scaling(BifPoint& gp, const Vec3& z, const Vec3& t, int k) {
    const double side = t[2] >= 0 ? 1.0 : -1.0;
    // The scaling: orbits at fixed q whose impacts are 1e-4, 3e-4 and 1e-3 m/s fast (d from the tangent).
    // Slower impacts are below what the Simulator resolves on the real map (an impact of 1e-7 m/s comes
    // out at 3e-6: the event is located to about 1e-12 m); faster ones are no longer near the grazing.
    if (std::abs(t[2]) > 1e-9 && t[1] > 0) {
        double sx = 0, sy_mu = 0, sy_v = 0, sxx = 0, sxm = 0, sxv = 0;
        int n = 0;
        const double dv_dd = t[1] * kVScale / std::abs(t[2]);   // [m/s] per scaled q
        for (double v_target : {1e-4, 3e-4, 1e-3}) {
            const double d = v_target / dv_dd;
            if (!(d < 0.5)) continue;
            Vec3 zd;
            Eigen::Matrix<double, 2, 3> Jd;
            Vec2 sec;
            const Vec3 pred = z + (side * d / t[2]) * t;
            if (!correct_impacting(pred, Vec3(0, 0, 1), k, zd, Jd, sec) || !(zd[1] > 0)) continue;
            const MapResult m = map(u_of(sec, q_of(zd)), k, true);
            if (m.impacts != 1) continue;   // the orbit is not admissible there
            const double mu = std::abs(floquet(m.M).mu[0]);
            const double lx = std::log(d), lm = std::log(mu), lv = std::log(zd[1] * kVScale);
            sx += lx; sxx += lx * lx; sy_mu += lm; sy_v += lv; sxm += lx * lm; sxv += lx * lv;
            ++n;
        }
        if (n == 3) {
            const double den = n * sxx - sx * sx;
            gp.mu_exponent = (n * sxm - sx * sy_mu) / den;
            gp.speed_exponent = (n * sxv - sx * sy_v) / den;
        }
    }
}

ContinuationResult Continuer::run() {
    const auto t0 = std::chrono::steady_clock::now();
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    const double q0 = std::isnan(spec_.start) ? lo : spec_.start;
    // The first orbit: settle from the guess (or the left well's bottom) and polish by Newton.
    const double omega0 = apply(q0);
    Vec2 guess = spec_.guess;
    if (!guess.allFinite()) guess = settle(work_, omega0, Vec2(left_well(work_), 0.0), 200, spec_.sim);
    OrbitOptions oo;
    oo.period = spec_.period;
    oo.sim = spec_.sim;
    const Orbit o = find_orbit(work_, omega0, guess, oo);
    if (!o.converged) {
        result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        Branch b;
        b.end = "no periodic orbit of period " + std::to_string(spec_.period) + " found at the start: " + o.message;
        result_.branches.push_back(b);
        return std::move(result_);
    }
    jobs_.push_back({spec_.period, -1, u_of(o.y, q0), Vec3(0, 0, 1), q0 > lo && q0 < hi, 0});
    if (!(q0 > lo && q0 < hi) && q0 >= hi) jobs_.back().t = Vec3(0, 0, -1);
    while (!jobs_.empty() && static_cast<int>(result_.branches.size()) < spec_.max_branches) {
        const Job job = jobs_.front();
        jobs_.pop_front();
        if (cancelled()) {
            result_.cancelled = true;
            break;
        }
        // A period doubling that an earlier period-2k branch already reached (the far end of a bubble).
        // Any of a period-k orbit's k section points may be where the switch lands (the same orbit, another
        // phase): each is compared.
        bool known = false;
        for (const auto& b : result_.branches)
            if (job.mode == 0 && b.period == job.period)
                for (const auto& pt : b.points)
                    if (std::abs(pt.param / q_scale_ - job.u[2]) < 0.3)
                        for (const Vec2& sp : pt.sections)
                            if (scaled_norm(sp - y_of(job.u)) < 0.3) known = true;
        if (known) continue;
        Branch br;
        br.id = static_cast<int>(result_.branches.size());
        br.period = job.period;
        br.parent = job.parent;
        if (job.mode == 1) follow_impacting(job, br);
        else follow(job, br);
        if (job.mode == 1 && br.points.empty() && br.end == "reached") continue;
        result_.branches.push_back(std::move(br));
        branch_fraction_ += (1.0 - branch_fraction_) / static_cast<double>(1 + jobs_.size());
    }
    if (cancelled()) result_.cancelled = true;
    std::sort(result_.points.begin(), result_.points.end(),
              [](const BifPoint& a, const BifPoint& b) { return a.param < b.param; });
    result_.map_evaluations = evaluations_;
    result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress_) progress_->fraction.store(1.0, std::memory_order_relaxed);
    return std::move(result_);
}

}  // namespace

ContinuationResult continue_orbits(const Params& p, const ContinuationSpec& spec, Progress* progress) {
    Continuer c(p, spec, progress);
    return c.run();
}

}  // namespace impactlab::analysis



