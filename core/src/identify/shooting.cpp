// The simulation error: multiple shooting over windows of 1 and 10 forcing periods, free runs, and the
// distance between measured and simulated bifurcation diagrams. Every run is the core Simulator's, driven by
// the omega(t) fitted to phi or by the record's input u(t), one per run (Prep::drives).
#include <algorithm>
#include <cmath>
#include <map>

#include "identify/internal.hpp"
#include "parallel.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::identify::detail {

namespace {

// Samples i0..i1 of the model on the core simulator (the drive carries phi(t) or the input u(t)); true
// coordinates out.
class Collect : public Observer {
public:
    Collect(const Drive& d, double dt, double t0, std::vector<double>& out, std::size_t count)
        : sampler_(d, dt, t0, [this](const Sample& s) {
              if (k_ < out_.size()) out_[k_++] = s.x;
          }),
          out_(out) {
        out_.assign(count, kNaN);
    }
    void on_piece(const Piece& p) override { sampler_.on_piece(p); }
    std::size_t filled() const { return k_; }

private:
    UniformSampler sampler_;
    std::vector<double>& out_;
    std::size_t k_ = 0;
};

void run(const Prep& pr, const Model& m, std::size_t i0, std::size_t i1, double x, double v, double rtol,
         std::vector<double>& out) {
    const MeasuredData& d = *pr.data;
    Simulator sim(fit_tolerances(pr, m, rtol));
    State s;
    s.t = d.t[i0];
    s.x = x;
    s.v = v;
    const Drive& drive = pr.drive_of(i0);
    Simulator::make_consistent(m.p, drive, s);
    Collect c(drive, pr.dt, d.t[i0], out, i1 - i0 + 1);
    try {
        sim.advance(m.p, drive, s, d.t[i1] + 0.5 * pr.dt, &c);
    } catch (const SimulationStalled&) {
        return;   // a trial model the integrator cannot run: NaN from the stall on, an infinite error
    }
    // Samples the sampler could not reach (rounding at the end) repeat the last state.
    for (std::size_t k = c.filled(); k < out.size(); ++k) out[k] = k ? out[k - 1] : s.x;
}

double sse(const Prep& pr, const Model& m, std::size_t i0, const std::vector<double>& sim, std::vector<double>* e) {
    const double g = m.sensor_gain(), o = m.sensor_offset();
    const bool curved = m.sensor_curved();
    double s = 0;
    if (e) e->resize(sim.size());
    for (std::size_t k = 0; k < sim.size(); ++k) {
        const double r = (curved ? m.measure(sim[k]) : g * sim[k] + o) - pr.data->x[i0 + k];
        s += r * r;
        if (e) (*e)[k] = r;
    }
    return std::isfinite(s) ? s : INFINITY;
}

}  // namespace

Tolerances fit_tolerances(const Prep& pr, const Model& m, double rtol) {
    Tolerances tol;
    tol.rtol = rtol;
    // The rig's defaults are in metres; a model in its record's units (strain, volts) takes the record's own
    // scales, so the integrator's error is the same share of the signal in any unit.
    if (stiffness_kind(m.p) == StiffnessKind::DataUnits && pr.x_typ > 0 && pr.v_typ > 0) {
        tol.x_scale = pr.x_typ;
        tol.v_scale = pr.v_typ;
    }
    return tol;
}

std::size_t usable_start(const Prep& pr, std::size_t i, std::size_t limit) {
    while (i < limit && (pr.zone[i] || !std::isfinite(pr.xs[i]) || !std::isfinite(pr.vs[i]))) ++i;
    return i;
}

