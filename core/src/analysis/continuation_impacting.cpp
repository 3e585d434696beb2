// The continuation near a rigid grazing: an orbit written from impact to impact (the impact phase and the
// impact speed as unknowns, smooth through v- = 0), the hand-over to and from the stroboscopic map, and
// what a grazing crossed is reported with (its scenario, the measured scaling of the impacting orbit).
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>


#include "analysis/continuer.hpp"
#include "impactlab/analysis.hpp"

namespace impactlab::analysis::detail {

bool Continuer::shot(const Vec3& z, int k, Vec2& G, Eigen::Matrix<double, 2, 3>& J, Vec2& section) {
    const double q = q_of(z);
    if (spec_.param == ContParam::Omega && !(q > 0)) return false;
    try {
        const double omega = apply(q);
        ++evaluations_;
        const ImpactShot a = impact_shot(work_, omega, z[0], z[1] * kVScale, k, true, spec_.sim);
        const double dq = 1e-6;
        const double omega_q = apply(q + dq * q_scale_);
        ++evaluations_;
        const ImpactShot b = impact_shot(work_, omega_q, z[0], z[1] * kVScale, k, false, spec_.sim);
        apply(q);
        G = a.residual;
        J.leftCols<2>() = a.J;
        J.col(2) = (b.residual - a.residual) / dq;
        section = a.section;
        return G.allFinite() && J.allFinite();
    } catch (const std::exception&) {
        apply(q);
        return false;
    }
}

bool Continuer::correct_impacting(const Vec3& z_pred, const Vec3& n, int k, Vec3& z, Eigen::Matrix<double, 2, 3>& J,
                                  Vec2& section) {
    z = z_pred;
    for (int it = 0; it <= kMaxCorrector; ++it) {
        Vec2 G;
        if (!shot(z, k, G, J, section)) return false;
        const double h = n.dot(z - z_pred);
        if (G.cwiseAbs().maxCoeff() < res_tol_ && std::abs(h) < 1e-9) return true;
        if (it == kMaxCorrector) break;
        Mat3 A;
        A.topRows<2>() = J;
        A.row(2) = n.transpose();
        const Vec3 dz = A.fullPivLu().solve(-Vec3(G[0], G[1], h));
        if (!dz.allFinite() || dz.norm() > 1.0) return false;
        z += dz;
    }
    return false;
}

bool Continuer::slow_impacts_start(const Job& job, Vec3& z, Vec3& t, Vec2& section, std::string& failure) {
    const int k = job.period;
    Eigen::Matrix<double, 2, 3> J;
    double theta = 0, vm = 0;
    if (!first_impact(work_, apply(q_of(job.u)), y_of(job.u), k, spec_.sim, theta, vm) ||
        !correct_impacting(Vec3(theta, vm / kVScale, job.u[2]), Vec3(0, 0, 1), k, z, J, section)) {
        failure = "the impacting orbit did not converge from impact to impact";
        return false;
    }
    t = Vec3(J.row(0).transpose()).cross(Vec3(J.row(1).transpose()));
    if (!(t.norm() > 0) || !t.allFinite()) {
        failure = "singular impact-to-impact equations";
        return false;
    }
    t.normalize();
    if (t[2] * job.t[2] < 0) t = -t;   // the way the stroboscopic branch was going in the parameter
    return true;
}

std::string Continuer::impacting_limit(const Vec3& z, const Vec3& t, double ds, int k) {
    Vec2 Gl;
    Eigen::Matrix<double, 2, 3> Jl;
    Vec2 sl;
    const double rl = shot(z + 2 * ds * t, k, Gl, Jl, sl) ? Gl.cwiseAbs().maxCoeff() : NAN;
    char buf[160];
    std::snprintf(buf, sizeof buf, ": the corrector fails at steps down to %.1g (residual %.2g there)", spec_.ds_min, rl);
    return "numerical limit (impact to impact) near " + std::string(sweep_param_name(spec_.param)) + " = " +
           std::to_string(q_of(z)) + buf;
}

std::string Continuer::impacts_end(const Vec3& z, const Vec3& t, double ds, const Vec3& zn, const Vec2& sec, int k,
                                   int branch) {
    // v- passes zero between z and zn: a grazing, located by a secant on v- along the step (the equations
    // are smooth there).
    double sa = 0, sb = ds, va = z[1], vb = zn[1];
    Vec3 zm = zn;
    Vec2 secm = sec;
    for (int it = 0; it < 60 && std::abs(vb - va) > 0; ++it) {
        double sm = sb - vb * (sb - sa) / (vb - va);
        Eigen::Matrix<double, 2, 3> Jm;
        // Where the secant's point does not converge (its prediction off the branch), the midpoint once.
        if (!correct_impacting(z + sm * t, t, k, zm, Jm, secm)) {
            sm = 0.5 * (sa + sb);
            if (!correct_impacting(z + sm * t, t, k, zm, Jm, secm)) break;
        }
        sa = sb; va = vb; sb = sm; vb = zm[1];
        if (std::abs(vb) * kVScale < 1e-12) break;
    }
    BifPoint bp{BifKind::Grazing, q_of(zm), secm, k, branch, std::abs(sb - sa) * q_scale_, {}, NAN, NAN};
    bp.precision = std::max(bp.precision, 1e-9 * q_scale_);
    bool known = false;
    for (const BifPoint& q : result_.points)
        if (q.kind == BifKind::Grazing && std::abs(q.param - bp.param) < 1e-5 * q_scale_) known = true;
    // Where the corrector gave out before v- reached zero (the equations turn singular there) the grazing is
    // only bracketed: named at the branch's end, not marked as a located point.
    const bool located = bp.precision <= 1e-6 * q_scale_;
    // (With a dwell at rest the orbit arriving at rest grazes nothing: its end is named, not marked.)
    if (!known && located && dwell_at_rest() == 0) result_.points.push_back(bp);
    reached_.push_back(bp.param);
    const std::string at = std::string(sweep_param_name(spec_.param)) + " = " + std::to_string(bp.param);
    if (dwell_at_rest() > 0)
        return "at rest at " + at +
               " (the impacts end arriving at rest, where T_imp(0) > 0 still holds the cart: no free orbit joins there)";
    if (!located) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.2g", bp.precision);
        return "grazing near " + at + " (+- " + buf + "; the impacts end, v- not followed to zero)";
    }
    return "grazing at " + at + " (the impacts end)";
}

