// A clip's export (app_replay.cpp): its window's inputs, the plan of frames over the replayed past, the
// writer of its PNG frames (and the ffmpeg video), the frame being rendered and how it ended. UI thread only.
#pragma once

#include <string>

#include "files/clip_writer.hpp"
#include "sim/replay.hpp"

namespace impactlab::gui {

struct ClipExport {
    static constexpr double kFps = 30.0;
    ClipWriter writer;
    ClipPlan plan;
    int frame = -1;            // the clip frame being rendered (-1: no export)
    bool from_live = false;    // replay was entered for the clip: left when it is done
    bool window = false;       // the clip window is open
    bool started = false;
    char dir[512] = ".";
    float seconds = 5.0f;
    std::string summary, error;

    bool exporting() const { return frame >= 0; }
};

}  // namespace impactlab::gui
