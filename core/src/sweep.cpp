#include "impactlab/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <ostream>
#include <numbers>
#include <sstream>
#include <string>

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

bool simulate_sampled(const Params& p, const Drive& d, State& s, double duration, double dt, const Tolerances& tol,
                      Progress* progress, const std::function<void(const Sample&)>& sink) {
    // The sampler stops the simulator at a cancel; the slices keep the progress moving on long runs.
    struct Sampler : UniformSampler {
        Sampler(const Drive& dr, double step, std::function<void(const Sample&)> f, const Progress* pr)
            : UniformSampler(dr, step, 0.0, std::move(f)), progress(pr) {}
        bool stop() const override { return cancelled(progress); }
        const Progress* progress;
    };
    Simulator sim(tol);
    Simulator::make_consistent(p, d, s);
    Sampler sampler(d, dt, sink, progress);
    const int slices = 200;
    for (int i = 1; i <= slices; ++i) {
        sim.advance(p, d, s, duration * i / slices, &sampler);
        if (cancelled(progress)) return false;
        if (progress) progress->fraction.store(static_cast<double>(i) / slices, std::memory_order_relaxed);
    }
    return true;
}

const char* sweep_param_name(SweepParam s) {
    switch (s) {
        case SweepParam::Omega: return "omega";
        case SweepParam::XI: return "xI";
        case SweepParam::M0e: return "m0e";
    }
    return "?";
}

const char* sweep_param_unit(SweepParam s) {
    switch (s) {
        case SweepParam::Omega: return "rad/s";
        case SweepParam::XI: return "m";
        case SweepParam::M0e: return "kg m";
    }
    return "?";
}

SweepParamAxis sweep_param_axis(SweepParam s) {
    return s == SweepParam::XI ? SweepParamAxis{"mm", 1e3} : SweepParamAxis{sweep_param_unit(s), 1.0};
}

std::optional<SweepParam> parse_sweep_param(const std::string& name) {
    for (const SweepParam s : {SweepParam::Omega, SweepParam::XI, SweepParam::M0e})
        if (name == sweep_param_name(s)) return s;
    return std::nullopt;
}

double level_value(const CfLevel& lv, SweepParam s) {
    return s == SweepParam::Omega ? lv.omega : s == SweepParam::XI ? lv.xI : lv.m0e;
}

double& level_value(CfLevel& lv, SweepParam s) {
    return s == SweepParam::Omega ? lv.omega : s == SweepParam::XI ? lv.xI : lv.m0e;
}

std::vector<CfLevel> sweep_levels(const Params& p, const ParamSweep& s) {
    std::vector<CfLevel> levels(static_cast<std::size_t>(std::max(s.steps, 0)));
    for (int j = 0; j < s.steps; ++j) {
        const double u = s.steps == 1 ? s.lo : s.lo + (s.hi - s.lo) * j / (s.steps - 1);
        CfLevel& lv = levels[static_cast<std::size_t>(j)];
        lv = {s.omega, p.xI, p.m0e};
        level_value(lv, s.over) = u;
    }
    if (s.direction == SweepDirection::Down) std::reverse(levels.begin(), levels.end());
    return levels;
}

std::string check_sweep(const Params& p, const ParamSweep& s) {
    const auto num = [](double v) {
        std::ostringstream o;
        o << v;
        return o.str();
    };
    const std::string name = sweep_param_name(s.over), unit = sweep_param_unit(s.over);
    if (!std::isfinite(s.lo) || !std::isfinite(s.hi)) return name + " range: not a finite number";
    if (s.steps < 1) return "steps: " + std::to_string(s.steps) + " is below 1";
    // omega > 0 (a period is infinite at 0) up to the CLI's omega flags' 1000 rad/s.
    constexpr double kOmegaHi = 1000.0;
    double lo_ok = 0, hi_ok = kOmegaHi;
    bool lo_open = true;
    if (s.over == SweepParam::XI) {
        if (!p.has_bumper()) return "xI: model " + p.name + " has no bumper to move (impact law 'none')";
        lo_ok = -kRailHalfTravel;
        hi_ok = kRailHalfTravel;
        lo_open = false;
    } else if (s.over == SweepParam::M0e) {
        for (const ParamRange& r : param_ranges())
            if (std::string(r.key) == "m0e") hi_ok = r.hi;
    }
    const std::string range = (lo_open ? "(" : "[") + num(lo_ok) + ", " + num(hi_ok) + "] " + unit;
    if (s.lo < lo_ok || (lo_open && s.lo <= lo_ok) || s.hi > hi_ok)
        return name + " range " + num(s.lo) + ".." + num(s.hi) + " " + unit + " is outside " + range;
    if (s.hi < s.lo) return name + " range: the end " + num(s.hi) + " is below the start " + num(s.lo) + " " + unit;
    if (s.over != SweepParam::Omega && !(s.omega > 0 && s.omega <= kOmegaHi))
        return "omega " + num(s.omega) + " rad/s (fixed during the " + name + " sweep) is outside (0, " + num(kOmegaHi) +
               "] rad/s";
    return "";
}

