// The fit's small tools: the least-squares passes it runs, knobs, significance tests, plausibility checks.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

void lm_residual(const Prep& pr, Model& m, std::vector<Knob>& knobs, int max_iter, Eigen::VectorXd& R, Eigen::MatrixXd& J) {
    ResidualCache cache(pr, m, knobs);
    auto eval = [&](Eigen::VectorXd& out) {
        cache.eval(out);
        return out.squaredNorm();
    };
    // The knob's own step, taken downwards where upwards would leave its bounds.
    auto step_of = [](const Knob& kb, double v0) { return v0 + kb.step > kb.hi ? -kb.step : kb.step; };
    LsqOptions lo;
    lo.max_iterations = max_iter;
    lo.function_tolerance = 1e-9;
    least_squares(knobs, eval, step_of, lo, R, &J);
}

void check_plausible(const MeasuredData& data, const Model& m, const FitOptions& o) {
    if (stiffness_kind(m.p) == StiffnessKind::DataUnits) return;   // data units: no rail, no bumper
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

std::size_t oe_fit_end(const Prep& pr, std::size_t a, std::size_t max_samples) {
    const std::size_t last = pr.run_last(a);   // a free run stays within its run
    return std::min(last, a + std::min(max_samples, (last + 1 - a) / 2));
}

double free_run_rms(const std::vector<double>& fr, const std::vector<double>& x, std::size_t from) {
    double s = 0;
    std::size_t c = 0;
    for (std::size_t i = from; i < fr.size(); ++i)
        if (std::isfinite(fr[i])) {
            s += (fr[i] - x[i]) * (fr[i] - x[i]);
            ++c;
        }
    return c ? std::sqrt(s / static_cast<double>(c)) : -1.0;
}


namespace {
// Where a knob of a model lies, so that the same knob can be set in a copy: an effect's parameter by instance
// and index, or a base parameter by its offset in the Model object.
struct KnobPlace {
    std::ptrdiff_t effect = -1;   // -1: `at` is the byte offset in the Model
    std::size_t at = 0;
};
bool knob_places(const Model& m, const std::vector<Knob>& knobs, std::vector<KnobPlace>& out) {
    const char* base = reinterpret_cast<const char*>(&m);
    for (const Knob& k : knobs) {
        const char* v = reinterpret_cast<const char*>(k.value);
        KnobPlace pl;
        if (v >= base && v + sizeof(double) <= base + sizeof(Model)) {
            pl.at = static_cast<std::size_t>(v - base);
        } else {
            const int e = effect_holding(m, k.value);
            if (e < 0) return false;
            pl.effect = e;
            pl.at = static_cast<std::size_t>(k.value - m.p.effects[static_cast<std::size_t>(e)].p.data());
        }
        out.push_back(pl);
    }
    return true;
}
double* place_in(Model& c, const KnobPlace& pl) {
    if (pl.effect < 0) return reinterpret_cast<double*>(reinterpret_cast<char*>(&c) + pl.at);
    return &c.p.effects[static_cast<std::size_t>(pl.effect)].p[pl.at];
}
}  // namespace

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
    // A declared high-pass of the record's x acts on both over the stretch fitted: like with like.
    const bool hp = pr.x_highpass_hz > 0;
    const std::vector<double> xd = hp ? highpass_fft(std::vector<double>(d.x.begin() + static_cast<long>(a), d.x.begin() + static_cast<long>(b) + 1),
                                                     pr.dt, pr.x_highpass_hz)
                                      : std::vector<double>(d.x.begin() + static_cast<long>(a), d.x.begin() + static_cast<long>(b) + 1);
    auto err_of = [&](const Model& mm, Eigen::VectorXd& e) {
        std::vector<double> fr = simulate_window(pr, mm, a, b, false, fit_rtol);
        if (hp && fr.size() == xd.size()) fr = highpass_fft(fr, pr.dt, pr.x_highpass_hz);
        e.resize(static_cast<Eigen::Index>(b - a + 1));
        double ss = 0;
        for (std::size_t i = 0; i + a <= b; ++i) {
            const double r = i < fr.size() && std::isfinite(fr[i]) ? fr[i] - xd[i] : 0.0;
            e[static_cast<Eigen::Index>(i)] = r;
            ss += r * r;
        }
        return std::isfinite(ss) ? ss : INFINITY;
    };
    auto err = [&](Eigen::VectorXd& e) { return err_of(m, e); };
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
    // A trial model whose free run turns slow (a stiff or nearly unstable one) must not hold the fit: the
    // solve ends, at its best point, after a time in proportion to the samples it fits.
    lo.max_seconds = 20.0 + 1e-3 * static_cast<double>(b - a);
    // Each Jacobian column is a free run of its own: they run side by side, each on a copy of the model.
    std::vector<KnobPlace> places;
    if (knob_places(m, knobs, places))
        lo.eval_at = [&](const std::vector<double>& values, Eigen::VectorXd& out) {
            Model c = m;
            for (std::size_t k = 0; k < values.size(); ++k) *place_in(c, places[k]) = values[k];
            return err_of(c, out) < INFINITY;
        };
    least_squares(knobs, err, step_of, lo, e);
}

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

