// The loop of impactlab fit: baseline, residual, effect selection, the model with the effects, errors before
// and after.
#include <algorithm>
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

// A parameter the nonlinear least squares may move: its address, finite-difference step and bounds.
struct Knob {
    double* value;
    double step, lo, hi;
    std::string name;
};

// Levenberg-Marquardt over `knobs` (clamped to their bounds) with a forward-difference Jacobian, shared by
// the equation-error and the simulation-error fits. eval(R) fills the residual at the knobs' current values
// and returns |R|^2 (infinite if not finite); step_of(knob, value) is the finite-difference step. Stops when
// an iteration gains less than min_gain of |R|^2. Leaves the final residual in R and, if final_jacobian, its
// Jacobian in J (a Jacobian costs one evaluation per knob).
template <class Eval, class StepOf>
void lm_knobs(std::vector<Knob>& knobs, Eval&& eval, StepOf&& step_of, int max_iter, double lambda, double min_gain,
              bool final_jacobian, Eigen::VectorXd& R, Eigen::MatrixXd& J) {
    double ss = eval(R);
    const auto p = static_cast<Eigen::Index>(knobs.size());
    J.resize(R.size(), p);
    if (p == 0) return;
    Eigen::VectorXd Rt;
    auto jacobian = [&]() {
        for (Eigen::Index k = 0; k < p; ++k) {
            Knob& kb = knobs[static_cast<std::size_t>(k)];
            const double v0 = *kb.value;
            const double h = step_of(kb, v0);
            *kb.value = v0 + h;
            eval(Rt);
            *kb.value = v0;
            J.col(k) = (Rt - R) / h;
        }
    };
    jacobian();
    std::vector<double> old(knobs.size());
    for (int it = 0; it < max_iter; ++it) {
        const Eigen::MatrixXd A = J.transpose() * J;
        const Eigen::VectorXd g = J.transpose() * R;
        bool improved = false;
        for (int tries = 0; tries < 8; ++tries) {
            Eigen::MatrixXd Ad = A;
            for (Eigen::Index k = 0; k < p; ++k) Ad(k, k) += lambda * A(k, k) + 1e-300;
            const Eigen::VectorXd d = Ad.ldlt().solve(-g);
            for (std::size_t k = 0; k < knobs.size(); ++k) {
                old[k] = *knobs[k].value;
                *knobs[k].value = std::clamp(old[k] + d[static_cast<Eigen::Index>(k)], knobs[k].lo, knobs[k].hi);
            }
            const double ss_new = eval(Rt);
            if (std::isfinite(ss_new) && ss_new < ss) {
                improved = (ss - ss_new) > min_gain * ss;
                R.swap(Rt);
                ss = ss_new;
                lambda = std::max(lambda / 4, 1e-9);
                break;
            }
            for (std::size_t k = 0; k < knobs.size(); ++k) *knobs[k].value = old[k];
            lambda *= 8;
        }
        if (!improved) break;
        if (final_jacobian || it + 1 < max_iter) jacobian();
    }
}

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
    lm_knobs(knobs, eval, step_of, max_iter, 1e-4, 1e-9, true, R, J);
}

// The output-error fit uses samples [a, end]; the rest of the record validates it.
std::size_t oe_fit_end(const Prep& pr, std::size_t a, std::size_t max_samples) {
    return std::min(pr.n - 1, a + std::min(max_samples, (pr.n - a) / 2));
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
    std::size_t a = 0;
    while (a + 2 < pr.n && (pr.zone[a] || !std::isfinite(pr.xs[a]) || !std::isfinite(pr.vs[a]))) ++a;
    const std::size_t b = oe_fit_end(pr, a, kOeSamples);
    auto err = [&](Eigen::VectorXd& e) {
        const std::vector<double> fr = simulate_window(pr, m, a, b, false, rtol);
        e.resize(static_cast<Eigen::Index>(b - a + 1));
        double ss = 0;
        for (std::size_t i = 0; i + a <= b; ++i) {
            const double r = i < fr.size() && std::isfinite(fr[i]) ? fr[i] - d.x[a + i] : 0.0;
            e[static_cast<Eigen::Index>(i)] = r;
            ss += r * r;
        }
        return std::isfinite(ss) ? ss : INFINITY;
    };
    auto step_of = [](const Knob& kb, double v0) { return std::max(1e-5 * std::abs(v0), kb.step); };
    Eigen::VectorXd e;
    Eigen::MatrixXd J;
    lm_knobs(knobs, err, step_of, max_iter, 1e-3, 1e-7, false, e, J);
}

