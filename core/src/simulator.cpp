#include "impactlab/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "impactlab/forces.hpp"
#include "impactlab/rig.hpp"

namespace impactlab {

namespace {
const char* regime_words(Regime r) {
    return r == Regime::Free ? "free flight" : r == Regime::Sticking ? "sticking at the bumper" : "permanent contact";
}
}  // namespace

const char* regime_name(Regime r) {
    switch (r) {
        case Regime::Free: return "I";
        case Regime::Sticking: return "II";
        case Regime::Contact: return "III";
    }
    return "?";
}

namespace {

constexpr double kRestartStep = 1e-4;   // [s] first step after a discontinuity; the controller grows it
// h * (largest rate) below which the explicit method is stable (Dormand-Prince's region reaches -3.3 on
// the real axis); kept below that bound so that a step never hovers at the edge of stability.
constexpr double kExplicitStabilityLimit = 2.0;

// Eq. (1) as a first-order system y = (x, v) for the stepper, in free flight or against a compliant bumper.
struct RigSystem {
    const Params& p;
    const Drive& d;
    bool compliant;

    Vec2 rhs(double t, const Vec2& y) const { return rig_rhs(p, d, t, y, compliant); }

    // Largest rate of the linearised system [1/s]: friction (and contact damping), contact stiffness.
    double stiffness(const Vec2& y) const {
        double damp = resistance(p, y[1]).dF, spring = std::abs(spring_magnet(p, y[0]).dF);
        if (compliant && y[0] > p.xI) {
            const ContactForce c = p.impact->contact(p.ip.data(), y[0] - p.xI, y[1]);
            damp += c.dF_dhdot;
            spring += c.dF_dh;
        }
        return damp / p.m + std::sqrt(spring / p.m);
    }