Followed Continuer::follow_impacting(const Job& job, Branch& br) {
    const int k = job.period;
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    Vec3 z, t;
    Vec2 section;
    if (job.mode == JobMode::Grazing && dwell_at_rest() > 0) {
        if (!grazing_start(q_of(job.u), y_of(job.u), k, z, t, section, true)) {
            br.end = "the impacting orbit that arrives at rest did not converge from impact to impact";
            return Followed::Branch;
        }
        for (BifPoint& b : result_.points)
            if (b.kind == BifKind::Grazing && b.param == q_of(job.u) && b.scenario.empty()) describe_dwell(b, z, section, k);
        for (double qr : reached_)
            if (std::abs(qr - q_of(z)) < 1e-5 * q_scale_) return Followed::AlreadyReached;
    } else if (job.mode == JobMode::Grazing) {
        if (!grazing_start(q_of(job.u), y_of(job.u), k, z, t, section)) {
            br.end = "the grazing orbit did not converge from impact to impact";
            return Followed::Branch;
        }
        for (BifPoint& b : result_.points)
            if (b.kind == BifKind::Grazing && b.param == q_of(job.u) && b.scenario.empty()) describe_grazing(b, job.t[2], z, t, k);
        // Its impacting branch already followed to here from another grazing: not again.
        for (double qr : reached_)
            if (std::abs(qr - q_of(job.u)) < 1e-5 * q_scale_) return Followed::AlreadyReached;
    } else if (!slow_impacts_start(job, z, t, section, br.end)) {
        return Followed::Branch;
    }
    double ds = 0.01;
    std::string end;
    bool handed = false, have_prev = false;
    Sol prev;
    while (true) {
        if (cancelled()) { end = "cancelled"; break; }
        if (static_cast<int>(br.points.size()) >= spec_.max_points) { end = "point limit"; break; }
        Vec3 zn;
        Vec2 sec;
        Eigen::Matrix<double, 2, 3> Jn;
        if (!correct_impacting(z + ds * t, t, k, zn, Jn, sec)) {
            ds *= 0.5;
            if (ds < spec_.ds_min) {
                end = impacting_limit(z, t, ds, k);
                break;
            }
            continue;
        }
        if (zn[1] <= 0 && z[1] > 0) {
            end = impacts_end(z, t, ds, zn, sec, k, br.id);
            break;
        }
        const double q = q_of(zn);
        if (q < lo || q > hi) { end = std::string(sweep_param_name(spec_.param)) + " range"; break; }
        // The same orbit on the real map: one impact per k periods and a fixed point of P^k. Otherwise the
        // flight crosses xI in between (a second impact) and the orbit is not the rig's.
        Sol sp;
        sp.u = u_of(sec, q);
        sp.r = map(sp.u, k, true);
        // One impact, yet the rig's map does not quite return the section point (a section phase at the
        // release, or the shot's residual amplified by the orbit's instability): the orbit polished by Newton
        // on the rig's map, if it is there. Unpolished, a point must return within 1e-5: a bound scaled by
        // |mu| admitted anything where |mu| ~ 1e6 (A1G's period 8 at 16.7984 came back 6e-4 away, and Newton
        // on the rig's map found the impact-free orbit 2e-5 off instead).
        // Newton's own noise there may stall it at rtol: then again at rtol / 100.
        bool polished = false;
        for (double sharper : {1.0, 0.01}) {
            if (polished || sp.r.impacts != 1 || scaled_norm(sp.r.y - sec) <= 1e-5) break;
            OrbitOptions oo;
            oo.period = k;
            oo.sim = spec_.sim;
            oo.sim.rtol = std::max(oo.sim.rtol * sharper, 1e-13);
            oo.max_iterations = 8;
            ++evaluations_;
            const Orbit o = find_orbit(work_, apply(q), sec, oo);
            if (o.converged && o.impacts == 1 && scaled_norm(o.y - sec) < 1e-3) {
                sp.u = u_of(o.y, q);
                sp.r = map(sp.u, k, true);
                polished = true;
            }
        }
        // (A polished orbit's residual comes back amplified by its instability.)
        const double returns_within = polished ? std::max(1e-5, 10 * res_tol_ * std::abs(floquet(sp.r.M).mu[0])) : 1e-5;
        if (sp.r.impacts != 1 || scaled_norm(sp.r.y - y_of(sp.u)) > returns_within) {
            char why[160];
            if (sp.r.impacts != 1)
                std::snprintf(why, sizeof why, "%d impacts on the rig's map: %s", sp.r.impacts,
                              sp.r.impacts > 1 ? "its flight crosses xI" : "its impact is lost");
            else
                std::snprintf(why, sizeof why, "the rig's map does not return it: %.2g (scaled) away",
                              scaled_norm(sp.r.y - y_of(sp.u)));
            end = "the impacting orbit is no longer admissible near " + std::string(sweep_param_name(spec_.param)) +
                  " = " + std::to_string(q) + " (" + why + ")";
            break;
        }
        Vec3 tn = Vec3(Jn.row(0).transpose()).cross(Vec3(Jn.row(1).transpose()));
        if (tn.norm() > 0 && tn.allFinite()) {
            tn.normalize();
            if (tn.dot(t) < 0) tn = -tn;
        } else {
            tn = t;
        }
        if (have_prev)
            for (BifKind kind : {BifKind::Fold, BifKind::PeriodDoubling, BifKind::NeimarkSacker}) {
                const double fa = test(kind, prev), fb = test(kind, sp);
                if (!std::isfinite(fa) || !std::isfinite(fb) || (fa > 0) == (fb > 0)) continue;
                if (kind == BifKind::NeimarkSacker && !(complex_pair(prev.r.M) && complex_pair(sp.r.M))) continue;
                locate_impacting(kind, z, t, ds, prev, sp, k, br.id);
            }
        prev = sp;
        have_prev = true;
        z = zn;
        t = tn;
        section = sec;
        br.points.push_back(point_of(sp, k));
        ds = std::min(ds * 1.5, 0.1);
        // Fast enough for the stroboscopic map (and growing): on with it.
        if (zn[1] * kVScale > kHandover && t[1] > 0) {
            handed = true;
            break;
        }
    }
    if (!handed) {
        br.end = std::string(job_mode_name(job.mode)) + " / " + end;
        return Followed::Branch;
    }
    Branch onward;
    onward.id = br.id;
    follow({k, job.parent, u_of(section, q_of(z)), Vec3(0, 0, t[2] >= 0 ? 1.0 : -1.0), false, JobMode::Onward}, onward);
    br.points.insert(br.points.end(), onward.points.begin(), onward.points.end());
    br.end = std::string(job_mode_name(job.mode)) + " / " + onward.end;
    return Followed::Branch;
}

