// The one finder of sign changes: bisection, the equilibria of a force law, the potential's floor and the
// cart's turning points, against closed forms.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "impactlab/analysis.hpp"
#include "impactlab/equilibria.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"

using namespace impactlab;

TEST_CASE("bisect: the boundary where the predicate turns, to the last bit; the predicate places an exact zero") {
    const double r = bisect([](double x) { return x * x < 2.0; }, 1.0, 2.0);
    CHECK(std::abs(r - std::sqrt(2.0)) <= 4e-16);
    // Once the bracket is two neighbouring doubles more halvings change nothing.
    CHECK(bisect([](double x) { return x * x < 2.0; }, 1.0, 2.0, 200) == r);
    CHECK(bisect([](double x) { return x * x < 2.0; }, 1.0, 2.0, 1) == 1.25);
    // f(x) = x - 0.5 is exactly zero at the first midpoint: "zero is on b's side" keeps the left half,
    // "zero is on a's side" the right one.
    CHECK(bisect([](double x) { return x - 0.5 < 0; }, 0.0, 1.0, 2) == 0.375);
    CHECK(bisect([](double x) { return x - 0.5 <= 0; }, 0.0, 1.0, 2) == 0.625);
}

TEST_CASE("equilibria: wells and the hilltop of R(x) = x^3 - x, ascending, each to the last bits") {
    const auto eq = equilibria([](double x) { return x * x * x - x; }, -1.7, 1.3, 300);
    REQUIRE(eq.size() == 3);
    CHECK(eq[0].x == doctest::Approx(-1.0).epsilon(1e-15));
    CHECK(std::abs(eq[1].x) < 1e-15);
    CHECK(eq[2].x == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(eq[0].stable);    // R rises through zero: the cart is pushed back, a well
    CHECK(!eq[1].stable);   // the hilltop
    CHECK(eq[2].stable);
    CHECK(equilibria([](double x) { return x + 3.0; }, -1.0, 1.0, 10).empty());
}

TEST_CASE("left_well and potential_floor: the rig's wells as equilibria finds them") {
    const Params p = make_version("A1H");
    const auto F = [&](double x) { return spring_magnet(p, x).F; };
    const auto eq = equilibria(F, -0.1, 0.1, 2000);
    std::vector<double> wells;
    for (const auto& e : eq)
        if (e.stable) wells.push_back(e.x);
    REQUIRE(wells.size() == 2);   // A1: a double well
    CHECK(wells[0] == doctest::Approx(-10.88e-3).epsilon(1e-3));
    // The orbit search starts in the left well: the same root, bracketed by one cell.
    CHECK(std::abs(analysis::left_well(p) - wells[0]) < 1e-15);
    CHECK(std::abs(F(analysis::left_well(p))) < 1e-9);
    const double floor = potential_floor(p);
    CHECK(floor == std::min(spring_magnet_potential(p, wells[0]), spring_magnet_potential(p, wells[1])));
    for (int i = -1000; i <= 1000; ++i) CHECK(floor <= spring_magnet_potential(p, 1e-4 * i) + 1e-15);
}

TEST_CASE("turning_point: where v turns from + to - on the dense output, NaN when it does not") {
    DenseStep step;
    step.t0 = 2.0;
    step.h = 0.5;
    step.y0 = Vec2(0.0, 1.0);
    step.y1 = Vec2(0.5, -1.0);
    step.cont3 = Vec2(0.1, 0.0);
    step.cont4 = Vec2(0.0, 0.0);   // v linear in t: zero at the middle
    Piece piece{2.0, 2.5, Regime::Free, &step, 0.0};
    CHECK(turning_point(piece) == doctest::Approx(2.25).epsilon(1e-15));
    step.y0[1] = -1.0;   // falling throughout: no turning point
    CHECK(std::isnan(turning_point(piece)));
    const Piece held{2.0, 2.5, Regime::Free, nullptr, 0.01};
    CHECK(std::isnan(turning_point(held)));
}