// Small LM for the impact laws: minimises sum f(theta)^2 with bounds; returns the covariance scale (J'J)^-1.
Eigen::MatrixXd lm_small(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, Eigen::VectorXd& th,
                         const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
    const Eigen::Index p = th.size();
    Eigen::VectorXd r = f(th);
    double ss = r.squaredNorm(), lambda = 1e-3;
    Eigen::MatrixXd J(r.size(), p);
    auto jac = [&] {
        for (Eigen::Index k = 0; k < p; ++k) {
            Eigen::VectorXd t2 = th;
            const double h = 1e-6 * std::max(1.0, std::abs(th[k])) * (th[k] + 1e-6 * std::max(1.0, std::abs(th[k])) > hi[k] ? -1 : 1);
            t2[k] += h;
            J.col(k) = (f(t2) - r) / h;
        }
    };
    jac();
    for (int it = 0; it < 100; ++it) {
        const Eigen::MatrixXd A = J.transpose() * J;
        const Eigen::VectorXd g = J.transpose() * r;
        bool ok = false;
        for (int tries = 0; tries < 10; ++tries) {
            Eigen::MatrixXd Ad = A;
            for (Eigen::Index k = 0; k < p; ++k) Ad(k, k) += lambda * A(k, k) + 1e-12;
            Eigen::VectorXd tn = th + Ad.ldlt().solve(-g);
            for (Eigen::Index k = 0; k < p; ++k) tn[k] = std::clamp(tn[k], lo[k], hi[k]);
            const Eigen::VectorXd rn = f(tn);
            if (rn.squaredNorm() < ss) {
                ok = (ss - rn.squaredNorm()) > 1e-12 * ss;
                th = tn;
                r = rn;
                ss = r.squaredNorm();
                lambda = std::max(lambda / 4, 1e-12);
                break;
            }
            lambda *= 8;
        }
        if (!ok) break;
        jac();
    }
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

ImpactLawError impact_error(const Prep& pr, const Model& m) {
    ImpactLawError e;
    if (!m.bumper || pr.impacts.empty()) return e;
    const double g = m.sensor_gain(), o = m.sensor_offset();
    double sk = 0, sd = 0;
    std::size_t nk = 0;
    std::vector<double> lev;
    for (const auto& im : pr.impacts) {
        double kappa, dwell;
        model_impact_law(m.p, im.v_minus / g, kappa, dwell);
        if (im.v_minus > 0.02) {
            const double k = -im.v_plus / im.v_minus - kappa;
            sk += k * k;
            ++nk;
        }
        const double dd = (im.t_out - im.t_in) - dwell;
        sd += dd * dd;
        lev.push_back(im.level);
    }
    e.impacts = pr.impacts.size();
    e.kappa_rms = nk ? std::sqrt(sk / static_cast<double>(nk)) : 0.0;
    e.duration_rms_s = std::sqrt(sd / static_cast<double>(pr.impacts.size()));
    e.level_offset_m = median(lev) - (g * m.p.xI + o);
    return e;
}

std::vector<std::pair<std::string, double>> named(const EffectInstance& e) {
    std::vector<std::pair<std::string, double>> v;
    for (std::size_t k = 0; k < kMaxLawParams && e.law->names[k]; ++k) v.emplace_back(e.law->names[k], e.p[k]);
    return v;
}

double rms_of(const Eigen::VectorXd& R) { return R.size() ? std::sqrt(R.squaredNorm() / static_cast<double>(R.size())) : 0.0; }

}  // namespace