void Continuer::locate_impacting(BifKind kind, const Vec3& z, const Vec3& t, double ds, const Sol& a, const Sol& b,
                                 int k, int branch) {
    double s_lo = 0, s_hi = ds, f_lo = test(kind, a), f_hi = test(kind, b);
    Sol lo = a, hi = b;
    for (int it = 0; it < 80 && std::abs(q_of(hi.u) - q_of(lo.u)) > spec_.locate_tol; ++it) {
        // The midpoint, or failing that a quarter from either end: a corrector that fails once in a wide
        // bracket (A1H's fold at 19.1877, 4.6e-3 wide, on one processor path) must not leave it unnarrowed.
        double sm = 0.5 * (s_lo + s_hi);
        Vec3 zm;
        Eigen::Matrix<double, 2, 3> Jm;
        Vec2 sec;
        bool ok = correct_impacting(z + sm * t, t, k, zm, Jm, sec);
        for (double f : {0.25, 0.75}) {
            if (ok) break;
            sm = s_lo + f * (s_hi - s_lo);
            ok = correct_impacting(z + sm * t, t, k, zm, Jm, sec);
        }
        if (!ok) break;
        Sol m;
        m.u = u_of(sec, q_of(zm));
        m.r = map(m.u, k, true);
        const double fm = test(kind, m);
        if ((fm > 0) == (f_hi > 0)) { s_hi = sm; hi = m; f_hi = fm; }
        else { s_lo = sm; lo = m; f_lo = fm; }
    }
    // A crossing of the multiplier it names, near +1, -1 or the unit circle on both sides (see locate()).
    const double target = 1.0 * (kind == BifKind::PeriodDoubling ? -1.0 : 1.0);
    const double m_lo = crossing_multiplier(kind, lo.r.M), m_hi = crossing_multiplier(kind, hi.r.M);
    if (!std::isfinite(m_lo) || !std::isfinite(m_hi)) return;
    if (std::abs(m_lo - target) > kNearCrossing || std::abs(m_hi - target) > kNearCrossing) return;
    const Sol& best = std::abs(f_lo) < std::abs(f_hi) ? lo : hi;
    // Moved as on the stroboscopic map: at rtol 1e-10 an impacting orbit's multiplier jitters by 3e-3 (A1G's
    // period-2 doubling sat 5.7e-6 rad/s off, within a bracket of 9e-8). No steepness test here: from impact
    // to impact the map is smooth, and a crossing near a slow impact is steep yet true.
    double precision = std::abs(q_of(hi.u) - q_of(lo.u)), shift = 0;
    refine_crossing(kind, lo, hi, best, k, precision, shift);
    BifPoint bp{kind, q_of(best.u) + shift, y_of(best.u), k, branch, precision, {}, NAN, NAN};
    for (const BifPoint& q : result_.points)
        if (q.kind == kind && q.period == k && std::abs(q.param - bp.param) < std::max(1e-5 * q_scale_, 3 * (q.precision + bp.precision)))
            return;
    result_.points.push_back(bp);
    // A doubling of an impacting orbit: its period-2k branch switched onto, as on the stroboscopic map.
    if (kind == BifKind::PeriodDoubling && 2 * k <= spec_.max_period) switch_to_doubled(best, k, branch);
}

