#include "impactlab/plane_doubling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace impactlab::analysis {

namespace {

double second_of(const Params& p, ContParam c) { return c == ContParam::M0e ? p.m0e : p.xI; }

}  // namespace

PlaneDoubling doubling_over_plane(const Params& p, const PlaneDoublingSpec& spec, Progress* progress) {
    const auto t0 = std::chrono::steady_clock::now();
    PlaneDoubling out;
    out.curve.second = spec.second;
    auto done = [&] {
        out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (progress) progress->fraction.store(1.0, std::memory_order_relaxed);
        return out;
    };
    auto cancelled = [&] { return progress && progress->cancel.load(std::memory_order_relaxed); };
    // The model at its own second parameter, moved onto the plane's axis if it lies off it.
    const double lo = std::min(spec.lo, spec.hi), hi = std::max(spec.lo, spec.hi);
    const double q0 = std::clamp(second_of(p, spec.second), lo, hi);
    Params base = p;
    (spec.second == ContParam::M0e ? base.m0e : base.xI) = q0;
    if (q0 != second_of(p, spec.second)) out.note = "the model's value lies off the plane: the curve starts at its edge; ";
    // The period-1 branch alone (no switching at the doublings): its first doubling is the start.
    ContinuationSpec cs;
    cs.param = ContParam::Omega;
    cs.lo = std::max(spec.omega_lo, 0.5);   // near omega = 0 the arclength steps crawl (as the GUI's overlay)
    cs.hi = std::max(spec.omega_hi, cs.lo + 0.5);
    cs.start = cs.lo;
    cs.period = 1;
    cs.max_period = 1;
    const ContinuationResult r = continue_orbits(base, cs, progress);
    if (r.cancelled || cancelled()) {
        out.cancelled = true;
        return done();
    }
    const BifPoint* pd = nullptr;
    for (const BifPoint& q : r.points)
        if (q.kind == BifKind::PeriodDoubling && q.period == 1 && (!pd || q.param < pd->param)) pd = &q;
    if (!pd) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "no period-1 doubling for omega in [%.3g, %.3g] rad/s", cs.lo, cs.hi);
        out.note += buf;
        return done();
    }
    out.found = true;
    out.omega0 = pd->param;
    out.y0 = pd->y;
    // Each side of q0 apart, so that a cancel is seen between them; each call locates q0 again on its way up.
    BifCurve up, down;
    if (hi > q0) up = continue_doubling_curve(base, spec.second, out.omega0, out.y0, 1, q0, hi, spec.step);
    if (cancelled()) out.cancelled = true;
    else if (q0 > lo) down = continue_doubling_curve(base, spec.second, out.omega0, out.y0, 1, lo, q0, spec.step);
    out.curve.points = up.points;
    for (const CurvePoint& c : down.points)
        if (up.points.empty() || c.q < q0) out.curve.points.push_back(c);   // q0 once
    std::sort(out.curve.points.begin(), out.curve.points.end(), [](const CurvePoint& a, const CurvePoint& b) { return a.q < b.q; });
    // continue_doubling_curve says "<why the lower side ended> / <why the upper side ended>".
    auto side = [](const std::string& e, bool upper) {
        const std::size_t k = e.find(" / ");
        return k == std::string::npos ? e : upper ? e.substr(k + 3) : e.substr(0, k);
    };
    out.curve.end = (q0 > lo ? side(down.end, false) : std::string("at the axis' end")) + " / " +
                    (hi > q0 ? side(up.end, true) : std::string("at the axis' end"));
    out.note += out.curve.end;
    return done();
}

}  // namespace impactlab::analysis
