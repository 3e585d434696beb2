// impactlab synth: synthetic measured data with effects, sensor noise and quantisation.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab::cli {

namespace {

constexpr const char* kSynthHelp =
    "usage: impactlab synth --model A1H [--effect ID=VALUE ...] --out FILE.csv[.gz] [options]\n\n"
    "Simulates the model with extra effects and writes t,x,phi in the MODEL.md layout, x with sensor noise and\n"
    "quantisation, phi quantised to an encoder's counts; samples are exact integrator stops.\n"
    "  --model NAME|FILE.json  model version or parameter file (default A1H); --xI X, --m0e M override\n"
    "  --effect ID=VALUE       add an effect, VALUE for its first parameter; ID.PARAM=VALUE sets another one.\n"
    "                          Repeat the flag or separate with commas. IDs: impactlab fit's library, e.g.\n"
    "                          constant_force=-0.3, quadratic_damping=4, bumper_offset=5e-4, sensor_offset=2e-4,\n"
    "                          impact_duration=6e-3, cart_mass=-0.2 (the mass m + dm [kg]), stribeck_friction=0.5\n"
    "                          --effect stribeck_friction.vs=0.01\n"
    "  --out FILE              output CSV (FILE.gz: gzip)\n"
    "  --duration S            simulated time [s] (default 60)\n"
    "  --rate HZ               sample rate (default 1000)\n"
    "  --noise M               sensor noise sigma [m] (default 3e-6)\n"
    "  --quantum M             x resolution [m] (default 1e-6; 0: none)\n"
    "  --phi-counts N          encoder counts per revolution (default 4096; 0: exact)\n"
    "  omega profile (default: steps 9,13.5,16,18 rad/s):\n"
    "  --omega LIST            constant steps [rad/s], with --plateau S (default duration / steps) and --ramp S (default 2)\n"
    "  --ef WMAX:TRAMP         the EF ramp omega = WMAX t / TRAMP\n"
    "  --omega-knots t:w,...   omega piecewise linear through knots\n"
    "  --x0 X, --v0 V          initial state (default -0.01 m, 0)\n"
    "  --seed N                noise seed (default 1)\n"
    "  --rtol R                integrator tolerance (default 1e-10)\n"
    "Input-forced data (writes t,x,u; the model is driven by input_gain * u, plus its unbalance if m0e > 0):\n"
    "  --input FILE            a record whose u column drives the model (MODEL.md layout, or mapped:)\n"
    "  --u-col C, --x-col C, --t-col C, --input-rate HZ, --u-scale S   its columns, rate and unit\n"
    "  --gain G                input_gain [N per unit of u] (default: the model's, 1 if it has none)\n"
    "                          (--duration defaults to the input's length; --rate to its rate)\n";

std::vector<double> numbers(const std::string& flag, const std::string& s) {
    std::vector<double> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
            throw UsageError("synth: " + flag + ": '" + item + "' is not a number");
        out.push_back(v);
    }
    if (out.empty()) throw UsageError("synth: " + flag + ": empty list");
    return out;
}

double number(const std::string& what, const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
        throw UsageError("synth: " + what + ": '" + s + "' is not a finite number");
    return v;
}