int hac_lag_of(const Prep& pr) {
    const int stride = std::max(1, pr.K.H / 4);
    return static_cast<int>(std::ceil(2.0 * (2 * pr.K.H + 1) / stride));
}

std::vector<Knob> base_knobs(Model& m, const std::vector<std::string>& names, const Prep& pr) {
    std::vector<Knob> knobs;
    for (const auto& b : base_params(m, names)) {
        // Unbounded but for the physics (Ceres leaves a bound beyond 1e11 unset), whatever the record's units.
        double lo = -INFINITY, hi = INFINITY;
        if (b.name == "c" || b.name == "T" || b.name == "m0e" || b.name == "m") lo = 0;
        if (b.name == "gain") (*b.value >= 0 ? lo : hi) = 0;
        if (b.name == "b2") lo = -50;   // the magnets' law is the rig's, in metres: 1 + b2 x^2 > 0 on the rail
        // The step follows the value, or the record's own scale of the parameter when the value is near zero
        // (a cubic started at 0 in units of 1e-4 would otherwise move no force at all).
        knobs.push_back({b.value, std::max(1e-4 * std::abs(*b.value), 1e-6 * base_scale(b.name, pr, m)), lo, hi, b.name});
    }
    return knobs;
}

void effect_knobs(const Candidate& c, EffectInstance& inst, std::vector<Knob>& knobs) {
    for (std::size_t li = 0; li < c.free.size(); ++li) {
        const auto pi = static_cast<std::size_t>(c.free[li]);
        knobs.push_back({&inst.p[pi], c.step[li], c.law->fit.lo[pi], c.law->fit.hi[pi], c.law->names[pi]});
    }
}

double base_value(const Model& m, const char* name) {
    Model copy = m;
    return *base_params(copy, {name}).front().value;
}

Knob base_change_knob(const Candidate& c, Model& m, const Model& base) {
    const double at_base = base_value(base, c.base);
    return {base_params(m, {c.base}).front().value, c.step[0], at_base + c.lo, at_base + c.hi, c.base};
}

double base_change(const Candidate& c, const Model& m, const Model& base) { return base_value(m, c.base) - base_value(base, c.base); }

std::vector<Knob> found_effect_knobs(Model& m, const Model& base, const std::vector<Candidate>& cands, std::vector<std::size_t>* owner) {
    std::vector<Knob> knobs;
    for (std::size_t k = base.p.effects.size(); k < m.p.effects.size(); ++k)
        for (const auto& c : cands)
            if (c.law && c.id == m.p.effects[k].law->id) {
                effect_knobs(c, m.p.effects[k], knobs);
                if (owner) owner->resize(knobs.size(), k);
                break;
            }
    for (const auto& c : cands)
        if (c.base && base_change(c, m, base) != 0.0) knobs.push_back(base_change_knob(c, m, base));
    if (owner) owner->resize(knobs.size(), SIZE_MAX);
    return knobs;
}

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


double rms_of(const Eigen::VectorXd& R) { return R.size() ? std::sqrt(R.squaredNorm() / static_cast<double>(R.size())) : 0.0; }

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

std::vector<std::pair<std::string, double>> refit_impact_law(const Prep& pr, const Model& m, const FoundEffect& f,
                                                             const std::vector<char>& use) {
    const ImpactLawData d = impact_law_data(pr, m, impact_trait(f.id) == ImpactTrait::Dwell, use);
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

}  // namespace impactlab::identify::detail
