// Small OpenGL 3.3 helpers: programs from source, RGBA textures, reading the framebuffer into a PNG.
// Main (GL) thread only.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

#include <string>
#include <vector>

namespace impactlab::gui {

// Compiles and links a program; on failure returns 0 and puts the driver's log in `error`.
GLuint build_program(const char* vert_src, const char* frag_src, const char* name, std::string& error);

// Creates or updates a 2-D RGBA8 texture (linear filtering, clamped); returns its id.
GLuint upload_rgba_texture(GLuint tex, int w, int h, const unsigned char* rgba);

// Reads the current read framebuffer (w x h from the lower left) and writes a PNG (top row first).
// Returns false and fills `error` on failure.
bool save_framebuffer_png(const std::string& path, int w, int h, std::string& error);

// Reads pixels as RGB rows, top row first.
std::vector<unsigned char> read_framebuffer_rgb(int w, int h);

}  // namespace impactlab::gui
