// The frame loop's bookkeeping: the frame's wall-clock step, the frames per second, the frame counts (all,
// and those a --frames run counts), whether a submitted frame waits for its swap, and a screenshot asked
// for, saved at the frame's end. UI thread only.
#pragma once

#include <algorithm>
#include <string>

namespace impactlab::gui {

struct FrameStats {
    double last_time = 0, fps = 0, dt = 1.0 / 60;
    double fps_since = 0;       // [s] wall time the frames counted in fps_frames began
    int fps_frames = 0;
    long count = 0;             // frames drawn
    long counted = 0;           // frames a --frames run counts
    bool pending = false;       // a frame is submitted and waits for the next one's swap
    std::string pending_shot;   // a screenshot's path, saved after this frame renders ("" none)

    // A new frame at wall time t [s]: its step dt and the frame rate.
    void tick(double t) {
        dt = std::clamp(t - last_time, 1e-4, 0.25);
        last_time = t;
        // Frames counted over half a second of wall time: an average of 1/dt would follow a burst of frames
        // shown back to back (a swap deferred, a resize) up to 1000 fps and more.
        ++fps_frames;
        if (fps_since <= 0) fps_since = t;
        if (t - fps_since >= 0.5 || (fps <= 0 && fps_frames >= 3 && t > fps_since)) {
            fps = fps_frames / (t - fps_since);
            fps_frames = 0;
            fps_since = t;
        }
    }
};

}  // namespace impactlab::gui
