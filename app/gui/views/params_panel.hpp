// The parameters panel (F4, View > Parameters): m, c, k, T, m0e, eps and the impact law's own parameters of
// the running model, edited live (x, v and phi carry on), each checked by the core's validate() before it is
// sent, with a reset to the version's values from the paper. It takes a Context and returns an Action; the
// App applies it. UI thread.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "impactlab/params.hpp"

namespace impactlab::gui {

struct ParamsContext {
    const Params* params = nullptr;   // the UI's copy of the running model
    std::string model;                // its version's name
    float ui_scale = 1;
};

struct ParamsAction {
    std::optional<std::pair<std::string, double>> set;   // a key and its new value
    bool reset = false;                                  // every value back to the version's
};

class ParamsPanel {
public:
    // Inside its own window; *open goes false when the user closes it.
    ParamsAction draw(bool* open, const ParamsContext& c);
    // The last refusal (the core's words), "" when the last edit was taken.
    void set_error(std::string e) {
        if (!e.empty()) edit_for_.clear();   // a refused value: the fields show the running ones again
        error_ = std::move(e);
    }

private:
    std::vector<double> edit_;   // the fields' values while typed
    std::string edit_for_;       // the model (and values) the fields were filled from
    std::string error_;
};

}  // namespace impactlab::gui
