#include "opaque_image.hpp"

#include <GL/glext.h>

#include <cstdint>
#include <vector>

#include "embedded_shaders.hpp"
#include "render/gl_util.hpp"

namespace impactlab::gui::opaque_image {

namespace {

struct Item {
    GLuint tex;
    ImVec2 min, max, uv0, uv1;
};

GLuint g_prog = 0, g_vao = 0;
GLint g_rect = -1, g_uv = -1, g_display_pos = -1, g_display_size = -1, g_tex = -1;
std::vector<Item> g_items;   // this frame's images (the callbacks refer to them by index)

void draw_item(const ImDrawList*, const ImDrawCmd* cmd) {
    const auto index = static_cast<std::size_t>(reinterpret_cast<std::intptr_t>(cmd->UserCallbackData));
    if (index >= g_items.size()) return;
    const Item& it = g_items[index];
    if (!scissor_to_clip(cmd->ClipRect)) return;
    draw(it.tex, it.min, it.max, it.uv0, it.uv1);
    // ImGui restores its own state with the ImDrawCallback_ResetRenderState queued after this callback.
}

}  // namespace

bool draw(GLuint tex, ImVec2 min, ImVec2 max, ImVec2 uv0, ImVec2 uv1) {
    const ImDrawData* dd = ImGui::GetDrawData();
    if (!g_prog || !dd) return false;
    glDisable(GL_BLEND);
    glUseProgram(g_prog);
    glUniform4f(g_rect, min.x, min.y, max.x, max.y);
    glUniform4f(g_uv, uv0.x, uv0.y, uv1.x, uv1.y);
    glUniform2f(g_display_pos, dd->DisplayPos.x, dd->DisplayPos.y);
    glUniform2f(g_display_size, dd->DisplaySize.x, dd->DisplaySize.y);
    glUniform1i(g_tex, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex);
    glBindVertexArray(g_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    return true;
}

bool init(std::string& error) {
    g_prog = build_program(shaders::image_opaque_vert, shaders::image_opaque_frag, "image_opaque", error);
    if (!g_prog) return false;
    g_rect = glGetUniformLocation(g_prog, "u_rect");
    g_uv = glGetUniformLocation(g_prog, "u_uv");
    g_display_pos = glGetUniformLocation(g_prog, "u_display_pos");
    g_display_size = glGetUniformLocation(g_prog, "u_display_size");
    g_tex = glGetUniformLocation(g_prog, "u_tex");
    glGenVertexArrays(1, &g_vao);
    return true;
}

void shutdown() {
    if (g_vao) glDeleteVertexArrays(1, &g_vao);
    if (g_prog) glDeleteProgram(g_prog);
    g_vao = g_prog = 0;
}

bool ready() { return g_prog != 0; }

void begin_frame() { g_items.clear(); }

void add(ImDrawList* dl, GLuint tex, ImVec2 min, ImVec2 max, ImVec2 uv0, ImVec2 uv1) {
    const auto id = reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex));
    if (!g_prog) {
        dl->AddImage(id, min, max, uv0, uv1);
        return;
    }
    g_items.push_back({tex, min, max, uv0, uv1});
    dl->AddCallback(draw_item, reinterpret_cast<void*>(static_cast<std::intptr_t>(g_items.size() - 1)));
    dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
}

}  // namespace impactlab::gui::opaque_image
