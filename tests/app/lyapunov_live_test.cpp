// The state panel's live Lyapunov exponent: its sign tells a periodic orbit from chaos, and a change of
// omega drops the old attractor's value.
#include <doctest/doctest.h>

#include <cmath>

#include "../../app/gui/analysis/lyapunov_live.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;

TEST_CASE("live Lyapunov: negative on A1H's period 1 at 9 rad/s, positive in its chaos at 16 rad/s") {
    const Params p = make_version("A1H");
    gui::LiveLyapunov live;
    CHECK(live.text() == "(omega = 0: no forcing period)");
    live.update(p, 9.0, -0.011, 0.0, 0.0);
    CHECK(live.text() == "computing...");
    live.wait();
    live.update(p, 9.0, -0.011, 0.0, 0.1);
    CAPTURE(live.text());
    CHECK(live.value() < -0.02);
    CHECK(live.text().find("settles") != std::string::npos);
    // A new omega: the old value is dropped at once, the new one computed.
    live.update(p, 16.0, -0.011, 0.0, 0.2);
    CHECK(std::isnan(live.value()));
    live.wait();
    live.update(p, 16.0, -0.011, 0.0, 0.3);
    live.wait();
    live.update(p, 16.0, -0.011, 0.0, 0.4);
    CAPTURE(live.text());
    CHECK(live.value() > 0.02);
    CHECK(live.text().find("chaos") != std::string::npos);
}
