// Two-parameter continuation: the period doubling of A1C followed in (omega, xI) against the brute-force
// period map of the plane; the grazing and fold of A1G; a cancel between the curve's steps.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "newton_reference.hpp"
#include "impactlab/plane_doubling.hpp"
#include "impactlab/scan.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

TEST_CASE("curves: A1C's doubling curve through (10.8613, xI = 0) bounds the period-2 region of the plane scan") {
    const Params p = make_version("A1C");
    const BifCurve c = continue_doubling_curve(p, ContParam::XI, 10.8613339, Vec2(-0.0142521, -0.0499209), 1, -3e-3, 1e-3,
                                               5e-4);
    REQUIRE(c.points.size() == 9);   // -3..1 mm: the period-1 orbit stays clear of the bumper (its largest x: -3.3 mm)
    for (const auto& q : c.points) CHECK(std::abs(q.omega - 10.861335) < 1e-5);   // the reference's doubling

    // The plane: rows in xI, each a CF sweep in omega from rest, with the grid step 0.1 rad/s. (At xI = -3 mm
    // the sweep from rest arrives on another attractor, which does not double here; the rows stop at -2 mm.)
    ScanSpec spec;
    spec.x = parse_scan_axis("omega:10.3:11.4:12");
    spec.y = parse_scan_axis("xI:-0.002:0.001:4");
    const double grid = (spec.x.hi - spec.x.lo) / (spec.x.n - 1);
    for (int row = 0; row < spec.y.n; ++row) {
        const double xI = spec.y.at(row);
        CAPTURE(xI);
        // The curve at this xI (the rows fall on its points).
        double w = NAN;
        for (const auto& q : c.points)
            if (std::abs(q.q - xI) < 1e-9) w = q.omega;
        REQUIRE(std::isfinite(w));
        const std::vector<ScanPoint> pts = scan_row(p, spec, row);
        REQUIRE(pts.size() == static_cast<std::size_t>(spec.x.n));
        // Period 1 below the curve, the doubled region above it (period 2, or more clusters where the period-2
        // orbit still converges slowly, or chaos past its own grazing), the switch within one grid step of the
        // curve (the sweep may see period 2 a level early: its transient still alternates near mu = -1).
        int first = -1;
        for (int i = 0; i < spec.x.n; ++i)
            if (pts[static_cast<std::size_t>(i)].period != 1 && first < 0) first = i;
        REQUIRE(first >= 0);
        CHECK(std::abs(spec.x.at(first) - w) <= grid);
        CHECK(pts[static_cast<std::size_t>(first)].period == 2);
        for (int i = 0; i < spec.x.n; ++i) {
            CAPTURE(spec.x.at(i));
            if (spec.x.at(i) < w - grid) CHECK(pts[static_cast<std::size_t>(i)].period == 1);
            if (spec.x.at(i) > w + grid) CHECK(pts[static_cast<std::size_t>(i)].period != 1);
        }
    }
    // Below -3.3 mm the bumper reaches the orbit: the multiplier jumps there (a grazing) and the curve says so.
    const BifCurve lower = continue_doubling_curve(p, ContParam::XI, 10.8613339, Vec2(-0.0142521, -0.0499209), 1, -6e-3,
                                                   0.0, 2.5e-4);
    CHECK(lower.points.front().q > -3.5e-3);
    CHECK(lower.end.find("lost") != std::string::npos);
}

TEST_CASE("curves: in (omega, m0e) the doubling moves with the forcing and is followed to both ends of the range") {
    // A stronger unbalance doubles the orbit earlier: 17.7 rad/s at 0.81 m0e, 10.86 at m0e, 9.2 at 1.19 m0e.
    const Params p = make_version("A1C");
    const BifCurve c = continue_doubling_curve(p, ContParam::M0e, 10.8613339, Vec2(-0.0142521, -0.0499209), 1, 0.8 * p.m0e,
                                               1.2 * p.m0e, 0.02 * p.m0e);
    REQUIRE(c.points.size() > 10);
    CHECK(c.end == "m0e range / m0e range");
    CHECK((c.below.stop == CurveStop::Range && c.above.stop == CurveStop::Range));
    CHECK(c.points.front().q < 0.82 * p.m0e);
    CHECK(c.points.back().q > 1.18 * p.m0e);
    for (std::size_t i = 1; i < c.points.size(); ++i) {
        CHECK(c.points[i].q > c.points[i - 1].q);
        CHECK(c.points[i].omega < c.points[i - 1].omega);
    }
}

