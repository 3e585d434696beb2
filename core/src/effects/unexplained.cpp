// Generic smooth forces for a residual that no named effect explains (impactlab fit's last resort).
// Each names the variable the missing force depends on:
//   unexplained_x        F = S(x)                    S a cubic B-spline on [lo, hi], 6 coefficients [N]
//   unexplained_v        F = S(v)                    (held constant outside [lo, hi])
//   unexplained_x_signv  F = S(x) v/sqrt(v^2+eps^2)  (a position-dependent dry friction or hysteresis)
//   unexplained_x_v      F = S(x) v                  (a damping that depends on position) [S in N s/m]
//   unexplained_phi      F = sum_k a_k cos(k phi) + b_k sin(k phi), k = 1..3 [N]
//   unexplained_x_local  F = S(x) over a narrow range where the residual has a feature (a rail defect)
//   unexplained_v_local  F = S(v) likewise (a friction bump near v = 0)
// Parameters of the spline laws: lo, hi (the range, in the variable's unit), c1..c6 [N]. The global laws
// span the data; the local ones the feature identify/features.cpp finds, and are offered only where it finds one.
#include <algorithm>
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {

constexpr double kEps = 1e-6;   // [m/s], the model's friction smoothing

// S(s) and dS/ds: 6 uniform B-splines centred at lo - h, lo, ..., hi + h with h = (hi - lo) / 3. At any s only
// the four around its interval are nonzero; they are evaluated in closed form (the fit's inner loop): the
// uniform cubic B-spline 2/3 - u^2 + |u|^3/2 for |u| <= 1, (2 - |u|)^3/6 for 1 < |u| < 2.
struct Value { double S, dS; };
Value spline(const double* p, double s) {
    const double lo = p[0], hi = p[1];
    if (!(hi > lo)) return {0.0, 0.0};
    // A state that is not a number (a trial model the integrator cannot follow) has no interval: its force is
    // NaN, which stalls the simulation, never an index out of the coefficients.
    if (std::isnan(s)) return {s, s};
    const double h = (hi - lo) / 3.0, ih = 1.0 / h;
    const bool inside = s > lo && s < hi;
    const double t = (std::clamp(s, lo, hi) - lo) * ih;   // in [0, 3]
    const int i = std::clamp(static_cast<int>(t), 0, 2);
    const double f = t - i, g = 1.0 - f, f2 = f * f, g2 = g * g;
    // Basis i .. i+3 at u = f + 1, f, f - 1, f - 2 (the kernel above, piece by piece).
    const double b0 = g2 * g / 6.0, b1 = 2.0 / 3.0 - f2 + 0.5 * f2 * f, b2 = 2.0 / 3.0 - g2 + 0.5 * g2 * g, b3 = f2 * f / 6.0;
    const double d0 = -0.5 * g2, d1 = -2.0 * f + 1.5 * f2, d2 = 2.0 * g - 1.5 * g2, d3 = 0.5 * f2;
    const double* c = p + 2 + i;
    const double S = c[0] * b0 + c[1] * b1 + c[2] * b2 + c[3] * b3;
    const double dS = (c[0] * d0 + c[1] * d1 + c[2] * d2 + c[3] * d3) * ih;
    return {S, inside ? dS : 0.0};
}

EffectForce force_x(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.x);
    return {s.S, s.dS, 0.0, 0.0};
}

EffectForce force_v(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.v);
    return {s.S, 0.0, s.dS, 0.0};
}

EffectForce force_x_signv(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.x);
    const double s2 = c.v * c.v + kEps * kEps, inv = 1.0 / std::sqrt(s2);
    const double sg = c.v * inv, dsg = kEps * kEps * inv / s2;
    return {s.S * sg, s.dS * sg, s.S * dsg, 0.0};
}

EffectForce force_x_v(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.x);
    return {s.S * c.v, s.dS * c.v, s.S, 0.0};
}

EffectForce force_phi(const double* p, const ForceContext& c) {
    double F = 0.0, dF = 0.0;
    for (int k = 1; k <= 3; ++k) {
        const double a = p[2 * (k - 1)], b = p[2 * (k - 1) + 1];
        const double cs = std::cos(k * c.phi), sn = std::sin(k * c.phi);
        F += a * cs + b * sn;
        dF += k * (-a * sn + b * cs);
    }
    return {F, 0.0, 0.0, dF * c.omega};
}



