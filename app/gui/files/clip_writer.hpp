// A clip exported from replay: numbered PNG frames through the core's PNG writer, and an MP4 video
// where ffmpeg is on PATH (raw RGB frames piped to it). Everything goes into a hidden staging folder that
// is renamed to its final name only when the clip is complete, so a failed or cancelled export leaves
// nothing half-written. GL-free (the app reads the framebuffer and hands the pixels over); UI thread only.
#pragma once

#include <cstdio>
#include <string>

namespace impactlab::gui {

// The full path of an executable `name` on PATH, or "" if there is none.
std::string find_on_path(const std::string& name);

class ClipWriter {
public:
    ClipWriter() = default;
    ~ClipWriter() { abort(); }
    ClipWriter(const ClipWriter&) = delete;
    ClipWriter& operator=(const ClipWriter&) = delete;

    // Starts the clip `name` (a folder to be) in out_dir, frames w x h at `fps`; with `video`, also starts
    // ffmpeg if it is on PATH. False with `error` naming the folder and the problem (nothing is created).
    bool begin(const std::string& out_dir, const std::string& name, int w, int h, double fps, bool video,
               std::string& error);
    // One frame: w * h * 3 bytes, RGB, rows top-down. False with `error` (the clip is then aborted).
    bool add_frame(const unsigned char* rgb, std::string& error);
    // Completes the clip: closes the video, renames the staging folder to out_dir/name. `summary` says
    // what was written ("wrote 60 PNG frames and clip.mp4 to DIR", or "ffmpeg not found: wrote 60 PNG
    // frames to DIR"). False with `error` (nothing is left then).
    bool finish(std::string& summary, std::string& error);
    // Drops a clip in progress: stops ffmpeg, removes the staging folder. Idempotent.
    void abort();

    bool active() const { return !staging_.empty(); }
    int frames() const { return frames_; }
    int width() const { return w_; }
    int height() const { return h_; }
    const std::string& folder() const { return final_; }   // where the clip lands (valid after begin())

private:
    bool close_video(std::string& error);
    std::string staging_, final_;
    int w_ = 0, h_ = 0, frames_ = 0;
    std::FILE* ffmpeg_ = nullptr;
    bool video_asked_ = false;
};

}  // namespace impactlab::gui
