#include "analysis/tangent.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/LU>

#include "parallel.hpp"

#include "impactlab/equilibria.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/rig.hpp"

namespace impactlab::analysis::detail {

namespace {

constexpr int kMaxDepth = 30;
// No substep refined below this [s] away from the zeros of v: where the cart creeps (|v| ~ eps, the friction
// relaxing at ~1e5 1/s) the propagator's fast part has decayed within the substep and what is left of the
// error cannot be seen in a period's multipliers; without a floor a creeping second would cost 1e6 substeps.
constexpr double kMinSubstep = 2e-6;
// Graded mesh around a zero of v: the smoothed friction's slope T eps^2 / (v^2 + eps^2)^1.5 is a spike
// about eps/|a| ~ 1e-6 s wide that an adaptive rule sampling at Gauss points could step over unseen; the
// mesh puts substeps of 1e-10 s at the zero and grows them by 4 outwards.
constexpr double kSpikeInner = 1e-10;   // [s]
constexpr double kSpikeGrowth = 4.0;
// A compliant-contact step shorter than this [s] is part of an impact (A1C1's are ~1 us).
constexpr double kShortContactStep = 1e-5;
// Magnus order 6 where h |A| (as a rate, below) is at most this, order 4 beyond: the Magnus series converges
// for h |A| < pi, and order 6's nested commutators are accurate well inside that.
constexpr double kMagnus6Rate = 0.5;

// exp(M) of a 2x2 matrix in closed form: M = s I + N with tr N = 0, N^2 = q2 I.
Mat2 expm2(const Mat2& M) {
    const double s = 0.5 * (M(0, 0) + M(1, 1));
    Mat2 N = M;
    N(0, 0) -= s;
    N(1, 1) -= s;
    const double q2 = N(0, 0) * N(0, 0) + N(0, 1) * N(1, 0);
    double c, sq;   // e^s cosh(q) and e^s sinh(q)/q (or cos, sin for q2 < 0)
    if (std::abs(q2) < 1e-8) {
        const double es = std::exp(s);
        c = es * (1.0 + q2 / 2.0 + q2 * q2 / 24.0);
        sq = es * (1.0 + q2 / 6.0 + q2 * q2 / 120.0);
    } else if (q2 > 0) {
        // Written as exponentials of s +/- q: a stiff friction gives s ~ -q, large, and cosh(q) alone overflows.
        const double q = std::sqrt(q2);
        const double ep = std::exp(s + q), em = std::exp(s - q);
        c = 0.5 * (ep + em);
        sq = 0.5 * (ep - em) / q;
    } else {
        const double q = std::sqrt(-q2), es = std::exp(s);
        c = es * std::cos(q);
        sq = es * std::sin(q) / q;
    }
    return c * Mat2::Identity() + sq * N;
}

double scaled_max(const Mat2& E) {
    // D E D^-1 with D = diag(1/xs, 1/vs): the propagator in the scaled variables.
    constexpr double xs = 1e-2, vs = 1e-1;
    return std::max({std::abs(E(0, 0)), std::abs(E(0, 1)) * vs / xs, std::abs(E(1, 0)) * xs / vs, std::abs(E(1, 1))});
}

}  // namespace

double acceleration(const Params& p, const Drive& d, double t, double x, double v) {
    return rig_rhs(p, d, t, {x, v}, p.compliant())[1];
}

// The law hands the integrator a bounded secant slope in h' (MODEL.md); the tangent needs the true one.
Mat2 jacobian(const Params& p, const Drive& d, double t, double x, double v) {
    Mat2 A;
    rig_jacobian(p, d, t, {x, v}, p.compliant(), ContactSlope::Exact, A);
    return A;
}

Mat2 magnus4_step(const Mat2& A1, const Mat2& A2, double h) {
    return expm2(0.5 * h * (A1 + A2) + (std::sqrt(3.0) / 12.0) * h * h * (A2 * A1 - A1 * A2));
}

Mat2 magnus6_step(const Mat2& A1, const Mat2& A2, const Mat2& A3, double h) {
    auto comm = [](const Mat2& x, const Mat2& y) -> Mat2 { return x * y - y * x; };
    const Mat2 a1 = h * A2, a2 = (std::sqrt(15.0) / 3.0) * h * (A3 - A1), a3 = (10.0 / 3.0) * h * (A3 - 2.0 * A2 + A1);
    const Mat2 C1 = comm(a1, a2), C2 = (-1.0 / 60.0) * comm(a1, 2.0 * a3 + C1);
    return expm2(a1 + a3 / 12.0 + (1.0 / 240.0) * comm(-20.0 * a1 - a3 + C1, a2 + C2));
}

void TangentTracker::on_piece(const Piece& piece) {
    if (piece.regime != Regime::Free || !piece.step) return;   // held: Phi is carried by the saltation
    const Vec2 y1 = piece.at(piece.t1);
    max_x = std::max(max_x, y1[0]);
    if (const double tm = turning_point(piece); !std::isnan(tm)) max_x = std::max(max_x, piece.at(tm)[0]);
    if (p_.compliant()) {
        const bool inside = piece.at(0.5 * (piece.t0 + piece.t1))[0] > p_.xI;
        if (inside && !inside_) ++impacts;
        inside_ = inside;
    }
    if (!tangent_ || piece.t1 <= piece.t0) return;
    if (defer) {   // kept for finish(): the piece's propagator does not depend on Phi
        tape_.push_back({Op::Piece, Mat2::Zero(), pieces_.size()});
        pieces_.push_back({piece, *piece.step});
        return;
    }
    substeps_.clear();
    propagator(piece, substeps_);
    for (const Mat2& S : substeps_) Phi = S * Phi;
}

void TangentTracker::propagator(const Piece& piece, std::vector<Mat2>& out) const {
    const Vec2 y0 = piece.at(piece.t0), y1 = piece.at(piece.t1);
    // Zeros of v inside the piece: the friction spike (and the Hunt-Crossley damping's infinite slope).
    std::array<double, 8> zeros{};
    int nz = 0;
    constexpr int kScan = 8;
    double ta = piece.t0, va = y0[1];
    for (int k = 1; k <= kScan && nz < 8; ++k) {
        const double tb = piece.t0 + (piece.t1 - piece.t0) * k / kScan;
        const double vb = piece.at(tb)[1];
        if ((va < 0) != (vb < 0) && va != 0) {
            zeros[static_cast<std::size_t>(nz++)] = bisect([&](double t) { return (piece.at(t)[1] < 0) == (va < 0); }, ta, tb, 80);
        }
        ta = tb;
        va = vb;
    }
    double t = piece.t0;
    for (int z = 0; z <= nz; ++z) {
        const double tz = z < nz ? zeros[static_cast<std::size_t>(z)] : piece.t1;
        if (z < nz) {
            // Outward-graded steps from t up to the zero: largest first, then ever smaller.
            double tau = kSpikeInner;
            while (tz - tau * kSpikeGrowth > t) tau *= kSpikeGrowth;
            while (tau >= kSpikeInner && tz - tau > t) {
                propagate(piece, t, tz - tau, out);
                t = tz - tau;
                tau /= kSpikeGrowth;
            }
            const double next = z + 1 < nz ? zeros[static_cast<std::size_t>(z + 1)] : piece.t1;
            const double te = std::min(tz + kSpikeInner, 0.5 * (tz + next));
            propagate_across_zero(piece, t, te, out);
            t = te;
            // And graded outwards after it, up to the next zero or the end.
            tau = kSpikeGrowth * kSpikeInner;
            while (tz + tau < next) {
                propagate(piece, t, tz + tau, out);
                t = tz + tau;
                tau *= kSpikeGrowth;
            }
        } else if (t < tz) {
            propagate(piece, t, tz, out);
            t = tz;
        }
    }
    // A compliant contact piece is propagated on its own and then made consistent with the flow (below).
    if (p_.compliant() && std::max(y0[0], y1[0]) > p_.xI) {
        Mat2 G = Mat2::Identity();
        for (const Mat2& S : out) G = S * G;
        out.assign(1, flow_consistent(piece, y0, y1, G));
    }
}

void TangentTracker::finish() {
    if (tape_.empty()) return;
    // The propagators side by side (each in its own slot: the same numbers on any number of threads), then
    // applied in time order.
    std::vector<std::vector<Mat2>> G(pieces_.size());
    ::impactlab::detail::for_each_index(pieces_.size(), [&](std::size_t i) {
        Piece piece = pieces_[i].piece;
        piece.step = &pieces_[i].step;
        propagator(piece, G[i]);
    });
    for (const Op& op : tape_) {
        if (op.kind == Op::Section) section_Phi->push_back(Phi);
        else if (op.kind == Op::Matrix) Phi = op.M * Phi;
        else
            for (const Mat2& S : G[op.index]) Phi = S * Phi;
    }
    tape_.clear();
    pieces_.clear();
}

Mat2 TangentTracker::flow_consistent(const Piece& piece, const Vec2& y0, const Vec2& y1, const Mat2& P) const {
    // Near the zero of v at the deepest penetration the Hunt-Crossley damping jumps by tens of newtons within
    // |v| < 1e-7 m/s, which a step of the simulator spans and its cubic dense output smooths: the propagator
    // integrated along that interpolant then depends on where the steps fall (A1C at 16 rad/s: multipliers
    // scattered by 3e-4 with the Newton start). The exact flow obeys d/dt f(t, y) = A f + df/dt, so the
    // piece's propagator must carry f(y0) to f(y1) less the forcing's drift; the step ends are accurate to
    // rtol, the interior is not. The smallest (scaled) correction that restores it is applied.
    const double ta = piece.t0, tb = piece.t1, dt = tb - ta;
    auto f = [&](double t, const Vec2& y) { return Vec2(y[1], acceleration(p_, d_, t, y[0], y[1])); };
    const Vec2 fa = f(ta, y0), fb = f(tb, y1);
    constexpr double xs = 1e-2, vs = 1e-1;
    auto scaled_f = [&](const Vec2& v) { return Vec2(v[0] / xs, v[1] / vs); };
    const Vec2 sa = scaled_f(fa), sb = scaled_f(fb);
    // Only where the motion is fast and the piece short against the forcing period: a cart resting or creeping
    // against the bumper has f ~ 0 (nothing to carry), and over a long piece the drift term's trapezoid fails.
    const double omega = std::max(d_.omega(ta), 1e-3);
    if (sa.norm() < 1.0 || sb.norm() < 1.0 || dt > 1e-3 * kTwoPi / omega) return P;
    auto f_t = [&](double t, const Vec2& y) {
        const double e = 1e-9 * std::max(1.0, std::abs(t));
        return Vec2(0.0, (acceleration(p_, d_, t + e, y[0], y[1]) - acceleration(p_, d_, t - e, y[0], y[1])) / (2 * e));
    };
    const Vec2 target = fb - 0.5 * dt * (P * f_t(ta, y0) + f_t(tb, y1));
    Mat2 D = Mat2::Zero();
    D(0, 0) = 1 / xs;
    D(1, 1) = 1 / vs;
    const Mat2 Di = D.inverse();
    const Vec2 r = D * (target - P * fa);
    return Di * (D * P * Di + r * sa.transpose() / sa.squaredNorm()) * D;
}

void TangentTracker::propagate(const Piece& piece, double a, double b, std::vector<Mat2>& P) const {
    // Magnus order 6, step halving until the step and its two halves agree; a half computed for the test is
    // handed to its child as the child's whole step. In free flight order 4 needed ~1000 substeps a period
    // for 1e-11 (its error ~ (h w0)^5), order 6 a third of them.
    struct Frame { double a, b; int depth; Mat2 full; bool known; };
    std::array<Frame, kMaxDepth + 2> stack{};
    int top = 0;
    stack[0] = {a, b, 0, Mat2::Identity(), false};
    auto A_at = [&](double t) {
        const Vec2 y = piece.at(t);
        return jacobian(p_, d_, t, y[0], y[1]);
    };
    // h |A| as a rate, the same in any units of x and v: the damping rate plus the stiffness's frequency.
    auto rate = [](const Mat2& A) { return std::abs(A(1, 1)) + std::sqrt(std::abs(A(1, 0) * A(0, 1))); };
    auto magnus = [&](double ta, double tb) {
        const double h = tb - ta, tm = 0.5 * (ta + tb);
        const Mat2 A1 = A_at(tm - kGauss3 * h), A2 = A_at(tm), A3 = A_at(tm + kGauss3 * h);
        if (h * std::max({rate(A1), rate(A2), rate(A3)}) <= kMagnus6Rate) return magnus6_step(A1, A2, A3, h);
        // Where h A is large (the friction's relaxation, a stiff contact) order 6's nested commutators grow
        // as (h |A|)^3 and its series diverges; order 4's single commutator stays near the mean's exponential.
        return magnus4_step(A_at(tm - kGauss2 * h), A_at(tm + kGauss2 * h), h);
    };
    // The floor on substeps is for creeping; a compliant contact's fast dynamics are otherwise resolved.
    const Vec2 ya = piece.at(a), yb = piece.at(b);
    const bool in_contact = p_.compliant() && std::max(ya[0], yb[0]) > p_.xI;
    // Creeping (|v| below 0.1 mm/s at both ends): the tangent is slaved to the friction's fast relaxation and
    // an exact exponential over 10 ms substeps follows its slow part. Pressed against a compliant bumper
    // (the low-omega levels of a sweep that starts at xI = 0) the contact's fast mode is slaved as well once
    // the acceleration is small too (not the instant of v = 0 at the deepest point of an impact), over 1 ms:
    // resolving it cost 1e6 substeps per simulated second, and 1 ms substeps keep lambda_max of A1C's sweep
    // at 0.5..7.4 rad/s within 2e-6 1/s of it (10 ms moved the creeping levels by up to 0.013 1/s).
    bool creeping = std::max(std::abs(ya[1]), std::abs(yb[1])) < 1e-4;
    if (creeping && in_contact)
        creeping = std::max(std::abs(acceleration(p_, d_, a, ya[0], ya[1])), std::abs(acceleration(p_, d_, b, yb[0], yb[1]))) < 1.0;
    const double floor = creeping ? (in_contact ? 1e-3 : 1e-2) : in_contact ? 0.0 : kMinSubstep;
    // A looser target only within an impact's short steps: in free flight the friction's spikes at the
    // turning points, and in a long contact the many substeps' sum, need 1e-11 even for an exponent (A1C's
    // sweep at 4.9..5.9 rad/s, pressed against the bumper, moved by up to 1.6 1/s at 1e-9 there).
    const double tol = in_contact && piece.t1 - piece.t0 < kShortContactStep ? step_tol : std::min(step_tol, 1e-11);
    // Depth-first, left to right: each accepted interval is applied in time order.
    while (top >= 0) {
        const Frame f = stack[static_cast<std::size_t>(top--)];
        const double m = 0.5 * (f.a + f.b);
        const Mat2 full = f.known ? f.full : magnus(f.a, f.b);
        const Mat2 left = magnus(f.a, m), right = magnus(m, f.b);
        const Mat2 half = right * left;
        if (f.depth >= kMaxDepth || f.b - f.a < floor || m <= f.a || m >= f.b ||
            scaled_max(full - half) <= tol) {
            P.push_back(half);
            continue;
        }
        stack[static_cast<std::size_t>(++top)] = {m, f.b, f.depth + 1, right, true};
        stack[static_cast<std::size_t>(++top)] = {f.a, m, f.depth + 1, left, true};
    }
}

void TangentTracker::propagate_across_zero(const Piece& piece, double a, double b, std::vector<Mat2>& P) const {
    // The innermost interval around a zero of v, where the v-slopes are singular (|h'|^(n3-1) of the
    // Hunt-Crossley damping) or a spike (the smoothed friction). Over so short an interval v is linear in t
    // and x constant, so the integral of dF/dv dt is exactly dt times the secant slope (F(v_b) - F(v_a)) /
    // (v_b - v_a): the integrable singularity enters with its true weight, which no quadrature rule at
    // points inside the interval could give.
    const double tm = 0.5 * (a + b), h = b - a;
    const Vec2 ym = piece.at(tm);
    const double va = piece.at(a)[1], vb = piece.at(b)[1];
    Mat2 A = jacobian(p_, d_, tm, ym[0], ym[1]);
    if (vb != va) {
        auto Fv = [&](double v) {
            double F = resistance(p_, v).F;
            if (p_.compliant() && ym[0] > p_.xI) F += p_.impact->contact(p_.ip.data(), ym[0] - p_.xI, v).F;
            return F;
        };
        // Replace the pointwise friction and contact slopes by their secant; effects keep their own slope.
        double point = resistance(p_, ym[1]).dF;
        if (p_.compliant() && ym[0] > p_.xI) {
            const double depth = ym[0] - p_.xI;
            point += contact_true_slope(p_, p_.impact->contact(p_.ip.data(), depth, ym[1]), depth, ym[1]);
        }
        A(1, 1) += (point - (Fv(vb) - Fv(va)) / (vb - va)) / p_.m;
    }
    P.push_back(expm2(h * A));
}

void TangentTracker::on_section(const SectionPoint& sp) {
    if (sections) sections->emplace_back(sp.x, sp.v);
    if (section_Phi && !tape_.empty()) tape_.push_back({Op::Section, Mat2::Zero(), 0});
    else if (section_Phi) section_Phi->push_back(Phi);
}

void TangentTracker::on_impact(const ImpactEvent& ev) {
    ++impacts;
    min_impact_speed = std::min(min_impact_speed, ev.v_minus);
    t_hit_ = ev.t;
    v_minus_ = ev.v_minus;
    v_plus_ = ev.v_plus;
    if (tangent_ && ev.duration == 0.0) apply_impact_saltation(ev.t, ev.v_minus, ev.t, ev.v_plus);
}

void TangentTracker::on_regime(double t, Regime from, Regime to) {
    if (to == Regime::Contact) contact = true;
    if (!tangent_) return;
    // Regime III holds the cart at (xI, 0) and releases it when N(t), a function of time alone, crosses
    // zero: nothing of the initial perturbation survives it.
    if (to == Regime::Contact || from == Regime::Contact) apply(Mat2::Zero());
    else if (from == Regime::Sticking && to == Regime::Free) apply_impact_saltation(t_hit_, v_minus_, t, v_plus_);
}

void TangentTracker::apply_impact_saltation(double t_hit, double vm, double t_rel, double vp) {
    // The perturbed cart hits at t* + dt* (dt* = -dx/v-), with v- + dv-; it is held for T_imp(v-) and leaves
    // with v+ = -kappa(v-) v-; the perturbation after release is measured on the free branch at the nominal
    // release time (the release state minus f+ times the release-time shift). For T_imp = 0 this is the
    // classical S = DR + (f+ - DR f-) e1^T / v-.
    const double xI = p_.xI;
    const double am = acceleration(p_, d_, t_hit, xI, vm), ap = acceleration(p_, d_, t_rel, xI, vp);
    const double hv = 1e-6 * std::max(vm, 1e-3);
    const auto* law = p_.impact;
    const double* ip = p_.ip.data();
    const double kap = law->restitution(ip, vm);
    const double dkap = (law->restitution(ip, vm + hv) - law->restitution(ip, std::max(vm - hv, 0.0))) /
                        (vm + hv - std::max(vm - hv, 0.0));
    const double dT = (law->duration(ip, vm + hv) - law->duration(ip, std::max(vm - hv, 0.0))) /
                      (vm + hv - std::max(vm - hv, 0.0));
    const double D = -(kap + dkap * vm);   // dv+/dv-
    const Eigen::RowVector2d dt_hit(-1.0 / vm, 0.0);
    const Eigen::RowVector2d dv_minus(-am / vm, 1.0);
    const Eigen::RowVector2d dt_rel = dt_hit + dT * dv_minus;
    Mat2 S;
    S.row(0) = -vp * dt_rel;
    S.row(1) = D * dv_minus - ap * dt_rel;
    apply(S);
}

}  // namespace impactlab::analysis::detail
