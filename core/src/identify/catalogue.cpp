// The effect catalogue of impactlab fit: which library effects exist, how each is screened and fitted, and
// the plain sentence that reports it. Force laws live in core/src/effects (one file each); this file only
// says how to look for them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "identify/internal.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab::identify {

double Model::sensor_gain() const {
    for (const auto& e : p.effects)
        if (std::strcmp(e.law->id, "sensor_gain") == 0) return e.p[0];
    return 1.0;
}
double Model::sensor_offset() const {
    for (const auto& e : p.effects)
        if (std::strcmp(e.law->id, "sensor_offset") == 0) return e.p[0];
    return 0.0;
}

Model resolve_fit_model(const std::string& name, Forcing forcing) {
    Model m;
    m.forcing = forcing;
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower == "duffing") {
        // m y'' + d y' + k y + k3 y^3 = gain u: a Params with m = 1, no dry friction, no magnets' denominator,
        // and no bumper. Starting values are placeholders: fit mode estimates d, k, k3 and the gain.
        m.p = make_version("A1none");
        m.p.name = "duffing";
        m.p.stiffness_id = "duffing";
        m.p.m = 1.0;
        m.p.m0e = 0.0;
        m.p.k = 1.0;
        m.p.c = 0.0;
        m.p.T = 0.0;
        m.p.a = {0, 0, 0, 0};
        m.p.b = {0, 0, 0, 0};
        m.p.xI = 0.0;
        m.p.input_gain = 1.0;
        m.forcing = Forcing::Input;
        return m;
    }
    m.p = resolve_model(name);
    // A measured input drives the rig through a gain the fit estimates; a file may state its own.
    if (forcing == Forcing::Input && m.p.input_gain == 0.0) m.p.input_gain = 1.0;
    return m;
}

namespace {

std::vector<EffectInfo> build_catalogue() {
    std::vector<EffectInfo> out;
    for (const auto& law : effect_laws()) {
        EffectInfo e;
        e.id = law.id;
        e.meaning = law.meaning;
        for (std::size_t i = 0; i < kMaxLawParams && law.names[i]; ++i) {
            e.names.emplace_back(law.names[i]);
            e.units.emplace_back(law.units[i]);
            e.defaults.push_back(law.defaults[i]);
        }
        e.generic = e.id.rfind("unexplained_", 0) == 0;
        out.push_back(std::move(e));
    }
    out.push_back({"bumper_offset", "the bumper stands dx off the model's xI (moves xI)", {"dx"}, {"m"}, {0.0}, false, true});
    out.push_back({"impact_duration", "each impact holds the cart at the bumper for T_imp(v-) (sets the impact law's Ti0, Ti1, a_T)",
                   {"Ti0", "Ti1", "a_T"}, {"s", "s", "s/m"}, {6.2193e-3, 4.0689e-3, 2.1733}, false, true});
    out.push_back({"restitution", "a velocity-dependent restitution kappa(v-) (sets the impact law's kappa0, kappa1, a_kappa)",
                   {"kappa0", "kappa1", "a_kappa"}, {"-", "-", "s/m"}, {0.6150, 0.1350, 0.6594}, false, true});
    return out;
}

}  // namespace

const std::vector<EffectInfo>& effect_catalogue() {
    static const std::vector<EffectInfo> cat = build_catalogue();
    return cat;
}

const EffectInfo* find_catalogue_effect(const std::string& id) {
    for (const auto& e : effect_catalogue())
        if (e.id == id) return &e;
    return nullptr;
}

