#include "grazing_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "impactlab/equilibria.hpp"

namespace impactlab::gui {

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
    if (const double tm = turning_point(piece); !std::isnan(tm)) top = std::max(top, piece.at(tm)[0]);
    x_max_ = std::max(x_max_, top);
    if (!compliant) return;
    // The compliant bumper: a contact begins where x rises through xI (the simulator restarts there, so
    // this is mostly the piece's first instant); its entry velocity and depth are the monitor's.
    if (top > xI) {
        penetration_ = std::max(penetration_, top - xI);
        if (!in_contact_ && y0[0] <= xI) {
            // The entry: x - xI from <= 0 to > 0 (a piece starting on the bumper's face enters at t0).
            const double te = bisect([&](double t) { return !(piece.at(t)[0] - xI > 0); }, piece.t0, piece.t1);
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
