#include "plane_curves.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace impactlab::gui {

int plane_curve_index(analysis::BifKind kind) {
    for (int i = 0; i < kPlaneCurves; ++i)
        if (kPlaneCurveKinds[i] == kind) return i;
    return -1;
}

const char* plane_curve_word(analysis::BifKind kind) {
    switch (kind) {
    case analysis::BifKind::Grazing: return "grazing";
    case analysis::BifKind::Fold: return "fold";
    default: return "doubling";
    }
}

const char* plane_curve_label(analysis::BifKind kind) {
    switch (kind) {
    case analysis::BifKind::Grazing: return "grazing, continued (dashed)";
    case analysis::BifKind::Fold: return "fold, continued (dotted)";
    default: return "period doubling, continued";
    }
}

std::optional<CurveStart> parse_curve_start(const std::string& text) {
    CurveStart s;
    if (text == "auto") return s;
    double w[4] = {0, 0, 0, 1};
    char tail = 0;
    const int n = std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &w[0], &w[1], &w[2], &w[3], &tail);
    // Within the model's physical range, as impactlab scan checks it: omega >= 0.05 rad/s, the point on the rail
    // at a speed the rig can have (a start at omega = 1e-300 kept the curve's Newton busy for ever).
    if ((n != 3 && n != 4) || !(w[0] >= 0.05 && w[0] <= 1000.0) || !(std::fabs(w[1]) <= 0.1) || !(std::fabs(w[2]) <= 10.0) ||
        !(w[3] >= 1 && w[3] <= 64) || w[3] != std::floor(w[3]))
        return std::nullopt;
    s.from = CurveStart::From::Point;
    s.omega = w[0];
    s.x = w[1];
    s.v = w[2];
    s.period = static_cast<int>(w[3]);
    return s;
}

std::string curve_start_text(const CurveStart& s) {
    char buf[128];
    switch (s.from) {
    case CurveStart::From::Auto: return "auto";
    case CurveStart::From::Point: std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%d", s.omega, s.x, s.v, s.period); break;
    case CurveStart::From::Picked: std::snprintf(buf, sizeof buf, "picked at omega = %.6g rad/s, %.6g", s.omega, s.q); break;
    }
    return buf;
}

std::string PlaneCurves::start(analysis::BifKind kind, const PlaneData& pl, const Params& p, const std::string& model,
                               const CurveStart& from) {
    const int i = plane_curve_index(kind);
    const std::string word = plane_curve_word(kind);
    if (i < 0) return "no curve of that kind over the plane";
    if (pl.x_name != "omega" || (pl.y_name != "xI" && pl.y_name != "m0e") || pl.nx() < 2 || pl.ny() < 2)
        return word + " curve: the plane's axes must be omega and xI or m0e";
    if (kind == analysis::BifKind::Grazing && !p.has_bumper()) return "grazing curve: " + model + " has no bumper";
    analysis::PlaneCurveSpec spec;
    spec.second = pl.y_name == "xI" ? analysis::ContParam::XI : analysis::ContParam::M0e;
    spec.kind = kind;
    spec.omega_lo = pl.xs.front();
    spec.omega_hi = pl.xs.back();
    spec.lo = pl.ys.front();
    spec.hi = pl.ys.back();
    spec.step = 0.5 * (spec.hi - spec.lo) / (pl.ny() - 1);   // half the grid step, as impactlab scan
    Params q = p;
    if (from.from == CurveStart::From::Picked) {   // the first one above the picked omega, at the picked row
        (spec.second == analysis::ContParam::XI ? q.xI : q.m0e) = from.q;
        spec.omega_lo = from.omega;
        if (!(spec.omega_hi > spec.omega_lo + 1e-9)) return word + " curve: the picked omega is the plane's last";
    }
    const std::size_t k = static_cast<std::size_t>(i);
    asked_[k] = PlaneCurveShown{{}, model, pl.y_name, from};
    if (from.from == CurveStart::From::Point) {
        const Vec2 y0(from.x, from.v);
        const int period = from.period;
        const double w = from.omega;
        jobs_[k].start([q, spec, w, y0, period](Progress& prog) { return analysis::curve_over_plane_from(q, spec, w, y0, period, &prog); });
    } else {
        jobs_[k].start([q, spec](Progress& prog) { return analysis::curve_over_plane(q, spec, &prog); });
    }
    return "";
}

std::string PlaneCurves::poll(std::string& failed) {
    std::string toast;
    for (int i = 0; i < kPlaneCurves; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        const char* word = plane_curve_word(kPlaneCurveKinds[i]);
        if (std::string err = jobs_[k].take_error(); !err.empty()) failed = std::string(word) + " curve: " + err;
        auto r = jobs_[k].take_result();
        if (!r) continue;
        char buf[256];
        const char* cancelled = r->cancelled ? " (cancelled: partial)" : "";
        if (r->found)
            std::snprintf(buf, sizeof buf, "%s curve %s: from omega = %.7f, %zu points in %.1f s%s", word, asked_[k].model.c_str(),
                          r->omega0, r->curve.points.size(), r->seconds, cancelled);
        else std::snprintf(buf, sizeof buf, "%s curve %s: %s%s", word, asked_[k].model.c_str(), r->note.c_str(), cancelled);
        toast = buf;
        shown_[k] = asked_[k];
        shown_[k]->result = std::move(*r);
    }
    return toast;
}

bool PlaneCurves::any_running() const {
    for (const auto& j : jobs_)
        if (j.running()) return true;
    return false;
}

void PlaneCurves::clear() {
    for (auto& s : shown_) s.reset();
}

}  // namespace impactlab::gui
