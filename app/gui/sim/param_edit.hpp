// The parameters panel's edits of the running model (m, c, k, T, m0e, eps and the impact law's own
// parameters), checked by the core's validate() so that the panel, --param and the simulation thread refuse
// the same values with the same words. GL- and ImGui-free.
#pragma once

#include <string>
#include <vector>

#include "impactlab/params.hpp"

namespace impactlab::gui {

struct EditableParam {
    std::string key;    // "m", "c", ..., or the impact law's name ("kI", "kappa0", ...)
    std::string unit;
    double value = 0;
    double paper = 0;   // the version's own value (the reset)
};

// The keys the panel offers for p, in order: the rig's six, then the impact law's.
std::vector<EditableParam> editable_params(const Params& p);
// Sets key to value in p if the result validates; else p is unchanged and error says why: the core's
// reason (the range and what it means), without the key, which the caller names ("key 'k': " is kept
// where another key's limit refused the value).
bool set_param(Params& p, const std::string& key, double value, std::string& error);
// True when p differs from its version's values in any editable parameter.
bool params_edited(const Params& p);

}  // namespace impactlab::gui
