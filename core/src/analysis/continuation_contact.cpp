// The continuation through a compliant contact's grazing layer. A stiff compliant bumper (C: kI = 2.4e8)
// smooths the rigid grazing's square-root map over a layer of about a micron: within it the branch turns and
// its multipliers run from +1 to -20 over nanometres of depth, a curvature the arclength corrector cannot
// follow at any step it may take. Written with the contact's depth d = (largest x) - xI as the parameter, the
// same branch is a smooth function of d (Newton converges in 2-4 iterations), so the layer is crossed in depth
// and the arclength continuation resumes on the far side.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/continuer.hpp"
#include "impactlab/analysis.hpp"

namespace impactlab::analysis::detail {

namespace {

// Depths are stepped in s = asinh(d / scale): linear across the touch, geometric beyond the scale, which is
// the depth where the corrector failed over kScaleDivisor (C's layer turns at 60 nm, C1's, 1e4 times stiffer,
// at 0.03 nm), and at least kMinDepthScale [m].
constexpr double kScaleDivisor = 4.0;
constexpr double kMinDepthScale = 1e-13;
// The layer is entered only from an orbit this close to the touch [m], and left this deep in the contact,
// or this far clear of it [m]: past that the arclength corrector follows the branch again.
constexpr double kLayerEntry = kContactDepth;
constexpr double kLayerExitIn = 2e-6;
constexpr double kLayerExitOut = 5e-7;
// Steps in s: the first, the longest, and the shortest before the layer is given up.
constexpr double kFirstStep = 0.25, kMaxStep = 1.0, kMinStep = 1e-3;
// The finite-difference step of the largest x in the scaled section point.
constexpr double kDepthFd = 1e-7;

double depth_of(const Sol& s, double xI) { return s.r.max_x - xI; }

}  // namespace

bool Continuer::correct_depth(const Vec3& u_pred, double depth, int k, Sol& out) {
    Vec3 u = u_pred;
    for (int it = 0; it <= kMaxCorrector; ++it) {
        if (spec_.param == ContParam::Omega && !(q_of(u) > 0)) return false;
        // The point with its monodromy, the parameter's neighbour and the depth's two neighbours, side by side.
        Vec3 ux = u, uv = u;
        ux[0] += kDepthFd;
        uv[1] += kDepthFd;
        std::vector<MapResult> rs = maps({{u, true}, {shifted_q(u), false}, {ux, false}, {uv, false}}, k);
        MapResult r = std::move(rs[0]);
        const Vec2 G = residual(r, u);
        const double g3 = (r.max_x - work_.xI - depth) / kXScale;
        if (!G.allFinite() || !std::isfinite(g3)) return false;
        const Eigen::Matrix<double, 2, 3> J = jacobian(r, rs[1]);
        // The depth to a part in 100 of itself (C1's layer is a fraction of a nanometre deep), or the map's tolerance.
        const double depth_tol = std::min(res_tol_, std::max(0.01 * std::abs(depth), kMinDepthScale) / kXScale);
        if (G.cwiseAbs().maxCoeff() < res_tol_ && std::abs(g3) < depth_tol) return take(out, u, r, J, it);
        if (it == kMaxCorrector) break;
        // The depth's row: the largest x by forward differences in x and v, and the parameter's map above.
        Mat3 A;
        A.topRows<2>() = J;
        A(2, 0) = (rs[2].max_x - r.max_x) / kXScale / kDepthFd;
        A(2, 1) = (rs[3].max_x - r.max_x) / kXScale / kDepthFd;
        A(2, 2) = (rs[1].max_x - r.max_x) / kXScale / kDq;
        const Vec3 du = A.fullPivLu().solve(-Vec3(G[0], G[1], g3));
        if (!du.allFinite() || du.norm() > 0.1) return false;   // left the neighbourhood of the branch
        u += du;
    }
    return false;
}

void Continuer::locate_depth(BifKind kind, const Sol& a, double sa, const Sol& b, double sb, double scale, int k,
                             int branch) {
    Sol lo = a, hi = b;
    double s_lo = sa, s_hi = sb, f_lo = test(kind, a), f_hi = test(kind, b);
    for (int it = 0; it < 60 && std::abs(q_of(hi.u) - q_of(lo.u)) > spec_.locate_tol; ++it) {
        const double w = s_hi - s_lo;
        double s = (f_hi == f_lo) ? 0.5 * (s_lo + s_hi) : s_hi - f_hi * w / (f_hi - f_lo);
        s = std::clamp(s, std::min(s_lo, s_hi) + 0.02 * std::abs(w), std::max(s_lo, s_hi) - 0.02 * std::abs(w));
        const Vec3 pred = lo.u + (hi.u - lo.u) * ((s - s_lo) / w);
        Sol m;
        if (!correct_depth(pred, scale * std::sinh(s), k, m)) break;
        const double fm = test(kind, m);
        if ((fm > 0) == (f_hi > 0)) {
            s_hi = s;
            hi = std::move(m);
            f_hi = fm;
            f_lo *= 0.5;
        } else {
            s_lo = s;
            lo = std::move(m);
            f_lo = fm;
            f_hi *= 0.5;
        }
    }
    record(kind, lo, hi, f_lo, f_hi, k, branch);
}

bool Continuer::cross_contact_layer(Sol& cur, Vec3& t, int k, int branch, std::vector<BranchPoint>& pts,
                                    std::vector<double>& arc) {
    if (!work_.has_bumper() || work_.rigid() || pts.size() < 2) return false;
    const double xI = work_.xI;
    const double d0 = depth_of(cur, xI);
    if (!(std::abs(d0) < kLayerEntry)) return false;
    const BranchPoint& before = pts[pts.size() - 2];
    // The way the branch was going: deeper into the contact or out of it, and up or down in the parameter.
    const double sigma = d0 >= before.max_x - xI ? 1.0 : -1.0;
    const double q_dir = q_of(cur.u) >= before.param ? 1.0 : -1.0;
    const double scale = std::max(std::abs(d0) / kScaleDivisor, kMinDepthScale);
    double s = std::asinh(d0 / scale);
    const double s_exit = sigma > 0 ? std::asinh(kLayerExitIn / scale) : std::asinh(-kLayerExitOut / scale);
    if (sigma * (s_exit - s) <= 0) return false;   // already past the layer: not what failed the corrector

    const double q_entry = q_of(cur.u);
    Sol a = cur, prev;
    double s_prev = s, h = kFirstStep;
    bool have_prev = false, turned = false;
    double q_turn = NAN, d_turn = NAN, q_touch = NAN;
    int steps = 0;
    while (sigma * (s_exit - s) > 0) {
        if (cancelled() || static_cast<int>(pts.size()) >= spec_.max_points) break;
        double s_new = s + sigma * h;
        if (sigma * (s_new - s_exit) > 0) s_new = s_exit;
        Vec3 pred = a.u;
        if (have_prev) pred += (a.u - prev.u) * ((s_new - s) / (s - s_prev));   // the secant through the last two
        Sol b;
        if (!correct_depth(pred, scale * std::sinh(s_new), k, b)) {
            h *= 0.5;
            if (h < kMinStep) break;
            continue;
        }
        for (BifKind kind : {BifKind::Fold, BifKind::PeriodDoubling, BifKind::NeimarkSacker}) {
            const double fa = test(kind, a), fb = test(kind, b);
            if (!std::isfinite(fa) || !std::isfinite(fb) || (fa > 0) == (fb > 0)) continue;
            if (kind == BifKind::NeimarkSacker && !(complex_pair(a.r.M) && complex_pair(b.r.M))) continue;
            locate_depth(kind, a, s, b, s_new, scale, k, branch);
        }
        // The touch itself (depth 0) crossed in this step: the grazing orbit, solved for at depth 0.
        if ((depth_of(a, xI) > 0) != (depth_of(b, xI) > 0)) {
            Sol g;
            const Vec3 gp = a.u + (b.u - a.u) * ((0.0 - s) / (s_new - s));
            if (correct_depth(gp, 0.0, k, g)) {
                record(BifKind::Grazing, g, g, 0.0, 0.0, k, branch);
                q_touch = q_of(g.u);
            }
        }
        // The parameter turning back inside the layer: the smoothed nonsmooth fold.
        if (!turned && (q_of(b.u) - q_of(a.u)) * q_dir < 0) {
            turned = true;
            q_turn = q_of(a.u);
            d_turn = depth_of(a, xI);
        }
        pts.push_back(point_of(b, k));
        arc.push_back((arc.empty() ? 0.0 : arc.back()) + (b.u - a.u).norm());
        prev = std::move(a);
        s_prev = s;
        a = std::move(b);
        s = s_new;
        have_prev = true;
        ++steps;
        h = std::min(h * 1.5, kMaxStep);
    }
    if (sigma * (s_exit - s) > 0) {   // not crossed: the branch is left as it was at the layer's edge
        pts.resize(pts.size() - static_cast<std::size_t>(steps));
        arc.resize(arc.size() - static_cast<std::size_t>(steps));
        return false;
    }
    cur = a;
    const Vec3 secant = (a.u - prev.u).normalized();
    t = tangent_of(cur, secant);

    // The grazing this layer belongs to: the one just crossed, or the one located as the corrector stepped in.
    if (std::isnan(q_touch)) q_touch = q_entry;
    BifPoint* gp = nullptr;
    for (BifPoint& q : result_.points)
        if (q.kind == BifKind::Grazing && q.period == k && std::abs(q.param - q_touch) < 1e-2 * q_scale_ &&
            (!gp || std::abs(q.param - q_touch) < std::abs(gp->param - q_touch)))
            gp = &q;
    if (gp && gp->scenario.empty()) {
        char buf[200];
        if (turned)
            std::snprintf(buf, sizeof buf,
                          "nonsmooth fold, smoothed by the compliant contact: the branch turns at %s = %.9g, %.2g um "
                          "into the contact",
                          sweep_param_name(spec_.param), q_turn, d_turn * 1e6);
        else
            std::snprintf(buf, sizeof buf, "persistence: the branch goes on into the compliant contact");
        gp->scenario = buf;
    }
    return true;
}

}  // namespace impactlab::analysis::detail
