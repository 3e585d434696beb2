#include "gl_util.hpp"

#include <stb_image_write.h>   // libstb exports the implementation

#include <algorithm>
#include <cstring>

namespace impactlab::gui {

namespace {
GLuint compile(GLenum type, const char* src, const char* name, std::string& error) {
    const GLuint s = glCreateShader(type);
#ifdef __EMSCRIPTEN__
    // WebGL2: the same shaders as GLSL ES 3.00 (they use nothing of 3.30 that ES 3.00 lacks).
    std::string es(src);
    if (const std::string desktop = "#version 330 core"; es.compare(0, desktop.size(), desktop) == 0)
        es.replace(0, desktop.size(), "#version 300 es\nprecision highp float;\nprecision highp int;");
    src = es.c_str();
#endif
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        GLsizei n = 0;
        glGetShaderInfoLog(s, sizeof log, &n, log);
        error = std::string(name) + (type == GL_VERTEX_SHADER ? ".vert" : ".frag") + ": " + std::string(log, static_cast<std::size_t>(n));
        glDeleteShader(s);
        return 0;
    }
    return s;
}
}  // namespace

GLuint build_program(const char* vert_src, const char* frag_src, const char* name, std::string& error) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vert_src, name, error);
    if (!vs) return 0;
    const GLuint fs = compile(GL_FRAGMENT_SHADER, frag_src, name, error);
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    const GLuint prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glLinkProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        GLsizei n = 0;
        glGetProgramInfoLog(prog, sizeof log, &n, log);
        error = std::string(name) + ": link: " + std::string(log, static_cast<std::size_t>(n));
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

GLuint upload_rgba_texture(GLuint tex, int w, int h, const unsigned char* rgba) {
    if (!tex) glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    // Every texture made here is shown pixel for pixel (plot canvases, the rig's framebuffer, the diagram),
    // where nearest sampling gives the same picture as linear and costs far less under llvmpipe.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, 0);
    return tex;
}

namespace {
// The textures with an upload recorded this frame (the GL thread's only).
std::vector<CanvasTexture*>& pending_canvases() {
    static std::vector<CanvasTexture*> list;
    return list;
}
}  // namespace

CanvasTexture::~CanvasTexture() {
    if (pending_) {
        auto& list = pending_canvases();
        list.erase(std::remove(list.begin(), list.end(), this), list.end());
    }
    if (tex_) glDeleteTextures(1, &tex_);
}

GLuint CanvasTexture::ensure() {
    if (!tex_) glGenTextures(1, &tex_);
    return tex_;
}

GLuint CanvasTexture::upload(const unsigned char* rgba, int w, int h, int x0, int y0, int x1, int y1) {
    ensure();
    const bool resized = w != pw_ || h != ph_;
    if (!pending_ || resized) {
        x0_ = y0_ = 0;
        x1_ = y1_ = -1;
    }
    rgba_ = rgba;
    pw_ = w;
    ph_ = h;
    if (w != w_ || h != h_) {   // a new size: all of it
        x0_ = y0_ = 0;
        x1_ = w - 1;
        y1_ = h - 1;
    } else if (x0 <= x1 && y0 <= y1) {   // drawn twice before a flush: the union
        if (x1_ < x0_) {
            x0_ = x0, y0_ = y0, x1_ = x1, y1_ = y1;
        } else {
            x0_ = std::min(x0_, x0), y0_ = std::min(y0_, y0), x1_ = std::max(x1_, x1), y1_ = std::max(y1_, y1);
        }
    }
    if (!pending_) {
        pending_ = true;
        pending_canvases().push_back(this);
    }
    return tex_;
}

void CanvasTexture::send() {
    pending_ = false;
    if (pw_ != w_ || ph_ != h_) {
        tex_ = upload_rgba_texture(tex_, pw_, ph_, rgba_);   // keeps the name
        w_ = pw_;
        h_ = ph_;
        return;
    }
    if (x1_ < x0_ || y1_ < y0_) return;
    glBindTexture(GL_TEXTURE_2D, tex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, pw_);
    const unsigned char* first = rgba_ + (static_cast<std::size_t>(y0_) * static_cast<std::size_t>(pw_) + static_cast<std::size_t>(x0_)) * 4;
    glTexSubImage2D(GL_TEXTURE_2D, 0, x0_, y0_, x1_ - x0_ + 1, y1_ - y0_ + 1, GL_RGBA, GL_UNSIGNED_BYTE, first);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

void flush_canvas_uploads() {
    auto& list = pending_canvases();
    for (CanvasTexture* t : list) t->send();
    list.clear();
}

bool scissor_to_clip(const ImVec4& c) {
    const ImDrawData* dd = ImGui::GetDrawData();
    if (!dd) return false;
    // Framebuffer pixels, origin at the bottom left.
    const ImVec2 scale = dd->FramebufferScale;
    const float fb_h = dd->DisplaySize.y * scale.y;
    const float x0 = (c.x - dd->DisplayPos.x) * scale.x, y0 = (c.y - dd->DisplayPos.y) * scale.y;
    const float x1 = (c.z - dd->DisplayPos.x) * scale.x, y1 = (c.w - dd->DisplayPos.y) * scale.y;
    if (x1 <= x0 || y1 <= y0) return false;
    glEnable(GL_SCISSOR_TEST);
    glScissor(static_cast<GLint>(x0), static_cast<GLint>(fb_h - y1), static_cast<GLsizei>(x1 - x0),
              static_cast<GLsizei>(y1 - y0));
    return true;
}

std::vector<unsigned char> read_framebuffer_rgb(int w, int h) {
    std::vector<unsigned char> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px.data());
    // GL's rows run bottom-up: flip to top-down.
    const std::size_t row = static_cast<std::size_t>(w) * 3;
    std::vector<unsigned char> tmp(row);
    for (int y = 0; y < h / 2; ++y) {
        unsigned char* a = px.data() + static_cast<std::size_t>(y) * row;
        unsigned char* b = px.data() + static_cast<std::size_t>(h - 1 - y) * row;
        std::memcpy(tmp.data(), a, row);
        std::memcpy(a, b, row);
        std::memcpy(b, tmp.data(), row);
    }
    return px;
}

bool save_framebuffer_png(const std::string& path, int w, int h, std::string& error) {
    if (w <= 0 || h <= 0) {
        error = "empty framebuffer";
        return false;
    }
    const std::vector<unsigned char> px = read_framebuffer_rgb(w, h);
    if (!stbi_write_png(path.c_str(), w, h, 3, px.data(), w * 3)) {
        error = path + ": cannot write the PNG";
        return false;
    }
    return true;
}

}  // namespace impactlab::gui
