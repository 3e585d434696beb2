#include "data_panel.hpp"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>

#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

struct XY {
    double x, y;
};

Range to_range(std::pair<double, double> e, double min_span) {
    Range r{e.first, e.second};
    if (r.span() < min_span) {
        const double c = 0.5 * (r.lo + r.hi);
        r = {c - 0.5 * min_span, c + 0.5 * min_span};
    }
    return r;
}

// The axes of an x(t) plot: t in s, x in mm.
Axes x_of_t_axes() {
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = "x [mm]";
    ax.y_scale = 1e3;
    return ax;
}

ImU32 after_color() { return palette().energy; }
ImU32 before_color() { return palette().section_new; }
ImU32 measured_color() { return palette().trace; }

void legend_item(ImU32 col, const char* label) {
    const float fs = ImGui::GetFontSize();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + fs * 0.35f), ImVec2(p.x + fs * 1.2f, p.y + fs * 0.65f), col);
    ImGui::Dummy(ImVec2(fs * 1.35f, fs));
    ImGui::SameLine(0, 0);
    ImGui::TextUnformatted(label);
}

// An indeterminate spinner: an arc turning with the clock.
void spinner(float radius) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float t = static_cast<float>(ImGui::GetTime());
    const ImVec2 c(p.x + radius, p.y + ImGui::GetFrameHeight() * 0.5f);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PathArcTo(c, radius, t * 6.0f, t * 6.0f + 4.2f, 24);
    dl->PathStroke(palette().trace, 0, std::max(2.0f, radius * 0.3f));
    ImGui::Dummy(ImVec2(radius * 2.0f, ImGui::GetFrameHeight()));
}

void row_label(const char* s) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(s);
}

}  // namespace

DataPanel::DataPanel() { fit_options_.plots = false; }

void DataPanel::load(const std::string& path, bool then_fit) {
    std::snprintf(path_, sizeof path_, "%s", path.c_str());
    DataColumns c;
    c.t = t_col_;
    c.x = x_col_;
    c.forcing = f_col_;
    c.forcing_is_u = f_is_u_;
    c.rate = rate_;
    c.x_scale = x_scale_ > 0 ? x_scale_ : 1.0;
    c.free_run = free_run_;
    error_.clear();
    pending_fit_ = then_fit;
    job_.start_load(path, load_options_from(c));
}

nlohmann::json DataPanel::state() const {
    nlohmann::json j;
    j["path"] = loaded_path();
    j["samples"] = data_ ? data_->size() : 0;
    j["duration_s"] = data_ && data_->size() > 1 ? nlohmann::json(data_->t.back() - data_->t.front()) : nlohmann::json(nullptr);
    j["busy"] = busy();
    j["fitted"] = has_report();
    j["error"] = error_.empty() ? nlohmann::json(nullptr) : nlohmann::json(error_);
    return j;
}

void DataPanel::start_fit(const DataPanelContext& ctx) {
    pending_fit_ = false;
    if (!data_) return;
    try {
        identify::Model m = model_for_data(ctx.model, *data_);
        m.p.xI = ctx.xI;
        base_model_ = m;
        fit_model_name_ = ctx.model;
        error_.clear();
        job_.start_fit(data_, m, fit_options_);
    } catch (const std::exception& e) {
        error_ = panel_wording(e.what());
    }
}

