#include "view.hpp"

#include "render/theme.hpp"

namespace impactlab::gui {

ImU32 companion_color(float alpha) {
    const ImVec4 c = palette().dark ? ImVec4(0.94f, 0.45f, 0.88f, alpha) : ImVec4(0.66f, 0.13f, 0.58f, alpha);
    return ImGui::ColorConvertFloat4ToU32(c);
}

std::optional<std::pair<double, double>> delayed_click(ClickDelay& delay, bool hovered, bool clicked, double x, double v,
                                                       double now) {
    if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) delay.double_clicked();
    if (clicked) delay.click(x, v, now);
    return delay.due(now, ImGui::GetIO().MouseDoubleClickTime);
}

}  // namespace impactlab::gui