std::vector<double> simulate_window(const Prep& pr, const Model& m, std::size_t i0, std::size_t i1, bool refine, double rtol,
                                    std::size_t refine_end) {
    pr.check_cancel();
    std::vector<double> best;
    if (i1 <= i0) return best;
    const double g = m.sensor_gain(), o = m.sensor_offset();
    const bool curved = m.sensor_curved();
    double x = m.true_x(pr.xs[i0]), v = pr.vs[i0] / m.measure_slope(x);
    run(pr, m, i0, i1, x, v, rtol, best);
    // The refinement fits the initial state to samples [i0, refine_end] only.
    const std::size_t nfit = std::min(i1, refine_end) - i0 + 1;
    auto fit_sse = [&](const std::vector<double>& sim) {
        const std::vector<double> head(sim.begin(), sim.begin() + static_cast<long>(std::min(nfit, sim.size())));
        return sse(pr, m, i0, head, nullptr);
    };
    double best_sse = fit_sse(best);
    if (refine) {
        const double dx = std::max(1e-5 * pr.x_typ, 0.3 * pr.sigma_x), dv = dx / (pr.dt * 10);
        std::vector<double> sx, sv, trial, e;
        for (int it = 0; it < 2; ++it) {
            sse(pr, m, i0, best, &e);
            run(pr, m, i0, i1, x + dx, v, rtol, sx);
            run(pr, m, i0, i1, x, v + dv, rtol, sv);
            Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
            Eigen::Vector2d b = Eigen::Vector2d::Zero();
            for (std::size_t k = 0; k < std::min(nfit, best.size()); ++k) {
                const double gk = curved ? m.measure_slope(best[k]) : g;
                const double jx = gk * (sx[k] - best[k]) / dx, jv = gk * (sv[k] - best[k]) / dv;
                if (!std::isfinite(jx) || !std::isfinite(jv)) continue;
                A(0, 0) += jx * jx;
                A(0, 1) += jx * jv;
                A(1, 1) += jv * jv;
                b[0] -= jx * e[k];
                b[1] -= jv * e[k];
            }
            A(1, 0) = A(0, 1);
            A(0, 0) *= 1.0 + 1e-6;
            A(1, 1) *= 1.0 + 1e-6;
            if (!(A.determinant() > 0)) break;
            const Eigen::Vector2d step = A.ldlt().solve(b);
            // Trust region: a refinement corrects the estimate, it does not replace it. Its size follows the
            // sensor noise, or the smoother's own error on a record far cleaner than its signal's curvature.
            const double scale = std::max({pr.sigma_x, 1e-3 * pr.x_span, 1e-12});
            const double sx_lim = 50 * scale, sv_lim = 50 * scale / (pr.dt * 5);
            const double nx = x + std::clamp(step[0], -sx_lim, sx_lim), nv = v + std::clamp(step[1], -sv_lim, sv_lim);
            run(pr, m, i0, i1, nx, nv, rtol, trial);
            const double s2 = fit_sse(trial);
            if (!(s2 < best_sse)) break;
            best.swap(trial);
            best_sse = s2;
            x = nx;
            v = nv;
        }
    }
    for (double& s : best) s = curved ? m.measure(s) : g * s + o;
    return best;
}

std::vector<std::pair<std::size_t, std::size_t>> windows(const Prep& pr, double periods) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    const MeasuredData& d = *pr.data;
    // Run by run: a window never reaches across the start of the next run.
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t first = pr.run_start[r], last = pr.run_last(first);
        const double t_first = d.t[first], t_last = d.t[last];
        const Drive& drive = pr.drives[r];
        std::vector<double> bounds;
        if (pr.phi_forced) {
            const double k0 = std::ceil(drive.phi(t_first) / kTwoPi);
            for (double k = k0;; k += periods) {
                const double tb = drive.time_of_phase(kTwoPi * k);
                if (!(tb <= t_last)) break;
                bounds.push_back(tb);
            }
        } else {
            const double len = pr.period * periods;
            for (double tb = t_first; tb <= t_last; tb += len) bounds.push_back(tb);
        }
        for (std::size_t w = 0; w + 1 < bounds.size(); ++w) {
            const double ta = bounds[w], tb = bounds[w + 1];
            std::size_t a = first + static_cast<std::size_t>(std::max(0.0, std::ceil((ta - t_first) / pr.dt - 1e-9)));
            std::size_t b = first + static_cast<std::size_t>(std::max(0.0, std::floor((tb - t_first) / pr.dt - 1e-9)));
            b = std::min(b, last);
            a = usable_start(pr, a, b);
            if (b > a + 3) out.emplace_back(a, b);
        }
    }
    return out;
}

