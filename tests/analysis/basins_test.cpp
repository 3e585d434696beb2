// Basins of attraction: the same grid for any thread count; both attractors of the hysteresis at omega = 13
// (A1G: the CF sweep up is chaotic there, the sweep down on the large period-1 orbit); a start on a stable
// periodic orbit labelled with that orbit; a cart pressed onto a moved bumper labelled resting.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "impactlab/analysis.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

namespace {

BasinSpec small_grid(int n, int threads) {
    BasinSpec s;
    s.omega = 13;
    s.nx = s.nv = n;
    s.threads = threads;
    return s;
}

const Attractor* find_kind(const BasinResult& r, AttractorKind k, int period = 0) {
    for (const auto& a : r.attractors)
        if (a.kind == k && (period == 0 || a.period == period)) return &a;
    return nullptr;
}

}  // namespace

TEST_CASE("basins: 1 and 2 threads give the same labels and attractors") {
    const Params p = make_version("A1G");
    const BasinResult r1 = compute_basins(p, small_grid(8, 1));
    const BasinResult r2 = compute_basins(p, small_grid(8, 2));
    CHECK(r1.threads == 1);
    CHECK(r2.threads == 2);
    REQUIRE(r1.label.size() == 64);
    CHECK(r1.label == r2.label);
    CHECK(std::none_of(r1.label.begin(), r1.label.end(), [](int l) { return l < 0; }));
    REQUIRE(r1.attractors.size() == r2.attractors.size());
    for (std::size_t k = 0; k < r1.attractors.size(); ++k) {
        CHECK(r1.attractors[k].kind == r2.attractors[k].kind);
        CHECK(r1.attractors[k].first_cell == r2.attractors[k].first_cell);
        CHECK(r1.attractors[k].cells == r2.attractors[k].cells);
        CHECK(r1.attractors[k].points == r2.attractors[k].points);   // bit-identical section points
    }
    CHECK(r1.periods_run == r2.periods_run);
    // Ids follow the first cell reaching each attractor.
    for (std::size_t k = 1; k < r1.attractors.size(); ++k) CHECK(r1.attractors[k - 1].first_cell < r1.attractors[k].first_cell);
}

TEST_CASE("basins: at omega = 13 (A1G hysteresis) both the chaotic attractor and the large period-1 orbit have basins") {
    const Params p = make_version("A1G");
    const BasinResult r = compute_basins(p, small_grid(10, 2));
    const Attractor* chaos = find_kind(r, AttractorKind::Chaos);
    const Attractor* p1 = find_kind(r, AttractorKind::Periodic, 1);
    REQUIRE(chaos != nullptr);
    REQUIRE(p1 != nullptr);
    // The sweep down sits on this orbit at omega = 13: x = -19.67 mm at phi = 0, in the left well.
    const Orbit o = find_orbit(p, 13.0, p1->representative);
    REQUIRE(o.converged);
    CHECK(o.floquet.stable);
    CHECK(o.y[0] == doctest::Approx(-0.019673).epsilon(1e-3));
    CHECK(scaled_norm(o.y - p1->representative) < 1e-3);
    CHECK(p1->well == -1);
    // The chaotic set is the sweep up's band at omega = 13 (section x between -16 and -4.9 mm), in the left well.
    CHECK(chaos->well == -1);
    for (const auto& q : chaos->points) {
        CHECK(q[0] > -0.0175);
        CHECK(q[0] < -0.0040);
    }
    // One chaotic attractor, however many cells reach it: the matching merges their samples.
    int n_chaos = 0;
    for (const auto& a : r.attractors) n_chaos += a.kind == AttractorKind::Chaos;
    CHECK(n_chaos == 1);
    CHECK(chaos->cells + p1->cells >= r.label.size() * 9 / 10);
}

