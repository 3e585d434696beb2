// The mouse sets the state: a click in the phase portrait gives (x, v), in the potential well x
// at v = 0, a drag of the cart holds it at the mouse. What is asked is checked here before it becomes a
// SimCommand: kept on the rail, never beyond the bumper (put on it, with a note the UI shows as a toast).
// And a plain click becomes a state only once no second click has made it a double-click (which gives the
// plot's view back to its auto-fit). GL-free; UI thread.
#pragma once

#include <optional>
#include <string>

#include "impactlab/params.hpp"

namespace impactlab::gui {

struct PickedState {
    double x = 0, v = 0;   // [m], [m/s]
    std::string note;      // why x or v was moved ("" when taken as asked)
};

// xI: the bumper as the user sees it [m]; has_bumper: the model has one.
PickedState pick_state(double x, double v, double xI, bool has_bumper);

class ClickDelay {
public:
    // A plain click released at `now` [s] asking for (x, v).
    void click(double x, double v, double now);
    // The second click of a double-click: the first one was for the view, not for the state.
    void double_clicked() {
        pending_ = false;
        swallow_ = true;   // its release is no click of its own
    }
    // The asked (x, v) once `delay` [s] passed without a double-click; then forgotten.
    std::optional<std::pair<double, double>> due(double now, double delay);
    bool pending() const { return pending_; }

private:
    bool pending_ = false, swallow_ = false;
    double x_ = 0, v_ = 0, t_ = 0;
};

}  // namespace impactlab::gui
