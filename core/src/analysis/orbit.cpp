// Periodic orbits: the k-th stroboscopic map with its derivative, Newton on its fixed points, Floquet.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "analysis/tangent.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/equilibria.hpp"
#include "impactlab/forces.hpp"

namespace impactlab::analysis {

double scaled_norm(const Vec2& dy) { return std::max(std::abs(dy[0]) / kXScale, std::abs(dy[1]) / kVScale); }

Tolerances analysis_tolerances(double rtol) {
    Tolerances t;
    t.rtol = rtol;
    return t;
}

MapResult poincare_map(const Params& p, double omega, const Vec2& y0, int k, bool tangent, const Tolerances& tol) {
    return detail::period_map(p, omega, y0, k, tangent, tol, nullptr);
}

namespace detail {
MapResult period_map(const Params& p, double omega, const Vec2& y0, int k, bool tangent, const Tolerances& tol,
                     std::vector<Mat2>* section_Phi, bool defer) {
    MapResult r;
    Simulator sim(tol);
    const Drive d(omega, 0.0, 0.0);
    State s;
    s.x = y0[0];
    s.v = y0[1];
    Simulator::make_consistent(p, d, s);
    detail::TangentTracker tr(p, d, tangent);
    r.sections.reserve(static_cast<std::size_t>(k));
    tr.sections = &r.sections;
    tr.section_Phi = section_Phi;
    if (s.regime == Regime::Contact) tr.Phi.setZero();   // held: the start's perturbation is forgotten
    tr.max_x = s.x;
    tr.defer = tangent && defer;
    sim.advance(p, d, s, d.time_of_phase(kTwoPi * k), &tr);
    tr.finish();
    r.held = s.regime != Regime::Free;
    r.y = r.held ? Vec2(p.xI, 0.0) : Vec2(s.x, s.v);
    if (!r.sections.empty()) r.sections.back() = r.y;
    r.M = tr.Phi;
    r.impacts = tr.impacts;
    r.max_x = tr.max_x;
    r.min_impact_speed = tr.min_impact_speed;
    r.contact = tr.contact;
    r.steps = s.steps;
    return r;
}
}  // namespace detail

Mat2 monodromy_fd(const Params& p, double omega, const Vec2& y0, int k, const Tolerances& tol, double h) {
    Mat2 M;
    const double scale[2] = {kXScale, kVScale};
    for (int j = 0; j < 2; ++j) {
        Vec2 e = Vec2::Zero();
        e[j] = h * scale[j];
        const Vec2 yp = poincare_map(p, omega, y0 + e, k, false, tol).y;
        const Vec2 ym = poincare_map(p, omega, y0 - e, k, false, tol).y;
        M.col(j) = (yp - ym) / (2.0 * e[j]);
    }
    return M;
}

Floquet floquet(const Mat2& M) {
    Floquet f;
    const double tr = M.trace(), det = M.determinant();
    const std::complex<double> disc = std::sqrt(std::complex<double>(0.25 * tr * tr - det));
    f.mu[0] = 0.5 * tr + disc;
    f.mu[1] = 0.5 * tr - disc;
    if (std::abs(f.mu[1]) > std::abs(f.mu[0])) std::swap(f.mu[0], f.mu[1]);
    f.stable = std::abs(f.mu[0]) < 1.0;
    return f;
}

double left_well(const Params& p) {
    // The well of F_SA between -0.1 m and the hilltop (A1: -10.88 mm), taken as one cell: a double well has
    // F_SA > 0 just left of the hilltop (the magnets push the cart away from it), so F_SA rises through
    // zero there. None: a single well at x = 0.
    const auto found = equilibria([&](double x) { return spring_magnet(p, x).F; }, -0.1, -1e-6, 1);
    return !found.empty() && found[0].stable ? found[0].x : 0.0;
}

Vec2 settle(const Params& p, double omega, const Vec2& y0, int periods, const Tolerances& tol) {
    return poincare_map(p, omega, y0, periods, false, tol).y;
}

Orbit find_orbit(const Params& p, double omega, const Vec2& guess, const OrbitOptions& opt) {
    Orbit o;
    o.omega = omega;
    o.period = opt.period;
    Vec2 y = guess;
    Tolerances sim = opt.sim;
    MapResult r = poincare_map(p, omega, y, opt.period, true, sim);
    double res = scaled_norm(r.y - y);
    // The map is known only to about the integrator's tolerance: a residual below that is noise, and a
    // Newton asked for it stalls (rtol 1e-8 stops near 3e-9).
    const double tol = std::max(opt.tol, 10 * opt.sim.rtol);
    bool within_step = false;
    int sharpened = 0;
    for (o.iterations = 0; o.iterations < opt.max_iterations && res > tol; ++o.iterations) {
        const Mat2 J = r.M - Mat2::Identity();
        if (!std::isfinite(J.determinant()) || std::abs(J.determinant()) < 1e-300) {
            o.message = "the map's derivative minus I is singular (a multiplier at +1)";
            break;
        }
        const Vec2 step = -J.partialPivLu().solve(r.y - y);
        // Damped: halve until the residual drops (a step across a grazing can make it worse).
        double lam = 1.0;
        bool improved = false;
        for (int h = 0; h < 12; ++h, lam *= 0.5) {
            const Vec2 yn = y + lam * step;
            MapResult rn = poincare_map(p, omega, yn, opt.period, true, sim);
            const double rn_res = scaled_norm(rn.y - yn);
            if (rn_res < res || scaled_norm(lam * step) < 1e-13) {
                y = yn;
                r = std::move(rn);
                res = rn_res;
                improved = true;
                break;
            }
        }
        if (!improved) {
            // A long period (A3C's period 24: 8.3 s) carries the integrator's error far above 10 rtol: the
            // map is sharpened, twice at most, and Newton goes on to the tolerance asked for. This comes
            // before the noise-floor test below: otherwise whether a residual just above the tolerance is
            // accepted as noise or sharpened away follows the last bits of libm (A3C: 1e-9 or 6e-12).
            if (sim.rtol > 1e-13 && sharpened < 2) {
                ++sharpened;
                sim.rtol = std::max(sim.rtol * 1e-2, 1e-13);
                r = poincare_map(p, omega, y, opt.period, true, sim);
                res = scaled_norm(r.y - y);
                continue;
            }
            // At the map's noise floor (slow, |mu| near 1, where the residual's noise exceeds 10 rtol) no step
            // lowers the residual, yet a full step below the tolerance puts the fixed point within it of y.
            if (scaled_norm(step) <= tol) {
                within_step = true;
                break;
            }
            o.message = "Newton stalled (no step lowers the residual)";
            break;
        }
    }
    o.y = y;
    o.M = r.M;
    o.floquet = floquet(r.M);
    o.residual = res;
    o.impacts = r.impacts;
    o.max_x = r.max_x;
    o.min_impact_speed = r.min_impact_speed;
    o.sections = r.sections;
    o.converged = (res <= tol || within_step) && std::isfinite(res);
    if (!o.converged && o.message.empty()) o.message = "no convergence in " + std::to_string(opt.max_iterations) + " iterations";
    return o;
}

}  // namespace impactlab::analysis
