// The effects that change the base model rather than add a force: each a registry row like a force law's
// (core/src/effects), with its metadata, how it edits the model, how it is screened (if the screening looks
// for it at all) and its sentence. The impact-law stage of the fit finds the bumper and impact-law ones from
// the impacts themselves.
#include <string>

#include "effects/law_helpers.hpp"
#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

using effects::fmt;
using effects::pm;
using Values = std::vector<std::pair<std::string, double>>;

double get(const Values& v, const std::string& k) {
    for (const auto& [n, x] : v)
        if (n == k) return x;
    return 0.0;
}

// A compliant bumper has no T_imp or kappa law: switch to the rigid law (H's values) before setting these.
void make_rigid(Model& m) {
    if (m.p.rigid()) return;
    const ImpactModel* h = find_impact("H");
    m.p.impact = h;
    m.p.ip = h->defaults;
}

// The three values of an impact law (p0 at low speed, p1 at high, decay a) into ip[first..first+2]; a low-speed
// value given alone means a constant law.
void set_impact_law(Model& m, std::size_t first, std::vector<double>& v, const std::vector<bool>& given) {
    make_rigid(m);
    if (given[0] && !given[1]) v[1] = v[0];
    if (given[0] && !given[2]) v[2] = 0.0;
    for (std::size_t k = 0; k < 3; ++k) m.p.ip[first + k] = v[k];
}

BaseEffect bumper_offset() {
    BaseEffect e;
    e.info = {"bumper_offset", "the bumper stands dx off the model's xI (moves xI)", {"dx"}, {"m"}, {0.0}, false, true};
    e.needs_bumper = true;
    e.impacts = ImpactTrait::Level;
    e.apply = [](Model& m, std::vector<double>& v, const std::vector<bool>&) { m.p.xI += v[0]; };
    e.describe = [](const Model& b, const Values& v, const Values& s) {
        const double dx = get(v, "dx");
        return "the bumper stands " + pm(std::abs(dx), get(s, "dx"), 1e3) + " mm " + (dx > 0 ? "to the right (+x)" : "to the left (-x)") +
               " of the model's xI = " + fmt("%.3g", b.p.xI * 1e3) + " mm: the flat tops of the impacts sit there";
    };
    return e;
}

BaseEffect impact_duration() {
    BaseEffect e;
    e.info = {"impact_duration", "each impact holds the cart at the bumper for T_imp(v-) (sets the impact law's Ti0, Ti1, a_T)",
              {"Ti0", "Ti1", "a_T"}, {"s", "s", "s/m"}, {6.2193e-3, 4.0689e-3, 2.1733}, false, true};
    e.needs_bumper = true;
    e.impacts = ImpactTrait::Dwell;
    e.apply = [](Model& m, std::vector<double>& v, const std::vector<bool>& given) { set_impact_law(m, 3, v, given); };
    e.describe = [](const Model& b, const Values& v, const Values& s) -> std::string {
        auto val = [&](const char* k) { return get(v, k); };
        auto sig = [&](const char* k) { return get(s, k); };
        const std::string model_T = fmt("%.3g", b.p.rigid() ? b.p.ip[3] * 1e3 : 0.0);
        if (val("a_T") == 0.0 || std::abs(val("Ti0") - val("Ti1")) < 1e-12)
            return "each impact holds the cart at the bumper for " + pm(val("Ti0"), sig("Ti0"), 1e3) +
                   " ms whatever its speed, where the model's law gives " + model_T + " ms: a finite impact duration";
        return "each impact holds the cart at the bumper for a finite time, T_imp = " + pm(val("Ti0"), sig("Ti0"), 1e3) +
               " ms at low speed falling to " + pm(val("Ti1"), sig("Ti1"), 1e3) + " ms at high speed (the model's law gives " +
               model_T + " ms at low speed): a finite impact duration";
    };
    return e;
}

