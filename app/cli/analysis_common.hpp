// What the analysis commands (orbit, continue, lyapunov, basins) share: their help's ending, the tighter
// integrator they default to, and the printing of a Floquet multiplier.
#pragma once

#include <array>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "args.hpp"
#include "common.hpp"
#include "impactlab/analysis.hpp"

namespace impactlab::cli {

// Every analysis command takes the model flags: its help ends with them.
inline bool wants_help(const std::vector<std::string>& args, const char* text) { return show_help_if_asked(args, text, kModelHelp); }
// orbit and continue default to analysis_tol's 1e-10, not the shared help's 1e-8: their help says so.
inline bool wants_help_tight(const std::vector<std::string>& args, const char* text) {
    if (!show_help_if_asked(args, text, kModelHelp)) return false;
    std::printf("  (--rtol: default 1e-10 here: Newton and the monodromy need the map smooth far below the orbit tolerance)\n");
    return true;
}

// The analysis needs a tighter integrator than a sweep: --rtol given wins, else 1e-10.
inline Tolerances analysis_tol(const Args& a) {
    return a.has("--rtol") ? tolerances_from(a) : analysis::analysis_tolerances(1e-10);
}

inline Vec2 to_vec2(const std::array<double, 2>& y) { return {y[0], y[1]}; }

inline std::string fmt_mu(const std::complex<double>& m) {
    char buf[96];
    if (std::abs(m.imag()) < 1e-12) std::snprintf(buf, sizeof buf, "%.8g", m.real());
    else std::snprintf(buf, sizeof buf, "%.8g%+.8gi (|mu| = %.8g)", m.real(), m.imag(), std::abs(m));
    return buf;
}

}  // namespace impactlab::cli
