// Small ImGui helpers every panel uses (one copy instead of one per panel). UI thread.
#pragma once

#include <imgui.h>

namespace impactlab::gui {

// The last item's hover text, wrapped at about 24 em.
void tooltip(const char* text);
// The next item on the same line if `next_w` pixels still fit in the window's content region, else on the
// next line: a row of buttons wraps instead of running off a narrow panel (a large UI scale).
void same_line_or_wrap(float next_w);
// The width of a button labelled `label` (its text and frame padding) [px].
float button_width(const char* label);

// Text wrapped to the content region at spaces only: ImGui's own wrap also breaks after '.', ',' and ';',
// which splits a number ("cq = 4." / "001").
void text_wrapped_at_spaces(const char* text);

// A text on a dark (or light) plate that keeps it readable over plots and the rig; align as ImGui's (0:
// left/top, 1: right/bottom of the text at p).
void plate_text(ImDrawList* dl, ImVec2 p, const char* text, ImU32 col, ImVec2 align = ImVec2(0, 0));

}  // namespace impactlab::gui
