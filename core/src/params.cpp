#include "impactlab/params.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

namespace impactlab {

// Table 1 of the paper (stiffness versions), SI units.
const std::vector<StiffnessSet>& stiffness_sets() {
    static const std::vector<StiffnessSet> table{
        {"A1", "odd rational magnetic force of degree 1 (Table 1)", 0.025152, 1115.2, 12.373, 1.2267,
         {-1763.5, 0.0, 0.0, 0.0}, {4907.6, 0.0, 0.0, 0.0}},
        {"A3", "odd rational magnetic force of degree 3 (Table 1)", 0.02476, 1149.9, 13.324, 1.1002,
         {-1982.3, -4.1578e6, 0.0, 0.0}, {10578.0, -0.044258, 0.0, 0.0}},
    };
    return table;
}

const StiffnessSet* find_stiffness(const std::string& id) {
    for (const auto& s : stiffness_sets())
        if (id == s.id) return &s;
    return nullptr;
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
void positive(const std::string& src, const std::string& key, double v) {
    finite(src, key, v);
    if (!(v > 0)) fail(src, key, "must be positive", v);
}
void nonnegative(const std::string& src, const std::string& key, double v) {
    finite(src, key, v);
    if (v < 0) fail(src, key, "must not be negative", v);
}
}  // namespace

void validate(const Params& p, const std::string& src) {
    positive(src, "m", p.m);
    nonnegative(src, "m0e", p.m0e);
    finite(src, "k", p.k);
    nonnegative(src, "c", p.c);
    nonnegative(src, "T", p.T);
    positive(src, "eps", p.eps);
    for (int i = 0; i < 4; ++i) finite(src, "a[" + std::to_string(i) + "]", p.a[i]);
    for (int i = 0; i < 4; ++i) finite(src, "b[" + std::to_string(i) + "]", p.b[i]);
    finite(src, "xI", p.xI);
    finite(src, "input_gain", p.input_gain);
    if (std::abs(p.xI) > 0.1) fail(src, "xI", "must lie within +/-0.1 m of the springs' zero", p.xI);
    // The denominator of Eq. (3) must not vanish on the rail (|x| <= 0.1 m): sample it.
    for (int i = 0; i <= 1000; ++i) {
        const double x = -0.1 + 2e-4 * i, x2 = x * x;
        const double den = 1.0 + x2 * (p.b[0] + x2 * (p.b[1] + x2 * (p.b[2] + x2 * p.b[3])));
        if (!(den > 0)) fail(src, "b", "makes the denominator of F_SA vanish on |x| <= 0.1 m at x = " +
                                          std::to_string(x), den);
    }
    if (!p.impact) throw ParamError(src + ": no impact model");
    const std::string ik = std::string("impact.");
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i) finite(src, ik + p.impact->names[i], p.ip[i]);
    if (p.impact->kind == ImpactKind::Compliant) {
        positive(src, ik + "kI", p.ip[0]);
        nonnegative(src, ik + "b", p.ip[1]);
        for (int i = 2; i < 5; ++i) positive(src, ik + p.impact->names[i], p.ip[i]);
        if (p.ip[2] < 1.0) fail(src, ik + "n1", "must be at least 1 (a contact force vanishing at h = 0)", p.ip[2]);
    } else if (p.impact->kind == ImpactKind::Rigid) {
        for (int i = 0; i < 2; ++i) {
            nonnegative(src, ik + p.impact->names[i], p.ip[i]);
            if (p.ip[i] > 1.0) fail(src, ik + p.impact->names[i], "a restitution coefficient must lie in [0, 1]", p.ip[i]);
        }
        for (int i = 2; i < 6; ++i) nonnegative(src, ik + p.impact->names[i], p.ip[i]);
        if (p.ip[3] > 1.0 || p.ip[4] > 1.0) fail(src, ik + "Ti0", "impact durations are in seconds; above 1 s", std::max(p.ip[3], p.ip[4]));
    }
    for (const auto& e : p.effects) {
        if (!e.law) throw ParamError(src + ": an effect without a law");
        for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i)
            finite(src, std::string("effects.") + e.law->id + "." + e.law->names[i], e.p[i]);
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
