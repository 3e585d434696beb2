#include "plot_gpu.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>
#include <vector>

#include "embedded_shaders.hpp"
#include "render/gl_util.hpp"

namespace impactlab::gui::plot_gpu {

namespace {

struct Batch {
    bool lines;
    GLint first;
    GLsizei count;
    float color[4];
    float half;   // half line width or marker radius [px]
};

struct Program {
    GLuint id = 0;
    GLint display_pos = -1, display_size = -1, half = -1, color = -1;
    void locate() {
        display_pos = glGetUniformLocation(id, "u_display_pos");
        display_size = glGetUniformLocation(id, "u_display_size");
        half = glGetUniformLocation(id, "u_half");
        color = glGetUniformLocation(id, "u_color");
    }
};

Program g_lines, g_points;
GLuint g_vao = 0, g_vbo = 0;
std::vector<Vtx> g_vtx;
std::vector<Batch> g_batches;
GLsizeiptr g_capacity = 0;

void draw_batch(const ImDrawList*, const ImDrawCmd* cmd) {
    const auto index = static_cast<std::size_t>(reinterpret_cast<std::intptr_t>(cmd->UserCallbackData));
    if (index >= g_batches.size()) return;
    const Batch& b = g_batches[index];
    if (!scissor_to_clip(cmd->ClipRect)) return;   // the plot's clip rectangle
    const ImDrawData* dd = ImGui::GetDrawData();
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    const Program& p = b.lines ? g_lines : g_points;
    glUseProgram(p.id);
    glUniform2f(p.display_pos, dd->DisplayPos.x, dd->DisplayPos.y);
    glUniform2f(p.display_size, dd->DisplaySize.x, dd->DisplaySize.y);
    glUniform1f(p.half, b.half);
    glUniform4fv(p.color, 1, b.color);
    glBindVertexArray(g_vao);
    glBindBuffer(GL_ARRAY_BUFFER, g_vbo);
    const auto offset = [](GLint i) { return reinterpret_cast<const void*>(static_cast<std::intptr_t>(i) * sizeof(Vtx)); };
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(Vtx), offset(b.first));
    glVertexAttribDivisor(0, 1);
    if (b.lines) {
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vtx), offset(b.first + 1));
        glVertexAttribDivisor(1, 1);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, b.count - 1);
    } else {
        glDisableVertexAttribArray(1);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, b.count);
    }
    // ImGui restores its own state with the ImDrawCallback_ResetRenderState queued after this callback.
}

void add(ImDrawList* dl, const Vtx* pts, std::size_t n, ImU32 color, float half, bool lines) {
    if (!g_lines.id || n < (lines ? 2u : 1u)) return;
    Batch b;
    b.lines = lines;
    b.first = static_cast<GLint>(g_vtx.size());
    b.count = static_cast<GLsizei>(n);
    const ImVec4 c = ImGui::ColorConvertU32ToFloat4(color);
    b.color[0] = c.x;
    b.color[1] = c.y;
    b.color[2] = c.z;
    b.color[3] = c.w;
    b.half = half;
    g_vtx.insert(g_vtx.end(), pts, pts + n);
    g_batches.push_back(b);
    dl->AddCallback(draw_batch, reinterpret_cast<void*>(static_cast<std::intptr_t>(g_batches.size() - 1)));
    dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
}

}  // namespace

bool init(std::string& error) {
    g_lines.id = build_program(shaders::plot_lines_vert, shaders::plot_lines_frag, "plot_lines", error);
    if (!g_lines.id) return false;
    g_points.id = build_program(shaders::plot_points_vert, shaders::plot_points_frag, "plot_points", error);
    if (!g_points.id) {
        glDeleteProgram(g_lines.id);
        g_lines.id = 0;
        return false;
    }
    g_lines.locate();
    g_points.locate();
    glGenVertexArrays(1, &g_vao);
    glGenBuffers(1, &g_vbo);
    return true;
}

void shutdown() {
    if (g_vbo) glDeleteBuffers(1, &g_vbo);
    if (g_vao) glDeleteVertexArrays(1, &g_vao);
    if (g_lines.id) glDeleteProgram(g_lines.id);
    if (g_points.id) glDeleteProgram(g_points.id);
    g_vbo = g_vao = g_lines.id = g_points.id = 0;
    g_capacity = 0;
}

bool ready() { return g_lines.id != 0; }

void begin_frame() {
    g_vtx.clear();
    g_batches.clear();
}

void add_lines(ImDrawList* dl, const Vtx* pts, std::size_t n, ImU32 color, float thickness) {
    add(dl, pts, n, color, 0.5f * thickness, true);
}

void add_points(ImDrawList* dl, const Vtx* pts, std::size_t n, ImU32 color, float size) {
    add(dl, pts, n, color, 0.5f * size, false);
}

void upload() {
    if (!g_vbo || g_vtx.empty()) return;
    glBindBuffer(GL_ARRAY_BUFFER, g_vbo);
    const auto bytes = static_cast<GLsizeiptr>(g_vtx.size() * sizeof(Vtx));
    if (bytes > g_capacity) {
        g_capacity = bytes + bytes / 2;
        glBufferData(GL_ARRAY_BUFFER, g_capacity, nullptr, GL_STREAM_DRAW);
    } else {
        glBufferData(GL_ARRAY_BUFFER, g_capacity, nullptr, GL_STREAM_DRAW);   // orphan: no wait on the last frame
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, g_vtx.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

std::size_t queued_points() { return g_vtx.size(); }

}  // namespace impactlab::gui::plot_gpu
