// How the plots choose what they show, as plain arithmetic (GL-free, unit-tested): an axis fitted to its
// data with pixel margins kept free, the potential plot's energy range, and how long an impact label
// stays on the rig.
#pragma once

namespace impactlab::gui {

// The range of one plot axis that puts the data [lo, hi] (widened to min_span about its centre) inside a
// data area `px` pixels long with margin_lo and margin_hi pixels left free at its two ends: the markers'
// radius off the frame, a label's band off the points.
struct AxisFit {
    double lo, hi;
};
AxisFit fit_axis(double lo, double hi, double min_span, double px, double margin_lo, double margin_hi);

// Zoom and pan of a plot axis by the mouse: zoom_axis scales [lo, hi] by `factor` (< 1 zooms in) about
// `anchor` (the data value under the mouse, which stays under it); pan_axis shifts it by `pixels` of a
// data area `px` long (a drag to the right moves the data right: the range moves left).
AxisFit zoom_axis(AxisFit r, double anchor, double factor);
AxisFit pan_axis(AxisFit r, double pixels, double px);

// The potential plot's y range [J]: from a little below the wells' floor v_min (< 0) up to the higher of
// a fixed headroom (2.3 |v_min|, the energy of a typical chaotic orbit) and the largest energy of the
// recent trajectory, with label_px pixels above the energy line for its "E = ..." label.
AxisFit potential_y_range(double v_min, double e_max, double px, double label_px);

// The rig's impact label ("F = 142 N", "impact v- = ..."): on while the displayed state touches the
// bumper; after the contact it fades with wall time (readable at 1x) and is gone once the simulation has
// moved half a forcing period on, so it never outlasts the contact by more than that. Where a forcing
// period passes in under kMinWallPeriodS of wall time (10x and faster) a label per contact would only
// flicker: none is shown. Fed in time order with what the UI drains; UI thread.
class ImpactLabel {
public:
    void reset() { seen_ = in_contact_ = false; }
    // A sample: bumper force [N] at sim time t [s], received at wall time wall_s [s].
    void sample(double t, double wall_s, double force) {
        if (force > 0) {
            if (!in_contact_) peak_ = 0;
            in_contact_ = true;
            peak_ = force > peak_ ? force : peak_;
            mark(t, wall_s, false);
        } else {
            in_contact_ = false;
        }
    }
    // A rigid impact (G, H) with impact velocity v- [m/s].
    void impact(double t, double wall_s, double v_minus) {
        v_minus_ = v_minus;
        mark(t, wall_s, true);
    }
    // The opacity now (0: not shown) for the displayed state (in contact or not) at sim time t.
    double alpha(bool in_contact, double t, double wall_s, double period_s, double speed) const {
        if (period_s / speed < kMinWallPeriodS) return 0.0;
        if (in_contact) return 1.0;
        if (!seen_ || t < t_ || t - t_ > 0.5 * period_s) return 0.0;
        const double a = 1.0 - (wall_s - wall_) / kFadeS;
        return a > 0 ? a : 0.0;
    }
    bool was_impact() const { return was_impact_; }   // the last contact was a rigid impact
    double v_minus() const { return v_minus_; }       // [m/s] of the last rigid impact
    double peak_force() const { return peak_; }       // [N] of the last compliant contact

    static constexpr double kFadeS = 0.6;            // [s] of wall time
    static constexpr double kMinWallPeriodS = 0.12;  // [s] of wall time per forcing period

private:
    void mark(double t, double wall_s, bool impact) {
        t_ = t;
        wall_ = wall_s;
        seen_ = true;
        was_impact_ = impact;
    }
    double t_ = 0, wall_ = 0, peak_ = 0, v_minus_ = 0;
    bool seen_ = false, in_contact_ = false, was_impact_ = false;
};

}  // namespace impactlab::gui
