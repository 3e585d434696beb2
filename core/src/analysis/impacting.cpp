// Impacting orbits of a rigid bumper written from impact to impact, and where a free orbit touches xI.
//
// Why a second formulation: the stroboscopic map of a rigid bumper has a square-root singularity at a
// grazing (Nordmark 1991): an orbit that reaches xI with speed v- has a saltation matrix with a 1/v- term, so
// the map's derivative grows without bound as v- -> 0 and Newton on P^k(y) = y cannot step from the free
// orbit onto the impacting one. Written from impact to impact, with unknowns the impact phase theta and the
// impact speed v-, the same orbits solve two smooth equations: the flight that leaves xI with
// v+ = -kappa(v-) v- at the end of the sticking T_imp(v-) reaches xI again after k forcing periods with
// speed v-. The flight is the Simulator's on the rig without the bumper (which keeps the equations smooth
// through v- = 0, where the impacting orbit becomes the grazing one); whether the flight stays clear of
// the bumper in between is checked on the real map.
#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

#include "analysis/tangent.hpp"
#include "impactlab/analysis.hpp"

namespace impactlab::analysis {

namespace {

// Records the state at one instant of the pieces it is handed (the section after the release) without
// splitting the Simulator's steps there (a split would change the step sequence, and the equations' noise).
class Catcher : public detail::TangentTracker {
public:
    Catcher(const Params& p, const Drive& d, bool tangent, double t_catch)
        : TangentTracker(p, d, tangent), t_catch_(t_catch) {}
    void on_piece(const Piece& piece) override {
        TangentTracker::on_piece(piece);
        if (!caught && t_catch_ >= piece.t0 && t_catch_ <= piece.t1) {
            y_catch = piece.at(t_catch_);
            caught = true;
        }
    }
    Vec2 y_catch = Vec2::Zero();
    bool caught = false;

private:
    double t_catch_;
};

// The largest x over a flight and when it is reached: a zero of v from + to - inside a piece, by bisection
// on the piece's dense output.
class PeakFinder : public Observer {
public:
    void on_piece(const Piece& piece) override {
        const Vec2 a = piece.at(piece.t0), b = piece.at(piece.t1);
        if (a[0] > x_max) { x_max = a[0]; t_max = piece.t0; }
        if (b[0] > x_max) { x_max = b[0]; t_max = piece.t1; }
        if (!(a[1] > 0 && b[1] <= 0)) return;
        double lo = piece.t0, hi = piece.t1;
        for (int i = 0; i < 100 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
            const double m = 0.5 * (lo + hi);
            (piece.at(m)[1] > 0 ? lo : hi) = m;
        }
        const double t = 0.5 * (lo + hi), x = piece.at(t)[0];
        if (x > x_max) { x_max = x; t_max = t; }
    }
    double x_max = -1e300, t_max = 0;
};

// The first rigid impact of a run: its time and v-.
class FirstImpact : public Observer {
public:
    void on_impact(const ImpactEvent& ev) override {
        if (found) return;
        found = true;
        t = ev.t;
        v_minus = ev.v_minus;
    }
    bool found = false;
    double t = 0, v_minus = 0;
};

Params without_bumper(const Params& p) {
    Params q = p;
    q.impact = find_impact("none");
    return q;
}

}  // namespace

ImpactShot impact_shot(const Params& p, double omega, double theta, double v_minus, int k, bool jacobian,
                       const Tolerances& tol) {
    ImpactShot r;
    if (!p.rigid()) throw std::invalid_argument("impact_shot needs a rigid bumper (a G or H version)");
    const Params f = without_bumper(p);
    const Drive d(omega, 0.0, 0.0);
    const double* ip = p.ip.data();
    // The law is even in v- (it reads |v-|): on the virtual side v- < 0 the equations stay continuous.
    const double vm = v_minus;
    const double kap = p.impact->restitution(ip, std::abs(vm));
    const double t_imp = p.impact->duration(ip, std::abs(vm));
    const double v_plus = -kap * vm;
    const double t_hit = theta / omega, t_rel = t_hit + t_imp, t_end = t_hit + kTwoPi * k / omega;
    if (!(t_end > t_rel)) throw std::invalid_argument("impact_shot: the sticking outlasts the k periods");
    // The section after the release: the first phi = 2 pi n at or after it.
    const double n_sec = std::ceil(omega * t_rel / kTwoPi - 1e-12);
    const double t_sec = kTwoPi * n_sec / omega;
    State s;
    s.t = t_rel;
    s.x = p.xI;
    s.v = v_plus;
    Simulator::make_consistent(f, d, s);
    Catcher c(f, d, jacobian, t_sec);
    Simulator sim(tol);
    sim.advance(f, d, s, t_end, &c);
    r.residual = Vec2((s.x - p.xI) / kXScale, (s.v - vm) / kVScale);
    r.section = c.caught ? c.y_catch : Vec2(p.xI, 0.0);   // not caught: the section falls in the sticking
    r.section_phase = kTwoPi * n_sec;
    if (!jacobian) return r;
    // d y(t_end): a shift of theta moves the start and the end alike; v- moves the start state and, through
    // T_imp, the start time (slopes of the law one-sided on the impacting side, v- >= 0).
    const Vec2 f_start(v_plus, detail::acceleration(f, d, t_rel, p.xI, v_plus));
    const Vec2 f_end(s.v, detail::acceleration(f, d, t_end, s.x, s.v));
    const double hv = 1e-6 * std::max(std::abs(vm), 1e-3);
    const double a = std::abs(vm), lo = std::max(a - hv, 0.0), hi = a + hv;
    const double dkap = (p.impact->restitution(ip, hi) - p.impact->restitution(ip, lo)) / (hi - lo);
    const double dT = (p.impact->duration(ip, hi) - p.impact->duration(ip, lo)) / (hi - lo);
    const double sgn = vm < 0 ? -1.0 : 1.0;
    const double dvp = -(kap + sgn * dkap * vm);   // d v+ / d v-
    const Vec2 dy_dtheta = (f_end - c.Phi * f_start) / omega;
    const Vec2 dy_dvm = c.Phi * Vec2(0.0, dvp) - c.Phi * f_start * (sgn * dT);
    r.J(0, 0) = dy_dtheta[0] / kXScale;
    r.J(1, 0) = dy_dtheta[1] / kVScale;
    r.J(0, 1) = dy_dvm[0] / kXScale * kVScale;
    r.J(1, 1) = dy_dvm[1] / kVScale * kVScale - 1.0;
    return r;
}

ImpactOrbit find_impact_orbit(const Params& p, double omega, double theta, double v_minus, int k,
                              const Tolerances& tol, int max_iterations) {
    ImpactOrbit o;
    o.theta = theta;
    o.v_minus = v_minus;
    for (o.iterations = 0; o.iterations <= max_iterations; ++o.iterations) {
        const ImpactShot s = impact_shot(p, omega, o.theta, o.v_minus, k, true, tol);
        o.residual = s.residual.cwiseAbs().maxCoeff();
        o.section = s.section;
        if (o.residual < std::max(1e-9, 10 * tol.rtol)) {
            o.converged = true;
            break;
        }
        if (o.iterations == max_iterations) break;
        const Vec2 du = -s.J.fullPivLu().solve(s.residual);
        if (!du.allFinite() || std::abs(du[0]) > 1.0 || std::abs(du[1]) > 1.0) break;
        o.theta += du[0];
        o.v_minus += du[1] * kVScale;
    }
    return o;
}

double peak_phase(const Params& p, double omega, const Vec2& y, int k, const Tolerances& tol, double* x_max) {
    const Params f = without_bumper(p);
    const Drive d(omega, 0.0, 0.0);
    State s;
    s.x = y[0];
    s.v = y[1];
    Simulator::make_consistent(f, d, s);
    PeakFinder pk;
    Simulator sim(tol);
    sim.advance(f, d, s, kTwoPi * k / omega, &pk);
    if (x_max) *x_max = pk.x_max;
    return omega * pk.t_max;
}

bool first_impact(const Params& p, double omega, const Vec2& y, int k, const Tolerances& tol, double& theta,
                  double& v_minus) {
    const Drive d(omega, 0.0, 0.0);
    State s;
    s.x = y[0];
    s.v = y[1];
    Simulator::make_consistent(p, d, s);
    FirstImpact fi;
    Simulator sim(tol);
    sim.advance(p, d, s, kTwoPi * k / omega, &fi);
    theta = omega * fi.t;
    v_minus = fi.v_minus;
    return fi.found;
}

}  // namespace impactlab::analysis
