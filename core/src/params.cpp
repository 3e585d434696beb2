#include "impactlab/params.hpp"

#include "impactlab/drive.hpp"
#include "impactlab/forces.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

namespace impactlab {

// Table 1 of the paper (stiffness versions), SI units.
const std::vector<StiffnessSet>& stiffness_sets() {
    static const std::vector<StiffnessSet> table{
        {"A1", StiffnessKind::Rig, "odd rational magnetic force of degree 1 (Table 1)", 0.025152, 1115.2, 12.373, 1.2267,
         {-1763.5, 0.0, 0.0, 0.0}, {4907.6, 0.0, 0.0, 0.0}},
        {"A3", StiffnessKind::Rig, "odd rational magnetic force of degree 3 (Table 1)", 0.02476, 1149.9, 13.324, 1.1002,
         {-1982.3, -4.1578e6, 0.0, 0.0}, {10578.0, -0.044258, 0.0, 0.0}},
    };
    return table;
}

// m y'' + d y' + k y + k3 y^3 = gain u in a record's units: m = 1, no dry friction, no magnets' denominator.
const StiffnessSet& duffing_stiffness() {
    static const StiffnessSet row{"duffing", StiffnessKind::DataUnits, "plain Duffing law in the data's own units",
                                  0.0, 1.0, 0.0, 0.0, {0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
    return row;
}

const StiffnessSet* find_stiffness(const std::string& id) {
    for (const auto& s : stiffness_sets())
        if (id == s.id) return &s;
    if (id == duffing_stiffness().id) return &duffing_stiffness();
    return nullptr;
}

StiffnessKind stiffness_kind(const Params& p) {
    const StiffnessSet* s = find_stiffness(p.stiffness_id);
    return s ? s->kind : StiffnessKind::Rig;
}
const ImpactModel* find_impact(const std::string& id) {
    for (const auto& m : impact_models())
        if (id == m.id) return &m;
    return nullptr;
}
const EffectLaw* find_effect(const std::string& id) {
    for (const auto& e : effect_laws())
        if (id == e.id) return &e;
    return nullptr;
}

Params make_version(const std::string& name) {
    // Longest stiffness id that prefixes the name, the rest is the impact id ("A1C1" = A1 + C1).
    for (const auto& s : stiffness_sets()) {
        const std::size_t n = std::strlen(s.id);
        if (name.compare(0, n, s.id) != 0) continue;
        const ImpactModel* im = find_impact(name.substr(n));
        if (!im) continue;
        Params p;
        p.name = name;
        p.stiffness_id = s.id;
        p.m0e = s.m0e;
        p.k = s.k;
        p.c = s.c;
        p.T = s.T;
        p.a = s.a;
        p.b = s.b;
        p.impact = im;
        p.ip = im->defaults;
        return p;
    }
    std::ostringstream msg;
    msg << "unknown model version '" << name << "' (known: ";
    const auto names = version_names();
    for (std::size_t i = 0; i < names.size(); ++i) msg << (i ? ", " : "") << names[i];
    msg << ", or a .json parameter file)";
    throw ParamError(msg.str());
}

std::vector<std::string> version_names() {
    std::vector<std::string> out{"A1C", "A1C1", "A3C", "A1G", "A1H"};   // the paper's five first
    for (const auto& s : stiffness_sets())
        for (const auto& m : impact_models()) {
            std::string n = std::string(s.id) + m.id;
            bool seen = false;
            for (const auto& o : out) seen |= (o == n);
            if (!seen) out.push_back(n);
        }
    return out;
}

namespace {
[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& what, double v) {
    std::ostringstream msg;
    msg << source << ": key '" << key << "': " << what << ", got " << v;
    throw ParamError(msg.str());
}
void finite(const std::string& src, const std::string& key, double v) {
    if (!std::isfinite(v)) fail(src, key, "must be a finite number", v);
}
}  // namespace

const std::vector<ParamRange>& param_ranges() {
    // Wide enough for every rig and every data-unit Duffing fit seen; narrow enough that a slip of units or
    // a typo (m = 1e-20, eps = 1e-300, b = 1e308) is refused instead of stalling the integrator.
    static const std::vector<ParamRange> table{
        {"m", 1e-3, 1e4, "kg", "a cart between a gram and ten tonnes"},
        {"m0e", 0.0, 10.0, "kg m", "unbalance"},
        {"k", -1e9, 1e9, "N/m", "spring stiffness"},
        {"c", 0.0, 1e6, "N s/m", "viscous resistance"},
        {"T", 0.0, 1e5, "N", "dry rolling resistance"},
        {"eps", 1e-9, 1e-2, "m/s", "friction smoothing speed; below 1e-9 m/s friction is a step no integrator resolves"},
        {"xI", -kRailHalfTravel, kRailHalfTravel, "m", "bumper within the rail's travel"},
        {"input_gain", -1e9, 1e9, "N per unit of u", "input gain"},
        {"impact.kI", 1e-3, 1e14, "N/m^n1", "contact stiffness"},
        {"impact.b", 0.0, 1e4, "(s/m)^n3", "Hunt-Crossley damping factor"},
        {"impact.n1", 1.0, 3.0, "-", "elastic exponent (1: linear, 1.5: Hertz)"},
        {"impact.n2", 1.0, 3.0, "-", "damping's penetration exponent (below 1 the damping jumps at contact)"},
        {"impact.n3", 0.0, 2.0, "-", "damping's velocity exponent"},
        {"impact.kappa0", 0.0, 1.0, "-", "restitution coefficient"},
        {"impact.kappa1", 0.0, 1.0, "-", "restitution coefficient"},
        {"impact.a_kappa", 0.0, 1e3, "s/m", "restitution's speed scale"},
        {"impact.Ti0", 0.0, 1.0, "s", "impact duration"},
        {"impact.Ti1", 0.0, 1.0, "s", "impact duration"},
        {"impact.a_T", 0.0, 1e3, "s/m", "impact duration's speed scale"},
    };
    return table;
}

namespace {
void in_range(const std::string& src, const std::string& key, double v) {
    finite(src, key, v);
    for (const auto& r : param_ranges()) {
        if (key != r.key) continue;
        if (v < r.lo || v > r.hi) {
            std::ostringstream what;
            what << "must lie in [" << r.lo << ", " << r.hi << "] " << r.unit << " (" << r.why << ")";
            fail(src, key, what.str(), v);
        }
        return;
    }
}

// A law's force sampled over the rail, speeds and forcing a rig can reach: finite, and below kMaxLawForce.
// A model in its record's units (x_extent > 0) is sampled over its own extent, speeds scaled alike, and its
// forces need only be finite: a ceiling in newtons means nothing in strain or volts.
template <class ForceAt>
void bounded_force(const std::string& src, const std::string& key, ForceAt force_at, double x_extent = 0.0) {
    static constexpr double speeds[] = {-10.0, -1.0, -0.1, -1e-3, 0.0, 1e-3, 0.1, 1.0, 10.0};
    const double X = x_extent > 0 ? x_extent : kRailHalfTravel, scale = X / kRailHalfTravel;
    const double ceiling = x_extent > 0 ? std::numeric_limits<double>::max() : kMaxLawForce;
    for (int i = 0; i <= 40; ++i) {
        const double x = -X + X / 20.0 * i;
        for (const double v0 : speeds)
            for (int j = 0; j < 8; ++j) {
                const double v = v0 * scale;
                const double phi = kTwoPi * j / 8;
                for (const double omega : {0.0, 10.0, 100.0, 1000.0}) {
                    const double F = force_at(x, v, phi, omega);
                    if (!(std::abs(F) <= ceiling)) {
                        std::ostringstream what;
                        what << "gives a force of " << F << " N at x = " << x << " m, v = " << v << " m/s, phi = " << phi
                             << ", omega = " << omega << " rad/s; no law on the rig exceeds " << kMaxLawForce
                             << " N (a unit slip?)";
                        throw ParamError(src + ": key '" + key + "': " + what.str());
                    }
                }
            }
    }
}
}  // namespace

void validate(const Params& p, const std::string& src) {
    const std::pair<const char*, double> base[] = {{"m", p.m}, {"m0e", p.m0e}, {"c", p.c},   {"T", p.T},
                                                   {"eps", p.eps}, {"k", p.k},   {"xI", p.xI}, {"input_gain", p.input_gain}};
    for (const auto& [key, v] : base) in_range(src, key, v);
    if (!(p.x_extent >= 0.0) || !std::isfinite(p.x_extent)) fail(src, "x_extent", "must be >= 0 (0: the rail)", p.x_extent);
    for (int i = 0; i < 4; ++i) finite(src, "a[" + std::to_string(i) + "]", p.a[i]);
    for (int i = 0; i < 4; ++i) finite(src, "b[" + std::to_string(i) + "]", p.b[i]);
    // The denominator of Eq. (3) must not vanish on the rail (|x| <= 0.1 m): sample it.
    for (int i = 0; i <= 1000; ++i) {
        const double x = -kRailHalfTravel + 2e-4 * i, x2 = x * x;
        const double den = 1.0 + x2 * (p.b[0] + x2 * (p.b[1] + x2 * (p.b[2] + x2 * p.b[3])));
        if (!(den > 0)) fail(src, "b", "makes the denominator of F_SA vanish on |x| <= 0.1 m at x = " +
                                          std::to_string(x), den);
        // Its square enters the slope the integrator needs: an overflow there is a NaN slope, a stalled run.
        if (!std::isfinite(den * den))
            fail(src, "b", "makes the denominator of F_SA overflow on |x| <= 0.1 m at x = " + std::to_string(x), den);
    }
    bounded_force(src, "a", [&](double x, double, double, double) { return spring_magnet(p, x).F; }, p.x_extent);
    for (int i = 0; i <= 1000; ++i) {
        const double X = p.x_extent > 0 ? p.x_extent : kRailHalfTravel;
        const double x = -X + X / 500.0 * i, slope = spring_magnet(p, x).dF;
        if (!std::isfinite(slope))
            fail(src, "a", "makes the slope of F_SA overflow on |x| <= " + std::to_string(X) + " at x = " + std::to_string(x), slope);
    }
    if (!p.impact) throw ParamError(src + ": no impact model");
    const std::string ik = std::string("impact.");
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i) in_range(src, ik + p.impact->names[i], p.ip[i]);
    if (p.impact->kind == ImpactKind::Compliant) {
        // Penetrations up to 0.1 mm at the rig's speeds: the bumper's force stays a force a rail can take.
        bounded_force(src, "impact", [&](double x, double v, double, double) {
            return p.impact->contact(p.ip.data(), 1e-4 * (x + kRailHalfTravel) / (2 * kRailHalfTravel), v).F;
        });
    }
    for (const auto& e : p.effects) {
        if (!e.law) throw ParamError(src + ": an effect without a law");
        const std::string ek = std::string("effects.") + e.law->id;
        for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i) finite(src, ek + "." + e.law->names[i], e.p[i]);
        if (e.law->kind != EffectKind::Force) continue;
        bounded_force(
            src, ek, [&](double x, double v, double phi, double omega) { return e.law->force(e.p.data(), {0.0, x, v, phi, omega, 0.0, p.m0e, p.xI}).F; },
            p.x_extent);
    }
}

void validate_over(const Params& p, double t_begin, double t_end, const std::string& src) {
    // A law that changes with time (a drift) is checked where the run takes it, not only at t = 0: at both
    // ends and three times between (the drifts are linear in t, their largest force is at an end).
    for (const auto& e : p.effects) {
        if (!e.law || e.law->kind != EffectKind::Force) continue;
        const std::string ek = std::string("effects.") + e.law->id;
        for (int k = 0; k <= 4; ++k) {
            const double t = t_begin + (t_end - t_begin) * k / 4;
            try {
                bounded_force(src, ek, [&](double x, double v, double phi, double omega) {
                    return e.law->force(e.p.data(), {t, x, v, phi, omega, 0.0, p.m0e, p.xI}).F;
                });
            } catch (const ParamError& err) {
                std::ostringstream when;
                when << err.what() << " (at t = " << t << " s of the run's " << t_begin << " .. " << t_end << " s)";
                throw ParamError(when.str());
            }
        }
    }
}

double impact_param(const Params& p, const std::string& key) {
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i)
        if (key == p.impact->names[i]) return p.ip[i];
    throw ParamError("impact model '" + std::string(p.impact->id) + "' has no parameter '" + key + "'");
}

void set_impact_param(Params& p, const std::string& key, double value) {
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i)
        if (key == p.impact->names[i]) {
            p.ip[i] = value;
            return;
        }
    throw ParamError("impact model '" + std::string(p.impact->id) + "' has no parameter '" + key + "'");
}

EffectInstance& add_effect(Params& p, const std::string& id) {
    const EffectLaw* law = find_effect(id);
    if (!law) {
        std::string known;
        for (const auto& e : effect_laws()) known += (known.empty() ? "" : ", ") + std::string(e.id);
        throw ParamError("unknown effect '" + id + "' (known: " + known + ")");
    }
    p.effects.push_back({law, law->defaults});
    return p.effects.back();
}

}  // namespace impactlab