BaseEffect restitution() {
    BaseEffect e;
    e.info = {"restitution", "a velocity-dependent restitution kappa(v-) (sets the impact law's kappa0, kappa1, a_kappa)",
              {"kappa0", "kappa1", "a_kappa"}, {"-", "-", "s/m"}, {0.6150, 0.1350, 0.6594}, false, true};
    e.needs_bumper = true;
    e.impacts = ImpactTrait::Rebound;
    e.apply = [](Model& m, std::vector<double>& v, const std::vector<bool>& given) { set_impact_law(m, 0, v, given); };
    e.describe = [](const Model& b, const Values& v, const Values& s) -> std::string {
        auto val = [&](const char* k) { return get(v, k); };
        auto sig = [&](const char* k) { return get(s, k); };
        const std::string model_k = fmt("%.3g", b.p.rigid() ? b.p.ip[0] : 0.0) + " at low and " +
                                    fmt("%.3g", b.p.rigid() ? b.p.ip[1] : 0.0) + " at high speed";
        if (val("a_kappa") == 0.0 || std::abs(val("kappa0") - val("kappa1")) < 1e-12)
            return "the bumper returns " + pm(val("kappa0"), sig("kappa0")) + " of the impact speed whatever the speed (the model's law: " +
                   model_k + "): a different restitution";
        return "the restitution coefficient is " + pm(val("kappa0"), sig("kappa0")) + " at low and " + pm(val("kappa1"), sig("kappa1")) +
               " at high impact speed (the model's law: " + model_k + ")";
    };
    return e;
}

// A force law cannot take the acceleration, so a wrong mass is a base parameter moved: the residual is then
// dm x'', and the screening's column for it is the acceleration's (the m x'' term).
BaseEffect cart_mass() {
    BaseEffect e;
    e.info = {"cart_mass", "the cart's mass is m + dm instead of m (moves m)", {"dm"}, {"kg"}, {0.0}, false, true};
    e.apply = [](Model& m, std::vector<double>& v, const std::vector<bool>&) {
        if (!(m.p.m + v[0] > 0)) throw ParamError("effect 'cart_mass': dm = " + std::to_string(v[0]) + " leaves no mass");
        m.p.m += v[0];
    };
    e.describe = [](const Model& b, const Values& v, const Values& s) {
        const double dm = get(v, "dm");
        return "the cart's mass is " + pm(b.p.m + dm, get(s, "dm")) + " kg, " + fmt("%+.3g", 100.0 * dm / b.p.m) + " % off the model's " +
               fmt("%.6g", b.p.m) + " kg: the residual follows the acceleration";
    };
    // It competes with the force laws in the screening and the validation like any other. Not with fitted
    // base parameters (m, or m0e or the input gain, which rescale the whole equation with it), nor for a plain
    // Duffing model (m = 1 is its unit of force).
    e.candidate = [](const Model& m, const FitOptions& o, Candidate& c) {
        if (o.fit_baseline || stiffness_kind(m.p) == StiffnessKind::DataUnits || !(m.p.m > 0)) return false;
        c.base = "m";
        c.param = "dm";
        c.free = {0};
        c.step = {1e-4 * m.p.m};
        c.linear = {0};
        c.lo = -0.5 * m.p.m;   // the mass found stays within [0.5, 2] times the model's
        c.hi = m.p.m;
        return true;
    };
    return e;
}

}  // namespace

const std::vector<BaseEffect>& base_effects() {
    static const std::vector<BaseEffect> rows{bumper_offset(), impact_duration(), restitution(), cart_mass()};
    return rows;
}

const BaseEffect* find_base_effect(const std::string& id) {
    for (const auto& e : base_effects())
        if (e.info.id == id) return &e;
    return nullptr;
}

ImpactTrait impact_trait(const std::string& id) {
    const BaseEffect* b = find_base_effect(id);
    return b ? b->impacts : ImpactTrait::None;
}

}  // namespace impactlab::identify::detail
