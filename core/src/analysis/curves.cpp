// A period doubling or a grazing continued in two parameters (omega and xI or m0e): natural-parameter steps in
// the second parameter, the point's omega found again at each by a secant on its test (the crossing
// multiplier, or the bumperless orbit's largest x minus xI).
#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "impactlab/analysis.hpp"

namespace impactlab::analysis {

namespace {

// The real multiplier nearest -1 of the period-k orbit at omega near y (NaN when complex or not found).
struct Probe { double mu = NAN; Vec2 y = Vec2::Zero(); };
Probe probe(const Params& p, double omega, const Vec2& guess, int period, const Tolerances& sim) {
    OrbitOptions oo;
    oo.period = period;
    oo.sim = sim;
    oo.max_iterations = 12;
    Probe r;
    try {
        const Orbit o = find_orbit(p, omega, guess, oo);
        if (!o.converged || scaled_norm(o.y - guess) > 0.2) return r;
        if (o.floquet.mu[0].imag() != 0.0) return r;
        const double a = o.floquet.mu[0].real(), b = o.floquet.mu[1].real();
        r.mu = std::abs(a + 1) < std::abs(b + 1) ? a : b;
        r.y = o.y;
    } catch (const std::exception&) {
    }
    return r;
}

// The period-k orbit of the rig without its bumper at omega near y, and its largest x minus xI (NaN if not
// found): zero at a grazing, smooth through it (the bumper's law never enters).
struct GapProbe { double gap = NAN; Vec2 y = Vec2::Zero(); };
GapProbe gap_probe(const Params& p, double omega, const Vec2& guess, int period, const Tolerances& sim) {
    Params f = p;
    f.impact = find_impact("none");
    OrbitOptions oo;
    oo.period = period;
    oo.sim = sim;
    oo.max_iterations = 12;
    GapProbe r;
    try {
        const Orbit o = find_orbit(f, omega, guess, oo);
        if (!o.converged || scaled_norm(o.y - guess) > 0.2) return r;
        double x_max = 0;
        peak_phase(f, omega, o.y, period, sim, &x_max);
        r.gap = (x_max - p.xI) / kXScale;
        r.y = o.y;
    } catch (const std::exception&) {
    }
    return r;
}

// The fold's extended system at fixed second parameter: (P^k(y) - y scaled, det(M - I)) = 0 in (x, v, omega),
// by Newton with the derivatives by forward differences of the map (its own monodromy gives d/dy of the
// first two; det(M - I) needs the map's second derivative, which differences of M give).
struct FoldSolve { bool ok = false; double omega = 0; Vec2 y = Vec2::Zero(); };
FoldSolve fold_newton(const Params& p, double omega, Vec2 y, int period, const Tolerances& sim) {
    FoldSolve r;
    auto eval = [&](double w, const Vec2& yy, Eigen::Vector3d& F, Mat2& M) {
        const MapResult m = poincare_map(p, w, yy, period, true, sim);
        M = m.M;
        F = Eigen::Vector3d((m.y[0] - yy[0]) / kXScale, (m.y[1] - yy[1]) / kVScale, (m.M - Mat2::Identity()).determinant());
        return F.allFinite();
    };
    try {
        for (int it = 0; it < 25; ++it) {
            Eigen::Vector3d F;
            Mat2 M;
            if (!eval(omega, y, F, M)) return r;
            // Scale the determinant by the multipliers' size (an impacting orbit's run to hundreds).
            const double ds = std::max(1.0, std::abs(M.trace()));
            if (std::abs(F[0]) < 1e-9 && std::abs(F[1]) < 1e-9 && std::abs(F[2]) / ds < 1e-8) {
                r = {true, omega, y};
                return r;
            }
            Eigen::Matrix3d J;
            const double h[3] = {1e-7 * kXScale, 1e-7 * kVScale, 1e-7};
            for (int j = 0; j < 3; ++j) {
                Vec2 yj = y;
                double wj = omega;
                if (j < 2) yj[j] += h[j];
                else wj += h[j];
                Eigen::Vector3d Fj;
                Mat2 Mj;
                if (!eval(wj, yj, Fj, Mj)) return r;
                J.col(j) = (Fj - F) / h[j];
            }
            const Eigen::Vector3d d = J.fullPivLu().solve(-F);
            if (!d.allFinite()) return r;
            y += Vec2(d[0], d[1]);
            omega += d[2];
            if (!(omega > 0) || std::abs(d[2]) > 1.0) return r;
        }
    } catch (const std::exception&) {
    }
    return r;
}

}  // namespace

BifCurve continue_fold_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period, double lo,
                             double hi, double step, const Tolerances& sim) {
    if (second == ContParam::Omega) throw std::invalid_argument("a fold curve needs a second parameter besides omega");
    if (!(step > 0) || !(hi > lo)) throw std::invalid_argument("a fold curve needs lo < hi and a positive step");
    BifCurve c;
    c.kind = BifKind::Fold;
    c.second = second;
    c.period = period;
    Params work = p;
    double& q_ref = second == ContParam::XI ? work.xI : work.m0e;
    const double q0 = q_ref;
    std::vector<CurvePoint> sides[2];
    std::string ends[2];
    for (int side = 0; side < 2; ++side) {
        const double dir = side == 0 ? 1.0 : -1.0;
        std::vector<CurvePoint>& pts = sides[side];
        CurvePoint prev{omega0, q0, y0}, before = prev;
        int have = 1;
        double h = step;
        bool first = side == 0;
        while (true) {
            const double q = first ? q0 : prev.q + dir * h;
            if (q > hi + 1e-12 * std::abs(hi) || q < lo - 1e-12 * std::abs(lo)) {
                ends[side] = std::string(cont_param_name(second)) + " range";
                break;
            }
            q_ref = q;
            double w = prev.omega;
            Vec2 y = prev.y;
            if (have >= 2 && prev.q != before.q) {
                const double f = (q - prev.q) / (prev.q - before.q);
                w = prev.omega + f * (prev.omega - before.omega);
                y = prev.y + f * (prev.y - before.y);
            }
            const FoldSolve fs = fold_newton(work, w, y, period, sim);
            if (!fs.ok || scaled_norm(fs.y - y) > 0.5) {
                if (!first && h > step / 64) {
                    h *= 0.5;
                    continue;
                }
                ends[side] = "fold lost near " + std::string(cont_param_name(second)) + " = " + std::to_string(q);
                break;
            }
            pts.push_back({fs.omega, q, fs.y});
            if (!first) {
                before = prev;
                ++have;
                h = std::min(step, 2 * h);
            }
            prev = {fs.omega, q, fs.y};
            first = false;
        }
    }
    c.points.assign(sides[1].rbegin(), sides[1].rend());
    c.points.insert(c.points.end(), sides[0].begin(), sides[0].end());
    c.end = ends[1] + " / " + ends[0];
    return c;
}

