// A period doubling or a grazing continued in two parameters (omega and xI or m0e): natural-parameter steps in
// the second parameter, the point's omega found again at each by a secant on its test (the crossing
// multiplier, or the bumperless orbit's largest x minus xI).
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "impactlab/analysis.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::analysis {

namespace {

// A curve's test at one omega (NaN where the orbit is lost) and the orbit's section point there.
struct Test { double value = NAN; Vec2 y = Vec2::Zero(); };

// The real multiplier nearest -1 of the period-k orbit at omega near y (NaN when complex or not found).
Test probe(const Params& p, double omega, const Vec2& guess, int period, const Tolerances& sim) {
    OrbitOptions oo;
    oo.period = period;
    oo.sim = sim;
    oo.max_iterations = 12;
    Test r;
    try {
        const Orbit o = find_orbit(p, omega, guess, oo);
        if (!o.converged || scaled_norm(o.y - guess) > 0.2) return r;
        if (o.floquet.mu[0].imag() != 0.0) return r;
        const double a = o.floquet.mu[0].real(), b = o.floquet.mu[1].real();
        r.value = std::abs(a + 1) < std::abs(b + 1) ? a : b;
        r.y = o.y;
    } catch (const std::exception&) {
    }
    return r;
}

// The period-k orbit of the rig without its bumper at omega near y, and its largest x minus xI (NaN if not
// found): zero at a grazing, smooth through it (the bumper's law never enters).
Test gap_probe(const Params& p, double omega, const Vec2& guess, int period, const Tolerances& sim) {
    Params f = p;
    f.impact = find_impact("none");
    OrbitOptions oo;
    oo.period = period;
    oo.sim = sim;
    oo.max_iterations = 12;
    Test r;
    try {
        const Orbit o = find_orbit(f, omega, guess, oo);
        if (!o.converged || scaled_norm(o.y - guess) > 0.2) return r;
        double x_max = 0;
        peak_phase(f, omega, o.y, period, sim, &x_max);
        r.value = (x_max - p.xI) / kXScale;
        r.y = o.y;
    } catch (const std::exception&) {
    }
    return r;
}

// The fold's extended system at fixed second parameter: (P^k(y) - y scaled, det(M - I)) = 0 in (x, v, omega),
// by Newton with the derivatives by forward differences of the map (its own monodromy gives d/dy of the
// first two; det(M - I) needs the map's second derivative, which differences of M give).
// Where a curve's point lies at one value of the second parameter (a fold, a grazing, a doubling).
struct Located { bool ok = false; double omega = 0; Vec2 y = Vec2::Zero(); };

Located fold_newton(const Params& p, double omega, Vec2 y, int period, const Tolerances& sim) {
    Located r;
    auto eval = [&](double w, const Vec2& yy, Eigen::Vector3d& F, Mat2& M) {
        const MapResult m = poincare_map(p, w, yy, period, true, sim);
        M = m.M;
        F = Eigen::Vector3d((m.y[0] - yy[0]) / kXScale, (m.y[1] - yy[1]) / kVScale, (m.M - Mat2::Identity()).determinant());
        return F.allFinite();
    };
    int settled = 0;   // Newton steps in a row that left omega where it was
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
            // Near a grazing the monodromy's noise keeps det(M - I) at ~3e-5 (A1G, xI = -3.5 mm) while omega
            // stands still: an orbit that is a fixed point, with omega's step below 1e-9 twice running and the
            // determinant within its noise, is the fold.
            settled = std::abs(d[2]) < 1e-9 && std::abs(F[0]) < 1e-9 && std::abs(F[1]) < 1e-9 && std::abs(F[2]) / ds < 1e-3 ? settled + 1 : 0;
            if (settled >= 2) {
                r = {true, omega, y};
                return r;
            }
        }
    } catch (const std::exception&) {
    }
    return r;
}

// A secant in omega on test(omega) = target from w and w + 1e-3, each orbit started from the last one's;
// it gives up after `iterations` or where it runs more than `run_off` [rad/s] from w.
template <class TestFn>
Located secant(double w, const Vec2& y, double target, int iterations, double run_off, double tol, const TestFn& test) {
    double wa = w, wb = w + 1e-3;
    Test a = test(wa, y), b = test(wb, std::isfinite(a.value) ? a.y : y);
    for (int it = 0; it < iterations && std::isfinite(a.value) && std::isfinite(b.value) && b.value != a.value; ++it) {
        const double wn = wb - (b.value - target) * (wb - wa) / (b.value - a.value);
        if (!std::isfinite(wn) || std::abs(wn - w) > run_off) break;   // ran off: none near here
        a = b;
        wa = wb;
        wb = wn;
        b = test(wb, a.y);
        if (std::abs(wb - wa) < tol && std::isfinite(b.value)) return Located{true, wb, b.y};
    }
    return Located{};
}

