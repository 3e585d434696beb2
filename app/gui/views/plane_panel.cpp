#include "views/plane_panel.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "gl_util.hpp"
#include "theme.hpp"
#include "views/map_colors.hpp"
#include "widgets.hpp"

namespace impactlab::gui {

using namespace maps;

namespace {

// The doubling curve's colour: magenta with a dark edge, apart from every period class.
constexpr ImU32 kCurve = IM_COL32(255, 70, 200, 255);

}  // namespace

std::string PlanePanel::configure(const Options& opt) {
    want_plane_ = opt.small_plane;
    want_doubling_ = opt.plane_doubling;
    return opt.plane.empty() ? std::string() : load(opt.plane);
}

std::string PlanePanel::load(const std::string& path) {
    std::snprintf(path_, sizeof path_, "%s", path.c_str());
    try {
        plane_ = load_plane_csv(path);
        error_.clear();
        dirty_ = true;
        measure_ = std::max(plane_->measure_index("period"), 0);
    } catch (const PlaneError& e) {
        error_ = e.what();
    }
    return error_;
}

void PlanePanel::start(const AnalysisContext& c) {
    const Params p = *c.params;
    PlaneRequest req = req_;
    req.omega_lo = std::max(c.diagram_omega.lo, 0.1);
    req.omega_hi = std::max(c.diagram_omega.hi, req.omega_lo + 1.0);
    const std::string model = c.model;
    job_.start([p, req, model](Progress& prog) { return compute_plane(p, model, req, prog); });
}

std::string PlanePanel::start_doubling(const AnalysisContext& c) {
    if (!plane_) return "doubling curve: no plane yet (load or compute one)";
    const PlaneData& pl = *plane_;
    if (pl.x_name != "omega" || (pl.y_name != "xI" && pl.y_name != "m0e") || pl.nx() < 2 || pl.ny() < 2)
        return "doubling curve: the plane's axes must be omega and xI or m0e";
    analysis::PlaneCurveSpec spec;
    spec.second = pl.y_name == "xI" ? analysis::ContParam::XI : analysis::ContParam::M0e;
    spec.omega_lo = pl.xs.front();
    spec.omega_hi = pl.xs.back();
    spec.lo = pl.ys.front();
    spec.hi = pl.ys.back();
    spec.step = 0.5 * (spec.hi - spec.lo) / (pl.ny() - 1);   // half the grid step, as impactlab scan
    const Params p = *c.params;
    doubling_model_ = c.model;
    doubling_second_ = pl.y_name;
    doubling_job_.start([p, spec](Progress& prog) { return analysis::curve_over_plane(p, spec, &prog); });
    return "";
}

bool PlanePanel::busy() const { return want_plane_ || want_doubling_ || job_.running() || doubling_job_.running(); }

void PlanePanel::release_gl() {
    if (tex_) {
        const GLuint id = tex_;
        glDeleteTextures(1, &id);
        tex_ = 0;
    }
}

AnalysisAction PlanePanel::poll(const AnalysisContext& c, std::string& startup_error) {
    AnalysisAction act;
    if (std::exchange(want_plane_, false)) {
        start(c);
        act.open_plane = true;
    }
    auto report = [&](const std::string& what, const std::string& err) {
        if (err.empty()) return;
        act.toast = what + " failed: " + err;
        if (startup_error.empty()) startup_error = act.toast;
    };
    report("plane", job_.take_error());
    report("doubling curve", doubling_job_.take_error());
    if (auto r = job_.take_result()) {
        plane_ = std::move(*r);
        error_.clear();
        dirty_ = true;
        measure_ = std::max(plane_->measure_index("period"), 0);
        act.toast = "plane " + plane_->source + ": " + std::to_string(plane_->nx()) + " x " + std::to_string(plane_->ny());
    }
    // --plane-doubling: once the plane (loaded, or computed at start) is there.
    if (want_doubling_ && !job_.running() && plane_) {
        want_doubling_ = false;
        if (std::string err = start_doubling(c); !err.empty()) {
            act.toast = err;
            if (startup_error.empty()) startup_error = err;
        }
    } else if (want_doubling_ && !job_.running() && !want_plane_) {
        want_doubling_ = false;
        if (startup_error.empty()) startup_error = "--plane-doubling: no plane (give --plane FILE or --small-plane)";
    }
    if (auto r = doubling_job_.take_result()) {
        char buf[200];
        if (r->found)
            std::snprintf(buf, sizeof buf, "doubling curve %s: from omega = %.7f, %zu points in %.1f s%s", doubling_model_.c_str(),
                          r->omega0, r->curve.points.size(), r->seconds, r->cancelled ? " (cancelled, partial)" : "");
        else std::snprintf(buf, sizeof buf, "doubling curve %s: %s%s", doubling_model_.c_str(), r->note.c_str(),
                           r->cancelled ? " (cancelled)" : "");
        act.toast = buf;
        doubling_ = PlaneDoublingShown{std::move(*r), doubling_model_, doubling_second_};
    }
    return act;
}

AnalysisAction PlanePanel::draw(const AnalysisContext& c) {
    AnalysisAction act;
    const float fs = ImGui::GetFontSize(), sp = ImGui::GetStyle().ItemSpacing.x;
    ImGui::SetNextItemWidth(std::clamp(ImGui::GetContentRegionAvail().x * 0.3f, 4.0f * fs, 16.0f * fs));
    const bool enter = ImGui::InputTextWithHint("##planepath", "plane.csv (impactlab scan --out)", path_, sizeof path_,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if (ImGui::Button("Load") || enter) {
        const std::string err = load(path_);
        act.toast = err.empty() ? std::string("plane loaded: ") + path_ : err;
    }
    ImGui::SameLine();
    auto job_row = [&](auto& job, const char* idle_label, auto&& on_start, const char* tip) {
        if (job.running()) {
            ImGui::PushID(idle_label);
            if (ImGui::Button("Cancel")) job.cancel();
            ImGui::SameLine();
            ImGui::ProgressBar(static_cast<float>(job.progress()), ImVec2(std::max(3.0f * fs, std::min(8.0f * fs, ImGui::GetContentRegionAvail().x)), 0));
            ImGui::PopID();
        } else {
            if (ImGui::Button(idle_label)) on_start();
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tip);
        }
    };
    char label[48];
    std::snprintf(label, sizeof label, "Compute %dx%d", req_.nx, req_.ny);
    char tip[200];
    std::snprintf(tip, sizeof tip, "(ω over the diagram's range) x (x_I from -10 to 10 mm) for %s on a worker:\n"
                                   "each row a CF sweep along ω, as impactlab scan", c.model.c_str());
    job_row(job_, label, [&] { start(c); }, tip);
    same_line_or_wrap(button_width("Doubling curve") + sp);
    job_row(doubling_job_, "Doubling curve", [&] {
        if (std::string err = start_doubling(c); !err.empty()) act.toast = err;
    }, "The first period-1 doubling over the plane's ω range (continued in ω at the running model's own\n"
       "x_I or m0e), then followed along the plane's other axis, on a worker: the core's\n"
       "curve_over_plane, as impactlab scan --doubling-from auto.");
    if (!error_.empty()) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", error_.c_str());
    if (!plane_) {
        ImGui::TextDisabled("No plane: load a scan CSV (impactlab scan ... --out plane.csv) or compute one.");
        return act;
    }
    PlaneData& pl = *plane_;
    const std::vector<double>& vals = pl.values[static_cast<std::size_t>(measure_)];
    const bool classes = pl.measures[static_cast<std::size_t>(measure_)] == "period";
    double vmin = 1e300, vmax = -1e300;
    for (double v : vals)
        if (std::isfinite(v)) vmin = std::min(vmin, v), vmax = std::max(vmax, v);
    if (dirty_ || !tex_) {
        const int nx = pl.nx(), ny = pl.ny();
        std::vector<unsigned char> rgba(static_cast<std::size_t>(nx) * ny * 4, 0);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const double v = vals[static_cast<std::size_t>(j) * nx + i];
                if (!std::isfinite(v)) continue;   // not computed: transparent
                const Rgb cc = classes ? period_rgb(static_cast<int>(std::lround(v)))
                                       : ramp_rgb(vmax > vmin ? (v - vmin) / (vmax - vmin) : 0.5);
                unsigned char* px = &rgba[(static_cast<std::size_t>(ny - 1 - j) * nx + i) * 4];   // top row: the last y
                px[0] = cc.r, px[1] = cc.g, px[2] = cc.b, px[3] = 255;
            }
        tex_ = upload_rgba_texture(static_cast<GLuint>(tex_), nx, ny, rgba.data());
        dirty_ = false;
    }
    // The legend beside the map where the tile is wide enough; else the measure alone, above it.
    const float legend_w = fs * 9.5f;
    const bool legend = ImGui::GetContentRegionAvail().x > 3.0f * legend_w;
    std::vector<const char*> names;
    for (const auto& s : pl.measures) names.push_back(s.c_str());
    if (!legend) {
        ImGui::SetNextItemWidth(std::min(8.0f * fs, ImGui::GetContentRegionAvail().x));
        if (ImGui::Combo("##measure", &measure_, names.data(), static_cast<int>(names.size()))) dirty_ = true;
    }
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    ImGui::BeginGroup();
    const PlaneExtent e = plane_extent(pl);
    Axes ax;
    ax.x_label = axis_label(pl.x_name);
    ax.y_label = axis_label(pl.y_name);
    ax.x_scale = axis_scale(pl.x_name);
    ax.y_scale = axis_scale(pl.y_name);
    Plot plot;
    if (plot.begin("##plane", ImVec2(std::max(avail.x - (legend ? legend_w : 0.0f), 50.0f), avail.y), {e.x_lo, e.x_hi},
                   {e.y_lo, e.y_hi}, ax)) {
        ImDrawList* dl = plot.draw();
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex_)), plot.to_px(e.x_lo, e.y_hi),
                     plot.to_px(e.x_hi, e.y_lo));
        const Palette& pal = palette();
        // Where the bifurcation diagram lies on the plane.
        if (auto cut = diagram_cut(pl, c.diagram_omega.lo, c.diagram_omega.hi, c.xI, c.params->m0e)) {
            const ImVec2 p0 = plot.to_px(cut->x0, cut->y0), p1 = plot.to_px(cut->x1, cut->y1);
            dl->AddLine(p0, p1, IM_COL32(0, 0, 0, 200), 5.0f);
            dl->AddLine(p0, p1, IM_COL32(255, 255, 255, 255), 2.5f);
            const double wx = pl.x_name == "omega" ? c.omega : pl.x_name == "xI" ? c.xI : c.params->m0e;
            const double wy = pl.y_name == "omega" ? c.omega : pl.y_name == "xI" ? c.xI : c.params->m0e;
            const ImVec2 cur = plot.to_px(wx, wy);
            dl->AddCircleFilled(cur, 5.0f, IM_COL32(0, 0, 0, 220));
            dl->AddCircleFilled(cur, 3.5f, pal.cursor);
            plate_text(dl, ImVec2(std::min(p1.x, plot.area_max().x) - ImGui::CalcTextSize("bifurcation diagram").x - 6, p1.y + 4),
                       "bifurcation diagram", pal.axis_text);
        }
        // The continued doubling, where it is the plane's own second parameter.
        if (doubling_ && doubling_->second == pl.y_name && pl.x_name == "omega") {
            const auto& pts = doubling_->result.curve.points;
            std::vector<ImVec2> px;
            for (const analysis::CurvePoint& q : pts) px.push_back(plot.to_px(q.omega, q.q));
            if (px.size() >= 2) {
                dl->AddPolyline(px.data(), static_cast<int>(px.size()), IM_COL32(0, 0, 0, 220), 0, 5.0f);
                dl->AddPolyline(px.data(), static_cast<int>(px.size()), kCurve, 0, 2.5f);
            }
            for (const ImVec2& p : px) dl->AddCircleFilled(p, 2.5f, kCurve);
            char buf[96];
            std::snprintf(buf, sizeof buf, "period doubling of %s, continued", doubling_->model.c_str());
            plate_text(dl, ImVec2(plot.area_min().x + 4, plot.area_min().y + 4), buf, kCurve);
        }
        if (doubling_job_.running()) {
            char buf[80];
            std::snprintf(buf, sizeof buf, "following the doubling... %.0f%%", 100.0 * doubling_job_.progress());
            plate_text(dl, ImVec2(plot.area_min().x + 4, plot.area_min().y + 6 + ImGui::GetTextLineHeight()), buf, pal.axis_text);
        }
        const ImVec2 a = plot.area_min(), b = plot.area_max();
        const ImVec2 m = ImGui::GetIO().MousePos;
        if (plot.hovered()) {
            const auto cell = plane_pick(pl, (m.x - a.x) / (b.x - a.x), (b.y - m.y) / (b.y - a.y));
            if (cell) {
                const double v = vals[static_cast<std::size_t>(cell->j) * pl.nx() + cell->i];
                // A period is named as the map's legend names it ("chaos / > 16" for 0), not as a number.
                const std::string& measure = pl.measures[static_cast<std::size_t>(measure_)];
                char value[48];
                if (measure == "period" && std::isfinite(v)) std::snprintf(value, sizeof value, "%s", period_name(static_cast<int>(v)));
                else std::snprintf(value, sizeof value, "%s = %.4g", measure.c_str(), v);
                ImGui::SetTooltip("%s = %.4g, %s = %.4g\n%s\n(click: run there)", pl.x_name.c_str(), cell->x * axis_scale(pl.x_name),
                                  pl.y_name.c_str(), cell->y * axis_scale(pl.y_name), value);
                if (plot.clicked()) {
                    const PlaneClick click = plane_click(pl, *cell);
                    act.omega = click.omega;
                    act.xI = click.xI;
                    if (!click.ignored.empty()) act.toast = click.ignored + " is not a live parameter: only the other axis was set";
                }
            }
        }
        plate_text(dl, ImVec2(a.x + 4, b.y - ImGui::GetTextLineHeight() - 4), pl.source.c_str(), pal.axis_text);
        plot.end();
    }
    ImGui::EndGroup();
    if (!legend) return act;
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::SetNextItemWidth(legend_w - ImGui::GetStyle().ItemSpacing.x);
    if (ImGui::Combo("##measure", &measure_, names.data(), static_cast<int>(names.size()))) dirty_ = true;
    ImGui::Text("%d x %d points", pl.nx(), pl.ny());
    if (classes) {
        bool present[10] = {};
        for (double v : vals)
            if (std::isfinite(v)) present[std::clamp(period_class(static_cast<int>(std::lround(v))), 0, 9)] = true;
        for (int k : {1, 2, 3, 4, 5, 6, 7, 9, 0})
            if (present[k]) swatch(period_rgb(k), period_name(k));
    } else if (vmax >= vmin) {
        for (int k = 4; k >= 0; --k) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.4g", vmin + (vmax - vmin) * k / 4.0);
            swatch(ramp_rgb(k / 4.0), buf);
        }
    }
    ImGui::Spacing();
    ImGui::TextDisabled("line: the diagram");
    ImGui::TextDisabled("dot: running now");
    if (doubling_) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kCurve), "magenta: doubling");
    ImGui::EndGroup();
    return act;
}

nlohmann::json PlanePanel::state() const {
    using nlohmann::json;
    json j;
    j["loaded"] = plane_.has_value();
    if (plane_) {
        j["source"] = plane_->source;
        j["x"] = plane_->x_name;
        j["y"] = plane_->y_name;
        j["nx"] = plane_->nx();
        j["ny"] = plane_->ny();
    }
    j["running"] = job_.running();
    json d = nullptr;
    if (doubling_) {
        const analysis::PlaneCurve& r = doubling_->result;
        json pts = json::array();
        for (const analysis::CurvePoint& q : r.curve.points) pts.push_back({q.omega, q.q});
        d = {{"model", doubling_->model}, {"second", doubling_->second}, {"found", r.found}, {"omega0", r.omega0},
             {"y0", {r.y0[0], r.y0[1]}}, {"points", std::move(pts)}, {"end", r.curve.end}, {"note", r.note},
             {"cancelled", r.cancelled}, {"seconds", r.seconds}};
    }
    j["doubling"] = std::move(d);
    j["doubling_running"] = doubling_job_.running();
    return j;
}

}  // namespace impactlab::gui
