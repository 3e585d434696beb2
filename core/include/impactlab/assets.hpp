// The data files the programs read at run time (the font, the window icon): where an installed program
// finds them, PREFIX/share/impactlab next to PREFIX/bin, found from the program's own location so an
// installed impactlab runs from any directory; else the source tree's assets/ (a build that was not
// installed).
#pragma once

#include <string>

namespace impactlab {

// The path of `relative` (as "fonts/DejaVuSans.ttf") under the first folder that holds it:
// <program>/../share/impactlab, then the source tree's assets/. "" if neither does.
std::string asset_path(const std::string& relative);

}  // namespace impactlab
