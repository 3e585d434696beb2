// The weak-form equation error on free-flight samples: data preparation and evaluation.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "identify/internal.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/rig.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::identify::detail {

namespace {

// Velocity reversals. Dry friction makes the acceleration jump by 2T/m where v changes sign, and a
// Savitzky-Golay derivative smears that kink: it misplaces the reversal by milliseconds, and the friction
// force T sign(v) with it. Around each sign change of the smoothed velocity, fit
//   x = x0 + a1 s^2/2 + j s^3/6 + q s^4/24 (s = t - t0 < 0), a2 instead of a1 for s > 0,
// with the reversal time t0 found by a sub-sample search, and take v from that fit near t0.
void refine_reversals(const MeasuredData& d, Prep& pr) {
    const std::size_t n = pr.n;
    const int W = std::max(6, pr.Hv);
    std::vector<double> v = pr.vs;
    for (std::size_t c = static_cast<std::size_t>(W) + 1; c + static_cast<std::size_t>(W) + 2 < n; ++c) {
        if (!(pr.vs[c] * pr.vs[c + 1] <= 0) || !std::isfinite(pr.vs[c]) || !std::isfinite(pr.vs[c + 1])) continue;
        const std::size_t a = c - static_cast<std::size_t>(W), b = c + 1 + static_cast<std::size_t>(W);
        const double tc = d.t[c];
        double best = INFINITY, best_t0 = tc;
        Eigen::Matrix<double, 5, 1> best_beta = Eigen::Matrix<double, 5, 1>::Zero();
        for (double off = -3.0; off <= 4.0 + 1e-9; off += 0.1) {
            const double t0 = tc + off * pr.dt;
            Eigen::Matrix<double, 5, 5> G = Eigen::Matrix<double, 5, 5>::Zero();
            Eigen::Matrix<double, 5, 1> r = Eigen::Matrix<double, 5, 1>::Zero();
            double xx = 0;
            for (std::size_t j = a; j <= b; ++j) {
                const double s = d.t[j] - t0;
                Eigen::Matrix<double, 5, 1> row;
                row << 1.0, s < 0 ? 0.5 * s * s : 0.0, s < 0 ? 0.0 : 0.5 * s * s, s * s * s / 6.0, s * s * s * s / 24.0;
                G.noalias() += row * row.transpose();
                r.noalias() += row * d.x[j];
                xx += d.x[j] * d.x[j];
            }
            const Eigen::Matrix<double, 5, 1> beta = G.ldlt().solve(r);
            const double rss = xx - beta.dot(r);
            if (rss < best) {
                best = rss;
                best_t0 = t0;
                best_beta = beta;
            }
        }
        // Replace the smoothed velocity near the reversal (where the smearing matters) by the fit's.
        for (std::size_t j = a + 1; j < b; ++j) {
            const double s = d.t[j] - best_t0;
            v[j] = (s < 0 ? best_beta[1] : best_beta[2]) * s + 0.5 * best_beta[3] * s * s + best_beta[4] * s * s * s / 6.0;
        }
        c += static_cast<std::size_t>(W) / 2;
    }
    pr.vs.swap(v);
}

}  // namespace