Diagram run_cf_param_sweep(const Params& p, const ParamSweep& s, int transient, int record, Progress* progress,
                           const Tolerances& tol, LevelObserver* extra, int settle_budget) {
    Diagram diag = run_cf_levels(p, sweep_levels(p, s), transient, record, progress, tol, extra, s.over, settle_budget);
    diag.protocol = s.direction == SweepDirection::Up ? "cf-up" : "cf-down";
    if (s.over != SweepParam::Omega) diag.omega = s.omega;
    return diag;
}

Diagram run_cf_sweep(const Params& p, const CfSpec& spec, Progress* progress, const Tolerances& tol, LevelObserver* extra) {
    const ParamSweep s{SweepParam::Omega, spec.omega_min, spec.omega_max, spec.steps, spec.direction, 0.0};
    return run_cf_param_sweep(p, s, spec.transient, spec.record, progress, tol, extra);
}

namespace {

constexpr double kSettleTol = 1e-5;   // [m] as the CF sweep counts its section values

// How far xs is from recurring with any period up to max_period: the least, over k, of the largest
// |x_i - x_(i-k)| [m].
double recurrence_gap(const std::vector<double>& xs, int max_period) {
    double best = INFINITY;
    for (std::size_t k = 1; k <= static_cast<std::size_t>(max_period) && k < xs.size(); ++k) {
        double worst = 0;
        for (std::size_t i = k; i < xs.size(); ++i) worst = std::max(worst, std::abs(xs[i] - xs[i - k]));
        best = std::min(best, worst);
    }
    return best;
}

bool record_settled(const std::vector<double>& xs, int k) {
    const auto n = xs.size();
    const auto d = static_cast<std::size_t>(k);
    if (n < 2 * d + 2) return true;   // too short a record to tell (a scan's --record 1)
    for (std::size_t i = d; i < n; ++i)
        if (std::abs(xs[i] - xs[i - d]) > kSettleTol) return false;
    // The step to the next section, over the first and the last cycle: an alternation dying out shrinks.
    const auto step = [&](std::size_t from) {
        double g = 0;
        for (std::size_t i = from; i < from + d; ++i) g = std::max(g, std::abs(xs[i + 1] - xs[i]));
        return g;
    };
    return k == 1 || step(0) - step(n - 1 - d) <= kSettleTol;
}

}  // namespace

int settle_level(const Params& p, double omega, State s, std::vector<SectionPoint>& record, int max_period, int budget,
                 const Tolerances& tol, bool chaos_verdict) {
    const int len = static_cast<int>(record.size());
    if (len == 0) return kLevelNotSettled;
    std::vector<double> xs;
    double gap_before = INFINITY;
    for (int more = 0;; ++more) {
        xs.clear();
        for (const SectionPoint& sp : record) xs.push_back(sp.x);
        const int distinct = count_period(xs, kSettleTol, max_period);
        if (distinct <= max_period && record_settled(xs, distinct)) return distinct;
        // More than max_period values: chaos, unless the next record comes twice as close to recurring (a slow
        // transient: A1C at 11 rad/s after a CF step of 0.25 rad/s, lambda < 0, period 2 in the end).
        const double gap = recurrence_gap(xs, max_period);
        if (chaos_verdict && distinct > max_period && more > 0 && !(gap < 0.5 * gap_before)) return 0;
        if (more == budget) return kLevelNotSettled;
        gap_before = gap;
        record = poincare_section(p, omega, len, 0, s, tol);
    }
}

Diagram run_cf_levels(const Params& p0, const std::vector<CfLevel>& levels, int transient, int record, Progress* progress,
                      const Tolerances& tol, LevelObserver* extra, SweepParam over, int settle_budget) {
    Diagram diag;
    diag.model = p0.name;
    diag.protocol = "cf";
    diag.over = over;
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
        const double at = level_value(lv, over);
        DiagramLevel dl{at, 0, diag.points.size(), 0};
        if (settle_budget > 0)
            dl.period = settle_level(p, lv.omega, s, col.points, kDiagramMaxPeriod, settle_budget, tol, false);
        dl.count = col.points.size();
        if (settle_budget > 0) diag.levels.push_back(dl);
        for (const auto& sp : col.points) diag.points.push_back({at, sp.x, sp.v});
        if (extra) {
            extra->kept(j, dl, diag.points.data() + dl.first);
            extra->end_level(j, p, s);
        }
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
    if (d.levels.empty()) {
        out << sweep_param_name(d.over) << ",x,v\n";
        for (const auto& pt : d.points) out << pt.omega << ',' << pt.x << ',' << pt.v << '\n';
    } else {
        // The level's verdict on every row: its period, 0 for chaos, -1 for not settled.
        out << sweep_param_name(d.over) << ",x,v,period\n";
        for (const DiagramLevel& lv : d.levels)
            for (std::size_t i = lv.first; i < lv.first + lv.count; ++i)
                out << d.points[i].omega << ',' << d.points[i].x << ',' << d.points[i].v << ',' << lv.period << '\n';
    }
    out.precision(old);
}

}  // namespace impactlab
