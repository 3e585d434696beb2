// The peers' own model and CF regime machine (bench_cvode, bench_odeint): the oscillator written out again from
// MODEL.md, as an engineer using a general-purpose ODE library would write it. Nothing here includes impactlab
// (peer_common.hpp fills a Model from impactlab's Params), and it compiles as C++17 too: Boost 1.74's uBLAS,
// which odeint's rosenbrock4 needs, does not build as C++20 (it calls std::allocator::construct).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace peer {

inline constexpr double kTwoPi = 6.283185307179586476925286766559;

// The peers' tolerances, by default impactlab's: relative rtol, absolute rtol x (scale_x, scale_v) (the cart
// moves over ~1 cm at ~0.1 m/s, so that rtol alone sets the accuracy), and the largest step h_max. The step cap
// matters: at small omega (forcing periods of up to 75 s) the cart creeps near the hilltop x = 0 and grazes the
// bumper once a period; without a cap the integrators take steps of many seconds, step over those contacts, and
// the cart leaves the hilltop for the well at a different omega (A1H: CVODE 3.8 or 6.9 rad/s, odeint 0.75 or
// 1.0, instead of the 1.9 that impactlab finds at rtol 1e-6 to 1e-10).
struct Accuracy {
    double rtol = 1e-8;
    double scale_x = 1e-2;   // [m]
    double scale_v = 1e-1;   // [m/s]
    double h_max = 0.5;      // [s] largest step, impactlab's Tolerances::h_max; 0: none
};

// ---------------------------------------------------------------------------------------------------------------
// The model (MODEL.md), with the drive of one CF level: phi(t) = omega (t - t_level).
struct Model {
    double m = 0, m0e = 0, k = 0, c = 0, T = 0, eps = 0, xI = 0;
    double a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};
    bool rigid = false;
    double ip[8] = {0, 0, 0, 0, 0, 0, 0, 0};   // impact law parameters, Hunt-Crossley: kI b n1 n2 n3;
                                               // rigid: kappa0 kappa1 a_kappa Ti0 Ti1 a_T
    double eps_v = 1e-4;                       // rigid: |v+| below this may end in permanent contact [m/s]
    double omega = 0, t_level = 0;

    // |h'| below this enters the Newton matrix as this value: d|h'|^n3/dh' is infinite at 0 (MODEL.md allows a
    // bounded slope; it changes only the iteration matrix, never the solution).
    static constexpr double kSlopeFloor = 1e-3;   // [m/s]

    void set_level(double w, double t0) {
        omega = w;
        t_level = t0;
    }
    double phi(double t) const { return omega * (t - t_level); }
    double forcing(double t) const { return m0e * omega * omega * std::sin(phi(t)); }
    double dforcing_dt(double t) const { return m0e * omega * omega * omega * std::cos(phi(t)); }

    // F_SA and its slope.
    void spring(double x, double& F, double& dF) const {
        const double x2 = x * x;
        const double num = x * (a[0] + x2 * (a[1] + x2 * (a[2] + x2 * a[3])));
        const double dnum = a[0] + x2 * (3 * a[1] + x2 * (5 * a[2] + x2 * 7 * a[3]));
        const double den = 1.0 + x2 * (b[0] + x2 * (b[1] + x2 * (b[2] + x2 * b[3])));
        const double dden = x * (2 * b[0] + x2 * (4 * b[1] + x2 * (6 * b[2] + x2 * 8 * b[3])));
        F = k * x + num / den;
        dF = k + (dnum * den - num * dden) / (den * den);
    }
    // F_R and its slope.
    void resistance(double v, double& F, double& dF) const {
        const double s2 = v * v + eps * eps, s = std::sqrt(s2);
        F = c * v + T * v / s;
        dF = c + T * eps * eps / (s2 * s);
    }
    // Hunt-Crossley bumper force (compliant versions) and its partial derivatives (bounded dF/dh').
    void contact(double x, double v, double& F, double& dFdx, double& dFdv) const {
        F = dFdx = dFdv = 0.0;
        const double h = x - xI;
        if (rigid || h <= 0.0) return;
        const double kI = ip[0], bb = ip[1], n1 = ip[2], n2 = ip[3], n3 = ip[4];
        const double hn1 = std::pow(h, n1), hn2 = std::pow(h, n2);
        const double av = std::abs(v);
        const double avn3 = av > 0.0 ? std::pow(av, n3) : 0.0;
        const double sg = v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
        const double f = kI * (hn1 + bb * hn2 * avn3 * sg);
        if (f <= 0.0) return;   // the bumper never pulls
        F = f;
        dFdx = kI * (n1 * hn1 + bb * n2 * hn2 * avn3 * sg) / h;
        dFdv = kI * bb * hn2 * n3 * std::pow(std::max(av, kSlopeFloor), n3 - 1.0);
    }

    // y' = f(t, y), y = (x, v).
    void rhs(double t, double x, double v, double& dx, double& dv) const {
        double Fs, dFs, Fr, dFr, Fi, dFix, dFiv;
        spring(x, Fs, dFs);
        resistance(v, Fr, dFr);
        contact(x, v, Fi, dFix, dFiv);
        dx = v;
        dv = (forcing(t) - Fr - Fs - Fi) / m;
    }
    // J = df/dy (row major) and df/dt.
    void jacobian(double t, double x, double v, double J[2][2], double dfdt[2]) const {
        double Fs, dFs, Fr, dFr, Fi, dFix, dFiv;
        spring(x, Fs, dFs);
        resistance(v, Fr, dFr);
        contact(x, v, Fi, dFix, dFiv);
        J[0][0] = 0.0;
        J[0][1] = 1.0;
        J[1][0] = -(dFs + dFix) / m;
        J[1][1] = -(dFr + dFiv) / m;
        dfdt[0] = 0.0;
        dfdt[1] = dforcing_dt(t) / m;
    }

    // Rigid versions: normal force at the bumper, restitution and impact duration.
    double normal_force(double t) const {
        double Fs, dFs;
        spring(xI, Fs, dFs);
        return forcing(t) - Fs;
    }
    double kappa(double vm) const { return (ip[0] - ip[1]) * std::exp(-ip[2] * std::abs(vm)) + ip[1]; }
    double t_imp(double vm) const { return (ip[3] - ip[4]) * std::exp(-ip[5] * std::abs(vm)) + ip[4]; }
};

