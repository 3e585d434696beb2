// The final gate of impactlab fit: the model written is compared with the model given on every error the
// report prints, unit by unit (blocks of rows and samples, shooting windows, impacts, omega bins), so that
// "worse" means worse beyond the scatter of those units and never a number the report would print higher.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>
#include <map>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

// Contiguous blocks of `n` items (at most `blocks` of them): the units of a sum over rows or samples, long
// enough that the serial correlation within a block does not make neighbouring units dependent.
std::vector<std::pair<std::size_t, std::size_t>> blocks_of(std::size_t n, std::size_t blocks) {
    std::vector<std::pair<std::size_t, std::size_t>> b;
    if (n == 0) return b;
    const std::size_t k = std::min(blocks, n);
    for (std::size_t j = 0; j < k; ++j) b.emplace_back(j * n / k, (j + 1) * n / k);
    return b;
}

PrintedError squares_by_block(std::string name, std::size_t n, const std::function<double(std::size_t)>& err) {
    PrintedError e;
    e.name = std::move(name);
    for (const auto& [a, b] : blocks_of(n, 16)) {
        double s = 0, c = 0;
        for (std::size_t i = a; i < b; ++i) {
            const double r = err(i);
            if (!std::isfinite(r)) continue;
            s += r * r;
            c += 1;
        }
        e.num.push_back(c > 0 ? s : INFINITY);
        e.den.push_back(c > 0 ? c : 1.0);
    }
    return e;
}

PrintedError shooting_error(std::string name, const Prep& pr, const Model& m, double periods, const FitOptions& o) {
    PrintedError e;
    e.name = std::move(name);
    const auto wins = windows(pr, periods);
    const std::vector<double> sse = window_sse(pr, m, wins, o.refine_shooting, o.rtol);
    for (std::size_t w = 0; w < wins.size(); ++w) {
        e.num.push_back(sse[w]);
        e.den.push_back(static_cast<double>(wins[w].second - wins[w].first + 1));
    }
    return e;
}

}  // namespace

double PrintedError::value() const {
    if (kind == Kind::AbsMedian) {
        std::vector<double> v;
        for (double x : num)
            if (std::isfinite(x)) v.push_back(x);
        return v.empty() ? kNaN : median(v);
    }
    double s = 0, c = 0;
    for (std::size_t i = 0; i < num.size(); ++i)
        if (std::isfinite(num[i])) {
            s += num[i];
            c += den[i];
        }
    if (c <= 0) return kNaN;
    return kind == Kind::Rms ? std::sqrt(s / c) : s / c;
}

const PrintedError* PrintedErrors::find(const std::string& name) const {
    for (const auto& x : e)
        if (x.name == name) return &x;
    return nullptr;
}

