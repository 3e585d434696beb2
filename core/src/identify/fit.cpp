// The loop of impactlab fit: baseline, residual, effect selection, the model with the effects, errors before
// and after.
#include <algorithm>
#include <array>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>

#include "identify/internal.hpp"
#include "impactlab/forces.hpp"

namespace impactlab::identify {

using namespace detail;

namespace {

// Levenberg-Marquardt on the weak-form residual over `knobs` (numerical Jacobian). Returns the final
// residual in R and the Jacobian dR/dknob in J.
void lm_residual(const Prep& pr, Model& m, std::vector<Knob>& knobs, int max_iter, Eigen::VectorXd& R, Eigen::MatrixXd& J) {
    std::vector<double> pw;
    auto eval = [&](Eigen::VectorXd& out) {
        residual(pr, m, out, pw);
        return out.squaredNorm();
    };
    // The knob's own step, taken downwards where upwards would leave its bounds.
    auto step_of = [](const Knob& kb, double v0) { return v0 + kb.step > kb.hi ? -kb.step : kb.step; };
    LsqOptions lo;
    lo.max_iterations = max_iter;
    lo.function_tolerance = 1e-9;
    least_squares(knobs, eval, step_of, lo, R, &J);
}

// Measured positions a rig model can describe, or a DataError that says what is wrong and what to try: a
// position beyond the rail's travel (a unit slip, mm as m) or a record that runs through the bumper.
void check_plausible(const MeasuredData& data, const Model& m, const FitOptions& o) {
    if (m.p.stiffness_id == "duffing") return;   // data units: no rail, no bumper
    double x_max = 0;
    std::size_t i_max = 0;
    for (std::size_t i = 0; i < data.x.size(); ++i)
        if (std::abs(data.x[i]) > x_max) {
            x_max = std::abs(data.x[i]);
            i_max = i;
        }
    auto where = [&](std::size_t i) {
        return data.source + (i < data.line.size() ? ": line " + std::to_string(data.line[i]) : std::string()) + ": ";
    };
    if (x_max > kRailHalfTravel) {
        std::ostringstream msg;
        msg << where(i_max) << "x = " << data.x[i_max] << " m lies beyond the rail's travel (|x| <= " << kRailHalfTravel << " m)";
        if (x_max < 1e3 * kRailHalfTravel) msg << "; positions in mm? --x-scale 1e-3";
        else if (x_max < 1e6 * kRailHalfTravel) msg << "; positions in um? --x-scale 1e-6";
        else msg << "; check the position column and its unit (--x-col, --x-scale)";
        throw DataError(msg.str());
    }
    const bool xI_fitted = o.fit_baseline && std::find(o.fit_params.begin(), o.fit_params.end(), "xI") != o.fit_params.end();
    if (!m.p.has_bumper() || xI_fitted) return;
    // The bumper stops the cart at xI: mm of sensor offset or bumper shift are effects the fit looks
    // for; a record that lives beyond it is another geometry, sign or unit.
    constexpr double kMargin = 10e-3;   // [m]: twenty times the recovery matrix's bumper offset
    std::size_t beyond = 0, i_far = 0;
    for (std::size_t i = 0; i < data.x.size(); ++i)
        if (data.x[i] > m.p.xI + kMargin) {
            if (beyond++ == 0 || data.x[i] > data.x[i_far]) i_far = i;
        }
    if (beyond > data.x.size() / 100) {
        std::ostringstream msg;
        msg << where(i_far) << "x = " << data.x[i_far] << " m: " << beyond << " of " << data.x.size()
            << " samples lie more than " << kMargin * 1e3 << " mm beyond the bumper at xI = " << m.p.xI
            << " m, which stops the cart there. Is the bumper elsewhere (--xI, or --baseline fit --fit-params xI), or is "
               "x's sign or unit wrong (--x-scale -1, 1e-3)?";
        throw DataError(msg.str());
    }
}

// The output-error fit uses samples [a, end]; the rest of the record validates it.
std::size_t oe_fit_end(const Prep& pr, std::size_t a, std::size_t max_samples) {
    const std::size_t last = pr.run_last(a);   // a free run stays within its run
    return std::min(last, a + std::min(max_samples, (last + 1 - a) / 2));
}

// RMS of a free run against the measured x over samples [from, end) where the run is defined; -1 if none.
double free_run_rms(const std::vector<double>& fr, const std::vector<double>& x, std::size_t from = 0) {
    double s = 0;
    std::size_t c = 0;
    for (std::size_t i = from; i < fr.size(); ++i)
        if (std::isfinite(fr[i])) {
            s += (fr[i] - x[i]) * (fr[i] - x[i]);
            ++c;
        }
    return c ? std::sqrt(s / static_cast<double>(c)) : -1.0;
}


// Levenberg-Marquardt on the free-run simulation error (input-forced data only: there a free run over the
// record is meaningful, and it weighs the resonance the way the benchmark's simulation error does).
void lm_simulation(const Prep& pr, Model& m, std::vector<Knob>& knobs, int max_iter, double rtol) {
    const auto p = static_cast<Eigen::Index>(knobs.size());
    if (p == 0) return;
    const MeasuredData& d = *pr.data;
    // The fit runs on the first stretch of at most kOeSamples samples (a free run is sequential; this bounds the
    // cost of each Jacobian), from the first usable sample.
    constexpr std::size_t kOeSamples = 30000;
    const std::size_t a = usable_start(pr, 0, pr.n - 2);
    const std::size_t b = oe_fit_end(pr, a, kOeSamples);
    // The fit needs the simulation far more accurate than the sensor, not to the reporting tolerance.
    const double fit_rtol = std::max(rtol, 1e-6);
    auto err = [&](Eigen::VectorXd& e) {
        const std::vector<double> fr = simulate_window(pr, m, a, b, false, fit_rtol);
        e.resize(static_cast<Eigen::Index>(b - a + 1));
        double ss = 0;
        for (std::size_t i = 0; i + a <= b; ++i) {
            const double r = i < fr.size() && std::isfinite(fr[i]) ? fr[i] - d.x[a + i] : 0.0;
            e[static_cast<Eigen::Index>(i)] = r;
            ss += r * r;
        }
        return std::isfinite(ss) ? ss : INFINITY;
    };
    auto step_of = [](const Knob& kb, double v0) {
        const double h = std::max(1e-5 * std::abs(v0), kb.step);
        return v0 + h > kb.hi ? -h : h;
    };
    // A real record's free-run error has outliers (saturated samples, glitches, a slip between the wells):
    // Huber's loss beyond 3 robust standard deviations of the starting error keeps them from steering the fit.
    Eigen::VectorXd e;
    err(e);
    std::vector<double> a_e(static_cast<std::size_t>(e.size()));
    for (Eigen::Index i = 0; i < e.size(); ++i) a_e[static_cast<std::size_t>(i)] = std::abs(e[i]);
    LsqOptions lo;
    lo.max_iterations = max_iter;
    lo.function_tolerance = 1e-7;
    lo.huber_delta = 3.0 * 1.4826 * std::max(median(a_e), 1e-300);
    least_squares(knobs, err, step_of, lo, e);
}

// The impact laws' small fit: minimises sum f(theta)^2 within bounds; returns the covariance scale (J'J)^-1.
Eigen::MatrixXd lm_small(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, Eigen::VectorXd& th,
                         const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
    const Eigen::Index p = th.size();
    std::vector<Knob> knobs;
    for (Eigen::Index k = 0; k < p; ++k) knobs.push_back({&th[k], 1e-6, lo[k], hi[k], "theta"});
    auto eval = [&](Eigen::VectorXd& r) {
        r = f(th);
        const double ss = r.squaredNorm();
        return std::isfinite(ss) ? ss : INFINITY;
    };
    auto step_of = [](const Knob& kb, double v) {
        const double h = 1e-6 * std::max(1.0, std::abs(v));
        return v + h > kb.hi ? -h : h;
    };
    LsqOptions o;
    o.max_iterations = 100;
    o.function_tolerance = 1e-12;
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    least_squares(knobs, eval, step_of, o, r, &J);
    Eigen::MatrixXd A = J.transpose() * J;
    for (Eigen::Index k = 0; k < p; ++k) A(k, k) += 1e-12 * A(k, k) + 1e-300;
    return A.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
}

// Integrated correlation time of a residual series, by batch means over blocks of B rows (1 for white noise).
double corr_time(const Eigen::VectorXd& e, int B) {
    const Eigen::Index n = e.size(), b = std::max(1, B);
    double blocks = 0;
    for (Eigen::Index a = 0; a < n; a += b) {
        const double s = e.segment(a, std::min(b, n - a)).sum();
        blocks += s * s;
    }
    const double all = e.squaredNorm();
    return all > 0 ? std::max(1.0, blocks / all) : 1.0;
}

// Significance of a group of columns by the rise of the sum of squares if they were held at their null
// values and the others refitted (linearised: delta' S delta with S the Schur complement), against the
// residual's variance and correlation time. Robust where the group is nearly collinear with the rest.
double group_z_dss(const Eigen::MatrixXd& J, const Eigen::VectorXd& R, const std::vector<int>& sub, const Eigen::VectorXd& delta, int B) {
    const Eigen::Index p = J.cols(), q = static_cast<Eigen::Index>(sub.size());
    std::vector<int> others;
    for (Eigen::Index k = 0; k < p; ++k)
        if (std::find(sub.begin(), sub.end(), static_cast<int>(k)) == sub.end()) others.push_back(static_cast<int>(k));
    Eigen::MatrixXd Jg(J.rows(), q), Jo(J.rows(), static_cast<Eigen::Index>(others.size()));
    for (Eigen::Index i = 0; i < q; ++i) Jg.col(i) = J.col(sub[static_cast<std::size_t>(i)]);
    for (std::size_t i = 0; i < others.size(); ++i) Jo.col(static_cast<Eigen::Index>(i)) = J.col(others[i]);
    Eigen::MatrixXd S = Jg.transpose() * Jg;
    if (!others.empty()) {
        Eigen::MatrixXd Goo = Jo.transpose() * Jo;
        for (Eigen::Index i = 0; i < Goo.rows(); ++i) Goo(i, i) += 1e-10 * Goo(i, i) + 1e-300;
        const Eigen::MatrixXd Gog = Jo.transpose() * Jg;
        S -= Gog.transpose() * Goo.ldlt().solve(Gog);
    }
    const double dss = std::max(0.0, delta.dot(S * delta));
    const double s2 = R.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, R.size()));
    const double tau = corr_time(R, B);
    return chi2_to_z(dss / std::max(s2 * tau, 1e-300), static_cast<int>(q));
}

// Knobs for the fitted base parameters, with their physical bounds: mass, damping, friction and unbalance
// never negative, the input gain keeps the sign it starts with, the magnets' b2 keeps F_SA's denominator
// positive.
std::vector<Knob> base_knobs(Model& m, const std::vector<std::string>& names) {
    std::vector<Knob> knobs;
    for (const auto& b : base_params(m, names)) {
        double lo = -1e12, hi = 1e12;
        if (b.name == "c" || b.name == "T" || b.name == "m0e" || b.name == "m") lo = 0;
        if (b.name == "gain") (*b.value >= 0 ? lo : hi) = 0;
        if (b.name == "b2") lo = -50;
        knobs.push_back({b.value, std::max(1e-4 * std::abs(*b.value), 1e-6), lo, hi, b.name});
    }
    return knobs;
}

// Knobs for the free parameters of effect instance `inst` as candidate `c` fits them, with their bounds.
void effect_knobs(const Candidate& c, EffectInstance& inst, std::vector<Knob>& knobs) {
    for (std::size_t li = 0; li < c.free.size(); ++li) {
        const auto pi = static_cast<std::size_t>(c.free[li]);
        knobs.push_back({&inst.p[pi], c.step[li], c.law->fit.lo[pi], c.law->fit.hi[pi], c.law->names[pi]});
    }
}