std::vector<double> window_sse(const Prep& pr, const Model& m, const std::vector<std::pair<std::size_t, std::size_t>>& wins,
                               bool refine, double rtol) {
    std::vector<double> out(wins.size(), INFINITY);
    ::impactlab::detail::for_each_index(wins.size(), [&](std::size_t w) {
        const auto [a, b] = wins[w];
        const std::vector<double> sim = simulate_window(pr, m, a, b, refine, rtol);
        double e = sim.empty() ? INFINITY : 0.0;
        for (std::size_t k = 0; k < sim.size(); ++k) e += (sim[k] - pr.data->x[a + k]) * (sim[k] - pr.data->x[a + k]);
        out[w] = std::isfinite(e) ? e : INFINITY;
    });
    return out;
}

Horizon predictability_horizon(const Prep& pr, const Model& m, double rtol) {
    Horizon h;
    constexpr double kLengths[] = {0.25, 0.5, 1.0, 2.0, 5.0};
    double first = -1;
    for (double L : kLengths) {
        if (L * pr.period < 16.0 * pr.dt) continue;   // a window needs samples to fit its initial state to
        const auto wins = windows(pr, L);
        if (wins.size() < 12) break;   // too few windows to compare two models on
        const std::vector<double> e = window_sse(pr, m, wins, true, rtol);
        double s = 0;
        std::size_t c = 0;
        for (std::size_t w = 0; w < e.size(); ++w)
            if (std::isfinite(e[w])) {
                s += e[w];
                c += wins[w].second - wins[w].first + 1;
            }
        if (c == 0) break;
        const double rms = std::sqrt(s / static_cast<double>(c));
        h.growth.emplace_back(L, rms);
        if (first < 0) first = rms;
        // Within the horizon the error has at most doubled from the shortest windows' (the noise, for a
        // good model): beyond it the record's own instability, not the model, decides the error.
        if (rms <= 2.0 * first + 1e-300) h.periods = L;
        else break;
    }
    if (h.periods <= 0 && !h.growth.empty()) h.periods = h.growth.front().first;
    return h;
}

ShootOut shooting(const Prep& pr, const Model& m, const FitOptions& o) {
    ShootOut s;
    for (int periods : {1, 10}) {
        double total = 0;
        std::size_t count = 0, nw = 0;
        for (const auto& [a, b] : windows(pr, periods)) {
            const std::vector<double> sim = simulate_window(pr, m, a, b, o.refine_shooting, o.rtol);
            if (sim.empty()) continue;
            double e = 0;
            for (std::size_t k = 0; k < sim.size(); ++k) {
                const double r = sim[k] - pr.data->x[a + k];
                e += r * r;
            }
            if (!std::isfinite(e)) continue;
            total += e;
            count += sim.size();
            ++nw;
            if (periods == 10) s.windows10.emplace_back(a, std::sqrt(e / static_cast<double>(sim.size())));
        }
        const double rms = count ? std::sqrt(total / static_cast<double>(count)) : kNaN;
        if (periods == 1) {
            s.rms1 = rms;
            s.n1 = nw;
        } else {
            s.rms10 = rms;
            s.n10 = nw;
        }
    }
    return s;
}

std::vector<double> free_run(const Prep& pr, const Model& m, double rtol) {
    std::vector<double> out(pr.n, kNaN);
    for (std::size_t first : pr.run_start) {   // each run from its own first usable sample
        const std::size_t last = pr.run_last(first);
        const std::size_t a = usable_start(pr, first, last);
        if (a + 2 >= last) continue;
        std::vector<double> sim = simulate_window(pr, m, a, last, false, rtol);
        if (pr.x_highpass_hz > 0) sim = highpass_fft(sim, pr.dt, pr.x_highpass_hz);   // like with like: the record's chain
        std::copy(sim.begin(), sim.end(), out.begin() + static_cast<long>(a));
    }
    return out;
}

namespace {
class Sections : public Observer {
public:
    Sections(const Drive& d, std::vector<std::pair<double, double>>& out) : d_(d), out_(out) {}
    void on_section(const SectionPoint& p) override { out_.emplace_back(d_.omega(p.t), p.x); }

private:
    const Drive& d_;
    std::vector<std::pair<double, double>>& out_;
};
}  // namespace

