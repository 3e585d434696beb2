// The effect catalogue of impactlab fit: the registry's effects (each law carries how it is looked for and
// described, core/src/effects) and the rows of the effects that change the base model (base_effects.cpp),
// turned into candidates, applied to a model and described.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "effects/law_helpers.hpp"
#include "identify/internal.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab::identify {

namespace {
bool curved_sensor(const EffectInstance& e) { return e.law->kind == EffectKind::Sensor && e.law->measure && e.law->curved; }
bool affine_sensor(const EffectInstance& e) { return e.law->kind == EffectKind::Sensor && e.law->measure && !e.law->curved; }
// The curved sensors' maps, in the order they were added (the identity without any).
double curve(const Params& p, double x) {
    for (const auto& e : p.effects)
        if (curved_sensor(e)) x = e.law->measure(e.p.data(), x);
    return x;
}
}  // namespace

// The sensor effects' affine maps combined as x_measured = g c(x) + o: gains multiply, offsets add (an offset
// is a zero error of the reading, whatever the gain); a curved scale c acts on the true position first.
double Model::sensor_gain() const {
    double g = 1.0;
    for (const auto& e : p.effects)
        if (affine_sensor(e)) g *= e.law->measure(e.p.data(), 1.0) - e.law->measure(e.p.data(), 0.0);
    return g;
}
double Model::sensor_offset() const {
    double o = 0.0;
    for (const auto& e : p.effects)
        if (affine_sensor(e)) o += e.law->measure(e.p.data(), 0.0);
    return o;
}
bool Model::sensor_curved() const { return std::any_of(p.effects.begin(), p.effects.end(), curved_sensor); }
double Model::measure(double x) const { return sensor_gain() * curve(p, x) + sensor_offset(); }
double Model::measure_slope(double x) const {
    if (!sensor_curved()) return sensor_gain();
    const double h = 1e-7 * (1.0 + std::abs(x));
    return sensor_gain() * (curve(p, x + h) - curve(p, x - h)) / (2.0 * h);
}
double Model::true_x(double xm) const {
    const double y = (xm - sensor_offset()) / sensor_gain();
    if (!sensor_curved()) return y;
    // Newton on c(x) = y from x = y: a sensor's curve is a small bend of the identity.
    double x = y;
    for (int it = 0; it < 8; ++it) {
        const double h = 1e-7 * (1.0 + std::abs(x));
        const double f = curve(p, x) - y, d = (curve(p, x + h) - curve(p, x - h)) / (2.0 * h);
        if (!(std::abs(d) > 1e-12)) break;
        const double step = f / d;
        x -= step;
        if (std::abs(step) < 1e-15 * (1.0 + std::abs(x))) break;
    }
    return x;
}

Model resolve_fit_model(const std::string& name, Forcing forcing) {
    Model m;
    m.forcing = forcing;
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower == duffing_stiffness().id) {
        // m y'' + d y' + k y + k3 y^3 = gain u: a Params with m = 1, no dry friction, no magnets' denominator,
        // and no bumper. Starting values are placeholders: fit mode estimates d, k, k3 and the gain.
        const StiffnessSet& s = duffing_stiffness();
        m.p = make_version("A1none");
        m.p.name = s.id;
        m.p.stiffness_id = s.id;
        m.p.m = 1.0;
        m.p.m0e = s.m0e;
        m.p.k = s.k;
        m.p.c = s.c;
        m.p.T = s.T;
        m.p.a = s.a;
        m.p.b = s.b;
        m.p.xI = 0.0;
        m.p.input_gain = 1.0;
        m.forcing = Forcing::Input;
        m.placeholder = true;
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
        e.generic = law.fit.generic;
        out.push_back(std::move(e));
    }
    for (const auto& b : detail::base_effects()) out.push_back(b.info);
    return out;
}

}  // namespace

const std::vector<EffectInfo>& effect_catalogue() {
    // Rebuilt when the registry changed (a scoped law added, gone, or one swapped for another: the size and
    // the last law's id together tell).
    static std::mutex mutex;
    static std::vector<EffectInfo> cat;
    static std::size_t laws = static_cast<std::size_t>(-1);
    static std::string last;
    const std::lock_guard<std::mutex> lock(mutex);
    const auto& table = effect_laws();
    const std::string now_last = table.empty() ? std::string() : table.back().id;
    if (laws != table.size() || last != now_last) {
        cat = build_catalogue();
        laws = table.size();
        last = now_last;
    }
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
        if (!inst) {   // a new instance: defaults, and what it shares with the model (magnet_offset's law)
            inst = &add_effect(m.p, id);
            if (inst->law->adapt) inst->law->adapt(inst->p.data(), m.p);
        }
        for (std::size_t k = 0; k < v.size(); ++k)
            if (given[k]) inst->p[k] = v[k];
        return;
    }
    const detail::BaseEffect* b = detail::find_base_effect(id);
    if (b->needs_bumper && !m.bumper()) throw ParamError("effect '" + id + "' needs a model with a bumper");
    b->apply(m, v, given);
}

}  // namespace impactlab::identify

