// The plots' fits (app/gui/view_fit): an axis fitted with pixel margins, the potential plot's range
// following the energy, and the rig's impact label in sim and wall time.
#include <doctest/doctest.h>

#include "../../app/gui/views/view_fit.hpp"

using namespace impactlab::gui;

TEST_CASE("view fit: data lands inside the area with the margins free") {
    // 300 px, 20 px free below, 50 px above (a label band): the data's ends map to pixels 20 and 250.
    const AxisFit f = fit_axis(-0.015, -0.005, 0.002, 300, 20, 50);
    const auto px = [&](double v) { return (v - f.lo) / (f.hi - f.lo) * 300; };
    CHECK(px(-0.015) == doctest::Approx(20));
    CHECK(px(-0.005) == doctest::Approx(250));
    // A single point (period 1) is widened to min_span about itself.
    const AxisFit one = fit_axis(0.01, 0.01, 0.002, 300, 10, 10);
    CHECK(one.lo < 0.009);
    CHECK(one.hi > 0.011);
    CHECK((one.lo + one.hi) / 2 == doctest::Approx(0.01));
    // Margins larger than the plot still leave the data a third of it.
    const AxisFit tiny = fit_axis(0, 1, 0, 60, 50, 50);
    CHECK((tiny.hi - tiny.lo) == doctest::Approx(3.0));
}

TEST_CASE("view fit: zoom keeps the point under the mouse, pan follows the drag") {
    const AxisFit r{0.0, 25.0};   // omega [rad/s]
    const AxisFit z = zoom_axis(r, 16.45, 0.5);
    CHECK(z.hi - z.lo == doctest::Approx(12.5));
    // 16.45 sits at the same fraction of the axis before and after.
    CHECK((16.45 - z.lo) / (z.hi - z.lo) == doctest::Approx((16.45 - r.lo) / (r.hi - r.lo)));
    const AxisFit back = zoom_axis(z, 16.45, 2.0);
    CHECK(back.lo == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(back.hi == doctest::Approx(25.0));
    // A 100 px drag to the right on a 500 px axis of 25 rad/s: the view moves 5 rad/s to the left.
    const AxisFit p = pan_axis(r, 100, 500);
    CHECK(p.lo == doctest::Approx(-5.0));
    CHECK(p.hi == doctest::Approx(20.0));
}

TEST_CASE("view fit: the potential plot's top follows the energy, with room for its label") {
    const double vmin = -0.0152;   // [J] the A1 wells' floor
    const AxisFit quiet = potential_y_range(vmin, -0.010, 200, 20);
    CHECK(quiet.lo == doctest::Approx(1.18 * vmin));
    CHECK(quiet.hi > -2.3 * vmin);   // the fixed headroom when the energy is low
    // 50 mJ (the A1H window, above the old fixed limit of ~35 mJ): the line and 20 px above it in view.
    const double e = 0.050;
    const AxisFit high = potential_y_range(vmin, e, 200, 20);
    CHECK(high.hi > e);
    CHECK((high.hi - e) / (high.hi - high.lo) * 200 == doctest::Approx(20));
}

TEST_CASE("view fit: the impact label lives during the contact and briefly after, never at speed") {
    const double T = 0.4;   // [s] forcing period
    ImpactLabel l;
    CHECK(l.alpha(false, 0.0, 0.0, T, 1.0) == 0.0);   // nothing seen yet
    l.sample(1.00, 10.00, 0.0);
    l.sample(1.01, 10.01, 50.0);   // a compliant contact begins
    l.sample(1.02, 10.02, 120.0);
    CHECK(l.alpha(true, 1.02, 10.02, T, 1.0) == 1.0);
    l.sample(1.03, 10.03, 0.0);    // and ends
    CHECK(l.peak_force() == doctest::Approx(120.0));
    CHECK_FALSE(l.was_impact());
    // 1x: fades with wall time...
    const double a1 = l.alpha(false, 1.10, 10.10, T, 1.0);
    const double a2 = l.alpha(false, 1.20, 10.20, T, 1.0);
    CHECK(a1 > a2);
    CHECK(a2 > 0.0);
    // ...and is gone half a forcing period after the contact, whatever the wall clock says.
    CHECK(l.alpha(false, 1.02 + 0.21, 10.05, T, 1.0) == 0.0);
    // At 10x a forcing period lasts 40 ms of wall time: no label, not even during a contact.
    CHECK(l.alpha(true, 1.02, 10.02, T, 10.0) == 0.0);
    // A rigid impact: its v- is what the label says.
    l.impact(2.0, 11.0, -0.31);
    CHECK(l.was_impact());
    CHECK(l.v_minus() == doctest::Approx(-0.31));
    CHECK(l.alpha(false, 2.05, 11.05, T, 1.0) > 0.0);
    l.reset();   // a reset of the simulation: time starts over
    CHECK(l.alpha(false, 0.01, 11.06, T, 1.0) == 0.0);
}
