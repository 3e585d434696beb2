#include "widgets.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/theme.hpp"

namespace impactlab::gui {

void tooltip(const char* text) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void same_line_or_wrap(float next_w) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + next_w <= right) ImGui::SameLine();
}

float button_width(const char* label) {
    return ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
}

void text_wrapped_at_spaces(const char* text) {
    const float width = std::max(ImGui::GetContentRegionAvail().x, ImGui::GetFontSize() * 4.0f);
    std::string line, word;
    const auto flush_word = [&] {
        if (word.empty()) return;
        const std::string joined = line.empty() ? word : line + " " + word;
        if (!line.empty() && ImGui::CalcTextSize(joined.c_str()).x > width) {
            ImGui::TextUnformatted(line.c_str());
            line = word;
        } else {
            line = joined;
        }
        word.clear();
    };
    for (const char* c = text; *c; ++c) {
        if (*c == ' ') flush_word();
        else if (*c == '\n') {
            flush_word();
            ImGui::TextUnformatted(line.c_str());
            line.clear();
        } else {
            word += *c;
        }
    }
    flush_word();
    if (!line.empty()) ImGui::TextUnformatted(line.c_str());
}

void plate_text(ImDrawList* dl, ImVec2 p, const char* text, ImU32 col, ImVec2 align) {
    const ImVec2 ts = ImGui::CalcTextSize(text);
    const ImVec2 a(std::round(p.x - ts.x * align.x), std::round(p.y - ts.y * align.y));
    const ImU32 bg = palette().dark ? IM_COL32(10, 12, 16, 170) : IM_COL32(255, 255, 255, 190);
    dl->AddRectFilled(ImVec2(a.x - 3, a.y - 1), ImVec2(a.x + ts.x + 3, a.y + ts.y + 1), bg, 3.0f);
    dl->AddText(a, col, text);
}

}  // namespace impactlab::gui