void apply_effect(Model& m, const std::string& id, const std::vector<std::pair<std::string, double>>& values) {
    const EffectInfo* info = find_catalogue_effect(id);
    if (!info) {
        std::string known;
        for (const auto& e : effect_catalogue()) known += (known.empty() ? "" : ", ") + e.id;
        throw ParamError("unknown effect '" + id + "' (known: " + known + ")");
    }
    std::vector<double> v = info->defaults;
    std::vector<bool> given(v.size(), false);
    for (const auto& [name, value] : values) {
        std::size_t k = 0;
        if (!name.empty()) {
            k = static_cast<std::size_t>(std::find(info->names.begin(), info->names.end(), name) - info->names.begin());
            if (k >= info->names.size()) {
                std::string list;
                for (const auto& n : info->names) list += (list.empty() ? "" : ", ") + n;
                throw ParamError("effect '" + id + "' has no parameter '" + name + "' (it has: " + list + ")");
            }
        }
        if (!std::isfinite(value)) throw ParamError("effect '" + id + "': parameter values must be finite numbers");
        v[k] = value;
        given[k] = true;
    }
    if (!info->changes_base) {
        EffectInstance* inst = nullptr;
        for (auto& e : m.p.effects)
            if (id == e.law->id) inst = &e;
        if (!inst) {   // a new instance: defaults, and the model's own magnetic law for magnet_offset
            inst = &add_effect(m.p, id);
            if (id == "magnet_offset") inst->p = {0.0, m.p.a[0], m.p.a[1], m.p.b[0], m.p.b[1], 0, 0, 0};
        }
        for (std::size_t k = 0; k < v.size(); ++k)
            if (given[k]) inst->p[k] = v[k];
        return;
    }
    if (!m.bumper()) throw ParamError("effect '" + id + "' needs a model with a bumper");
    if (id == "bumper_offset") {
        m.p.xI += v[0];
        return;
    }
    if (!m.p.rigid()) {
        // A compliant bumper has no T_imp or kappa law: switch to the rigid law (H's values) and set these.
        const ImpactModel* h = find_impact("H");
        m.p.impact = h;
        m.p.ip = h->defaults;
    }
    if (id == "impact_duration") {
        if (given[0] && !given[1]) v[1] = v[0];
        if (given[0] && !given[2]) v[2] = 0.0;
        m.p.ip[3] = v[0];
        m.p.ip[4] = v[1];
        m.p.ip[5] = v[2];
    } else {   // restitution
        if (given[0] && !given[1]) v[1] = v[0];
        if (given[0] && !given[2]) v[2] = 0.0;
        m.p.ip[0] = v[0];
        m.p.ip[1] = v[1];
        m.p.ip[2] = v[2];
    }
}

}  // namespace impactlab::identify