// A base parameter's value in model m.
double base_value(const Model& m, const char* name) {
    Model copy = m;
    return *base_params(copy, {name}).front().value;
}

// The knob of a base-changing candidate (cart_mass: m), its bounds about the base model's value.
Knob base_change_knob(const Candidate& c, Model& m, const Model& base) {
    const double at_base = base_value(base, c.base);
    return {base_params(m, {c.base}).front().value, c.step[0], at_base + c.lo, at_base + c.hi, c.base};
}

// The value of a base-changing candidate's parameter in model m (what it moved from the base model).
double base_change(const Candidate& c, const Model& m, const Model& base) { return base_value(m, c.base) - base_value(base, c.base); }

// Knobs of the effects a fit added to model m (the effects after base's, and a base parameter a
// base-changing candidate moved), as their candidates fit them.
std::vector<Knob> found_effect_knobs(Model& m, const Model& base, const std::vector<Candidate>& cands) {
    std::vector<Knob> knobs;
    for (std::size_t k = base.p.effects.size(); k < m.p.effects.size(); ++k)
        for (const auto& c : cands)
            if (c.law && c.id == m.p.effects[k].law->id) {
                effect_knobs(c, m.p.effects[k], knobs);
                break;
            }
    for (const auto& c : cands)
        if (c.base && base_change(c, m, base) != 0.0) knobs.push_back(base_change_knob(c, m, base));
    return knobs;
}

// Why a model is not physical, or empty: what a fit must never write.
std::string unphysical(const Model& m) {
    try {
        validate(m.p, "fitted model");
    } catch (const ParamError& e) {
        return e.what();
    }
    for (const auto& e : m.p.effects) {   // each law's physical bounds on the parameters a fit moves
        const EffectFitHint& h = e.law->fit;
        for (int k = 0; k < h.n_free; ++k) {
            const auto i = static_cast<std::size_t>(h.free[static_cast<std::size_t>(k)]);
            if (!(e.p[i] >= h.lo[i] && e.p[i] <= h.hi[i]))
                return std::string(e.law->id) + "." + e.law->names[i] + " = " + std::to_string(e.p[i]) + " outside [" +
                       std::to_string(h.lo[i]) + ", " + std::to_string(h.hi[i]) + "]";
        }
    }
    return {};
}

ImpactLawError impact_error(const Prep& pr, const PredictedImpacts& pred) {
    ImpactLawError e;
    double sk = 0, sd = 0;
    std::size_t nk = 0;
    std::vector<double> lev;
    for (std::size_t k = 0; k < pr.impacts.size(); ++k) {
        if (!pred.ok[k]) continue;
        const ImpactObs& im = pr.impacts[k];
        const ImpactObs& sm = pred.obs[k];
        if (im.v_minus > 0.02) {
            const double dk = apparent_kappa(im) - apparent_kappa(sm);
            sk += dk * dk;
            ++nk;
        }
        const double dd = (im.t_out - im.t_in) - (sm.t_out - sm.t_in);
        sd += dd * dd;
        lev.push_back(im.level - sm.level);
        ++e.impacts;
    }
    if (e.impacts == 0) return e;
    e.kappa_rms = nk ? std::sqrt(sk / static_cast<double>(nk)) : 0.0;
    e.duration_rms_s = std::sqrt(sd / static_cast<double>(e.impacts));
    e.level_offset_m = median(lev);
    return e;
}

std::vector<std::pair<std::string, double>> named(const EffectInstance& e) {
    std::vector<std::pair<std::string, double>> v;
    for (std::size_t k = 0; k < kMaxLawParams && e.law->names[k]; ++k) v.emplace_back(e.law->names[k], e.p[k]);
    return v;
}

// The changes a fit made to the model given, in order: each step's model, the effects it holds and its
// held-out shooting RMS. The final gate walks back from the last step until the model is not worse than the
// model given on any error the report prints.
struct ChainStep {
    std::string what;
    Model model;
    std::vector<FoundEffect> found;
    double held_out_rms_m = -1;
    bool baseline = false;   // a step of the baseline fit (before any effect)
};
using Chain = std::vector<ChainStep>;

double rms_of(const Eigen::VectorXd& R) { return R.size() ? std::sqrt(R.squaredNorm() / static_cast<double>(R.size())) : 0.0; }

// The flat-top shift that puts a model's simulated impacts on the measured ones, from the impacts with
// use[k] set: the median of the paired level differences, corrected until the moved bumper's own forces
// (and a compliant contact's penetration with them) are accounted for. Returns the shift of xI [m]; the model
// is left with it.
double fit_bumper_shift(const Prep& pr, Model& m, const std::vector<char>& use, double rtol, double tol) {
    const double g = m.sensor_gain();
    double dx = 0;
    for (int it = 0; it < 4; ++it) {
        const PredictedImpacts pred = predict_impacts(pr, m, rtol);
        std::vector<double> miss;
        for (std::size_t k = 0; k < pr.impacts.size(); ++k)
            if (use[k] && pred.ok[k]) miss.push_back((pr.impacts[k].level - pred.obs[k].level) / g);
        if (miss.size() < 3) break;
        const double step = median(miss);
        dx += step;
        m.p.xI += step;
        if (std::abs(step) < tol) break;
    }
    return dx;
}

// An impact law (impact_duration or restitution) refitted to the impacts with use[k] set, in the form the
// whole record chose (a constant when its decay rate is 0, else the full law from the whole record's values).
std::vector<std::pair<std::string, double>> refit_impact_law(const Prep& pr, const Model& m, const FoundEffect& f,
                                                             const std::vector<char>& use) {
    const ImpactLawData d = impact_law_data(pr, m, f.id == "impact_duration", use);
    const auto nm = impact_law_names(d.dwell);
    auto value = [&](const char* k) {
        for (const auto& [n, v] : f.parameters)
            if (n == k) return v;
        return 0.0;
    };
    if (d.obs.size() < 3) return f.parameters;
    double mean = 0;
    for (double v : d.obs) mean += v;
    mean /= static_cast<double>(d.obs.size());
    if (value(nm[2]) == 0.0) return {{nm[0], mean}, {nm[1], mean}, {nm[2], 0.0}};
    Eigen::VectorXd th(3), lo(3), hi(3);
    th << value(nm[0]), value(nm[1]), value(nm[2]);
    lo << 0, 0, 0;
    hi << 1.0, 1.0, 50.0;
    lm_small([&](const Eigen::VectorXd& t) { return impact_law_residual(d, t); }, th, lo, hi);
    return {{nm[0], th[0]}, {nm[1], th[1]}, {nm[2], th[2]}};
}

// One-sample t test of mean > 0, as the equivalent standard-normal z (read through F(1, n-1), signed).
double t_test_z(const std::vector<double>& d) {
    const double n = static_cast<double>(d.size());
    if (d.size() < 2) return 0.0;
    double mean = 0, var = 0;
    for (double v : d) mean += v;
    mean /= n;
    for (double v : d) var += (v - mean) * (v - mean);
    var /= (n - 1.0);
    const double t = var > 0 ? mean / std::sqrt(var / n) : (mean > 0 ? 1e6 : -1e6);
    return std::copysign(f_to_z(t * t, 1.0, n - 1.0), t);
}

// The window length [forcing periods] of every held-out judgement: the record's own predictability (measured
// from the data), not the model's, whose error grows from its own faults and would make a periodic record look
// chaotic. A regular record is judged over whole periods; a chaotic one within the doubling time of nearby
// returns; windows short enough that there are about 40 of them (the paired test's power). Where the record is
// too short to measure, `model_horizon` (the model's error growth) decides.
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

// The record cut for held-out checks: windows within the predictability horizon of `m`, and blocks of
// about an eighth of the record alternately in fold 0 and fold 1 (rows and windows by fold).
struct HeldOutSplit {
    Horizon hz;
    double periods = 0;   // window length [forcing periods]
    std::vector<std::pair<std::size_t, std::size_t>> wins;
    std::array<Prep, 2> fold_pr;
    std::array<std::vector<std::size_t>, 2> fold_wins;   // indices into wins
    double t0 = 0, block = 1;
    int fold_of(const Prep& pr, std::size_t i) const { return static_cast<int>(std::floor((pr.data->t[i] - t0) / block)) % 2; }
};
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

// Two models' held-out errors compared window by window: the relative fall of the summed error, and the
// paired z of the fall. The paired test runs over the informative windows, where the two models' errors
// differ by more than a tenth of the window's noise: an impact-law effect changes only the windows with
// impacts in them. The t statistic is read through F(1, n-1), so a few windows need a large and consistent
// fall.
struct Compare { double gain = 0, z = 0, sum_cur = 0, sum_new = 0; };
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

// Whether a change `cand` of model `cur` is better beyond the noise on held-out windows: a paired z >= 3 and
// a fall of the summed error by at least 2 % of its part above the sensor noise.
bool better_beyond_noise(const Prep& pr, const std::vector<std::pair<std::size_t, std::size_t>>& wins, const Compare& c) {
    std::size_t samples = 0;
    for (const auto& [a, b] : wins) samples += b - a + 1;
    const double excess = std::max(c.sum_cur - static_cast<double>(samples) * pr.sigma_x * pr.sigma_x, 0.0);
    return c.z >= 3.0 && c.sum_cur - c.sum_new > 0.02 * excess && c.gain > 1e-3;
}

// Whether an output-error refinement (`refined`) predicts the part of the record its fit did not use better
// than the equation-error values (`before`), by the shooting error over the judging windows (initial states
// fitted) after the samples the refinement was fitted to. A long free run of a chaotic record drifts onto
// another trajectory whatever the model, so the free-run error alone cannot say whether a refinement helped;
// a regular record is judged over long windows, where the equation error's bias at a few samples per period
// shows. No held-out part, no refinement.
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

// Whether the fitted baseline predicts held-out data better than the parameters given (a record forced by
// the unbalance, whose given model is a physical one): each fold's windows simulated with the base
// parameters refitted on the other fold's equation error, against the given model, by the same test as an
// effect. A baseline fit that only matches the equation error (biased at a few samples per period, or
// fitting noise) must not replace the parameters it was given.
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
        std::vector<Knob> knobs = base_knobs(mf, names);
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