TEST_CASE("curves: A1G's grazing curve through (9.6005, xI = -4 mm) bounds the impacting region of the plane scan") {
    // The free period-1 orbit of the left well reaches a bumper at -4 mm at 9.60049627 rad/s (continue's
    // grazing); its grazing followed in xI is where the orbit without the bumper peaks at xI.
    Params p = make_version("A1G");
    p.xI = -0.004;
    const BifCurve c = continue_grazing_curve(p, ContParam::XI, 9.60049627, Vec2(-0.0156163, -0.00744857), 1, -0.007,
                                              -0.004, 5e-4);
    REQUIRE(c.points.size() == 7);
    CHECK(c.kind == BifKind::Grazing);
    for (std::size_t i = 1; i < c.points.size(); ++i) CHECK(c.points[i].omega > c.points[i - 1].omega);   // a higher bumper is reached later
    // The plane: rows in xI, each a CF sweep in omega from rest with the grid step 0.05 rad/s. Below the curve
    // (in omega) the cart flies free; the first impacts appear within a grid step of it (a nonsmooth fold:
    // the free orbit ends there and the sweep jumps onto an impacting one).
    ScanSpec spec;
    spec.x = parse_scan_axis("omega:8.5:10.5:41");
    spec.y = parse_scan_axis("xI:-0.007:-0.004:4");
    spec.measures.impacts = true;
    const double grid = (spec.x.hi - spec.x.lo) / (spec.x.n - 1);
    for (int row = 0; row < spec.y.n; ++row) {
        const double xI = spec.y.at(row);
        CAPTURE(xI);
        double w = NAN;
        for (const auto& q : c.points)
            if (std::abs(q.q - xI) < 1e-9) w = q.omega;
        REQUIRE(std::isfinite(w));
        const std::vector<ScanPoint> pts = scan_row(p, spec, row);
        REQUIRE(pts.size() == static_cast<std::size_t>(spec.x.n));
        int first = -1;
        for (int i = 0; i < spec.x.n; ++i)
            if (pts[static_cast<std::size_t>(i)].impacts > 0 && first < 0) first = i;
        REQUIRE(first >= 0);
        CAPTURE(spec.x.at(first));
        CAPTURE(w);
        // (At -4 mm the sweep's 20-period transient, near the grazing, already touches at 9.60: the impacting
        // orbits coexist with the free ones down to their fold at 9.549.)
        CHECK(std::abs(spec.x.at(first) - w) <= grid);
    }
}

TEST_CASE("curves: A1G's fold of the impacting period-1 orbit followed in xI is where continue in omega finds it") {
    // At xI = -4 mm the impacting orbit past the grazing at 9.6005 turns in a fold at 9.548943 (continue).
    Params p = make_version("A1G");
    p.xI = -0.004;
    const BifCurve c = continue_fold_curve(p, ContParam::XI, 9.548943, Vec2(-0.0157368, 0.00230387), 1, -0.0045, -0.003,
                                           5e-4);
    CHECK(c.end == "xI range / xI range");   // (towards -4.5 mm the steps are halved: the fold nears its grazing)
    CHECK(c.kind == BifKind::Fold);
    int checked = 0;
    const CurvePoint* pick = &c.points.front();   // the point nearest xI = -3.5 mm
    for (const CurvePoint& q : c.points)
        if (std::abs(q.q + 0.0035) < std::abs(pick->q + 0.0035)) pick = &q;
    CHECK(std::abs(pick->q + 0.0035) < 2.5e-4);
    for (const CurvePoint& q : c.points) {
        if (&q != pick) continue;
        // The one-parameter continuation at that xI, from the free orbit at 9, through the grazing.
        Params pq = p;
        pq.xI = q.q;
        ContinuationSpec spec;
        spec.lo = 8.0;
        spec.hi = 12.0;
        spec.start = 9.0;
        spec.max_period = 1;
        const ContinuationResult r = continue_orbits(pq, spec);
        bool found = false;
        for (const BifPoint& b : r.points)
            if (b.kind == BifKind::Fold && std::abs(b.param - q.omega) < 1e-5) found = true;
        CAPTURE(q.omega);
        CHECK(found);
        ++checked;
    }
    CHECK(checked == 1);
}

TEST_CASE("curves: started on continue's fold at xI = -3.5 mm, where the monodromy is noisy, the fold curve starts") {
    // Near its grazing the fold's det(M - I) keeps a noise of ~3e-5 while omega stands still to 1e-10: the
    // Newton once ran out of steps there and the curve was "lost" at its own start.
    Params p = make_version("A1G");
    p.xI = -0.0035;
    const BifCurve c = continue_fold_curve(p, ContParam::XI, 9.69923488501, Vec2(-0.0159455019081, -7.99497499868e-05), 1, -0.004,
                                           -0.003, 2.5e-4);
    CHECK(c.end == "xI range / xI range");
    bool at_start = false;
    for (const CurvePoint& q : c.points)
        if (q.q == -0.0035) {
            at_start = true;
            CHECK(std::abs(q.omega - 9.69923488501) < 1e-6);   // continue's fold there
        }
    CHECK(at_start);
    CHECK(c.points.size() >= 5);
}