void DataPanel::take(DataJobResult r, const DataPanelContext& ctx) {
    if (!r.error.empty()) {
        const char* what = r.kind == DataJobResult::Kind::Load ? "load" : r.kind == DataJobResult::Kind::Fit ? "fit" : "evaluation";
        error_ = std::string(what) + ": " + panel_wording(r.error);
        if (r.kind == DataJobResult::Kind::Evaluate) eval_errors_[r.mask] = panel_wording(r.error);
        if (r.kind == DataJobResult::Kind::Load) pending_fit_ = false;
        return;
    }
    switch (r.kind) {
        case DataJobResult::Kind::Load:
            data_ = std::move(r.data);
            if (data_->size() > 1) record_t_ = {data_->t.front(), data_->t.back()};
            record_x_ = to_range(robust_extent({&data_->x}, 0.0, 0.08), 1e-4);
            report_.reset();
            evals_.clear();
            eval_errors_.clear();
            if (pending_fit_) start_fit(ctx);
            break;
        case DataJobResult::Kind::Fit: {
            report_ = std::move(r.report);
            all_ = all_effects_mask(*report_);
            mask_ = all_;
            evals_.clear();
            eval_errors_.clear();
            // The fit measured its baseline and its final model: the subsets "none" and "all" (the baseline is
            // the fitted one where the gate kept it, else the model given).
            evals_[0] = report_->baseline_column ? report_->error_baseline : report_->error_before;
            evals_[all_] = report_->error_after;
            const auto& tr = report_->trace;
            if (!tr.t.empty()) trace_t_ = {tr.t.front(), tr.t.back()};
            trace_x_ = to_range(robust_extent({&tr.measured, &tr.before, &tr.after}, 0.0, 0.08), 1e-4);
            const auto& rc = report_->residual;
            res_y_ = to_range(robust_extent({&rc.before, &rc.after}, 0.005, 0.08), 1e-6);
            res_x_ = to_range(robust_extent({&rc.x}, 0.0, 0.04), 1e-4);
            res_v_ = to_range(robust_extent({&rc.v}, 0.0, 0.04), 1e-3);
            {
                double wl = 1e300, wh = -1e300, xl = 1e300, xh = -1e300;
                for (const auto* pts : {&report_->diagram_measured, &report_->diagram_before, &report_->diagram_after})
                    for (const auto& [w, x] : *pts) {
                        if (!std::isfinite(w) || !std::isfinite(x)) continue;
                        wl = std::min(wl, w);
                        wh = std::max(wh, w);
                        xl = std::min(xl, x);
                        xh = std::max(xh, x);
                    }
                if (wl > wh) wl = wh = xl = xh = 0.0;
                sec_w_ = to_range({wl - 0.25, wh + 0.25}, 0.5);
                sec_x_ = to_range({xl - 5e-4, xh + 5e-4}, 1e-3);
            }
            break;
        }
        case DataJobResult::Kind::Evaluate:
            evals_[r.mask] = r.errors;
            break;
    }
}

void DataPanel::poll(const DataPanelContext& ctx) {
    if (auto r = job_.take_result()) take(std::move(*r), ctx);
    // The errors of the chosen subset: evaluated once, on the worker, then kept.
    if (report_ && data_ && !job_.running() && !evals_.count(mask_) && !eval_errors_.count(mask_)) {
        try {
            job_.start_evaluate(data_, model_for_subset(*report_, mask_), fit_options_, mask_);
        } catch (const std::exception& e) {
            eval_errors_[mask_] = e.what();
        }
    }
}

void DataPanel::settle(const DataPanelContext& ctx, double timeout_s) {
    for (int k = 0; k < 8; ++k) {
        if (!job_.wait(timeout_s)) return;
        poll(ctx);
        if (!job_.running()) return;
    }
}