// The held-out validation of the effects found (stage 6 of run_fit). The record is cut into blocks of about
// an eighth of its length, alternately in fold 0 and fold 1. For each fold, the force effects' parameters are
// refitted on the equation error of the other fold's rows (an impact-law effect on the other fold's impacts),
// and the model is simulated over the fold's windows, each as long as the record's
// predictability horizon (a chaotic record cannot be judged by a long free run). Effects are tried in the
// order they were found; each must lower the summed held-out error against the model without it, with a
// paired z >= 3 over the windows and by at least 2 % of the error above the sensor noise.
void validate_effects(const Prep& pr, const Model& base, const std::vector<Candidate>& cands, const FitOptions& o,
                      const std::vector<std::string>& base_names, const SentenceContext& sc, FitReport& rep, Model& after,
                      Chain& chain) {
    // A fitted baseline of a record forced by the unbalance is refitted with the effects (per fold, and on the
    // whole record at the end): base parameters fitted without an effect have absorbed what they could of it
    // (a spring rate bent by a missing even stiffness), and those values beside the effect's make neither
    // model. An input-forced record keeps its output-error baseline (refined on the free-run error).
    const bool refit_base = o.fit_baseline && pr.phi_forced && !base_names.empty();
    // The horizon of the best model at hand (the baseline with every effect found): a wrong baseline's error
    // grows from its own fault, not from the record's instability. An unphysical candidate falls back to the
    // baseline.
    const HeldOutSplit sp = held_out_split(pr, unphysical(after).empty() ? after : base, o.rtol);
    rep.horizon_growth = sp.hz.growth;
    rep.horizon_periods = sp.periods;
    const auto& wins = sp.wins;
    rep.validation_windows = wins.size();
    const std::array<Prep, 2>& fold_pr = sp.fold_pr;
    const std::array<std::vector<std::size_t>, 2>& fold_wins = sp.fold_wins;
    auto fold_of = [&](std::size_t i) { return sp.fold_of(pr, i); };

    // Held-out SSE of each window: fold f's windows simulated with model_for[f], its force effects refitted
    // on the other fold's rows (the impact-law effects come refitted on the other fold's impacts).
    auto held_out_folds = [&](const std::array<Model, 2>& model_for) {
        std::vector<double> e(wins.size(), INFINITY);
        for (std::size_t f = 0; f < 2; ++f) {
            Model mf = model_for[f];
            std::vector<Knob> knobs = found_effect_knobs(mf, base, cands);
            if (refit_base)
                for (const Knob& k : base_knobs(mf, base_names)) knobs.push_back(k);
            const Prep& fit_on = fold_pr[1 - f];
            if (!knobs.empty() && fit_on.rows.size() >= 20) {
                Eigen::VectorXd R;
                Eigen::MatrixXd J;
                lm_residual(fit_on, mf, knobs, 15, R, J);
            }
            std::vector<std::pair<std::size_t, std::size_t>> sub;
            for (std::size_t w : fold_wins[f]) sub.push_back(wins[w]);
            const std::vector<double> ef = window_sse(pr, mf, sub, o.refine_shooting, o.rtol);
            for (std::size_t k = 0; k < sub.size(); ++k) e[fold_wins[f][k]] = ef[k];
        }
        return e;
    };
    auto held_out = [&](const Model& m) { return held_out_folds({m, m}); };
    // Impacts by fold (of their entry sample), for refitting an impact-law effect on one fold only.
    std::array<std::vector<char>, 2> impacts_in;
    for (std::size_t f = 0; f < 2; ++f) {
        impacts_in[f].assign(pr.impacts.size(), 0);
        for (std::size_t k = 0; k < pr.impacts.size(); ++k) impacts_in[f][k] = fold_of(pr.impacts[k].i_first) == static_cast<int>(f);
    }
    std::array<std::vector<char>, 2> strays_in;
    for (std::size_t f = 0; f < 2; ++f) {
        strays_in[f].assign(pr.stray.size(), 0);
        for (std::size_t k = 0; k < pr.stray.size(); ++k) strays_in[f][k] = fold_of(pr.stray[k].i_first) == static_cast<int>(f);
    }
    std::size_t samples = 0;
    for (const auto& [a, b] : wins) samples += b - a + 1;
    auto compare = [&](const std::vector<double>& cur, const std::vector<double>& cand) { return compare_held_out(pr, wins, cur, cand); };

    std::vector<FoundEffect> found = std::move(rep.effects_found);
    rep.effects_found.clear();
    Model cur = base;
    const std::vector<double> e_base = wins.size() >= 12 ? held_out(base) : std::vector<double>{};
    std::vector<double> e_cur = e_base;
    std::size_t tried = 0;
    // An effect turned down for too small a fall is tried again once another has been kept: validated alone, a
    // force's per-fold refit absorbs the error of a partner effect not yet in the model (an even stiffness
    // and a phase offset, say) and its fall looks small. It must pass the same test against the new model.
    std::vector<std::size_t> queue(found.size());
    std::iota(queue.begin(), queue.end(), std::size_t{0});
    struct TooSmall {
        std::size_t effect, kept_before;   // index into found; effects kept when it was tried
        RejectedEffect rej;
    };
    std::vector<TooSmall> too_small;
    // The held-out shooting RMS of a model's windows (their SSE summed).
    auto total = [&](const std::vector<double>& e) {
        double s = 0;
        for (double v : e) s += std::isfinite(v) ? v : 0.0;
        return samples ? std::sqrt(s / static_cast<double>(samples)) : 0.0;
    };
    Chain kept;   // the model after each effect kept, in order, with its held-out RMS
    // A kept step's name in the chain, with the held-out fall that kept it.
    auto step_name = [](const std::string& what, const Compare& c) {
        char buf[96];
        std::snprintf(buf, sizeof buf, " (held-out simulation error %s by %.2f %%)", c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain));
        return what + buf;
    };
    // Effects finally turned down for too small a fall (index into found, into effects_rejected).
    constexpr std::size_t kTaken = static_cast<std::size_t>(-1);
    std::vector<std::pair<std::size_t, std::size_t>> small_final;
    auto f_ok_for_pair = [](const FoundEffect& f) { return f.evidence != "impact law" && f.id.rfind("unexplained", 0) != 0; };
    for (int pass = 0; pass < 3 && !queue.empty(); ++pass) {
        too_small.clear();
        for (std::size_t fi : queue) {
            FoundEffect& f = found[fi];
            if (pr.progress)   // the validation's share of the fit, effect by effect
                pr.progress->fraction.store(0.34 + 0.46 * static_cast<double>(std::min(++tried, found.size())) / static_cast<double>(found.size() + 1),
                                            std::memory_order_relaxed);
            RejectedEffect rej{f.id, "", 0, 0, f.parameters};
            if (e_cur.empty()) {
                rej.reason = "too few windows to validate it on held-out data";
                rep.effects_rejected.push_back(std::move(rej));
                continue;
            }
            Model cand = cur;
            if (f.evidence == "impact law" && pr.impacts.size() >= 3) {
                // Refitted on every impact against the model it joins (the stage fitted it against the model
                // with every effect found, some of which may have gone): the model kept is the model validated.
                const std::vector<char> all(pr.impacts.size(), 1);
                if (f.id == "bumper_offset") f.parameters = {{"dx", fit_bumper_shift(pr, cand, all, o.rtol, 0.05 * pr.sigma_x)}};
                else apply_effect(cand, f.id, f.parameters = refit_impact_law(pr, cur, f, all));
                f.sentence = sentence(f.id, cur, f.parameters, f.sigma, sc);
                rej.parameters = f.parameters;
                // A shift of the flat tops must still stand out as the stage required.
                const double dx = f.parameters.front().second, se = f.sigma.empty() ? 0.0 : f.sigma.front().second;
                if (f.id == "bumper_offset" && !(std::abs(dx) >= o.z_threshold * se && std::abs(dx) > 2.0 * pr.sigma_x + 1e-7)) {
                    char buf[200];
                    std::snprintf(buf, sizeof buf, "refitted against the model it joins, the shift is %.3g +/- %.2g m: not significant", dx, se);
                    rej.reason = buf;
                    too_small.push_back({fi, rep.effects_found.size(), std::move(rej)});
                    continue;
                }
            } else if (f.evidence == "stray impacts") {
                // Refitted against the model it joins, as an impact law is.
                double se = 0;
                const auto values = end_stop_values(pr, cur, {}, o.rtol, &se);
                if (!values.empty()) {
                    f.parameters = values;
                    f.sigma.front().second = se;
                }
                f.sentence = sentence(f.id, cur, f.parameters, f.sigma, sc) + "; seen in " + std::to_string(pr.stray.size()) +
                             " reversals the model cannot make";
                rej.parameters = f.parameters;
                apply_effect(cand, f.id, f.parameters);
            } else {
                apply_effect(cand, f.id, f.parameters);
            }
            const std::string why = unphysical(cand);
            if (!why.empty()) {
                rej.reason = "unphysical: " + why;
                rep.effects_rejected.push_back(std::move(rej));
                continue;
            }
            std::vector<double> e_new;
            if (f.evidence == "impact law") {
                // Refitted on the other fold's impacts, for each fold in turn.
                std::array<Model, 2> per_fold{cur, cur};
                for (std::size_t ff = 0; ff < 2; ++ff) {
                    const std::vector<char>& use = impacts_in[1 - ff];
                    // A fold with fewer than three impacts cannot refit the law: there the whole record's values
                    // stand (the windows are still held out).
                    if (std::count(use.begin(), use.end(), 1) < 3) per_fold[ff] = cand;
                    else if (f.id == "bumper_offset") fit_bumper_shift(pr, per_fold[ff], use, o.rtol, 0.05 * pr.sigma_x);
                    else apply_effect(per_fold[ff], f.id, refit_impact_law(pr, cur, f, use));
                }
                e_new = held_out_folds(per_fold);
            } else if (f.evidence == "stray impacts") {
                // The stop fitted to the other fold's reversals, for each fold in turn.
                std::array<Model, 2> per_fold{cand, cand};
                for (std::size_t ff = 0; ff < 2; ++ff) {
                    const auto values = end_stop_values(pr, cur, strays_in[1 - ff], o.rtol);
                    if (values.empty()) continue;   // too few there: the whole record's values stand
                    per_fold[ff] = cur;
                    apply_effect(per_fold[ff], f.id, values);
                }
                e_new = held_out_folds(per_fold);
            } else {
                e_new = held_out(cand);
            }
            const Compare c = compare(e_cur, e_new);
            f.validation_gain = rej.validation_gain = c.gain;
            f.validation_z = rej.validation_z = c.z;
            if (!better_beyond_noise(pr, wins, c)) {
                char buf[200];
                std::snprintf(buf, sizeof buf, "held-out simulation error %s by %.2f %% (paired z = %.1f over %zu windows): not better beyond the noise",
                              c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain), c.z, wins.size());
                rej.reason = buf;
                too_small.push_back({fi, rep.effects_found.size(), std::move(rej)});
                continue;
            }
            cur = std::move(cand);
            e_cur = e_new;
            rep.effects_found.push_back(f);
            kept.push_back({step_name("added " + f.id, c), cur, rep.effects_found, total(e_cur), false});
        }
        // Again only those tried before the last effect kept (the others met the same model).
        queue.clear();
        for (const auto& t : too_small)
            if (t.kept_before < rep.effects_found.size()) queue.push_back(t.effect);
        for (auto& t : too_small)
            if (pass == 2 || t.kept_before == rep.effects_found.size()) {
                if (f_ok_for_pair(found[t.effect])) small_final.push_back({t.effect, rep.effects_rejected.size()});
                rep.effects_rejected.push_back(std::move(t.rej));
            }
    }
    // Two force effects that act together (a resistance stronger in one direction: a constant force and a
    // Coulomb friction) each look too small alone, since each one's per-fold refit absorbs what it can of
    // the other. Pairs of them are tried jointly: the pair must pass the same test, and each member must
    // add beyond the noise to the other alone.
    for (std::size_t a = 0; a < small_final.size() && !e_cur.empty(); ++a)
        for (std::size_t b = a + 1; b < small_final.size(); ++b) {
            FoundEffect& fa = found[small_final[a].first];
            FoundEffect& fb = found[small_final[b].first];
            if (small_final[a].second == kTaken || small_final[b].second == kTaken) continue;
            Model both = cur, only_a = cur, only_b = cur;
            apply_effect(both, fa.id, fa.parameters);
            apply_effect(both, fb.id, fb.parameters);
            apply_effect(only_a, fa.id, fa.parameters);
            apply_effect(only_b, fb.id, fb.parameters);
            if (!unphysical(both).empty()) continue;
            const std::vector<double> e_both = held_out(both);
            const Compare c = compare(e_cur, e_both);
            if (!better_beyond_noise(pr, wins, c)) continue;
            const Compare ca = compare(held_out(only_b), e_both), cb = compare(held_out(only_a), e_both);
            if (!better_beyond_noise(pr, wins, ca) || !better_beyond_noise(pr, wins, cb)) continue;
            cur = std::move(both);
            e_cur = e_both;
            for (const auto& [fi, ri] : {small_final[a], small_final[b]}) {
                FoundEffect& f = found[fi];
                f.validation_gain = c.gain;
                f.validation_z = c.z;
                rep.effects_found.push_back(f);
                rep.effects_rejected[ri].id.clear();   // no longer turned down
            }
            small_final[a].second = small_final[b].second = kTaken;
            kept.push_back({step_name("added " + fa.id + " and " + fb.id + " together", c), cur, rep.effects_found, total(e_cur), false});
        }
    rep.effects_rejected.erase(std::remove_if(rep.effects_rejected.begin(), rep.effects_rejected.end(),
                                              [](const RejectedEffect& r) { return r.id.empty(); }),
                               rep.effects_rejected.end());
    if (!rep.effects_found.empty()) {
        const Compare c = compare(e_base, e_cur);
        if (!(c.sum_new < c.sum_cur)) {   // never a worse model than the baseline
            for (auto& f : rep.effects_found)
                rep.effects_rejected.push_back({f.id, "the model with every effect does not beat the baseline on held-out data", c.gain, c.z, f.parameters});
            rep.effects_found.clear();
            cur = base;
            e_cur = e_base;
            kept.clear();
        }
    }
    for (auto& k : kept) chain.push_back(std::move(k));
    bool refitted = false;
    // The kept force effects were fitted jointly with the rejected ones (and a fitted baseline of a record
    // forced by the unbalance without them): refit them on the whole record (equation error; an input-forced
    // record keeps its output-error values when nothing was dropped).
    if ((!rep.effects_rejected.empty() || refit_base) && !rep.effects_found.empty() && pr.phi_forced) {
        Model refit = cur;
        std::vector<Knob> knobs = found_effect_knobs(refit, base, cands);
        if (refit_base)
            for (const Knob& k : base_knobs(refit, base_names)) knobs.push_back(k);
        if (!knobs.empty()) {
            Eigen::VectorXd R;
            Eigen::MatrixXd J;
            lm_residual(pr, refit, knobs, 20, R, J);
            if (unphysical(refit).empty()) {
                cur = refit;
                refitted = true;
            }
        }
        for (auto& f : rep.effects_found) {
            for (const auto& e : cur.p.effects)
                if (f.id == e.law->id) f.parameters = named(e);
            for (const auto& c : cands)
                if (c.base && f.id == c.id) {
                    f.parameters = {{c.param, base_change(c, cur, base)}};
                    f.sentence = sentence(f.id, base, f.parameters, f.sigma, sc);
                }
        }
    }
    if (!rep.effects_found.empty() && refitted) {
        const double h = chain.empty() ? -1 : chain.back().held_out_rms_m;
        chain.push_back({"the effects refitted on the whole record", cur, rep.effects_found, h, false});
    }
    rep.validation_rms_before_m = total(e_base);
    rep.validation_rms_after_m = total(e_cur);
    after = cur;
}

