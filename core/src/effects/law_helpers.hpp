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

}  // namespace impactlab::effects
