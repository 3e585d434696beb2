// "What to try": the first screen of an interactive start (Help > What to try, --guide). Five scripted
// demonstrations, each a button that sets the state and one sentence on what to look for; the App runs
// the one asked for (GuideAction). UI thread.
#pragma once

namespace impactlab::gui {

inline constexpr int kDemoCount = 5;

struct GuideDemo {
    const char* title;
    const char* does;       // what the button sets
    const char* look_for;   // the one sentence
};
// 1 period doubling, 2 the road to chaos, 3 switching the impact model, 4 the energy budget, 5 basins.
const GuideDemo& guide_demo(int k);

struct GuideAction {
    int demo = 0;   // 1..kDemoCount: run it; 0: nothing
};

class GuidePanel {
public:
    // Inside its own window; *open goes false when the user closes it.
    GuideAction draw(bool* open, int last_demo);
};

}  // namespace impactlab::gui
