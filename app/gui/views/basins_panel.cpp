#include "basins_panel.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "render/gl_util.hpp"
#include "render/plot2d.hpp"
#include "render/theme.hpp"
#include "views/map_colors.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

using namespace maps;

void BasinsPanel::configure(const Options& opt) {
    want_ = opt.basins;
    if (opt.basins_box.size() == 4) box_ = Box{opt.basins_box[0], opt.basins_box[1], opt.basins_box[2], opt.basins_box[3]};
}

void BasinsPanel::start(const AnalysisContext& c) {
    const Params p = *c.params;
    analysis::BasinSpec spec = basin_request(p, c.omega, grid_, 2);
    if (box_) {   // as impactlab basins --x-range X0:X1 --v-range V0:V1
        spec.x_min = box_->x0;
        spec.x_max = box_->x1;
        spec.v_min = box_->v0;
        spec.v_max = box_->v1;
    }
    job_.start([p, spec](Progress& prog) { return analysis::compute_basins(p, spec, &prog); });
    model_ = c.model;
}

void BasinsPanel::release_gl() {
    if (tex_) {
        const GLuint id = tex_;
        glDeleteTextures(1, &id);
        tex_ = 0;
    }
}

AnalysisAction BasinsPanel::poll(const AnalysisContext& c, std::string& startup_error) {
    AnalysisAction act;
    if (std::exchange(want_, false)) {
        start(c);
        act.open_basins = true;
    }
    if (const std::string err = job_.take_error(); !err.empty()) {
        act.toast = "basins failed: " + err;
        if (startup_error.empty()) startup_error = act.toast;
    }
    if (auto r = job_.take_result()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "basins at omega = %.3f: %zu attractors in %.1f s%s", r->spec.omega, r->attractors.size(),
                      r->seconds, r->cancelled ? " (cancelled, partial)" : "");
        act.toast = buf;
        basins_ = std::move(*r);
        dirty_ = true;
    }
    return act;
}

// The grid, and Compute (or Cancel and the progress), and Whole window once a box was computed.
void BasinsPanel::draw_controls(const AnalysisContext& c) {
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7);
    ImGui::SliderInt("##grid", &grid_, 20, 200, "grid %d");
    ImGui::SameLine();
    if (job_.running()) {
        if (ImGui::Button("Cancel")) job_.cancel();
        ImGui::SameLine();
        ImGui::ProgressBar(static_cast<float>(job_.progress()), ImVec2(-1, 0));
    } else {
        char label[64];
        std::snprintf(label, sizeof label, "Compute at omega = %.2f", c.omega);
        if (ImGui::Button(label)) start(c);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Every (x0, v0) of the grid at φ = 0 run to its attractor on a worker (2 threads).\n"
                              "Right-drag a box on the map: the basins over that box.");
        if (box_) {
            ImGui::SameLine();
            if (ImGui::Button("Whole window")) {
                box_.reset();
                start(c);
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("Forget the box: the rail left of the bumper, |v0| <= 0.3 m/s.");
        }
    }
}

namespace {
// Beside the map: each attractor in its colour, with its kind, well and cells.
void draw_legend(const analysis::BasinResult& r) {
    ImGui::BeginGroup();
    ImGui::TextUnformatted("attractors (cells)");
    for (const analysis::Attractor& at : r.attractors) {
        char buf[96];
        const char* well = at.well < 0 ? "left" : at.well > 0 ? "right" : "centre";
        if (at.kind == analysis::AttractorKind::Periodic)
            std::snprintf(buf, sizeof buf, "%d: period %d, %s (%zu)", at.id, at.period, well, at.cells);
        else
            std::snprintf(buf, sizeof buf, "%d: %s, %s (%zu)", at.id, analysis::attractor_kind_name(at.kind), well, at.cells);
        swatch(label_rgb(at.id), buf);
    }
    ImGui::Spacing();
    ImGui::TextDisabled("dots: section points");
    ImGui::TextDisabled("click: run from there");
    ImGui::EndGroup();
}
}  // namespace

