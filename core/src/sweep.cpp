#include "impactlab/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <ostream>
#include <numbers>

namespace impactlab {

namespace {

// Collects section points with n in [first, last] and watches for cancellation.
class SectionCollector : public Observer {
public:
    SectionCollector(std::int64_t first, Progress* progress, Observer* extra = nullptr)
        : first_(first), progress_(progress), extra_(extra) {}
    void on_section(const SectionPoint& sp) override {
        if (sp.n >= first_) points.push_back(sp);
        if (on_section_progress) on_section_progress(sp);
        if (extra_) extra_->on_section(sp);
    }
    void on_piece(const Piece& piece) override {
        if (extra_) extra_->on_piece(piece);
    }
    void on_impact(const ImpactEvent& ev) override {
        if (extra_) extra_->on_impact(ev);
    }
    void on_regime(double t, Regime from, Regime to) override {
        if (extra_) extra_->on_regime(t, from, to);
    }
    bool stop() const override { return progress_ && progress_->cancel.load(std::memory_order_relaxed); }
    std::vector<SectionPoint> points;
    std::function<void(const SectionPoint&)> on_section_progress;

private:
    std::int64_t first_;
    Progress* progress_;
    Observer* extra_;
};

bool cancelled(const Progress* p) { return p && p->cancel.load(std::memory_order_relaxed); }
}  // namespace

std::vector<SectionPoint> poincare_section(const Params& p, double omega, int periods, int transient, State& s,
                                           const Tolerances& tol, Progress* progress, double phi0) {
    Simulator sim(tol);
    sim.set_section_phase(phi0);
    const Drive drive(omega, s.t, 0.0);
    Simulator::make_consistent(p, drive, s);
    SectionCollector col(transient + 1, progress);
    if (progress)
        col.on_section_progress = [&](const SectionPoint& sp) {
            progress->fraction.store(static_cast<double>(sp.n) / (periods + transient), std::memory_order_relaxed);
        };
    sim.advance(p, drive, s, drive.time_of_phase(sim.section_phi(periods + transient)), &col);
    return std::move(col.points);
}

Diagram run_cf_sweep(const Params& p, const CfSpec& spec, Progress* progress, const Tolerances& tol, LevelObserver* extra) {
    std::vector<CfLevel> levels(static_cast<std::size_t>(spec.steps));
    for (int j = 0; j < spec.steps; ++j) {
        const double w = spec.steps == 1 ? spec.omega_min
                                         : spec.omega_min + (spec.omega_max - spec.omega_min) * j / (spec.steps - 1);
        levels[static_cast<std::size_t>(j)] = {w, p.xI, p.m0e};
    }
    if (spec.direction == SweepDirection::Down) std::reverse(levels.begin(), levels.end());
    Diagram diag = run_cf_levels(p, levels, spec.transient, spec.record, progress, tol, extra);
    diag.protocol = spec.direction == SweepDirection::Up ? "cf-up" : "cf-down";
    return diag;
}

Diagram run_cf_levels(const Params& p0, const std::vector<CfLevel>& levels, int transient, int record, Progress* progress,
                      const Tolerances& tol, LevelObserver* extra) {
    Diagram diag;
    diag.model = p0.name;
    diag.protocol = "cf";
    // Progress counted in levels: the work per level is roughly constant (steps go with periods).
    const double total = static_cast<double>(levels.size());
    double done = 0;
    diag.points.reserve(levels.size() * static_cast<std::size_t>(record));

    Params p = p0;
    Simulator sim(tol);
    State s;   // at rest at x = 0
    const int n_total = transient + record;
    bool first = true;
    for (std::size_t j = 0; j < levels.size(); ++j) {
        if (cancelled(progress)) {
            diag.cancelled = true;
            break;
        }
        const CfLevel& lv = levels[j];
        const Drive drive(lv.omega, s.t, 0.0);   // each level starts at a section instant: phi = 0 mod 2 pi
        p.m0e = lv.m0e;
        if (first) {
            p.xI = lv.xI;
            Simulator::make_consistent(p, drive, s);
        } else {
            if (lv.xI != p.xI) Simulator::move_bumper(p, drive, s, lv.xI);
            Simulator::sync_sections(drive, s);
        }
        first = false;
        if (extra) extra->begin_level(j, lv);
        SectionCollector col(transient + 1, progress, extra);
        if (progress)
            col.on_section_progress = [&](const SectionPoint& sp) {
                progress->fraction.store((done + static_cast<double>(sp.n) / n_total) / total, std::memory_order_relaxed);
            };
        sim.advance(p, drive, s, drive.time_of_phase(kTwoPi * n_total), &col);
        if (cancelled(progress)) {
            diag.cancelled = true;
            break;
        }
        for (const auto& sp : col.points) diag.points.push_back({lv.omega, sp.x, sp.v});
        if (extra) extra->end_level(j, p, s);
        done += 1.0;
    }
    diag.simulated_seconds = s.t;
    diag.steps = s.steps;
    diag.impacts = s.impacts;
    if (progress && !diag.cancelled) progress->fraction.store(1.0);
    return diag;
}

Diagram run_ef_ramp(const Params& p, const EfSpec& spec, Progress* progress, const Tolerances& tol, Observer* extra) {
    Diagram diag;
    diag.model = p.name;
    diag.protocol = "ef";
    const Drive drive = Drive::ef_ramp(spec.omega_max, spec.t_ramp);
    Simulator sim(tol);
    State s;
    Simulator::make_consistent(p, drive, s);
    SectionCollector col(1, progress, extra);
    col.on_section_progress = [&](const SectionPoint& sp) {
        progress->fraction.store(sp.t / spec.t_ramp, std::memory_order_relaxed);
    };
    if (!progress) col.on_section_progress = nullptr;
    sim.advance(p, drive, s, spec.t_ramp, &col);
    diag.cancelled = cancelled(progress);
    for (const auto& sp : col.points) diag.points.push_back({drive.omega(sp.t), sp.x, sp.v});
    diag.simulated_seconds = s.t;
    diag.steps = s.steps;
    diag.impacts = s.impacts;
    if (progress && !diag.cancelled) progress->fraction.store(1.0);
    return diag;
}

int count_period(const std::vector<double>& xs, double tol, int max_period) {
    if (xs.empty()) return 0;
    std::vector<double> v(xs);
    std::sort(v.begin(), v.end());
    int clusters = 1;
    for (std::size_t i = 1; i < v.size(); ++i)
        if (v[i] - v[i - 1] > tol) ++clusters;
    return std::min(clusters, max_period + 1);
}

Transitions find_transitions(const Diagram& d, double cluster_tol) {
    Transitions tr;
    // Group the points by omega (consecutive equal omegas form one level).
    std::vector<double> means;
    for (std::size_t i = 0; i < d.points.size();) {
        std::size_t j = i;
        std::vector<double> xs;
        double sum = 0;
        while (j < d.points.size() && d.points[j].omega == d.points[i].omega) {
            xs.push_back(d.points[j].x);
            sum += std::abs(d.points[j].x);
            ++j;
        }
        tr.omegas.push_back(d.points[i].omega);
        tr.periods.push_back(count_period(xs, cluster_tol));
        means.push_back(sum / static_cast<double>(xs.size()));
        i = j;
    }
    const std::size_t n = tr.omegas.size();
    auto chaotic = [&](std::size_t k) { return tr.periods[k] > 8; };
    // The jump off the hilltop exists only if the sweep starts there (CF up does; CF down starts in a well).
    std::size_t k = 0;
    while (k < n && means[k] <= 5e-3) ++k;
    if (k == n) return tr;
    if (k > 0) tr.jump = tr.omegas[k];
    for (std::size_t i = k; i < n; ++i)
        if (tr.periods[i] == 2) {
            tr.period_doubling = tr.omegas[i];
            break;
        }
    // Chaos: runs of at least five consecutive levels (0.4 rad/s in the paper's sweep) with more than 8
    // distinct section values; shorter runs are slow transients at a bifurcation point, where 20 transient
    // periods are not enough to settle.
    std::size_t first = n, last = n;
    for (std::size_t i = k; i < n;) {
        std::size_t j = i;
        while (j < n && chaotic(j)) ++j;
        if (j - i >= 5) {
            if (first == n) first = i;
            last = j - 1;
        }
        i = (j == i) ? i + 1 : j;
    }
    if (first == n) return tr;
    tr.chaos_start = tr.omegas[first];
    tr.chaos_end = tr.omegas[last];
    for (std::size_t i = last + 1; i < n; ++i)
        if (tr.periods[i] == 1) {
            tr.period1_return = tr.omegas[i];
            break;
        }
    for (std::size_t i = first; i <= last;) {
        if (tr.periods[i] <= 4) {
            std::size_t j = i;
            while (j <= last && tr.periods[j] <= 4) ++j;
            if (j - i >= 4) tr.windows.push_back({tr.omegas[i], tr.omegas[j - 1]});
            i = j;
        } else {
            ++i;
        }
    }
    return tr;
}

void write_diagram_csv(const Diagram& d, std::ostream& out) {
    const auto old = out.precision(10);
    out << "omega,x,v\n";
    for (const auto& pt : d.points) out << pt.omega << ',' << pt.x << ',' << pt.v << '\n';
    out.precision(old);
}

}  // namespace impactlab
