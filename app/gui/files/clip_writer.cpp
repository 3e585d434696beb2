#include "clip_writer.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

#include "impactlab/atomic_file.hpp"
#include "impactlab/plot.hpp"

namespace impactlab::gui {

namespace fs = std::filesystem;

std::string find_on_path(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (!path || name.empty()) return {};
    std::string dirs(path);
    std::size_t from = 0;
    while (from <= dirs.size()) {
        std::size_t to = dirs.find(':', from);
        if (to == std::string::npos) to = dirs.size();
        const std::string dir = to > from ? dirs.substr(from, to - from) : ".";
        const std::string full = dir + "/" + name;
        std::error_code ec;
        if (fs::is_regular_file(full, ec) && ::access(full.c_str(), X_OK) == 0) return full;
        from = to + 1;
    }
    return {};
}

namespace {
// A path in single quotes for /bin/sh (popen), a quote inside as '\''.
std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
}  // namespace

bool ClipWriter::begin(const std::string& out_dir, const std::string& name, int w, int h, double fps, bool video,
                       std::string& error) {
    abort();
    if (w <= 0 || h <= 0 || !(fps > 0)) {
        error = "clip export: empty frame size or frame rate";
        return false;
    }
    std::error_code ec;
    const fs::path dir = out_dir.empty() ? fs::path(".") : fs::path(out_dir);
    if (!fs::is_directory(dir, ec)) {
        error = "clip export: '" + dir.string() + "' is not a folder";
        return false;
    }
    const fs::path target = dir / name;
    if (fs::exists(target, ec)) {
        error = "clip export: '" + target.string() + "' already exists";
        return false;
    }
    const std::string staging = partial_path(target.string());
    if (!fs::create_directory(staging, ec) || ec) {
        error = "clip export: cannot write in '" + dir.string() + "' (" + (ec ? ec.message() : "exists") + ")";
        return false;
    }
    staging_ = staging;
    final_ = target.string();
    w_ = w;
    h_ = h;
    frames_ = 0;
    video_asked_ = video;
    if (video) {
        if (const std::string ff = find_on_path("ffmpeg"); !ff.empty()) {
            // A dead ffmpeg must turn our writes into errors (EPIPE), not kill the app with SIGPIPE.
            std::signal(SIGPIPE, SIG_IGN);
            char geometry[64], rate[32];
            std::snprintf(geometry, sizeof geometry, "%dx%d", w, h);
            std::snprintf(rate, sizeof rate, "%.6g", fps);
            // yuv420p wants even sizes: pad by a pixel where needed.
            const std::string cmd = shell_quote(ff) + " -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " +
                                    geometry + " -r " + rate + " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' " +
                                    "-pix_fmt yuv420p " + shell_quote(staging_ + "/clip.mp4");
            ffmpeg_ = ::popen(cmd.c_str(), "w");
            if (!ffmpeg_) {
                error = "clip export: cannot start ffmpeg";
                abort();
                return false;
            }
        }
    }
    return true;
}

bool ClipWriter::add_frame(const unsigned char* rgb, std::string& error) {
    if (!active()) {
        error = "clip export: no clip in progress";
        return false;
    }
    const std::size_t n = static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_);
    plot::Image img;
    img.width = w_;
    img.height = h_;
    img.rgba.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
        img.rgba[i * 4 + 0] = rgb[i * 3 + 0];
        img.rgba[i * 4 + 1] = rgb[i * 3 + 1];
        img.rgba[i * 4 + 2] = rgb[i * 3 + 2];
        img.rgba[i * 4 + 3] = 255;
    }
    char file[32];
    std::snprintf(file, sizeof file, "frame-%05d.png", frames_ + 1);
    try {
        plot::save_png(img, staging_ + "/" + file);
    } catch (const std::exception& e) {
        error = std::string("clip export: ") + e.what();
        abort();
        return false;
    }
    if (ffmpeg_ && std::fwrite(rgb, 3, n, ffmpeg_) != n) {
        error = "clip export: ffmpeg stopped taking frames";
        abort();
        return false;
    }
    ++frames_;
    return true;
}

bool ClipWriter::close_video(std::string& error) {
    if (!ffmpeg_) return true;
    const int status = ::pclose(ffmpeg_);
    ffmpeg_ = nullptr;
    if (status != 0) {
        error = "clip export: ffmpeg failed (exit status " + std::to_string(status) + ")";
        return false;
    }
    return true;
}

bool ClipWriter::finish(std::string& summary, std::string& error) {
    if (!active()) {
        error = "clip export: no clip in progress";
        return false;
    }
    const bool had_video = ffmpeg_ != nullptr;
    if (!close_video(error)) {
        abort();
        return false;
    }
    std::error_code ec;
    fs::rename(staging_, final_, ec);
    if (ec) {
        error = "clip export: cannot write '" + final_ + "' (" + ec.message() + ")";
        abort();
        return false;
    }
    staging_.clear();
    const std::string frames = std::to_string(frames_) + " PNG frame" + (frames_ == 1 ? "" : "s");
    if (had_video) summary = "wrote " + frames + " and clip.mp4 to " + final_;
    else if (video_asked_) summary = "ffmpeg not found: wrote " + frames + " to " + final_;
    else summary = "wrote " + frames + " to " + final_;
    return true;
}

void ClipWriter::abort() {
    if (ffmpeg_) {
        ::pclose(ffmpeg_);
        ffmpeg_ = nullptr;
    }
    if (!staging_.empty()) {
        std::error_code ec;
        fs::remove_all(staging_, ec);
        staging_.clear();
    }
}

}  // namespace impactlab::gui