namespace {

// The sampling must be uniform: every step within 1 % of the mean step pr.dt.
void check_uniform(const MeasuredData& d, const Prep& pr) {
    for (std::size_t i = 1; i < pr.n; ++i) {
        const double step = d.t[i] - d.t[i - 1];
        if (std::abs(step - pr.dt) > 0.01 * pr.dt) {
            std::ostringstream msg;
            msg << std::setprecision(6) << d.source << ": line " << d.line[i] << ": the time step " << step
                << " s differs from the mean step " << pr.dt << " s by more than 1%; impactlab fit needs uniform sampling";
            throw DataError(msg.str());
        }
    }
}

// Each run's drive (omega(t) fitted to its phi, or its measured input u), and the record's period. Returns the
// characteristic time the kernel's width follows.
double drives_by_run(const MeasuredData& d, const FitOptions& o, Prep& pr) {
    const std::size_t n = pr.n;
    double t_char;
    pr.phi.assign(n, 0.0);
    pr.omega.assign(n, 0.0);
    pr.alpha.assign(n, 0.0);
    pr.run_start = d.run_starts.empty() ? std::vector<std::size_t>{0} : d.run_starts;
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t a = pr.run_start[r], b = pr.run_last(a) + 1;
        if (b - a < 200)
            throw DataError((r < d.run_sources.size() ? d.run_sources[r] : d.source + ": run " + std::to_string(r + 1)) + ": only " +
                            std::to_string(b - a) + " samples; impactlab fit needs at least 200 in each run");
        const std::vector<double> t(d.t.begin() + static_cast<long>(a), d.t.begin() + static_cast<long>(b));
        if (pr.phi_forced) {
            double rms = 0;
            const std::vector<double> ph(d.phi.begin() + static_cast<long>(a), d.phi.begin() + static_cast<long>(b));
            pr.drives.push_back(fit_drive(t, ph, o.knot_spacing, rms));
            pr.drive_rms = std::max(pr.drive_rms, rms);
            for (std::size_t i = a; i < b; ++i) {
                pr.phi[i] = pr.drives.back().phi(d.t[i]);
                pr.omega[i] = pr.drives.back().omega(d.t[i]);
                pr.alpha[i] = pr.drives.back().alpha(d.t[i]);
            }
        } else {
            Drive in(0.0, t.front());
            in.set_input(t.front(), pr.dt, std::vector<double>(d.u.begin() + static_cast<long>(a), d.u.begin() + static_cast<long>(b)));
            pr.drives.push_back(std::move(in));
        }
    }
    if (pr.phi_forced) {
        const double wmax = std::max(quantile(pr.omega, 0.99), 0.5);
        t_char = kTwoPi / wmax;
        pr.period = kTwoPi / std::max(median(pr.omega), 0.5);
    } else {
        pr.u = d.u;
        // Each run about its own mean: runs in different wells would otherwise make their step between runs
        // the record's "dominant period", longer than any run, and leave no shooting window at all.
        std::vector<double> xc = d.x;
        for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
            const std::size_t a = pr.run_start[r], b = pr.run_last(a) + 1;
            double mean = 0, cnt = 0;
            for (std::size_t i = a; i < b; ++i)
                if (std::isfinite(xc[i])) {
                    mean += xc[i];
                    cnt += 1;
                }
            for (std::size_t i = a; i < b; ++i) xc[i] -= cnt > 0 ? mean / cnt : 0.0;
        }
        // A free run's "forcing period" is its own oscillation's. Its x may also settle (a decay into one of two
        // wells), a step whose spectrum would outweigh the oscillation's: the velocity's spectrum weighs each
        // frequency by itself, so the oscillation stands out (a 4 Hz decay into a well read as a 20 s period).
        if (pr.unforced) {
            for (std::size_t i = 0; i + 1 < xc.size(); ++i) xc[i] = xc[i + 1] - xc[i];
            if (!xc.empty()) xc.pop_back();
        }
        pr.period = dominant_period(xc, pr.dt);
        t_char = pr.period;
    }
    return t_char;
}

// The record's typical speed, input and force (the scales of the fit's knobs and tolerances).
void typical_sizes(const Model& m, Prep& pr) {
    double sv2 = 0, su2 = 0, cv = 0;
    for (std::size_t i = 0; i < pr.n; ++i)
        if (std::isfinite(pr.vs[i])) {
            sv2 += pr.vs[i] * pr.vs[i];
            cv += 1;
        }
    for (double u : pr.u)
        if (std::isfinite(u)) su2 += u * u;
    pr.v_typ = cv > 0 ? std::sqrt(sv2 / cv) : 0.0;
    if (!(pr.v_typ > 0)) pr.v_typ = pr.x_typ * kTwoPi / pr.period;
    pr.u_typ = pr.u.empty() ? 0.0 : std::sqrt(su2 / static_cast<double>(pr.u.size()));
    pr.f_typ = std::max(m.p.m * pr.v_typ * kTwoPi / pr.period, 1e-300);
}

