// The two-parameter curves over the plane view: a period doubling, a grazing and a fold, each followed
// along the plane's second axis on its own worker by the core (analysis::curve_over_plane and
// curve_over_plane_from, the functions `impactlab scan --doubling-from/--grazing-from/--fold-from` call),
// from the first one over the plane's omega range, from a known point, or from a cell the user picked.
// GL-free; UI thread.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "analysis/analysis_jobs.hpp"
#include "impactlab/plane_doubling.hpp"
#include "analysis/plane_data.hpp"

namespace impactlab::gui {

// The curves the view draws, in the order of their styles: solid, dashed, dotted (as scan's PNG).
inline constexpr analysis::BifKind kPlaneCurveKinds[] = {analysis::BifKind::PeriodDoubling, analysis::BifKind::Grazing,
                                                         analysis::BifKind::Fold};
inline constexpr int kPlaneCurves = 3;
int plane_curve_index(analysis::BifKind kind);   // 0, 1, 2 (-1 for a kind the view does not draw)
const char* plane_curve_word(analysis::BifKind kind);    // "doubling", "grazing", "fold"
const char* plane_curve_label(analysis::BifKind kind);   // the PNG's legend: "grazing, continued (dashed)"

// Where a curve starts.
struct CurveStart {
    enum class From { Auto, Point, Picked } from = From::Auto;
    double omega = 0;            // Point: the known point's omega [rad/s]; Picked: look from here up
    double x = 0, v = 0;         // Point: its section point [m, m/s]
    int period = 1;              // Point: its orbit's period
    double q = 0;                // Picked: the second parameter there [m] or [kg m]
};
// "auto" or OMEGA,X,V[,K] (as `impactlab continue` prints a point); none when it is neither.
std::optional<CurveStart> parse_curve_start(const std::string& text);
std::string curve_start_text(const CurveStart& s);   // "auto", "9.6005,-0.0156163,-0.00744857,1", "picked at ..."

struct PlaneCurveShown {
    analysis::PlaneCurve result;
    std::string model, second;   // "A1G", "xI" or "m0e"
    CurveStart start;
};

class PlaneCurves {
public:
    // Starts the curve of `kind` over `plane` for the model p ("" when started, else why not: the axes are
    // not omega and xI or m0e, a grazing without a bumper).
    std::string start(analysis::BifKind kind, const PlaneData& plane, const Params& p, const std::string& model,
                      const CurveStart& from);
    // Every frame: takes the finished curves; a toast for the newest ("" when none finished). A job that
    // failed sets `failed` ("grazing curve: why").
    std::string poll(std::string& failed);
    bool running(int i) const { return jobs_[static_cast<std::size_t>(i)].running(); }
    bool any_running() const;
    double progress(int i) const { return jobs_[static_cast<std::size_t>(i)].progress(); }
    void cancel(int i) { jobs_[static_cast<std::size_t>(i)].cancel(); }
    const std::optional<PlaneCurveShown>& shown(int i) const { return shown_[static_cast<std::size_t>(i)]; }
    void clear();   // forgets the curves shown (a running job still hands its curve over)

private:
    std::array<Job<analysis::PlaneCurve>, kPlaneCurves> jobs_;
    std::array<std::optional<PlaneCurveShown>, kPlaneCurves> shown_;
    std::array<PlaneCurveShown, kPlaneCurves> asked_;   // of the jobs running: model, axis, start
};

}  // namespace impactlab::gui