void DataPanel::draw_file_row() {
    const float fs = ImGui::GetFontSize();
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("File");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(std::max(fs * 10.0f, ImGui::GetContentRegionAvail().x - fs * 22.0f));
    const bool enter = ImGui::InputTextWithHint("##path", "data.csv or data.csv.gz (t, x, phi or u)", path_, sizeof path_,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button("Load") || enter) && path_[0]) load(path_, false);
    ImGui::SameLine();
    if (ImGui::Button(browsing_ ? "Hide files" : "Browse...")) browsing_ = !browsing_;
    ImGui::SameLine();
    if (data_) {
        const auto& d = *data_;
        ImGui::TextDisabled("%zu samples, %.1f s, forced by %s", d.size(), d.size() ? d.t.back() - d.t.front() : 0.0,
                            d.has_phi() ? "phi" : "u");
    } else {
        ImGui::TextDisabled("no data loaded");
    }
    if (browsing_ && browser_.draw("##data_files", path_, sizeof path_, 6)) load(path_, false);   // a double-click loads
    if (ImGui::TreeNode("Column mapping (for files not in the t, x, phi layout)")) {
        const float w = fs * 7.0f;
        ImGui::SetNextItemWidth(w);
        ImGui::InputTextWithHint("time##tcol", "t", t_col_, sizeof t_col_);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(w);
        ImGui::InputTextWithHint("x##xcol", "x", x_col_, sizeof x_col_);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(w);
        ImGui::InputTextWithHint("forcing##fcol", f_is_u_ ? "u" : "phi", f_col_, sizeof f_col_);
        ImGui::SameLine();
        ImGui::Checkbox("forcing is an input u", &f_is_u_);
        ImGui::SetNextItemWidth(w);
        ImGui::InputFloat("sample rate [Hz] (0: time column)", &rate_, 0, 0, "%.2f");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(w);
        ImGui::InputFloat("x scale (1e-3: mm)", &x_scale_, 0, 0, "%g");
        ImGui::Checkbox("a free run (nothing drove it: a decay; other columns ignored)", &free_run_);
        ImGui::TextDisabled("A column is a header name or a 1-based number; empty: the conventional name.");
        ImGui::TreePop();
    }
}

void DataPanel::draw_fit_row(const DataPanelContext& ctx) {
    ImGui::AlignTextToFramePadding();
    ImGui::Text("Model %s, x_I = %.2f mm", ctx.model.c_str(), ctx.xI * 1e3);
    ImGui::SameLine();
    const bool running = job_.running();
#ifdef __EMSCRIPTEN__
    // The page has no least squares (Ceres): the button says where the fit runs instead of failing.
    ImGui::BeginDisabled();
    ImGui::Button("Run fit");
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("the fit runs in the desktop program (impactlab fit, or impactlab-gui)");
#else
    ImGui::BeginDisabled(!data_ || running);
    if (ImGui::Button("Run fit")) start_fit(ctx);
    ImGui::EndDisabled();
#endif
    if (running) {
        ImGui::SameLine();
        spinner(ImGui::GetFontSize() * 0.45f);
        ImGui::SameLine();
        if (job_.running_kind() == DataJobResult::Kind::Fit) {
            // The core's stage and its share of the whole fit.
            const int stage = job_.fit_stage();
            char label[96];
            std::snprintf(label, sizeof label, "%s  %.0f %%",
                          stage >= 0 ? identify::fit_stage_name(static_cast<identify::FitStage>(stage)) : "starting",
                          100.0 * job_.fit_fraction());
            ImGui::ProgressBar(static_cast<float>(job_.fit_fraction()), ImVec2(ImGui::GetFontSize() * 18.0f, 0.0f), label);
            ImGui::SameLine();
            ImGui::Text("%.1f s", job_.running_for_s());
        } else {
            const char* what = job_.running_kind() == DataJobResult::Kind::Load ? "loading" : "evaluating the chosen effects";
            ImGui::Text("%s ... %.1f s", what, job_.running_for_s());
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) {
            job_.cancel();
            pending_fit_ = false;
            if (report_) eval_errors_[mask_] = "cancelled";
        }
    } else if (report_) {
        ImGui::SameLine();
        if (report_->metres())
            ImGui::TextDisabled("fit of %s: %.2f s, noise %.1f um, %zu impacts", fit_model_name_.c_str(), report_->runtime_s,
                                report_->sigma_x * 1e6, report_->impacts.size());
        else   // a plain Duffing model works in the data's own units
            ImGui::TextDisabled("fit of %s: %.2f s, noise %.3g (%s)", fit_model_name_.c_str(), report_->runtime_s, report_->sigma_x,
                                report_->x_unit());
    }
    if (!error_.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 80, 70, 255));
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(error_.c_str());
        ImGui::PopTextWrapPos();
        ImGui::PopStyleColor();
    }
}