// The zone no row's window may touch: the reach of the smoothers and the kernel (half-width H) around each
// run's start, and the impacts (found run by run) with a margin.
void impact_zone(const MeasuredData& d, const Model& m, int H, Prep& pr) {
    const std::size_t n = pr.n;
    pr.zone.assign(n, 0);
    // Nothing reaches across the start of a run: the smoothers' and the kernel's reach around it is left out.
    for (std::size_t r = 1; r < pr.run_start.size(); ++r) {
        const std::size_t reach = static_cast<std::size_t>(H + pr.Hv + 2);
        const std::size_t a = pr.run_start[r] >= reach ? pr.run_start[r] - reach : 0;
        for (std::size_t j = a; j < std::min(n, pr.run_start[r] + reach); ++j) pr.zone[j] = 1;
    }
    if (!m.bumper()) return;
    // Impacts run by run, so that the jump from one run to the next is never read as one.
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t a = pr.run_start[r], b = pr.run_last(a) + 1;
        const std::vector<double> t(d.t.begin() + static_cast<long>(a), d.t.begin() + static_cast<long>(b));
        const std::vector<double> x(d.x.begin() + static_cast<long>(a), d.x.begin() + static_cast<long>(b));
        for (ImpactObs im : find_impacts(t, x, pr.sigma_x, m.measure(m.p.xI))) {
            im.i_first += a;
            im.i_last += a;
            pr.impacts.push_back(im);
        }
    }
    // A margin of kMargin samples keeps the zone's edge away from the samples whose noise decided it
    // (otherwise the windows next to it would be chosen by the noise they contain: a biased residual).
    constexpr std::size_t kMargin = 10;
    for (const auto& im : pr.impacts) {
        const std::size_t a = im.i_first >= kMargin ? im.i_first - kMargin : 0, b = std::min(n - 1, im.i_last + kMargin);
        for (std::size_t j = a; j <= b; ++j) pr.zone[j] = 1;
    }
}

// Grazing contacts too brief to fit as impacts: every sample at the bumper's level joins the zone.
void grazing_zone(const MeasuredData& d, const Model& m, Prep& pr) {
    const std::size_t n = pr.n;
    std::vector<double> lev;
    for (const auto& im : pr.impacts) lev.push_back(im.level);
    // The lower of the measured flat tops and the model's own bumper: past the latter the model's
    // contact force acts, and a bumper or sensor that is off would fill the residual with it.
    const double model_level = m.measure(m.p.xI);
    const double level = lev.size() >= 3 ? std::min(median(lev), model_level) : model_level;
    const double near = 8.0 * pr.sigma_x + 2e-6;
    for (std::size_t i = 0; i < n; ++i)
        if (d.x[i] >= level - near)
            for (std::size_t j = i >= 10 ? i - 10 : 0; j <= std::min(n - 1, i + 10); ++j) pr.zone[j] = 1;
}

// Turning points where the other forces cannot overcome the dry friction: the cart may stick there for a
// while, and the smoothed velocity cannot tell; those stretches are left out too.
std::vector<char> stick_zone(const MeasuredData& d, const Model& m, const Prep& pr) {
    const std::size_t n = pr.n;
    std::vector<char> stick(n, 0);
    const double Tlim = 3.0 * m.p.T;
    if (m.p.T > 0) {
        for (std::size_t i = 0; i + 1 < n; ++i) {
            if (!(pr.vs[i] * pr.vs[i + 1] <= 0) || !std::isfinite(pr.vs[i])) continue;
            const double x = m.true_x(d.x[i]);
            double F = -spring_magnet(m.p, x).F;
            if (pr.phi_forced) F += unbalance_force(m.p, pr.phi[i], pr.omega[i]);
            else F += m.p.input_gain * pr.u[i];
            if (std::abs(F) < Tlim) {
                const std::size_t a = i >= static_cast<std::size_t>(pr.Hv) ? i - static_cast<std::size_t>(pr.Hv) : 0;
                const std::size_t b = std::min(n - 1, i + static_cast<std::size_t>(pr.Hv) + 1);
                for (std::size_t j = a; j <= b; ++j) stick[j] = 1;
            }
        }
    }
    return stick;
}