FitReport run_fit(const MeasuredData& data, const Model& model0, const FitOptions& o, const MeasuredData* test) {
    const auto clock0 = std::chrono::steady_clock::now();
    FitReport rep;
    rep.data_source = data.source;
    rep.model_name = model0.p.name;
    rep.forcing = data.has_phi() ? "phi (unbalance)" : "u (measured input)";
    rep.baseline = o.fit_baseline ? "fit" : "fixed";
    validate(model0.p, "model");
    const Prep pr = prepare(data, model0, o, rep.notes);
    rep.samples = pr.n;
    rep.rows_used = pr.rows.size();
    rep.dt = pr.dt;
    rep.duration = data.t.back() - data.t.front();
    rep.sigma_x = pr.sigma_x;
    rep.window_s = (pr.K.H + 1) * pr.dt;
    rep.period_s = pr.period;
    rep.drive_fit_rms_rad = pr.drive_rms;
    if (pr.phi_forced) {
        rep.omega_min = *std::min_element(pr.omega.begin(), pr.omega.end());
        rep.omega_max = *std::max_element(pr.omega.begin(), pr.omega.end());
    }
    const int stride = std::max(1, pr.K.H / 4);
    const int hac_lag = static_cast<int>(std::ceil(2.0 * (2 * pr.K.H + 1) / stride));

    // ---- 1. the baseline --------------------------------------------------------------------------------
    Model base = model0;
    std::vector<double> pw;
    Eigen::VectorXd R0, Rtmp;
    Eigen::MatrixXd Jtmp;
    std::vector<std::string> base_names;
    if (o.fit_baseline) {
        base_names = o.fit_params.empty() ? default_fit_params(base) : o.fit_params;
        auto bp = base_params(base, base_names);
        std::vector<Knob> knobs;
        for (const auto& b : bp) {
            double lo = -1e12, hi = 1e12;
            if (b.name == "c" || b.name == "T" || b.name == "m0e" || b.name == "m") lo = 0;
            if (b.name == "b2") lo = -50;
            knobs.push_back({b.value, std::max(1e-4 * std::abs(*b.value), 1e-6), lo, hi, b.name});
        }
        // A first pass from the starting values (linear parameters converge in one step), then refine.
        lm_residual(pr, base, knobs, 40, R0, Jtmp);
        // Input-forced data: refine by the simulation error, which the equation error at a few samples per
        // period of the resonance cannot match.
        if (!pr.phi_forced) {
            lm_simulation(pr, base, knobs, 30, o.rtol);
            rep.notes.push_back("baseline refined on the free-run simulation error (output error)");
        }
    }
    residual(pr, base, R0, pw);
    rep.before = base;
    const double in0 = R0.squaredNorm();
    rep.noise_floor_N = base.p.m * pr.sigma_x * pr.K.noise_gain / base.sensor_gain();

    // ---- 2. candidate columns -----------------------------------------------------------------------------
    struct Group {
        std::size_t cand;
        double start;
        EffectInstance inst;
        std::vector<int> cols;
    };
    const std::vector<Candidate> cands = library_candidates(base, pr, o);
    std::vector<Eigen::VectorXd> columns;
    std::vector<int> base_cols;
    std::vector<BaseParam> bparams;
    if (o.fit_baseline) {
        bparams = base_params(base, base_names);
        for (const auto& b : bparams) {
            const double v0 = *b.value, h = std::max(1e-4 * std::abs(v0), 1e-6);
            *b.value = v0 + h;
            residual(pr, base, Rtmp, pw);
            *b.value = v0;
            columns.push_back(-(Rtmp - R0) / h);
            base_cols.push_back(static_cast<int>(columns.size()) - 1);
        }
    }
    std::vector<Group> groups;
    for (std::size_t ci = 0; ci < cands.size(); ++ci) {
        const Candidate& c = cands[ci];
        const std::vector<double> starts = c.starts.empty() ? std::vector<double>{0.0} : c.starts;
        for (double st : starts) {
            Group g{ci, st, start_instance(c, base, pr, st), {}};
            for (int li : c.linear) {
                const int k = c.free[static_cast<std::size_t>(li)];
                const double h = c.step[static_cast<std::size_t>(li)];
                Eigen::VectorXd col(static_cast<Eigen::Index>(pr.rows.size()));
                if (c.sensor) {
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
            groups.push_back(std::move(g));
        }
    }
    Eigen::MatrixXd X(R0.size(), static_cast<Eigen::Index>(columns.size()));
    for (std::size_t k = 0; k < columns.size(); ++k) X.col(static_cast<Eigen::Index>(k)) = columns[k];
    const Folds folds = make_folds(X, R0, 5);

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

    // ---- 3. greedy selection ------------------------------------------------------------------------------
    std::vector<int> cur = base_cols;
    double cv_cur, in_cur;
    cv_sse(folds, cur, cv_cur, in_cur);
    const double in_base = in_cur;
    std::vector<std::size_t> chosen;   // group indices
    std::vector<double> step_gain;
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
            for (const auto& e : evals)
                rep.candidates.push_back({cands[groups[e.g].cand].id, e.gain_in, e.z, false});
        const Eval* lib = nullptr;
        const Eval* gen = nullptr;
        for (const auto& e : evals) {
            if (!(e.gain_cv >= o.min_gain && e.z >= o.z_threshold && e.gain_in > 0)) continue;
            const bool g = cands[groups[e.g].cand].generic;
            if (g && !gen) gen = &e;
            if (!g && !lib) lib = &e;
        }
        const Eval* pick = lib;
        if (gen && (!lib || lib->gain_cv < 0.8 * gen->gain_cv)) pick = gen;
        if (!pick) break;
        const Group& g = groups[pick->g];
        cand_used[g.cand] = true;
        chosen.push_back(pick->g);
        step_gain.push_back(pick->gain_in);
        cur.insert(cur.end(), g.cols.begin(), g.cols.end());
        cv_sse(folds, cur, cv_cur, in_cur);
        for (auto& cs : rep.candidates)
            if (cs.id == cands[g.cand].id) cs.selected = true;
    }

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
        sc.m = base.p.m;
    }
    Model after = base;
    std::vector<FoundEffect> force_found;
    const std::size_t first_new = base.p.effects.size();
    for (;;) {
        after = base;
        {
            std::vector<int> cols = base_cols;
            for (std::size_t gi : chosen) cols.insert(cols.end(), groups[gi].cols.begin(), groups[gi].cols.end());
            double cv, in;
            Eigen::VectorXd beta;
            cv_sse(folds, cols, cv, in, &beta);
            std::size_t pos = base_cols.size();   // base parameters: refitted below
            for (std::size_t gi : chosen) {
                const Group& g = groups[gi];
                EffectInstance inst = g.inst;
                const Candidate& c = cands[g.cand];
                for (int li : c.linear)
                    inst.p[static_cast<std::size_t>(c.free[static_cast<std::size_t>(li)])] += beta[static_cast<Eigen::Index>(pos++)];
                after.p.effects.push_back(inst);
            }
        }
        std::vector<Knob> knobs;
        if (o.fit_baseline) {
            for (const auto& b : base_params(after, base_names)) {
                double lo = -1e12;
                if (b.name == "c" || b.name == "T" || b.name == "m0e" || b.name == "m") lo = 0;
                if (b.name == "b2") lo = -50;
                knobs.push_back({b.value, std::max(1e-4 * std::abs(*b.value), 1e-6), lo, 1e12, b.name});
            }
        }
        const std::size_t n_base_knobs = knobs.size();
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            const Candidate& c = cands[groups[chosen[k]].cand];
            EffectInstance& inst = after.p.effects[first_new + k];
            for (std::size_t li = 0; li < c.free.size(); ++li) {
                const auto pi = static_cast<std::size_t>(c.free[li]);
                double lo = -1e12, hi = 1e12;
                if (c.id == "stribeck_friction") lo = pi == 1 ? 0.005 : 0.0;
                if (c.id == "sensor_gain") {
                    lo = 0.5;
                    hi = 2.0;
                }
                knobs.push_back({&inst.p[pi], c.step[li], lo, hi, c.law->names[pi]});
            }
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
            const EffectInstance& inst = after.p.effects[first_new + k];
            FoundEffect f;
            f.id = c.id;
            f.evidence = "equation error";
            f.explained_fraction = step_gain[k] * in_base / std::max(in0, 1e-300);
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
            if (c.id == "stribeck_friction") {   // the speed scale has no null value: test Fs alone
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
    // Input-forced data: the simulation error decides. Refit everything on it, then keep an effect only if
    // the refitted model without it simulates the validation part clearly worse (1 %).
    if (!pr.phi_forced && o.fit_baseline && !chosen.empty()) {
        auto oe_fit = [&](Model& m, std::size_t skip, int iters) {
            std::vector<Knob> kn;
            for (const auto& b : base_params(m, base_names)) {
                double lo = -1e12;
                if (b.name == "c" || b.name == "T" || b.name == "m0e" || b.name == "m") lo = 0;
                kn.push_back({b.value, std::max(1e-4 * std::abs(*b.value), 1e-6), lo, 1e12, b.name});
            }
            for (std::size_t k = 0, e = 0; k < chosen.size(); ++k) {
                if (k == skip) continue;
                const Candidate& c = cands[groups[chosen[k]].cand];
                EffectInstance& inst = m.p.effects[first_new + e++];
                for (std::size_t li = 0; li < c.free.size(); ++li) {
                    const auto pi = static_cast<std::size_t>(c.free[li]);
                    kn.push_back({&inst.p[pi], c.step[li], c.id == "stribeck_friction" ? (pi == 1 ? 0.005 : 0.0) : -1e12,
                                  c.id == "sensor_gain" ? 2.0 : 1e12, c.law->names[pi]});
                }
            }
            lm_simulation(pr, m, kn, iters, o.rtol);
            // Judged out of sample: on the part of the record the fit did not use.
            const std::vector<double> fr = free_run(pr, m, o.rtol);
            std::size_t first = 0;
            while (first < pr.n && !std::isfinite(fr[first])) ++first;
            const std::size_t fit_end = oe_fit_end(pr, first, 30000);
            const double rms = free_run_rms(fr, data.x, fit_end + 1);
            return rms < 0 ? INFINITY : rms;
        };
        double rms_all = oe_fit(after, chosen.size(), 20);
        for (std::size_t k = chosen.size(); k-- > 0;) {
            Model without = after;
            without.p.effects.erase(without.p.effects.begin() + static_cast<long>(first_new + k));
            const double rms_without = oe_fit(without, k, 10);
            if (rms_without <= 1.01 * rms_all) {
                rms_all = std::min(rms_all, rms_without);
                rep.notes.push_back("dropped " + force_found[k].id + ": without it the refitted model simulates the validation part as well (" +
                                    std::to_string(rms_without) + " against " + std::to_string(rms_all) + ")");
                for (auto& cs : rep.candidates)
                    if (cs.id == force_found[k].id) cs.selected = false;
                after = without;
                chosen.erase(chosen.begin() + static_cast<long>(k));
                force_found.erase(force_found.begin() + static_cast<long>(k));
            }
        }
        // The reported values are the simulation-error fit's; their uncertainties stay the equation error's.
        for (std::size_t k = 0; k < force_found.size(); ++k) {
            force_found[k].parameters = named(after.p.effects[first_new + k]);
            force_found[k].sentence = sentence(force_found[k].id, base, force_found[k].parameters, force_found[k].sigma, sc);
        }
        rep.notes.push_back("effects refitted on the free-run simulation error (output error)");
    }
    // A sensor offset moves the measured bumper level too: if the impacts' flat tops contradict it, the
    // offset is an artefact of the free-flight fit and goes (the impact stage then sees the level as it is).
    if (after.bumper && pr.impacts.size() >= 3) {
        for (std::size_t k = 0; k < force_found.size(); ++k) {
            if (force_found[k].id != "sensor_offset") continue;
            std::vector<double> lev;
            for (const auto& im : pr.impacts) lev.push_back(im.level);
            const double o_imp = median(lev) - after.sensor_gain() * after.p.xI;
            const double o_fit = after.sensor_offset(), so = force_found[k].sigma.empty() ? 0.0 : force_found[k].sigma[0].second;
            if (std::abs(o_fit - o_imp) > std::max(5.0 * so, 5.0 * pr.sigma_x + 1e-6)) {
                rep.notes.push_back("dropped sensor_offset: the impacts' flat tops put the bumper where the uncorrected sensor does");
                for (auto& cs : rep.candidates)
                    if (cs.id == "sensor_offset") cs.selected = false;
                for (auto it = after.p.effects.begin(); it != after.p.effects.end(); ++it)
                    if (std::string(it->law->id) == "sensor_offset") {
                        after.p.effects.erase(it);
                        break;
                    }
                force_found.erase(force_found.begin() + static_cast<long>(k));
                break;
            }
        }
    }
    for (auto& f : force_found) rep.effects_found.push_back(std::move(f));

    // ---- 5. the impact law: bumper position, impact duration, restitution ----------------------------------
    if (after.bumper && pr.impacts.size() >= 3) {
        const double g = after.sensor_gain(), off = after.sensor_offset();
        const std::size_t ni = pr.impacts.size();
        std::vector<double> lev;
        for (const auto& im : pr.impacts) lev.push_back((im.level - off) / g);
        const double med = median(lev);
        std::vector<double> dev;
        for (double l : lev) dev.push_back(std::abs(l - med));
        const double se = std::max(1.2533 * 1.4826 * median(dev), 0.3 * pr.sigma_x) / std::sqrt(static_cast<double>(ni));
        const double delta = med - after.p.xI;
        if (std::abs(delta) / se >= o.z_threshold && std::abs(delta) > 2.0 * pr.sigma_x + 1e-7) {
            double sb = 0, sa = 0;
            for (double l : lev) {
                sb += (l - after.p.xI) * (l - after.p.xI);
                sa += (l - med) * (l - med);
            }
            FoundEffect f;
            f.id = "bumper_offset";
            f.evidence = "impact law";
            f.explained_fraction = sb > 0 ? 1.0 - sa / sb : 0.0;
            f.parameters = {{"dx", delta}};
            f.sigma = {{"dx", se}};
            f.z = std::abs(delta) / se;
            f.sentence = sentence("bumper_offset", after, f.parameters, f.sigma, sc);
            apply_effect(after, "bumper_offset", {{"dx", delta}});
            rep.effects_found.push_back(std::move(f));
        }
        // The dwell time and the restitution against the model's laws.
        for (const char* which : {"impact_duration", "restitution"}) {
            const bool dur = std::strcmp(which, "impact_duration") == 0;
            std::vector<double> vm, obs;
            for (const auto& im : pr.impacts) {
                if (!dur && im.v_minus < 0.02) continue;
                vm.push_back(im.v_minus / g);
                obs.push_back(dur ? im.t_out - im.t_in : -im.v_plus / im.v_minus);
            }
            const auto n = static_cast<Eigen::Index>(vm.size());
            if (n < 3) continue;
            Eigen::VectorXd model_pred(n);
            for (Eigen::Index i = 0; i < n; ++i) {
                double kap, dw;
                model_impact_law(after.p, vm[static_cast<std::size_t>(i)], kap, dw);
                model_pred[i] = dur ? dw : kap;
            }
            auto law = [&](const Eigen::VectorXd& th) {
                Eigen::VectorXd r(n);
                for (Eigen::Index i = 0; i < n; ++i)
                    r[i] = (th[0] - th[1]) * std::exp(-th[2] * vm[static_cast<std::size_t>(i)]) + th[1] - obs[static_cast<std::size_t>(i)];
                return r;
            };
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
            double sb = 0;
            for (Eigen::Index i = 0; i < n; ++i) sb += std::pow(obs[static_cast<std::size_t>(i)] - model_pred[i], 2);
            const double floor_var = dur ? std::pow(0.05 * pr.dt, 2) : 1e-4;
            const double s2 = std::max(sa / std::max<double>(1.0, static_cast<double>(n) - 3.0), floor_var);
            const double z = chi2_to_z((sb - sa) / s2, 3);
            const double gain_rms = std::sqrt(sb / static_cast<double>(n)) - std::sqrt(sa / static_cast<double>(n));
            const bool practical = dur ? gain_rms > 0.2 * pr.dt : gain_rms > 0.02;
            if (z >= o.z_threshold && practical && sb > 0) {
                FoundEffect f;
                f.id = which;
                f.evidence = "impact law";
                f.explained_fraction = 1.0 - sa / sb;
                const char* nm[3] = {dur ? "Ti0" : "kappa0", dur ? "Ti1" : "kappa1", dur ? "a_T" : "a_kappa"};
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
    std::stable_sort(rep.effects_found.begin(), rep.effects_found.end(),
                     [](const FoundEffect& a, const FoundEffect& b) { return a.explained_fraction > b.explained_fraction; });
    if (!rep.effects_found.empty()) after.p.name = base.p.name + "+" + rep.effects_found.front().id;
    for (std::size_t k = 1; k < rep.effects_found.size(); ++k) after.p.name += "+" + rep.effects_found[k].id;
    rep.after = after;

    // ---- 6. errors before and after ------------------------------------------------------------------------
    Eigen::VectorXd R1;
    residual(pr, after, R1, pw);
    auto errors = [&](const Model& m, const Eigen::VectorXd& R, ErrorSummary& e, ShootOut& so) {
        e.residual_rms_N = rms_of(R);
        so = shooting(pr, m, o);
        e.shooting_rms_1_m = so.rms1;
        e.shooting_rms_10_m = so.rms10;
        e.impact = impact_error(pr, m);
        if (!pr.phi_forced) {
            e.simulation_rms_m = free_run_rms(free_run(pr, m, o.rtol), data.x);
        }
    };
    ShootOut sb, sa;
    errors(base, R0, rep.error_before, sb);
    errors(after, R1, rep.error_after, sa);
    if (pr.phi_forced && rep.omega_max - rep.omega_min > 2 * o.omega_bin) {
        rep.diagram_measured = measured_sections(pr);
        rep.diagram_before = free_run_sections(pr, base, o.rtol);
        rep.diagram_after = free_run_sections(pr, after, o.rtol);
        rep.error_before.diagram_distance_m =
            diagram_distance(rep.diagram_measured, rep.diagram_before, o.omega_bin, rep.error_before.diagram_bins,
                             &rep.error_before.diagram_per_bin);
        rep.error_after.diagram_distance_m =
            diagram_distance(rep.diagram_measured, rep.diagram_after, o.omega_bin, rep.error_after.diagram_bins,
                             &rep.error_after.diagram_per_bin);
    }
    if (test) {
        std::vector<std::string> tnotes;
        const Prep pt = prepare(*test, model0, o, tnotes);
        for (auto [m, e] : {std::pair<const Model*, ErrorSummary*>{&base, &rep.error_before}, {&after, &rep.error_after}}) {
            const std::vector<double> fr = free_run(pt, *m, o.rtol);
            double s = 0;
            std::size_t c = 0;
            for (std::size_t i = 0; i < pt.n; ++i)
                if (std::isfinite(fr[i])) {
                    s += (fr[i] - test->x[i]) * (fr[i] - test->x[i]);
                    ++c;
                }
            e->test_simulation_rms_m = c ? std::sqrt(s / static_cast<double>(c)) : -1;
        }
    }

    // ---- 7. material for the plots -----------------------------------------------------------------------
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
        if (!sb.windows10.empty()) {
            const auto worst = std::max_element(sb.windows10.begin(), sb.windows10.end(),
                                                [](const auto& a, const auto& b) { return a.second < b.second; });
            for (const auto& [a, b] : windows(pr, 10))
                if (a == worst->first) {
                    rep.trace.before = simulate_window(pr, base, a, b, o.refine_shooting, o.rtol);
                    rep.trace.after = simulate_window(pr, after, a, b, o.refine_shooting, o.rtol);
                    for (std::size_t i = a; i <= b; ++i) {
                        rep.trace.t.push_back(data.t[i]);
                        rep.trace.measured.push_back(data.x[i]);
                    }
                    break;
                }
        }
        for (const auto& im : pr.impacts) rep.impacts.push_back({im.t_in, im.v_minus, im.v_plus, im.t_out - im.t_in, im.level});
    }
    if (rep.effects_found.empty()) rep.notes.push_back("no missing effect: the residual is at the level of the noise and the model's own error");
    rep.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
    return rep;
}

ErrorSummary evaluate_model(const MeasuredData& data, const Model& model, const FitOptions& o) {
    std::vector<std::string> notes;
    validate(model.p, "model");
    const Prep pr = prepare(data, model, o, notes);
    ErrorSummary e;
    Eigen::VectorXd R;
    std::vector<double> pw;
    residual(pr, model, R, pw);
    e.residual_rms_N = rms_of(R);
    const ShootOut so = shooting(pr, model, o);
    e.shooting_rms_1_m = so.rms1;
    e.shooting_rms_10_m = so.rms10;
    e.impact = impact_error(pr, model);
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