TEST_CASE("basins: a start on a stable periodic orbit gets that orbit's label, at once") {
    const Params p = make_version("A1G");
    const Orbit o = find_orbit(p, 13.0, Vec2(-0.0197, -0.013));
    REQUIRE(o.converged);
    REQUIRE(o.floquet.stable);
    // A 3 x 3 grid whose centre cell is the orbit's section point.
    BasinSpec s = small_grid(3, 2);
    const double dx = 1e-3, dv = 1e-2;
    s.x_min = o.y[0] - 1.5 * dx;
    s.x_max = o.y[0] + 1.5 * dx;
    s.v_min = o.y[1] - 1.5 * dv;
    s.v_max = o.y[1] + 1.5 * dv;
    const BasinResult r = compute_basins(p, s);
    const int centre = r.label[4];
    REQUIRE(centre >= 0);
    const Attractor& a = r.attractors[static_cast<std::size_t>(centre)];
    CHECK(a.kind == AttractorKind::Periodic);
    CHECK(a.period == 1);
    CHECK(scaled_norm(a.representative - o.y) < s.match_tol);
    // Started on the orbit, the cell recurs from its first periods: the early stop.
    const CellOutcome c = run_to_attractor(p, s, o.y);
    CHECK(c.kind == AttractorKind::Periodic);
    CHECK(c.periods_run <= 5);
    // Far from it, a start reaches the chaotic attractor, not this orbit.
    const CellOutcome far = run_to_attractor(p, s, Vec2(-0.005, 0.0));
    CHECK_FALSE(same_attractor(far, c, s));
}

TEST_CASE("basins: a chaotic start that lands on a saddle cycle through permanent contact is not labelled with it") {
    // A1G at omega 13: these starts reach the unstable period-6 orbit (mu = -1.74) to round-off through a
    // permanent contact, and repeat it for dozens of periods; the recurrence alone took it for period 6 / 12.
    // Cells (96, 110) and (171, 112) of the 200 x 200 grid at rtol 1e-8.
    const Params p = make_version("A1G");
    BasinResult grid;
    grid.spec.omega = 13;
    grid.spec.sim = Tolerances{};   // rtol 1e-8, at which these two starts were found
    const BasinSpec& s = grid.spec;
    for (const auto& [i, j] : {std::pair{96, 110}, std::pair{171, 112}}) {
        const CellOutcome c = run_to_attractor(p, s, Vec2(grid.x0(i), grid.v0(j)));
        CHECK((c.kind == AttractorKind::Chaos || c.period == 1));
        CHECK(c.period != 6);
        CHECK(c.period != 12);
    }
}

TEST_CASE("basins: a cart pressed onto a bumper moved into the right well rests there") {
    // xI = 5 mm: F_SA(xI) = -2.3 N pushes the cart onto the bumper harder than the unbalance (0.63 N at
    // omega = 5) ever pulls it off, so a cart right of the hilltop ends held in regime III.
    Params p = make_version("A1G");
    p.xI = 0.005;
    REQUIRE(-spring_magnet(p, p.xI).F > p.m0e * 25.0);
    BasinSpec s;
    s.omega = 5;
    const CellOutcome right = run_to_attractor(p, s, Vec2(0.002, 0.0));
    CHECK(right.kind == AttractorKind::Resting);
    REQUIRE(right.points.size() == 1);
    CHECK(right.points[0][0] == p.xI);
    CHECK(right.points[0][1] == 0.0);
    const CellOutcome left = run_to_attractor(p, s, Vec2(-0.011, 0.0));
    CHECK(left.kind != AttractorKind::Resting);
    CHECK_FALSE(same_attractor(left, right, s));
}

TEST_CASE("basins: an empty grid or an inverted range is refused") {
    const Params p = make_version("A1G");
    BasinSpec s = small_grid(0, 1);
    CHECK_THROWS_AS(compute_basins(p, s), std::invalid_argument);
    s = small_grid(2, 1);
    s.v_max = s.v_min;
    CHECK_THROWS_AS(compute_basins(p, s), std::invalid_argument);
}

TEST_CASE("basins: a cancelled job stops, says so and leaves the unrun cells unlabelled") {
    const Params p = make_version("A1G");
    Progress progress;
    progress.cancel = true;
    const BasinResult r = compute_basins(p, small_grid(6, 2), &progress);
    CHECK(r.cancelled);
    CHECK(r.attractors.empty());
    CHECK(std::all_of(r.label.begin(), r.label.end(), [](int l) { return l == -1; }));
    // Uncancelled, progress reaches 1 with every cell labelled.
    Progress full;
    const BasinResult f = compute_basins(p, small_grid(6, 2), &full);
    CHECK_FALSE(f.cancelled);
    CHECK(full.fraction.load() == doctest::Approx(1.0));
    CHECK(std::none_of(f.label.begin(), f.label.end(), [](int l) { return l < 0; }));
}
