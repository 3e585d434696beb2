// The Boost.Odeint peer of bench_odeint: the CF diagrams written with rosenbrock4, its step-size controller and
// dense output (make_dense_output(atol, rtol, rosenbrock4<double>())).
//
// - Free flight: do_step on the dense-output stepper (its controller capped at h_max, impactlab's 0.5 s). The step that would pass the next Poincare section is
//   shortened to land on it (initialize(x, t, t_sec - t)); after the landing the step-size proposal from before
//   it is restored.
// - Events: x - xI sampled at four points of every accepted step on the dense output (calc_state), the first
//   crossing refined by Illinois regula falsi on calc_state, the stepper restarted there (initialize) with the
//   state of the dense output. Rigid: only the approach from below counts (an impact); compliant: both ways.
// - Rigid regime III: N(t) is known in closed form; its zero is bracketed on a grid of a 64th of a period and
//   refined by the same root finder (odeint has no root-finding of its own).
//
// Boost 1.74's rosenbrock4 has gamma_4 = sum_j gamma_4j (its d4, the weight of df/dt in stage 4) with the wrong
// sign: +0.0362 where Hairer & Wanner's RODAS (rodas.f) and KPP's Rodas4 have -0.0362. For a non-autonomous
// system (here the forcing, df/dt != 0) the method then drops to order 2 and its error estimate with it, and the
// controller takes some ten times more steps. The stock stepper is the default (what a user of the library
// gets); --fixed-gamma4 runs rosenbrock4 with the corrected coefficient (odeint's Coefficients parameter).
//
// This file is compiled as C++17 (see sources.cmake): Boost 1.74's uBLAS calls std::allocator::construct, gone
// in C++20. It sees only peer_model.hpp, not impactlab.
#include <boost/numeric/odeint.hpp>
#include <utility>

#include "peer_model.hpp"

namespace {

namespace odeint = boost::numeric::odeint;
using state_t = boost::numeric::ublas::vector<double>;
using matrix_t = boost::numeric::ublas::matrix<double>;

// The state is scaled, z = (x / scale_x, v / scale_v), so that odeint's single absolute tolerance (rtol x 1)
// means rtol x (scale_x, scale_v), the tolerances the CVODE peer gets per component.
struct OdeSystem {
    const peer::Model* M;
    double kSx, kSv;
    void operator()(const state_t& z, state_t& dzdt, double t) const {
        double dx, dv;
        M->rhs(t, z[0] * kSx, z[1] * kSv, dx, dv);
        dzdt[0] = dx / kSx;
        dzdt[1] = dv / kSv;
    }
};
struct OdeJacobian {
    const peer::Model* M;
    double kSx, kSv;
    void operator()(const state_t& z, matrix_t& J, const double& t, state_t& dfdt) const {
        double Jm[2][2], d[2];
        M->jacobian(t, z[0] * kSx, z[1] * kSv, Jm, d);
        J(0, 0) = Jm[0][0];
        J(0, 1) = Jm[0][1] * kSv / kSx;
        J(1, 0) = Jm[1][0] * kSx / kSv;
        J(1, 1) = Jm[1][1];
        dfdt[0] = d[0] / kSx;
        dfdt[1] = d[1] / kSv;
    }
};

// odeint's RODAS4 coefficients with gamma_4 corrected (the member hides the base class's d4).
struct CorrectedCoefficients : odeint::default_rosenbrock_coefficients<double> {
    const double d4 = -0.3620000000000023e-01;
};

template <class Stepper>
class OdeintBackend {
public:
    using Dense = odeint::rosenbrock4_dense_output<odeint::rosenbrock4_controller<Stepper>>;

    OdeintBackend(peer::Model& model, const peer::Accuracy& acc)
        : M_(model), kSx(acc.scale_x), kSv(acc.scale_v),
          // atol: rtol x the scales of z; max_dt 0: no limit
          stepper_(odeint::make_dense_output(acc.rtol, acc.rtol, acc.h_max, Stepper())),
          y_(2), tmp_(2) {}
    void restart_free(double t, double x, double v, int side) {
        y_[0] = x / kSx;
        y_[1] = v / kSv;
        side_ = side > 0 ? 1 : -1;   // not known (at rest on the plane x = xI): a move inwards is the event
        stepper_.initialize(y_, t, kRestartStep);
    }
    void restart_contact(double /*t*/) {}