BifCurve continue_grazing_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period, double lo,
                                double hi, double step, const Tolerances& sim) {
    if (second == ContParam::Omega) throw std::invalid_argument("a grazing curve needs a second parameter besides omega");
    if (!(step > 0) || !(hi > lo)) throw std::invalid_argument("a grazing curve needs lo < hi and a positive step");
    if (!p.has_bumper()) throw std::invalid_argument("a grazing curve needs a bumper");
    BifCurve c;
    c.kind = BifKind::Grazing;
    c.second = second;
    c.period = period;
    Params work = p;
    double& q_ref = second == ContParam::XI ? work.xI : work.m0e;
    const double q0 = q_ref;
    std::vector<CurvePoint> sides[2];
    std::string ends[2];
    for (int side = 0; side < 2; ++side) {
        const double dir = side == 0 ? 1.0 : -1.0;
        std::vector<CurvePoint>& pts = sides[side];
        CurvePoint prev{omega0, q0, y0}, before = prev;
        int have = 1;
        double h = step;
        bool first = side == 0;
        while (true) {
            const double q = first ? q0 : prev.q + dir * h;
            if (q > hi + 1e-12 * std::abs(hi) || q < lo - 1e-12 * std::abs(lo)) {
                ends[side] = std::string(cont_param_name(second)) + " range";
                break;
            }
            q_ref = q;
            double w = prev.omega;
            Vec2 y = prev.y;
            if (have >= 2 && prev.q != before.q) {
                const double f = (q - prev.q) / (prev.q - before.q);
                w = prev.omega + f * (prev.omega - before.omega);
                y = prev.y + f * (prev.y - before.y);
            }
            // Secant on the gap in omega, from w and w + 1e-3.
            double wa = w, wb = w + 1e-3;
            GapProbe a = gap_probe(work, wa, y, period, sim), b = gap_probe(work, wb, std::isfinite(a.gap) ? a.y : y, period, sim);
            bool ok = false;
            for (int it = 0; it < 30 && std::isfinite(a.gap) && std::isfinite(b.gap) && b.gap != a.gap; ++it) {
                const double wn = wb - b.gap * (wb - wa) / (b.gap - a.gap);
                if (!std::isfinite(wn) || std::abs(wn - w) > 1.0) break;   // ran off: no grazing near here
                a = b;
                wa = wb;
                wb = wn;
                b = gap_probe(work, wb, a.y, period, sim);
                if (std::abs(wb - wa) < 1e-8 && std::isfinite(b.gap)) {
                    ok = true;
                    break;
                }
            }
            if (!ok) {
                if (!first && h > step / 64) {
                    h *= 0.5;
                    continue;
                }
                ends[side] = "grazing lost near " + std::string(cont_param_name(second)) + " = " + std::to_string(q);
                break;
            }
            pts.push_back({wb, q, b.y});
            if (!first) {
                before = prev;
                ++have;
                h = std::min(step, 2 * h);
            }
            prev = {wb, q, b.y};
            first = false;
        }
    }
    c.points.assign(sides[1].rbegin(), sides[1].rend());
    c.points.insert(c.points.end(), sides[0].begin(), sides[0].end());
    c.end = ends[1] + " / " + ends[0];
    return c;
}

