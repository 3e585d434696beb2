// --bench-plot (harness.cpp): the plots show the newest `window` samples (0: the normal trail and strip),
// and a headless engine appends what the live app would receive at 100x real time every frame; the timed
// parts of each frame are summed here. UI thread only.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "sim/sim_engine.hpp"
#include "sim/sim_messages.hpp"
#include "views/view_table.hpp"

namespace impactlab::gui {

struct BenchPlot {
    static constexpr int kFrames = 220;   // kWarm warm-up frames, then 200 timed
    static constexpr int kWarm = 20;
    bool on = false;
    std::size_t window = 0;
    std::unique_ptr<SimEngine> engine;
    std::unique_ptr<MsgSink> sink;
    std::vector<SimMsg> feed;              // the timed frames' samples, computed before
    std::size_t fed = 0;
    double events_s = 0, build_s = 0, wait_s = 0, submit_s = 0;
    double panel_s[1 + kPanelCount] = {};  // the controls, then each view (the view table's order)
    int frame = 0;                         // frames run so far (bench_frame)
    double timed_s = 0;                    // wall time of the timed frames, each shown by the next one
    std::size_t verts = 0;                 // the most vertices a timed frame sent
};

}  // namespace impactlab::gui
