// A Rosenbrock method for small stiff systems: RODAS4 (Hairer & Wanner, "Solving ODEs II", IV.7), the
// coefficient set also used by Boost.Odeint's rosenbrock4, with its order-3 dense output.
//
// Why this method: the smoothed dry friction T v / sqrt(v^2 + eps^2) has a slope of T/eps at v = 0, a
// relaxation rate of ~1.8e5 1/s, and the cart sits in that regime for thousands of seconds at small omega
// (and a compliant bumper adds a stiff contact mode). An explicit method would need ~1e-5 s steps there.
// RODAS4 is L-stable and stiffly accurate, so it takes steps set by accuracy alone; being linearly
// implicit it needs no Newton iteration, only one 2x2 solve per stage with the analytic Jacobian, which
// for a 2-state system costs less than the right-hand sides. Order 4 keeps the step count low in the
// smooth free flights that make up most of a chaotic run; its embedded order-3 estimate drives the step
// control, and the dense output locates events.
//
// The stepper knows nothing of the rig: a System provides
//   Vec2 rhs(double t, const Vec2& y) const;
//   void jacobian(double t, const Vec2& y, Mat2& J, Vec2& dfdt) const;
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace impactlab {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

// Error per step relative to rtol * (scale + |y|): the scales make the absolute part follow rtol, so
// that one number sets the accuracy (the cart moves over ~1 cm at ~0.1 m/s).
struct Tolerances {
    double rtol = 1e-8;
    double x_scale = 1e-2;   // [m]
    double v_scale = 1e-1;   // [m/s]
    double h_max = 0.5;      // [s]
    double h_min = 1e-14;    // [s] below this a step is forced through
    // Budgets (Simulator throws SimulationStalled past them): a run that needs more than max_step_rate
    // steps per simulated second over kStallWindow steps is stalled, not slow (the stiffest legal run, C1
    // hammering, needs ~1e5); max_wall_s > 0 caps the wall-clock time of one advance() call.
    double max_step_rate = 1e7;   // [steps / simulated s]
    double max_wall_s = 0;        // [s], 0: no limit
};

// One step of either method with its error estimate and a cubic dense output
//   y(s) = (1-s) y0 + s (y1 + (1-s)(cont3 + s cont4)),  s = (t - t0)/h,
// which is RODAS4's own order-3 interpolant, or the Hermite cubic through (y0, f0), (y1, f1) after a
// Dormand-Prince step. Allocation-free.
struct DenseStep {
    double t0 = 0, h = 0;
    Vec2 y0, y1, err;
    Vec2 cont3, cont4;   // dense-output coefficients
    Vec2 f1;             // Dormand-Prince: f(t0+h, y1), reused by the next step (FSAL)
    bool implicit = true;

    Vec2 at(double t) const {
        const double s = (t - t0) / h, s1 = 1.0 - s;
        return y0 * s1 + s * (y1 + s1 * (cont3 + s * cont4));
    }

    // Dormand-Prince 5(4) (Hairer, Norsett & Wanner, "Solving ODEs I", II.5): the explicit method for the
    // non-stiff stretches (free flight away from v = 0), where it needs a fraction of RODAS4's steps.
    // f0 = f(t, y) is passed in (first same as last).
    template <class System>
    void take_explicit(const System& sys, double t, const Vec2& y, double step, const Vec2& f0) {
        constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
        constexpr double a21 = 1.0 / 5;
        constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
        constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
        constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
        constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                         a65 = -5103.0 / 18656;
        constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
        constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                         e6 = 22.0 / 525, e7 = -1.0 / 40;
        t0 = t;
        h = step;
        y0 = y;
        implicit = false;
        const Vec2& k1 = f0;
        const Vec2 k2 = sys.rhs(t + c2 * h, y + h * (a21 * k1));
        const Vec2 k3 = sys.rhs(t + c3 * h, y + h * (a31 * k1 + a32 * k2));
        const Vec2 k4 = sys.rhs(t + c4 * h, y + h * (a41 * k1 + a42 * k2 + a43 * k3));
        const Vec2 k5 = sys.rhs(t + c5 * h, y + h * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4));
        const Vec2 k6 = sys.rhs(t + h, y + h * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5));
        y1 = y + h * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6);
        f1 = sys.rhs(t + h, y1);
        err = h * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * f1);
        // Hermite cubic in the form of at().
        const Vec2 dy = y1 - y0;
        cont3 = h * k1 - dy;
        cont4 = 2.0 * dy - h * (k1 + f1);
    }

    template <class System>
    void take(const System& sys, double t, const Vec2& y, double step) {
        implicit = true;
        // Coefficients of RODAS4 (gamma = 0.25).
        // d_i = gamma_i, the df/dt weights (Hairer's rodas.f: D4 = -0.0362; Boost 1.74's rosenbrock4 has +0.0362,
        // which drops the method to order 2 whenever the forcing makes df/dt nonzero).
        constexpr double gamma = 0.25, d1 = 0.25, d2 = -0.1043, d3 = 0.1035, d4 = -0.3620000000000023e-01;
        constexpr double c2 = 0.386, c3 = 0.21, c4 = 0.63;
        constexpr double c21 = -0.5668800000000000e+01, a21 = 0.1544000000000000e+01;
        constexpr double c31 = -0.2430093356833875e+01, c32 = -0.2063599157091915e+00;
        constexpr double a31 = 0.9466785280815826e+00, a32 = 0.2557011698983284e+00;
        constexpr double c41 = -0.1073529058151375e+00, c42 = -0.9594562251023355e+01, c43 = -0.2047028614809616e+02;
        constexpr double a41 = 0.3314825187068521e+01, a42 = 0.2896124015972201e+01, a43 = 0.9986419139977817e+00;
        constexpr double c51 = 0.7496443313967647e+01, c52 = -0.1024680431464352e+02, c53 = -0.3399990352819905e+02,
                         c54 = 0.1170890893206160e+02;
        constexpr double a51 = 0.1221224509226641e+01, a52 = 0.6019134481288629e+01, a53 = 0.1253708332932087e+02,
                         a54 = -0.6878860361058950e+00;
        constexpr double c61 = 0.8083246795921522e+01, c62 = -0.7981132988064893e+01, c63 = -0.3152159432874371e+02,
                         c64 = 0.1631930543123136e+02, c65 = -0.6058818238834054e+01;
        constexpr double d21 = 0.1012623508344586e+02, d22 = -0.7487995877610167e+01, d23 = -0.3480091861555747e+02,
                         d24 = -0.7992771707568823e+01, d25 = 0.1025137723295662e+01;
        constexpr double d31 = -0.6762803392801253e+00, d32 = 0.6087714651680015e+01, d33 = 0.1643084320892478e+02,
                         d34 = 0.2476722511418386e+02, d35 = -0.6594389125716872e+01;

        t0 = t;
        h = step;
        y0 = y;
        Mat2 J;
        Vec2 dfdt;
        sys.jacobian(t, y, J, dfdt);
        // W = I/(gamma h) - J, inverted in closed form (2x2).
        Mat2 W = -J;
        W(0, 0) += 1.0 / (gamma * h);
        W(1, 1) += 1.0 / (gamma * h);
        const double det = W(0, 0) * W(1, 1) - W(0, 1) * W(1, 0);
        Mat2 Wi;
        Wi << W(1, 1) / det, -W(0, 1) / det, -W(1, 0) / det, W(0, 0) / det;
        const double ih = 1.0 / h;

        const Vec2 f0 = sys.rhs(t, y);
        const Vec2 g1 = Wi * (f0 + h * d1 * dfdt);
        const Vec2 g2 = Wi * (sys.rhs(t + c2 * h, y + a21 * g1) + h * d2 * dfdt + c21 * ih * g1);
        const Vec2 g3 = Wi * (sys.rhs(t + c3 * h, y + a31 * g1 + a32 * g2) + h * d3 * dfdt + ih * (c31 * g1 + c32 * g2));
        const Vec2 g4 = Wi * (sys.rhs(t + c4 * h, y + a41 * g1 + a42 * g2 + a43 * g3) + h * d4 * dfdt +
                              ih * (c41 * g1 + c42 * g2 + c43 * g3));
        const Vec2 y5 = y + a51 * g1 + a52 * g2 + a53 * g3 + a54 * g4;
        const Vec2 g5 = Wi * (sys.rhs(t + h, y5) + ih * (c51 * g1 + c52 * g2 + c53 * g3 + c54 * g4));
        const Vec2 y6 = y5 + g5;
        err = Wi * (sys.rhs(t + h, y6) + ih * (c61 * g1 + c62 * g2 + c63 * g3 + c64 * g4 + c65 * g5));
        y1 = y6 + err;
        cont3 = d21 * g1 + d22 * g2 + d23 * g3 + d24 * g4 + d25 * g5;
        cont4 = d31 * g1 + d32 * g2 + d33 * g3 + d34 * g4 + d35 * g5;
    }

    // Scaled error norm (max over components); <= 1 means the step is accepted.
    double error_norm(const Tolerances& tol) const {
        const double sx = tol.rtol * (tol.x_scale + std::max(std::abs(y0[0]), std::abs(y1[0])));
        const double sv = tol.rtol * (tol.v_scale + std::max(std::abs(y0[1]), std::abs(y1[1])));
        return std::max(std::abs(err[0]) / sx, std::abs(err[1]) / sv);
    }
};

// Standard step-size proposal for an embedded pair whose error estimate is O(h^order).
inline double next_step_size(double h, double err_norm, bool accepted, int order = 4) {
    const double e = std::max(err_norm, 1e-10);
    double fac = 0.9 * std::pow(e, order == 5 ? -0.2 : -0.25);
    fac = std::clamp(fac, 0.2, accepted ? 6.0 : 1.0);
    return h * fac;
}

}  // namespace impactlab
