// Impacts the model has no stop for: abrupt velocity reversals at the end of the travel away from the
// model's bumper (or at either end of a model without one). They are found in the data before anything is
// fitted, so the equation error never reads their impulses as a force of the state (a smaller unbalance, a
// heavier cart), and they propose an end stop whose position and restitution come from the reversals
// themselves. The held-out simulation error then decides, as for every other effect.
#include <algorithm>
#include <cmath>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {
constexpr std::size_t kMargin = 10;   // samples kept clear around a reversal, as around a bumper impact

// Reversals at one end of the travel, run by run (a jump between runs is never one). side = -1 reads the
// mirrored record, so the detector's "bumper at +x" is the lower end; levels come back in measured x.
std::vector<ImpactObs> reversals(const Prep& pr, const MeasuredData& d, int side) {
    std::vector<ImpactObs> out;
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t a = pr.run_start[r], b = pr.run_last(a) + 1;
        const std::vector<double> t(d.t.begin() + static_cast<long>(a), d.t.begin() + static_cast<long>(b));
        std::vector<double> x(d.x.begin() + static_cast<long>(a), d.x.begin() + static_cast<long>(b));
        if (side < 0)
            for (double& v : x) v = -v;
        for (ImpactObs im : find_impacts(t, x, pr.sigma_x, NAN)) {
            im.i_first += a;
            im.i_last += a;
            if (side < 0) im.level = -im.level;
            out.push_back(im);
        }
    }
    return out;
}
}  // namespace

void find_stray_impacts(const MeasuredData& d, const Model& m, Prep& pr) {
    pr.stray.clear();
    pr.stray_side = 0;
    std::vector<double> xs(d.x.begin(), d.x.end());
    const double lo = quantile(xs, 0.005), hi = quantile(xs, 0.995), travel = std::max(hi - lo, 1e-12);
    for (int side : {-1, 1}) {
        if (side > 0 && m.bumper()) continue;   // reversals there are the bumper's own impacts
        std::vector<ImpactObs> ev = reversals(pr, d, side);
        if (ev.size() < 3) continue;
        // A stop holds the cart at one level: the reversals must cluster near the extreme of the travel.
        std::vector<double> lev;
        for (const auto& im : ev) lev.push_back(im.level);
        const double med = median(lev);
        const double extreme = side < 0 ? lo : hi;
        if (std::abs(med - extreme) > 0.05 * travel) continue;
        const double keep = std::max(0.05 * travel, 10.0 * pr.sigma_x);
        ev.erase(std::remove_if(ev.begin(), ev.end(), [&](const ImpactObs& im) { return std::abs(im.level - med) > keep; }), ev.end());
        if (ev.size() < 3 || ev.size() <= pr.stray.size()) continue;
        pr.stray = std::move(ev);
        pr.stray_side = side;
    }
    for (const auto& im : pr.stray) {
        const std::size_t a = im.i_first >= kMargin ? im.i_first - kMargin : 0, b = std::min(pr.n - 1, im.i_last + kMargin);
        for (std::size_t j = a; j <= b; ++j) pr.zone[j] = 1;
    }
    // Touches too brief or slow to fit as reversals: every sample that reaches the stop joins the zone, as at
    // the bumper. A compliant stop turns a slow cart round near xS and a fast one deeper, so the contact
    // begins about as far inside the shallowest reversal as the reversals spread.
    if (!pr.stray.empty()) {
        double shallow = pr.stray.front().level, deep = shallow;
        for (const auto& im : pr.stray) {
            if (pr.stray_side * (im.level - shallow) < 0) shallow = im.level;
            if (pr.stray_side * (im.level - deep) > 0) deep = im.level;
        }
        const double reach = std::abs(deep - shallow) + 8.0 * pr.sigma_x + 2e-6;
        for (std::size_t i = 0; i < pr.n; ++i)
            if (pr.stray_side * (d.x[i] - shallow) >= -reach)
                for (std::size_t j = i >= kMargin ? i - kMargin : 0; j <= std::min(pr.n - 1, i + kMargin); ++j) pr.zone[j] = 1;
    }
}