enum class Var { X, V, XSignV, XV, Phi };

// Where the fitted force is largest, and the sentence that names the variable it depends on.
std::string describe_var(Var var, EffectForceFn force, const double* p, const EffectReportContext& c) {
    const char* name = var == Var::X ? "the position x" : var == Var::V ? "the velocity v" : var == Var::Phi ? "the unbalance angle phi"
                                                                                                      : "the position x, with the sign of v";
    const bool periodic = var == Var::Phi;
    const double lo = periodic ? 0.0 : p[0], hi = periodic ? 2 * kPi : p[1];
    double best = 0, at = lo;
    for (int k = 0; k <= 200; ++k) {
        const double q = lo + (hi - lo) * k / 200.0;
        ForceContext ctx{0.0, 0.0, 1.0, 0.0, 0.0, 0.0, c.model ? c.model->m0e : 0.0, c.model ? c.model->xI : 0.0};
        if (var == Var::XV) ctx.v = 1.0;   // S(x) itself: the damping coefficient at x
        if (var == Var::V) ctx.v = q;
        else if (periodic) ctx.phi = q;
        else ctx.x = q;
        const double F = force(p, ctx).F;
        if (std::abs(F) > std::abs(best)) {
            best = F;
            at = q;
        }
    }
    // A plain Duffing model in the record's own units says its numbers in them, not in SI.
    const bool si = c.rig;
    const std::string where = var == Var::V ? "v = " + fmt("%.3g", at) + (si ? " m/s" : " (data units / s)")
                              : periodic    ? "phi = " + fmt("%.2f", at) + " rad"
                                            : "x = " + (si ? fmt("%.3g", at * 1e3) + " mm" : fmt("%.3g", at) + " (data units)");
    if (var == Var::XV)
        return "no library effect explains this part of the residual; a damping force S(x) v that depends on the position does, "
               "its coefficient S up to " + fmt("%.2g", best) + (si ? " N s/m" : " (model force units per data unit / s)") + " at " + where +
               ": the missing physics is a damping that varies along the rail";
    return std::string("no library effect explains this part of the residual; a smooth force of ") + name + " does, up to " +
           fmt("%.2g", best) + (si ? " N" : " model force units") + " at " + where + (var == Var::XSignV ? " (for v > 0; reversed for v < 0)" : "") +
           ": the missing physics depends on " + name;
}

std::string describe_x(const double* p, const double*, const EffectReportContext& c) { return describe_var(Var::X, force_x, p, c); }
std::string describe_v(const double* p, const double*, const EffectReportContext& c) { return describe_var(Var::V, force_v, p, c); }
std::string describe_x_signv(const double* p, const double*, const EffectReportContext& c) {
    return describe_var(Var::XSignV, force_x_signv, p, c);
}
std::string describe_x_v(const double* p, const double*, const EffectReportContext& c) { return describe_var(Var::XV, force_x_v, p, c); }
std::string describe_phi(const double* p, const double*, const EffectReportContext& c) { return describe_var(Var::Phi, force_phi, p, c); }

// The spline's range: where the data go (in the variable of the law).
void start_x(double* p, const EffectStartContext& c) {
    p[0] = c.x_lo;
    p[1] = c.x_hi > c.x_lo ? c.x_hi : c.x_lo + 1e-6;
}
void start_v(double* p, const EffectStartContext& c) {
    p[0] = c.v_lo;
    p[1] = c.v_hi > c.v_lo ? c.v_hi : c.v_lo + 1e-6;
}
// The feature's window, narrowed by the trial value (the screening keeps the width that explains most): the
// window found carries the residual's blur, and six knots follow a narrow feature only if they sit close.
void window(double* p, double lo, double hi, double scale) {
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo) * (scale > 0 ? scale : 1.0);
    p[0] = mid - half;
    p[1] = mid + half;
}
void start_x_local(double* p, const EffectStartContext& c) { window(p, c.x_feature_lo, c.x_feature_hi, c.start); }
void start_v_local(double* p, const EffectStartContext& c) { window(p, c.v_feature_lo, c.v_feature_hi, c.start); }