using Locate = std::function<Located(const Params& work, double omega, const Vec2& y)>;

// The curves' one following loop: natural-parameter steps in the second parameter from its model value to
// each end of [lo, hi], the point located again at each from the last two points extrapolated. A step the
// predictor cannot bridge is halved, down to step / 64. The cancel is looked at before every step.
// What the last point of a fold or doubling curve was near where the next is lost: a rigid bumper's grazing (an
// impact of its orbit slower than 1 cm/s, where it meets the nonsmooth fold and changes type), else "".
std::string lost_near(const Params& work, const CurvePoint& last, int period, const Tolerances& sim) {
    if (!work.rigid()) return "";
    try {
        const MapResult r = poincare_map(work, last.omega, last.y, period, false, sim);
        if (r.impacts == 0 || !(r.min_impact_speed < 0.01)) return "";
        char buf[200];
        std::snprintf(buf, sizeof buf, "its last orbit's slowest impact is %.2g m/s: it runs into the grazing, where the "
                      "smooth and the nonsmooth fold meet and the curve changes type", r.min_impact_speed);
        return buf;
    } catch (const std::exception&) {
        return "";
    }
}

BifCurve follow_curve(const Params& p, BifKind kind, ContParam second, double omega0, const Vec2& y0, int period,
                      double lo, double hi, double step, Progress* progress, const Locate& locate, const Tolerances& sim) {
    BifCurve c;
    c.kind = kind;
    c.second = second;
    c.period = period;
    Params work = p;
    double& q_ref = second == ContParam::XI ? work.xI : work.m0e;
    const double q0 = q_ref;
    std::vector<CurvePoint> sides[2];
    CurveEnd* ends[2] = {&c.above, &c.below};
    bool ended[2] = {false, false};
    double covered[2] = {0, 0};   // how far each side has come [the second parameter's unit]
    for (int side = 0; side < 2 && !c.cancelled; ++side) {
        const double dir = side == 0 ? 1.0 : -1.0;
        std::vector<CurvePoint>& pts = sides[side];
        // The known point starts both sides (it is kept once, on the upward side).
        CurvePoint prev{omega0, q0, y0}, before = prev;
        int have = 1;
        double h = step;
        bool first = side == 0;   // the known point is located again once, on the upward side
        while (true) {
            if (progress && progress->cancel.load(std::memory_order_relaxed)) {
                c.cancelled = true;
                *ends[side] = {CurveStop::Cancelled, 0.0, {}};
                ended[side] = true;
                break;
            }
            const double q = first ? q0 : prev.q + dir * h;
            if (q > hi + 1e-12 * std::abs(hi) || q < lo - 1e-12 * std::abs(lo)) {
                *ends[side] = {CurveStop::Range, 0.0, {}};
                ended[side] = true;
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
            const Located at = locate(work, w, y);
            if (!at.ok) {
                // A step too long for the predictor (a doubling moves fast in m0e): shorter.
                if (!first && h > step / 64) {
                    h *= 0.5;
                    continue;
                }
                q_ref = prev.q;
                *ends[side] = {CurveStop::Lost, q, kind == BifKind::Grazing ? "" : lost_near(work, prev, period, sim)};
                ended[side] = true;
                break;
            }
            pts.push_back({at.omega, q, at.y});
            if (!first) {
                before = prev;
                ++have;
                h = std::min(step, 2 * h);
            }
            prev = {at.omega, q, at.y};
            first = false;
            covered[side] = std::abs(q - q0);
            if (progress && hi > lo)
                progress->fraction.store(std::min(1.0, (covered[0] + covered[1]) / (hi - lo)), std::memory_order_relaxed);
        }
    }
    for (int side = 0; side < 2; ++side)   // the side a cancel kept from starting
        if (!ended[side]) *ends[side] = {CurveStop::Cancelled, 0.0, {}};
    c.points.assign(sides[1].rbegin(), sides[1].rend());
    c.points.insert(c.points.end(), sides[0].begin(), sides[0].end());
    c.end = curve_ends_name(c);
    return c;
}

void check_curve(const char* what, ContParam second, double lo, double hi, double step) {
    if (second == ContParam::Omega)
        throw std::invalid_argument(std::string("a ") + what + " curve needs a second parameter besides omega");
    if (!(step > 0) || !(hi > lo)) throw std::invalid_argument(std::string("a ") + what + " curve needs lo < hi and a positive step");
}

}  // namespace

