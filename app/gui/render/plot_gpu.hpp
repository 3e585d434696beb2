// The GPU side of the plotting layer: curves and markers with many points are not tessellated by ImGui
// but queued here (positions already in display pixels), uploaded once per frame into one vertex buffer,
// and drawn by the shaders plot_lines.* / plot_points.* from an ImDrawList callback, so they sit in the
// right place between the plot's background and its overlays and obey its clip rectangle.
// Main (GL) thread only.
#pragma once

#include <imgui.h>

#include <cstddef>
#include <string>

namespace impactlab::gui::plot_gpu {

struct Vtx {
    float x, y;    // display pixels
    float alpha;   // 0..1, multiplies the batch colour
    float pad;
};

// Compiles the shaders; false (with the log) if the driver refuses them; the plots then fall back to ImDrawList.
bool init(std::string& error);
void shutdown();
bool ready();

// Frame protocol: begin_frame() before building the UI; add_*() while drawing plots; upload() after
// ImGui::Render() and before the backend renders the draw data.
void begin_frame();
// Queues a polyline (n points) or markers and records the callback in `dl` at the current clip rect.
void add_lines(ImDrawList* dl, const Vtx* pts, std::size_t n, ImU32 color, float thickness);
void add_points(ImDrawList* dl, const Vtx* pts, std::size_t n, ImU32 color, float size);
void upload();
// Points queued in the current frame (benchmark).
std::size_t queued_points();

}  // namespace impactlab::gui::plot_gpu
