// The time strip's quantities by key, GL-free: the strip view, the --strip flag and session files read the
// one list (its order is StripQuantity's: x, v, E, F, drive).
#pragma once

namespace impactlab::gui {

inline constexpr const char* kStripKeys[] = {"x", "v", "E", "F", "drive"};

}  // namespace impactlab::gui
