// A two-parameter curve (a period doubling, a fold or a grazing) over a parameter plane (omega, xI) or
// (omega, m0e), found and followed without a starting point from the user: the period-1 branch is
// continued in omega at the model's own second parameter until its first point of that kind, which
// continue_doubling_curve (continue_fold_curve, continue_grazing_curve) then follows along the plane's
// second axis. The visualiser's plane view and `impactlab scan --doubling-from auto` (--grazing-from,
// --fold-from) both call it.
#pragma once

#include <string>

#include "impactlab/analysis.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::analysis {

struct PlaneCurveSpec {
    ContParam second = ContParam::XI;   // the plane's y axis: xI [m] or m0e [kg m]
    double omega_lo = 5, omega_hi = 25; // where the first point of the kind is looked for [rad/s]
    double lo = -0.01, hi = 0.01;       // the second parameter's range
    double step = 0.0005;               // its step along the curve
    BifKind kind = BifKind::PeriodDoubling;   // PeriodDoubling, Fold or Grazing
};
struct PlaneCurve {
    bool found = false;                 // a period-1 point of the kind lay in [omega_lo, omega_hi]
    double omega0 = 0;                  // the curve's point at the model's own second parameter [rad/s]
                                        // (where it was found, located again by the curve's own test)
    Vec2 y0 = Vec2::Zero();             // its section point [m, m/s]
    BifCurve curve;                     // ordered by the second parameter
    bool cancelled = false;
    double seconds = 0;                 // wall time
    std::string note;                   // why nothing was found, or why the curve ended
};
// The curve of spec.kind from the known point (omega0, y0) of the period-k orbit at the model's own second
// parameter (moved onto the plane's axis if it lies off it), as `impactlab scan --grazing-from` follows it.
// A cancel is seen between the curve's steps. Any thread.
PlaneCurve curve_over_plane_from(const Params& p, const PlaneCurveSpec& spec, double omega0, const Vec2& y0, int period,
                                 Progress* progress = nullptr);
// The same from the first period-1 point of spec.kind over [omega_lo, omega_hi]. Progress is the
// continuation's, then the curve's; a cancel stops either. Any thread.
PlaneCurve curve_over_plane(const Params& p, const PlaneCurveSpec& spec, Progress* progress = nullptr);

}  // namespace impactlab::analysis
