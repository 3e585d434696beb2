// The toast: one short message shown in the corner for a few seconds. UI thread only.
#pragma once

#include <string>

namespace impactlab::gui {

struct Toast {
    static constexpr double kShownFor = 4.0;   // [s]
    std::string text;
    double until = 0;   // [s] wall time it goes

    void show(const std::string& msg, double now) {
        text = msg;
        until = now + kShownFor;
    }
    bool visible(double now) const { return !text.empty() && now <= until; }
};

}  // namespace impactlab::gui