AnalysisAction BasinsPanel::draw(const AnalysisContext& c) {
    AnalysisAction act;
    draw_controls(c);
    if (!basins_) {
        ImGui::TextDisabled("No basins yet: compute them at the current ω.");
        return act;
    }
    const analysis::BasinResult& r = *basins_;
    const analysis::BasinSpec& sp = r.spec;
    if (dirty_ || !tex_) {
        std::vector<unsigned char> rgba(static_cast<std::size_t>(sp.nx) * sp.nv * 4, 0);
        for (int j = 0; j < sp.nv; ++j)
            for (int i = 0; i < sp.nx; ++i) {
                const int l = r.label[static_cast<std::size_t>(j) * sp.nx + i];
                if (l < 0) continue;
                const Rgb cc = label_rgb(l);
                unsigned char* px = &rgba[(static_cast<std::size_t>(sp.nv - 1 - j) * sp.nx + i) * 4];
                px[0] = cc.r, px[1] = cc.g, px[2] = cc.b, px[3] = 255;
            }
        tex_ = upload_rgba_texture(static_cast<GLuint>(tex_), sp.nx, sp.nv, rgba.data());
        dirty_ = false;
    }
    // The legend beside the map where the tile is wide enough; the tooltip names a cell's attractor anyway.
    float legend_w = ImGui::GetFontSize() * 12.5f;
    const bool legend = ImGui::GetContentRegionAvail().x > 2.5f * legend_w;
    if (!legend) legend_w = 0;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    Axes ax;
    ax.x_label = "x0 [mm]";
    ax.y_label = "v0 [mm/s]";
    ax.x_scale = ax.y_scale = 1e3;
    Plot plot;
    if (plot.begin("##basins", ImVec2(std::max(avail.x - legend_w, 50.0f), avail.y), {sp.x_min, sp.x_max}, {sp.v_min, sp.v_max}, ax)) {
        ImDrawList* dl = plot.draw();
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex_)), plot.to_px(sp.x_min, sp.v_max),
                     plot.to_px(sp.x_max, sp.v_min));
        // Each attractor's section points, ringed so they show on their own basin's colour.
        for (const analysis::Attractor& at : r.attractors)
            for (std::size_t k = 0; k < at.points.size() && k < 64; ++k) {
                const ImVec2 p = plot.to_px(at.points[k][0], at.points[k][1]);
                dl->AddCircleFilled(p, 4.0f, IM_COL32(0, 0, 0, 230));
                dl->AddCircleFilled(p, 2.5f, IM_COL32(255, 255, 255, 255));
            }
        const ImVec2 a = plot.area_min(), b = plot.area_max(), m = ImGui::GetIO().MousePos;
        // A box dragged with the right button: the basins over it, at the same grid.
        const double mx = plot.x_at(std::clamp(m.x, a.x, b.x)), mv = plot.y_at(std::clamp(m.y, a.y, b.y));
        if (plot.hovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
            dragging_ = true;
            drag_x_ = mx;
            drag_v_ = mv;
        }
        if (dragging_) {
            const ImVec2 p0 = plot.to_px(drag_x_, drag_v_), p1 = plot.to_px(mx, mv);
            const ImVec2 r0(std::min(p0.x, p1.x), std::min(p0.y, p1.y)), r1(std::max(p0.x, p1.x), std::max(p0.y, p1.y));
            dl->AddRectFilled(r0, r1, IM_COL32(255, 255, 255, 40));
            dl->AddRect(r0, r1, IM_COL32(255, 255, 255, 230), 0.0f, 0, 1.5f);
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
                dragging_ = false;
                if (r1.x - r0.x >= 5.0f && r1.y - r0.y >= 5.0f) {
                    box_ = Box{std::min(drag_x_, mx), std::max(drag_x_, mx), std::min(drag_v_, mv), std::max(drag_v_, mv)};
                    start(c);
                }
            }
        } else if (plot.hovered()) {
            const int i = std::clamp(static_cast<int>((m.x - a.x) / (b.x - a.x) * sp.nx), 0, sp.nx - 1);
            const int j = std::clamp(static_cast<int>((b.y - m.y) / (b.y - a.y) * sp.nv), 0, sp.nv - 1);
            const int l = r.label[static_cast<std::size_t>(j) * sp.nx + i];
            ImGui::SetTooltip("x0 = %.2f mm, v0 = %.1f mm/s: attractor %d\n(click: start the simulation here at ω = %.3f;\n"
                              "right-drag: the basins over a box)",
                              1e3 * r.x0(i), 1e3 * r.v0(j), l, sp.omega);
            if (plot.clicked()) {
                act.reset = std::make_pair(r.x0(i), r.v0(j));
                if (std::abs(c.omega - sp.omega) > 1e-12) act.omega = sp.omega;
            }
        }
        char info[96];
        std::snprintf(info, sizeof info, "%s  omega = %.3f rad/s  %d x %d  %.1f s", model_.c_str(), sp.omega, sp.nx, sp.nv, r.seconds);
        plate_text(dl, ImVec2(a.x + 4, b.y - ImGui::GetTextLineHeight() - 4), info, palette().axis_text);
        plot.end();
    }
    if (!legend) return act;
    ImGui::SameLine();
    draw_legend(r);
    return act;
}

nlohmann::json BasinsPanel::state() const {
    using nlohmann::json;
    if (!basins_) return {{"computed", false}, {"running", job_.running()}};
    const analysis::BasinResult& r = *basins_;
    json ats = json::array();
    for (const analysis::Attractor& at : r.attractors)
        ats.push_back({{"kind", analysis::attractor_kind_name(at.kind)}, {"period", at.period}, {"cells", at.cells}});
    return {{"computed", true},
            {"running", job_.running()},
            {"model", model_},
            {"omega", r.spec.omega},
            {"x_range", {r.spec.x_min, r.spec.x_max}},
            {"v_range", {r.spec.v_min, r.spec.v_max}},
            {"nx", r.spec.nx},
            {"nv", r.spec.nv},
            {"cancelled", r.cancelled},
            {"attractors", std::move(ats)}};
}

}  // namespace impactlab::gui