// Stage 1: the baseline. With fit_baseline, the base parameters `base_names` are fitted to the equation
// error (the input's polarity found, a bistable model kept bistable) and, for an input-forced record,
// refined on the free-run simulation error when that predicts the held-out part better. Throws ParamError
// for a fit that leaves the physical range.
Model fit_baseline_stage(const Prep& pr, const Model& model0, const FitOptions& o, const std::vector<std::string>& base_names,
                         FitReport& rep, Model& equation_error_base) {
    Model base = model0;
    Eigen::VectorXd R0;
    Eigen::MatrixXd Jtmp;
    if (o.fit_baseline) {
        std::vector<Knob> knobs = base_knobs(base, base_names);
        // A bistable starting model stays bistable: a fit that merges the wells into one is a fit to the
        // wrong attractor (a chaotic record's free run, say), and that stage is undone.
        const std::size_t wells0 = well_report(base, {}, pr).wells.size();
        auto keeps_wells = [&](const Model& m, const char* stage) {
            const std::size_t w = well_report(m, {}, pr).wells.size();
            if (wells0 == 2 && w < 2) {
                rep.notes.push_back(std::string("the ") + stage + " fit of the baseline would merge its two wells into " +
                                    (w ? "one" : "none") + "; that stage is undone");
                return false;
            }
            return true;
        };
        // A first pass from the starting values (linear parameters converge in one step), then refine.
        const Model start = base;
        lm_residual(pr, base, knobs, 40, R0, Jtmp);
        // The input gain keeps its sign in a fit; which sign the record has (a voltage's polarity is a
        // convention) is decided here, once: if the gain ran into zero, the other sign is tried.
        const bool fits_gain = std::find(base_names.begin(), base_names.end(), "gain") != base_names.end();
        if (fits_gain && start.p.input_gain != 0.0 && std::abs(base.p.input_gain) < 1e-9 * std::abs(start.p.input_gain)) {
            Model flipped = start;
            flipped.p.input_gain = -start.p.input_gain;
            std::vector<Knob> kf = base_knobs(flipped, base_names);
            Eigen::VectorXd Rf;
            lm_residual(pr, flipped, kf, 40, Rf, Jtmp);
            if (Rf.squaredNorm() < R0.squaredNorm()) {
                base = flipped;
                R0 = Rf;
                rep.notes.push_back("the input acts with the opposite sign to the starting gain's");
            }
            knobs = base_knobs(base, base_names);
        }
        if (!keeps_wells(base, "equation-error")) base = start;
        equation_error_base = base;
        // Input-forced data: refine by the simulation error, which the equation error at a few samples per
        // period of the resonance cannot match.
        if (!pr.phi_forced) {
            const Model ee = base;
            knobs = base_knobs(base, base_names);
            lm_simulation(pr, base, knobs, 30, o.rtol);
            if (!keeps_wells(base, "output-error")) {
                base = ee;
            } else if (!refinement_predicts_better(pr, base, ee, o.rtol)) {
                // A chaotic record's free run, or a fit of what the held-out tail does not show: not the rig.
                rep.notes.push_back("the output-error refinement of the baseline does not predict the tail of the record it was not "
                                    "fitted to better (a consistent fall over the judging windows, paired z >= 2); the "
                                    "equation-error baseline is kept");
                base = ee;
            } else {
                rep.notes.push_back("baseline refined on the free-run simulation error (output error)");
            }
        }
        if (const std::string why = unphysical(base); !why.empty())
            throw ParamError("the baseline fit leaves the physical range (" + why + "); fix the starting values or --fit-params");
    }
    return base;
}

// Stage 5: the impact law. Each measured impact is compared with the same impact simulated with the model
// (predict_impacts): a bumper offset moves the flat tops, a finite impact duration or another restitution
// shifts or tilts the paired differences with the approach speed. What is found is applied to `after`.
void impact_law_stage(const Prep& pr, const FitOptions& o, const SentenceContext& sc, Model& after, FitReport& rep) {
    // So a compliant bumper's apparent penetration or a sampled flat top is never mistaken for an effect.
    if (after.bumper() && pr.impacts.size() >= 3) {
        const double g = after.sensor_gain();
        PredictedImpacts pred = predict_impacts(pr, after, o.rtol);
        std::vector<double> dlev;
        for (std::size_t k = 0; k < pr.impacts.size(); ++k)
            if (pred.ok[k]) dlev.push_back((pr.impacts[k].level - pred.obs[k].level) / g);
        const std::size_t ni = dlev.size();
        if (ni >= 3) {
            const double med = median(dlev);
            std::vector<double> dev;
            for (double l : dlev) dev.push_back(std::abs(l - med));
            const double se = std::max(1.2533 * 1.4826 * median(dev), 0.3 * pr.sigma_x) / std::sqrt(static_cast<double>(ni));
            const double delta = med;
            if (std::abs(delta) / se >= o.z_threshold && std::abs(delta) > 2.0 * pr.sigma_x + 1e-7) {
                double sb = 0, sa = 0;
                for (double l : dlev) {
                    sb += l * l;
                    sa += (l - med) * (l - med);
                }
                FoundEffect f;
                f.id = "bumper_offset";
                f.evidence = "impact law";
                f.explained_fraction = sb > 0 ? 1.0 - sa / sb : 0.0;
                f.parameters = {{"dx", delta}};
                f.sigma = {{"dx", se}};
                f.z = std::abs(delta) / se;
                // The shift that puts the simulated flat tops on the measured ones: the forces at the moved
                // bumper differ, and a compliant contact's apparent penetration with them.
                const Model at_nominal = after;
                const double dx = fit_bumper_shift(pr, after, std::vector<char>(pr.impacts.size(), 1), o.rtol, 0.05 * se);
                pred = predict_impacts(pr, after, o.rtol);
                f.parameters = {{"dx", dx}};
                f.z = std::abs(dx) / se;
                f.sentence = sentence("bumper_offset", at_nominal, f.parameters, f.sigma, sc);
                rep.effects_found.push_back(std::move(f));
            }
        }
        // The dwell time and the restitution against the model's, impact by impact.
        for (const char* which : {"impact_duration", "restitution"}) {
            const bool dur = std::strcmp(which, "impact_duration") == 0;
            // The impacts the model also makes, measured and simulated.
            const ImpactLawData data = impact_law_data(pr, after, dur, pred.ok);
            const ImpactLawData simulated_data = [&] {
                ImpactLawData s;
                for (std::size_t k = 0; k < pr.impacts.size(); ++k)
                    if (pred.ok[k] && (dur || pr.impacts[k].v_minus >= 0.02))
                        s.obs.push_back(dur ? pred.obs[k].t_out - pred.obs[k].t_in : apparent_kappa(pred.obs[k]));
                return s;
            }();
            const std::vector<double>& vm = data.vm;
            const std::vector<double>& obs = data.obs;
            const auto n = static_cast<Eigen::Index>(vm.size());
            if (n < 3) continue;
            const Eigen::VectorXd model_pred = Eigen::Map<const Eigen::VectorXd>(simulated_data.obs.data(), n);
            auto law = [&](const Eigen::VectorXd& th) { return impact_law_residual(data, th); };
            double mean = 0;
            for (double v : obs) mean += v;
            mean /= static_cast<double>(n);
            // A constant first; the full law (value at low speed, at high speed, decay rate) only if the data
            // clearly ask for it.
            Eigen::VectorXd th(3), lo(3), hi(3);
            th << mean, mean, 0.0;
            double ss_const = 0;
            for (double v : obs) ss_const += (v - mean) * (v - mean);
            Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 3);
            C(0, 0) = C(1, 1) = C(0, 1) = C(1, 0) = 1.0 / static_cast<double>(n);
            double sa = ss_const;
            if (n >= 8) {
                Eigen::VectorXd full(3);
                full << mean, mean, 1.0;
                lo << 0, 0, 0;
                hi << 1.0, 1.0, 50.0;
                const Eigen::MatrixXd Cf = lm_small(law, full, lo, hi);
                const double sf = law(full).squaredNorm();
                const double s2f = std::max(sf / (static_cast<double>(n) - 3.0), dur ? std::pow(0.05 * pr.dt, 2) : 1e-4);
                if (chi2_to_z((ss_const - sf) / s2f, 2) >= 3.0) {
                    th = full;
                    C = Cf;
                    sa = sf;
                }
            }
            // The paired differences measured - simulated: an effect shifts them (a constant) or tilts them
            // with the approach speed; under the model they scatter around zero. Wald test on both.
            double sb = 0, vbar = 0;
            for (Eigen::Index i = 0; i < n; ++i) {
                sb += std::pow(obs[static_cast<std::size_t>(i)] - model_pred[i], 2);
                vbar += vm[static_cast<std::size_t>(i)];
            }
            vbar /= static_cast<double>(n);
            Eigen::MatrixXd Xd(n, 2);
            Eigen::VectorXd dd(n);
            for (Eigen::Index i = 0; i < n; ++i) {
                Xd(i, 0) = 1.0;
                Xd(i, 1) = vm[static_cast<std::size_t>(i)] - vbar;
                dd[i] = obs[static_cast<std::size_t>(i)] - model_pred[i];
            }
            Eigen::Matrix2d XtX = Xd.transpose() * Xd;
            XtX(1, 1) += 1e-12 * XtX(0, 0) + 1e-300;
            const Eigen::Vector2d bd = XtX.ldlt().solve(Xd.transpose() * dd);
            const double rss_d = (dd - Xd * bd).squaredNorm();
            const double floor_var = dur ? std::pow(0.05 * pr.dt, 2) : 1e-4;
            const double s2d = std::max(rss_d / std::max(1.0, static_cast<double>(n) - 2.0), 2.0 * floor_var);
            const double W = bd.dot(XtX * bd) / s2d;
            const double z = f_to_z(W / 2.0, 2.0, std::max(1.0, static_cast<double>(n) - 2.0));
            const double s2 = std::max(sa / std::max<double>(1.0, static_cast<double>(n) - 3.0), floor_var);
            // Practical size: the systematic part of the differences, not their scatter.
            const double shift_rms = std::sqrt((Xd * bd).squaredNorm() / static_cast<double>(n));
            const bool practical = dur ? shift_rms > 0.2 * pr.dt : shift_rms > 0.02;
            // A handful of impacts cannot reach the equation error's z; the held-out validation decides.
            if (z >= std::min(o.z_threshold, 3.0) && practical && sb > 0) {
                FoundEffect f;
                f.id = which;
                f.evidence = "impact law";
                f.explained_fraction = 1.0 - sa / sb;
                const auto nm = impact_law_names(dur);
                for (int k = 0; k < 3; ++k) {
                    f.parameters.emplace_back(nm[k], th[k]);
                    f.sigma.emplace_back(nm[k], std::sqrt(std::max(0.0, C(k, k) * s2)));
                }
                f.z = z;
                f.sentence = sentence(which, after, f.parameters, f.sigma, sc);
                apply_effect(after, which, f.parameters);
                rep.effects_found.push_back(std::move(f));
            }
        }
    }
}

