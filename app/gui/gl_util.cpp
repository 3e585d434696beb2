#include "gl_util.hpp"

#include <stb_image_write.h>   // libstb exports the implementation

#include <cstring>

namespace impactlab::gui {

namespace {
GLuint compile(GLenum type, const char* src, const char* name, std::string& error) {
    const GLuint s = glCreateShader(type);
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

CanvasTexture::~CanvasTexture() {
    if (tex_) glDeleteTextures(1, &tex_);
}

GLuint CanvasTexture::ensure() {
    if (!tex_) glGenTextures(1, &tex_);
    return tex_;
}

GLuint CanvasTexture::upload(const unsigned char* rgba, int w, int h, int x0, int y0, int x1, int y1) {
    if (!tex_ || w != w_ || h != h_) {
        tex_ = upload_rgba_texture(tex_, w, h, rgba);   // keeps the name if there is one
        w_ = w;
        h_ = h;
        return tex_;
    }
    if (x1 < x0 || y1 < y0) return tex_;
    glBindTexture(GL_TEXTURE_2D, tex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, w);
    const unsigned char* first = rgba + (static_cast<std::size_t>(y0) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x0)) * 4;
    glTexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, x1 - x0 + 1, y1 - y0 + 1, GL_RGBA, GL_UNSIGNED_BYTE, first);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    return tex_;
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
