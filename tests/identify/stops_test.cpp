// Impacts the model has no stop for: reversals at the end of the travel away from the bumper are found in
// the data, kept out of the equation error, and named an end stop with its place and restitution, never a
// smaller unbalance or a heavier cart.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "fit_cases.hpp"
#include "identify/internal.hpp"
#include "impactlab/identify.hpp"

namespace id = impactlab::identify;
using id::test::analyse;
using id::test::named;
using id::test::short_run;

namespace {
double value(const std::vector<std::pair<std::string, double>>& v, const std::string& k) {
    for (const auto& [n, x] : v)
        if (n == k) return x;
    return NAN;
}
// The restitution of the stop's spring-dashpot contact for a cart of mass m.
double restitution(double kS, double cS, double m) {
    const double z = cS / (2.0 * std::sqrt(kS * m));
    return std::exp(-3.141592653589793 * z / std::sqrt(1.0 - z * z));
}
}  // namespace

TEST_CASE("stops: a second stop below the travel is named end_stop at its place, and nothing else") {
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    const double xS = -0.0165, kS = 1e7, cS = 2000.0;
    id::apply_effect(truth, "end_stop", {{"xS", xS}, {"kS", kS}, {"cS", cS}, {"side", -1.0}});
    const id::FitReport r = analyse(truth, short_run(3));
    REQUIRE(r.effects_found.size() == 1);
    const id::FoundEffect& f = r.effects_found.front();
    CHECK(f.id == "end_stop");
    CHECK(f.evidence == id::Evidence::StrayImpacts);
    const double got = value(f.parameters, "xS"), se = value(f.sigma, "xS");
    CAPTURE(got);
    CAPTURE(se);
    CHECK(std::abs(got - xS) <= 3.0 * se);
    CHECK(std::abs(got - xS) < 1e-4);
    CHECK(value(f.parameters, "side") == -1.0);
    CHECK(restitution(value(f.parameters, "kS"), value(f.parameters, "cS"), truth.p.m) ==
          doctest::Approx(restitution(kS, cS, truth.p.m)).epsilon(0.08));
    // The model written predicts what the model given could not.
    CHECK(r.error_after.shooting_rms_1_m < 0.05 * r.error_before.shooting_rms_1_m);
    CHECK(r.error_after.shooting_rms_1_m < 2.0 * r.sigma_x);
}

TEST_CASE("stops: no reversal away from the bumper in a record without a second stop") {
    for (const char* version : {"A1H", "A1C", "A3G"}) {
        CAPTURE(version);
        const id::Model m = id::resolve_fit_model(version, id::Forcing::Unbalance);
        const id::MeasuredData d = id::synthesize(m, short_run(4));
        std::vector<std::string> notes;
        id::FitOptions o;
        const id::detail::Prep pr = id::detail::prepare(d, m, o, notes);
        CHECK(pr.stray.empty());
        CHECK(pr.stray_side == 0);
    }
}

TEST_CASE("FitOptions::wants: --exclude always wins; an --only list admits just its ids") {
    impactlab::identify::FitOptions o;
    CHECK(o.wants("end_stop"));
    CHECK(o.wants("viscous_damping"));
    o.only = {"end_stop", "viscous_damping"};
    CHECK(o.wants("end_stop"));
    CHECK(!o.wants("coulomb_friction"));
    o.exclude = {"end_stop"};
    CHECK(!o.wants("end_stop"));
    CHECK(o.wants("viscous_damping"));
    o.only.clear();
    CHECK(!o.wants("end_stop"));
    CHECK(o.wants("coulomb_friction"));
}