// Stages 7 and 8: the final gate, the errors of the model given and of the model written (the equation
// error, multiple shooting at 1 and 10 periods and at the judging horizon, impacts, diagrams, free runs, the
// test rows), the plots' material, and the verdict. The gate walks the chain of changes back from the last
// until the model is not worse than the model given on any of those errors beyond its scatter; the printed
// numbers are the very ones it compared, so the report can never show the model written worse.
void errors_stage(const Prep& pr, const Model& model0, const Chain& chain, const FitOptions& o, const MeasuredData* test,
                  FitReport& rep, Model& after) {
    const MeasuredData& data = *pr.data;
    std::vector<std::string> tnotes;
    Prep pt;
    if (test) pt = prepare(*test, model0, o, tnotes);
    const Prep* ptp = test ? &pt : nullptr;
    const double judge = rep.horizon_periods;
    const PrintedErrors pg = printed_errors(pr, model0, o, judge, ptp);
    // The baseline the effects are judged against too: the last baseline step not worse than the model given
    // (a fitted baseline is a change like any other). An effect must not make the model worse than either.
    std::size_t last_base = 0;
    while (last_base + 1 < chain.size() && chain[last_base + 1].baseline) ++last_base;
    std::size_t ref_base = 0;
    PrintedErrors pb;
    for (std::size_t j = last_base; j > 0; --j) {
        pb = printed_errors(pr, chain[j].model, o, judge, ptp);
        const GateCheck g = gate_check(pg, pb);
        if (!g.worse) {
            ref_base = j;
            break;
        }
        rep.gate.push_back("undone: " + chain[j].what + ", since against the model given the " + g.why);
    }
    std::size_t kept_step = chain.size() - 1;
    PrintedErrors pa;
    // Effects fitted on a baseline the gate undid go with it.
    if (ref_base != last_base && kept_step > last_base) {
        rep.gate.push_back("undone: every effect, since they were fitted on top of the baseline undone");
        kept_step = last_base;
    }
    for (; kept_step > last_base; --kept_step) {
        pa = printed_errors(pr, chain[kept_step].model, o, judge, ptp);
        GateCheck g = gate_check(pg, pa);
        std::string against = "the model given";
        if (!g.worse && ref_base > 0) {
            g = gate_check(pb, pa);
            against = "the fitted baseline";
        }
        if (!g.worse) {
            rep.gate_within = g.within;
            if (ref_base > 0)
                for (const auto& w : gate_check(pg, pa).within) rep.gate_within.push_back(w + " (against the model given)");
            break;
        }
        rep.gate.push_back("undone: " + chain[kept_step].what + ", since against " + against + " the " + g.why);
    }
    if (kept_step <= last_base) {
        kept_step = ref_base;
        pa = ref_base > 0 ? pb : pg;
    }
    if (ref_base > 0) {
        rep.baseline_column = true;
        rep.baseline_step = chain[ref_base].what;
    }
    const ChainStep& chosen = chain[kept_step];
    after = chosen.model;
    // Effects the gate undid are reported as turned down, with the reason.
    for (const FoundEffect& f : chain.back().found) {
        const bool kept = std::any_of(chosen.found.begin(), chosen.found.end(), [&](const FoundEffect& c) { return c.id == f.id; });
        if (!kept)
            rep.effects_rejected.push_back({f.id, "undone by the final gate: the model with it is worse than the model given (" +
                                                      (rep.gate.empty() ? std::string("?") : rep.gate.back()) + ")",
                                            f.validation_gain, f.validation_z, f.parameters});
    }
    rep.effects_found = chosen.found;
    // The held-out RMS of the model written: the baseline's where no effect stays, else its step's.
    if (kept_step <= last_base) rep.validation_rms_after_m = rep.validation_rms_before_m;
    else if (chosen.held_out_rms_m >= 0) rep.validation_rms_after_m = chosen.held_out_rms_m;
    if (kept_step == 0 && rep.baseline == "fit") rep.baseline = "fixed";
    rep.gate_passed = chosen.what;

    auto fill = [&](const PrintedErrors& p, ErrorSummary& e) {
        e.residual_rms_N = p.value(kErrResidual);
        e.shooting_rms_1_m = p.value(kErrShoot1);
        e.shooting_rms_10_m = p.value(kErrShoot10);
        e.shooting_rms_judge_m = judge == 1.0 ? e.shooting_rms_1_m : judge == 10.0 ? e.shooting_rms_10_m : p.value(kErrShootJudge);
        e.impact = impact_error(pr, p.pred);
        if (const PrintedError* d = p.find(kErrDiagram)) {   // its units are the omega bins
            e.diagram_bins = d->num.size();
            e.diagram_per_bin.clear();
            for (std::size_t k = 0; k < d->num.size(); ++k) e.diagram_per_bin.emplace_back(d->keys[k], d->num[k]);
            e.diagram_distance_m = d->num.empty() ? -1.0 : d->value();
        }
        e.simulation_rms_m = p.find(kErrFree) ? p.value(kErrFree) : -1;
        e.test_simulation_rms_m = p.find(kErrTestFree) ? p.value(kErrTestFree) : -1;
        e.test_shooting_rms_m = p.find(kErrTestShoot) ? p.value(kErrTestShoot) : -1;
    };
    fill(pg, rep.error_before);
    fill(pa, rep.error_after);
    if (ref_base > 0) fill(pb, rep.error_baseline);
    if (!pg.diagram_measured.empty()) {
        rep.diagram_measured = pg.diagram_measured;
        rep.diagram_before = pg.diagram;
        rep.diagram_after = pa.diagram;
    }
    if (test && rep.error_after.test_simulation_rms_m > rep.error_before.test_simulation_rms_m &&
        rep.error_after.test_shooting_rms_m <= rep.error_before.test_shooting_rms_m)
        rep.notes.push_back("the free run over the test rows ends further from them with the effects found, while the "
                            "shooting error within the predictability horizon falls: the free run drifts onto another "
                            "trajectory (a chaotic record), which no model avoids");
    const Eigen::VectorXd& R0 = pg.R;
    const Eigen::VectorXd& R1 = pa.R;
    const PredictedImpacts& pred_before = pg.pred;
    const PredictedImpacts& pred_after = pa.pred;
    const Model& base = model0;

    // The material for the plots.
    {
        const std::size_t step = std::max<std::size_t>(1, pr.rows.size() / 20000);
        for (std::size_t r = 0; r < pr.rows.size(); r += step) {
            const std::size_t i = pr.rows[r];
            rep.residual.x.push_back(data.x[i]);
            rep.residual.v.push_back(pr.vs[i]);
            rep.residual.phi.push_back(pr.phi_forced ? std::fmod(pr.phi[i], kTwoPi) : 0.0);
            rep.residual.before.push_back(R0[static_cast<Eigen::Index>(r)]);
            rep.residual.after.push_back(R1[static_cast<Eigen::Index>(r)]);
        }
        // The given model's worst 10-period window (the gate's own units: one per window of windows(pr, 10)).
        const PrintedError* s10 = pg.find(kErrShoot10);
        const auto wins10 = windows(pr, 10);
        std::size_t worst = wins10.size();
        for (std::size_t w = 0; s10 && w < wins10.size() && w < s10->num.size(); ++w)
            if (std::isfinite(s10->num[w]) && (worst == wins10.size() || s10->num[w] / s10->den[w] > s10->num[worst] / s10->den[worst]))
                worst = w;
        if (worst < wins10.size()) {
            const auto [a, b] = wins10[worst];
            rep.trace.before = simulate_window(pr, base, a, b, o.refine_shooting, o.rtol);
            rep.trace.after = simulate_window(pr, after, a, b, o.refine_shooting, o.rtol);
            for (std::size_t i = a; i <= b; ++i) {
                rep.trace.t.push_back(data.t[i]);
                rep.trace.measured.push_back(data.x[i]);
            }
        }
        for (std::size_t k = 0; k < pr.impacts.size(); ++k) {
            const ImpactObs& im = pr.impacts[k];
            const bool b = k < pred_before.ok.size() && pred_before.ok[k], a = k < pred_after.ok.size() && pred_after.ok[k];
            rep.impacts.push_back({im.t_in, im.v_minus, im.v_plus, im.t_out - im.t_in, im.level,
                                   b ? apparent_kappa(pred_before.obs[k]) : kNaN, b ? pred_before.obs[k].t_out - pred_before.obs[k].t_in : kNaN,
                                   a ? apparent_kappa(pred_after.obs[k]) : kNaN, a ? pred_after.obs[k].t_out - pred_after.obs[k].t_in : kNaN});
        }
    }
    // The verdict says what the numbers say: at the noise floor only when the equation error is there and the
    // shooting error within the judging horizon is at the sensor noise, with nothing left that a smooth function
    // of one variable explains; otherwise how far off, and what the remainder depends on.
    {
        const double ratio = rep.noise_floor_N > 0 ? rep.error_after.residual_rms_N / rep.noise_floor_N : INFINITY;
        // The shooting error a right model leaves: the sensor noise over one period (its initial state fitted
        // to the window, it does not drift within one). A record whose returns double their separation within
        // a period is judged on its shorter windows, where the error may have grown to twice the noise.
        const Prep::Predictability& dh = pr.predictability;
        const bool short_horizon = dh.measured && !dh.regular && dh.periods < 1.0 && rep.error_after.shooting_rms_judge_m >= 0;
        const double shoot = short_horizon ? rep.error_after.shooting_rms_judge_m : rep.error_after.shooting_rms_1_m;
        const double shoot_limit = short_horizon ? 2.0 : 1.25;
        const double sratio = pr.sigma_x > 0 ? shoot / pr.sigma_x : INFINITY;
        rep.remainder = remainder_dependence(pr, R1);
        std::string depends;
        // A share counts only where it stands above the noise floor's own: the measured x's noise enters the
        // equation error through every x term, so at the floor a function of x seems to explain a part of it.
        for (const auto& [what, share] : rep.remainder)
            if (share >= 0.05 && share * ratio * ratio >= 0.25) {
                char b[80];
                std::snprintf(b, sizeof b, "%s%s (%.0f %%)", depends.empty() ? "" : ", ", what.c_str(), 100.0 * share);
                depends += b;
            }
        const bool at_floor = ratio <= 1.5 && sratio <= shoot_limit;
        char buf[700];
        if (at_floor) {
            std::snprintf(buf, sizeof buf,
                          "the residual (%.3g %s RMS) is at its noise floor (%.3g %s) and the shooting error (%.3g) at the "
                          "sensor noise (%.3g)%s",
                          rep.error_after.residual_rms_N, rep.force_unit.c_str(), rep.noise_floor_N, rep.force_unit.c_str(), shoot,
                          pr.sigma_x, rep.effects_found.empty() ? ": no missing effect" : " with the effects found");
        } else {
            std::snprintf(buf, sizeof buf,
                          "the model %s misses something: the residual (%.3g %s RMS) is %.3g times its noise floor (%.3g %s) and the "
                          "shooting error %.3g times the sensor noise; %s%s",
                          rep.effects_found.empty() ? "still" : "with the effects found still", rep.error_after.residual_rms_N,
                          rep.force_unit.c_str(), ratio, rep.noise_floor_N, rep.force_unit.c_str(), sratio,
                          depends.empty() ? "no smooth function of x, v, the phase, time or the impacts alone explains what is left"
                                          : "what is left depends on ",
                          depends.c_str());
        }
        rep.verdict = buf;
    }
}

