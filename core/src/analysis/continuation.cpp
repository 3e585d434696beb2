// Pseudo-arclength continuation of periodic orbits (fixed points of P^k) in omega, xI or m0e, with test
// functions for folds (det(M - I)), period doublings (det(M + I)), Neimark-Sacker (det M - 1 with complex
// multipliers) and grazing (the largest x of the orbit reaching xI, or the smallest impact speed reaching 0),
// each located by bisection along the arclength; at a period doubling the period-2k branch is switched onto.
// A sign change counts only as the multiplier crossing it names (real through +1 or -1, a complex pair through
// the unit circle, at a finite rate, clear of a grazing); a doubling or Neimark-Sacker is then re-located on
// the orbit found again at a tighter tolerance.
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

namespace impactlab::analysis {

const char* bif_kind_name(BifKind k) {
    switch (k) {
        case BifKind::Fold: return "fold";
        case BifKind::PeriodDoubling: return "period_doubling";
        case BifKind::NeimarkSacker: return "neimark_sacker";
        case BifKind::Grazing: return "grazing";
    }
    return "?";
}

namespace detail {


void Continuer::locate(BifKind kind, const Sol& a, const Vec3& t, double ds, const Sol& b, int k, int branch,
                       bool off_bumper) {
    double s_lo = 0, s_hi = ds, f_lo = test(kind, a), f_hi = test(kind, b);
    Sol lo = a, hi = b;
    // A rigid grazing is located on the orbit without the bumper, whose largest x is smooth in the parameter
    // and equals xI exactly at the grazing (on the impacting side the map's derivative grows without bound
    // and the corrector may fail inside the bracket). The same holds for a compliant bumper: its force is
    // zero up to the touch.
    const ImpactModel* rigid_law = nullptr;
    if (kind == BifKind::Grazing && (work_.rigid() || off_bumper)) {
        rigid_law = work_.impact;
        work_.impact = find_impact("none");
        // Walk along the step (and a little past it) on the bumperless orbit until its largest x passes xI.
        Sol la, lb;
        bool bracketed = false;
        Sol start;
        if (correct(a.u, t, k, start)) {
            // From a sixteenth of the step, doubling; failing that, from a step of the order of the distance
            // left (an orbit nanometres short of xI may turn back within the longer first step).
            const double g0 = std::abs(test(kind, start));
            for (double first : {ds / 16, std::clamp(4 * g0, 16 * spec_.ds_min, ds / 16)}) {
                double s_prev = 0;
                la = start;
                for (double sg = first; sg <= 2 * ds && !bracketed; sg *= 2) {
                    if (!correct(a.u + sg * t, t, k, lb)) break;
                    if (((la.r.max_x - work_.xI) > 0) != ((lb.r.max_x - work_.xI) > 0)) {
                        bracketed = true;
                        s_lo = s_prev;
                        s_hi = sg;
                    } else {
                        la = lb;
                        s_prev = sg;
                    }
                }
                if (bracketed || first <= 16 * spec_.ds_min) break;
            }
        }
        if (bracketed) {
            lo = la;
            hi = lb;
            f_lo = test(kind, lo);
            f_hi = test(kind, hi);
        } else {
            work_.impact = rigid_law;
            rigid_law = nullptr;
        }
    }
    if ((f_lo > 0) == (f_hi > 0)) return;   // nothing bracketed (a rigid grazing the corrector cannot reach)
    for (int it = 0; it < 80 && std::abs(q_of(hi.u) - q_of(lo.u)) > spec_.locate_tol; ++it) {
        // Illinois step on the arclength, kept inside the bracket.
        double s = (f_hi == f_lo) ? 0.5 * (s_lo + s_hi) : s_hi - f_hi * (s_hi - s_lo) / (f_hi - f_lo);
        const double w = s_hi - s_lo;
        s = std::clamp(s, s_lo + 0.02 * w, s_hi - 0.02 * w);
        Sol m;
        if (!correct(a.u + s * t, t, k, m)) break;
        const double fm = test(kind, m);
        if ((fm > 0) == (f_hi > 0)) {
            s_hi = s;
            hi = m;
            f_hi = fm;
            f_lo *= 0.5;
        } else {
            s_lo = s;
            lo = m;
            f_lo = fm;
            f_hi *= 0.5;
        }
    }
    if (rigid_law) work_.impact = rigid_law;
    record(kind, lo, hi, f_lo, f_hi, k, branch);
}

void Continuer::record(BifKind kind, const Sol& lo, const Sol& hi, double f_lo, double f_hi, int k, int branch) {
    const Sol& best = std::abs(f_lo) < std::abs(f_hi) ? lo : hi;
    double precision = std::abs(q_of(hi.u) - q_of(lo.u)), shift = 0;
    if (kind != BifKind::Grazing && !true_crossing(kind, lo, hi, best, k, precision, shift)) return;
    // A compliant bumper's grazing is an orbit touching it: one that stays clear by more than the grazing
    // layer is a sign change across a jump between two segments, the corrector failing in between (A1C's
    // period 8 near 16.8003: the free orbit 1.2 um short of the bumper on one side, one pressing it on the other).
    if (kind == BifKind::Grazing && work_.compliant() && std::abs(best.r.max_x - work_.xI) > kGrazingLayer) return;
    BifPoint bp{kind, q_of(best.u) + shift, y_of(best.u), k, branch, precision, {}, NAN, NAN};
    // The same point met again (from the other side of a bubble, on another branch through the same orbit at
    // another of its k phases, or by a failed corrector after its sign change): reported once.
    for (std::size_t qi = 0; qi < result_.points.size(); ++qi) {
        const BifPoint& q = result_.points[qi];
        if (q.kind != kind || q.period != k) continue;
        if (std::abs(q.param - bp.param) > std::max(1e-5 * q_scale_, 3 * (q.precision + bp.precision))) continue;
        bool same = scaled_norm(q.y - bp.y) < 1e-3;
        for (const Vec2& sp : best.r.sections) same = same || scaled_norm(q.y - sp) < 1e-3;
        if (same) {
            last_located_ = static_cast<int>(qi);
            return;
        }
    }
    last_located_ = static_cast<int>(result_.points.size());
    result_.points.push_back(bp);
    if (kind != BifKind::PeriodDoubling || 2 * k > spec_.max_period) return;
    switch_to_doubled(best, k, branch);
}

bool Continuer::true_crossing(BifKind kind, const Sol& lo, const Sol& hi, const Sol& best, int k, double& precision,
                              double& shift) {
    // A fold, a doubling or a Neimark-Sacker is a multiplier crossing +1, -1 or the unit circle: it
    // must be of that sort on both sides of the bracket, near the value it crosses, and change at a
    // finite rate along the arclength. A sign change of the test function without that is a jump (a
    // grazing's: the impacting orbit's multiplier runs from +1 to -22 within 1e-5 rad/s of it), not a
    // bifurcation of that kind.
    const double c = kind == BifKind::Fold ? 1.0 : -1.0;
    const double target = kind == BifKind::NeimarkSacker ? 1.0 : c;
    const double m_lo = crossing_multiplier(kind, lo.r.M), m_hi = crossing_multiplier(kind, hi.r.M);
    if (!std::isfinite(m_lo) || !std::isfinite(m_hi)) return false;
    if (std::abs(m_lo - target) > kNearCrossing || std::abs(m_hi - target) > kNearCrossing) return false;
    if (multiplier_jumps(m_lo, m_hi, (hi.u - lo.u).norm())) return false;
    // Inside a compliant bumper's grazing layer the crossing is the grazing's, however smooth it looks
    // there (A3C's period 2 at 12.8999, 1e-4 past its grazing: mu = -1.005 with 0.22 um of penetration).
    if (work_.compliant() && best.r.max_x > work_.xI && best.r.max_x - work_.xI < kGrazingLayer) return false;
    refine_crossing(kind, lo, hi, best, k, precision, shift);
    return true;
}

void Continuer::refine_crossing(BifKind kind, const Sol& lo, const Sol& hi, const Sol& best, int k, double& precision,
                                double& shift) {
    // The bracket is only as good as the monodromy: at rtol 1e-10 the multiplier of A1C near its first
    // doubling jitters by 5e-5 from one omega to the next (the step sequence changes), so a bracket of
    // 1e-7 may sit 6e-5 from the crossing. The orbit is found again at rtol / 100, where the multiplier is
    // smooth, the crossing moved there by a secant, and its error bounded by how far the multiplier
    // still moves from rtol / 10. A fold needs no move: its parameter is stationary in the multiplier.
    // The secant's first step is ten brackets long (at least 1e-7, at most 1e-3, scaled): near a slow impact
    // the multiplier runs from -6 to -0.9 within 1e-5 rad/s (A1H's period 8 at 18.6821), and a secant over
    // 1e-3 would land far off. But the step must move the multiplier well beyond its noise at rtol / 100
    // (a shallow crossing, A1C's period 1 at 22.147: 0.15 per rad/s; one deep in the contact, its period 4 at
    // 19.1511: noise 5e-6 at 74 per rad/s), or the secant follows the noise: it grows tenfold until it does.
    // Up to four secant steps, while each brings the multiplier closer.
    if (kind == BifKind::Fold || kind == BifKind::Grazing) return;
    const double target = kind == BifKind::NeimarkSacker ? 1.0 : -1.0;
    const double width = std::abs(q_of(hi.u) - q_of(lo.u));
    double dq = std::clamp(10 * width, 1e-7 * q_scale_, 1e-3 * q_scale_) * (q_of(hi.u) > q_of(lo.u) ? 1 : -1);
    const Vec2 y = y_of(best.u);
    const double q0 = q_of(best.u);
    const double m0 = crossing_at(kind, q0, y, k, 0.01);
    const double m_mid = crossing_at(kind, q0, y, k, 0.1);
    // The multiplier's noise at rtol / 100: a tenth of its move from rtol / 10, and never below the tangent
    // tracker's own floor (its Magnus tolerance does not follow rtol).
    const double noise = std::max(0.1 * std::abs(m0 - m_mid), kMultiplierFloor);
    const double distinct = 30 * noise;   // two multipliers this far apart give a slope above the noise
    double qb = q0 + dq, mb = crossing_at(kind, qb, y, k, 0.01);
    // A probe beyond the crossing's neighbourhood reads another multiplier (past A1C's period-8 doubling at
    // 18.50471 the crossing one runs to -4 within 1e-4 and the nearest to -1 is then the other, -1e-5):
    // shorter, down to the bracket's width.
    while (std::isfinite(mb) && std::abs(mb - target) > kNearCrossing && std::abs(dq) > width) {
        dq *= 0.1;
        qb = q0 + dq;
        mb = crossing_at(kind, qb, y, k, 0.01);
    }
    if (!std::isfinite(mb) || std::abs(mb - target) > kNearCrossing) return;   // the bracket stands
    while (std::isfinite(mb) && std::abs(mb - m0) < distinct && std::abs(dq) < 1e-3 * q_scale_) {
        dq *= 10;
        qb = q0 + dq;
        mb = crossing_at(kind, qb, y, k, 0.01);
    }
    if (!std::isfinite(m0) || !std::isfinite(m_mid) || !std::isfinite(mb) || mb == m0) return;
    // Secant steps from the point nearest the crossing; the slope is renewed only from two points whose
    // multipliers differ well beyond the noise (near the crossing they need not).
    double slope = (mb - m0) / (qb - q0);   // d mu / d q at rtol / 100
    double q1 = q0, m1 = m0;
    if (std::abs(mb - target) < std::abs(m0 - target)) {
        q1 = qb;
        m1 = mb;
    }
    for (int it = 0; it < 4 && std::abs(m1 - target) > 1e-9; ++it) {
        const double qc = q1 - (m1 - target) / slope;
        const double mc = crossing_at(kind, qc, y, k, 0.01);
        // A first secant step that brings the multiplier no closer had a slope it cannot trust.
        if (it == 0 && !(std::abs(mc - target) < std::abs(m1 - target))) return;
        if (!std::isfinite(mc) || std::abs(mc - target) >= std::abs(m1 - target)) break;
        if (std::abs(mc - m1) > distinct) slope = (mc - m1) / (qc - q1);
        q1 = qc;
        m1 = mc;
    }
    const double q_cross = q1 - (m1 - target) / slope;
    if (!std::isfinite(q_cross) || std::abs(q_cross - q0) > 1e-3 * q_scale_) return;   // no smooth crossing: the bracket stands
    shift = q_cross - q0;
    precision = std::max({std::abs(m0 - m_mid) / std::abs(slope), std::abs(shift) * 0.1, noise / std::abs(slope)});
}

void Continuer::switch_to_doubled(const Sol& best, int k, int branch) {
    // Switch onto the period-2k branch: it leaves the period-k orbit along the eigenvector of mu = -1.
    Eigen::EigenSolver<Mat2> es(best.r.M);
    int i = std::abs(es.eigenvalues()[0] + 1.0) < std::abs(es.eigenvalues()[1] + 1.0) ? 0 : 1;
    Vec2 e = es.eigenvectors().col(i).real();
    e = Vec2(e[0] / kXScale, e[1] / kVScale);
    if (e.norm() == 0) return;
    e.normalize();
    jobs_.push_back({2 * k, branch, best.u, Vec3(e[0], e[1], 0.0), false, JobMode::Start});
}

std::string Continuer::corrector_limit(const Sol& cur, const Vec3& t, double ds, int k, int branch) {
    std::string end = "numerical limit near " + std::string(sweep_param_name(spec_.param)) + " = " + std::to_string(q_of(cur.u));
    // An orbit about to graze: the impacting side is out of the corrector's reach (a rigid
    // bumper, or a compliant one as stiff as C1's), the grazing itself is still located on
    // the bumperless orbit.
    const double g = test(BifKind::Grazing, cur);
    // The corrector's last residual there: the numerical limit the end states.
    double res_last = NAN;
    {
        const MapResult rl = map(cur.u + ds * 2 * t, k, false);
        res_last = residual(rl, cur.u + ds * 2 * t).cwiseAbs().maxCoeff();
    }
    char rbuf[240];
    std::snprintf(rbuf, sizeof rbuf, ": the corrector fails at steps down to %.1g (residual %.2g there)",
                  spec_.ds_min, res_last);
    end += rbuf;
    if (deep_contact(cur)) {
        std::snprintf(rbuf, sizeof rbuf, ", the orbit %.3g mm deep in the compliant contact", g * kXScale * 1e3);
        end += rbuf;
    } else if (work_.has_bumper() && std::abs(g) < 0.01) {
        std::snprintf(rbuf, sizeof rbuf, ", the orbit's largest x %.3g mm %s the bumper (a grazing ahead or begun)",
                      std::abs(g) * kXScale * 1e3, g < 0 ? "short of" : "into");
        end += rbuf;
    }
    // A compliant contact's orbit that has just begun to press the bumper (inside its first
    // millimetre): the grazing it came from is located on the bumperless orbit and named.
    if (work_.compliant() && g >= 0 && g < 0.1) {
        // Located already as the corrector stepped in (the test's sign change): that one, to
        // its bracket; else located now, back along the branch on the bumperless orbit.
        last_located_ = -1;
        for (std::size_t qi = 0; qi < result_.points.size(); ++qi) {
            const BifPoint& q = result_.points[qi];
            if (q.kind == BifKind::Grazing && q.period == k && std::abs(q.param - q_of(cur.u)) < 1e-3 * q_scale_ &&
                (last_located_ < 0 || q.precision < result_.points[static_cast<std::size_t>(last_located_)].precision))
                last_located_ = static_cast<int>(qi);
        }
        if (last_located_ < 0) locate(BifKind::Grazing, cur, -t, 0.05, cur, k, branch, true);
        if (last_located_ >= 0) {
            const BifPoint& g0 = result_.points[static_cast<std::size_t>(last_located_)];
            char gbuf[320];
            std::snprintf(gbuf, sizeof gbuf,
                          "grazing at %s = %.9g, pressing the compliant contact %.3g mm deep at %s = %.9g, "
                          "where the corrector's steps fail (residual %.2g at a step of %.1g)",
                          sweep_param_name(spec_.param), g0.param, g * kXScale * 1e3,
                          sweep_param_name(spec_.param), q_of(cur.u), res_last, spec_.ds_min);
            end = gbuf;
        }
    }
    if (work_.has_bumper() && g < 0 && g > -0.1) {
        last_located_ = -1;
        locate(BifKind::Grazing, cur, t, 0.05, cur, k, branch, true);
        if (last_located_ >= 0) {
            end = work_.rigid() ? "grazing (rigid impacts begin)" : "grazing (the corrector cannot step into the contacts)";
            // A free orbit touching a rigid bumper: its impacting continuation starts there. H's
            // zero-speed impact still holds the cart for T_imp(0) = 6.2 ms, so its map jumps there:
            // the impacting branch starts at the orbit that arrives at rest and dwells.
            if (work_.rigid() && dwell_at_rest() > 0)
                end = "grazing (rigid impacts begin; a zero-speed impact still sticks for T_imp(0) > 0, "
                      "so the map jumps there)";
            if (work_.rigid() && cur.r.impacts == 0) queue_grazing(result_.points[static_cast<std::size_t>(last_located_)], t, k, branch);
        }
    }
    return end;
}

std::string Continuer::dwell_jump_end(const Sol& cur, const Vec3& t, const Sol& next, int k, int branch) {
    const double qa = q_of(cur.u), qb = q_of(next.u);
    // The grazing located on the step (on the bumperless orbit, so it may lie just outside it: the impacting
    // orbit the corrector landed on can be on the free orbit's side, a nonsmooth fold).
    const BifPoint* g = nullptr;
    const double reach = std::abs(qb - qa) + 1e-4 * q_scale_;
    for (const BifPoint& q : result_.points)
        if (q.kind == BifKind::Grazing && q.period == k && std::abs(q.param - qa) < reach &&
            (!g || std::abs(q.param - qa) < std::abs(g->param - qa)))
            g = &q;
    char buf[200];
    if (cur.r.impacts == 0 && g) {
        // The impacting branch begins apart, at the orbit that arrives at rest: a job of its own.
        queue_grazing(*g, t, k, branch);
        std::snprintf(buf, sizeof buf, "grazing at %s = %.9g (rigid impacts begin; a zero-speed impact still sticks for "
                      "T_imp(0) > 0, so the map jumps there)", sweep_param_name(spec_.param), g->param);
    } else {
        std::snprintf(buf, sizeof buf, "the impacts end across a jump of the map near %s = %.9g (a zero-speed impact still "
                      "sticks for T_imp(0) > 0)", sweep_param_name(spec_.param), 0.5 * (qa + qb));
    }
    return buf;
}

void Continuer::locate_crossings(const Sol& cur, const Vec3& t, double ds, const Sol& next, int k, int branch) {
    for (BifKind kind : {BifKind::Fold, BifKind::PeriodDoubling, BifKind::NeimarkSacker, BifKind::Grazing}) {
        const double fa = test(kind, cur), fb = test(kind, next);
        if (!((fa > 0) != (fb > 0)) || !std::isfinite(fa) || !std::isfinite(fb)) continue;
        if (kind == BifKind::NeimarkSacker && !(complex_pair(cur.r.M) && complex_pair(next.r.M))) continue;
        last_located_ = -1;
        locate(kind, cur, t, ds, next, k, branch);
        // A rigid grazing the corrector itself stepped across (a continuous law): its scenario and
        // exponents, from the grazing orbit.
        if (kind == BifKind::Grazing && last_located_ >= 0 && work_.rigid() && dwell_at_rest() == 0.0 &&
            (cur.r.impacts == 0) != (next.r.impacts == 0)) {
            BifPoint& gp = result_.points[static_cast<std::size_t>(last_located_)];
            Vec3 zg, tg;
            Vec2 sec;
            if (gp.scenario.empty() && grazing_start(gp.param, gp.y, k, zg, tg, sec))
                describe_grazing(gp, cur.r.impacts == 0 ? t[2] : -t[2], zg, tg, k);
        }
    }
}

bool Continuer::passes_by(const BranchPoint& pj, const Vec3& a, const Vec3& b) const {
    for (const Vec2& sp : pj.sections)
        if (segment_distance(u_of(sp, pj.param), a, b) < 1e-3) return true;
    return false;
}

bool Continuer::sharpen(Sol& cur, const Vec3& t, int k, double& ds, int& sharpened, bool at_limit) {
    // A long period (8 periods and more of a cascade) carries the integrator's error up to the corrector's
    // tolerance, and the steps shrink for noise rather than for the branch's shape: the map is sharpened for
    // the rest of this branch (twice at most, down to rtol 1e-12). (Not beside a bumper: there the steps
    // shrink for the grazing, and a sharper map only costs; but at the numerical limit, deep in a compliant
    // contact, the map's noise is the likelier cause, and a limit is stated only after the sharper map.)
    if (!(sharpened < 2 && spec_.sim.rtol > 1.5e-12 &&
          (at_limit ? deep_contact(cur) : ds < 2e-3 && !(work_.has_bumper() && std::abs(test(BifKind::Grazing, cur)) < 0.01))))
        return false;
    ++sharpened;
    spec_.sim.rtol = std::max(spec_.sim.rtol * 0.01, 1e-12);
    Sol again;
    if (correct(cur.u, t, k, again)) cur = std::move(again);   // the point on the sharper map
    ds = std::max(ds, 4e-3);
    return true;
}

bool Continuer::shorten(const Sol& cur, const Vec3& t, const Sol& next, bool first, bool& clipped, double& ds) const {
    // Approaching a grazing (the test function falls towards 0): shorten the step so that the corrector,
    // whose map loses smoothness there, is not thrown across it.
    if (work_.has_bumper() && !first) {
        const double g0 = test(BifKind::Grazing, cur), g1 = test(BifKind::Grazing, next);
        if (g1 < 0 && g1 > g0 && ds > std::max(4 * std::abs(g1), 20 * spec_.ds_min)) {
            ds = std::max(2 * std::abs(g1), 10 * spec_.ds_min);
            return true;
        }
    }
    // A corrector that wandered far from the predictor, or multipliers that moved a lot in one step: the step
    // may have left the branch's segment (the stable period 2 of A1C at 12.78 once landed on the impacting
    // orbit at 12.96, past the fold, with a multiplier of -13). Shorter, down to a crawl: a true jump (a
    // grazing) is then crossed in steps that bracket it.
    // The first step off a doubling too: its branch bends back in the parameter as the square of the step, and
    // a long first step jumps past the next doubling of a cascade (A1C's period 8 from 19.4957 landed at
    // 19.4036, past its own doubling at 19.43, with mu = -2.1).
    if (ds > 16 * spec_.ds_min &&
        ((next.u - (cur.u + ds * t)).norm() > 0.5 * ds || (!first && multiplier_change(cur.r.M, next.r.M) > kMaxMultiplierStep))) {
        ds *= 0.5;
        return true;
    }
    // A step past the end of the range: once, shorten it to end there, so that the branch reaches the range's
    // end rather than stopping up to ds_max short of it.
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    if (const double qn = q_of(next.u); (qn < lo || qn > hi) && !clipped) {
        clipped = true;
        const double frac = ((qn > hi ? hi : lo) - q_of(cur.u)) / (qn - q_of(cur.u));
        if (frac > 0 && frac < 1 && frac * ds > spec_.ds_min) {
            ds *= 0.999 * frac;
            return true;
        }
    }
    return false;
}

void Continuer::report_progress(double q) {
    if (!progress_) return;
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    const double f = (q - lo) / (hi - lo);
    const double now = std::clamp(branch_fraction_ + f / std::max<double>(1, 1 + jobs_.size()), 0.0, 1.0);
    if (now > progress_->fraction.load(std::memory_order_relaxed))   // never backwards
        progress_->fraction.store(now, std::memory_order_relaxed);
}

std::string Continuer::hand_over(const Job& job, const Sol& next, const Vec3& t, int branch, std::vector<BranchPoint>& pts) {
    const int k = job.period;
    pts.push_back(point_of(next, k));
    Branch rest;
    rest.id = branch;
    Job on{k, job.parent, next.u, t, false, JobMode::SlowImpacts};
    ++handoffs_;
    follow_impacting(on, rest);
    pts.insert(pts.end(), rest.points.begin(), rest.points.end());
    return rest.end;
}

void Continuer::follow(const Job& job, Branch& br) {
    const int k = job.period;
    std::vector<BranchPoint> fwd, bwd;
    std::string end_fwd, end_bwd, skipped;
    // The map's tolerance may be sharpened along this branch (below); the next branch starts from the spec's.
    const Tolerances sim0 = spec_.sim;
    struct Restore {
        Tolerances& sim;
        Tolerances saved;
        ~Restore() { sim = saved; }
    } restore{spec_.sim, sim0};
    int sharpened = 0, layers = 0;
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    bool closed = false;
    for (int dir = 0; dir < (job.both_ways && !closed ? 2 : 1); ++dir) {
        auto& pts = dir == 0 ? fwd : bwd;
        auto& end = dir == 0 ? end_fwd : end_bwd;
        std::vector<double> arc(pts.size(), 0.0);   // arclength of each point from this direction's start
        Vec3 t = dir == 0 ? job.t : Vec3(-job.t);
        Sol cur;
        double ds = spec_.ds;
        if (job.both_ways || job.mode == JobMode::Onward) {   // the start is a converged point of this branch
            if (!correct(job.u, t, k, cur)) {
                end = "the start did not converge";
                continue;
            }
            if (dir == 0) pts.push_back(point_of(cur, k));
            t = tangent_of(cur, t);
        } else {               // a switch: the start is the period-doubling point, step off along t
            cur.u = job.u;
            cur.r = map(job.u, k, true);
            pts.push_back(point_of(cur, k));
        }
        bool first = !job.both_ways && job.mode != JobMode::Onward;
        bool clipped = false;
        // d t / ds from the last two tangents: the predictor u + ds t + ds^2/2 dt/ds lands an order closer to
        // a bending branch, and its corrector needs fewer maps (zero after anything but a plain step).
        Vec3 curv = Vec3::Zero();
        while (true) {
            if (cancelled()) {
                end = "cancelled";
                break;
            }
            if (static_cast<int>(fwd.size() + bwd.size()) >= spec_.max_points) {
                end = "point limit";
                break;
            }
            Sol next;
            if (!correct(cur.u + ds * t + 0.5 * ds * ds * curv, t, k, next)) {
                if (sharpen(cur, t, k, ds, sharpened)) {
                    curv.setZero();
                    continue;
                }
                ds *= 0.5;
                if (ds < spec_.ds_min) {
                    curv.setZero();   // whatever follows moves cur or ends the branch
                    // Within a compliant contact's grazing layer: on in the contact's depth, then onward.
                    if (layers < kMaxLayers && std::abs(test(BifKind::Grazing, cur)) < kContactDepth / kXScale && !work_.rigid()) {
                        ++layers;
                        if (cross_contact_layer(cur, t, k, br.id, pts, arc)) {
                            // Resume at the layer's last step: the branch's scale there.
                            ds = std::clamp(arc.size() > 1 ? arc.back() - arc[arc.size() - 2] : spec_.ds, 16 * spec_.ds_min, spec_.ds);
                            continue;
                        }
                    }
                    // A cart held by dry friction (a real multiplier within 1 % of +1: the creeping mode)
                    // has a nearly singular M - I, and the corrector fails where the damped Newton of
                    // find_orbit still converges: restart a little further on at fixed q, the same branch.
                    if (sharpen(cur, t, k, ds, sharpened, true)) continue;
                    if (restart(cur, t, k, ds, skipped)) continue;
                    end = corrector_limit(cur, t, ds, k, br.id);
                    break;
                }
                continue;
            }
            // A period-2k branch that shrinks back onto its period-k orbit has reached the other period
            // doubling of a bubble: stop there (the period-k branch holds the rest).
            if (k > 1 && job.parent >= 0) {
                const double gap = half_gap(next, k);
                if (gap < 1e-5) {
                    // A collapse from far in one step is a corrector that jumped onto the period-k orbit
                    // (which P^2k also fixes): retry shorter; so is the first step off the doubling, whose
                    // period-2k orbits lie about ds apart. A gradual one is the bubble's other end.
                    if ((first || half_gap(cur, k) > 100 * std::max(gap, 1e-4)) && ds > 10 * spec_.ds_min) {
                        ds *= 0.25;
                        continue;
                    }
                    end = "rejoined the period-" + std::to_string(k / 2) + " branch";
                    break;
                }
            }
            if (shorten(cur, t, next, first, clipped, ds)) continue;
            // Slow rigid impacts (near a grazing): the stroboscopic map's derivative grows as 1/v-, and its
            // corrector crawls or jumps across; on from impact to impact, where the grazing can be reached.
            if (work_.rigid() && !first && next.r.impacts == 1 && cur.r.impacts == 1 && handoffs_ < 16 &&
                next.r.min_impact_speed < 0.8 * kHandover) {
                end = hand_over(job, next, t, br.id, pts);
                break;
            }
            // With several impacts a period, one slowing towards zero cannot be handed over (the impact-to-impact
            // equations hold one impact): the corrector would crawl at the 1/v- derivative for the point limit.
            if (work_.rigid() && !first && next.r.impacts >= 2 && next.r.min_impact_speed < kSlowImpact &&
                next.r.min_impact_speed < cur.r.min_impact_speed) {
                pts.push_back(point_of(next, k));
                char buf[240];
                std::snprintf(buf, sizeof buf, "a grazing ahead near %s = %.9g: one of %d impacts a period slows to "
                              "%.2g m/s (the impact-to-impact equations follow one)", sweep_param_name(spec_.param),
                              q_of(next.u), next.r.impacts, next.r.min_impact_speed);
                end = buf;
                break;
            }
            const Vec3 t_next = tangent_of(next, t);
            if (!first) {
                locate_crossings(cur, t, ds, next, k, br.id);
                // H's map jumps at a grazing (a touch at rest still dwells T_imp(0)): a step between a free
                // orbit and an impacting one joins two branches, not one; it ends here.
                if (dwell_at_rest() > 0 && (cur.r.impacts == 0) != (next.r.impacts == 0)) {
                    end = dwell_jump_end(cur, t, next, k, br.id);
                    break;
                }
            }
            const bool first_step = first;
            first = false;
            const double q = q_of(next.u);
            if (q < lo || q > hi) {
                end = std::string(sweep_param_name(spec_.param)) + " range";
                break;
            }
            pts.push_back(point_of(next, k));
            arc.push_back((arc.empty() ? 0.0 : arc.back()) + (next.u - cur.u).norm());
            // Back at an earlier orbit of the branch (or at one of its k phases, the same orbit): a closed
            // branch, an isola. Without this it would be followed round again up to the point limit.
            if (pts.size() > 8) {
                // Only orbits at least 0.5 (scaled arclength) behind: a branch's own last steps are always near.
                for (std::size_t j = 0; j + 8 < pts.size() && !closed; ++j)
                    if (arc.back() - arc[j] > 0.5) closed = passes_by(pts[j], cur.u, next.u);
                if (!closed && dir == 1 && !fwd.empty() && arc.back() > 0.5) closed = passes_by(fwd.front(), cur.u, next.u);
                if (closed) {
                    end = "closed loop (back at an earlier orbit)";
                    break;
                }
            }
            const double step = (next.u - cur.u).norm();
            curv = !first_step && step > 0 ? Vec3((t_next - t) / step) : Vec3::Zero();
            cur = std::move(next);
            t = t_next;
            if (dir == 0) report_progress(q);
            // Step control: grow after an easy correction, shrink after a hard one.
            ds = cur.iterations <= 2 ? std::min(ds * 1.5, spec_.ds_max) : cur.iterations >= 5 ? ds * 0.6 : ds;
        }
    }
    br.points.assign(bwd.rbegin(), bwd.rend());
    br.points.insert(br.points.end(), fwd.begin(), fwd.end());
    br.end = job.both_ways && !bwd.empty() ? end_bwd + " / " + end_fwd : job.both_ways && !closed ? end_bwd + " / " + end_fwd : end_fwd;
    if (!skipped.empty()) br.end += " (restarted across " + skipped + ": near-neutral orbit, corrector failed)";
}

bool Continuer::covered(const Job& job) const {
    // The branch passes through the doubling's orbit: some step of it (between consecutive points, section
    // by section) comes within 0.01 (scaled) of it. A step is up to ds_max long, so a point alone may not.
    const Vec3 c = job.u;
    for (const auto& b : result_.branches) {
        if (b.period != job.period) continue;
        for (std::size_t j = 0; j + 1 < b.points.size(); ++j) {
            const BranchPoint &p0 = b.points[j], &p1 = b.points[j + 1];
            if (std::abs(p0.param / q_scale_ - c[2]) > 0.5 && std::abs(p1.param / q_scale_ - c[2]) > 0.5) continue;
            for (std::size_t i = 0; i < p0.sections.size() && i < p1.sections.size(); ++i)
                if (segment_distance(c, u_of(p0.sections[i], p0.param), u_of(p1.sections[i], p1.param)) < 0.01) return true;
        }
    }
    return false;
}

ContinuationResult Continuer::run() {
    const auto t0 = std::chrono::steady_clock::now();
    const double lo = std::min(spec_.lo, spec_.hi), hi = std::max(spec_.lo, spec_.hi);
    const double q0 = std::isnan(spec_.start) ? lo : spec_.start;
    // The first orbit: settle from the guess (or the left well's bottom) and polish by Newton.
    const double omega0 = apply(q0);
    Vec2 guess = spec_.guess;
    if (!guess.allFinite()) guess = settle(work_, omega0, Vec2(left_well(work_), 0.0), 200, spec_.sim);
    OrbitOptions oo;
    oo.period = spec_.period;
    oo.sim = spec_.sim;
    const Orbit o = find_orbit(work_, omega0, guess, oo);
    if (!o.converged) {
        result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        Branch b;
        b.end = "no periodic orbit of period " + std::to_string(spec_.period) + " found at the start: " + o.message;
        result_.branches.push_back(b);
        return std::move(result_);
    }
    jobs_.push_back({spec_.period, -1, u_of(o.y, q0), Vec3(0, 0, 1), q0 > lo && q0 < hi, JobMode::Start});
    if (!(q0 > lo && q0 < hi) && q0 >= hi) jobs_.back().t = Vec3(0, 0, -1);
    while (!jobs_.empty() && static_cast<int>(result_.branches.size()) < spec_.max_branches) {
        const Job job = jobs_.front();
        jobs_.pop_front();
        if (cancelled()) {
            result_.cancelled = true;
            break;
        }
        // A period doubling that an earlier period-2k branch already reached (the far end of a bubble).
        // Any of a period-k orbit's k section points may be where the switch lands (the same orbit, another
        // phase): each is compared.
        if (job.mode == JobMode::Start && covered(job)) continue;
        Branch br;
        br.id = static_cast<int>(result_.branches.size());
        br.period = job.period;
        br.parent = job.parent;
        if (job.mode == JobMode::Grazing) {
            if (follow_impacting(job, br) == Followed::AlreadyReached) continue;
        } else {
            follow(job, br);
        }
        result_.branches.push_back(std::move(br));
        branch_fraction_ += (1.0 - branch_fraction_) / static_cast<double>(1 + jobs_.size());
    }
    if (cancelled()) result_.cancelled = true;
    std::sort(result_.points.begin(), result_.points.end(),
              [](const BifPoint& a, const BifPoint& b) { return a.param < b.param; });
    result_.map_evaluations = evaluations_;
    result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress_) progress_->fraction.store(1.0, std::memory_order_relaxed);
    return std::move(result_);
}

}  // namespace detail


ContinuationResult continue_orbits(const Params& p, const ContinuationSpec& spec, Progress* progress) {
    detail::Continuer c(p, spec, progress);
    return c.run();
}

}  // namespace impactlab::analysis



