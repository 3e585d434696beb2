// The final gate (core/src/identify/gate.cpp): "worse" is a rise of a printed error beyond the scatter of its
// units, or a unit the model cannot simulate; a rise within the scatter or below what the data resolve is not.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "identify/internal.hpp"

namespace dt = impactlab::identify::detail;

namespace {

dt::PrintedErrors one(const char* name, const std::vector<double>& num, dt::PrintedError::Kind kind = dt::PrintedError::Kind::Rms) {
    dt::PrintedErrors p;
    dt::PrintedError e;
    e.name = name;
    e.num = num;
    e.den.assign(num.size(), 1.0);
    e.kind = kind;
    p.e.push_back(e);
    return p;
}

std::vector<double> noisy(double level, double sd, unsigned seed, std::size_t n = 40) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, sd);
    std::vector<double> v;
    for (std::size_t i = 0; i < n; ++i) v.push_back(level + g(rng));
    return v;
}

}  // namespace

TEST_CASE("gate: a consistent rise of a printed error is worse; the same error with noise is not") {
    const std::vector<double> base = noisy(1.0, 0.2, 1);
    std::vector<double> up = base, same = base;
    std::mt19937 rng(2);
    std::normal_distribution<double> g(0.0, 0.01);
    for (std::size_t i = 0; i < base.size(); ++i) {
        up[i] += 0.1 + g(rng);     // every unit 10 % worse
        same[i] += g(rng);          // only noise, mean zero
    }
    const auto ref = one(dt::kErrShoot1, base);
    const dt::GateCheck w = dt::gate_check(ref, one(dt::kErrShoot1, up));
    CHECK(w.worse);
    CHECK(w.why.find(dt::kErrShoot1) != std::string::npos);
    CHECK(w.why.find("rose from") != std::string::npos);
    const dt::GateCheck s = dt::gate_check(ref, one(dt::kErrShoot1, same));
    CHECK_FALSE(s.worse);
    // A fall is never worse.
    std::vector<double> down = base;
    for (double& v : down) v *= 0.5;
    CHECK_FALSE(dt::gate_check(ref, one(dt::kErrShoot1, down)).worse);
}

TEST_CASE("gate: a rise within the scatter is said, not counted; below the data's resolution it is neither") {
    std::vector<double> base(10, 1.0), cand(10, 1.0);
    // Half the units rise, half fall, a little more rise than fall: within the scatter.
    for (std::size_t i = 0; i < 10; ++i) cand[i] = i % 2 ? 1.3 : 0.75;
    const dt::GateCheck g = dt::gate_check(one(dt::kErrResidual, base), one(dt::kErrResidual, cand));
    CHECK_FALSE(g.worse);
    REQUIRE(g.within.size() == 1);
    CHECK(g.within[0].find("within its scatter") != std::string::npos);
    // An impact's dwell changed by far less than a sample: consistent, but not resolved by the data.
    auto ref = one(dt::kErrDwell, std::vector<double>(5, 1.0e-8));
    ref.e[0].resolution = 1e-4;
    auto cand2 = one(dt::kErrDwell, std::vector<double>(5, 1.2e-8));
    CHECK_FALSE(dt::gate_check(ref, cand2).worse);
    ref.e[0].resolution = 0;
    CHECK(dt::gate_check(ref, cand2).worse);
}

TEST_CASE("gate: a unit the given model simulates and the new one cannot is worse; a missed impact is not") {
    std::vector<double> base(20, 1.0), cand(20, 1.0);
    cand[7] = INFINITY;
    const dt::GateCheck g = dt::gate_check(one(dt::kErrShoot10, base), one(dt::kErrShoot10, cand));
    CHECK(g.worse);
    CHECK(g.why.find("could not be simulated") != std::string::npos);
    auto ref = one(dt::kErrKappa, base), c = one(dt::kErrKappa, cand);
    ref.e[0].missing_fails = c.e[0].missing_fails = false;
    CHECK_FALSE(dt::gate_check(ref, c).worse);
    // No unit at all: the printed value is not a number where the given one was.
    CHECK(dt::gate_check(one(dt::kErrFree, base), one(dt::kErrFree, std::vector<double>(20, INFINITY))).worse);
    // Where the given model could not be simulated there is nothing to be worse than.
    CHECK_FALSE(dt::gate_check(one(dt::kErrFree, std::vector<double>(20, INFINITY)), one(dt::kErrFree, base)).worse);
}

TEST_CASE("gate: diagram bins are paired by omega and their sampling noise is part of the scatter") {
    auto bins = [](std::vector<double> d, std::vector<double> w, double noise) {
        dt::PrintedErrors p;
        dt::PrintedError e;
        e.name = dt::kErrDiagram;
        e.kind = dt::PrintedError::Kind::Mean;
        e.num = d;
        e.den.assign(d.size(), 1.0);
        e.keys = w;
        e.noise.assign(d.size(), noise);
        p.e.push_back(e);
        return p;
    };
    // Three bins, the new model's bins listed in another order: 10 % higher on each, with no sampling noise.
    const auto ref = bins({1.0, 2.0, 3.0}, {9.0, 13.5, 16.0}, 0.0);
    CHECK(dt::gate_check(ref, bins({3.3, 1.1, 2.2}, {16.0, 9.0, 13.5}, 0.0)).worse);
    // The same rise when each bin's distance carries a sampling noise of 0.5: not beyond the scatter.
    CHECK_FALSE(dt::gate_check(bins({1.0, 2.0, 3.0}, {9.0, 13.5, 16.0}, 0.5), bins({3.3, 1.1, 2.2}, {16.0, 9.0, 13.5}, 0.5)).worse);
}

TEST_CASE("gate: impacts only the candidate predicts do not count against it; both are judged on the impacts both have") {
    // The given model misses the slow impacts (their apparent restitution is the noisiest); the candidate
    // predicts them too, and matches the ones both predict as well.
    std::vector<double> ref = noisy(0.0009, 0.0002, 5, 30), cand = ref;
    for (std::size_t i = 0; i < ref.size(); i += 3) {
        ref[i] = INFINITY;   // missed by the given model
        cand[i] = 0.01;      // a slow impact: ten times the squared error of the rest
    }
    auto with = [](const std::vector<double>& v) {
        dt::PrintedErrors p = one(dt::kErrKappa, v);
        p.e.front().missing_fails = false;
        return p;
    };
    CHECK(with(cand).e.front().value() > 2.0 * with(ref).e.front().value());   // over its own set it looks worse
    const dt::GateCheck g = dt::gate_check(with(ref), with(cand));
    CAPTURE(g.why);
    CHECK_FALSE(g.worse);
    // On the impacts both have, a real rise still counts.
    std::vector<double> worse = cand;
    for (std::size_t i = 0; i < worse.size(); ++i)
        if (i % 3) worse[i] *= 3.0;
    CHECK(dt::gate_check(with(ref), with(worse)).worse);
}