// The candidates' regressors (stage 2): for each library candidate, and each trial value of its nonlinear
// parameter, the columns dR/dp of its linear parameters at the baseline (and the fitted base parameters'
// columns first), with the 5-fold cross-validation blocks over them.
struct Group {
    std::size_t cand;
    double start;
    EffectInstance inst;
    std::vector<int> cols;
};
struct Screen {
    std::vector<Candidate> cands;
    std::vector<Group> groups;
    std::vector<int> base_cols;
    Eigen::MatrixXd X;
    Folds folds;
};
Screen screen_candidates(const Prep& pr, const Model& base, const FitOptions& o, const std::vector<std::string>& base_names,
                         const Eigen::VectorXd& R0) {
    Screen sc;
    sc.cands = library_candidates(base, pr, o);
    const std::vector<Candidate>& cands = sc.cands;
    std::vector<Eigen::VectorXd> columns;
    std::vector<double> pw;
    Eigen::VectorXd Rtmp;
    if (o.fit_baseline) {
        Model mb = base;
        const std::vector<BaseParam> bparams = base_params(mb, base_names);
        for (const auto& b : bparams) {
            const double v0 = *b.value, h = std::max(1e-4 * std::abs(v0), 1e-6);
            *b.value = v0 + h;
            residual(pr, mb, Rtmp, pw);
            *b.value = v0;
            columns.push_back(-(Rtmp - R0) / h);
            sc.base_cols.push_back(static_cast<int>(columns.size()) - 1);
        }
    }
    for (std::size_t ci = 0; ci < cands.size(); ++ci) {
        const Candidate& c = cands[ci];
        const std::vector<double> starts = c.starts.empty() ? std::vector<double>{0.0} : c.starts;
        for (double st : starts) {
            Group g{ci, st, start_instance(c, base, pr, st), {}};
            for (int li : c.linear) {
                const int k = c.free[static_cast<std::size_t>(li)];
                const double h = c.step[static_cast<std::size_t>(li)];
                Eigen::VectorXd col(static_cast<Eigen::Index>(pr.rows.size()));
                if (c.base) {   // the base parameter it moves: its column, as the fitted base parameters'
                    Model mp = base;
                    double* value = base_params(mp, {c.base}).front().value;
                    *value += h;
                    residual(pr, mp, Rtmp, pw);
                    *value -= 2 * h;
                    Eigen::VectorXd Rm;
                    residual(pr, mp, Rm, pw);
                    col = -(Rtmp - Rm) / (2 * h);
                } else if (c.sensor) {
                    Model mp = base;
                    mp.p.effects.push_back(g.inst);
                    mp.p.effects.back().p[static_cast<std::size_t>(k)] += h;
                    residual(pr, mp, Rtmp, pw);
                    mp.p.effects.back().p[static_cast<std::size_t>(k)] -= 2 * h;
                    Eigen::VectorXd Rm;
                    residual(pr, mp, Rm, pw);
                    col = -(Rtmp - Rm) / (2 * h);
                } else {
                    effect_column(pr, base, g.inst, k, h, col, pw);
                }
                if (!col.allFinite()) col.setZero();
                columns.push_back(col);
                g.cols.push_back(static_cast<int>(columns.size()) - 1);
            }
            sc.groups.push_back(std::move(g));
        }
    }
    sc.X.resize(R0.size(), static_cast<Eigen::Index>(columns.size()));
    for (std::size_t k = 0; k < columns.size(); ++k) sc.X.col(static_cast<Eigen::Index>(k)) = columns[k];
    sc.folds = make_folds(sc.X, R0, 5);
    return sc;

}

// Stage 3: greedy forward selection over the screened candidates. Each round adds the candidate (at its best
// trial value) that lowers the cross-validated residual most, if it explains at least o.min_gain of it and
// its coefficients stand out of the noise (z from serially-correlation-robust errors); a generic smooth
// force only where no library effect comes close. Fills rep.candidates from the first round.
struct Selection {
    std::vector<std::size_t> chosen;   // group indices, in the order chosen
    std::vector<double> step_gain;     // the in-sample share each one added
    double in_base = 0;                // in-sample SSE with the base columns alone
};
Selection select_effects(const Screen& screen, const Eigen::VectorXd& R0, const FitOptions& o, int hac_lag, FitReport& rep) {
    const std::vector<Candidate>& cands = screen.cands;
    const std::vector<Group>& groups = screen.groups;
    const Eigen::MatrixXd& X = screen.X;
    const Folds& folds = screen.folds;
    auto zscore = [&](const std::vector<int>& cols, const std::vector<int>& sub) {
        double cv, in;
        Eigen::VectorXd beta;
        cv_sse(folds, cols, cv, in, &beta);
        Eigen::MatrixXd Xs(X.rows(), static_cast<Eigen::Index>(cols.size()));
        for (std::size_t k = 0; k < cols.size(); ++k) Xs.col(static_cast<Eigen::Index>(k)) = X.col(cols[k]);
        const Eigen::VectorXd e = R0 - Xs * beta;
        const Eigen::MatrixXd V = hac_cov(Xs, e, hac_lag);
        // Wald statistic of the sub-block (positions in cols).
        const auto q = static_cast<Eigen::Index>(sub.size());
        Eigen::MatrixXd Vs(q, q);
        Eigen::VectorXd bs(q);
        for (Eigen::Index i = 0; i < q; ++i) {
            bs[i] = beta[sub[static_cast<std::size_t>(i)]];
            for (Eigen::Index j = 0; j < q; ++j) Vs(i, j) = V(sub[static_cast<std::size_t>(i)], sub[static_cast<std::size_t>(j)]);
        }
        for (Eigen::Index i = 0; i < q; ++i) Vs(i, i) += 1e-12 * Vs(i, i) + 1e-300;
        const double W = bs.dot(Vs.ldlt().solve(bs));
        const double z_hac = std::isfinite(W) ? chi2_to_z(W, static_cast<int>(q)) : 0.0;
        return std::min(z_hac, group_z_dss(Xs, e, sub, bs, 2 * hac_lag));
    };

    std::vector<int> cur = screen.base_cols;
    double cv_cur, in_cur;
    cv_sse(folds, cur, cv_cur, in_cur);
    Selection sel;
    sel.in_base = in_cur;
    const double in_base = in_cur;
    std::vector<std::size_t>& chosen = sel.chosen;
    std::vector<double>& step_gain = sel.step_gain;
    std::vector<bool> cand_used(cands.size(), false);
    for (int round = 0; round < o.max_effects; ++round) {
        struct Eval {
            std::size_t g;
            double gain_cv, gain_in, z = 0;
        };
        std::vector<Eval> best_per_cand(cands.size(), {0, -INFINITY, 0, 0});
        bool generic_chosen = false;
        for (std::size_t gi : chosen) generic_chosen = generic_chosen || cands[groups[gi].cand].generic;
        for (std::size_t gi = 0; gi < groups.size(); ++gi) {
            const Group& g = groups[gi];
            if (cand_used[g.cand]) continue;
            // After a generic smooth force, a sensor calibration is no longer identifiable against it.
            if (generic_chosen && cands[g.cand].sensor) continue;
            std::vector<int> cols = cur;
            cols.insert(cols.end(), g.cols.begin(), g.cols.end());
            double cv, in;
            cv_sse(folds, cols, cv, in);
            const double gcv = (cv_cur - cv) / cv_cur, gin = (in_cur - in) / in_base;
            if (cands[g.cand].positive) {
                Eigen::VectorXd beta;
                double cv2, in2;
                cv_sse(folds, cols, cv2, in2, &beta);
                if (!(beta[static_cast<Eigen::Index>(cur.size())] > 0)) continue;
            }
            if (gcv > best_per_cand[g.cand].gain_cv) best_per_cand[g.cand] = {gi, gcv, gin, 0};
        }
        std::vector<Eval> evals;
        for (std::size_t c = 0; c < cands.size(); ++c)
            if (!cand_used[c] && std::isfinite(best_per_cand[c].gain_cv)) evals.push_back(best_per_cand[c]);
        std::sort(evals.begin(), evals.end(), [](const Eval& a, const Eval& b) { return a.gain_cv > b.gain_cv; });
        int lib_checked = 0, gen_checked = 0;
        for (auto& e : evals) {
            const bool gen = cands[groups[e.g].cand].generic;
            int& checked = gen ? gen_checked : lib_checked;
            if (checked >= 4 && round > 0) continue;
            ++checked;
            std::vector<int> cols = cur, sub;
            for (int c : groups[e.g].cols) {
                sub.push_back(static_cast<int>(cols.size()));
                cols.push_back(c);
            }
            e.z = zscore(cols, sub);
        }
        if (round == 0)
            for (const auto& e : evals) {
                // Its parameters fitted alone on the baseline residual: sign and size, selected or not.
                const Group& g = groups[e.g];
                const Candidate& c = cands[g.cand];
                std::vector<int> cols = cur;
                cols.insert(cols.end(), g.cols.begin(), g.cols.end());
                double cv, in;
                Eigen::VectorXd beta;
                cv_sse(folds, cols, cv, in, &beta);
                if (c.base) {
                    rep.candidates.push_back({c.id, e.gain_in, e.z, false, {{c.param, beta[static_cast<Eigen::Index>(cur.size())]}}, e.gain_cv});
                    continue;
                }
                EffectInstance inst = g.inst;
                for (std::size_t li = 0; li < c.linear.size(); ++li)
                    inst.p[static_cast<std::size_t>(c.free[static_cast<std::size_t>(c.linear[li])])] +=
                        beta[static_cast<Eigen::Index>(cur.size() + li)];
                rep.candidates.push_back({c.id, e.gain_in, e.z, false, named(inst), e.gain_cv});
            }
        const Eval* lib = nullptr;
        const Eval* gen = nullptr;
        for (const auto& e : evals) {
            if (!(e.gain_cv >= o.min_gain && e.z >= o.z_threshold && e.gain_in > 0)) continue;
            const bool g = cands[groups[e.g].cand].generic;
            if (g && !gen) gen = &e;
            if (!g && !lib) lib = &e;
        }
        // Named physics before curve fits: a generic term is chosen only where neither the best library effect
        // nor the best pair of library effects fitted jointly comes within the scatter of what it explains
        // (the CV sums' difference against its noise, plus a penalty for each parameter the generic term has
        // more, and never closer than 2 % of what the generic term explains).
        std::vector<const Eval*> picks;
        if (lib) picks = {lib};
        if (gen) {
            const double cv_gen = cv_cur * (1.0 - gen->gain_cv);
            const double sigma2 = cv_gen / static_cast<double>(std::max<Eigen::Index>(1, X.rows()));
            const double B = std::max(1.0, static_cast<double>(hac_lag));
            auto tol = [&](std::size_t named_params) {
                const double dp = static_cast<double>(groups[gen->g].cols.size()) - static_cast<double>(named_params);
                return std::max(sigma2 * B * (16.0 + 2.0 * std::max(dp, 0.0)), 0.02 * (cv_cur - cv_gen));
            };
            const bool lib_close = lib && cv_cur * (1.0 - lib->gain_cv) <= cv_gen + tol(groups[lib->g].cols.size());
            if (!lib_close) {
                // Pairs of the strongest library effects, fitted jointly; each must stand out of the noise in the pair.
                std::vector<const Eval*> top;
                for (const auto& e : evals)
                    if (!cands[groups[e.g].cand].generic && e.gain_cv > 0 && top.size() < 8) top.push_back(&e);
                double best_cv = INFINITY;
                std::vector<const Eval*> best_pair;
                double pair_gain_in = 0;
                for (std::size_t a = 0; a < top.size(); ++a)
                    for (std::size_t b = a + 1; b < top.size(); ++b) {
                        const Candidate& ca = cands[groups[top[a]->g].cand];
                        const Candidate& cb = cands[groups[top[b]->g].cand];
                        if (generic_chosen && (ca.sensor || cb.sensor)) continue;
                        std::vector<int> cols = cur, sa, sb;
                        for (int c : groups[top[a]->g].cols) {
                            sa.push_back(static_cast<int>(cols.size()));
                            cols.push_back(c);
                        }
                        for (int c : groups[top[b]->g].cols) {
                            sb.push_back(static_cast<int>(cols.size()));
                            cols.push_back(c);
                        }
                        double cv, in;
                        cv_sse(folds, cols, cv, in);
                        if (!(cv < best_cv)) continue;
                        const std::size_t np = groups[top[a]->g].cols.size() + groups[top[b]->g].cols.size();
                        if (cv > cv_gen + tol(np)) continue;
                        if (zscore(cols, sa) < o.z_threshold || zscore(cols, sb) < o.z_threshold) continue;
                        best_cv = cv;
                        best_pair = {top[a], top[b]};
                        pair_gain_in = (in_cur - in) / in_base;
                    }
                if (!best_pair.empty()) {
                    picks = best_pair;
                    rep.notes.push_back("a pair of named effects, " + cands[groups[best_pair[0]->g].cand].id + " and " +
                                        cands[groups[best_pair[1]->g].cand].id + ", fitted jointly explains as much as the generic " +
                                        cands[groups[gen->g].cand].id + ": the named pair is preferred");
                    // The pair's explained share is split by each one's share alone.
                    const double ga = std::max(best_pair[0]->gain_in, 1e-12), gb = std::max(best_pair[1]->gain_in, 1e-12);
                    step_gain.push_back(pair_gain_in * ga / (ga + gb));
                    step_gain.push_back(pair_gain_in * gb / (ga + gb));
                } else {
                    picks = {gen};
                }
            }
        }
        if (picks.empty()) break;
        const bool pair = picks.size() == 2;
        for (const Eval* pick : picks) {
            const Group& g = groups[pick->g];
            cand_used[g.cand] = true;
            chosen.push_back(pick->g);
            if (!pair) step_gain.push_back(pick->gain_in);
            cur.insert(cur.end(), g.cols.begin(), g.cols.end());
            for (auto& cs : rep.candidates)
                if (cs.id == cands[g.cand].id) cs.selected = true;
        }
        cv_sse(folds, cur, cv_cur, in_cur);
        if (pair) ++round;
    }

    return sel;
}