    void jacobian(double t, const Vec2& y, Mat2& J, Vec2& dfdt) const {
        rig_jacobian(p, d, t, y, compliant, ContactSlope::Secant, J, &dfdt);
    }
};

// Illinois (modified regula falsi) on g over [a, b] with g(a) <= 0 < g(b) or the reverse.
template <class G>
double find_root(G&& g, double a, double b, double ga, double gb) {
    for (int it = 0; it < 100 && b - a > 1e-15 * std::max(1.0, std::abs(b)); ++it) {
        const double c = (ga == gb) ? 0.5 * (a + b) : b - gb * (b - a) / (gb - ga);
        const double m = std::clamp(c, a, b);
        const double gm = g(m);
        if (gm == 0.0) return m;
        if ((gm > 0) == (gb > 0)) {
            b = m;
            gb = gm;
            ga *= 0.5;
        } else {
            a = m;
            ga = gm;
            gb *= 0.5;
        }
    }
    return b;   // the side past the crossing
}

// Where an explicit step that reverses v across the friction's smoothing band in more than this many eps
// is cut: 0.9 of the way to the zero of v on its dense output, so that the next step starts at a tenth of
// |v0| and the approach to the kink narrows geometrically, a few steps a reversal.
constexpr double kReversalSpan = 4.0;
double reversal_cut(const Params& p, const DenseStep& step, double t0, double v0) {
    const double v1 = step.y1[1];
    if (p.T == 0.0 || v0 == 0.0 || (v0 < 0) == (v1 < 0) || std::abs(v1 - v0) <= kReversalSpan * p.eps) return t0;
    const double t_zero = find_root([&](double t) { return step.at(t)[1]; }, t0, step.t0 + step.h, v0, v1);
    return t0 + 0.9 * (t_zero - t0);
}

}  // namespace

// The cart at rest on the bumper: every force of Eq. (1) but the contact's (no resistance at v = 0).
double normal_force(const Params& p, const Drive& d, double t) { return rig_forces(p, d, t, p.xI, 0.0, false).net(); }

double bumper_elastic_energy(const Params& p, double x) {
    if (!p.compliant() || x <= p.xI) return 0.0;
    const double n1 = p.ip[2];
    return p.ip[0] * std::pow(x - p.xI, n1 + 1.0) / (n1 + 1.0);
}

double mechanical_energy(const Params& p, double x, double v) {
    return 0.5 * p.m * v * v + spring_magnet_potential(p, x) + bumper_elastic_energy(p, x);
}

double bumper_force(const Params& p, const Drive& d, const State& s) {
    if (!p.has_bumper()) return 0.0;
    if (p.compliant()) return p.impact->contact(p.ip.data(), s.x - p.xI, s.v).F;
    if (s.regime == Regime::Contact) return std::max(0.0, normal_force(p, d, s.t));
    if (s.regime == Regime::Sticking) {
        const double T = p.impact->duration(p.ip.data(), s.v_impact);
        return T > 0 ? p.m * (std::abs(s.v_impact) + std::abs(s.v_release)) / T : 0.0;
    }
    return 0.0;
}

ForceTerms force_terms(const Params& p, double t, double x, double v, double phi, double omega, double alpha) {
    const RigForces r = rig_forces(p, t, x, v, phi, omega, alpha, 0.0, p.compliant());
    return {r.resistance, r.spring_magnet, r.impact, r.unbalance, r.effects};
}

void Simulator::make_consistent(const Params& p, const Drive& d, State& s) {
    if (!p.has_bumper()) {
        s.regime = Regime::Free;
    } else if (p.rigid()) {
        if (s.regime != Regime::Free || s.x > p.xI || (s.x == p.xI && s.v >= 0)) {
            // On (or beyond) the bumper: held there, pressed or not.
            if (s.regime != Regime::Sticking) s.regime = normal_force(p, d, s.t) > 0 ? Regime::Contact : Regime::Free;
            s.x = p.xI;
            s.v = 0.0;
        }
    } else {
        s.regime = Regime::Free;
    }
    s.side = 0;
    s.h = 0;
    sync_sections(d, s);
}

void Simulator::move_bumper(Params& p, const Drive& d, State& s, double xI) {
    const bool held = s.regime != Regime::Free;
    // A compliant bumper the cart already presses h deep carries it along at that depth: moving it by
    // nothing (the GUI resends its slider's value) or away must not pull the cart out of contact.
    const double h_old = p.has_bumper() && !p.rigid() ? std::max(s.x - p.xI, 0.0) : 0.0;
    const double x_max = xI + h_old;
    p.xI = xI;
    if (s.regime == Regime::Sticking) s.regime = Regime::Free;
    if (held || s.x > x_max) {
        s.x = std::min(s.x, x_max);
        s.v = 0.0;
    }
    make_consistent(p, d, s);
}

void Simulator::set_section_phase(double phi0) {
    if (!(phi0 >= 0.0 && phi0 <= kTwoPi)) {
        std::ostringstream msg;
        msg << "section phase phi0 = " << phi0 << " rad is outside [0, 2 pi]";
        throw std::invalid_argument(msg.str());
    }
    phi0_ = phi0;
    psi_ = phi0 > 0.0 ? kTwoPi - phi0 : 0.0;
}

double Simulator::next_section_time(const Drive& d, const State& s) const {
    // As step() sees it: a section at or before now (the revolution's, ahead of its end) is passed over.
    double t = d.time_of_phase(section_phi(s.next_section));
    if (t <= s.t) t = d.time_of_phase(section_phi(s.next_section + 1));
    return t;
}

void Simulator::sync_sections(const Drive& d, State& s) {
    // The next section is in the first revolution ending (phi = 2 pi n) strictly after now.
    const double periods = d.phi(s.t) / kTwoPi;
    s.next_section = static_cast<std::int64_t>(std::floor(periods + 1e-9)) + 1;
}

bool Simulator::step(const Params& p, const Drive& d, State& s, double t_limit, Observer* obs) {
    // Parameters or drive may have changed since the last call: the FSAL value is only trusted inside one
    // advance(), where both are fixed.
    if (!in_advance_) fsal_valid_ = false;
    if (!(s.t < t_limit)) return false;
    const double t_sec = d.time_of_phase(section_phi(s.next_section));
    // A section at this very instant was already taken, the drive was swapped, or (phi0 > 0) the section
    // of the revolution now running lies behind.
    if (t_sec <= s.t) {
        ++s.next_section;
        return true;
    }
    double t_stop = std::min(t_limit, d.next_knot(s.t));
    const bool at_section = t_sec <= t_stop;
    if (at_section) t_stop = t_sec;

    if (s.regime == Regime::Free) {
        free_step(p, d, s, t_stop, obs);
        if (s.steps + s.rejected - s.steps_mark >= kStallWindow) check_step_budget(s);
    } else {
        hold_step(p, d, s, t_stop, obs);
    }
    if (at_section && s.t == t_stop) {
        const bool held = s.regime != Regime::Free;
        if (obs) obs->on_section({s.next_section, s.t, held ? p.xI : s.x, held ? 0.0 : s.v, s.regime});
        ++s.next_section;
    }
    return true;
}

void Simulator::check_step_budget(State& s) const {
    const std::uint64_t done = s.steps + s.rejected;
    const double advanced = s.t - s.t_mark;
    // A state moved back in time (a reset) or a fresh mark only restarts the count.
    if (advanced >= 0 && s.steps_mark != 0 &&
        advanced * tol_.max_step_rate < static_cast<double>(done - s.steps_mark)) {
        std::ostringstream msg;
        msg << "simulation stalled in regime " << regime_name(s.regime) << " (" << regime_words(s.regime)
            << ") at t = " << s.t << " s, x = " << s.x << " m, v = " << s.v << " m/s: " << (done - s.steps_mark)
            << " steps advanced only " << advanced << " s (step size " << s.h
            << " s); the equations are too stiff or discontinuous there: look at m, eps, the impact law and "
               "the effects' sizes";
        throw SimulationStalled(msg.str());
    }
    s.t_mark = s.t;
    s.steps_mark = done;
}

void Simulator::advance(const Params& p, const Drive& d, State& s, double t_end, Observer* obs) {
    fsal_valid_ = false;
    in_advance_ = true;
    const auto wall_start = std::chrono::steady_clock::now();
    std::uint32_t pieces = 0;
    try {
        while (s.t < t_end) {
            if (!step(p, d, s, t_end, obs)) break;
            if (obs && obs->stop()) break;
            // The clock every 64 pieces: a stiff contact's pieces can each cost milliseconds on a busy machine,
            // and the budget must hold within a fraction of itself (a clock read costs tens of ns).
            if (tol_.max_wall_s > 0 && (++pieces & 0x3Fu) == 0) {
                const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
                if (wall > tol_.max_wall_s) {
                    std::ostringstream msg;
                    msg << "simulation ran past its wall-clock budget of " << tol_.max_wall_s << " s in regime "
                        << regime_name(s.regime) << " (" << regime_words(s.regime) << ") at t = " << s.t
                        << " s of " << t_end << " s (step size " << s.h << " s, " << s.steps << " steps)";
                    throw SimulationStalled(msg.str());
                }
            }
        }
    } catch (...) {
        in_advance_ = false;
        throw;
    }
    in_advance_ = false;
}

namespace {
// Rigid bumper: an impact at s.t, restitution and dwell from the law at the arrival speed. A dwell holds
// the mass at the bumper (sticking until s.t_release); without one it leaves at once: the speed returned,
// for release().
inline std::optional<double> rigid_impact(const Params& p, State& s, Observer* obs) {
    const double v_minus = std::max(s.v, 0.0);
    const double kappa = p.impact->restitution(p.ip.data(), v_minus);
    const double t_imp = p.impact->duration(p.ip.data(), v_minus);
    const double v_plus = -kappa * v_minus;
    ++s.impacts;
    s.x = p.xI;
    if (obs) obs->on_impact({s.t, v_minus, v_plus, t_imp});
    if (t_imp > 0) {
        s.regime = Regime::Sticking;
        s.t_release = s.t + t_imp;
        s.v_release = v_plus;
        s.v_impact = v_minus;
        s.v = 0.0;
        if (obs) obs->on_regime(s.t, Regime::Free, Regime::Sticking);
        return std::nullopt;
    }
    return v_plus;
}
}  // namespace

bool Simulator::free_step(const Params& p, const Drive& d, State& s, double t_stop,
                          Observer* obs) {
    const RigSystem sys{p, d, p.compliant()};
    const Vec2 y0(s.x, s.v);
    const double t0 = s.t;
    double h = std::min(s.h > 0 ? s.h : kRestartStep, tol_.h_max);
    bool truncated = false;
    // Land exactly on t_stop; avoid leaving a sliver behind it.
    if (t0 + 1.05 * h >= t_stop) {
        h = t_stop - t0;
        truncated = true;
    }
    // Stiffness switching: Dormand-Prince where h * rate stays inside its stability region, RODAS4 where
    // the friction (|v| within a few eps of 0: sticking, creeping) or a compliant contact is stiff.
    const double rate = sys.stiffness(y0);
    // The smallest step that still moves t (at t ~ 4e4 s one ulp is 7e-12 s): below it a step is forced.
    const double h_min = std::max(tol_.h_min, 16.0 * std::numeric_limits<double>::epsilon() * std::abs(t0));
    h = std::max(h, std::min(h_min, t_stop - t0));
    double err = 0;
    bool explicit_step = false;
    for (;;) {
        explicit_step = h * rate < kExplicitStabilityLimit;
        if (explicit_step) {
            if (!(fsal_valid_ && fsal_t_ == t0 && fsal_y_ == y0)) fsal_f_ = sys.rhs(t0, y0);
            work_.take_explicit(sys, t0, y0, h, fsal_f_);
        } else {
            work_.take(sys, t0, y0, h);
        }
        err = work_.error_norm(tol_);
        if (err <= 1.0 && explicit_step && h > h_min) {
            // A dry-friction reversal inside an explicit step: the friction flips from -T to +T within
            // ~eps/|a| (1 us), a kink the stages can straddle unseen while the error estimate passes (A1H
            // at 13.645 rad/s: one such step put 2e-6 m/s into v at rtol 1e-10). The step is cut short
            // of the zero until it crosses the band in a few eps, where the error control sees the kink.
            const double t_cut = reversal_cut(p, work_, t0, y0[1]);
            if (t_cut > t0) {
                ++s.rejected;
                h = std::max(t_cut - t0, h_min);
                truncated = false;
                continue;
            }
        }
        if (err <= 1.0 || h <= h_min) break;
        ++s.rejected;
        h = std::isfinite(err) ? next_step_size(h, err, false, explicit_step ? 5 : 4) : 0.25 * h;
        h = std::max(h, h_min);
        truncated = false;
    }
    ++s.steps;
    double h_next = next_step_size(h, err, true, explicit_step ? 5 : 4);
    if (explicit_step) {
        fsal_valid_ = true;
        fsal_t_ = t0 + h;
        fsal_y_ = work_.y1;
        fsal_f_ = work_.f1;
    }

    // Events on the accepted step: the bumper plane x = xI, sampled on the dense output.
    const double xI = p.xI;
    if (s.side == 0 && !p.rigid()) s.side = s.x > xI ? 1 : -1;
    const bool inside_before = p.rigid() ? false : s.side > 0;
    auto crossed = [&](double t) {
        const bool inside = work_.at(t)[0] - xI > 0;
        return inside != inside_before;
    };
    constexpr int kSamples = 4;
    double ta = t0, tb = t0;
    bool event = false;
    for (int k = 1; k <= kSamples && p.has_bumper(); ++k) {   // without a bumper: no event
        tb = (k == kSamples) ? t0 + h : t0 + h * k / kSamples;
        if (crossed(tb)) {
            event = true;
            break;
        }
        ta = tb;
    }
    if (!event) {
        s.t = truncated ? t_stop : t0 + h;
        if (truncated) fsal_t_ = t_stop;
        s.x = work_.y1[0];
        s.v = work_.y1[1];
        s.h = truncated ? std::max(h_next, s.h) : h_next;
        if (obs) obs->on_piece({t0, s.t, Regime::Free, &work_, 0.0});
        return truncated;
    }

    // Bracket the first crossing; a step that starts on the bumper plane (just released) needs a point
    // clear of it, found by halving towards the start.
    auto g = [&](double t) { return (work_.at(t)[0] - xI) * (inside_before ? -1.0 : 1.0); };
    if (ta == t0 && g(t0) >= 0) {
        double tm = tb;
        for (int j = 0; j < 60 && g(tm) >= 0; ++j) tm = t0 + 0.5 * (tm - t0);
        if (g(tm) < 0) ta = tm;
    }
    double t_ev = (g(ta) < 0) ? find_root(g, ta, tb, g(ta), g(tb)) : ta;
    // Hit the event with a real step (not the interpolant). A rigid bumper needs x = xI to the last digit:
    // Newton on the step length. For a compliant bumper the crossing is only a restart point at the
    // kink of h^n1, so the interpolated time is enough.
    for (int it = 0; it < (p.rigid() ? 4 : 1); ++it) {
        const double h_ev = std::max(t_ev - t0, h_min);
        if (explicit_step) retry_.take_explicit(sys, t0, y0, h_ev, sys.rhs(t0, y0));
        else retry_.take(sys, t0, y0, h_ev);
        const double miss = retry_.y1[0] - xI;
        if (!p.rigid() || std::abs(miss) <= 1e-14 || retry_.y1[1] <= 0.0) break;
        const double t_new = std::clamp(t_ev - miss / retry_.y1[1], t0 + h_min, t0 + h);
        if (std::abs(t_new - t_ev) <= 1e-15 * std::max(1.0, std::abs(t_ev))) break;
        t_ev = t_new;
    }
    s.t = retry_.t0 + retry_.h;
    s.x = retry_.y1[0];
    s.v = retry_.y1[1];
    s.h = std::min(h_next, kRestartStep);
    if (obs) obs->on_piece({t0, s.t, Regime::Free, &retry_, 0.0});

    if (!p.rigid()) {
        s.side = inside_before ? -1 : 1;   // now on the other side of the plane
        return false;
    }
    if (const std::optional<double> v_plus = rigid_impact(p, s, obs)) release(p, d, s, *v_plus, obs);
    return false;
}

void Simulator::release(const Params& p, const Drive& d, State& s, double v_plus, Observer* obs) {
    const Regime before = s.regime;
    s.x = p.xI;
    if (std::abs(v_plus) < p.impact->eps_v && normal_force(p, d, s.t) > 0) {
        s.regime = Regime::Contact;
        s.v = 0.0;
    } else {
        s.regime = Regime::Free;
        s.v = v_plus;
    }
    s.h = kRestartStep;
    if (obs && before != s.regime) obs->on_regime(s.t, before, s.regime);
}

void Simulator::hold_step(const Params& p, const Drive& d, State& s, double t_stop, Observer* obs) {
    const double t0 = s.t;
    if (s.regime == Regime::Sticking) {
        const double t1 = std::min(t_stop, s.t_release);
        s.t = t1;
        if (obs) obs->on_piece({t0, t1, Regime::Sticking, nullptr, p.xI});
        if (t1 == s.t_release) release(p, d, s, s.v_release, obs);
        return;
    }
    // Regime III: held until the normal force N(t) (known in closed form) falls to zero.
    const double w = std::max(d.omega(t0), 1e-3);
    const double scan = std::min(kTwoPi / w / 64.0, 0.05);
    double ta = t0, na = normal_force(p, d, t0);
    while (ta < t_stop) {
        const double tb = std::min(ta + scan, t_stop);
        const double nb = normal_force(p, d, tb);
        if (nb <= 0.0) {
            auto N = [&](double t) { return normal_force(p, d, t); };
            const double t_lift = na > 0 ? find_root(N, ta, tb, na, nb) : ta;
            s.t = t_lift;
            if (obs) obs->on_piece({t0, t_lift, Regime::Contact, nullptr, p.xI});
            s.regime = Regime::Free;
            s.x = p.xI;
            s.v = 0.0;
            s.h = kRestartStep;
            if (obs) obs->on_regime(t_lift, Regime::Contact, Regime::Free);
            return;
        }
        ta = tb;
        na = nb;
    }
    s.t = t_stop;
    if (obs) obs->on_piece({t0, t_stop, Regime::Contact, nullptr, p.xI});
}

void UniformSampler::on_piece(const Piece& piece) {
    while (next_ <= piece.t1) {
        if (next_ >= piece.t0) {
            const Vec2 y = piece.at(next_);
            sink_({next_, y[0], y[1], drive_.phi(next_), drive_.omega(next_), piece.regime});
        }
        ++k_;
        next_ = t_first_ + dt_ * static_cast<double>(k_);
    }
}

}  // namespace impactlab
