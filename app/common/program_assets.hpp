// The data files the programs read at run time (the font, the window icon), found by the program, not by
// core: an installed program finds them in PREFIX/share/impactlab next to PREFIX/bin, from its own
// location, so it runs from any directory; a build that was not installed finds the source tree's assets/.
// Each program (the CLI, the GUI, the tests) hands core's plot layer its font once at start.
#pragma once

#include <string>
#include <vector>

namespace impactlab {

// The path of `relative` (as "fonts/DejaVuSans.ttf") under the first folder that holds it:
// <program>/../share/impactlab, then the source tree's assets/. "" if neither does.
std::string asset_path(const std::string& relative);

// The font files to try, in order: $IMPACTLAB_FONT when set, the program's DejaVuSans (asset_path), the
// system's DejaVuSans.
std::vector<std::string> font_files();

// Hands font_files() to core's plot layer (plot::set_font_files), before any figure is drawn.
void use_program_fonts();

}  // namespace impactlab
