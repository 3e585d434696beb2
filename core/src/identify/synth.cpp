// Synthetic measured data: the model (with its effects) sampled at exact integrator stops, with sensor
// noise and quantisation, as the rig's Hall sensor and encoder would deliver it.
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <stdexcept>

#include "identify/internal.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::identify {

void steps_profile(const std::vector<double>& omegas, double plateau, double ramp, std::vector<double>& t,
                   std::vector<double>& w) {
    t.clear();
    w.clear();
    double now = 0;
    for (std::size_t k = 0; k < omegas.size(); ++k) {
        if (k > 0) now += ramp;
        t.push_back(now);
        w.push_back(omegas[k]);
        now += plateau;
        t.push_back(now);
        w.push_back(omegas[k]);
    }
}

MeasuredData synthesize(const Model& m, const SynthOptions& o) {
    const bool input = !o.input.empty();
    if (m.forcing == Forcing::Input && !input) throw ParamError("synth: an input-forced model needs the input u to drive it");
    if (!(o.duration > 0) || !(o.rate > 0)) throw ParamError("synth: the duration and the rate must be positive");
    validate(m.p, "synth model");
    // Knots closer than a microsecond (a step profile with zero ramp) are separated by one.
    std::vector<double> kt = o.knot_t, kw = o.knot_omega;
    for (std::size_t i = 1; i < kt.size(); ++i) kt[i] = std::max(kt[i], kt[i - 1] + 1e-6);
    Drive drive = Drive::piecewise_linear(kt, kw, 0.0);
    if (input) {
        try {
            drive.set_input(o.input_t0, o.input_dt, o.input);
        } catch (const std::invalid_argument& e) {
            throw ParamError(std::string("synth: ") + e.what());
        }
    }
    Tolerances tol;
    tol.rtol = o.rtol;
    Simulator sim(tol);
    State s;
    s.t = 0;
    s.x = o.x0;
    s.v = o.v0;
    Simulator::make_consistent(m.p, drive, s);
    const auto n = static_cast<std::size_t>(std::floor(o.duration * o.rate + 1e-9)) + 1;
    const double g = m.sensor_gain(), off = m.sensor_offset();
    std::mt19937_64 rng(o.seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    const double phi_q = o.phi_counts > 0 ? kTwoPi / o.phi_counts : 0.0;
    MeasuredData d;
    d.source = "synth";
    d.t.resize(n);
    d.x.resize(n);
    (input ? d.u : d.phi).resize(n);
    d.line.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double tk = static_cast<double>(k) / o.rate;
        sim.advance(m.p, drive, s, tk);
        double x = (m.sensor_curved() ? m.measure(s.x) : g * s.x + off) + o.noise * noise(rng);
        if (o.quantum > 0) x = std::round(x / o.quantum) * o.quantum;
        double phi = drive.phi(tk);
        if (phi_q > 0) phi = std::round(phi / phi_q) * phi_q;
        d.t[k] = tk;
        d.x[k] = x;
        if (input) d.u[k] = drive.input(tk);
        else d.phi[k] = phi;
        d.line[k] = static_cast<long>(k) + 2;
    }
    std::ostringstream eff, prof;
    for (const auto& e : m.p.effects) {
        eff << (eff.tellp() > 0 ? " " : "") << e.law->id;
        for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i) eff << (i ? "," : "=") << e.law->names[i] << ":" << e.p[i];
    }
    for (std::size_t i = 0; i < kt.size(); ++i) prof << (i ? " " : "") << kt[i] << ":" << kw[i];
    if (input) d.meta["input_gain"] = std::to_string(m.p.input_gain);
    d.meta["generated_by"] = "impactlab synth";
    d.meta["model"] = m.p.name;
    auto g6 = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", v);
        return std::string(buf);
    };
    d.meta["xI_m"] = g6(m.p.xI);
    d.meta["effects"] = eff.str().empty() ? "none" : eff.str();
    d.meta["noise_m"] = g6(o.noise);
    d.meta["quantum_m"] = g6(o.quantum);
    d.meta["phi_counts"] = std::to_string(o.phi_counts);
    d.meta["rate_hz"] = g6(o.rate);
    d.meta["omega_knots"] = prof.str();
    d.meta["x0_m"] = g6(o.x0);
    d.meta["seed"] = std::to_string(o.seed);
    d.meta["impacts"] = std::to_string(s.impacts);
    return d;
}

}  // namespace impactlab::identify
