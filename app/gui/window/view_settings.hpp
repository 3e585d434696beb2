// The display settings the user chooses (theme, UI scale, trail and strip lengths, the section phase) and
// which floating windows are open. Sessions save most of them. UI thread only.
#pragma once

namespace impactlab::gui {

struct ViewSettings {
    bool dark = true;
    float ui_scale = 1.0f;
    bool fonts_dirty = true;      // the fonts are rebuilt for ui_scale before the next frame
    float trail_periods = 8.0f;
    float strip_window = 6.0f;
    double section_phase = 0;     // [rad] the Poincare section's phase phi0, as last sent
    bool details = false;         // the status bar's technical fields
    bool show_help = false;
    bool show_data = false;       // "Measured data"
    bool show_params = false;     // the parameters panel (F4)
};

}  // namespace impactlab::gui
