// Small ImGui helpers every panel uses (one copy instead of one per panel). UI thread.
#pragma once

#include <imgui.h>

namespace impactlab::gui {

// The last item's hover text, wrapped at about 24 em.
void tooltip(const char* text);

// A text on a dark (or light) plate that keeps it readable over plots and the rig; align as ImGui's (0:
// left/top, 1: right/bottom of the text at p).
void plate_text(ImDrawList* dl, ImVec2 p, const char* text, ImU32 col, ImVec2 align = ImVec2(0, 0));

}  // namespace impactlab::gui
