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
    // After "Show me": folded to its title bar in the bottom-left corner, off the plots the demo speaks of
    // (its title bar unfolds it again).
    void move_aside() { aside_pending_ = true; }
    bool collapsed() const { return collapsed_; }
    // The window's rectangle as last drawn (screen pixels): x0, y0, x1, y1.
    const float* rect() const { return rect_; }

private:
    bool aside_pending_ = false, collapsed_ = false, was_collapsed_ = false;
    float rect_[4] = {0, 0, 0, 0};
};

}  // namespace impactlab::gui