// ---------------------------------------------------------------------------------------------------------------
// The CF sweep's regime machine, over a Backend that integrates the smooth pieces:
//   void restart_free(double t, double x, double v, int side);
//        (re)start free flight (regime I) after a discontinuity; side: +1 in contact with a compliant bumper
//        (x > xI), -1 clear of it (always for a rigid one), 0 not known (x = xI, v = 0)
//   void restart_contact(double t);                      rigid regime III starts
//   bool free_flight(double t_stop, double& t, double& x, double& v);
//        integrate regime I until t_stop (returns false, t == t_stop) or until x crosses xI leaving `side`
//        (returns true, t the crossing time); side 0: either way
//   bool contact(double t_stop, double& t);               regime III until t_stop (false) or until N falls to 0 (true)
//   std::uint64_t steps() const;                          accepted integration steps so far
enum class Regime { Free, Sticking, Contact };

struct Point { double omega, x, v; };

struct PeerDiagram {
    std::vector<Point> points;   // `record` section points per omega, in sweep order
    double simulated_seconds = 0;
    std::uint64_t steps = 0, impacts = 0;
};

struct CfGrid {
    std::vector<double> omegas;   // in sweep order
    int transient = 20, record = 70;
    bool verbose = false;         // one line per omega on stderr: steps, impacts, time, state
};

