// Each named law against the generic terms of its variables (core/src/identify/fit/shape.cpp), on records
// of the randomized benchmark (seed 1): an x^5 force, which a linear, an even and a cubic stiffness fitted
// together as a polynomial, is left to the generic term; an x^2 force keeps its named law; a damping that
// depends on position is no viscous damping; a polynomial in v is no sensor curvature.
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

TEST_CASE("shape: a damping that varies with position is a shape S(x) v, not a viscous damping") {
    // x^2 v reads as a viscous damping (its mean over the motion), which the generic S(x) v beside it improves
    // on held-out data and replaces: the report names no law.
    // A stepped record, not a chaotic one, so the record itself is the same on any processor.
    const id::IdentifyBenchRecord r = bench_record(103);
    CHECK(r.truth.find("bench_mixed_xv(-0.145, 0.0101") != std::string::npos);
    CHECK(r.named == std::vector<std::string>{"unexplained_x_v"});
    CHECK_FALSE(r.false_claim);
    CHECK(r.after <= 1.1 * r.noise);
}

TEST_CASE("shape: a polynomial in v is a shape of v, not a curved sensor") {
    // A sensor's x^2 differentiates into a v^2 force: the generic force of v beside the curvature predicts
    // held-out data better and does as well alone.
    const id::IdentifyBenchRecord r = bench_record(144);
    CHECK(r.truth.find("bench_poly_v(0, -0.261, -0.249, -0.174") != std::string::npos);
    CHECK(r.named == std::vector<std::string>{"unexplained_v"});
    CHECK_FALSE(r.false_claim);
    CHECK(r.better);
}
