// Each named law against the generic term of its variable (core/src/identify/fit/shape.cpp), on two records
// of the randomized benchmark (seed 1): an x^5 force, which a linear, an even and a cubic stiffness fitted
// together as a polynomial, is left to the generic term; an x^2 force keeps its named law.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "impactlab/identify.hpp"

namespace id = impactlab::identify;

namespace {
id::IdentifyBenchRecord bench_record(int k) {
    id::IdentifyBenchOptions o;
    o.seed = 1;
    o.only = k;
    const id::IdentifyBenchResult r = id::run_identify_bench(o);
    REQUIRE(r.rows.size() == 1);
    REQUIRE(r.rows[0].error.empty());
    return r.rows[0];
}
}  // namespace

TEST_CASE("shape: an x^5 force is a shape of x, not a linear, an even and a cubic stiffness") {
    const id::IdentifyBenchRecord r = bench_record(44);
    CHECK(r.truth.find("bench_poly_x(0, 0, 0, 0, 0, -0.0951)") != std::string::npos);
    CHECK(r.named == std::vector<std::string>{"unexplained_x"});
    CHECK_FALSE(r.false_claim);
    CHECK(r.after <= 1.1 * r.noise);   // at the noise, as the three laws were
}

TEST_CASE("shape: an x^2 force keeps its named law, the generic term beside it adding nothing") {
    const id::IdentifyBenchRecord r = bench_record(53);
    CHECK(r.truth.find("bench_poly_x(0, 0, 0.321, 0, 0, 0)") != std::string::npos);
    CHECK(r.named == std::vector<std::string>{"even_stiffness"});
    CHECK_FALSE(r.false_claim);
    CHECK(r.better);
}