    bool free_flight(double t_stop, double& t, double& x, double& v) {
        auto sys = std::make_pair(OdeSystem{&M_, kSx, kSv}, OdeJacobian{&M_, kSx, kSv});
        for (;;) {
            const double t0 = stepper_.current_time();
            const double dt = stepper_.current_time_step();
            const bool landing = t0 + 1.05 * dt >= t_stop;
            if (landing) {
                y_ = stepper_.current_state();
                stepper_.initialize(y_, t0, t_stop - t0);
            }
            const auto [ta0, tb0] = stepper_.do_step(sys);
            ++steps_;
            // Events: sample x - xI on the dense output.
            const bool inside_before = side_ > 0;
            double ta = ta0, tb = ta0;
            bool event = false;
            for (int k = 1; k <= 4; ++k) {
                tb = k == 4 ? tb0 : ta0 + (tb0 - ta0) * k / 4.0;
                if ((x_at(tb) - M_.xI > 0) != inside_before) {
                    event = true;
                    break;
                }
                ta = tb;
            }
            if (event) {
                const double sgn = inside_before ? -1.0 : 1.0;
                auto g = [&](double s) { return sgn * (x_at(s) - M_.xI); };
                double ga = g(ta);
                if (ga >= 0) {   // a step starting on the bumper plane: find a point clear of it
                    double tm = tb;
                    for (int j = 0; j < 60 && g(tm) >= 0; ++j) tm = ta0 + 0.5 * (tm - ta0);
                    if (g(tm) < 0) {
                        ta = tm;
                        ga = g(tm);
                    }
                }
                const double t_ev = ga < 0 ? peer::illinois(g, ta, tb, ga, g(tb)) : ta;
                stepper_.calc_state(t_ev, tmp_);
                t = t_ev;
                x = tmp_[0] * kSx;
                v = tmp_[1] * kSv;
                return true;
            }
            if (landing && std::abs(tb0 - t_stop) <= 1e-13 * std::max(1.0, std::abs(t_stop))) {
                // Restore the proposal from before the landing (a shortened step proposes a short one).
                const double dt_next = std::max(dt, stepper_.current_time_step());
                y_ = stepper_.current_state();
                stepper_.initialize(y_, t_stop, dt_next);
                t = t_stop;
                x = y_[0] * kSx;
                v = y_[1] * kSv;
                return false;
            }
        }
    }

    bool contact(double t_stop, double& t) {
        const double scan = std::min(peer::kTwoPi / M_.omega / 64.0, 0.05);
        double ta = t, na = M_.normal_force(ta);
        while (ta < t_stop) {
            const double tb = std::min(ta + scan, t_stop);
            const double nb = M_.normal_force(tb);
            if (nb <= 0.0) {
                auto N = [&](double s) { return M_.normal_force(s); };
                t = na > 0 ? peer::illinois(N, ta, tb, na, nb) : ta;
                return true;
            }
            ta = tb;
            na = nb;
        }
        t = t_stop;
        return false;
    }
    std::uint64_t steps() const { return steps_; }

private:
    static constexpr double kRestartStep = 1e-4;   // [s] first step after a discontinuity; the controller grows it
    double x_at(double t) {
        if (t == stepper_.current_time()) return stepper_.current_state()[0] * kSx;
        stepper_.calc_state(t, tmp_);
        return tmp_[0] * kSx;
    }

    peer::Model& M_;
    double kSx, kSv;
    Dense stepper_;
    state_t y_, tmp_;
    int side_ = -1;
    std::uint64_t steps_ = 0;
};

}  // namespace

namespace peer {

PeerDiagram run_cf_odeint(Model& M, const CfGrid& grid, const Accuracy& acc, bool fixed_gamma4) {
    if (fixed_gamma4) {
        OdeintBackend<odeint::rosenbrock4<double, CorrectedCoefficients>> B(M, acc);
        return run_cf(M, B, grid);
    }
    OdeintBackend<odeint::rosenbrock4<double>> B(M, acc);
    return run_cf(M, B, grid);
}

}  // namespace peer