// Stage 4: the model with the chosen effects. Linear estimates from the screening, then a joint nonlinear
// refinement of their parameters (and the fitted base parameters) on the equation error, with HAC
// uncertainties; an effect whose significance does not survive the joint fit is dropped and the rest
// refitted. An input-forced record then refines them on the free-run simulation error where that predicts
// the held-out part better; a sensor effect the impacts' flat tops contradict goes. The effects found are
// appended to rep.effects_found; returns the model with them.
Model refit_stage(const Prep& pr, const Model& base, const Screen& screen, Selection sel, const std::vector<std::string>& base_names,
                  const FitOptions& o, int hac_lag, double in0, const SentenceContext& sc, FitReport& rep) {
    const std::vector<Candidate>& cands = screen.cands;
    const std::vector<Group>& groups = screen.groups;
    const std::vector<int>& base_cols = screen.base_cols;
    const Folds& folds = screen.folds;
    std::vector<std::size_t>& chosen = sel.chosen;
    std::vector<double>& step_gain = sel.step_gain;
    const double in_base = sel.in_base;
    std::vector<double> pw;
    Model after = base;
    std::vector<FoundEffect> force_found;
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> inst_of;   // per chosen effect: its instance in after.p.effects (kNone: base-changing)
    for (;;) {
        after = base;
        {
            std::vector<int> cols = base_cols;
            for (std::size_t gi : chosen) cols.insert(cols.end(), groups[gi].cols.begin(), groups[gi].cols.end());
            double cv, in;
            Eigen::VectorXd beta;
            cv_sse(folds, cols, cv, in, &beta);
            std::size_t pos = base_cols.size();   // base parameters: refitted below
            inst_of.clear();
            for (std::size_t gi : chosen) {
                const Group& g = groups[gi];
                const Candidate& c = cands[g.cand];
                if (c.base) {   // a base-changing candidate moves its base parameter
                    apply_effect(after, c.id, {{c.param, std::clamp(beta[static_cast<Eigen::Index>(pos++)], c.lo, c.hi)}});
                    inst_of.push_back(kNone);
                    continue;
                }
                EffectInstance inst = g.inst;
                for (int li : c.linear)
                    inst.p[static_cast<std::size_t>(c.free[static_cast<std::size_t>(li)])] += beta[static_cast<Eigen::Index>(pos++)];
                inst_of.push_back(after.p.effects.size());
                after.p.effects.push_back(inst);
            }
        }
        std::vector<Knob> knobs;
        if (o.fit_baseline) knobs = base_knobs(after, base_names);
        const std::size_t n_base_knobs = knobs.size();
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            const Candidate& c = cands[groups[chosen[k]].cand];
            if (c.base) knobs.push_back(base_change_knob(c, after, base));
            else effect_knobs(c, after.p.effects[inst_of[k]], knobs);
        }
        Eigen::VectorXd R1;
        Eigen::MatrixXd J1;
        if (knobs.empty()) residual(pr, after, R1, pw);
        else lm_residual(pr, after, knobs, 30, R1, J1);

        // Uncertainties (HAC) and significance of each found effect at the joint fit.
        std::vector<double> knob_sigma(knobs.size(), 0.0);
        Eigen::MatrixXd V;
        if (!knobs.empty()) {
            V = hac_cov(-J1, R1, hac_lag);
            for (std::size_t k = 0; k < knobs.size(); ++k)
                knob_sigma[k] = std::sqrt(std::max(0.0, V(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k))));
        }
        force_found.clear();
        std::size_t kk = n_base_knobs;
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            const Candidate& c = cands[groups[chosen[k]].cand];
            FoundEffect f;
            f.id = c.id;
            f.evidence = "equation error";
            f.explained_fraction = step_gain[k] * in_base / std::max(in0, 1e-300);
            if (c.base) {   // one parameter, its null value the base model's
                const double d = base_change(c, after, base);
                f.parameters = {{c.param, d}};
                f.sigma = {{c.param, knob_sigma[kk]}};
                f.z = std::min(std::abs(d) / std::max(knob_sigma[kk], 1e-300),
                               group_z_dss(J1, R1, {static_cast<int>(kk)}, Eigen::VectorXd::Constant(1, d), 2 * hac_lag));
                ++kk;
                f.sentence = sentence(c.id, base, f.parameters, f.sigma, sc);
                force_found.push_back(std::move(f));
                continue;
            }
            const EffectInstance& inst = after.p.effects[inst_of[k]];
            f.parameters = named(inst);
            std::vector<int> sub;
            for (std::size_t li = 0; li < c.free.size(); ++li, ++kk) {
                f.sigma.emplace_back(c.law->names[static_cast<std::size_t>(c.free[li])], knob_sigma[kk]);
                sub.push_back(static_cast<int>(kk));
            }
            // Wald z over the effect's parameters, against their null values.
            const auto q = static_cast<Eigen::Index>(sub.size());
            Eigen::MatrixXd Vs(q, q);
            Eigen::VectorXd d(q);
            const EffectInstance null_inst = start_instance(c, base, pr, c.starts.empty() ? 0.0 : inst.p[1]);
            for (Eigen::Index i = 0; i < q; ++i) {
                const auto pi = static_cast<std::size_t>(c.free[static_cast<std::size_t>(i)]);
                d[i] = inst.p[pi] - null_inst.p[pi];
                for (Eigen::Index j = 0; j < q; ++j) Vs(i, j) = V(sub[static_cast<std::size_t>(i)], sub[static_cast<std::size_t>(j)]);
            }
            if (c.law->fit.test_first_only) {   // a shape parameter (a speed scale) has no null value: test the first alone
                f.z = std::abs(inst.p[0]) / std::max(knob_sigma[static_cast<std::size_t>(sub[0])], 1e-300);
                f.z = std::min(f.z, group_z_dss(J1, R1, {sub[0]}, d.head(1), 2 * hac_lag));
            } else {
                for (Eigen::Index i = 0; i < q; ++i) Vs(i, i) += 1e-12 * Vs(i, i) + 1e-300;
                const double W = d.dot(Vs.ldlt().solve(d));
                f.z = std::min(std::isfinite(W) ? chi2_to_z(W, static_cast<int>(q)) : 0.0, group_z_dss(J1, R1, sub, d, 2 * hac_lag));
            }
            f.sentence = sentence(c.id, base, f.parameters, f.sigma, sc);
            force_found.push_back(std::move(f));
        }
        // Backward elimination: the weakest effect below the threshold goes, the rest are refitted.
        std::size_t weakest = chosen.size();
        for (std::size_t k = 0; k < force_found.size(); ++k)
            if (force_found[k].z < o.z_threshold && (weakest == chosen.size() || force_found[k].z < force_found[weakest].z)) weakest = k;
        if (weakest == chosen.size()) break;
        for (auto& cs : rep.candidates)
            if (cs.id == force_found[weakest].id) cs.selected = false;
        rep.notes.push_back("dropped " + force_found[weakest].id + ": its significance fell to z = " +
                            std::to_string(force_found[weakest].z) + " in the joint fit");
        chosen.erase(chosen.begin() + static_cast<long>(weakest));
        step_gain.erase(step_gain.begin() + static_cast<long>(weakest));
    }
    // A sensor effect moves the measured bumper level too: if the impacts' flat tops contradict it, it is an
    // artefact of the free-flight fit and goes (the impact stage then sees the level as it is).
    if (after.bumper() && pr.impacts.size() >= 3) {
        for (std::size_t k = 0; k < force_found.size(); ++k) {
            const EffectLaw* law = find_effect(force_found[k].id);
            if (!law || law->kind != EffectKind::Sensor) continue;
            // The flat tops measured against the same impacts simulated with the sensor effect in the model (so
            // a compliant bumper's apparent penetration is on both sides).
            const PredictedImpacts pred = predict_impacts(pr, after, o.rtol);
            std::vector<double> lev;
            for (std::size_t i = 0; i < pr.impacts.size(); ++i)
                if (pred.ok[i]) lev.push_back(pr.impacts[i].level - pred.obs[i].level);
            if (lev.size() < 3) continue;
            // The level's own uncertainty from the effect's: its first parameter moved by its standard error.
            const double s0 = force_found[k].sigma.empty() ? 0.0 : force_found[k].sigma[0].second;
            double level_sigma = 0;
            std::array<double, kMaxLawParams> moved{};
            for (const auto& e : after.p.effects)
                if (e.law == law) {
                    moved = e.p;
                    moved[0] += s0;
                    level_sigma = std::abs(law->measure(moved.data(), after.p.xI) - law->measure(e.p.data(), after.p.xI));
                }
            const double miss = median(lev);
            if (std::abs(miss) > std::max(5.0 * level_sigma, 5.0 * pr.sigma_x + 1e-6)) {
                rep.notes.push_back("dropped " + force_found[k].id + ": the impacts' flat tops put the bumper where the uncorrected sensor does");
                for (auto& cs : rep.candidates)
                    if (cs.id == force_found[k].id) cs.selected = false;
                for (auto it = after.p.effects.begin(); it != after.p.effects.end(); ++it)
                    if (it->law == law) {
                        after.p.effects.erase(it);
                        break;
                    }
                force_found.erase(force_found.begin() + static_cast<long>(k));
                break;
            }
        }
    }
    for (auto& f : force_found) rep.effects_found.push_back(std::move(f));
    return after;
}

