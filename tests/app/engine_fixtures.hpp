// What the headless engine tests share: a sink that keeps every record, and an engine configuration.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "../../app/gui/sim/sim_engine.hpp"

namespace impactlab::gui::testing {

struct VectorSink final : MsgSink {
    std::vector<SimMsg> msgs;
    void put(const SimMsg& m) override { msgs.push_back(m); }
    std::size_t count(MsgKind k) const {
        std::size_t n = 0;
        for (const auto& m : msgs) n += m.kind == k;
        return n;
    }
    std::vector<SimMsg> of(MsgKind k) const {
        std::vector<SimMsg> r;
        for (const auto& m : msgs)
            if (m.kind == k) r.push_back(m);
        return r;
    }
};

inline EngineConfig config(const std::string& model, double omega, double x0 = -0.011) {
    EngineConfig c;
    c.model = model;
    c.omega = omega;
    c.x0 = x0;
    return c;
}

}  // namespace impactlab::gui::testing
