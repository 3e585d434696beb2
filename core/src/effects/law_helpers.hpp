// Small helpers the effect files share to define their registry rows: a fit hint, and number formatting
// for the sentences that describe a fitted effect.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>

#include "impactlab/params.hpp"

namespace impactlab::effects {

inline constexpr double kPi = 3.141592653589793;

// Parameters `free` fitted (with finite-difference steps `steps`, in the same order); the first `n_linear`
// enter the screening linearly (all of them by default).
inline EffectFitHint hint(std::initializer_list<int> free, std::initializer_list<double> steps, int n_linear = -1) {
    EffectFitHint h;
    int k = 0;
    for (int i : free) h.free[static_cast<std::size_t>(k++)] = i;
    h.n_free = k;
    h.n_linear = n_linear < 0 ? k : n_linear;
    k = 0;
    for (double s : steps) h.step[static_cast<std::size_t>(h.free[static_cast<std::size_t>(k++)])] = s;
    return h;
}

inline std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// A unit for a sentence: SI on a rig's model, the record's own on a plain Duffing model in data units.
inline std::string unit(const EffectReportContext& c, const char* si, const char* data_units) {
    const char* u = c.rig ? si : data_units;
    return *u ? std::string(" ") + u : std::string();
}

// "v +/- s" with as many decimals as the uncertainty warrants (scaled by `scale` for display units).
inline std::string pm(double v, double s, double scale = 1.0) {
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

// The magnets' law F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4) and its slope, with (a1, a3, b2, b4) in
// p[1..4]: the effects that act through the model's own magnets (magnet_offset, magnet_drift) carry a copy.
struct MagnetForce { double F, dF; };
inline MagnetForce magnet_law(const double* p, double x) {
    const double x2 = x * x;
    const double num = x * (p[1] + p[2] * x2), dnum = p[1] + 3.0 * p[2] * x2;
    const double den = 1.0 + x2 * (p[3] + p[4] * x2), dden = x * (2.0 * p[3] + 4.0 * p[4] * x2);
    return {num / den, (dnum * den - num * dden) / (den * den)};
}
// Copies the model's magnetic law into p[1..4] (an EffectAdaptFn), and starts p[0] at its null value 0.
inline void adapt_magnets(double* p, const Params& m) {
    p[1] = m.a[0];
    p[2] = m.a[1];
    p[3] = m.b[0];
    p[4] = m.b[1];
}
inline void start_magnets(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt_magnets(p, *c.model);
}
// The registry row of an effect acting through the model's magnets: its own parameter p[0] (`name`, `unit`,
// fitted alone from 0), then the copied magnetic law (a1, a3, b2, b4; defaults A1's).
inline EffectLaw magnet_effect_law(const char* id, const char* meaning, const char* name, const char* unit, EffectForceFn force,
                                   EffectDescribeFn describe) {
    EffectLaw l{id, meaning, {name, "a1", "a3", "b2", "b4", nullptr}, {unit, "N/m", "N/m^3", "1/m^2", "1/m^4", nullptr},
                {0.0, -1763.5, 0.0, 4907.6, 0.0}, force};
    l.fit = hint({0}, {1e-5});
    l.fit.needs = FitNeeds::Magnets;
    l.start = start_magnets;
    l.adapt = adapt_magnets;
    l.describe = describe;
    return l;
}

// A parameter scaled by 1 + r (t - t0) over the record (the drifts): the sentence naming it and its rate.
inline std::string drift_sentence(const char* what, const char* why, const double* p, const double* s) {
    return std::string(what) + " drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" +
           fmt("%+.2g", 100.0 * p[0] * 60.0) + " % a minute; " + why + ")";
}
// The drift of the base parameter P: copies the model's P into p[1] (an EffectAdaptFn), and starts r at 0.
template <double Params::*P>
void adapt_base(double* p, const Params& m) {
    p[1] = m.*P;
}
template <double Params::*P>
void start_base(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt_base<P>(p, *c.model);
}
// Its registry row: r [1/s] fitted alone from 0, then P (`name`, `unit`, copied; default A1's), then t0 [s],
// the record's start (the fit sets it).
template <double Params::*P>
EffectLaw base_drift_law(const char* id, const char* meaning, const char* name, const char* unit, double a1_value, EffectForceFn force,
                         EffectDescribeFn describe, unsigned needs = 0) {
    EffectLaw l{id, meaning, {"r", name, "t0", nullptr}, {"1/s", unit, "s", nullptr}, {0.0, a1_value, 0.0}, force};
    l.fit = hint({0}, {1e-5});
    l.fit.needs = needs;
    l.describe = describe;
    l.start = start_base<P>;
    l.adapt = adapt_base<P>;
    return l;
}

}  // namespace impactlab::effects
