#include "view_table.hpp"

namespace impactlab::gui {

std::optional<PanelId> panel_from_key(const std::string& key) {
    for (const ViewInfo& v : kViews)
        if (key == v.key) return v.id;
    return std::nullopt;
}

std::string panel_keys(bool presentable) {
    std::string all;
    if (presentable) {
        for (PanelId p : presentation_plots()) all += (all.empty() ? "" : ", ") + std::string(panel_key(p));
        return all;
    }
    for (const ViewInfo& v : kViews) all += (all.empty() ? "" : ", ") + std::string(v.key);
    return all;
}

std::vector<PanelId> presentation_plots() {
    std::vector<PanelId> out;
    for (int order = 1; order <= kPanelCount; ++order)
        for (const ViewInfo& v : kViews)
            if (v.presentation_order == order) out.push_back(v.id);
    return out;
}

}  // namespace impactlab::gui