namespace impactlab::identify::detail {

std::vector<Candidate> library_candidates(const Model& m, const Prep& pr, const FitOptions& o) {
    std::vector<Candidate> out;
    const bool phi = pr.phi_forced;
    double alpha_rms = 0;
    for (double a : pr.alpha) alpha_rms += a * a;
    alpha_rms = std::sqrt(alpha_rms / static_cast<double>(std::max<std::size_t>(1, pr.alpha.size())));
    auto allowed = [&](const std::string& id) {
        if (std::find(o.exclude.begin(), o.exclude.end(), id) != o.exclude.end()) return false;
        if (!o.only.empty() && std::find(o.only.begin(), o.only.end(), id) == o.only.end()) return false;
        return true;
    };
    auto add = [&](const char* id, std::vector<int> free, std::vector<double> step, std::vector<int> linear,
                   std::vector<double> starts = {}) {
        if (!allowed(id)) return;
        Candidate c;
        c.id = id;
        c.law = find_effect(id);
        c.free = std::move(free);
        c.step = std::move(step);
        c.linear = std::move(linear);
        c.starts = std::move(starts);
        c.generic = c.id.rfind("unexplained_", 0) == 0;
        c.sensor = c.id.rfind("sensor_", 0) == 0;
        if (c.law) out.push_back(std::move(c));
    };
    // In fit mode the base parameters absorb these; in validate mode they say which base value is off.
    auto fitted = [&](const char* name) {
        if (!o.fit_baseline) return false;
        const auto names = o.fit_params.empty() ? default_fit_params(m) : o.fit_params;
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    const double vscale = 0.1, xscale = 0.01;
    add("constant_force", {0}, {1.0}, {0});
    add("quadratic_damping", {0}, {1.0}, {0});
    if (phi && alpha_rms > 1e-3) add("tangential_unbalance", {0}, {1.0}, {0});
    if (m.p.a[0] != 0.0 || m.p.a[1] != 0.0) add("magnet_offset", {0}, {1e-5}, {0});
    add("even_stiffness", {0}, {1.0}, {0});
    if (!fitted("k")) add("linear_stiffness", {0}, {1.0}, {0});
    if (!fitted("c")) add("viscous_damping", {0}, {1.0}, {0});
    if (!fitted("T") && m.p.T > 0) add("coulomb_friction", {0}, {1.0}, {0});
    // Extra friction (Fs > 0) below a speed vs the data can resolve: a reversal's timing is known to a fraction
    // of a millisecond, so speeds below a few mm/s are out of reach (a "negative Stribeck" there only
    // smooths the friction step and is not physics).
    add("stribeck_friction", {0, 1}, {1.0, 1e-3 * vscale}, {0}, {0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.05, 0.075, 0.1});
    if (!out.empty() && out.back().id == "stribeck_friction") out.back().positive = true;
    if (phi) add("phase_offset", {0}, {1e-4}, {0});
    if (phi && !fitted("m0e")) add("unbalance_scale", {0}, {1.0}, {0});
    if (!fitted("gain")) add("sensor_offset", {0}, {1e-3 * xscale}, {0});
    // A gain error rescales every term of the equation: with fitted base parameters it is not identifiable.
    if (!o.fit_baseline) add("sensor_gain", {0}, {1e-3}, {0});
    if (o.generic) {
        add("unexplained_x", {2, 3, 4, 5, 6, 7}, {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5});
        add("unexplained_v", {2, 3, 4, 5, 6, 7}, {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5});
        add("unexplained_x_signv", {2, 3, 4, 5, 6, 7}, {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5});
        if (phi) add("unexplained_phi", {0, 1, 2, 3, 4, 5}, {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5});
    }
    return out;
}

EffectInstance start_instance(const Candidate& c, const Model& m, const Prep& pr, double start) {
    EffectInstance e{c.law, c.law->defaults};
    const std::string& id = c.id;
    const MeasuredData& d = *pr.data;
    const double g = m.sensor_gain(), o = m.sensor_offset();
    if (id == "magnet_offset") {
        e.p = {0.0, m.p.a[0], m.p.a[1], m.p.b[0], m.p.b[1], 0, 0, 0};
    } else if (id == "sensor_gain") {
        e.p[0] = 1.0;
    } else if (id == "stribeck_friction") {
        e.p[0] = 0.0;
        e.p[1] = start;
    } else if (c.generic && id != "unexplained_phi") {
        std::vector<double> s;
        s.reserve(pr.rows.size());
        for (std::size_t r : pr.rows) s.push_back(id == "unexplained_v" ? pr.vs[r] / g : (d.x[r] - o) / g);
        e.p = {quantile(s, 0.005), quantile(s, 0.995), 0, 0, 0, 0, 0, 0};
        if (!(e.p[1] > e.p[0])) e.p[1] = e.p[0] + 1e-6;
    } else {
        e.p.fill(0.0);
    }
    return e;
}

std::vector<std::string> default_fit_params(const Model& m) {
    if (m.forcing == Forcing::Input) {
        std::vector<std::string> v{"c", "k", "gain"};
        if (!m.bumper()) v.insert(v.begin() + 2, "a3");
        else {
            if (m.p.T > 0) v.push_back("T");
            if (m.p.a[0] != 0) v.push_back("a1");
        }
        return v;
    }
    std::vector<std::string> v{"c", "T", "k", "a1", "b2", "m0e"};
    if (m.p.a[1] != 0) v.push_back("a3");
    if (m.p.b[1] != 0) v.push_back("b4");
    return v;
}

std::vector<BaseParam> base_params(Model& m, const std::vector<std::string>& names) {
    std::vector<BaseParam> out;
    for (const auto& n : names) {
        double* p = nullptr;
        if (n == "c") p = &m.p.c;
        else if (n == "T") p = &m.p.T;
        else if (n == "k") p = &m.p.k;
        else if (n == "a1") p = &m.p.a[0];
        else if (n == "a3") p = &m.p.a[1];
        else if (n == "a5") p = &m.p.a[2];
        else if (n == "b2") p = &m.p.b[0];
        else if (n == "b4") p = &m.p.b[1];
        else if (n == "m0e") p = &m.p.m0e;
        else if (n == "gain") p = &m.p.input_gain;
        else if (n == "m") p = &m.p.m;
        else if (n == "xI") p = &m.p.xI;
        if (!p) throw ParamError("--fit-params: unknown parameter '" + n + "' (known: c, T, k, a1, a3, a5, b2, b4, m0e, gain, m, xI)");
        out.push_back({n, p, std::max(1e-6 * std::abs(*p), 1e-9)});
    }
    return out;
}

namespace {
std::string fmt(const char* f, double a) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, a);
    return buf;
}
// "1.23 +/- 0.04" with the uncertainty's two significant digits deciding the decimals.
std::string pm(double v, double s, double scale = 1.0) {
    v *= scale;
    s *= scale;
    char buf[96];
    if (!(s > 0) || !std::isfinite(s)) {
        std::snprintf(buf, sizeof buf, "%.3g", v);
        return buf;
    }
    const int dec = std::clamp(1 - static_cast<int>(std::floor(std::log10(s))), 0, 12);
    std::snprintf(buf, sizeof buf, "%.*f +/- %.*f", dec, v, dec, s);
    return buf;
}
double get(const std::vector<std::pair<std::string, double>>& v, const std::string& k) {
    for (const auto& [n, x] : v)
        if (n == k) return x;
    return 0.0;
}
}  // namespace