bool Continuer::grazing_start(double q_g, const Vec2& y_g, int k, Vec3& z, Vec3& t, Vec2& section, bool dwell) {
    // The grazing orbit written from impact to impact touches xI at the peak of the bumperless orbit, v- = 0:
    // found at the grazing's parameter; with a dwell at rest, v- = 0 is held and the parameter is free.
    Eigen::Matrix<double, 2, 3> J;
    const double theta_g = peak_phase(work_, apply(q_g), y_g, k, spec_.sim);
    const Vec3 held = dwell ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    if (!correct_impacting(Vec3(theta_g, 0.0, q_g / q_scale_), held, k, z, J, section)) return false;
    t = Vec3(J.row(0).transpose()).cross(Vec3(J.row(1).transpose()));
    if (!(t.norm() > 0) || !t.allFinite()) return false;
    t.normalize();
    if (t[1] < 0) t = -t;   // onto the impacting side: v- grows
    return true;
}

void Continuer::describe_dwell(BifPoint& gp, const Vec3& z, const Vec2& section, int k) {
    // The jump: the grazing orbit's section point against the nearest of the dwelling orbit's k section points.
    const double q0 = q_of(z);
    const MapResult r = map(u_of(section, q0), k, false);
    Vec2 nearest = section;
    for (const Vec2& sp : r.sections)
        if (scaled_norm(sp - gp.y) < scaled_norm(nearest - gp.y)) nearest = sp;
    apply(gp.param);
    char buf[360];
    std::snprintf(buf, sizeof buf,
                  "dwell at rest: an impact at v- -> 0 still holds the cart for T_imp(0) = %.3g ms, so the map jumps "
                  "here; the impacting branch starts at %s = %.9g (%+.3g from the grazing), arriving at rest, its "
                  "section point %+.3g mm, %+.3g mm/s from the grazing orbit's",
                  dwell_at_rest() * 1e3, sweep_param_name(spec_.param), q0, q0 - gp.param,
                  (nearest[0] - gp.y[0]) * 1e3, (nearest[1] - gp.y[1]) * 1e3);
    gp.scenario = buf;
}