std::string curve_end_name(const BifCurve& c, const CurveEnd& e) {
    switch (e.stop) {
    case CurveStop::Range: return std::string(sweep_param_name(c.second)) + " range";
    case CurveStop::Lost: {
        const char* what = c.kind == BifKind::Fold ? "fold" : c.kind == BifKind::Grazing ? "grazing" : "doubling";
        return std::string(what) + " lost near " + sweep_param_name(c.second) + " = " + std::to_string(e.q) +
               (e.why.empty() ? "" : " (" + e.why + ")");
    }
    case CurveStop::Cancelled: return "cancelled";
    case CurveStop::AxisEnd: return "at the axis' end";
    }
    return "?";
}

std::string curve_ends_name(const BifCurve& c) { return curve_end_name(c, c.below) + " / " + curve_end_name(c, c.above); }

BifCurve continue_fold_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period, double lo,
                             double hi, double step, const Tolerances& sim, Progress* progress) {
    check_curve("fold", second, lo, hi, step);
    return follow_curve(p, BifKind::Fold, second, omega0, y0, period, lo, hi, step, progress,
                        [&](const Params& work, double w, const Vec2& y) {
                            const Located at = fold_newton(work, w, y, period, sim);
                            return at.ok && scaled_norm(at.y - y) <= 0.5 ? at : Located{};
                        }, sim);
}

BifCurve continue_grazing_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period, double lo,
                                double hi, double step, const Tolerances& sim, Progress* progress) {
    check_curve("grazing", second, lo, hi, step);
    if (!p.has_bumper()) throw std::invalid_argument("a grazing curve needs a bumper");
    return follow_curve(p, BifKind::Grazing, second, omega0, y0, period, lo, hi, step, progress,
                        [&](const Params& work, double w, const Vec2& y) {
                            // Zero gap: the bumperless orbit's largest x at xI.
                            return secant(w, y, 0.0, 30, 1.0, 1e-8, [&](double wt, const Vec2& yt) {
                                return gap_probe(work, wt, yt, period, sim);
                            });
                        }, sim);
}

BifCurve continue_doubling_curve(const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                                 double lo, double hi, double step, const Tolerances& sim, Progress* progress) {
    check_curve("doubling", second, lo, hi, step);
    // The multiplier is smooth only far below the orbit's tolerance: at rtol 1e-10 it jitters by 5e-5 (A1C's
    // first doubling) to 3e-3 (an impacting orbit), which put the curve's points 2e-6 and 1.4e-4 rad/s off
    // the crossing of Newton's orbits at 1e-12. The secant runs at rtol / 100, as the continuation's refinement.
    Tolerances fine = sim;
    fine.rtol = std::max(sim.rtol * 0.01, 1e-13);
    return follow_curve(p, BifKind::PeriodDoubling, second, omega0, y0, period, lo, hi, step, progress,
                        [&](const Params& work, double w, const Vec2& y) {
                            // The multiplier nearest -1 at -1.
                            return secant(w, y, -1.0, 20, 0.5, 1e-7, [&](double wt, const Vec2& yt) {
                                return probe(work, wt, yt, period, fine);
                            });
                        }, fine);
}

BifCurve continue_curve(BifKind kind, const Params& p, ContParam second, double omega0, const Vec2& y0, int period,
                        double lo, double hi, double step, const Tolerances& sim, Progress* progress) {
    switch (kind) {
    case BifKind::PeriodDoubling: return continue_doubling_curve(p, second, omega0, y0, period, lo, hi, step, sim, progress);
    case BifKind::Grazing: return continue_grazing_curve(p, second, omega0, y0, period, lo, hi, step, sim, progress);
    case BifKind::Fold: return continue_fold_curve(p, second, omega0, y0, period, lo, hi, step, sim, progress);
    default: throw std::invalid_argument(std::string("no two-parameter curve of a ") + bif_kind_name(kind));
    }
}

}  // namespace impactlab::analysis
