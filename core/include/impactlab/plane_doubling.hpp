// A period doubling over a parameter plane (omega, xI) or (omega, m0e), found and followed without a
// starting point from the user: the period-1 branch is continued in omega at the model's own second
// parameter until its first period doubling, which continue_doubling_curve then follows along the plane's
// second axis. The visualiser's plane view and `impactlab scan --doubling-from auto` both call it.
#pragma once

#include <string>

#include "impactlab/analysis.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::analysis {

struct PlaneDoublingSpec {
    ContParam second = ContParam::XI;   // the plane's y axis: xI [m] or m0e [kg m]
    double omega_lo = 5, omega_hi = 25; // where the first period doubling is looked for [rad/s]
    double lo = -0.01, hi = 0.01;       // the second parameter's range
    double step = 0.0005;               // its step along the curve
};
struct PlaneDoubling {
    bool found = false;                 // a period-1 doubling lay in [omega_lo, omega_hi]
    double omega0 = 0;                  // where it was found, at the model's own second parameter [rad/s]
    Vec2 y0 = Vec2::Zero();             // its section point [m, m/s]
    BifCurve curve;                     // ordered by the second parameter
    bool cancelled = false;
    double seconds = 0;                 // wall time
    std::string note;                   // why nothing was found, or why the curve ended
};
// Progress and cancel are the continuation's (a cancel stops it); the curve's two sides follow it, and a
// cancel is seen between them (the curve's own steps do not look at it). Any thread.
PlaneDoubling doubling_over_plane(const Params& p, const PlaneDoublingSpec& spec, Progress* progress = nullptr);

}  // namespace impactlab::analysis