template <class Backend>
PeerDiagram run_cf(Model& M, Backend& B, const CfGrid& grid) {
    PeerDiagram out;
    out.points.reserve(grid.omegas.size() * static_cast<std::size_t>(grid.record));
    Regime reg = Regime::Free;
    double t = 0, x = 0, v = 0;            // at rest at the springs' zero position
    double t_release = 0, v_release = 0;   // regime II
    // Compliant bumper: which side of x = xI the cart is on. It flips at every crossing and decides which
    // crossing comes next; it is not read off the sign of v at the crossing, which near a turning point (the cart
    // creeping against the bumper at small omega) is noise and would let the same crossing be found again and
    // again without progress.
    int side = -1;
    const int n_total = grid.transient + grid.record;

    auto release = [&](double vplus) {
        x = M.xI;
        if (std::abs(vplus) < M.eps_v && M.normal_force(t) > 0) {
            reg = Regime::Contact;
            v = 0;
            B.restart_contact(t);
        } else {
            reg = Regime::Free;
            v = vplus;
            B.restart_free(t, x, v, -1);
        }
    };

    bool first = true;
    for (const double w : grid.omegas) {
        M.set_level(w, t);   // every level starts at a section instant, phi = 0
        if (first && M.rigid && x >= M.xI) {
            // On the bumper at rest: regime III if the unbalance presses the cart on it (N > 0, or N = 0 and
            // rising, as at t = 0 with xI = 0), else free flight.
            const double N = M.normal_force(t);
            x = M.xI;
            v = 0;
            reg = (N > 0 || (N == 0 && M.dforcing_dt(t) > 0)) ? Regime::Contact : Regime::Free;
        }
        if (first && !M.rigid) side = x > M.xI ? 1 : (x < M.xI ? -1 : (v > 0 ? 1 : (v < 0 ? -1 : 0)));
        first = false;
        // The right-hand side changes with omega: restart whatever is being integrated.
        if (reg == Regime::Free) B.restart_free(t, x, v, side);
        else if (reg == Regime::Contact) B.restart_contact(t);

        for (int i = 1; i <= n_total; ++i) {
            const double t_sec = M.t_level + kTwoPi * i / w;
            while (t < t_sec) {
                if (reg == Regime::Free) {
                    if (!B.free_flight(t_sec, t, x, v)) break;   // reached t_sec
                    if (!M.rigid) {
                        // Compliant bumper: contact starts or ends at x = xI, a kink in the force: restart there.
                        side = side != 0 ? -side : (v > 0 ? 1 : -1);
                        if (side > 0) ++out.impacts;
                        x = M.xI;
                        B.restart_free(t, x, v, side);
                        continue;
                    }
                    // Rigid bumper: an impact with v- = v.
                    ++out.impacts;
                    const double vm = std::max(v, 0.0);
                    const double vp = -M.kappa(vm) * vm;
                    const double Ti = M.t_imp(vm);
                    x = M.xI;
                    if (Ti > 0) {
                        reg = Regime::Sticking;
                        t_release = t + Ti;
                        v_release = vp;
                        v = 0;
                    } else {
                        release(vp);
                    }
                } else if (reg == Regime::Sticking) {
                    if (t_release <= t_sec) {
                        t = t_release;
                        release(v_release);
                    } else {
                        t = t_sec;
                    }
                } else {
                    if (B.contact(t_sec, t)) {   // N fell to zero: free flight from rest at the bumper
                        reg = Regime::Free;
                        x = M.xI;
                        v = 0;
                        B.restart_free(t, x, v, -1);
                    } else {
                        t = t_sec;
                    }
                }
            }
            t = t_sec;
            if (i > grid.transient) {
                const bool held = reg != Regime::Free;
                out.points.push_back({w, held ? M.xI : x, held ? 0.0 : v});
            }
        }
        if (grid.verbose)
            std::fprintf(stderr, "omega %8.4f  t %10.2f  steps %10llu  impacts %8llu  x %+.6e  v %+.6e  regime %d\n", w, t,
                         static_cast<unsigned long long>(B.steps()), static_cast<unsigned long long>(out.impacts), x, v,
                         static_cast<int>(reg));
    }
    out.simulated_seconds = t;
    out.steps = B.steps();
    return out;
}

// Illinois (modified regula falsi) for g(t) = 0 on [a, b], g(a) and g(b) of opposite signs.
// Returns the end of the final bracket on b's side (past the crossing).
template <class G>
double illinois(G&& g, double a, double b, double ga, double gb) {
    for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
        double c = (ga == gb) ? 0.5 * (a + b) : b - gb * (b - a) / (gb - ga);
        if (!(c > a && c < b)) c = 0.5 * (a + b);
        const double gc = g(c);
        if (gc == 0.0) return c;
        if ((gc > 0) == (gb > 0)) {
            b = c;
            gb = gc;
            ga *= 0.5;
        } else {
            a = c;
            ga = gc;
            gb *= 0.5;
        }
    }
    return b;
}

// The odeint peer's entry point (bench_odeint_backend.cpp, compiled as C++17). fixed_gamma4: rosenbrock4 with
// the sign of its gamma_4 coefficient corrected (see there).
PeerDiagram run_cf_odeint(Model& M, const CfGrid& grid, const Accuracy& acc, bool fixed_gamma4);

}  // namespace peer