// The rows: window centres (every H/4-th sample) whose reach is clear of the zone and of the stick stretches,
// with at most a twentieth of the window's samples slower than `slow`.
void choose_rows(const MeasuredData& d, const std::vector<char>& stick, int H, double slow, Prep& pr) {
    const std::size_t n = pr.n;
    std::vector<std::size_t> cum(n + 1, 0), cum_slow(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        cum[i + 1] = cum[i] + (pr.zone[i] || stick[i] ? 1 : 0);
        cum_slow[i + 1] = cum_slow[i] + (std::abs(pr.vs[i]) < slow ? 1 : 0);
    }
    const std::size_t reach = static_cast<std::size_t>(H + pr.Hv);
    const std::size_t stride = static_cast<std::size_t>(std::max(1, H / 4));
    const std::size_t max_slow = static_cast<std::size_t>(std::max(1, (2 * H + 1) / 20));
    std::size_t tried = 0, in_zone = 0, lingering = 0;
    for (std::size_t i = reach; i + reach < n; i += stride) {
        ++tried;
        const bool clear = cum[i + reach + 1] - cum[i - reach] == 0, moving = cum_slow[i + H + 1] - cum_slow[i - H] <= max_slow;
        in_zone += clear ? 0 : 1;
        lingering += clear && !moving ? 1 : 0;
        if (clear && moving) pr.rows.push_back(i);
    }
    if (pr.rows.size() < 20) {
        // Say which it was: a record that barely moves (at rest, or all noise) is not one full of impacts.
        std::string why;
        if (tried > 0 && lingering * 2 >= tried)
            why = "; in " + std::to_string(lingering) + " of " + std::to_string(tried) +
                  " the speed stays within the noise (the record barely moves: at rest, or noise alone?)";
        else if (tried > 0 && in_zone * 2 >= tried)
            why = "; " + std::to_string(in_zone) + " of " + std::to_string(tried) + " touch an impact, the bumper or a run's start";
        throw DataError(d.source + ": too few free-flight stretches for the residual (" + std::to_string(pr.rows.size()) + " windows" +
                        why + ")");
    }
    pr.j_lo = pr.rows.front() - static_cast<std::size_t>(H);
    pr.j_hi = pr.rows.back() + static_cast<std::size_t>(H) + 1;
}

}  // namespace

