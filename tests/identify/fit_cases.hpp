// What the loop tests share: the short synthetic record they analyse and the analysis itself.
#pragma once

#include <algorithm>
#include <string>

#include "impactlab/identify.hpp"

namespace impactlab::identify::test {

// 20 s at the default rate: steps at 9 and 16 rad/s, periodic then chaotic with impacts.
inline SynthOptions short_run(unsigned seed) {
    SynthOptions o;
    o.duration = 20.0;
    o.seed = seed;
    steps_profile({9.0, 16.0}, 9.0, 2.0, o.knot_t, o.knot_omega);
    return o;
}

// impactlab fit without plots: `truth` synthesized with `so`, analysed with the version `model`.
inline FitReport analyse(const Model& truth, const SynthOptions& so, const std::string& model = "A1H") {
    FitOptions fo;
    fo.plots = false;
    return run_fit(synthesize(truth, so), resolve_fit_model(model, Forcing::Unbalance), fo);
}

// Whether the fit named `effect` among the effects it kept.
inline bool named(const FitReport& r, const std::string& effect) {
    return std::any_of(r.effects_found.begin(), r.effects_found.end(), [&](const FoundEffect& f) { return f.id == effect; });
}

}  // namespace impactlab::identify::test