namespace impactlab::identify::detail {

Candidate candidate_of(const EffectLaw& law) {
    const EffectFitHint& h = law.fit;
    Candidate c;
    c.id = law.id;
    c.law = &law;
    for (int k = 0; k < h.n_free; ++k) {
        c.free.push_back(h.free[static_cast<std::size_t>(k)]);
        c.step.push_back(h.step[static_cast<std::size_t>(h.free[static_cast<std::size_t>(k)])]);
    }
    for (int k = 0; k < h.n_linear; ++k) c.linear.push_back(k);
    c.starts.assign(h.starts.begin(), h.starts.begin() + h.n_starts);
    c.generic = h.generic;
    c.sensor = law.kind == EffectKind::Sensor;
    c.positive = h.positive;
    return c;
}

std::vector<Candidate> library_candidates(const Model& m, const Prep& pr, const FitOptions& o) {
    std::vector<Candidate> out;
    double alpha_rms = 0;
    for (double a : pr.alpha) alpha_rms += a * a;
    alpha_rms = std::sqrt(alpha_rms / static_cast<double>(std::max<std::size_t>(1, pr.alpha.size())));
    // In fit mode the base parameters absorb some effects; in validate mode those say which base value is off.
    const auto fitted_names = fitted_base_names(m, pr, o);
    auto fitted = [&](const char* name) { return std::find(fitted_names.begin(), fitted_names.end(), name) != fitted_names.end(); };
    for (const auto& law : effect_laws()) {
        const EffectFitHint& h = law.fit;
        const std::string id = law.id;
        if (h.n_free == 0) continue;
        if (!o.wants(id)) continue;
        if (h.generic && !o.generic) continue;
        if ((h.needs & FitNeeds::Phi) && !pr.phi_forced) continue;
        if ((h.needs & FitNeeds::SpeedChanges) && !(alpha_rms > 1e-3)) continue;
        if ((h.needs & FitNeeds::Magnets) && m.p.a[0] == 0.0 && m.p.a[1] == 0.0) continue;
        if ((h.needs & FitNeeds::DryFriction) && !(m.p.T > 0)) continue;
        if ((h.needs & FitNeeds::FixedBaseline) && o.fit_baseline) continue;
        if ((h.needs & FitNeeds::XFeature) && !pr.x_feature.found()) continue;
        if ((h.needs & FitNeeds::VFeature) && !pr.v_feature.found()) continue;
        if ((h.needs & FitNeeds::Cycle) && !pr.cycle.found()) continue;
        if (h.absorbed_by && fitted(h.absorbed_by)) continue;
        if (id == "sensor_offset" && fitted("x0")) continue;   // the model's own origin, fitted already
        out.push_back(candidate_of(law));
    }
    // The base-changing effects the screening looks for (a wrong cart mass: the acceleration's column).
    for (const auto& b : base_effects()) {
        if (!b.candidate) continue;
        const std::string& id = b.info.id;
        if (!o.wants(id)) continue;
        Candidate c;
        c.id = id;
        if (b.candidate(m, o, c)) out.push_back(std::move(c));
    }
    return out;
}

EffectInstance start_instance(const Candidate& c, const Model& m, const Prep& pr, double start) {
    EffectInstance e{c.law, {}};
    if (c.law && c.law->start) {
        // What the law may take its shape from: the model, and the data's ranges in true coordinates.
        const MeasuredData& d = *pr.data;
        std::vector<double> xs, vs;
        xs.reserve(pr.rows.size());
        vs.reserve(pr.rows.size());
        for (std::size_t r : pr.rows) {
            xs.push_back(m.true_x(d.x[r]));
            vs.push_back(pr.vs[r] / m.measure_slope(xs.back()));
        }
        EffectStartContext ctx{&m.p,
                               quantile(xs, 0.005),
                               quantile(xs, 0.995),
                               quantile(vs, 0.005),
                               quantile(vs, 0.995),
                               start,
                               pr.x_feature.lo,
                               pr.x_feature.hi,
                               pr.v_feature.lo,
                               pr.v_feature.hi,
                               pr.cycle.period};
        c.law->start(e.p.data(), ctx);
    }
    // A law with a time origin (the drifts) measures time from the record's start, so a record on a late clock
    // shows a drift as a drift and not as a constant change times the clock.
    if (c.law)
        for (std::size_t k = 0; k < kMaxLawParams && c.law->names[k]; ++k)
            if (std::string(c.law->names[k]) == "t0") e.p[k] = pr.data->t.front();
    return e;
}

std::vector<std::string> default_fit_params(const Model& m, const Prep& pr) {
    if (m.forcing == Forcing::Input) {
        // A free run has no input to scale: its gain is not a parameter of the record.
        std::vector<std::string> v{"c", "k"};
        if (!pr.unforced) v.push_back("gain");
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

bool centred_placeholder(const Model& m) {
    return m.placeholder && std::any_of(m.p.effects.begin(), m.p.effects.end(),
                                        [](const EffectInstance& e) { return e.law == find_effect("sensor_offset"); });
}

std::vector<std::string> fitted_base_names(const Model& m, const Prep& pr, const FitOptions& o) {
    if (!o.fit_baseline) return {};
    std::vector<std::string> v = o.fit_params.empty() ? default_fit_params(m, pr) : o.fit_params;
    // A placeholder centred on its record (fit/origin.cpp) fits its origin beside the parameters, given or
    // default: it is a coordinate the record sets, not one a user could have named.
    if (centred_placeholder(m) && std::find(v.begin(), v.end(), "x0") == v.end()) v.push_back("x0");
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
        else if (n == "k2" || n == "x0") {
            // k2: the model's own even stiffness (an even_stiffness effect it carries); x0: the origin of a
            // placeholder's spring in the record's coordinates (a sensor_offset it carries).
            const EffectLaw* law = find_effect(n == "k2" ? "even_stiffness" : "sensor_offset");
            for (auto& e : m.p.effects)
                if (e.law && e.law == law) p = &e.p[0];
        }
        if (!p) throw ParamError("--fit-params: unknown parameter '" + n + "' (known: c, T, k, a1, a3, a5, b2, b4, m0e, gain, m, xI; k2 where the model carries an even_stiffness, x0 where it carries a sensor_offset)");
        out.push_back({n, p, std::max(1e-6 * std::abs(*p), 1e-9)});
    }
    return out;
}

double base_scale(const std::string& name, const Prep& pr, const Model& m) {
    const double f = pr.f_typ > 0 ? pr.f_typ : 1.0, x = pr.x_typ > 0 ? pr.x_typ : 1.0, v = pr.v_typ > 0 ? pr.v_typ : 1.0;
    const double w = pr.period > 0 ? kTwoPi / pr.period : 1.0;
    double s = 1.0;
    if (name == "k" || name == "a1") s = f / x;
    else if (name == "a3") s = f / (x * x * x);
    else if (name == "a5") s = f / (x * x * x * x * x);
    else if (name == "c") s = f / v;
    else if (name == "T") s = f;
    else if (name == "gain") s = pr.u_typ > 0 ? f / pr.u_typ : 1.0;
    else if (name == "m0e") s = f / (w * w);
    else if (name == "m") s = m.p.m;
    else if (name == "b2") s = 1.0 / (x * x);
    else if (name == "k2") s = f / (x * x);
    else if (name == "b4") s = 1.0 / (x * x * x * x);
    else if (name == "xI" || name == "x0") s = x;
    return std::isfinite(s) && s > 0 ? s : 1.0;
}

namespace {
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
    // A force or sensor effect describes itself (its law's metadata).
    if (const EffectLaw* law = find_effect(id); law && law->describe) {
        std::array<double, kMaxLawParams> p{}, sg{};
        for (std::size_t k = 0; k < kMaxLawParams && law->names[k]; ++k) {
            p[k] = val(law->names[k]);
            sg[k] = sig(law->names[k]);
        }
        const EffectReportContext ctx{&b.p, stiffness_kind(b.p) == StiffnessKind::Rig, c.v_typ, c.x_typ};
        return law->describe(p.data(), sg.data(), ctx);
    }
    // An effect that changes the base model.
    if (const BaseEffect* be = find_base_effect(id)) return be->describe(b, v, s);
    return "";
}

}  // namespace impactlab::identify::detail
