#include "plane_panel.hpp"

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
#include "render/theme.hpp"
#include "views/map_colors.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

using namespace maps;

namespace {

// The curves' colour: magenta with a dark edge, apart from every period class; told apart by their
// strokes as on impactlab scan's PNG (solid doubling, dashed grazing, dotted fold).
constexpr ImU32 kCurve = IM_COL32(255, 70, 200, 255);

// A polyline solid (on = 0), or dashed / dotted: `on` pixels drawn, `off` left, along its length.
void stroke(ImDrawList* dl, const std::vector<ImVec2>& px, ImU32 col, float width, float on, float off) {
    if (px.size() < 2) return;
    if (on <= 0) {
        dl->AddPolyline(px.data(), static_cast<int>(px.size()), col, 0, width);
        return;
    }
    float pos = 0;   // along the period on + off
    for (std::size_t k = 1; k < px.size(); ++k) {
        const ImVec2 a = px[k - 1], b = px[k];
        const float len = std::hypot(b.x - a.x, b.y - a.y);
        float t = 0;
        while (t < len) {
            const bool drawn = pos < on;
            const float run = std::min(len - t, drawn ? on - pos : on + off - pos);
            if (drawn) {
                const float t0 = t / len, t1 = (t + run) / len;
                dl->AddLine(ImVec2(a.x + (b.x - a.x) * t0, a.y + (b.y - a.y) * t0), ImVec2(a.x + (b.x - a.x) * t1, a.y + (b.y - a.y) * t1),
                            col, width);
            }
            t += run;
            pos += run;
            if (pos >= on + off) pos = 0;
        }
    }
}

// The strokes of scan's PNG, 8 on 6 off (dashed) and 3 on 4 off (dotted), at the UI's scale [px].
void curve_dash(int i, float scale, float& on, float& off) {
    on = i == 1 ? 8.0f * scale : i == 2 ? 3.0f * scale : 0.0f;
    off = i == 1 ? 6.0f * scale : i == 2 ? 4.0f * scale : 0.0f;
}

// A short sample of curve i's stroke, for a legend line.
void stroke_sample(ImDrawList* dl, ImVec2 p, float w, int i, float scale) {
    float on, off;
    curve_dash(i, scale, on, off);
    const std::vector<ImVec2> px = {p, ImVec2(p.x + w, p.y)};
    stroke(dl, px, IM_COL32(0, 0, 0, 220), 4.0f, on, off);
    stroke(dl, px, kCurve, 2.0f, on, off);
}

}  // namespace

std::string PlanePanel::configure(const Options& opt) {
    want_plane_ = opt.small_plane;
    if (opt.plane_doubling) want_curve_[0] = CurveStart{};
    if (!opt.plane_grazing.empty()) want_curve_[1] = parse_curve_start(opt.plane_grazing);   // checked by options
    if (!opt.plane_fold.empty()) want_curve_[2] = parse_curve_start(opt.plane_fold);
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

std::string PlanePanel::start_curve(const AnalysisContext& c, analysis::BifKind kind, const CurveStart& from) {
    if (!plane_) return std::string(plane_curve_word(kind)) + " curve: no plane yet (load or compute one)";
    return curves_.start(kind, *plane_, *c.params, c.model, from);
}

bool PlanePanel::busy() const {
    bool wanted = want_plane_;
    for (const auto& w : want_curve_) wanted = wanted || w.has_value();
    return wanted || job_.running() || curves_.any_running();
}

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
    if (auto r = job_.take_result()) {
        plane_ = std::move(*r);
        error_.clear();
        dirty_ = true;
        measure_ = std::max(plane_->measure_index("period"), 0);
        act.toast = "plane " + plane_->source + ": " + std::to_string(plane_->nx()) + " x " + std::to_string(plane_->ny());
    }
    // --plane-doubling, --plane-grazing, --plane-fold: once the plane (loaded, or computed at start) is there.
    static const char* const flags[kPlaneCurves] = {"--plane-doubling", "--plane-grazing", "--plane-fold"};
    for (int i = 0; i < kPlaneCurves; ++i) {
        auto& want = want_curve_[static_cast<std::size_t>(i)];
        if (!want || job_.running()) continue;
        std::string err;
        if (plane_) err = start_curve(c, kPlaneCurveKinds[i], *want);
        else if (!want_plane_) err = std::string(flags[i]) + ": no plane (give --plane FILE or --small-plane)";
        else continue;
        want.reset();
        if (!err.empty()) {
            act.toast = plane_ ? std::string(flags[i]) + ": " + err : err;
            if (startup_error.empty()) startup_error = act.toast;
        }
    }
    std::string failed;
    if (std::string toast = curves_.poll(failed); !toast.empty()) act.toast = std::move(toast);
    if (!failed.empty()) report(failed.substr(0, failed.find(':')), failed.substr(failed.find(':') + 2));
    return act;
}

