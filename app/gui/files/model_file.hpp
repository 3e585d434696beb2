// --model FILE.json in the visualiser: the parameter file read by the core's own parser (load_params, as
// every CLI --model does), then said in the GUI's terms: a built-in version, the parameters the Parameters
// panel edits, and x_I. What the GUI cannot show exactly (another stiffness polynomial, force effects, a
// bumper beyond the slider's +-20 mm) is refused, naming the key, rather than run as something else.
// GL- and ImGui-free.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impactlab::gui {

struct ModelFileError : std::runtime_error { using std::runtime_error::runtime_error; };

struct GuiModel {
    std::string version;                                 // "A1G": the stiffness set and the impact law
    std::vector<std::pair<std::string, double>> params;  // the panel's keys whose values differ from it
    double xI = 0;                                       // [m]
    std::string name;                                    // the file's "name"
};

// Throws ModelFileError with the core's message ("FILE: key 'k': ...") or "FILE: key 'K': the visualiser
// cannot show ..." for what it cannot run as given.
GuiModel gui_model_from_file(const std::string& path);

}  // namespace impactlab::gui