PrintedErrors printed_errors(const Prep& pr, const Model& m, const FitOptions& o, double judge_periods, const Prep* test) {
    PrintedErrors pe;
    std::vector<double> pw;
    residual(pr, m, pe.R, pw);
    pe.e.push_back(squares_by_block(kErrResidual, static_cast<std::size_t>(pe.R.size()),
                                    [&](std::size_t i) { return pe.R[static_cast<Eigen::Index>(i)]; }));
    pr.check_cancel();
    // A chaotic record's trajectory errors judge only within its predictability horizon; past it they are
    // printed as such and the attractor's statistics judge.
    const Prep::Predictability& dh = pr.predictability;
    const bool chaotic = dh.measured && !dh.regular;
    pe.e.push_back(shooting_error(kErrShoot1, pr, m, 1.0, o));
    pe.e.back().decides = !chaotic || dh.periods >= 1.0;
    pe.e.push_back(shooting_error(kErrShoot10, pr, m, 10.0, o));
    pe.e.back().decides = !chaotic || dh.periods >= 10.0;
    if (judge_periods > 0 && judge_periods != 1.0 && judge_periods != 10.0)
        pe.e.push_back(shooting_error(kErrShootJudge, pr, m, judge_periods, o));
    pr.check_cancel();
    pe.pred = predict_impacts(pr, m, o.rtol);
    {
        PrintedError kap{kErrKappa, {}, {}, PrintedError::Kind::Rms, {}, {}}, dwell{kErrDwell, {}, {}, PrintedError::Kind::Rms, {}, {}},
            level{kErrLevel, {}, {}, PrintedError::Kind::AbsMedian, {}, {}};
        for (std::size_t k = 0; k < pr.impacts.size(); ++k) {
            const bool ok = k < pe.pred.ok.size() && pe.pred.ok[k];
            const ImpactObs& im = pr.impacts[k];
            if (im.v_minus > 0.02) {
                const double dk = ok ? apparent_kappa(im) - apparent_kappa(pe.pred.obs[k]) : kNaN;
                kap.num.push_back(ok ? dk * dk : INFINITY);
                kap.den.push_back(1.0);
            }
            const double dd = ok ? (im.t_out - im.t_in) - (pe.pred.obs[k].t_out - pe.pred.obs[k].t_in) : kNaN;
            dwell.num.push_back(ok ? dd * dd : INFINITY);
            dwell.den.push_back(1.0);
            level.num.push_back(ok ? im.level - pe.pred.obs[k].level : INFINITY);
            level.den.push_back(1.0);
        }
        // What the record resolves of each: the dwell to a sample, an apparent restitution to the velocity
        // noise over the approach speed, a level to the position noise; over the impacts compared.
        double vm = 0;
        for (const ImpactObs& im : pr.impacts) vm += im.v_minus;
        vm = pr.impacts.empty() ? 1.0 : std::max(vm / static_cast<double>(pr.impacts.size()), 1e-9);
        const double ni = std::sqrt(std::max<double>(1.0, static_cast<double>(pr.impacts.size())));
        // A dwell is counted in samples: one impact's dwell one sample longer moves the printed RMS by the
        // quantum's share. A level below twice the sensor noise is no shift the impact stage would name either.
        dwell.quantum = pr.dt;
        kap.resolution = std::sqrt(2.0) * pr.sigma_x / pr.dt / vm / ni;
        level.resolution = 2.0 * pr.sigma_x;
        kap.missing_fails = dwell.missing_fails = level.missing_fails = false;
        if (!dwell.num.empty()) {
            pe.e.push_back(std::move(kap));
            pe.e.push_back(std::move(dwell));
            pe.e.push_back(std::move(level));
        }
    }
    if (pr.phi_forced) {
        const auto [wmin, wmax] = std::minmax_element(pr.omega.begin(), pr.omega.end());
        if (*wmax - *wmin > 2 * o.omega_bin) {
            pe.diagram_measured = measured_sections(pr);
            pe.diagram = free_run_sections(pr, m, o.rtol);
            std::size_t bins = 0;
            std::vector<std::pair<double, double>> per_bin;
            diagram_distance(pe.diagram_measured, pe.diagram, o.omega_bin, bins, &per_bin);
            PrintedError d{kErrDiagram, {}, {}, PrintedError::Kind::Mean, {}, {}};
            // Each bin's distance is itself a sample statistic: two finite clouds of one distribution lie about
            // sd sqrt(1/n1 + 1/n2) apart. That sampling noise is part of the scatter of a change.
            std::map<long, std::array<double, 4>> cnt;   // n measured, n simulated, sum x, sum x^2 (measured)
            for (const auto& [w, x] : pe.diagram_measured) {
                auto& c = cnt[std::lround(std::floor(w / o.omega_bin))];
                c[0] += 1;
                c[2] += x;
                c[3] += x * x;
            }
            for (const auto& [w, x] : pe.diagram) cnt[std::lround(std::floor(w / o.omega_bin))][1] += 1;
            for (const auto& [w, dist] : per_bin) {
                d.num.push_back(dist);
                d.den.push_back(1.0);
                d.keys.push_back(w);
                const auto& c = cnt[std::lround(std::floor(w / o.omega_bin))];
                const double mean = c[0] > 0 ? c[2] / c[0] : 0.0, var = c[0] > 1 ? std::max(0.0, c[3] / c[0] - mean * mean) : 0.0;
                d.noise.push_back(c[0] > 0 && c[1] > 0 ? std::sqrt(var * (1.0 / c[0] + 1.0 / c[1])) : 0.0);
            }
            pe.e.push_back(std::move(d));
        }
    } else {
        const std::vector<double> fr = free_run(pr, m, o.rtol);
        const MeasuredData& data = *pr.data;
        pe.e.push_back(squares_by_block(kErrFree, pr.n, [&](std::size_t i) { return fr[i] - data.x[i]; }));
        pe.e.back().decides = !chaotic;
        // The attractor judges a chaotic record; a regular one's free run is the stricter test, so there the
        // statistics are printed only.
        pe.attractor = attractor_stats(pr, fr);
        for (PrintedError& a : attractor_errors(pe.attractor)) {
            a.decides = chaotic;
            pe.e.push_back(std::move(a));
        }
    }
    if (test) {
        pr.check_cancel();
        const std::vector<double> fr = free_run(*test, m, o.rtol);
        const MeasuredData& td = *test->data;
        pe.e.push_back(squares_by_block(kErrTestFree, test->n, [&](std::size_t i) { return fr[i] - td.x[i]; }));
        pe.e.back().decides = !chaotic;
        pe.e.push_back(shooting_error(kErrTestShoot, *test, m, judge_periods > 0 ? judge_periods : 1.0, o));
    }
    return pe;
}