AnalysisAction PlanePanel::draw_controls(const AnalysisContext& c) {
    AnalysisAction act;
    const float fs = ImGui::GetFontSize(), sp = ImGui::GetStyle().ItemSpacing.x;
    // One row, so that the plot keeps the tile at a large UI scale: the plane's and the curves' settings in
    // popups, and only a running job's bar and Cancel beside them.
    if (ImGui::Button("Plane...")) ImGui::OpenPopup("##plane_settings");
    tooltip("Load a scan CSV (impactlab scan --out) or compute a plane on a worker");
    if (ImGui::BeginPopup("##plane_settings")) {
        ImGui::SetNextItemWidth(16.0f * fs);
        const bool enter = ImGui::InputTextWithHint("##planepath", "plane.csv (impactlab scan --out)", path_, sizeof path_,
                                                    ImGuiInputTextFlags_EnterReturnsTrue);
        ImGui::SameLine();
        if (ImGui::Button("Load") || enter) {
            const std::string err = load(path_);
            act.toast = err.empty() ? std::string("plane loaded: ") + path_ : err;
            if (err.empty()) ImGui::CloseCurrentPopup();
        }
        char label[48];
        std::snprintf(label, sizeof label, "Compute %dx%d", req_.nx, req_.ny);
        if (ImGui::Button(label)) {
            start(c);
            ImGui::CloseCurrentPopup();
        }
        char tip[200];
        std::snprintf(tip, sizeof tip, "(ω over the diagram's range) x (x_I from -10 to 10 mm) for %s on a worker:\n"
                                       "each row a CF sweep along ω, as impactlab scan", c.model.c_str());
        tooltip(tip);
        ImGui::EndPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Curves...")) ImGui::OpenPopup("##plane_curves");
    tooltip("Continue a period doubling, grazing or fold over the plane (right-click the plane: from a cell)");
    if (ImGui::BeginPopup("##plane_curves")) {
        for (int i = 0; i < kPlaneCurves; ++i) {
            const analysis::BifKind kind = kPlaneCurveKinds[i];
            char item[64];
            std::snprintf(item, sizeof item, "%s%s curve (the first over ω)", i == 0 ? "Doubling" : i == 1 ? "Grazing" : "Fold",
                          curves_.running(i) ? " (running)" : "");
            if (ImGui::MenuItem(item)) {
                if (std::string err = start_curve(c, kind, CurveStart{}); !err.empty()) act.toast = err;
            }
        }
        ImGui::TextDisabled("From the first period-1 one over the plane's ω range at the\n"
                            "model's own second parameter, followed along the plane's y axis\n"
                            "by the core (impactlab scan --doubling-from/--grazing-from/\n"
                            "--fold-from auto). Right-click the plane: from that cell.");
        if (ImGui::MenuItem("Clear curves")) curves_.clear();
        ImGui::EndPopup();
    }
    if (plane_) {
        const PlaneData& pl = *plane_;
        std::vector<const char*> names;
        for (const auto& m : pl.measures) names.push_back(m.c_str());
        // As wide as the row has room for, down to 4 em (a period class's name still shows).
        same_line_or_wrap(4.0f * fs);
        ImGui::SetNextItemWidth(std::clamp(ImGui::GetContentRegionAvail().x, 4.0f * fs, 7.0f * fs));
        if (ImGui::Combo("##measure", &measure_, names.data(), static_cast<int>(names.size()))) dirty_ = true;
    }
    // A running job: its bar and Cancel, the plane's first.
    auto running = [&](const char* id, double fraction, auto&& cancel) {
        same_line_or_wrap(button_width("Cancel") + 3.0f * fs + sp);
        ImGui::PushID(id);
        if (ImGui::Button("Cancel")) cancel();
        ImGui::PopID();
        tooltip(id);
        ImGui::SameLine();
        ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(std::max(3.0f * fs, std::min(6.0f * fs, ImGui::GetContentRegionAvail().x)), 0));
    };
    if (job_.running()) running("cancel the plane", job_.progress(), [&] { job_.cancel(); });
    for (int i = 0; i < kPlaneCurves; ++i) {
        if (!curves_.running(i)) continue;
        char id[48];
        std::snprintf(id, sizeof id, "cancel the %s curve", plane_curve_word(kPlaneCurveKinds[i]));
        running(id, curves_.progress(i), [&] { curves_.cancel(i); });
    }
    if (!error_.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", error_.c_str());
        ImGui::PopTextWrapPos();
    }
    return act;
}

