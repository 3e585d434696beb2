// Eq. (1), the rig's equation of motion, assembled once: its force terms at an instant, the first-order
// system y = (x, v) the integrator steps, and that system's derivatives. The simulator, force_terms (the
// fit's equation error) and the tangent tracker all call these, so a new force term goes in one place.
#pragma once

#include "impactlab/drive.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"

namespace impactlab {

// Sum of the extra effects at one instant.
inline EffectForce effects_at(const Params& p, const ForceContext& ctx) {
    EffectForce sum;
    for (const auto& e : p.effects) {
        const EffectForce f = e.law->force(e.p.data(), ctx);
        sum.F += f.F;
        sum.dF_dx += f.dF_dx;
        sum.dF_dv += f.dF_dv;
        sum.dF_dt += f.dF_dt;
    }
    return sum;
}

// Each term of Eq. (1) at (t, x, v), with the drive's phi, omega, alpha and input u there [N]; signs as they
// act on the cart: resistance, spring_magnet and impact oppose it.
struct RigForces {
    double resistance = 0, spring_magnet = 0, impact = 0, unbalance = 0, input = 0, effects = 0;
    // The cart's acceleration times m, summed in the integrator's order (its results are reproduced bit for bit).
    double net() const { return ((((-resistance - spring_magnet) + unbalance) + input) - impact) + effects; }
};
// `contact`: a compliant bumper's force is on (the simulator's free flight against a compliant law). The
// unbalance and the input are added only where the model has them (an input-driven model has no unbalance).
inline RigForces rig_forces(const Params& p, double t, double x, double v, double phi, double omega, double alpha, double u,
                            bool contact) {
    RigForces f;
    f.resistance = resistance(p, v).F;
    f.spring_magnet = spring_magnet(p, x).F;
    if (p.m0e != 0.0) f.unbalance = unbalance_force(p, phi, omega);
    if (p.input_gain != 0.0) f.input = p.input_gain * u;
    if (contact) f.impact = p.impact->contact(p.ip.data(), x - p.xI, v).F;
    if (!p.effects.empty()) f.effects = effects_at(p, {t, x, v, phi, omega, alpha, p.m0e, p.xI}).F;
    return f;
}
inline RigForces rig_forces(const Params& p, const Drive& d, double t, double x, double v, bool contact) {
    const Drive::At a = d.at(t);
    return rig_forces(p, t, x, v, a.phi, a.omega, a.alpha, p.input_gain != 0.0 ? d.input(t) : 0.0, contact);
}

// y' = (v, F / m).
inline Vec2 rig_rhs(const Params& p, const Drive& d, double t, const Vec2& y, bool contact) {
    return {y[1], rig_forces(p, d, t, y[0], y[1], contact).net() / p.m};
}

// How the derivative of a compliant contact's force in h' is taken: the law's own bounded secant slope (what
// the stiff integrator wants, MODEL.md) or the true one (what a tangent needs): the law's, else by central
// differences.
enum class ContactSlope { Secant, Exact };

// The true dF/dh' of a compliant contact c = contact(h, hdot): the law's, else by central differences.
inline double contact_true_slope(const Params& p, const ContactForce& c, double h, double hdot) {
    if (std::isfinite(c.dF_dhdot_true)) return c.dF_dhdot_true;
    const double dv = 1e-6 * std::abs(hdot) + 1e-12;
    return (p.impact->contact(p.ip.data(), h, hdot + dv).F - p.impact->contact(p.ip.data(), h, hdot - dv).F) / (2.0 * dv);
}

// dy'/dy in J and, if asked, dy'/dt in *dfdt (the unbalance's and the input's time derivatives, the effects'):
// a tangent needs only J, and skips the drive's derivatives.
inline void rig_jacobian(const Params& p, const Drive& d, double t, const Vec2& y, bool contact, ContactSlope slope, Mat2& J,
                         Vec2* dfdt = nullptr) {
    // The drive's state enters only the time derivative and the effects: a tangent without effects skips it.
    const bool need_drive = dfdt || !p.effects.empty();
    const Drive::At a = need_drive ? d.at(t) : Drive::At{0.0, 0.0, 0.0};
    const double w = a.omega, phi = a.phi, al = a.alpha;
    double dFdx = -spring_magnet(p, y[0]).dF, dFdv = -resistance(p, y[1]).dF;
    double dFdt = dfdt ? unbalance_force_rate(p, phi, w, al) + p.input_gain * d.input_rate(t) : 0.0;
    if (contact) {
        const double h = y[0] - p.xI;
        const ContactForce c = p.impact->contact(p.ip.data(), h, y[1]);
        dFdx -= c.dF_dh;
        if (slope == ContactSlope::Secant || h <= 0.0) {
            dFdv -= c.dF_dhdot;
        } else {
            dFdv -= contact_true_slope(p, c, h, y[1]);
        }
    }
    if (!p.effects.empty()) {
        const EffectForce e = effects_at(p, {t, y[0], y[1], phi, w, al, p.m0e, p.xI});
        dFdx += e.dF_dx;
        dFdv += e.dF_dv;
        dFdt += e.dF_dt;
    }
    J << 0.0, 1.0, dFdx / p.m, dFdv / p.m;
    if (dfdt) *dfdt << 0.0, dFdt / p.m;
}

}  // namespace impactlab