std::string shortest(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// --effect may repeat: take those out before the strict parser sees them.
void split_effects(const std::vector<std::string>& argv_in, std::vector<std::string>& argv, std::vector<std::string>& effects) {
    for (std::size_t i = 0; i < argv_in.size(); ++i) {
        const std::string& s = argv_in[i];
        if (s == "--effect") {
            if (i + 1 >= argv_in.size()) throw UsageError("synth: option '--effect' needs a value");
            effects.push_back(argv_in[++i]);
        } else if (s.rfind("--effect=", 0) == 0) {
            effects.push_back(s.substr(9));
        } else {
            argv.push_back(s);
        }
    }
}

// The model flags: the model resolved (an unbalance-forced rig, or any model driven by --input) with its
// overrides.
identify::Model synth_model(const Args& a, bool input) {
    identify::Model model;
    try {
        model = identify::resolve_fit_model(a.str("--model", "A1H"), input ? identify::Forcing::Input : identify::Forcing::Unbalance);
    } catch (const ParamError& e) {
        throw UsageError(std::string("--model: ") + e.what());
    }
    if (!input && (!model.bumper() || model.forcing != identify::Forcing::Unbalance))
        throw UsageError("synth: --model must be an unbalance-forced rig model (a version or a parameter file), or give --input");
    if (a.has("--gain")) model.p.input_gain = a.num("--gain", 1.0, -1e12, 1e12);
    if (a.has("--xI")) model.p.xI = a.num("--xI", 0.0, -0.1, 0.1);
    if (a.has("--m0e")) model.p.m0e = a.num("--m0e", model.p.m0e, 0.0, 10.0);
    return model;
}

// Each --effect ID=VALUE or ID.PARAM=VALUE (comma-separated lists too) applied to the model.
void apply_effects(identify::Model& model, const std::vector<std::string>& effects) {
    for (const auto& spec_list : effects) {
        std::stringstream ss(spec_list);
        std::string spec;
        while (std::getline(ss, spec, ',')) {
            const auto eq = spec.find('=');
            if (eq == std::string::npos || eq == 0) throw UsageError("synth: --effect '" + spec + "': expected ID=VALUE or ID.PARAM=VALUE");
            std::string id = spec.substr(0, eq), param;
            const auto dot = id.find('.');
            if (dot != std::string::npos) {
                param = id.substr(dot + 1);
                id = id.substr(0, dot);
            }
            const double v = number("--effect " + spec, spec.substr(eq + 1));
            try {
                identify::apply_effect(model, id, {{param, v}});
            } catch (const ParamError& e) {
                throw UsageError(std::string("synth: --effect: ") + e.what());
            }
        }
    }
}

// The omega profile flags: steps (the default), an EF ramp or knots; none with an input record.
void set_profile(const Args& a, bool input, identify::SynthOptions& o) {
    const int profiles = (a.has("--omega") ? 1 : 0) + (a.has("--ef") ? 1 : 0) + (a.has("--omega-knots") ? 1 : 0);
    if (profiles > 1) throw UsageError("synth: give one of --omega, --ef, --omega-knots");
    if (input && profiles == 0) {
        // driven by the input alone: omega stays 0
    } else if (a.has("--ef")) {
        const std::string s = a.str("--ef", "");
        const auto colon = s.find(':');
        if (colon == std::string::npos) throw UsageError("synth: --ef: expected WMAX:TRAMP");
        const double wmax = number("--ef", s.substr(0, colon)), tr = number("--ef", s.substr(colon + 1));
        if (!(wmax > 0) || !(tr > 0)) throw UsageError("synth: --ef: WMAX and TRAMP must be positive");
        o.knot_t = {0.0, tr};
        o.knot_omega = {0.0, wmax};
    } else if (a.has("--omega-knots")) {
        o.knot_t.clear();
        o.knot_omega.clear();
        std::stringstream ss(a.str("--omega-knots", ""));
        std::string item;
        while (std::getline(ss, item, ',')) {
            const auto colon = item.find(':');
            if (colon == std::string::npos) throw UsageError("synth: --omega-knots: expected t:w pairs, got '" + item + "'");
            o.knot_t.push_back(number("--omega-knots", item.substr(0, colon)));
            o.knot_omega.push_back(number("--omega-knots", item.substr(colon + 1)));
        }
        if (o.knot_t.empty()) throw UsageError("synth: --omega-knots: empty");
    } else {
        const std::vector<double> w = a.has("--omega") ? numbers("--omega", a.str("--omega", "")) : std::vector<double>{9, 13.5, 16, 18};
        const double ramp = a.num("--ramp", 2.0, 0.0, 1e6);
        const double nstep = static_cast<double>(w.size());
        const double plateau = a.num("--plateau", std::max(0.1, (o.duration - ramp * (nstep - 1)) / nstep), 1e-3, 1e6);
        identify::steps_profile(w, plateau, ramp, o.knot_t, o.knot_omega);
    }
}

// The profile and the record's size within what simulate and memory allow.
void check_run(const Args& a, const identify::SynthOptions& o) {
    for (std::size_t i = 0; i < o.knot_omega.size(); ++i)
        if (!(o.knot_omega[i] >= 0 && o.knot_omega[i] <= 1000.0))
            throw UsageError("synth: omega " + shortest(o.knot_omega[i]) + " rad/s is outside [0, 1000] (as for simulate)");
    // The whole record is held in memory as text: 5e7 samples (~2 GB of CSV) is the most a run may ask for.
    if (o.duration * o.rate > 5e7)
        throw UsageError("synth: --rate " + a.str("--rate", "1000") + " x --duration " + a.str("--duration", "60") + " = " +
                         shortest(o.duration * o.rate) + " samples, more than 5e7; shorten the run or lower the rate");
    for (std::size_t i = 1; i < o.knot_t.size(); ++i)
        if (o.knot_t[i] < o.knot_t[i - 1]) throw UsageError("synth: the omega knots' times must not decrease");
}

// The run's flags: the input record's drive, the span and rate, the sensor, the start, the seed, the
// integrator and the omega profile.
identify::SynthOptions synth_options(const Args& a, const identify::Model& model, const std::optional<identify::MeasuredData>& rec) {
    const bool input = rec.has_value();
    identify::SynthOptions o;
    if (input) {
        o.input = rec->u;
        o.input_t0 = 0.0;   // the record is re-timed from 0
        o.input_dt = (rec->t.back() - rec->t.front()) / static_cast<double>(rec->size() - 1);
        o.phi_counts = 0;
        o.knot_t = {0.0};
        o.knot_omega = {0.0};
    }
    const double in_len = input ? o.input_dt * static_cast<double>(rec->size() - 1) : 60.0;
    o.duration = a.num("--duration", in_len, 1e-3, 1e6);
    o.rate = a.num("--rate", input ? 1.0 / o.input_dt : 1000.0, 1.0, 1e7);
    o.noise = a.num("--noise", 3e-6, 0.0, 1.0);
    o.quantum = a.num("--quantum", 1e-6, 0.0, 1.0);
    o.phi_counts = a.integer("--phi-counts", 4096, 0, 1 << 30);
    o.x0 = a.num("--x0", -0.01, -0.1, 0.1);
    if (a.has("--x0")) check_start(model.p, o.x0, "synth", "--x0");
    o.v0 = a.num("--v0", 0.0, -10.0, 10.0);
    o.seed = static_cast<unsigned>(a.integer("--seed", 1, 0, 1 << 30));
    o.rtol = a.num("--rtol", 1e-10, 1e-13, 1e-3);
    set_profile(a, input, o);
    check_run(a, o);
    return o;
}

}  // namespace