void PlanePanel::draw_curves(Plot& plot, bool legend) {
    ImDrawList* dl = plot.draw();
    const float fs = ImGui::GetFontSize(), scale = fs / 13.0f, line = ImGui::GetTextLineHeight();
    ImVec2 key(plot.area_min().x + 4, plot.area_min().y + 4);   // a one-row key where no legend is beside
    bool keyed = false;
    for (int i = 0; i < kPlaneCurves; ++i) {
        const auto& shown = curves_.shown(i);
        // A curve is drawn where it is the plane's own second parameter (omega across).
        if (!shown || shown->second != plane_->y_name || plane_->x_name != "omega" || shown->result.curve.points.empty()) continue;
        std::vector<ImVec2> px;
        for (const analysis::CurvePoint& q : shown->result.curve.points) px.push_back(plot.to_px(q.omega, q.q));
        float on, off;
        curve_dash(i, scale, on, off);
        stroke(dl, px, IM_COL32(0, 0, 0, 220), 5.0f, on, off);
        stroke(dl, px, kCurve, 2.5f, on, off);
        if (on <= 0)   // the solid curve's computed points (dots would blur the others' strokes)
            for (const ImVec2& p : px) dl->AddCircleFilled(p, 2.5f, kCurve);
        if (legend) continue;
        const char* word = plane_curve_word(kPlaneCurveKinds[i]);
        const ImVec2 text = ImGui::CalcTextSize(word);
        dl->AddRectFilled(key, ImVec2(key.x + 1.6f * fs + text.x + 6, key.y + line), IM_COL32(0, 0, 0, 170), 3.0f);
        stroke_sample(dl, ImVec2(key.x + 2, key.y + 0.5f * line), 1.3f * fs, i, scale);
        dl->AddText(ImVec2(key.x + 1.6f * fs, key.y), kCurve, word);
        key.x += 1.6f * fs + text.x + 0.8f * fs;
        keyed = true;
    }
    float y = plot.area_min().y + 4 + (keyed ? line + 2 : 0.0f);
    for (int i = 0; i < kPlaneCurves; ++i) {
        if (!curves_.running(i)) continue;
        char buf[80];
        std::snprintf(buf, sizeof buf, "following the %s... %.0f%%", plane_curve_word(kPlaneCurveKinds[i]), 100.0 * curves_.progress(i));
        plate_text(dl, ImVec2(plot.area_min().x + 4, y), buf, palette().axis_text);
        y += line + 2;
    }
}

void PlanePanel::draw_legend(const std::vector<double>& vals, bool classes, double vmin, double vmax) {
    const PlaneData& pl = *plane_;
    ImGui::Text("%d x %d points", pl.nx(), pl.ny());
    if (classes) {
        bool present[10] = {};
        for (double v : vals)
            if (std::isfinite(v)) present[std::clamp(period_class(static_cast<int>(std::lround(v))), 0, 9)] = true;
        for (int k : {1, 2, 3, 4, 5, 6, 7, 9, 0, 8})
            if (present[k]) swatch(period_rgb(k == 8 ? -1 : k), period_name(k == 8 ? -1 : k));
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
    // The curves as scan's PNG names them, each after a sample of its stroke.
    const float fs = ImGui::GetFontSize();
    for (int i = 0; i < kPlaneCurves; ++i) {
        if (!curves_.shown(i) || curves_.shown(i)->result.curve.points.empty()) continue;   // none found: the toast said why
        const ImVec2 p = ImGui::GetCursorScreenPos();
        stroke_sample(ImGui::GetWindowDrawList(), ImVec2(p.x, p.y + 0.5f * ImGui::GetTextLineHeight()), 1.6f * fs, i, fs / 13.0f);
        ImGui::Dummy(ImVec2(1.8f * fs, ImGui::GetTextLineHeight()));
        ImGui::SameLine();
        // The PNG's label less its "(dashed)": the sample shows the stroke, and the column is narrow.
        const std::string label = plane_curve_label(kPlaneCurveKinds[i]);
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kCurve), "%s", label.substr(0, label.find(", continued")).c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s of %s", label.c_str(), curves_.shown(i)->model.c_str());
    }
}