void DataPanel::draw_effects() {
    const auto& r = *report_;
    ImGui::TextUnformatted("Effects found (switch them on and off: the errors below follow)");
    ImGui::Separator();
    if (r.effects_found.empty()) text_wrapped_at_spaces("No effect passed the held-out test and the final gate.");
    // What the fit concluded, and what the final gate undid: the same sentences as report.md (wrapped at
    // spaces: a fitted value is never split).
    text_wrapped_at_spaces(("Verdict: " + r.verdict + ".").c_str());
    for (const auto& g : r.gate) text_wrapped_at_spaces(("Final gate: " + g + ".").c_str());
    for (std::size_t k = 0; k < r.effects_found.size() && k < kMaxToggleEffects; ++k) {
        const auto& f = r.effects_found[k];
        const std::uint32_t bit = std::uint32_t{1} << k;
        bool on = (mask_ & bit) != 0;
        char label[160];
        std::snprintf(label, sizeof label, "%s   %.1f %%  z %.0f##eff%zu", f.id.c_str(), 100.0 * f.explained_fraction, f.z, k);
        if (ImGui::Checkbox(label, &on)) {
            mask_ = on ? (mask_ | bit) : (mask_ & ~bit);
            eval_errors_.erase(mask_);   // a failed or cancelled evaluation is tried again
        }
        ImGui::Indent();
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        text_wrapped_at_spaces((f.sentence + " (" + identify::evidence_name(f.evidence) + ")" +
                                (f.not_told_from.empty() ? std::string() : "; its shape is not resolved from " + f.not_told_from + ", so its law is no finding"))
                                   .c_str());
        ImGui::PopStyleColor();
        ImGui::Unindent();
    }
    if (!r.candidates.empty() && ImGui::TreeNode("Candidates tried", "Candidates tried (%zu)", r.candidates.size())) {
        if (ImGui::BeginTable("##cand", 4, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg)) {
            ImGui::TableSetupColumn("effect");
            ImGui::TableSetupColumn("alone");
            ImGui::TableSetupColumn("z");
            ImGui::TableSetupColumn("kept");
            ImGui::TableHeadersRow();
            for (const auto& c : r.candidates) {
                row_label(c.id.c_str());
                ImGui::TableSetColumnIndex(1);
                ImGui::Text("%.1f %%", 100.0 * c.gain);
                ImGui::TableSetColumnIndex(2);
                ImGui::Text("%.1f", c.z);
                ImGui::TableSetColumnIndex(3);
                ImGui::TextUnformatted(c.selected ? "yes" : "");
            }
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
}

void DataPanel::draw_errors() {
    const auto& r = *report_;
    ImGui::Spacing();
    ImGui::TextUnformatted("Error: the model given, the fit's model, your choice");
    ImGui::Separator();
    const auto it = evals_.find(mask_);
    const identify::ErrorSummary* sel = it != evals_.end() ? &it->second : nullptr;
    const auto eit = eval_errors_.find(mask_);
    if (!ImGui::BeginTable("##err", 4, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV))
        return;
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("baseline");
    ImGui::TableSetupColumn("fit");
    ImGui::TableSetupColumn("chosen");
    ImGui::TableHeadersRow();
    struct Row {
        const char* label;
        double identify::ErrorSummary::*field;
        double scale;
        const char* fmt;
    };
    const Row rows[] = {{"residual RMS [N]", &identify::ErrorSummary::residual_rms_N, 1.0, "%.4f"},
                        {"shooting 1 period [mm]", &identify::ErrorSummary::shooting_rms_1_m, 1e3, "%.4f"},
                        {"shooting 10 periods [mm]", &identify::ErrorSummary::shooting_rms_10_m, 1e3, "%.4f"},
                        {"diagram distance [mm]", &identify::ErrorSummary::diagram_distance_m, 1e3, "%.4f"}};
    for (const Row& row : rows) {
        if (row.field == &identify::ErrorSummary::diagram_distance_m && r.error_before.diagram_distance_m < 0) continue;
        row_label(row.label);
        const identify::ErrorSummary* cols[3] = {&r.error_before, &r.error_after, sel};
        for (int c = 0; c < 3; ++c) {
            ImGui::TableSetColumnIndex(c + 1);
            if (!cols[c]) {
                ImGui::TextDisabled("%s", eit != eval_errors_.end() ? "failed" : "...");
                continue;
            }
            const double v = cols[c]->*row.field;
            if (c == 2 && v < r.error_before.*row.field)
                ImGui::PushStyleColor(ImGuiCol_Text, after_color());
            else
                ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_Text]);
            ImGui::Text(row.fmt, v * row.scale);
            ImGui::PopStyleColor();
        }
    }
    // The impact law (kappa and dwell) as the model predicts it against the data.
    row_label("impact law kappa RMS");
    const identify::ErrorSummary* cols[3] = {&r.error_before, &r.error_after, sel};
    for (int c = 0; c < 3; ++c) {
        ImGui::TableSetColumnIndex(c + 1);
        if (cols[c]) ImGui::Text("%.4f", cols[c]->impact.kappa_rms);
        else ImGui::TextDisabled("...");
    }
    ImGui::EndTable();
    if (sel && mask_ != 0 && sel->shooting_rms_10_m > 0) {
        ImGui::TextDisabled("chosen / baseline, shooting over 10 periods: %.2f",
                            sel->shooting_rms_10_m / std::max(1e-300, r.error_before.shooting_rms_10_m));
    }
}