namespace {
// Short windows around the reversals with use[k] set (all when empty), for the simulation error of a stop.
std::vector<std::pair<std::size_t, std::size_t>> reversal_windows(const Prep& pr, const std::vector<char>& use) {
    std::vector<std::pair<std::size_t, std::size_t>> wins;
    const auto reach = static_cast<std::size_t>(std::max(20.0, 0.3 * pr.period / pr.dt));
    for (std::size_t k = 0; k < pr.stray.size(); ++k) {
        if (!use.empty() && !use[k]) continue;
        const ImpactObs& im = pr.stray[k];
        const std::size_t lo = im.i_first > reach ? im.i_first - reach : 0;
        const std::size_t a = usable_start(pr, lo, im.i_first);
        const std::size_t b = std::min(pr.run_last(im.i_first), im.i_last + reach);
        if (a + 8 < im.i_first && b > im.i_last) wins.emplace_back(a, b);
    }
    return wins;
}

// The stiffness first on a coarse grid (a stop stiffer than the sampling resolves barely moves the error, so a
// local fit from a poor start wanders): lk gets the start with the least median window error (eval: the
// windows' root errors at the current lk, from wins).
template <class Eval>
void coarse_stiffness(double& lk, const Eval& eval, std::vector<std::pair<std::size_t, std::size_t>>& wins) {
    double best = INFINITY, best_lk = lk;
    Eigen::VectorXd r;
    for (double k = 1e5; k <= 1.01e9; k *= std::sqrt(10.0)) {
        lk = std::log(k);
        eval(r);
        std::vector<double> a(r.data(), r.data() + r.size());
        const double med = a.empty() ? INFINITY : median(a);
        if (med < best) {
            best = med;
            best_lk = lk;
        }
    }
    lk = best_lk;
    // Windows far off the rest there (a chaotic stretch entered from a slightly wrong start diverges
    // whatever the stop) are left out of the fit.
    eval(r);
    std::vector<std::pair<std::size_t, std::size_t>> kept;
    for (std::size_t w = 0; w < wins.size(); ++w)
        if (r[static_cast<Eigen::Index>(w)] <= 5.0 * best) kept.push_back(wins[w]);
    if (kept.size() >= 3) wins = std::move(kept);
}
}  // namespace