Prep prepare(const MeasuredData& d, const Model& m, const FitOptions& o, std::vector<std::string>& notes) {
    Prep pr;
    pr.data = &d;
    pr.n = d.size();
    pr.x_highpass_hz = o.x_highpass_hz;
    const std::size_t n = pr.n;
    if (n < 200) throw DataError(d.source + ": only " + std::to_string(n) + " samples; impactlab fit needs at least 200");
    pr.dt = (d.t.back() - d.t.front()) / static_cast<double>(n - 1);
    check_uniform(d, pr);
    // The sensor noise: the smaller of the two estimates, since signal can only add to either (a noise
    // floor too high would pass a real residual off as noise).
    pr.sigma_x = estimate_noise(d.x);
    pr.x_span = quantile(d.x, 0.995) - quantile(d.x, 0.005);
    {
        // A record that does not move (a sensor read at rest) has nothing to fit, in any units.
        double lo = INFINITY, hi = -INFINITY;
        for (double x : d.x)
            if (std::isfinite(x)) {
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
        if (!(hi - lo > 1e-12 * std::max(std::abs(lo), std::abs(hi))))
            throw DataError(d.source + ": x does not move (every sample reads " + std::to_string(lo) + "): a record at rest has nothing to fit");
    }
    pr.x_typ = std::max({0.5 * pr.x_span, 10.0 * pr.sigma_x, 1e-300});
    pr.phi_forced = d.has_phi();
    pr.unforced = !pr.phi_forced && std::all_of(d.u.begin(), d.u.end(), [](double u) { return u == 0.0; });
    if (pr.phi_forced != (m.forcing == Forcing::Unbalance))
        throw ParamError(pr.phi_forced ? "the data are forced through phi, but the model expects an input u"
                                       : "the data carry an input u, but the model is forced by the unbalance angle phi");
    const double t_char = drives_by_run(d, o, pr);
    // A free run is judged over periods of its own oscillation: one that does not oscillate (a cart coasting
    // along the rail) leaves no window to judge a model on.
    const double duration = d.t.back() - d.t.front();
    if (pr.unforced && !(duration >= 4.0 * pr.period))
        throw DataError(d.source + ": the free run does not oscillate within the record (its strongest period, " + std::to_string(pr.period) +
                        " s from the velocity's spectrum, is more than a quarter of its " + std::to_string(duration) +
                        " s): no window of its own motion to judge a model on");
    int H = o.window > 0 ? static_cast<int>(std::lround(o.window / pr.dt))
                         : static_cast<int>(std::lround(t_char / (12.0 * pr.dt)));
    H = std::clamp(H, 6, 400);
    pr.K = make_kernel(H, pr.dt);
    pr.Hv = std::max(3, H / 2);
    pr.xs = apply_fir(d.x, savgol(pr.Hv, 4, 0, pr.dt));
    pr.vs = apply_fir(d.x, savgol(pr.Hv, 3, 1, pr.dt));
    if (d.v.size() == n) {
        pr.vs = d.v;   // a measured velocity is used as it is (its own noise, no smoothing lag at reversals)
    } else {
        refine_reversals(d, pr);
    }
    typical_sizes(m, pr);
    impact_zone(d, m, H, pr);
    find_stray_impacts(d, m, pr);
    // Rows: window centres whose kernel (and the velocity estimates under it) stay clear of every impact,
    // and that do not linger at v = 0: there the sign of the estimated velocity, and so the dry friction
    // force, is unknown (a cart at rest or creeping).
    const auto cv = savgol(pr.Hv, 3, 1, pr.dt);
    double sv = 0;
    for (double c : cv) sv += c * c;
    // The floor for noise-free data is a rig's 1 um/s, or less in a record whose own speeds are far smaller (a
    // nanometre resonator in metres: every sample was once "at rest", and no row was left).
    const double slow = 3.0 * pr.sigma_x * std::sqrt(sv) + (pr.v_typ > 0 ? std::min(1e-6, 1e-5 * pr.v_typ) : 1e-6);
    if (m.bumper()) grazing_zone(d, m, pr);
    const std::vector<char> stick = stick_zone(d, m, pr);
    choose_rows(d, stick, H, slow, pr);
    if (pr.phi_forced && pr.drive_rms > 0.05)
        notes.push_back("the fitted omega(t) leaves a phase error of " + std::to_string(pr.drive_rms) +
                        " rad RMS: phi is not a smooth rotation");
    return pr;
}

namespace {
// The true positions and speeds of the samples the rows' windows touch, through a curved sensor's inverse
// (an affine map is applied in place, as a scale on the weak form).
void true_states(const Prep& pr, const Model& m, std::vector<double>& xt, std::vector<double>& vt) {
    xt.assign(pr.n, 0.0);
    vt.assign(pr.n, 0.0);
    for (std::size_t j = pr.j_lo; j < pr.j_hi; ++j) {
        xt[j] = m.true_x(pr.data->x[j]);
        vt[j] = pr.vs[j] / m.measure_slope(xt[j]);
    }
}
}  // namespace

void residual(const Prep& pr, const Model& m, Eigen::VectorXd& R, std::vector<double>& pw) {
    const MeasuredData& d = *pr.data;
    const double g = m.sensor_gain(), o = m.sensor_offset(), ig = 1.0 / g;
    pw.resize(pr.n);
    const bool input = !pr.phi_forced;
    // A curved sensor: the weak form's acceleration comes from the true positions, not a scaled reading.
    const bool curved = m.sensor_curved();
    std::vector<double> xt, vt;
    if (curved) true_states(pr, m, xt, vt);
    const std::vector<double>& xa = curved ? xt : d.x;
    const double scale = curved ? 1.0 : ig;
    // The sampled phi'' sums to zero only up to the grid's error, which a record far from its zero (500 units
    // swinging by 3) multiplies into a force: the reading's offset is taken out first, as the integral allows.
    const double xa0 = curved ? 0.0 : o;
    for (std::size_t j = pr.j_lo; j < pr.j_hi; ++j) {
        const double x = curved ? xt[j] : (d.x[j] - o) * ig, v = curved ? vt[j] : pr.vs[j] * ig;
        const ForceTerms f = force_terms(m.p, d.t[j], x, v, pr.phi[j], pr.omega[j], pr.alpha[j]);
        double val = -f.net();
        if (input) val -= m.p.input_gain * pr.u[j];
        pw[j] = val;
    }
    const int H = pr.K.H;
    const std::size_t len = static_cast<std::size_t>(2 * H + 1);
    R.resize(static_cast<Eigen::Index>(pr.rows.size()));
    for (std::size_t r = 0; r < pr.rows.size(); ++r) {
        const std::size_t a = pr.rows[r] - static_cast<std::size_t>(H);
        double acc = 0, frc = 0;
        for (std::size_t k = 0; k < len; ++k) {
            acc += pr.K.w2[k] * (xa[a + k] - xa0);
            frc += pr.K.w[k] * pw[a + k];
        }
        R[static_cast<Eigen::Index>(r)] = m.p.m * acc * scale + frc;
    }
}

int effect_holding(const Model& m, const double* value) {
    for (std::size_t e = 0; e < m.p.effects.size(); ++e) {
        const auto& q = m.p.effects[e].p;
        if (value >= q.data() && value < q.data() + q.size()) return static_cast<int>(e);
    }
    return -1;
}

ResidualCache::ResidualCache(const Prep& pr, const Model& m, const std::vector<Knob>& knobs)
    : pr_(pr), m_(m), knobs_(knobs), owner_(knobs.size(), -1), at_(knobs.size(), 0.0), effect_(m.p.effects.size()) {
    for (std::size_t k = 0; k < knobs.size(); ++k) {
        const int e = effect_holding(m, knobs[k].value);
        if (e >= 0 && m.p.effects[static_cast<std::size_t>(e)].law->kind == EffectKind::Force) owner_[k] = e;
    }
}

void ResidualCache::pointwise(std::size_t j, double effects) {
    const ForceTerms f{resistance_[j], spring_magnet_[j], impact_[j], unbalance_[j], effects};
    double val = -f.net();
    if (!pr_.phi_forced) val -= m_.p.input_gain * pr_.u[j];
    pw_[j] = val;
}

void ResidualCache::eval(Eigen::VectorXd& R) {
    if (!kept_) return full(R);
    // The force effects whose parameters moved since the kept evaluation; a base or sensor knob: all anew.
    moved_.assign(effect_.size(), 0);
    std::size_t n_moved = 0;
    for (std::size_t k = 0; k < knobs_.size(); ++k) {
        if (*knobs_[k].value == at_[k]) continue;
        if (owner_[k] < 0) return full(R);
        char& mv = moved_[static_cast<std::size_t>(owner_[k])];
        if (!mv) ++n_moved;
        mv = 1;
    }
    // One effect moved is a Jacobian's column, which the next evaluation takes back; several are a new point
    // (a trial step), kept with the rig's forces, which did not move.
    const bool keep = n_moved > 1;
    const MeasuredData& d = *pr_.data;
    const Params& p = m_.p;
    for (std::size_t j = pr_.j_lo; j < pr_.j_hi; ++j) {
        double sum = 0.0;   // effects_at's order
        for (std::size_t e = 0; e < effect_.size(); ++e) {
            if (moved_[e]) {
                const EffectInstance& fx = p.effects[e];
                const ForceContext c{d.t[j], x_[j], v_[j], pr_.phi[j], pr_.omega[j], pr_.alpha[j], p.m0e, p.xI};
                const double F = fx.law->force(fx.p.data(), c).F;
                if (keep) effect_[e][j] = F;
                sum += F;
            } else {
                sum += effect_[e][j];
            }
        }
        pointwise(j, sum);
    }
    if (keep)
        for (std::size_t k = 0; k < knobs_.size(); ++k) at_[k] = *knobs_[k].value;
    finish(R);
}

void ResidualCache::full(Eigen::VectorXd& R) {
    const MeasuredData& d = *pr_.data;
    const Model& m = m_;
    const double g = m.sensor_gain(), o = m.sensor_offset(), ig = 1.0 / g;
    const std::size_t n = pr_.n;
    for (auto* v : {&unbalance_, &resistance_, &spring_magnet_, &impact_, &x_, &v_, &pw_}) v->assign(n, 0.0);
    for (auto& v : effect_) v.assign(n, 0.0);
    const bool curved = m.sensor_curved();
    std::vector<double> xt, vt;
    if (curved) true_states(pr_, m, xt, vt);
    Params base = m.p;   // the rig's own terms (force_terms without the effects, which are kept one by one)
    base.effects.clear();
    for (std::size_t j = pr_.j_lo; j < pr_.j_hi; ++j) {
        const double x = curved ? xt[j] : (d.x[j] - o) * ig, v = curved ? vt[j] : pr_.vs[j] * ig;
        const RigForces r = rig_forces(base, d.t[j], x, v, pr_.phi[j], pr_.omega[j], pr_.alpha[j], 0.0, base.compliant());
        const ForceContext c{d.t[j], x, v, pr_.phi[j], pr_.omega[j], pr_.alpha[j], m.p.m0e, m.p.xI};
        double sum = 0.0;
        for (std::size_t e = 0; e < effect_.size(); ++e) sum += effect_[e][j] = m.p.effects[e].law->force(m.p.effects[e].p.data(), c).F;
        unbalance_[j] = r.unbalance;
        resistance_[j] = r.resistance;
        spring_magnet_[j] = r.spring_magnet;
        impact_[j] = r.impact;
        x_[j] = x;
        v_[j] = v;
        pointwise(j, sum);
    }
    const std::vector<double>& xa = curved ? xt : d.x;
    scale_ = curved ? 1.0 : ig;
    const double xa0 = curved ? 0.0 : o;   // as residual(): the offset out before the weak form's phi''
    const int H = pr_.K.H;
    const std::size_t len = static_cast<std::size_t>(2 * H + 1);
    acc_.assign(pr_.rows.size(), 0.0);
    for (std::size_t r = 0; r < pr_.rows.size(); ++r) {
        const std::size_t a = pr_.rows[r] - static_cast<std::size_t>(H);
        double acc = 0;
        for (std::size_t k = 0; k < len; ++k) acc += pr_.K.w2[k] * (xa[a + k] - xa0);
        acc_[r] = acc;
    }
    for (std::size_t k = 0; k < knobs_.size(); ++k) at_[k] = *knobs_[k].value;
    kept_ = true;
    finish(R);
}

void ResidualCache::finish(Eigen::VectorXd& R) const {
    const int H = pr_.K.H;
    const std::size_t len = static_cast<std::size_t>(2 * H + 1);
    R.resize(static_cast<Eigen::Index>(pr_.rows.size()));
    for (std::size_t r = 0; r < pr_.rows.size(); ++r) {
        const std::size_t a = pr_.rows[r] - static_cast<std::size_t>(H);
        double frc = 0;
        for (std::size_t k = 0; k < len; ++k) frc += pr_.K.w[k] * pw_[a + k];
        R[static_cast<Eigen::Index>(r)] = m_.p.m * acc_[r] * scale_ + frc;
    }
}

void effect_column(const Prep& pr, const Model& m, const EffectInstance& e, int k, double h, Eigen::Ref<Eigen::VectorXd> X,
                   std::vector<double>& pw) {
    const MeasuredData& d = *pr.data;
    const double g = m.sensor_gain(), o = m.sensor_offset(), ig = 1.0 / g;
    pw.resize(pr.n);
    auto plus = e.p, minus = e.p;
    plus[static_cast<std::size_t>(k)] += h;
    minus[static_cast<std::size_t>(k)] -= h;
    const bool curved = m.sensor_curved();
    std::vector<double> xt, vt;
    if (curved) true_states(pr, m, xt, vt);
    for (std::size_t j = pr.j_lo; j < pr.j_hi; ++j) {
        const double x = curved ? xt[j] : (d.x[j] - o) * ig, v = curved ? vt[j] : pr.vs[j] * ig;
        const ForceContext c{d.t[j], x, v, pr.phi[j], pr.omega[j], pr.alpha[j], m.p.m0e, m.p.xI};
        pw[j] = (e.law->force(plus.data(), c).F - e.law->force(minus.data(), c).F) / (2 * h);
    }
    const int H = pr.K.H;
    const std::size_t len = static_cast<std::size_t>(2 * H + 1);
    for (std::size_t r = 0; r < pr.rows.size(); ++r) {
        const std::size_t a = pr.rows[r] - static_cast<std::size_t>(H);
        double s = 0;
        for (std::size_t q = 0; q < len; ++q) s += pr.K.w[q] * pw[a + q];
        X[static_cast<Eigen::Index>(r)] = s;
    }
}

}  // namespace impactlab::identify::detail