BifCurve continue_doubling_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                                 double lo, double hi, double step, const Tolerances& sim) {
    if (second == ContParam::Omega) throw std::invalid_argument("a doubling curve needs a second parameter besides omega");
    if (!(step > 0) || !(hi > lo)) throw std::invalid_argument("a doubling curve needs lo < hi and a positive step");
    BifCurve c;
    c.second = second;
    c.period = period;
    Params work = p;
    double& q_ref = second == ContParam::XI ? work.xI : work.m0e;
    const double q0 = q_ref;
    std::vector<CurvePoint> sides[2];
    std::string ends[2];
    for (int side = 0; side < 2; ++side) {
        const double dir = side == 0 ? 1.0 : -1.0;
        std::vector<CurvePoint>& pts = sides[side];
        // The known point starts both sides (it is kept once, on the upward side).
        CurvePoint prev{omega0, q0, y0}, before = prev;
        int have = 1;
        double h = step;
        bool first = side == 0;   // the known point is located again once, on the upward side
        while (true) {
            const double q = first ? q0 : prev.q + dir * h;
            if (q > hi + 1e-12 * std::abs(hi) || q < lo - 1e-12 * std::abs(lo)) {
                ends[side] = std::string(cont_param_name(second)) + " range";
                break;
            }
            q_ref = q;
            // Predictor: the last two points extrapolated (the first step: the last point).
            double w = prev.omega;
            Vec2 y = prev.y;
            if (have >= 2 && prev.q != before.q) {
                const double f = (q - prev.q) / (prev.q - before.q);
                w = prev.omega + f * (prev.omega - before.omega);
                y = prev.y + f * (prev.y - before.y);
            }
            // Secant on mu(omega) + 1 = 0, from w and w + 1e-3.
            double wa = w, wb = w + 1e-3;
            Probe a = probe(work, wa, y, period, sim), b = probe(work, wb, std::isfinite(a.mu) ? a.y : y, period, sim);
            bool ok = false;
            for (int it = 0; it < 20 && std::isfinite(a.mu) && std::isfinite(b.mu) && b.mu != a.mu; ++it) {
                const double wn = wb - (b.mu + 1.0) * (wb - wa) / (b.mu - a.mu);
                if (!std::isfinite(wn) || std::abs(wn - w) > 0.5) break;   // ran off: no doubling near here
                a = b;
                wa = wb;
                wb = wn;
                b = probe(work, wb, a.y, period, sim);
                if (std::abs(wb - wa) < 1e-7 && std::isfinite(b.mu)) {
                    ok = true;
                    break;
                }
            }
            if (!ok) {
                // A step too long for the predictor (the doubling moves fast in m0e): shorter, down to step / 64.
                if (!first && h > step / 64) {
                    h *= 0.5;
                    continue;
                }
                ends[side] = "doubling lost near " + std::string(cont_param_name(second)) + " = " + std::to_string(q);
                break;
            }
            pts.push_back({wb, q, b.y});
            if (!first) {
                before = prev;
                ++have;
                h = std::min(step, 2 * h);
            }
            prev = {wb, q, b.y};
            first = false;
        }
    }
    c.points.assign(sides[1].rbegin(), sides[1].rend());
    c.points.insert(c.points.end(), sides[0].begin(), sides[0].end());
    c.end = ends[1] + " / " + ends[0];
    return c;
}

}  // namespace impactlab::analysis
