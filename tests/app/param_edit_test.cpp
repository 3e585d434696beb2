// The parameters panel's edits (app/gui/sim/param_edit.hpp) and the engine's SetParam / ResetParams: a value the
// core's validate() takes changes the model live (x, v, phi kept), one it refuses changes nothing.
#include <doctest/doctest.h>

#include <string>

#include "../../app/gui/sim/param_edit.hpp"
#include "../../app/gui/sim/sim_engine.hpp"
#include "engine_fixtures.hpp"

using namespace impactlab;
using namespace impactlab::gui;
using namespace impactlab::gui::testing;

TEST_CASE("param_edit: a valid value is taken, a refused one changes nothing and says why") {
    const Params paper = make_version("A1C");
    Params p = paper;
    std::string err;
    CHECK_FALSE(params_edited(p));
    CHECK(set_param(p, "k", 1200.0, err));
    CHECK(err.empty());
    CHECK(p.k == 1200.0);
    CHECK(params_edited(p));
    CHECK(set_param(p, "kI", 2.0 * paper.ip[0], err));   // the compliant law's own stiffness
    CHECK(p.ip[0] == 2.0 * paper.ip[0]);
    const Params before = p;
    CHECK_FALSE(set_param(p, "m", -1.0, err));           // outside the validated range
    CHECK(err.rfind("must lie in [", 0) == 0);         // the reason alone: the caller names the key
    CHECK(err.find("key 'm'") == std::string::npos);
    CHECK(p.m == before.m);
    CHECK_FALSE(set_param(p, "kappa0", 0.5, err));       // C has no restitution coefficient
    CHECK(err.find("kappa0") != std::string::npos);
    CHECK_FALSE(set_param(p, "no_such", 1.0, err));
    // The panel lists the rig's six and the law's, with the paper's values beside the edited ones.
    const auto list = editable_params(p);
    REQUIRE(list.size() >= 7);
    CHECK(list[0].key == "m");
    bool saw_k = false;
    for (const auto& e : list)
        if (e.key == "k") {
            saw_k = true;
            CHECK(e.value == 1200.0);
            CHECK(e.paper == paper.k);
        }
    CHECK(saw_k);
}

TEST_CASE("engine: SetParam changes the running model live, ResetParams brings the version back") {
    VectorSink sink;
    SimEngine e(config("A1H", 12.0), &sink);
    e.advance_to(1.0);
    const double x = e.state().x, v = e.state().v, phi = e.phi();
    const auto epoch = e.epoch();
    REQUIRE(e.apply(SimCommand::set_param("m0e", 0.0)));
    CHECK(e.params().m0e == 0.0);
    CHECK(e.params().name == "A1H");
    CHECK(e.state().x == x);
    CHECK(e.state().v == v);
    CHECK(e.phi() == phi);
    CHECK(e.epoch() == epoch + 1);
    // Refused by validate(): nothing changes, no new epoch.
    CHECK_FALSE(e.apply(SimCommand::set_param("eps", 0.0)));
    CHECK(e.params().eps == make_version("A1H").eps);
    CHECK(e.epoch() == epoch + 1);
    // Without the unbalance the cart comes to rest in its well.
    e.advance_to(60.0);
    CHECK(std::abs(e.state().v) < 1e-3);
    REQUIRE(e.apply(SimCommand::reset_params()));
    CHECK(e.params().m0e == make_version("A1H").m0e);
}
