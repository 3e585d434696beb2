#include "analysis_jobs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace impactlab::gui {

namespace {

// The result as the diagram overlays it.
ContinuationOverlay overlay_of(const Params& p, const analysis::ContinuationSpec& spec, const analysis::ContinuationResult& r,
                               std::chrono::steady_clock::time_point t0) {
    ContinuationOverlay out;
    out.model = p.name;
    out.xI = p.xI;
    out.omega_lo = spec.lo;
    out.omega_hi = spec.hi;
    out.points = r.points;
    out.cancelled = r.cancelled;
    out.curves = analysis::branch_curves(r);
    if (!r.branches.empty()) out.end = r.branches.front().end;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace

ContinuationOverlay compute_continuation(const Params& p, double omega_lo, double omega_hi, Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    analysis::ContinuationSpec spec;
    spec.param = analysis::ContParam::Omega;
    // Near omega = 0 the forcing vanishes and the arclength steps crawl: the branch starts at 0.5 rad/s,
    // where the diagram's first columns already show the resting period 1.
    spec.lo = std::max(omega_lo, 0.5);
    spec.hi = std::max(omega_hi, spec.lo + 0.5);
    spec.start = spec.lo;
    spec.period = 1;
    spec.max_period = 8;
    const analysis::ContinuationResult r = analysis::continue_orbits(p, spec, &progress);
    return overlay_of(p, spec, r, t0);
}

ContinuationOverlay compute_continuation_from(const Params& p, double omega_lo, double omega_hi, double omega, double x,
                                              double v, int period, Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    analysis::ContinuationSpec spec;
    spec.param = analysis::ContParam::Omega;
    spec.lo = std::max(omega_lo, 0.5);
    spec.hi = std::max(omega_hi, spec.lo + 0.5);
    spec.start = std::clamp(omega, spec.lo, spec.hi);
    spec.guess = Vec2(x, v);
    spec.period = period;
    spec.max_period = std::max(8, 4 * period);   // its doublings, as from the left well
    const analysis::ContinuationResult r = analysis::continue_orbits(p, spec, &progress);
    ContinuationOverlay out = overlay_of(p, spec, r, t0);
    out.from_orbit = true;
    out.start_omega = spec.start;
    out.start_x = x;
    out.start_v = v;
    out.start_period = period;
    return out;
}

PlaneData compute_plane(const Params& p, const std::string& model, const PlaneRequest& req, Progress& progress) {
    ScanSpec spec;
    spec.x = {ScanParam::Omega, req.omega_lo, req.omega_hi, req.nx};
    spec.y = {ScanParam::XI, req.xI_lo, req.xI_hi, req.ny};
    spec.measures.period = true;
    spec.measures.impacts = true;
    spec.start = ScanStart::Continue;
    std::vector<int> todo(static_cast<std::size_t>(req.ny));
    for (int j = 0; j < req.ny; ++j) todo[static_cast<std::size_t>(j)] = j;
    std::vector<std::vector<ScanPoint>> rows(static_cast<std::size_t>(req.ny));
    // on_row is serialised by scan_rows, so the rows need no lock of their own.
    scan_rows(p, spec, todo, worker_threads(req.threads), &progress, Tolerances{},
              [&rows](int row, const std::vector<ScanPoint>& pts) { rows[static_cast<std::size_t>(row)] = pts; });
    std::string source = "computed: " + model;
    if (progress.cancel.load(std::memory_order_relaxed)) source += " (cancelled, partial)";
    return plane_from_scan(spec, rows, source);
}

analysis::BasinSpec basin_request(const Params& p, double omega, int grid, int threads) {
    analysis::BasinSpec spec;
    spec.omega = omega;
    spec.nx = spec.nv = grid;
    analysis::set_default_window(p, spec);
    spec.threads = worker_threads(threads);
    return spec;
}

}  // namespace impactlab::gui