GateCheck gate_check(const PrintedErrors& given, const PrintedErrors& cand, double z_tol) {
    GateCheck g;
    for (const PrintedError& ref : given.e) {
        const PrintedError* c = cand.find(ref.name);
        if (!c || !ref.decides) continue;
        double vr = ref.value(), vc = c->value();
        if (!std::isfinite(vr)) continue;   // the given model could not be simulated here: nothing to be worse than
        char buf[320];
        if (!std::isfinite(vc)) {
            std::snprintf(buf, sizeof buf, "%s: the model could not be simulated where the given model could", ref.name.c_str());
            g.worse = true;
            g.why = buf;
            return g;
        }
        // Paired units (by omega for the diagram's bins, by position otherwise). Both values are then taken over
        // the units both have: a model that also predicts the slow impacts the other misses is judged on the
        // impacts both predict, not on a harder set than the other's.
        PrintedError rc = ref, cc = *c;
        rc.num.clear();
        rc.den.clear();
        cc.num.clear();
        cc.den.clear();
        std::vector<double> d;
        double den = 0, noise2 = 0;
        std::size_t failed = 0;
        if (!ref.keys.empty()) {
            std::map<double, std::size_t> by_key;
            for (std::size_t i = 0; i < c->keys.size(); ++i) by_key[c->keys[i]] = i;
            for (std::size_t i = 0; i < ref.keys.size(); ++i) {
                const auto it = by_key.find(ref.keys[i]);
                if (it == by_key.end() || !std::isfinite(ref.num[i])) continue;
                d.push_back(c->num[it->second] - ref.num[i]);
                den += ref.den[i];
                rc.num.push_back(ref.num[i]);
                rc.den.push_back(ref.den[i]);
                cc.num.push_back(c->num[it->second]);
                cc.den.push_back(c->den[it->second]);
                const double na = i < ref.noise.size() ? ref.noise[i] : 0.0, nb = it->second < c->noise.size() ? c->noise[it->second] : 0.0;
                noise2 += na * na + nb * nb;
            }
        } else {
            const std::size_t n = std::min(ref.num.size(), c->num.size());
            for (std::size_t i = 0; i < n; ++i) {
                if (!std::isfinite(ref.num[i])) continue;
                if (!std::isfinite(c->num[i])) {
                    if (ref.missing_fails) ++failed;
                    continue;
                }
                d.push_back(c->num[i] - ref.num[i]);
                den += ref.den[i];
                rc.num.push_back(ref.num[i]);
                rc.den.push_back(ref.den[i]);
                cc.num.push_back(c->num[i]);
                cc.den.push_back(c->den[i]);
            }
        }
        if (failed > 0) {
            std::snprintf(buf, sizeof buf, "%s: %zu unit%s the given model simulates could not be simulated", ref.name.c_str(), failed,
                          failed == 1 ? "" : "s");
            g.worse = true;
            g.why = buf;
            return g;
        }
        if (d.empty() || den <= 0) continue;
        if (std::isfinite(rc.value()) && std::isfinite(cc.value())) {
            vr = rc.value();
            vc = cc.value();
        }
        const double n = static_cast<double>(d.size());
        double mean = 0;
        for (double x : d) mean += x;
        mean /= n;
        double var = 0;
        for (double x : d) var += (x - mean) * (x - mean);
        var = d.size() > 1 ? var / (n - 1.0) : 0.0;
        // The scatter of the printed value's rise, from the units' paired differences (for a median, the
        // median's standard error from the levels' own spread).
        double rise = 0, scatter = 0;
        if (ref.kind == PrintedError::Kind::AbsMedian) {
            rise = std::abs(vc) - std::abs(vr);
            scatter = median_se(rc.num, vr);
        } else {
            const double se_sum = std::sqrt(var * n);   // of the summed difference
            if (ref.kind == PrintedError::Kind::Rms) {
                rise = vc - vr;
                scatter = se_sum / den / std::max(vr + vc, 1e-300);   // d(MS) = 2 RMS d(RMS)
            } else {
                rise = vc - vr;
                scatter = std::sqrt(se_sum * se_sum + noise2) / den;
            }
        }
        // Worse: a rise beyond its scatter, and visible at the report's four significant digits.
        double resolution = ref.resolution;
        if (ref.quantum > 0 && ref.kind == PrintedError::Kind::Rms)
            resolution = std::max(resolution, std::sqrt(vr * vr + ref.quantum * ref.quantum / n) - vr);
        scatter = std::max(scatter, resolution / z_tol);
        if (rise > 1e-3 * std::abs(vr) && rise <= z_tol * scatter) {
            std::snprintf(buf, sizeof buf, "%s: %.4g -> %.4g, within its scatter (%.2g standard errors of %.2g)", ref.name.c_str(), vr, vc,
                          z_tol, scatter);
            g.within.emplace_back(buf);
        }
        if (rise > z_tol * scatter && rise > 1e-3 * std::abs(vr)) {
            std::snprintf(buf, sizeof buf, "%s rose from %.4g to %.4g (beyond %.2g standard errors of %.2g over %zu units)", ref.name.c_str(),
                          vr, vc, z_tol, scatter, d.size());
            g.worse = true;
            g.why = buf;
            return g;
        }
    }
    return g;
}

}  // namespace impactlab::identify::detail
