// Named starting points that land on interesting attractors, per model version. Each preset is a reset to
// (x0, v0 = 0) in the left well with xI = 0 at a chosen omega; the attractor reached is deterministic.
// Found with `impactlab poincare --model M --omega W --periods 64 --transient 300 --x0 -0.011` (see the
// table's comments). GL-free.
#pragma once

#include <string>
#include <vector>

namespace impactlab::gui {

struct Preset {
    const char* label;    // "Period 1", ...
    double omega;         // [rad/s]
    double x0;            // [m]
    int period;           // distinct Poincare points on the attractor; 0 for chaos
    const char* note;     // one line shown as a tooltip
};

// The presets for a model version ("A1H"); never empty for the built-in versions.
std::vector<Preset> presets_for(const std::string& model);

}  // namespace impactlab::gui