TEST_CASE("curves: a cancel is seen between the curve's steps, and the curve comes back marked cancelled") {
    const Params p = make_version("A1C");
    const Vec2 y0(-0.0142521, -0.0499209);
    const BifCurve whole = continue_doubling_curve(p, ContParam::XI, 10.8613339, y0, 1, -3e-3, 1e-3, 2e-4);
    REQUIRE(whole.points.size() == 21);
    CHECK_FALSE(whole.cancelled);

    // Cancelled before it starts: no step taken, both sides say why.
    Progress before;
    before.cancel = true;
    const BifCurve none = continue_grazing_curve(make_version("A1G"), ContParam::XI, 9.60049627, Vec2(-0.0156163, -0.00744857),
                                                 1, -0.0045, -0.004, 2.5e-4, analysis_tolerances(), &before);
    CHECK(none.cancelled);
    CHECK(none.points.empty());
    CHECK(none.end == "cancelled / cancelled");

    // Cancelled once the first step has reported its progress: it stops early with the points found so far,
    // the whole run's own.
    Progress prog;
    std::thread watcher([&] {
        while (prog.fraction.load() <= 0.0) std::this_thread::yield();
        prog.cancel = true;
    });
    const BifCurve part = continue_doubling_curve(p, ContParam::XI, 10.8613339, y0, 1, -3e-3, 1e-3, 2e-4,
                                                  analysis_tolerances(), &prog);
    watcher.join();
    CHECK(part.cancelled);
    CHECK(part.end.find("cancelled") != std::string::npos);
    REQUIRE(part.points.size() < whole.points.size());
    for (const CurvePoint& q : part.points) {
        bool in_whole = false;
        for (const CurvePoint& w : whole.points) in_whole = in_whole || (w.q == q.q && w.omega == q.omega);
        CHECK(in_whole);
    }
}

TEST_CASE("curves: the plane's automatic start finds A1G's grazing and fold, and a cancel stops it while it looks") {
    Params p = make_version("A1G");
    p.xI = -0.004;
    PlaneCurveSpec spec{ContParam::XI, 8.5, 10.5, -0.007, -0.004, 5e-4, BifKind::Grazing};
    const PlaneCurve g = curve_over_plane(p, spec);
    REQUIRE(g.found);
    CHECK(std::abs(g.omega0 - 9.60049626) < 1e-6);   // `impactlab continue`'s grazing at xI = -4 mm
    CHECK(g.curve.kind == BifKind::Grazing);
    CHECK(g.curve.points.size() == 7);
    CHECK(g.curve.end == "xI range / at the axis' end");
    CHECK(g.curve.below.stop == CurveStop::Range);
    CHECK(g.curve.above.stop == CurveStop::AxisEnd);
    spec.kind = BifKind::Fold;
    const PlaneCurve f = curve_over_plane(p, spec);
    REQUIRE(f.found);
    CHECK(std::abs(f.omega0 - 9.548943) < 1e-6);      // and its fold
    Progress cancelled;
    cancelled.cancel = true;
    const PlaneCurve c = curve_over_plane(p, spec, &cancelled);
    CHECK(c.cancelled);
    CHECK(c.curve.cancelled);
    CHECK(c.curve.points.empty());
}

TEST_CASE("curves: the automatic start of a doubling curve is one of the curve's points, where the reference puts it") {
    // The continuation locates the doubling with its own test (a secant at rtol / 100); the curve locates it
    // again with the curve's. The start printed is the curve's point (the reference: 10.861335 +- 3e-6).
    const Params p = make_version("A1G");
    PlaneCurveSpec spec{ContParam::XI, 8.0, 12.0, p.xI - 5e-4, p.xI + 5e-4, 5e-4, BifKind::PeriodDoubling};
    const PlaneCurve d = curve_over_plane(p, spec);
    REQUIRE(d.found);
    bool on_curve = false;
    for (const CurvePoint& c : d.curve.points) on_curve = on_curve || (c.q == p.xI && c.omega == d.omega0 && c.y == d.y0);
    CHECK(on_curve);
    CHECK(std::abs(d.omega0 - 10.861335) < 3e-6);
}

TEST_CASE("curves: a doubling curve of A1G's impacting period 2 crosses xI = 0 where Newton's orbits at rtol 1e-12 do") {
    // At the default rtol 1e-10 an impacting orbit's multiplier jitters by 3e-3: the curve's secant, run there,
    // put its point 1.4e-4 rad/s off. It runs at rtol / 100, where the multiplier is smooth.
    const Params p = make_version("A1G");
    const BifCurve c = continue_doubling_curve(p, ContParam::XI, 19.2312326, Vec2(-0.00537039, -0.0873334), 2, -4e-4, 4e-4, 2e-4);
    const CurvePoint* at0 = nullptr;
    for (const CurvePoint& q : c.points)
        if (q.q == 0.0) at0 = &q;
    REQUIRE(at0 != nullptr);
    CHECK(c.points.size() >= 5);
    const double below = test::doubling_side(p, at0->omega - 1e-6, at0->y, 2), above = test::doubling_side(p, at0->omega + 1e-6, at0->y, 2);
    CAPTURE(at0->omega);
    CAPTURE(below);
    CAPTURE(above);
    CHECK((below > 0) != (above > 0));
}
