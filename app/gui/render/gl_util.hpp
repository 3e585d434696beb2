// Small OpenGL 3.3 helpers: programs from source, RGBA textures, reading the framebuffer into a PNG.
// Main (GL) thread only.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>
#include <imgui.h>

#include <string>
#include <vector>

namespace impactlab::gui {

// Compiles and links a program; on failure returns 0 and puts the driver's log in `error`.
GLuint build_program(const char* vert_src, const char* frag_src, const char* name, std::string& error);

// Creates or updates a 2-D RGBA8 texture (nearest filtering: for images shown 1:1; clamped); returns its id.
GLuint upload_rgba_texture(GLuint tex, int w, int h, const unsigned char* rgba);

// An RGBA8 texture the size of a CPU image (a plot canvas), updated a rectangle at a time.
//
// upload() only records what changed; flush_canvas_uploads() sends every recorded rectangle once the whole
// UI is built. Under llvmpipe a texture upload waits for the rendering already queued (the rig's image,
// drawn while the tiles are built), so uploading in the middle of the frame would serialise the two.
class CanvasTexture {
public:
    CanvasTexture() = default;
    ~CanvasTexture();
    CanvasTexture(const CanvasTexture&) = delete;
    CanvasTexture& operator=(const CanvasTexture&) = delete;
    // Creates the texture name now (so a draw command can refer to it before the first upload).
    GLuint ensure();
    // Records columns [x0, x1] of rows [y0, y1] of `rgba` (w x h) for the next flush (all of it when the
    // size is new). `rgba` must stay valid and unchanged until then.
    GLuint upload(const unsigned char* rgba, int w, int h, int x0, int y0, int x1, int y1);
    GLuint id() const { return tex_; }

private:
    friend void flush_canvas_uploads();
    void send();
    GLuint tex_ = 0;
    int w_ = 0, h_ = 0;                 // the texture's size on the GL side
    const unsigned char* rgba_ = nullptr;
    int pw_ = 0, ph_ = 0;               // the recorded image's size
    int x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1;   // the rectangle to send (empty: nothing pending)
    bool pending_ = false;
};

// Sends every recorded CanvasTexture upload: once a frame, after the UI is built and before it is rendered.
void flush_canvas_uploads();

// From a draw-list callback: sets and enables the GL scissor to the command's clip rectangle (display
// pixels of the current draw data, as ImGui's backend does); false, setting nothing, if it is empty.
bool scissor_to_clip(const ImVec4& clip_rect);

// Reads the current read framebuffer (w x h from the lower left) and writes a PNG (top row first).
// Returns false and fills `error` on failure.
bool save_framebuffer_png(const std::string& path, int w, int h, std::string& error);

// Reads pixels as RGB rows, top row first.
std::vector<unsigned char> read_framebuffer_rgb(int w, int h);

}  // namespace impactlab::gui
