// The effect registry and the catalogue of impactlab fit: every law's partial derivatives match finite
// differences (the integrator's Newton matrix uses them), and base-changing effects edit the model.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "impactlab/identify.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;

TEST_CASE("effect laws: derivatives agree with finite differences") {
    for (const auto& law : effect_laws()) {
        CAPTURE(law.id);
        std::array<double, kMaxLawParams> p = law.defaults;
        // Give every effect a nonzero strength (and the generic ones a range and a shape).
        const std::string id = law.id;
        if (id.rfind("unexplained_", 0) == 0 && id != "unexplained_phi") p = {-0.02, 0.01, 0.3, -0.2, 0.5, 0.1, -0.4, 0.2};
        else if (id == "unexplained_phi") p = {0.3, -0.2, 0.1, 0.05, -0.1, 0.2, 0, 0};
        else if (id == "magnet_offset") p[0] = 5e-4;
        else if (id == "stribeck_friction") p = {0.5, 0.02};
        else if (id == "sensor_gain" || id == "tangential_unbalance") p[0] = 1.0;
        else p[0] = 0.7;
        for (double x : {-0.012, -0.004, 0.003})
            for (double v : {-0.15, 0.05, 0.3}) {
                const double t = 1.3, phi = 2.1, w = 14.0, al = 1.5;
                auto F = [&](double tt, double xx, double vv) {
                    const double ph = phi + w * (tt - t) + 0.5 * al * (tt - t) * (tt - t);
                    return law.force(p.data(), {tt, xx, vv, ph, w + al * (tt - t), al, 0.025152, 0.0}).F;
                };
                const EffectForce f = law.force(p.data(), {t, x, v, phi, w, al, 0.025152, 0.0});
                const double hx = 1e-7, hv = 1e-6, ht = 1e-6;
                const double dx = (F(t, x + hx, v) - F(t, x - hx, v)) / (2 * hx);
                const double dv = (F(t, x, v + hv) - F(t, x, v - hv)) / (2 * hv);
                const double dt = (F(t + ht, x, v) - F(t - ht, x, v)) / (2 * ht);
                CHECK(f.dF_dx == doctest::Approx(dx).epsilon(1e-4).scale(1.0));
                CHECK(f.dF_dv == doctest::Approx(dv).epsilon(1e-4).scale(1.0));
                CHECK(f.dF_dt == doctest::Approx(dt).epsilon(1e-4).scale(1.0));
            }
    }
}

TEST_CASE("effect catalogue: every registry law plus the base-changing effects") {
    for (const auto& law : effect_laws()) CHECK(identify::find_catalogue_effect(law.id) != nullptr);
    for (const char* id : {"bumper_offset", "impact_duration", "restitution", "cart_mass"}) {
        const auto* e = identify::find_catalogue_effect(id);
        REQUIRE(e != nullptr);
        CHECK(e->changes_base);
    }
    identify::Model m = identify::resolve_fit_model("A1C", identify::Forcing::Unbalance);
    identify::apply_effect(m, "bumper_offset", {{"", 5e-4}});
    CHECK(m.p.xI == doctest::Approx(5e-4));
    identify::apply_effect(m, "impact_duration", {{"", 6e-3}});   // a compliant bumper becomes rigid
    CHECK(m.p.rigid());
    CHECK(m.p.ip[3] == doctest::Approx(6e-3));
    CHECK(m.p.ip[4] == doctest::Approx(6e-3));
    identify::apply_effect(m, "sensor_offset", {{"o", 2e-4}});
    identify::apply_effect(m, "sensor_gain", {{"", 1.02}});
    CHECK(m.sensor_offset() == doctest::Approx(2e-4));
    CHECK(m.sensor_gain() == doctest::Approx(1.02));
    identify::apply_effect(m, "stribeck_friction", {{"", 0.4}, {"vs", 0.03}});
    CHECK(m.p.effects.back().p[1] == doctest::Approx(0.03));
    identify::apply_effect(m, "cart_mass", {{"dm", -0.2}});   // moves m, adds no force
    CHECK(m.p.m == doctest::Approx(6.73766 - 0.2));
    CHECK_THROWS_AS(identify::apply_effect(m, "cart_mass", {{"dm", -7.0}}), ParamError);
    CHECK_THROWS_AS(identify::apply_effect(m, "no_such_effect", {}), ParamError);
    CHECK_THROWS_AS(identify::apply_effect(m, "constant_force", {{"F9", 1.0}}), ParamError);
    const identify::Model duffing = identify::resolve_fit_model("duffing", identify::Forcing::Input);
    CHECK_FALSE(duffing.bumper());
    CHECK(duffing.p.m == 1.0);
}

TEST_CASE("effect laws carry their own metadata: fit hints in range, a sentence, sensors map x affinely") {
    for (const auto& law : effect_laws()) {
        CAPTURE(law.id);
        std::size_t n = 0;
        while (n < kMaxLawParams && law.names[n]) ++n;
        const EffectFitHint& h = law.fit;
        // Every registry effect is one fit can look for: screened on the equation error, or proposed from the
        // reversals the model cannot make.
        REQUIRE((h.n_free > 0 || h.from_reversals));
        CHECK(h.n_linear <= h.n_free);
        for (int k = 0; k < h.n_free; ++k) {
            const auto i = static_cast<std::size_t>(h.free[static_cast<std::size_t>(k)]);
            CHECK(i < n);
            CHECK(h.step[i] > 0);
            CHECK(h.lo[i] < h.hi[i]);
        }
        // A nonlinear parameter needs trial values, or a start the data give (the period of a cycle they show).
        if (h.n_free > h.n_linear) CHECK((h.n_starts > 0 || (h.needs & FitNeeds::Cycle) != 0));
        REQUIRE(static_cast<bool>(law.describe));
        std::array<double, kMaxLawParams> p = law.defaults, s{};
        p[0] = law.kind == EffectKind::Sensor && std::string(law.id) == "sensor_gain" ? 1.02 : 0.3;
        if (h.generic && std::string(law.id) != "unexplained_phi") {
            p[0] = -0.01;
            p[1] = 0.01;
            p[2] = 0.5;
        }
        s[0] = 0.01;
        const Params model = make_version("A1H");
        const std::string text = law.describe(p.data(), s.data(), {&model, true, 0.2, 0.012});
        CHECK(text.size() > 20);
        if (law.kind == EffectKind::Sensor) {
            REQUIRE(static_cast<bool>(law.measure));
            const double m0 = law.measure(p.data(), 0.0), m1 = law.measure(p.data(), 1.0), m2 = law.measure(p.data(), 2.0);
            if (law.curved) CHECK(m2 - m1 != doctest::Approx(m1 - m0));   // a curve
            else CHECK(m2 - m1 == doctest::Approx(m1 - m0));              // affine
            CHECK(law.force(p.data(), {0, 0.01, 0.1, 0, 10, 0, 0.025, 0}).F == 0.0);   // no force
        }
    }
    // The model's measurement map combines them: gains multiply, offsets add.
    identify::Model m = identify::resolve_fit_model("A1H", identify::Forcing::Unbalance);
    identify::apply_effect(m, "sensor_offset", {{"o", 2e-4}});
    identify::apply_effect(m, "sensor_gain", {{"g", 1.05}});
    CHECK(m.sensor_gain() == doctest::Approx(1.05));
    CHECK(m.sensor_offset() == doctest::Approx(2e-4));
}
