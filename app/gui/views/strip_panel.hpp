// The time strip's view (views/view.hpp): one or two traces of the user's choice over the last seconds
// (x, v, the energy, the bumper force, the unbalance's drive), each on its own axis, one above the other;
// it scrolls once the history covers its window. Right-click (or --strip) chooses them.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "sim/history.hpp"
#include "render/plot2d.hpp"
#include "views/view.hpp"

namespace impactlab::gui {

enum class StripQuantity : int { X, V, Energy, Force, Drive };
inline constexpr int kStripQuantities = 5;
// "x", "v", "E", "F", "drive" (--strip, --state-json).
const char* strip_key(StripQuantity q);
std::optional<StripQuantity> strip_from_key(const std::string& key);

class StripPanel {
public:
    ViewAction draw(const ViewContext& ctx);
    // The traces shown: the first always, the second when set (--strip, the right-click menu).
    void set_traces(StripQuantity first, std::optional<StripQuantity> second);
    StripQuantity first() const { return traces_[0].q; }
    std::optional<StripQuantity> second() const { return second_ ? std::optional<StripQuantity>(traces_[1].q) : std::nullopt; }
    Range view_y(int trace) const { return traces_[static_cast<std::size_t>(trace)].y.cur; }   // [SI units]

private:
    struct Trace {
        StripQuantity q = StripQuantity::X;
        AutoRange y;
        WindowExtent extent;   // the window's extent of q, kept incrementally
    };
    void draw_trace(const ViewContext& ctx, Trace& tr, const char* id, ImVec2 size, double t_from, double t_now,
                    std::size_t first);
    template <class Key>
    void draw_trace_with(const ViewContext& ctx, Trace& tr, const char* id, ImVec2 size, double t_from, double t_now,
                         std::size_t first, Key key);
    void draw_menu();
    void draw_separation(const ViewContext& ctx, ImVec2 size);   // beside x(t): log10 |dx| of cart and companion
    std::array<Trace, 2> traces_;
    bool second_ = false;
};

}  // namespace impactlab::gui