void Continuer::describe_grazing(BifPoint& gp, double free_dir, const Vec3& z, const Vec3& t, int k) {
    // The free orbits' side: where the bumperless orbit stays below xI, 1e-4 (scaled) either side of the
    // grazing. The way the branch was going (free_dir) is the fallback: it is not reliable, since a corrector
    // that steps across a nonsmooth fold turns back in the parameter there.
    double free_side = free_dir >= 0 ? -1.0 : 1.0;
    const ImpactModel* law = work_.impact;
    work_.impact = find_impact("none");
    int below = 0;
    double side_below = 0;
    for (double sgn : {-1.0, 1.0}) {
        const double q = gp.param + sgn * 1e-4 * q_scale_;
        OrbitOptions oo;
        oo.period = k;
        oo.sim = spec_.sim;
        const double omega = apply(q);
        const Orbit o = find_orbit(work_, omega, gp.y, oo);
        double x_max = 0;
        if (!o.converged) continue;
        peak_phase(work_, omega, o.y, k, spec_.sim, &x_max);
        if (x_max < work_.xI) {
            ++below;
            side_below = sgn;
        }
    }
    work_.impact = law;
    apply(gp.param);
    if (below == 1) free_side = side_below;
    gp.scenario = (t[2] >= 0) == (free_side >= 0) ? "nonsmooth fold" : "persistence";
    measure_scaling(gp, z, t, k);
}

void Continuer::measure_scaling(BifPoint& gp, const Vec3& z, const Vec3& t, int k) {
    const double side = t[2] >= 0 ? 1.0 : -1.0;
    // The scaling: orbits at fixed q whose impacts are 1e-4, 3e-4 and 1e-3 m/s fast (d from the tangent).
    // Slower impacts are below what the Simulator resolves on the real map (an impact of 1e-7 m/s comes
    // out at 3e-6: the event is located to about 1e-12 m); faster ones are no longer near the grazing.
    if (std::abs(t[2]) > 1e-9 && t[1] > 0) {
        double sx = 0, sy_mu = 0, sy_v = 0, sxx = 0, sxm = 0, sxv = 0;
        int n = 0;
        const double dv_dd = t[1] * kVScale / std::abs(t[2]);   // [m/s] per scaled q
        for (double v_target : {1e-4, 3e-4, 1e-3}) {
            const double d = v_target / dv_dd;
            if (!(d < 0.5)) continue;
            Vec3 zd;
            Eigen::Matrix<double, 2, 3> Jd;
            Vec2 sec;
            const Vec3 pred = z + (side * d / t[2]) * t;
            if (!correct_impacting(pred, Vec3(0, 0, 1), k, zd, Jd, sec) || !(zd[1] > 0)) continue;
            const MapResult m = map(u_of(sec, q_of(zd)), k, true);
            if (m.impacts != 1) continue;   // the orbit is not admissible there
            const double mu = std::abs(floquet(m.M).mu[0]);
            const double lx = std::log(d), lm = std::log(mu), lv = std::log(zd[1] * kVScale);
            sx += lx; sxx += lx * lx; sy_mu += lm; sy_v += lv; sxm += lx * lm; sxv += lx * lv;
            ++n;
        }
        if (n == 3) {
            const double den = n * sxx - sx * sx;
            gp.mu_exponent = (n * sxm - sx * sy_mu) / den;
            gp.speed_exponent = (n * sxv - sx * sy_v) / den;
        }
    }
}

}  // namespace impactlab::analysis::detail
