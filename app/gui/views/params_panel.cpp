#include "params_panel.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "sim/param_edit.hpp"
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

// What each rig parameter is, in a line (the impact law's take the core's range table's words).
const char* meaning(const std::string& key) {
    if (key == "m") return "the cart's mass";
    if (key == "c") return "viscous resistance of the bearings";
    if (key == "k") return "the coil springs' linear stiffness";
    if (key == "T") return "dry rolling resistance";
    if (key == "m0e") return "the unbalance: mass times eccentricity (the forcing is m0e ω²)";
    if (key == "eps") return "the speed over which the dry resistance is smoothed";
    for (const ParamRange& r : param_ranges()) {
        const std::string rk = r.key;
        if (rk.size() == key.size() + 7 && rk.compare(0, 7, "impact.") == 0 && rk.compare(7, std::string::npos, key) == 0)
            return r.why;
    }
    return "";
}

}  // namespace

ParamsAction ParamsPanel::draw(bool* open, const ParamsContext& c) {
    ParamsAction act;
    if (!c.params) return act;
    const float fs = ImGui::GetFontSize();
    ImGui::SetNextWindowSize(ImVec2(fs * 24.0f, 0), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Parameters###params", open, ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return act;
    }
    const std::vector<EditableParam> ps = editable_params(*c.params);
    // The fields follow the model whenever it changes outside them (a switch, a reset, --param).
    std::string key = c.model;
    for (const EditableParam& p : ps) key.append(" ").append(std::to_string(p.value));   // (GCC 12's -Wrestrict)
    if (key != edit_for_ || edit_.size() != ps.size()) {
        edit_for_ = key;
        edit_.clear();
        for (const EditableParam& p : ps) edit_.push_back(p.value);
    }
    ImGui::Text("%s%s", c.model.c_str(), params_edited(*c.params) ? "  (edited)" : "  (the paper's values)");
    tooltip("Changes apply at once; the cart goes on from where it is. A model switch (M, K, the combos) or a "
            "preset brings the version's own values back.");
    if (ImGui::BeginTable("##params", 3, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthFixed);
        ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableSetupColumn("unit", ImGuiTableColumnFlags_WidthFixed);
        for (std::size_t i = 0; i < ps.size(); ++i) {
            const EditableParam& p = ps[i];
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(p.key.c_str());
            char tip[256];
            std::snprintf(tip, sizeof tip, "%s\nthe paper's value: %.6g %s", meaning(p.key), p.paper, p.unit.c_str());
            tooltip(tip);
            ImGui::TableNextColumn();
            ImGui::SetNextItemWidth(-1.0f);
            ImGui::PushID(static_cast<int>(i));
            ImGui::InputDouble("##v", &edit_[i], 0, 0, "%.6g");
            if (ImGui::IsItemDeactivatedAfterEdit() && edit_[i] != p.value) act.set = std::make_pair(p.key, edit_[i]);
            ImGui::PopID();
            ImGui::TableNextColumn();
            ImGui::TextDisabled("%s%s", p.unit.c_str(), p.value != p.paper ? "  *" : "");
        }
        ImGui::EndTable();
    }
    if (ImGui::Button("Reset to the paper's values")) act.reset = true;
    if (!error_.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", error_.c_str());
        ImGui::PopTextWrapPos();
    }
    ImGui::End();
    return act;
}

}  // namespace impactlab::gui
