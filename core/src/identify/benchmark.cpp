// The loop's randomized benchmark: records drawn from broad families of effects the library has no name for
// (polynomials in x and in v of any symmetry, mixed x-v terms, narrow bumps, piecewise springs, a stiffness
// that cycles, pairs of these) and a null family, over versions, regimes and noise levels; each fitted with the
// version's parameters fixed. It measures rates, not examples: false physical claims (a named law that is
// not in the data), better models (the 1-period shooting error down 3x or to the noise) and honest verdicts
// (the noise floor claimed exactly when the model written is at the injected noise).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "identify/internal.hpp"
#include "impactlab/identify.hpp"

namespace impactlab::identify {

namespace {

constexpr double kXs = 0.015;   // [m] the scale of x in the drawn laws (the wells' distance from 0)
constexpr double kVs = 0.3;     // [m/s] the scale of v

// F = sum_{k=0..5} p[k] (x / kXs)^k [N]
EffectForce poly_x(const double* p, const ForceContext& c) {
    const double u = c.x / kXs;
    double F = 0, dF = 0, uk = 1;
    for (int k = 0; k <= 5; ++k) {
        F += p[k] * uk;
        if (k < 5) dF += (k + 1) * p[k + 1] * uk;
        uk *= u;
    }
    return {F, dF / kXs, 0.0, 0.0};
}
// F = sum_{k=1..4} p[k-1] (v / kVs)^k [N]
EffectForce poly_v(const double* p, const ForceContext& c) {
    const double u = c.v / kVs;
    double F = 0, dF = 0, uk = 1;
    for (int k = 1; k <= 4; ++k) {
        dF += k * p[k - 1] * uk;
        uk *= u;
        F += p[k - 1] * uk;
    }
    return {F, 0.0, dF / kVs, 0.0};
}
// F = p0 (x/kXs)^2 (v/kVs) + p1 (x/kXs) (v/kVs)^2 [N]: a position-dependent damping, a van der Pol-like term
EffectForce mixed_xv(const double* p, const ForceContext& c) {
    const double a = c.x / kXs, b = c.v / kVs;
    return {p[0] * a * a * b + p[1] * a * b * b, (2 * p[0] * a * b + p[1] * b * b) / kXs, (p[0] * a * a + 2 * p[1] * a * b) / kVs, 0.0};
}
// F = p0 exp(-((x - p1) / p2)^2) [N]: a narrow bump of the rail
EffectForce bump(const double* p, const ForceContext& c) {
    const double z = (c.x - p[1]) / p[2], g = std::exp(-z * z);
    return {p[0] * g, -2.0 * z / p[2] * p[0] * g, 0.0, 0.0};
}
// F = -p0 (|x| - p1) sign(x) beyond |x| > p1 [N]: a spring that engages past a play (piecewise linear)
EffectForce piecewise(const double* p, const ForceContext& c) {
    const double a = std::abs(c.x) - p[1];
    if (a <= 0) return {};
    return {-p[0] * a * (c.x > 0 ? 1.0 : -1.0), -p[0], 0.0, 0.0};
}
// F = -p0 sin(2 pi t / p1) x [N]: a spring rate that cycles (temperature, a loose mount)
EffectForce cycling_k(const double* p, const ForceContext& c) {
    const double s = std::sin(2.0 * 3.141592653589793 * c.t / p[1]);
    return {-p[0] * s * c.x, -p[0] * s, 0.0, -p[0] * c.x * std::cos(2.0 * 3.141592653589793 * c.t / p[1]) * 2.0 * 3.141592653589793 / p[1]};
}

EffectLaw unnamed(const char* id, EffectForceFn f) {
    // n_free = 0: never a candidate of the fit, only something synth injects.
    return EffectLaw{id, "an effect the library has no name for", {"p0", "p1", "p2", "p3", "p4", "p5", nullptr, nullptr},
                     {"", "", "", "", "", "", nullptr, nullptr}, {0, 0, 0, 0, 0, 0, 0, 0}, f};
}

struct Family {
    const char* name;
    // Draws the injection into m (its size: `strength` newtons at the typical state) and returns the library
    // ids whose physics is in it (a named law among them is no false claim).
    std::vector<std::string> (*draw)(Model& m, std::mt19937_64& rng, double strength);
};

double uni(std::mt19937_64& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
double sign(std::mt19937_64& rng) { return uni(rng, 0, 1) < 0.5 ? -1.0 : 1.0; }

void add(Model& m, const EffectLaw& law, std::initializer_list<double> p) {
    EffectInstance e;
    e.law = &law;
    std::size_t k = 0;
    for (double v : p) e.p[k++] = v;
    m.p.effects.push_back(e);
}

const EffectLaw& law_poly_x() { static const EffectLaw l = unnamed("bench_poly_x", poly_x); return l; }
const EffectLaw& law_poly_v() { static const EffectLaw l = unnamed("bench_poly_v", poly_v); return l; }
const EffectLaw& law_mixed() { static const EffectLaw l = unnamed("bench_mixed_xv", mixed_xv); return l; }
const EffectLaw& law_bump() { static const EffectLaw l = unnamed("bench_bump", bump); return l; }
const EffectLaw& law_piecewise() { static const EffectLaw l = unnamed("bench_piecewise", piecewise); return l; }
const EffectLaw& law_cycling() { static const EffectLaw l = unnamed("bench_cycling_k", cycling_k); return l; }

std::vector<std::string> draw_poly_x(Model& m, std::mt19937_64& rng, double s) {
    // Powers 2..5, each present with probability 1/2 (at least one), any sign: any symmetry.
    double c[6] = {0, 0, 0, 0, 0, 0};
    std::vector<std::string> allowed;
    bool any = false;
    for (int k = 2; k <= 5; ++k)
        if (uni(rng, 0, 1) < 0.5 || (k == 5 && !any)) {
            c[k] = sign(rng) * s * uni(rng, 0.3, 1.0);
            any = true;
        }
    if (c[2] != 0) allowed.push_back("even_stiffness");
    if (c[3] != 0) allowed.push_back("cubic_stiffness");
    add(m, law_poly_x(), {c[0], c[1], c[2], c[3], c[4], c[5]});
    return allowed;
}
std::vector<std::string> draw_poly_v(Model& m, std::mt19937_64& rng, double s) {
    // v^2 (even: a one-sided drag), v^3 and v^4: never the library's v|v| or viscous law alone.
    double c[4] = {0, 0, 0, 0};
    for (int k = 2; k <= 4; ++k)
        if (uni(rng, 0, 1) < 0.6 || k == 4) c[k - 1] = -s * uni(rng, 0.3, 1.0) * (k % 2 == 1 ? 1.0 : sign(rng));
    add(m, law_poly_v(), {c[0], c[1], c[2], c[3]});
    return {};
}
std::vector<std::string> draw_mixed(Model& m, std::mt19937_64& rng, double s) {
    add(m, law_mixed(), {-s * uni(rng, 0.3, 1.0), s * uni(rng, -0.5, 0.5)});
    return {};
}
std::vector<std::string> draw_bump(Model& m, std::mt19937_64& rng, double s) {
    add(m, law_bump(), {sign(rng) * 2.0 * s * uni(rng, 0.5, 1.0), uni(rng, -0.012, 0.004), uni(rng, 0.001, 0.003)});
    return {};
}
std::vector<std::string> draw_piecewise(Model& m, std::mt19937_64& rng, double s) {
    const double play = uni(rng, 0.008, 0.014);
    add(m, law_piecewise(), {s / 0.004 * uni(rng, 0.5, 1.5), play});
    return {};
}
std::vector<std::string> draw_cycling(Model& m, std::mt19937_64& rng, double s) {
    add(m, law_cycling(), {s / kXs * uni(rng, 0.5, 1.0), uni(rng, 4.0, 12.0)});
    return {"stiffness_drift", "linear_stiffness"};   // over a short stretch a cycle is a drift of k
}
std::vector<std::string> draw_null(Model&, std::mt19937_64&, double) { return {}; }

const std::vector<Family>& families() {
    static const std::vector<Family> f{{"null", draw_null},         {"poly_x", draw_poly_x},       {"poly_v", draw_poly_v},
                                       {"mixed_xv", draw_mixed},    {"bump", draw_bump},           {"piecewise", draw_piecewise},
                                       {"cycling_k", draw_cycling}};
    return f;
}

}  // namespace

IdentifyBenchResult run_identify_bench(const IdentifyBenchOptions& o) {
    IdentifyBenchResult res;
    std::mt19937_64 rng(o.seed);
    const char* versions[] = {"A1H", "A1C", "A1G", "A3G"};
    const auto& fam = families();
    for (int i = 0; i < o.records; ++i) {
        if (o.cancel && o.cancel->load()) break;
        IdentifyBenchRecord row;
        // Family: the null one every seventh record, else one or two unnamed effects.
        const std::size_t f1 = i % 7 == 0 ? 0 : 1 + static_cast<std::size_t>(uni(rng, 0, static_cast<double>(fam.size() - 1)));
        const bool pair = f1 != 0 && uni(rng, 0, 1) < 0.25;
        const std::size_t f2 = pair ? 1 + static_cast<std::size_t>(uni(rng, 0, static_cast<double>(fam.size() - 1))) : 0;
        row.version = versions[static_cast<std::size_t>(uni(rng, 0, 4))];
        Model truth = resolve_fit_model(row.version, Forcing::Unbalance);
        const double strength = uni(rng, 0.05, 0.4);   // [N] at the typical state
        std::vector<std::string> allowed = fam[f1].draw(truth, rng, strength);
        row.family = fam[f1].name;
        if (pair && f2 != f1) {
            for (const auto& a : fam[f2].draw(truth, rng, strength)) allowed.push_back(a);
            row.family += std::string("+") + fam[f2].name;
        }
        row.null_family = f1 == 0;
        row.allowed = allowed;
        SynthOptions so;
        so.duration = o.duration;
        so.rate = 1000.0;
        so.noise = std::exp(uni(rng, std::log(1e-6), std::log(1e-5)));
        so.quantum = uni(rng, 0, 1) < 0.5 ? 1e-6 : 0.0;
        so.seed = static_cast<unsigned>(rng() & 0xffffffu);
        // The regime: a periodic plateau, a chaotic one, or steps through both.
        const double regime = uni(rng, 0, 1);
        if (regime < 0.35) {
            so.knot_t = {0.0};
            so.knot_omega = {uni(rng, 8.5, 11.0)};
            row.regime = "periodic";
        } else if (regime < 0.7) {
            so.knot_t = {0.0};
            so.knot_omega = {uni(rng, 15.5, 18.5)};
            row.regime = "chaotic";
        } else {
            steps_profile({9.0, 13.5, 16.0, 18.0}, o.duration / 4.0 - 1.0, 1.0, so.knot_t, so.knot_omega);
            row.regime = "steps";
        }
        so.x0 = uni(rng, -0.014, -0.008);
        row.noise = so.noise;
        for (const EffectInstance& e : truth.p.effects) {
            row.truth += (row.truth.empty() ? "" : " + ") + std::string(e.law->id) + "(";
            for (std::size_t k = 0; k < 6; ++k) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%s%.3g", k ? ", " : "", e.p[k]);
                row.truth += buf;
            }
            row.truth += ")";
        }
        if (o.only > 0 && i + 1 != o.only) continue;   // every draw above is made: the records keep their numbers
        const auto t0 = std::chrono::steady_clock::now();
        try {
            MeasuredData d = synthesize(truth, so);
            d.source = "bench record " + std::to_string(i + 1);
            FitOptions fo;
            fo.plots = false;
            const FitReport r = run_fit(d, resolve_fit_model(row.version, Forcing::Unbalance), fo);
            if (o.only > 0 && !o.report_dir.empty()) write_report(r, o.report_dir, false);
            for (const auto& f : r.effects_found) {
                row.named.push_back(f.not_told_from.empty() ? f.id : f.id + "?");   // ?: its shape not resolved
                // A generic term, or a law whose shape the data did not resolve, names no physics.
                const bool generic = generic_effect(f.id) || !f.not_told_from.empty();
                if (!generic && std::find(allowed.begin(), allowed.end(), f.id) == allowed.end()) row.false_claim = true;
            }
            row.before = r.error_before.shooting_rms_1_m;
            row.after = r.error_after.shooting_rms_1_m;
            row.better = row.after <= row.before / 3.0 || row.after <= 1.5 * so.noise;
            const bool claims_floor = r.verdict.find("is at its noise floor") != std::string::npos;
            const bool at_floor = row.after <= 1.25 * std::hypot(so.noise, so.quantum / std::sqrt(12.0));
            row.honest = claims_floor == at_floor;
            row.before_at_floor = row.before <= 1.25 * std::hypot(so.noise, so.quantum / std::sqrt(12.0));
        } catch (const std::exception& e) {
            row.error = e.what();
        }
        row.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        res.rows.push_back(row);
        if (o.progress) o.progress(static_cast<int>(res.rows.size()), o.records, res.rows.back());
    }
    std::size_t nf = 0, nn = 0, nn_false = 0, nb = 0, nb_den = 0, nh = 0, ok = 0;
    for (const auto& r : res.rows) {
        if (!r.error.empty()) {
            ++res.errors;
            continue;
        }
        ++ok;
        if (r.false_claim) ++nf;
        if (r.honest) ++nh;
        if (r.null_family) {
            ++nn;
            if (!r.named.empty()) ++nn_false;
        } else if (!r.before_at_floor) {
            ++nb_den;
            if (r.better) ++nb;
        }
    }
    res.false_claim_rate = ok ? static_cast<double>(nf) / static_cast<double>(ok) : 0.0;
    res.null_claims = nn_false;
    res.null_records = nn;
    res.better_rate = nb_den ? static_cast<double>(nb) / static_cast<double>(nb_den) : 0.0;
    res.better_records = nb_den;
    res.honest_rate = ok ? static_cast<double>(nh) / static_cast<double>(ok) : 0.0;
    return res;
}

}  // namespace impactlab::identify
