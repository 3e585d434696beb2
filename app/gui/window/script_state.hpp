// What a scripted run (harness.cpp: --frames and its flags, --warmup, --double-click, --replay-back) has done
// so far, and the exit code the run ends with. UI thread only.
#pragma once

#include <imgui.h>

namespace impactlab::gui {

struct ScriptState {
    bool switched = false;           // the half-way change (--then-*, --switch-model) is done
    bool warming = false;            // --warmup: at 100x until the sim time reaches it
    bool replay_back_done = false;   // --replay-back: the replay is entered
    ImVec2 click_at{};               // --double-click: where the mouse is held
    int exit_code = 0;
};

}  // namespace impactlab::gui