std::string sentence(const std::string& id, const Model& b, const std::vector<std::pair<std::string, double>>& v,
                     const std::vector<std::pair<std::string, double>>& s, const SentenceContext& c) {
    auto val = [&](const char* k) { return get(v, k); };
    auto sig = [&](const char* k) { return get(s, k); };
    if (id == "constant_force" && !b.bumper())
        return "a constant force of " + pm(val("F0"), sig("F0")) +
               " (in the model's force units): an offset of the input or of the system's equilibrium";
    if (id == "even_stiffness" && !b.bumper())
        return "an even (quadratic) restoring term -k2 y^2 with k2 = " + pm(val("k2"), sig("k2")) +
               ": an asymmetric nonlinearity, the even-order distortion";
    if (id == "constant_force") {
        const double F = val("F0"), tilt = std::asin(std::min(1.0, std::abs(F) / (c.m * c.g_earth))) * 180.0 / kPi;
        return "a constant force of " + pm(F, sig("F0")) + " N along the rail (" + (F > 0 ? "towards +x" : "towards -x") +
               "): a tilt of about " + fmt("%.2g", tilt) + " degrees, or a pull on the cart";
    }
    if (id == "quadratic_damping") {
        const double cq = val("cq"), Fv = cq * c.v_typ * c.v_typ;
        return "a resistance growing with the square of the speed, cq = " + pm(cq, sig("cq")) + " N s^2/m^2: at the typical speed of " +
               fmt("%.2g", c.v_typ) + " m/s it adds " + fmt("%.2g", Fv) + " N to the viscous " + fmt("%.2g", b.p.c * c.v_typ) +
               " N (air or oil drag)";
    }
    if (id == "tangential_unbalance")
        return "the unbalance's tangential force -m0e phi'' cos(phi) at " + pm(val("scale"), sig("scale")) +
               " times its full size: the motor's speed changes push the cart";
    if (id == "magnet_offset") {
        const double d = val("d");
        return "the fixed magnet sits " + pm(std::abs(d), sig("d"), 1e3) + " mm " + (d > 0 ? "towards +x" : "towards -x") +
               " of x = 0 (misaligned magnets): the two wells are no longer mirror images";
    }
    if (id == "even_stiffness") {
        const double k2 = val("k2");
        return "an even stiffness term -k2 x^2 with k2 = " + pm(k2, sig("k2")) + " N/m^2: at |x| = " + fmt("%.3g", c.x_typ * 1e3) +
               " mm it adds " + fmt("%.2g", -k2 * c.x_typ * c.x_typ) + " N on both sides, so the wells differ (asymmetric magnets or springs)";
    }
    if (id == "linear_stiffness")
        return "the springs are " + pm(val("dk"), sig("dk")) + " N/m stiffer than the model's k = " + fmt("%.5g", b.p.k) + " N/m (" +
               fmt("%+.2g", 100 * val("dk") / (b.p.k != 0 ? b.p.k : 1)) + " %; negative: softer)";
    if (id == "viscous_damping")
        return "the viscous damping is " + pm(val("dc"), sig("dc")) + " N s/m more than the model's c = " + fmt("%.5g", b.p.c) +
               " N s/m (" + (b.p.c != 0 ? fmt("%+.2g", 100 * val("dc") / b.p.c) + " %" : std::string("new")) + "; negative: less)";
    if (id == "coulomb_friction")
        return "the dry rolling resistance is " + pm(val("dT"), sig("dT")) + " N more than the model's T = " + fmt("%.5g", b.p.T) +
               " N (" + (b.p.T != 0 ? fmt("%+.2g", 100 * val("dT") / b.p.T) + " %" : std::string("new")) + "; negative: less)";
    if (id == "stribeck_friction")
        return "extra friction of " + pm(val("Fs"), sig("Fs")) + " N at low speed that fades above about " +
               pm(std::abs(val("vs")), sig("vs")) + " m/s (a Stribeck effect: stiction in the bearings)";
    if (id == "phase_offset")
        return "the unbalance leads the measured angle by " + pm(val("delta"), sig("delta")) + " rad (" +
               fmt("%.2g", val("delta") * 180 / kPi) + " degrees): the encoder or optocoupler mark is off, or the angle lags";
    if (id == "unbalance_scale")
        return "the unbalance m0e is " + pm(val("s"), sig("s"), 100.0) + " % off the model's " + fmt("%.5g", b.p.m0e) +
               " kg m (a different mass or radius)";
    if (id == "sensor_offset")
        return "the position sensor reads " + pm(val("o"), sig("o"), 1e3) + " mm more than the true position (a zero offset of the Hall sensor or its tape)";
    if (id == "sensor_gain")
        return "the position sensor's gain is " + pm(val("g"), sig("g")) + " (it reads " + fmt("%+.2g", 100 * (val("g") - 1)) +
               " % of the travel too much): a calibration error";
    if (id == "bumper_offset") {
        const double dx = val("dx");
        return "the bumper stands " + pm(std::abs(dx), sig("dx"), 1e3) + " mm " + (dx > 0 ? "to the right (+x)" : "to the left (-x)") +
               " of the model's xI = " + fmt("%.3g", b.p.xI * 1e3) + " mm: the flat tops of the impacts sit there";
    }
    if (id == "impact_duration") {
        const std::string model_T = fmt("%.3g", b.p.rigid() ? b.p.ip[3] * 1e3 : 0.0);
        if (val("a_T") == 0.0 || std::abs(val("Ti0") - val("Ti1")) < 1e-12)
            return "each impact holds the cart at the bumper for " + pm(val("Ti0"), sig("Ti0"), 1e3) +
                   " ms whatever its speed, where the model's law gives " + model_T + " ms: a finite impact duration";
        return "each impact holds the cart at the bumper for a finite time, T_imp = " + pm(val("Ti0"), sig("Ti0"), 1e3) +
               " ms at low speed falling to " + pm(val("Ti1"), sig("Ti1"), 1e3) + " ms at high speed (the model's law gives " +
               model_T + " ms at low speed): a finite impact duration";
    }
    if (id == "restitution") {
        const std::string model_k = fmt("%.3g", b.p.rigid() ? b.p.ip[0] : 0.0) + " at low and " +
                                    fmt("%.3g", b.p.rigid() ? b.p.ip[1] : 0.0) + " at high speed";
        if (val("a_kappa") == 0.0 || std::abs(val("kappa0") - val("kappa1")) < 1e-12)
            return "the bumper returns " + pm(val("kappa0"), sig("kappa0")) + " of the impact speed whatever the speed (the model's law: " +
                   model_k + "): a different restitution";
        return "the restitution coefficient is " + pm(val("kappa0"), sig("kappa0")) + " at low and " + pm(val("kappa1"), sig("kappa1")) +
               " at high impact speed (the model's law: " + model_k + ")";
    }
    if (id.rfind("unexplained_", 0) == 0) {
        const std::string var = id == "unexplained_x" ? "the position x"
                                : id == "unexplained_v" ? "the velocity v"
                                : id == "unexplained_phi" ? "the unbalance angle phi"
                                                          : "the position x, with the sign of v";
        // Where the fitted force is largest.
        const EffectLaw* law = find_effect(id);
        std::array<double, kMaxLawParams> p{};
        for (std::size_t k = 0; k < kMaxLawParams && law && law->names[k]; ++k) p[k] = val(law->names[k]);
        const bool periodic = id == "unexplained_phi";
        const double lo = periodic ? 0.0 : p[0], hi = periodic ? 2 * kPi : p[1];
        double best = 0, at = lo;
        for (int k = 0; k <= 200 && law; ++k) {
            const double q = lo + (hi - lo) * k / 200.0;
            ForceContext ctx{0.0, 0.0, 1.0, 0.0, 0.0, 0.0, b.p.m0e, b.p.xI};
            if (id == "unexplained_v") ctx.v = q;
            else if (periodic) ctx.phi = q;
            else ctx.x = q;
            const double F = law->force(p.data(), ctx).F;
            if (std::abs(F) > std::abs(best)) {
                best = F;
                at = q;
            }
        }
        const std::string where = id == "unexplained_v" ? "v = " + fmt("%.3g", at) + " m/s"
                                  : periodic           ? "phi = " + fmt("%.2f", at) + " rad"
                                                       : "x = " + fmt("%.3g", at * 1e3) + " mm";
        return "no library effect explains this part of the residual; a smooth force of " + var + " does, up to " +
               fmt("%.2g", best) + " N at " + where + (id == "unexplained_x_signv" ? " (for v > 0; reversed for v < 0)" : "") +
               ": the missing physics depends on " + var;
    }
    return "";
}

}  // namespace impactlab::identify::detail
