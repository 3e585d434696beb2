// The energy bar's drawing (ImGui); the arithmetic is in energy_bar.cpp, GL-free and tested.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "views/energy_bar.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

void draw_energy_bars(const EnergyBars& bars, double t0, double t) {
    const Palette& pal = palette();
    const ImU32 in_col[3] = {pal.axis_text, pal.trace, pal.trace2};
    const ImU32 out_col[5] = {IM_COL32(90, 170, 250, 255), IM_COL32(120, 200, 120, 255),
                              IM_COL32(230, 150, 60, 255), pal.bumper, pal.trace2};
    const char* in_name[3] = {"at start", "unbalance", "effects"};
    const char* out_name[5] = {"kinetic", "potential", "resistance", "bumper", "effects"};
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float label_w = ImGui::CalcTextSize("out ").x;
    const float bar_w = std::max(40.0f, ImGui::GetContentRegionAvail().x - label_w);
    const float h = ImGui::GetTextLineHeight();
    auto row = [&](const char* label, const double* seg, const ImU32* col, int n) {
        const float line_x = ImGui::GetCursorPosX();
        ImGui::TextDisabled("%s", label);
        ImGui::SameLine(line_x + label_w);
        const ImVec2 p = ImGui::GetCursorScreenPos();
        dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + bar_w, p.y + h - 2), pal.plot_bg, 2.0f);
        float x = p.x;
        for (int i = 0; i < n; ++i) {
            const float len = bars.full > 0 ? static_cast<float>(seg[i] / bars.full) * bar_w : 0.0f;
            if (len > 0.5f) dl->AddRectFilled(ImVec2(x, p.y + 3), ImVec2(x + len, p.y + h - 3), col[i]);
            x += len;
        }
        ImGui::Dummy(ImVec2(bar_w, h));
        if (ImGui::IsItemHovered()) {
            ImGui::BeginTooltip();
            for (int i = 0; i < n; ++i)
                if (seg[i] > 0 || i < 2) ImGui::Text("%-10s %9.3f mJ", (label[0] == 'i' ? in_name : out_name)[i], seg[i] * 1e3);
            ImGui::EndTooltip();
        }
    };
    row("in", bars.in.data(), in_col, 3);
    row("out", bars.out.data(), out_col, 5);
    // Legend: one swatch and value per non-empty segment.
    auto legend = [&](const char* name, double value, ImU32 col) {
        const ImVec2 p = ImGui::GetCursorScreenPos();
        dl->AddRectFilled(ImVec2(p.x, p.y + 0.25f * h), ImVec2(p.x + 0.5f * h, p.y + 0.75f * h), col);
        ImGui::Dummy(ImVec2(0.6f * h, h));
        ImGui::SameLine(0, 2);
        ImGui::Text("%s %.1f", name, value * 1e3);
    };
    const float avail = ImGui::GetContentRegionAvail().x;
    float used = 0;
    auto next = [&](const char* name, double value, ImU32 col) {
        char probe[48];
        std::snprintf(probe, sizeof probe, "%s %.1f", name, value * 1e3);
        const float w = ImGui::CalcTextSize(probe).x + 0.6f * h + 2 + ImGui::GetStyle().ItemSpacing.x;
        if (used > 0 && used + w <= avail) ImGui::SameLine();
        else used = 0;
        legend(name, value, col);
        used += w;
    };
    next("unbalance", bars.in[1], in_col[1]);
    for (int i = 0; i < 4; ++i) next(out_name[i], bars.out[i], out_col[i]);
    if (bars.in[2] > 0) next("effects in", bars.in[2], in_col[2]);
    if (bars.out[4] > 0) next("effects out", bars.out[4], out_col[4]);
    ImGui::TextDisabled("mJ over %.1f s; balance closes to %.1e J", t - t0, std::abs(bars.residual));
}

}  // namespace impactlab::gui
