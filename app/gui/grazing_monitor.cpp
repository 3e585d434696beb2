#include "grazing_monitor.hpp"

#include <algorithm>

namespace impactlab::gui {

namespace {
// Bisection for the instant in [a, b] where f changes sign (f(a), f(b) of opposite signs): 50 halvings
// take a millisecond step below 1e-18 s, far under anything shown.
template <class F>
double root(F&& f, double a, double b) {
    double fa = f(a);
    for (int i = 0; i < 50; ++i) {
        const double m = 0.5 * (a + b), fm = f(m);
        if ((fm > 0) == (fa > 0)) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    return 0.5 * (a + b);
}
}  // namespace

void GrazingMonitor::reset() {
    started_ = false;
    in_contact_ = false;
    open();
}

void GrazingMonitor::open() {
    x_max_ = -std::numeric_limits<double>::infinity();
    v_impact_ = std::numeric_limits<double>::quiet_NaN();
    penetration_ = 0;
    impacts_ = 0;
}

void GrazingMonitor::on_piece(const Piece& piece, double xI, bool compliant) {
    if (!piece.step) {   // held at the bumper (regimes II, III)
        x_max_ = std::max(x_max_, piece.x_hold);
        in_contact_ = false;
        return;
    }
    const Vec2 y0 = piece.at(piece.t0), y1 = piece.at(piece.t1);
    double top = std::max(y0[0], y1[0]);
    // A turning point inside the piece (v from + to -): the dense output's maximum of x.
    if (y0[1] > 0 && y1[1] < 0) {
        const double tm = root([&](double t) { return piece.at(t)[1]; }, piece.t0, piece.t1);
        top = std::max(top, piece.at(tm)[0]);
    }
    x_max_ = std::max(x_max_, top);
    if (!compliant) return;
    // The compliant bumper: a contact begins where x rises through xI (the simulator restarts there, so
    // this is mostly the piece's first instant); its entry velocity and depth are the monitor's.
    if (top > xI) {
        penetration_ = std::max(penetration_, top - xI);
        if (!in_contact_ && y0[0] <= xI) {
            const double te = root([&](double t) { return piece.at(t)[0] - xI; }, piece.t0, piece.t1);
            v_impact_ = piece.at(te)[1];
            ++impacts_;
        } else if (!in_contact_ && y0[0] > xI) {   // already inside at the start (moved there): count it
            v_impact_ = y0[1];
            ++impacts_;
        }
    }
    in_contact_ = y1[0] > xI;
}

void GrazingMonitor::on_impact(const ImpactEvent& ev) {
    v_impact_ = ev.v_minus;
    ++impacts_;
}

bool GrazingMonitor::on_section(double t, double xI, Period& out) {
    const bool whole = started_ && std::isfinite(x_max_);
    if (whole) {
        out = Period{};
        out.t = t;
        out.x_max = x_max_;
        out.distance = xI - x_max_;
        out.v_impact = v_impact_;
        out.penetration = penetration_;
        out.impacts = impacts_;
    }
    started_ = true;
    open();
    return whole;
}

}  // namespace impactlab::gui