void DataPanel::draw_trace(ImVec2 size) {
    const auto& tr = report_->trace;
    const Palette& pal = palette();
    if (tr.t.empty()) {
        ImGui::TextDisabled("no x(t) trace in the report (record too short for a 10-period window)");
        return;
    }
    Plot plot;
    const Axes ax = x_of_t_axes();
    if (!plot.begin("##trace", size, trace_t_, trace_x_, ax)) return;
    if (data_) plot.hline(report_->before.p.xI, pal.bumper, 1.0f, true);
    const std::size_t n = tr.t.size();
    auto draw = [&](const std::vector<double>& y, ImU32 col, float w) {
        const std::size_t m = std::min(n, y.size());
        plot.series(m, [&](std::size_t i) { return XY{tr.t[i], y[i]}; }, col, w);
    };
    // The measured curve wide underneath, the two simulations thin on top: where they follow it, they sit
    // inside it.
    draw(tr.measured, measured_color(), 3.2f);
    draw(tr.before, before_color(), 1.3f);
    draw(tr.after, after_color(), 1.3f);
    plot.end();
}

// The record as loaded, whole (before a fit: what the file holds, so a bad unit or column shows at once).
void DataPanel::draw_record(ImVec2 size) {
    if (size.y < 4.0f * ImGui::GetFontSize()) return;
    Plot plot;
    const Axes ax = x_of_t_axes();
    if (!plot.begin("##record", size, record_t_, record_x_, ax)) return;
    const identify::MeasuredData& d = *data_;
    plot.series(d.size(), [&](std::size_t i) { return XY{d.t[i], d.x[i]}; }, measured_color(), 1.3f);
    plot.end();
}

// The Poincare points of the record (x at phi = 2 pi i, against the omega there), measured and simulated
// over the whole record by both models: where the model reproduces the data's attractors.
void DataPanel::draw_sections(ImVec2 size) {
    const identify::FitReport& r = *report_;
    if (r.diagram_measured.empty()) {
        ImGui::TextDisabled("no Poincare points (the record is forced by an input u, not by phi)");
        return;
    }
    Plot plot;
    Axes ax;
    ax.x_label = "ω [rad/s]";
    ax.y_label = "x at φ = 2πi [mm]";
    ax.y_scale = 1e3;
    if (!plot.begin("##sections", size, sec_w_, sec_x_, ax)) return;
    auto draw = [&](const std::vector<std::pair<double, double>>& pts, ImU32 col, float sz) {
        plot.scatter(pts.size(), [&](std::size_t i) { return XY{pts[i].first, pts[i].second}; }, col, sz);
    };
    draw(r.diagram_before, before_color(), 3.0f);
    draw(r.diagram_after, after_color(), 3.0f);
    draw(r.diagram_measured, measured_color(), 2.0f);
    plot.end();
}