std::vector<std::pair<std::string, double>> end_stop_values(const Prep& pr, const Model& m, const std::vector<char>& use, double rtol,
                                                            double* sigma_xS) {
    std::vector<std::pair<std::string, double>> out;
    const double side = pr.stray_side;
    std::vector<double> lev, kap, kap_all, dwell, vm;
    for (std::size_t k = 0; k < pr.stray.size(); ++k) {
        if (!use.empty() && !use[k]) continue;
        const ImpactObs& im = pr.stray[k];
        lev.push_back(m.true_x(im.level));
        dwell.push_back(im.t_out - im.t_in);
        vm.push_back(im.v_minus / std::abs(m.measure_slope(lev.back())));
        kap_all.push_back(apparent_kappa(im));
        if (im.v_minus >= 0.02) kap.push_back(kap_all.back());
    }
    if (lev.size() < 3) return out;
    if (kap.size() < 3) kap = kap_all;
    if (sigma_xS) {
        *sigma_xS = median_se(lev, median(lev), pr.sigma_x);
    }
    const double e = std::clamp(median(kap), 0.02, 0.98);
    // First estimates from the reversals as the detector reads them: the contact lasts about its measured
    // dwell, at least half a sample (a stop stiffer than the sampling resolves looks the same in the data),
    // which gives kS; the restitution gives the damping ratio; the cart turns round past xS by its largest
    // penetration.
    const double Tc = std::max(median(dwell), 0.5 * pr.dt);
    double lk = std::log(m.p.m * std::pow(kPi / Tc, 2));
    const double le = std::log(e);
    double zeta = -le / std::sqrt(kPi * kPi + le * le);
    auto penetration = [&](double kS, double z) {
        const double wn = std::sqrt(kS / m.p.m), wd = wn * std::sqrt(1.0 - z * z);
        return median(vm) / wn * std::exp(-z * wn / wd * std::atan2(wd, z * wn));
    };
    // The fit moves the turning level (where the data put the cart's reversals) rather than xS itself: a
    // stiffer stop further out turns the cart round at the same place, a long valley in (xS, kS) that is
    // short in (level, kS).
    double level = median(lev);
    double xS = level - side * penetration(std::exp(lk), zeta);
    // Then the three together on the simulation error of short windows around the reversals used: the
    // detector's plateau level and dwell are biased for a contact of a few samples, the simulation is not.
    std::vector<std::pair<std::size_t, std::size_t>> wins = reversal_windows(pr, use);
    Model trial = m;
    apply_effect(trial, "end_stop", {});
    EffectInstance& inst = trial.p.effects.back();
    auto set = [&] {
        const double kS = std::exp(lk);
        xS = level - side * penetration(kS, zeta);
        inst.p = {xS, kS, 2.0 * zeta * std::sqrt(kS * m.p.m), side};
    };
    set();
    if (wins.size() >= 3) {
        const double span = std::max(pr.x_span, 1e-6);
        std::vector<Knob> knobs{{&level, 0.1 * pr.sigma_x + 1e-8, level - 0.05 * span, level + 0.05 * span, "level"},
                                {&lk, 1e-3, std::log(1e3), std::log(1e10), "ln kS"},
                                {&zeta, 1e-4, 1e-3, 0.95, "zeta"}};
        auto eval = [&](Eigen::VectorXd& r) {
            set();
            const std::vector<double> e_w = window_sse(pr, trial, wins, false, rtol);
            r.resize(static_cast<Eigen::Index>(e_w.size()));
            double ss = 0;
            for (std::size_t w = 0; w < e_w.size(); ++w) {
                r[static_cast<Eigen::Index>(w)] = std::sqrt(e_w[w]);
                ss += e_w[w];
            }
            return std::isfinite(ss) ? ss : INFINITY;
        };
        auto step_of = [](const Knob& kb, double v) { return v + kb.step > kb.hi ? -kb.step : kb.step; };
        coarse_stiffness(lk, eval, wins);
        LsqOptions lo;
        lo.max_iterations = 40;
        lo.function_tolerance = 1e-6;
        Eigen::VectorXd R;
        Eigen::MatrixXd J;
        least_squares(knobs, eval, step_of, lo, R, &J);
        set();
        // xS's standard error from the windows' scatter about the fit (each window one observation: its
        // samples are not independent), which carries the trade of the stop's place against its stiffness
        // that a contact of a few samples cannot settle: xS = level - side pen(kS, zeta), linearised.
        if (sigma_xS && J.rows() > 3 && std::isfinite(R.squaredNorm())) {
            Eigen::Matrix3d A = J.transpose() * J;
            for (int k = 0; k < 3; ++k) A(k, k) += 1e-12 * A(k, k) + 1e-300;
            const double s2 = R.squaredNorm() / static_cast<double>(J.rows() - 3);
            const Eigen::Matrix3d C = A.ldlt().solve(Eigen::Matrix3d::Identity()) * s2;
            const double h_lk = 1e-3, h_z = 1e-4;
            Eigen::Vector3d grad;
            grad << 1.0, -side * (penetration(std::exp(lk + h_lk), zeta) - penetration(std::exp(lk), zeta)) / h_lk,
                -side * (penetration(std::exp(lk), std::min(zeta + h_z, 0.99)) - penetration(std::exp(lk), zeta)) / h_z;
            *sigma_xS = std::max(*sigma_xS, std::sqrt(std::max(0.0, grad.dot(C * grad))));
        }
    }
    for (std::size_t k = 0; k < 4; ++k) out.emplace_back(inst.law->names[k], inst.p[k]);
    return out;
}

void end_stop_stage(const Prep& pr, const FitOptions& o, const SentenceContext& sc, const Model& after, FitReport& rep) {
    const EffectLaw* law = find_effect("end_stop");
    if (pr.stray.size() < 3 || !law || !law->fit.from_reversals) return;
    const std::string id = law->id;
    if (!o.wants(id)) return;
    for (const auto& e : after.p.effects)
        if (e.law == law) return;   // the model given already has one
    double se = 0;
    const std::vector<std::pair<std::string, double>> values = end_stop_values(pr, after, {}, o.rtol, &se);
    if (values.empty()) return;
    FoundEffect f;
    f.id = "end_stop";
    f.evidence = Evidence::StrayImpacts;
    f.parameters = values;
    f.sigma = {{"xS", se}, {"kS", 0.0}, {"cS", 0.0}, {"side", 0.0}};
    f.z = static_cast<double>(pr.stray.size());   // the reversals the model cannot make; the held-out error decides
    f.sentence = end_stop_sentence(pr, after, f, sc);
    rep.effects_found.push_back(std::move(f));
}

std::string end_stop_sentence(const Prep& pr, const Model& m, const FoundEffect& f, const SentenceContext& sc) {
    return sentence(f.id, m, f.parameters, f.sigma, sc) + "; seen in " + std::to_string(pr.stray.size()) +
           " reversals the model cannot make";
}

}  // namespace impactlab::identify::detail