// Stage 6b, input-forced records with a fitted baseline: the effects that passed the validation, refitted
// together with the base parameters on the free-run simulation error (which weighs the resonance the way an
// equation error at a few samples per period cannot), kept only if that predicts the held-out part better.
void output_error_stage(const Prep& pr, const Model& base, const std::vector<Candidate>& cands,
                        const std::vector<std::string>& base_names, const FitOptions& o, const SentenceContext& sc,
                        FitReport& rep, Model& after, Chain& chain) {
    if (pr.phi_forced || !o.fit_baseline || rep.effects_found.empty()) return;
    Model refined = after;
    std::vector<Knob> knobs = base_knobs(refined, base_names);
    for (const Knob& k : found_effect_knobs(refined, base, cands)) knobs.push_back(k);
    lm_simulation(pr, refined, knobs, 20, o.rtol);
    if (!unphysical(refined).empty() || !refinement_predicts_better(pr, refined, after, o.rtol)) {
        rep.notes.push_back("the output-error refit of the effects does not predict the tail of the record it was not fitted "
                            "to better (paired z >= 2 over the judging windows); their equation-error values are kept");
        return;
    }
    after = refined;
    rep.notes.push_back("effects refitted on the free-run simulation error (output error)");
    // The reported values are the simulation-error fit's; their uncertainties stay the equation error's.
    for (auto& f : rep.effects_found)
        for (const auto& e : after.p.effects)
            if (f.id == e.law->id) {
                f.parameters = named(e);
                f.sentence = sentence(f.id, base, f.parameters, f.sigma, sc);
            }
    chain.push_back({"the effects and the base parameters refitted on the free-run simulation error", after, rep.effects_found,
                     chain.empty() ? -1 : chain.back().held_out_rms_m, false});
}

}  // namespace

const char* fit_stage_name(FitStage s) {
    switch (s) {
        case FitStage::Prepare: return "preparing the data";
        case FitStage::Baseline: return "fitting the baseline";
        case FitStage::Candidates: return "screening the candidate effects";
        case FitStage::Selection: return "selecting effects";
        case FitStage::Refit: return "refitting the effects";
        case FitStage::ImpactLaw: return "comparing the impacts";
        case FitStage::Validation: return "validating on held-out data";
        case FitStage::Errors: return "errors before and after";
        case FitStage::Count: break;
    }
    return "?";
}

FitReport run_fit(const MeasuredData& data, const Model& model0, const FitOptions& options, const MeasuredData* test,
                  FitProgress* progress) {
    FitOptions o = options;   // a baseline fit that does not hold on held-out data turns into a fixed baseline
    // Where each stage starts in the whole fit's progress (their typical share of the run time).
    static constexpr double kStageStart[] = {0.0, 0.04, 0.10, 0.14, 0.18, 0.24, 0.34, 0.80, 1.0};
    auto enter = [&](FitStage s) {
        if (!progress) return;
        if (progress->cancel.load(std::memory_order_relaxed)) throw FitCancelled();
        progress->stage.store(static_cast<int>(s), std::memory_order_relaxed);
        progress->fraction.store(kStageStart[static_cast<int>(s)], std::memory_order_relaxed);
    };
    enter(FitStage::Prepare);
    const auto clock0 = std::chrono::steady_clock::now();
    FitReport rep;
    rep.data_source = data.source;
    rep.model_name = model0.p.name;
    rep.forcing = data.has_phi() ? "phi (unbalance)" : "u (measured input)";
    rep.baseline = o.fit_baseline ? "fit" : "fixed";
    if (model0.p.stiffness_id == "duffing") {
        rep.x_unit = "data units";
        rep.force_unit = "model force units (m = 1: data units / s^2)";
    }
    validate(model0.p, "model");
    check_plausible(data, model0, o);
    Prep prep = prepare(data, model0, o, rep.notes);
    prep.progress = progress;
    prep.predictability = data_horizon(prep);
    const Prep& pr = prep;
    rep.samples = pr.n;
    rep.rows_used = pr.rows.size();
    rep.dt = pr.dt;
    rep.duration = data.t.back() - data.t.front();
    rep.sigma_x = pr.sigma_x;
    rep.window_s = (pr.K.H + 1) * pr.dt;
    rep.period_s = pr.period;
    rep.drive_fit_rms_rad = pr.drive_rms;
    rep.data_horizon_measured = pr.predictability.measured;
    rep.data_regular = pr.predictability.regular;
    rep.data_horizon_periods = pr.predictability.periods;
    rep.data_lambda = pr.predictability.lambda;
    if (pr.phi_forced) {
        rep.omega_min = *std::min_element(pr.omega.begin(), pr.omega.end());
        rep.omega_max = *std::max_element(pr.omega.begin(), pr.omega.end());
    }
    const int stride = std::max(1, pr.K.H / 4);
    const int hac_lag = static_cast<int>(std::ceil(2.0 * (2 * pr.K.H + 1) / stride));

    enter(FitStage::Baseline);
    // ---- 1. the baseline --------------------------------------------------------------------------------
    std::vector<std::string> base_names =
        o.fit_baseline ? (o.fit_params.empty() ? default_fit_params(model0) : o.fit_params) : std::vector<std::string>{};
    Model ee_base = model0;
    Model base = fit_baseline_stage(pr, model0, o, base_names, rep, ee_base);
    Chain chain{{"the model given", model0, {}, -1, false}};
    // Never a worse model than the one given: on a record forced by the unbalance (the given model is the rig's
    // physical one, not a starting guess) the fitted baseline must predict held-out data better.
    if (o.fit_baseline && pr.phi_forced) {
        std::string why;
        if (!baseline_predicts_better(pr, model0, base, base_names, o, why)) {
            rep.notes.push_back("the fitted baseline does not predict held-out data better than the parameters given (" + why +
                                "); the parameters given are kept, fixed");
            base = model0;
            o.fit_baseline = false;
            base_names.clear();
            rep.baseline = "fixed";
        }
    }
    if (o.fit_baseline) {
        chain.push_back({"the base parameters fitted to the equation error", ee_base, {}, -1, true});
        if (!pr.phi_forced && rep.notes.size() && rep.notes.back().rfind("baseline refined on the free-run", 0) == 0)
            chain.push_back({"the base parameters refined on the free-run simulation error", base, {}, -1, true});
    }
    std::vector<double> pw;
    Eigen::VectorXd R0;
    residual(pr, base, R0, pw);
    rep.before = model0;
    const double in0 = R0.squaredNorm();
    rep.noise_floor_N = base.p.m * pr.sigma_x * pr.K.noise_gain / base.sensor_gain();

    enter(FitStage::Candidates);
    // ---- 2. candidate columns -----------------------------------------------------------------------------
    const Screen screen = screen_candidates(pr, base, o, base_names, R0);

    enter(FitStage::Selection);
    // ---- 3. greedy selection ------------------------------------------------------------------------------
    const Selection sel = select_effects(screen, R0, o, hac_lag, rep);

    enter(FitStage::Refit);
    // ---- 4. the model with the effects: linear estimates, then joint nonlinear refinement; an effect whose
    //         significance does not survive the joint fit is dropped and the rest refitted ------------------
    SentenceContext sc;
    {
        std::vector<double> av, ax;
        for (std::size_t r : pr.rows) {
            av.push_back(std::abs(pr.vs[r]));
            ax.push_back(std::abs(data.x[r]));
        }
        double s = 0;
        for (double v : av) s += v * v;
        sc.v_typ = av.empty() ? 0.0 : std::sqrt(s / static_cast<double>(av.size()));
        sc.x_typ = quantile(ax, 0.9);
    }
    Model after = refit_stage(pr, base, screen, sel, base_names, o, hac_lag, in0, sc, rep);

    enter(FitStage::ImpactLaw);
    // ---- 5. the impact law: bumper position, impact duration, restitution ----------------------------------
    impact_law_stage(pr, o, sc, after, rep);
    end_stop_stage(pr, o, sc, after, rep);
    enter(FitStage::Validation);
    // ---- 6. validation: an effect stays only if it lowers the short-horizon simulation error on data held
    //         out from its fit, by more than the windows' scatter; the final model must beat the baseline ----
    validate_effects(pr, base, screen.cands, o, base_names, sc, rep, after, chain);
    output_error_stage(pr, base, screen.cands, base_names, o, sc, rep, after, chain);

    enter(FitStage::Errors);
    // ---- 7. the final gate, errors before and after; 8. material for the plots; the verdict ------------------
    errors_stage(pr, model0, chain, o, test, rep, after);
    std::stable_sort(rep.effects_found.begin(), rep.effects_found.end(),
                     [](const FoundEffect& a, const FoundEffect& b) { return a.explained_fraction > b.explained_fraction; });
    if (!rep.effects_found.empty()) after.p.name = base.p.name + "+" + rep.effects_found.front().id;
    for (std::size_t k = 1; k < rep.effects_found.size(); ++k) after.p.name += "+" + rep.effects_found[k].id;
    rep.after = after;
    rep.runs = pr.run_start.size();
    rep.wells_before = well_report(model0, {}, pr);
    rep.data_wells = data_wells(pr, hac_lag);
    rep.wells_from_data = wells_asymmetry(rep.data_wells, rep.x_unit == "m" ? "m" : rep.x_unit);
    rep.wells_after = well_report(after, rep.effects_found, pr);
    // Never a report whose headline numbers are not numbers: name the first and refuse to hand it over.
    const std::pair<const char*, double> headline[] = {
        {"sensor noise", rep.sigma_x},
        {"noise floor", rep.noise_floor_N},
        {"residual RMS before", rep.error_before.residual_rms_N},
        {"residual RMS after", rep.error_after.residual_rms_N},
        {"1-period shooting RMS after", rep.error_after.shooting_rms_1_m},
    };
    for (const auto& [what, v] : headline)
        if (!std::isfinite(v))
            throw std::runtime_error(data.source + ": the fit's " + what + " came out " + std::to_string(v) +
                                     "; no report is written (check the data's columns and units)");
    for (const auto& e : rep.effects_found)
        for (const auto& [name, v] : e.parameters)
            if (!std::isfinite(v))
                throw std::runtime_error(data.source + ": effect " + e.id + "." + name + " came out " + std::to_string(v) +
                                         "; no report is written");
    rep.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
    if (progress) progress->fraction.store(1.0, std::memory_order_relaxed);
    return rep;
}

ErrorSummary evaluate_model(const MeasuredData& data, const Model& model, const FitOptions& o) {
    std::vector<std::string> notes;
    validate(model.p, "model");
    check_plausible(data, model, o);
    const Prep pr = prepare(data, model, o, notes);
    ErrorSummary e;
    Eigen::VectorXd R;
    std::vector<double> pw;
    residual(pr, model, R, pw);
    e.residual_rms_N = rms_of(R);
    const ShootOut so = shooting(pr, model, o);
    e.shooting_rms_1_m = so.rms1;
    e.shooting_rms_10_m = so.rms10;
    e.impact = impact_error(pr, predict_impacts(pr, model, o.rtol));
    if (pr.phi_forced) {
        const auto [wmin, wmax] = std::minmax_element(pr.omega.begin(), pr.omega.end());
        if (*wmax - *wmin > 2 * o.omega_bin)
            e.diagram_distance_m = diagram_distance(measured_sections(pr), free_run_sections(pr, model, o.rtol), o.omega_bin,
                                                    e.diagram_bins, &e.diagram_per_bin);
    } else {
        e.simulation_rms_m = free_run_rms(free_run(pr, model, o.rtol), data.x);
    }
    return e;
}

}  // namespace impactlab::identify
