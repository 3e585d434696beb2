// Stages 2 and 3 of the fit: the candidates' regressors and the greedy selection.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

// The candidates' regressors (stage 2): for each library candidate, and each trial value of its nonlinear
// parameter, the columns dR/dp of its linear parameters at the baseline (and the fitted base parameters'
// columns first), with the 5-fold cross-validation blocks over them.
void screen_candidates(FitSession& fs) {
    const Prep& pr = fs.prep;
    const Model& base = fs.base;
    const FitOptions& o = fs.o;
    const std::vector<std::string>& base_names = fs.base_names;
    const Eigen::VectorXd& R0 = fs.R0;
    Screen& sc = fs.screen;
    sc.cands = library_candidates(base, pr, o);
    const std::vector<Candidate>& cands = sc.cands;
    std::vector<Eigen::VectorXd> columns;
    std::vector<double> pw;
    Eigen::VectorXd Rtmp;
    if (o.fit_baseline) {
        Model mb = base;
        const std::vector<BaseParam> bparams = base_params(mb, base_names);
        for (const auto& b : bparams) {
            const double v0 = *b.value, h = std::max(1e-4 * std::abs(v0), 1e-4 * base_scale(b.name, pr, base));
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

}

namespace {

// The greedy selection's state: the columns chosen so far (the base's first), their CV and in-sample sums of
// squares, and the candidates already used.
class Selector {
public:
    // A candidate's best group (trial value) in one round: its CV and in-sample gains, and its z.
    struct Eval {
        std::size_t g;
        double gain_cv, gain_in, z = 0;
    };

    explicit Selector(FitSession& fs)
        : fs_(fs), o_(fs.o), cands_(fs.screen.cands), groups_(fs.screen.groups), X_(fs.screen.X), folds_(fs.screen.folds),
          cur_(fs.screen.base_cols), cand_used_(cands_.size(), false) {
        cv_sse(folds_, cur_, cv_cur_, in_cur_);
        fs.sel.in_base = in_cur_;
        in_base_ = in_cur_;
    }

    // One round: false where nothing more is chosen. A pair of named effects counts as two rounds.
    bool round(int& round_no) {
        bool generic_chosen = false;
        for (std::size_t gi : fs_.sel.chosen) generic_chosen = generic_chosen || cands_[groups_[gi].cand].generic;
        std::vector<Eval> evals = evaluate(round_no, generic_chosen);
        if (round_no == 0) report_candidates(evals);
        const std::vector<const Eval*> picks = choose(evals, generic_chosen);
        if (picks.empty()) return false;
        set_rival_aside(evals, picks);
        const bool pair = picks.size() == 2;
        for (const Eval* pick : picks) {
            const Group& g = groups_[pick->g];
            cand_used_[g.cand] = true;
            fs_.sel.chosen.push_back(pick->g);
            if (!pair) fs_.sel.step_gain.push_back(pick->gain_in);
            cur_.insert(cur_.end(), g.cols.begin(), g.cols.end());
            for (auto& cs : fs_.rep.candidates)
                if (cs.id == cands_[g.cand].id) cs.selected = true;
        }
        cv_sse(folds_, cur_, cv_cur_, in_cur_);
        if (pair) ++round_no;
        return true;
    }

private:
    // The z of the sub-block `sub` (positions in cols) of the columns cols fitted together: the smaller of its
    // HAC Wald statistic's and of the rise of the sum of squares without it.
    double zscore(const std::vector<int>& cols, const std::vector<int>& sub) const {
        const int hac_lag = fs_.hac_lag;
        double cv, in;
        Eigen::VectorXd beta;
        cv_sse(folds_, cols, cv, in, &beta);
        Eigen::MatrixXd Xs(X_.rows(), static_cast<Eigen::Index>(cols.size()));
        for (std::size_t k = 0; k < cols.size(); ++k) Xs.col(static_cast<Eigen::Index>(k)) = X_.col(cols[k]);
        const Eigen::VectorXd e = fs_.R0 - Xs * beta;
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
    }

    // A group's coefficients fitted on top of the columns chosen so far: its instance with them, and the
    // coefficients (a base change's is its first).
    EffectInstance fitted_on_cur(const Group& g, Eigen::VectorXd& beta) const {
        std::vector<int> cols = cur_;
        cols.insert(cols.end(), g.cols.begin(), g.cols.end());
        double cv, in;
        cv_sse(folds_, cols, cv, in, &beta);
        EffectInstance inst = g.inst;
        const Candidate& c = cands_[g.cand];
        if (!c.base)
            for (std::size_t li = 0; li < c.linear.size(); ++li)
                inst.p[static_cast<std::size_t>(c.free[static_cast<std::size_t>(c.linear[li])])] +=
                    beta[static_cast<Eigen::Index>(cur_.size() + li)];
        return inst;
    }

    // Each unused candidate at its best trial value, best CV gain first, the strongest ones with their z.
    std::vector<Eval> evaluate(int round_no, bool generic_chosen) const {
        std::vector<Eval> best_per_cand(cands_.size(), {0, -INFINITY, 0, 0});
        for (std::size_t gi = 0; gi < groups_.size(); ++gi) {
            const Group& g = groups_[gi];
            if (cand_used_[g.cand]) continue;
            // After a generic smooth force, a sensor calibration is no longer identifiable against it.
            if (generic_chosen && cands_[g.cand].sensor) continue;
            std::vector<int> cols = cur_;
            cols.insert(cols.end(), g.cols.begin(), g.cols.end());
            double cv, in;
            cv_sse(folds_, cols, cv, in);
            const double gcv = (cv_cur_ - cv) / cv_cur_, gin = (in_cur_ - in) / in_base_;
            if (cands_[g.cand].positive) {
                Eigen::VectorXd beta;
                double cv2, in2;
                cv_sse(folds_, cols, cv2, in2, &beta);
                if (!(beta[static_cast<Eigen::Index>(cur_.size())] > 0)) continue;
            }
            if (gcv > best_per_cand[g.cand].gain_cv) best_per_cand[g.cand] = {gi, gcv, gin, 0};
        }
        std::vector<Eval> evals;
        for (std::size_t c = 0; c < cands_.size(); ++c)
            if (!cand_used_[c] && std::isfinite(best_per_cand[c].gain_cv)) evals.push_back(best_per_cand[c]);
        std::sort(evals.begin(), evals.end(), [](const Eval& a, const Eval& b) { return a.gain_cv > b.gain_cv; });
        int lib_checked = 0, gen_checked = 0;
        for (auto& e : evals) {
            const bool gen = cands_[groups_[e.g].cand].generic;
            int& checked = gen ? gen_checked : lib_checked;
            if (checked >= 4 && round_no > 0) continue;
            ++checked;
            std::vector<int> cols = cur_, sub;
            for (int c : groups_[e.g].cols) {
                sub.push_back(static_cast<int>(cols.size()));
                cols.push_back(c);
            }
            e.z = zscore(cols, sub);
        }
        return evals;
    }

    // The first round's scores: each candidate's parameters fitted alone on the baseline residual, sign and
    // size, selected or not.
    void report_candidates(const std::vector<Eval>& evals) const {
        for (const auto& e : evals) {
            const Candidate& c = cands_[groups_[e.g].cand];
            Eigen::VectorXd beta;
            const EffectInstance inst = fitted_on_cur(groups_[e.g], beta);
            if (c.base)
                fs_.rep.candidates.push_back({c.id, e.gain_in, e.z, false, {{c.param, beta[static_cast<Eigen::Index>(cur_.size())]}}, e.gain_cv});
            else fs_.rep.candidates.push_back({c.id, e.gain_in, e.z, false, named(inst), e.gain_cv});
        }
    }

    // What this round chooses: the best library effect, or where a generic term explains more than it by more
    // than the scatter, the best pair of library effects that comes as close, or the generic term.
    std::vector<const Eval*> choose(const std::vector<Eval>& evals, bool generic_chosen) {
        const Eval* lib = nullptr;
        const Eval* gen = nullptr;
        for (const auto& e : evals) {
            if (!(e.gain_cv >= o_.min_gain && e.z >= o_.z_threshold && e.gain_in > 0)) continue;
            const bool g = cands_[groups_[e.g].cand].generic;
            if (g && !gen) gen = &e;
            if (!g && !lib) lib = &e;
        }
        // Named physics before curve fits: a generic term is chosen only where neither the best library effect
        // nor the best pair of library effects fitted jointly comes within the scatter of what it explains
        // (the CV sums' difference against its noise, plus a penalty for each parameter the generic term has
        // more, and never closer than 2 % of what the generic term explains).
        std::vector<const Eval*> picks;
        if (lib) picks = {lib};
        if (!gen) return picks;
        const double cv_gen = cv_cur_ * (1.0 - gen->gain_cv);
        const double sigma2 = cv_gen / static_cast<double>(std::max<Eigen::Index>(1, X_.rows()));
        const double B = std::max(1.0, static_cast<double>(fs_.hac_lag));
        auto tol = [&](std::size_t named_params) {
            const double dp = static_cast<double>(groups_[gen->g].cols.size()) - static_cast<double>(named_params);
            return std::max(sigma2 * B * (16.0 + 2.0 * std::max(dp, 0.0)), 0.02 * (cv_cur_ - cv_gen));
        };
        const bool lib_close = lib && cv_cur_ * (1.0 - lib->gain_cv) <= cv_gen + tol(groups_[lib->g].cols.size());
        if (lib_close) return picks;
        double pair_gain_in = 0;
        const std::vector<const Eval*> best_pair = close_pair(evals, generic_chosen, cv_gen, tol, pair_gain_in);
        if (best_pair.empty()) return {gen};
        fs_.rep.notes.push_back("a pair of named effects, " + cands_[groups_[best_pair[0]->g].cand].id + " and " +
                                cands_[groups_[best_pair[1]->g].cand].id + ", fitted jointly explains as much as the generic " +
                                cands_[groups_[gen->g].cand].id + ": the named pair is preferred");
        // The pair's explained share is split by each one's share alone.
        const double ga = std::max(best_pair[0]->gain_in, 1e-12), gb = std::max(best_pair[1]->gain_in, 1e-12);
        fs_.sel.step_gain.push_back(pair_gain_in * ga / (ga + gb));
        fs_.sel.step_gain.push_back(pair_gain_in * gb / (ga + gb));
        return best_pair;
    }

    // Pairs of the strongest library effects, fitted jointly; each must stand out of the noise in the pair, and
    // the pair come within tol of the generic term's CV sum cv_gen. The best, with its in-sample gain; or none.
    template <class Tol>
    std::vector<const Eval*> close_pair(const std::vector<Eval>& evals, bool generic_chosen, double cv_gen, const Tol& tol,
                                        double& pair_gain_in) const {
        std::vector<const Eval*> top;
        for (const auto& e : evals)
            if (!cands_[groups_[e.g].cand].generic && e.gain_cv > 0 && top.size() < 8) top.push_back(&e);
        double best_cv = INFINITY;
        std::vector<const Eval*> best_pair;
        for (std::size_t a = 0; a < top.size(); ++a)
            for (std::size_t b = a + 1; b < top.size(); ++b) {
                const Candidate& ca = cands_[groups_[top[a]->g].cand];
                const Candidate& cb = cands_[groups_[top[b]->g].cand];
                if (generic_chosen && (ca.sensor || cb.sensor)) continue;
                std::vector<int> cols = cur_, sa, sb;
                for (int c : groups_[top[a]->g].cols) {
                    sa.push_back(static_cast<int>(cols.size()));
                    cols.push_back(c);
                }
                for (int c : groups_[top[b]->g].cols) {
                    sb.push_back(static_cast<int>(cols.size()));
                    cols.push_back(c);
                }
                double cv, in;
                cv_sse(folds_, cols, cv, in);
                if (!(cv < best_cv)) continue;
                const std::size_t np = groups_[top[a]->g].cols.size() + groups_[top[b]->g].cols.size();
                if (cv > cv_gen + tol(np)) continue;
                if (zscore(cols, sa) < o_.z_threshold || zscore(cols, sb) < o_.z_threshold) continue;
                best_cv = cv;
                best_pair = {top[a], top[b]};
                pair_gain_in = (in_cur_ - in) / in_base_;
            }
        return best_pair;
    }

    // The generic term set aside: the one that explains most, if it stands out at all (the selection's z bar is
    // for naming; the held-out judge decides between it and the named effects), with its coefficients fitted in
    // the named effects' place.
    void set_rival_aside(const std::vector<Eval>& evals, const std::vector<const Eval*>& picks) {
        const Eval* rival = nullptr;
        for (const auto& e : evals)
            if (cands_[groups_[e.g].cand].generic && e.gain_cv >= o_.min_gain && e.gain_in > 0 && e.z >= 3.0) {
                rival = &e;
                break;
            }
        if (!rival || std::find(picks.begin(), picks.end(), rival) != picks.end()) return;
        Eigen::VectorXd beta;
        Rival rv{{}, rival->g, fitted_on_cur(groups_[rival->g], beta), rival->z};
        for (const Eval* pick : picks) rv.named.push_back(pick->g);
        fs_.sel.rivals.push_back(std::move(rv));
    }

    FitSession& fs_;
    const FitOptions& o_;
    const std::vector<Candidate>& cands_;
    const std::vector<Group>& groups_;
    const Eigen::MatrixXd& X_;
    const Folds& folds_;
    std::vector<int> cur_;   // the columns chosen so far
    double cv_cur_ = 0, in_cur_ = 0, in_base_ = 0;
    std::vector<bool> cand_used_;
};

}  // namespace

// Stage 3: greedy forward selection over the screened candidates. Each round adds the candidate (at its best
// trial value) that lowers the cross-validated residual most, if it explains at least o.min_gain of it and
// its coefficients stand out of the noise (z from serially-correlation-robust errors); a generic smooth
// force only where no library effect comes close. Fills rep.candidates from the first round.
void select_effects(FitSession& fs) {
    Selector sel(fs);
    for (int round = 0; round < fs.o.max_effects; ++round)
        if (!sel.round(round)) break;
}

}  // namespace impactlab::identify::detail
