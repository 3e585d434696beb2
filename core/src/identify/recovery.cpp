// The recovery matrix: effects injected by synthesize() into a version, and whether run_fit() names them.
#include <cmath>

#include "identify/internal.hpp"

namespace impactlab::identify {

std::vector<RecoveryCase> recovery_cases(const std::vector<std::string>& versions) {
    // Moderate strengths: each changes the motion clearly, none changes its character.
    const std::vector<std::pair<RecoveryCase, bool>> library{
        {{"", "constant_force", "F0", -0.3}, false},     {{"", "quadratic_damping", "cq", 4.0}, false},
        {{"", "magnet_offset", "d", 3e-4}, false},       {{"", "even_stiffness", "k2", 3000.0}, false},
        {{"", "linear_stiffness", "dk", 20.0}, false},   {{"", "viscous_damping", "dc", 1.5}, false},
        {{"", "coulomb_friction", "dT", 0.3}, false},    {{"", "stribeck_friction", "Fs", 0.5}, false},
        {{"", "phase_offset", "delta", 0.05}, false},    {{"", "unbalance_scale", "s", 0.05}, false},
        {{"", "sensor_offset", "o", 3e-4}, false},       {{"", "sensor_gain", "g", 1.03}, false},
        {{"", "bumper_offset", "dx", 5e-4}, false},      {{"", "restitution", "kappa0", 0.4}, true},
        {{"", "cart_mass", "dm", -0.2}, false},          {{"", "sensor_delay", "tau", 3e-3}, false},
        {{"", "magnet_drift", "r", -1e-3}, false},       {{"", "sensor_curvature", "s", 0.133}, false},
        {{"", "unbalance_drift", "r", -1e-3}, false},    {{"", "damping_drift", "r", 3e-3}, false},
        {{"", "friction_drift", "r", 3e-3}, false},      {{"", "stiffness_drift", "r", -5e-4}, false},
    };
    std::vector<RecoveryCase> out;
    for (const auto& v : versions) {
        const bool rigid = make_version(v).rigid();
        for (const auto& [c, rigid_only] : library) {
            if (rigid_only && !rigid) continue;
            RecoveryCase k = c;
            k.version = v;
            out.push_back(k);
        }
    }
    return out;
}

RecoveryResult run_recovery(const RecoveryCase& c, double duration, unsigned seed) {
    RecoveryResult r;
    r.c = c;
    Model truth = resolve_fit_model(c.version, Forcing::Unbalance);
    std::vector<std::pair<std::string, double>> values{{c.param, c.truth}};
    if (c.effect == "stribeck_friction") values.emplace_back("vs", 0.02);
    apply_effect(truth, c.effect, values);
    SynthOptions so;
    so.duration = duration;
    so.seed = seed;
    steps_profile({9.0, 16.0}, 0.5 * duration - 1.0, 2.0, so.knot_t, so.knot_omega);
    const MeasuredData d = synthesize(truth, so);
    FitOptions fo;
    fo.plots = false;
    const FitReport rep = run_fit(d, resolve_fit_model(c.version, Forcing::Unbalance), fo);
    r.rms_before_m = rep.validation_rms_before_m;
    r.rms_after_m = rep.validation_rms_after_m;
    r.lowered = rep.validation_rms_after_m < rep.validation_rms_before_m;
    if (rep.effects_found.empty()) return r;
    const FoundEffect& f = rep.effects_found.front();
    r.first = f.id;
    r.named_first = f.id == c.effect && f.not_told_from.empty();
    for (const auto& [k, v] : f.parameters)
        if (k == c.param) r.estimate = v;
    for (const auto& [k, v] : f.sigma)
        if (k == c.param) r.sigma = v;
    r.within = r.named_first && std::abs(r.estimate - c.truth) <= 3.0 * r.sigma;
    return r;
}

NullResult run_null(const std::string& version, double duration, unsigned seed) {
    const Model truth = resolve_fit_model(version, Forcing::Unbalance);
    SynthOptions so;
    so.duration = duration;
    so.seed = seed;
    steps_profile({9.0, 16.0}, 0.5 * duration - 1.0, 2.0, so.knot_t, so.knot_omega);
    FitOptions fo;
    fo.plots = false;
    const FitReport rep = run_fit(synthesize(truth, so), truth, fo);
    NullResult r;
    for (const auto& f : rep.effects_found) r.found.push_back(f.id);
    r.model_unchanged = rep.after.p.effects.empty() && rep.after.p.m == truth.p.m && rep.after.p.xI == truth.p.xI && rep.after.p.impact == truth.p.impact &&
                        rep.after.p.ip == truth.p.ip && rep.after.p.input_gain == truth.p.input_gain;
    r.rms_m = rep.error_after.shooting_rms_1_m;
    return r;
}

}  // namespace impactlab::identify