AnalysisAction PlanePanel::draw(const AnalysisContext& c) {
    AnalysisAction act = draw_controls(c);
    if (!plane_) {
        ImGui::TextDisabled("No plane: load a scan CSV (impactlab scan ... --out plane.csv) or compute one (Plane...).");
        return act;
    }
    PlaneData& pl = *plane_;
    const float fs = ImGui::GetFontSize();
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
    // The legend beside the map where the tile is wide enough (the curves' names over the map otherwise).
    const float legend_w = fs * 9.5f;
    const bool legend = ImGui::GetContentRegionAvail().x > 3.0f * legend_w;
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
        draw_curves(plot, legend);
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
                ImGui::SetTooltip("%s = %.4g, %s = %.4g\n%s\n(click: run there; right-click: a curve from here)", pl.x_name.c_str(),
                                  cell->x * axis_scale(pl.x_name), pl.y_name.c_str(), cell->y * axis_scale(pl.y_name), value);
                if (plot.clicked()) {
                    const PlaneClick click = plane_click(pl, *cell);
                    act.omega = click.omega;
                    act.xI = click.xI;
                    if (!click.ignored.empty()) act.toast = click.ignored + " is not a live parameter: only the other axis was set";
                }
                if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
                    picked_ = cell;
                    ImGui::OpenPopup("##plane_menu");
                }
            }
        }
        // The file's name without its folders (a long path would cover the map at a large UI scale).
        const std::string name = pl.source.substr(pl.source.find_last_of("/\\") + 1);
        plate_text(dl, ImVec2(a.x + 4, b.y - ImGui::GetTextLineHeight() - 4), name.c_str(), pal.axis_text);
        plot.end();
    }
    // The context menu: a curve from the picked cell (the first one above its omega, at its row's value).
    if (ImGui::BeginPopup("##plane_menu")) {
        if (picked_) {
            ImGui::TextDisabled("ω = %.4g, %s = %.4g", picked_->x * axis_scale(pl.x_name), pl.y_name.c_str(),
                                picked_->y * axis_scale(pl.y_name));
            for (int i = 0; i < kPlaneCurves; ++i) {
                char item[64];
                std::snprintf(item, sizeof item, "%s curve from here", i == 0 ? "Doubling" : i == 1 ? "Grazing" : "Fold");
                if (ImGui::MenuItem(item)) {
                    CurveStart from;
                    from.from = CurveStart::From::Picked;
                    from.omega = picked_->x;
                    from.q = picked_->y;
                    if (std::string err = start_curve(c, kPlaneCurveKinds[i], from); !err.empty()) act.toast = err;
                }
            }
        }
        ImGui::EndPopup();
    }
    ImGui::EndGroup();
    if (!legend) return act;
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::PushItemWidth(legend_w - ImGui::GetStyle().ItemSpacing.x);
    draw_legend(vals, classes, vmin, vmax);
    ImGui::PopItemWidth();
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
        j["xs"] = plane_->xs;
        j["ys"] = plane_->ys;
        // The period measure cell by cell (x fastest; -1 not settled, 0 chaos, null not computed).
        if (const int m = plane_->measure_index("period"); m >= 0) {
            json per = json::array();
            for (const double v : plane_->values[static_cast<std::size_t>(m)]) per.push_back(std::isfinite(v) ? json(v) : json(nullptr));
            j["periods"] = std::move(per);
        }
    }
    j["running"] = job_.running();
    // Each curve: where it started, its points (omega [rad/s], the second parameter) and why it ended.
    json running = json::object();
    for (int k = 0; k < kPlaneCurves; ++k) {
        const char* word = plane_curve_word(kPlaneCurveKinds[k]);
        running[word] = curves_.running(k);
        json d = nullptr;
        if (const auto& shown = curves_.shown(k)) {
            const analysis::PlaneCurve& r = shown->result;
            json pts = json::array();
            for (const analysis::CurvePoint& q : r.curve.points) pts.push_back({q.omega, q.q});
            d = {{"model", shown->model}, {"second", shown->second}, {"start", curve_start_text(shown->start)},
                 {"period", r.curve.period}, {"found", r.found}, {"omega0", r.omega0}, {"y0", {r.y0[0], r.y0[1]}},
                 {"points", std::move(pts)}, {"end", r.curve.end}, {"note", r.note}, {"cancelled", r.cancelled},
                 {"seconds", r.seconds}};
        }
        j[word] = std::move(d);
    }
    j["doubling_running"] = curves_.running(0);
    j["curves_running"] = std::move(running);
    return j;
}

}  // namespace impactlab::gui
