// Held-out judgements: the judging windows, the two folds, and whether one model predicts better than another.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

double judging_periods(const Prep& pr, const std::function<double()>& model_horizon) {
    const Prep::Predictability& dh = pr.predictability;
    if (dh.measured && dh.regular) {
        for (double c : {10.0, 5.0, 2.0})
            if (windows(pr, c).size() >= 40) return c;
        return 1.0;
    }
    double L = 0.25;
    if (dh.measured) {
        for (double c : {5.0, 2.0, 1.0, 0.5})
            if (c <= dh.periods) {
                L = c;
                break;
            }
    } else {
        L = model_horizon();
    }
    while (L > 0.25 && L * pr.period >= 32.0 * pr.dt && windows(pr, L).size() < 40) L *= 0.5;
    return L;
}

HeldOutSplit held_out_split(const Prep& pr, const Model& m, double rtol) {
    const MeasuredData& data = *pr.data;
    HeldOutSplit s{predictability_horizon(pr, m, rtol), 0, {}, {pr, pr}, {}, data.t.front(), 1};
    const double L = judging_periods(pr, [&] { return s.hz.periods; });
    s.periods = L;
    if (L > 0) s.wins = windows(pr, L);
    s.block = std::max((data.t.back() - s.t0) / 8.0, 2.0 * L * pr.period);
    for (std::size_t f = 0; f < 2; ++f) {
        s.fold_pr[f].rows.clear();
        for (std::size_t r : pr.rows)
            if (s.fold_of(pr, r) == static_cast<int>(f)) s.fold_pr[f].rows.push_back(r);
    }
    for (std::size_t w = 0; w < s.wins.size(); ++w) s.fold_wins[static_cast<std::size_t>(s.fold_of(pr, s.wins[w].first))].push_back(w);
    return s;
}

Compare compare_held_out(const Prep& pr, const std::vector<std::pair<std::size_t, std::size_t>>& wins, const std::vector<double>& cur,
                         const std::vector<double>& cand) {
    Compare c;
    std::vector<double> d, rel;
    for (std::size_t w = 0; w < cur.size(); ++w) {
        if (!std::isfinite(cur[w]) && !std::isfinite(cand[w])) continue;
        // A window the new model cannot simulate counts against it; one the old cannot, for it.
        const double a = std::isfinite(cur[w]) ? cur[w] : 10.0 * cand[w] + 1.0, b = std::isfinite(cand[w]) ? cand[w] : 10.0 * cur[w] + 1.0;
        c.sum_cur += a;
        c.sum_new += b;
        const double noise_w = static_cast<double>(wins[w].second - wins[w].first + 1) * pr.sigma_x * pr.sigma_x;
        if (std::abs(a - b) > 0.1 * noise_w) {
            d.push_back(a - b);
            rel.push_back((a - b) / std::max(a, noise_w));
        }
    }
    c.gain = c.sum_cur > 0 ? (c.sum_cur - c.sum_new) / c.sum_cur : 0.0;
    if (d.size() < 3) return c;
    const double n = static_cast<double>(d.size());
    const double z_t = t_test_z(d);
    // Wilcoxon's signed-rank test as well: chaotic windows make the differences heavy-tailed, and a
    // consistent sign over the windows is what a real effect shows and a spurious one does not.
    std::vector<std::size_t> order(d.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return std::abs(d[i]) < std::abs(d[j]); });
    double w_plus = 0;
    for (std::size_t r = 0; r < order.size(); ++r)
        if (d[order[r]] > 0) w_plus += static_cast<double>(r + 1);
    const double z_w = (w_plus - n * (n + 1) / 4.0) / std::sqrt(n * (n + 1) * (2 * n + 1) / 24.0);
    // And the t test on each window's relative fall (bounded above by 1, so light-tailed): a bumper
    // offset removes most of the error of the few windows with impacts in them, every time.
    c.z = std::max({z_t, z_w, t_test_z(rel)});
    return c;
}

bool better_beyond_noise(const Prep& pr, const std::vector<std::pair<std::size_t, std::size_t>>& wins, const Compare& c) {
    std::size_t samples = 0;
    for (const auto& [a, b] : wins) samples += b - a + 1;
    const double excess = std::max(c.sum_cur - static_cast<double>(samples) * pr.sigma_x * pr.sigma_x, 0.0);
    return c.z >= 3.0 && c.sum_cur - c.sum_new > 0.02 * excess && c.gain > 1e-3;
}

bool refinement_predicts_better(const Prep& pr, const Model& refined, const Model& before, double rtol) {
    const std::size_t fit_end = oe_fit_end(pr, usable_start(pr, 0, pr.n - 2), 30000);
    const double L = judging_periods(pr, [&] {
        return std::max({predictability_horizon(pr, refined, rtol).periods, predictability_horizon(pr, before, rtol).periods, 0.25});
    });
    std::vector<std::pair<std::size_t, std::size_t>> wins;
    for (const auto& w : windows(pr, L))
        if (w.first > fit_end) wins.push_back(w);
    if (wins.size() < 10) return false;   // nothing held out to judge it on
    const std::vector<double> eb = window_sse(pr, before, wins, true, rtol), er = window_sse(pr, refined, wins, true, rtol);
    const Compare c = compare_held_out(pr, wins, eb, er);
    // A refinement of parameters already in the model: a consistent fall on the held-out windows.
    return c.sum_new < c.sum_cur && c.z >= 2.0;
}

bool baseline_predicts_better(const Prep& pr, const Model& given, const Model& fitted, const std::vector<std::string>& names,
                              const FitOptions& o, std::string& why) {
    const HeldOutSplit sp = held_out_split(pr, given, o.rtol);
    if (sp.wins.size() < 12) {
        why = "too few windows to check it on held-out data";
        return false;
    }
    std::vector<double> e_given(sp.wins.size(), INFINITY), e_fit(sp.wins.size(), INFINITY);
    for (std::size_t f = 0; f < 2; ++f) {
        std::vector<std::pair<std::size_t, std::size_t>> sub;
        for (std::size_t w : sp.fold_wins[f]) sub.push_back(sp.wins[w]);
        Model mf = fitted;
        std::vector<Knob> knobs = base_knobs(mf, names, pr);
        if (sp.fold_pr[1 - f].rows.size() >= 20) {
            Eigen::VectorXd R;
            Eigen::MatrixXd J;
            lm_residual(sp.fold_pr[1 - f], mf, knobs, 15, R, J);
        }
        if (!unphysical(mf).empty()) mf = fitted;
        const std::vector<double> eg = window_sse(pr, given, sub, o.refine_shooting, o.rtol);
        const std::vector<double> ef = window_sse(pr, mf, sub, o.refine_shooting, o.rtol);
        for (std::size_t k = 0; k < sub.size(); ++k) {
            e_given[sp.fold_wins[f][k]] = eg[k];
            e_fit[sp.fold_wins[f][k]] = ef[k];
        }
    }
    const Compare c = compare_held_out(pr, sp.wins, e_given, e_fit);
    char buf[240];
    std::snprintf(buf, sizeof buf, "held-out simulation error %s by %.2f %% (paired z = %.1f over %zu windows)",
                  c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain), c.z, sp.wins.size());
    why = buf;
    return better_beyond_noise(pr, sp.wins, c);
}

}  // namespace impactlab::identify::detail