void DataPanel::draw_residual(const char* id, const char* xlabel, const std::vector<double>& var, double scale,
                              Range xr, ImVec2 size) {
    const auto& rc = report_->residual;
    Plot plot;
    Axes ax;
    ax.x_label = xlabel;
    ax.y_label = "r [N]";
    ax.x_scale = scale;
    if (!plot.begin(id, size, xr, res_y_, ax)) return;
    plot.hline(0.0, palette().grid, 1.0f);
    const std::size_t n = std::min({var.size(), rc.before.size(), rc.after.size()});
    plot.scatter(n, [&](std::size_t i) { return XY{var[i], rc.before[i]}; }, before_color(), 2.0f);
    plot.scatter(n, [&](std::size_t i) { return XY{var[i], rc.after[i]}; }, after_color(), 2.0f);
    plot.end();
}

void DataPanel::draw(bool* open, const DataPanelContext& ctx) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.52f), ImGuiCond_FirstUseEver,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x * 0.92f, vp->Size.y * 0.86f), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Measured data", open, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    draw_file_row();
    draw_fit_row(ctx);
    ImGui::Separator();
    if (!report_) {
#ifdef __EMSCRIPTEN__
        ImGui::TextDisabled(data_ ? "The record's x(t)." : "Load a measured run: a CSV with t, x and phi (or an input u).");
#else
        ImGui::TextDisabled(data_ ? "The record's x(t). Run the fit to see the residual, the effects found and the error before and after."
                                  : "Load a measured run: a CSV (plain or gzip) with t, x and phi (or an input u).");
#endif
        if (data_) draw_record(ImGui::GetContentRegionAvail());
        ImGui::End();
        return;
    }
    const float fs = ImGui::GetFontSize();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float left_w = std::round(std::clamp(avail.x * 0.36f, fs * 18.0f, fs * 30.0f));
    if (ImGui::BeginChild("##left", ImVec2(left_w, avail.y), false)) {
        draw_effects();
        draw_errors();
        ImGui::TextDisabled("Poincare points: measured (blue) and simulated");
        const ImVec2 la = ImGui::GetContentRegionAvail();
        if (la.y > 6.0f * fs) draw_sections(ImVec2(la.x, la.y));
    }
    ImGui::EndChild();
    ImGui::SameLine();
    if (ImGui::BeginChild("##right", ImVec2(0, avail.y), false, ImGuiWindowFlags_NoScrollbar)) {
        const ImVec2 ra = ImGui::GetContentRegionAvail();
        legend_item(measured_color(), "measured");
        ImGui::SameLine(0, fs);
        legend_item(before_color(), "baseline");
        ImGui::SameLine(0, fs);
        legend_item(after_color(), "with the effects found");
        ImGui::SameLine(0, fs);
        ImGui::TextDisabled("x(t) in the worst 10-period window; dashed: x_I");
        const float line = ImGui::GetFrameHeightWithSpacing();
        const float h_trace = std::round((ra.y - 2.0f * line) * 0.5f);
        draw_trace(ImVec2(ra.x, h_trace));
        ImGui::TextDisabled("residual r = m x'' + F_R + F_SA + F_I - forcing on free-flight samples, against x, v, phi");
        const ImVec2 rest = ImGui::GetContentRegionAvail();
        const bool phi = data_ ? data_->has_phi() : true;
        const int n = phi ? 3 : 2;
        const float sp = ImGui::GetStyle().ItemSpacing.x;
        const float w = std::floor((rest.x - sp * static_cast<float>(n - 1)) / static_cast<float>(n));
        const ImVec2 sz(w, rest.y);
        const auto& rc = report_->residual;
        draw_residual("##rx", "x [mm]", rc.x, 1e3, res_x_, sz);
        ImGui::SameLine();
        draw_residual("##rv", "v [m/s]", rc.v, 1.0, res_v_, sz);
        if (phi) {
            ImGui::SameLine();
            draw_residual("##rphi", "phi mod 2 pi [rad]", rc.phi, 1.0, {0.0, 2.0 * std::numbers::pi}, sz);
        }
    }
    ImGui::EndChild();
    ImGui::End();
}

}  // namespace impactlab::gui
