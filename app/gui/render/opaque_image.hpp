// Opaque images drawn in an ImDrawList's order without blending: the plots' data areas (composited on the
// CPU, backdrop and grid included) and the rig's image. Under Mesa's llvmpipe an unblended plain texture
// copy is a blit (memory speed) and lets the rasterizer drop what lies under it, where ImGui's blended,
// colour-modulated AddImage costs several nanoseconds per pixel: this is most of a frame's rendering.
// Main (GL) thread only.
#pragma once

#include <imgui.h>

#include <GL/gl.h>

#include <string>

namespace impactlab::gui::opaque_image {

// Compiles the shaders; false (with the log) if the driver refuses them: add() then falls back to AddImage.
bool init(std::string& error);
void shutdown();
bool ready();

// Frame protocol: begin_frame() before building the UI; add() while drawing.
void begin_frame();
// Queues texture `tex` (every texel opaque) over [min, max) in display pixels, uv0 at min and uv1 at max,
// at this point of `dl`'s draw order and inside its current clip rectangle.
void add(ImDrawList* dl, GLuint tex, ImVec2 min, ImVec2 max, ImVec2 uv0 = ImVec2(0, 0), ImVec2 uv1 = ImVec2(1, 1));
// Draws one now, from inside a draw-list callback (ImGui's viewport over the whole framebuffer, the caller's
// scissor); leaves blending off and this module's program bound. False if the shader is not there.
bool draw(GLuint tex, ImVec2 min, ImVec2 max, ImVec2 uv0 = ImVec2(0, 0), ImVec2 uv1 = ImVec2(1, 1));

}  // namespace impactlab::gui::opaque_image