std::vector<std::pair<double, double>> free_run_sections(const Prep& pr, const Model& m, double rtol) {
    std::vector<std::pair<double, double>> out;
    if (!pr.phi_forced) return out;
    const MeasuredData& d = *pr.data;
    const double g = m.sensor_gain(), o = m.sensor_offset();
    for (std::size_t first : pr.run_start) {
        const std::size_t last = pr.run_last(first);
        const std::size_t a = usable_start(pr, first, last);
        if (a + 2 >= last) continue;
        const Drive& drive = pr.drive_of(a);
        Simulator sim(fit_tolerances(pr, m, rtol));
        State s;
        s.t = d.t[a];
        s.x = m.true_x(pr.xs[a]);
        s.v = pr.vs[a] / m.measure_slope(s.x);
        Simulator::make_consistent(m.p, drive, s);
        const std::size_t before = out.size();
        Sections obs(drive, out);
        try {
            sim.advance(m.p, drive, s, d.t[last], &obs);
        } catch (const SimulationStalled&) {
            // the sections up to the stall are what this model gives
        }
        for (std::size_t k = before; k < out.size(); ++k) out[k].second = m.sensor_curved() ? m.measure(out[k].second) : g * out[k].second + o;
    }
    return out;
}

std::vector<std::pair<double, double>> measured_sections(const Prep& pr) {
    std::vector<std::pair<double, double>> out;
    if (!pr.phi_forced) return out;
    const MeasuredData& d = *pr.data;
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t first = pr.run_start[r], last = pr.run_last(first);
        const Drive& drive = pr.drives[r];
        const double k0 = std::ceil(drive.phi(d.t[first]) / kTwoPi);
        for (double k = k0;; k += 1) {
            const double tk = drive.time_of_phase(kTwoPi * k);
            if (!(tk < d.t[last])) break;
            const auto i = first + static_cast<std::size_t>(std::floor((tk - d.t[first]) / pr.dt));
            if (i + 1 > last) break;
            const double f = (tk - d.t[i]) / pr.dt;
            double x;
            if (!pr.zone[i] && !pr.zone[i + 1] && std::isfinite(pr.xs[i]) && std::isfinite(pr.xs[i + 1])) {
                // Cubic Hermite through the smoothed positions and velocities.
                const double h00 = (1 + 2 * f) * (1 - f) * (1 - f), h10 = f * (1 - f) * (1 - f);
                const double h01 = f * f * (3 - 2 * f), h11 = f * f * (f - 1);
                x = h00 * pr.xs[i] + h10 * pr.dt * pr.vs[i] + h01 * pr.xs[i + 1] + h11 * pr.dt * pr.vs[i + 1];
            } else {
                x = d.x[i] + f * (d.x[i + 1] - d.x[i]);
            }
            out.emplace_back(drive.omega(tk), x);
        }
    }
    return out;
}

double diagram_distance(const std::vector<std::pair<double, double>>& a, const std::vector<std::pair<double, double>>& b,
                        double bin, std::size_t& bins, std::vector<std::pair<double, double>>* per_bin) {
    bins = 0;
    if (per_bin) per_bin->clear();
    if (a.empty() || b.empty() || !(bin > 0)) return -1;
    std::map<long, std::pair<std::vector<double>, std::vector<double>>> groups;
    for (const auto& [w, x] : a) groups[std::lround(std::floor(w / bin))].first.push_back(x);
    for (const auto& [w, x] : b) groups[std::lround(std::floor(w / bin))].second.push_back(x);
    double total = 0;
    for (auto& [key, g] : groups) {
        auto& [p, q] = g;
        if (p.size() < 5 || q.size() < 5) continue;
        std::sort(p.begin(), p.end());
        std::sort(q.begin(), q.end());
        const double w1 = wasserstein1_sorted(p, q, 200);
        total += w1;
        ++bins;
        if (per_bin) per_bin->emplace_back((static_cast<double>(key) + 0.5) * bin, w1);
    }
    return bins ? total / static_cast<double>(bins) : -1;
}

}  // namespace impactlab::identify::detail