constexpr const char* kSplineNames[] = {"lo", "hi", "c1", "c2", "c3", "c4", "c5", "c6"};
using Names = std::array<const char*, kMaxLawParams>;
constexpr Names kSpline{kSplineNames[0], kSplineNames[1], kSplineNames[2], kSplineNames[3],
                        kSplineNames[4], kSplineNames[5], kSplineNames[6], kSplineNames[7]};
constexpr Names kSplineXUnits{"m", "m", "N", "N", "N", "N", "N", "N"};
constexpr Names kSplineVUnits{"m/s", "m/s", "N", "N", "N", "N", "N", "N"};
constexpr Names kSplineXVUnits{"m", "m", "N s/m", "N s/m", "N s/m", "N s/m", "N s/m", "N s/m"};

EffectLaw spline_law(const char* id, const char* meaning, const Names& units, EffectForceFn f, EffectDescribeFn d, EffectStartFn st) {
    EffectLaw l{id, meaning, kSpline, units, {0.0}, f};
    l.fit = hint({2, 3, 4, 5, 6, 7}, {1, 1, 1, 1, 1, 1});
    l.fit.generic = true;
    l.describe = d;
    l.start = st;
    return l;
}
// A local law: offered only where the residual has a feature in its variable, tried at three widths of it.
EffectLaw local_law(const char* id, const char* meaning, const Names& units, EffectForceFn f, EffectDescribeFn d, EffectStartFn st,
                    unsigned needs) {
    EffectLaw l = spline_law(id, meaning, units, f, d, st);
    l.fit.needs = needs;
    l.fit.starts = {0.5, 0.75, 1.0};
    l.fit.n_starts = 3;
    return l;
}
}  // namespace

const EffectLaw& unexplained_x_law() {
    static const EffectLaw law = spline_law("unexplained_x", "a smooth force of the position x that no named effect explains",
                                            kSplineXUnits, force_x, describe_x, start_x);
    return law;
}
const EffectLaw& unexplained_v_law() {
    static const EffectLaw law = spline_law("unexplained_v", "a smooth force of the velocity v that no named effect explains",
                                            kSplineVUnits, force_v, describe_v, start_v);
    return law;
}
const EffectLaw& unexplained_x_signv_law() {
    static const EffectLaw law =
        spline_law("unexplained_x_signv", "a force S(x) sign(v) (position-dependent friction) no named effect explains", kSplineXUnits,
                   force_x_signv, describe_x_signv, start_x);
    return law;
}
const EffectLaw& unexplained_x_v_law() {
    static const EffectLaw law = spline_law("unexplained_x_v", "a damping force S(x) v (a damping that varies along the rail) no named effect explains",
                                            kSplineXVUnits, force_x_v, describe_x_v, start_x);
    return law;
}
const EffectLaw& unexplained_x_local_law() {
    static const EffectLaw law = local_law("unexplained_x_local", "a force over a narrow range of x (a defect of the rail) no named effect explains",
                                           kSplineXUnits, force_x, describe_x, start_x_local, FitNeeds::XFeature);
    return law;
}
const EffectLaw& unexplained_v_local_law() {
    static const EffectLaw law = local_law("unexplained_v_local", "a force over a narrow range of v (a friction bump) no named effect explains",
                                           kSplineVUnits, force_v, describe_v, start_v_local, FitNeeds::VFeature);
    return law;
}
const EffectLaw& unexplained_phi_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"unexplained_phi", "a force periodic in the unbalance angle that no named effect explains",
                    {"a1", "b1", "a2", "b2", "a3", "b3", nullptr}, {"N", "N", "N", "N", "N", "N", nullptr}, {0.0}, force_phi};
        l.fit = hint({0, 1, 2, 3, 4, 5}, {1, 1, 1, 1, 1, 1});
        l.fit.generic = true;
        l.fit.needs = FitNeeds::Phi;
        l.describe = describe_phi;
        return l;
    }();
    return law;
}

}  // namespace impactlab::effects
