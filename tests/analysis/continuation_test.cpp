// Continuation: the first period doubling and the grazing that ends the period-2 orbit, against the CF
// sweep's transitions (README: period 2 first seen at 10.83, chaos from 12.83, on a 0.083 rad/s grid).
#include <doctest/doctest.h>

#include <cmath>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

namespace {

const BifPoint* first_of(const ContinuationResult& r, BifKind kind, int period) {
    for (const auto& b : r.points)
        if (b.kind == kind && b.period == period) return &b;
    return nullptr;
}

ContinuationResult period_two_cascade(const char* name) {
    ContinuationSpec spec;
    spec.lo = 9.0;
    spec.hi = 13.5;
    spec.start = 9.0;
    spec.max_period = 2;   // the period-1 branch and the period-2 branch switched onto at its doubling
    return continue_orbits(make_version(name), spec);
}

}  // namespace

TEST_CASE("analysis: A1C's period doubling and grazing match the sweep, located to 1e-6 rad/s") {
    const ContinuationResult r = period_two_cascade("A1C");
    REQUIRE(r.branches.size() >= 2);
    const BifPoint* pd = first_of(r, BifKind::PeriodDoubling, 1);
    REQUIRE(pd != nullptr);
    // The sweep sees period 2 first at 10.83 (10.75 is still period 1; near mu = -1 a 20-period transient
    // still alternates, so the sweep's level lies just below the true doubling).
    CHECK(pd->param > 10.75);
    CHECK(pd->param < 10.83 + 25.0 / 300);
    CHECK(pd->precision < 1e-6);
    const BifPoint* gr = first_of(r, BifKind::Grazing, 2);
    REQUIRE(gr != nullptr);
    // The stable period-2 orbit dies in a fold at 12.8306 (the sweep's chaos starts at its 12.83 level); the
    // unstable one coming back from the fold touches the bumper at 12.7993.
    CHECK(gr->param > 12.75);
    CHECK(gr->param < 12.83 + 1e-2);
    CHECK(gr->precision < 1e-6);
    const BifPoint* fold = first_of(r, BifKind::Fold, 2);
    REQUIRE(fold != nullptr);
    CHECK(fold->param == doctest::Approx(12.83).epsilon(0.005));
    // Stability along the period-1 branch: stable below the doubling, unstable above.
    for (const auto& pt : r.branches[0].points) {
        if (pt.param < pd->param - 1e-3) CHECK(pt.stable);
        if (pt.param > pd->param + 1e-3) CHECK_FALSE(pt.stable);
    }
}

TEST_CASE("analysis: A1G's period doubling and grazing match the sweep") {
    const ContinuationResult r = period_two_cascade("A1G");
    const BifPoint* pd = first_of(r, BifKind::PeriodDoubling, 1);
    REQUIRE(pd != nullptr);
    CHECK(pd->param > 10.75);
    CHECK(pd->param < 10.83 + 25.0 / 300);
    CHECK(pd->precision < 1e-6);
    // The smooth flight is the same as A1C's until the bumper is touched.
    const ContinuationResult rc = period_two_cascade("A1C");
    CHECK(pd->param == doctest::Approx(first_of(rc, BifKind::PeriodDoubling, 1)->param).epsilon(1e-7));
    const BifPoint* gr = first_of(r, BifKind::Grazing, 2);
    REQUIRE(gr != nullptr);
    CHECK(gr->param > 12.75);
    CHECK(gr->param < 12.83 + 25.0 / 300);
}

TEST_CASE("continuation: the period-1 branch of A1C covers 0.05..25 rad/s across the friction-held range") {
    // Around 6.4..6.6 rad/s the cart is still held by dry friction (a multiplier of 0.9993): the corrector
    // fails there and the branch is restarted at fixed omega instead of ending.
    const Params p = make_version("A1C");
    ContinuationSpec spec;
    spec.lo = 0.05;
    spec.hi = 25;
    spec.max_period = 1;
    const ContinuationResult r = continue_orbits(p, spec);
    REQUIRE(r.branches.size() == 1);
    const auto& pts = r.branches[0].points;
    REQUIRE(pts.size() > 20);
    double lo = 1e9, hi = -1e9;
    for (const auto& q : pts) {
        lo = std::min(lo, q.param);
        hi = std::max(hi, q.param);
    }
    CHECK(lo < 0.1);
    CHECK(hi > 24.9);
    CHECK(r.branches[0].end.find("omega range") == 0);
    // The largest gap between neighbouring points stays below a restart's longest jump.
    for (std::size_t i = 1; i < pts.size(); ++i) CHECK(std::abs(pts[i].param - pts[i - 1].param) < 0.26);
    int doublings = 0;
    for (const auto& b : r.points) doublings += b.kind == BifKind::PeriodDoubling;
    CHECK(doublings == 2);   // 10.8613 and 22.1473
    CHECK(r.seconds < 10);
}
