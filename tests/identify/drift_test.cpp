// A parameter that drifts over the record: each drift is named with its parameter and its rate, also on a
// record whose clock starts late (time is measured from the record's start, so a drift is not read as a
// constant change times the clock, nor the other way round).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "fit_cases.hpp"
#include "impactlab/identify.hpp"

namespace id = impactlab::identify;
using id::test::short_run;

namespace {
double value(const std::vector<std::pair<std::string, double>>& v, const std::string& k) {
    for (const auto& [n, x] : v)
        if (n == k) return x;
    return NAN;
}

id::FitReport fit_shifted(const id::Model& truth, double shift) {
    id::MeasuredData d = id::synthesize(truth, short_run(7));
    for (double& t : d.t) t += shift;
    id::FitOptions fo;
    fo.plots = false;
    return id::run_fit(d, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
}
}  // namespace

TEST_CASE("drift: each drifting parameter is named with its rate, on a record starting at 0 s and at 1000 s") {
    const std::pair<const char*, double> cases[] = {
        {"unbalance_drift", -3e-3}, {"damping_drift", 1e-2}, {"friction_drift", 1e-2}, {"stiffness_drift", -1.5e-3}, {"magnet_drift", -3e-3}};
    for (const auto& [effect, r] : cases)
        for (double shift : {0.0, 1000.0}) {
            CAPTURE(effect);
            CAPTURE(shift);
            id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
            id::apply_effect(truth, effect, {{"r", r}});
            const id::FitReport rep = fit_shifted(truth, shift);
            CAPTURE(rep.verdict);
            REQUIRE(rep.effects_found.size() == 1);
            const id::FoundEffect& f = rep.effects_found.front();
            CHECK(f.id == effect);
            const double got = value(f.parameters, "r"), se = value(f.sigma, "r");
            CAPTURE(got);
            CAPTURE(se);
            CHECK(std::abs(got - r) <= std::max(3.0 * se, 0.03 * std::abs(r)));
            // Its time origin is the record's start, written with the model.
            REQUIRE(rep.after.p.effects.size() == 1);
            const impactlab::EffectInstance& inst = rep.after.p.effects.front();
            for (std::size_t k = 0; k < impactlab::kMaxLawParams && inst.law->names[k]; ++k)
                if (std::string(inst.law->names[k]) == "t0") CHECK(inst.p[k] == doctest::Approx(shift));
            CHECK(f.sentence.find("% per second") != std::string::npos);
            CHECK(rep.error_after.shooting_rms_1_m < 2.0 * rep.sigma_x);
        }
}
