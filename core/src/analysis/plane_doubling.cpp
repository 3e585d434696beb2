#include "impactlab/plane_doubling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace impactlab::analysis {

namespace {

double second_of(const Params& p, ContParam c) { return c == ContParam::M0e ? p.m0e : p.xI; }

const char* kind_word(BifKind k) {
    if (k == BifKind::NeimarkSacker) throw std::invalid_argument("no two-parameter curve of a Neimark-Sacker point");
    return k == BifKind::Fold ? "fold" : k == BifKind::Grazing ? "grazing" : "doubling";
}

// The model at its own second parameter, moved onto the plane's axis if it lies off it.
Params on_plane(const Params& p, const PlaneCurveSpec& spec, PlaneCurve& out) {
    const double lo = std::min(spec.lo, spec.hi), hi = std::max(spec.lo, spec.hi);
    const double q = second_of(p, spec.second), q0 = std::clamp(q, lo, hi);
    Params base = p;
    (spec.second == ContParam::M0e ? base.m0e : base.xI) = q0;
    if (q0 != q) out.note = "the model's value lies off the plane: the curve starts at its edge; ";
    return base;
}

PlaneCurve follow(const Params& base, const PlaneCurveSpec& spec, double omega0, const Vec2& y0, int period,
                  Progress* progress, PlaneCurve out) {
    const double lo = std::min(spec.lo, spec.hi), hi = std::max(spec.lo, spec.hi);
    const double q0 = second_of(base, spec.second);
    out.omega0 = omega0;
    out.y0 = y0;
    if (progress) progress->fraction.store(0.0, std::memory_order_relaxed);
    out.curve = continue_curve(spec.kind, base, spec.second, omega0, y0, period, lo, hi, spec.step, analysis_tolerances(), progress);
    out.cancelled = out.curve.cancelled;
    // The start is the curve's own point at q0, located again by the curve's test (the continuation's value
    // comes from another test, 2e-6 .. 1e-5 rad/s off at a doubling): what is printed as the start is on it.
    for (const CurvePoint& c : out.curve.points)
        if (c.q == q0) {
            out.omega0 = c.omega;
            out.y0 = c.y;
        }
    // A side that starts at the axis' end says so (the curve functions would call it the range's end); a
    // point lost there, or a cancel, keeps its own words.
    if (!(q0 > lo) && out.curve.below.stop == CurveStop::Range) out.curve.below.stop = CurveStop::AxisEnd;
    if (!(hi > q0) && out.curve.above.stop == CurveStop::Range) out.curve.above.stop = CurveStop::AxisEnd;
    out.curve.end = curve_ends_name(out.curve);
    out.note += out.curve.end;
    return out;
}

}  // namespace

PlaneCurve curve_over_plane_from(const Params& p, const PlaneCurveSpec& spec, double omega0, const Vec2& y0, int period,
                                 Progress* progress) {
    const auto t0 = std::chrono::steady_clock::now();
    PlaneCurve out;
    out.curve.second = spec.second;
    out.curve.kind = spec.kind;
    const Params base = on_plane(p, spec, out);
    out.found = true;
    out = follow(base, spec, omega0, y0, period, progress, std::move(out));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress) progress->fraction.store(1.0, std::memory_order_relaxed);
    return out;
}

PlaneCurve curve_over_plane(const Params& p, const PlaneCurveSpec& spec, Progress* progress) {
    const auto t0 = std::chrono::steady_clock::now();
    PlaneCurve out;
    out.curve.second = spec.second;
    out.curve.kind = spec.kind;
    auto done = [&] {
        out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (progress) progress->fraction.store(1.0, std::memory_order_relaxed);
        return out;
    };
    const char* word = kind_word(spec.kind);   // before the continuation: a kind without a curve throws
    const Params base = on_plane(p, spec, out);
    // The period-1 branch alone (no switching at the doublings): its first point of the kind is the start.
    ContinuationSpec cs;
    cs.param = ContParam::Omega;
    cs.lo = std::max(spec.omega_lo, 0.5);   // near omega = 0 the arclength steps crawl (as the GUI's overlay)
    cs.hi = std::max(spec.omega_hi, cs.lo + 0.5);
    cs.start = cs.lo;
    cs.period = 1;
    cs.max_period = 1;
    const ContinuationResult r = continue_orbits(base, cs, progress);
    if (r.cancelled || (progress && progress->cancel.load(std::memory_order_relaxed))) {
        out.cancelled = true;
        out.curve.cancelled = true;
        out.note += "cancelled while looking for the start";
        return done();
    }
    const BifPoint* first = nullptr;
    for (const BifPoint& q : r.points)
        if (q.kind == spec.kind && q.period == 1 && (!first || q.param < first->param)) first = &q;
    if (!first) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "no period-1 %s for omega in [%.3g, %.3g] rad/s", word, cs.lo, cs.hi);
        out.note += buf;
        return done();
    }
    out.found = true;
    out = follow(base, spec, first->param, first->y, 1, progress, std::move(out));
    return done();
}

}  // namespace impactlab::analysis