int cmd_synth(const std::vector<std::string>& argv_in) {
    if (show_help_if_asked(argv_in, kSynthHelp)) return 0;
    std::vector<std::string> argv, effects;
    split_effects(argv_in, argv, effects);
    const Args a("synth", argv,
                 {"--model", "--xI", "--m0e", "--out", "--duration", "--rate", "--noise", "--quantum", "--phi-counts", "--omega",
                  "--plateau", "--ramp", "--ef", "--omega-knots", "--x0", "--v0", "--seed", "--rtol", "--input", "--u-col", "--x-col",
                  "--t-col", "--input-rate", "--u-scale", "--gain"});
    if (!a.positional().empty()) throw UsageError("synth: unexpected argument '" + a.positional()[0] + "'");
    const std::string out_path = a.required("--out");
    note_input(a.str("--model", "A1H"));
    if (a.has("--gain") && !a.has("--input")) throw UsageError("synth: --gain needs --input");
    const std::optional<identify::MeasuredData> rec = input_from(a, "synth");
    const bool input = rec.has_value();
    identify::Model model = synth_model(a, input);
    apply_effects(model, effects);
    try {
        validate(model.p, "synth model");
    } catch (const ParamError& e) {
        throw UsageError(std::string("synth: ") + e.what());
    }
    OutputFile out(out_path, "--out", std::ios::out | std::ios::binary);
    const identify::SynthOptions o = synth_options(a, model, rec);

    check_run_span(model.p, 0.0, o.duration, "synth");
    const identify::MeasuredData d = identify::synthesize(model, o);
    std::ostringstream text;
    identify::write_measured_csv(text, d);
    const bool gz = out_path.size() > 3 && out_path.substr(out_path.size() - 3) == ".gz";
    out << (gz ? identify::gzip_stored(text.str()) : text.str());
    out.commit();
    std::fprintf(stderr, "synth: %s, %zu samples over %.6g s, %s impacts, effects: %s -> %s\n", printable(model.p.name).c_str(), d.size(),
                 o.duration, d.meta.at("impacts").c_str(), d.meta.at("effects").c_str(), printable(out_path).c_str());
    return 0;
}

}  // namespace impactlab::cli
