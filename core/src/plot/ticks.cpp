// Tick positions on 1-2-5 steps and their labels.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "impactlab/plot.hpp"

namespace impactlab::plot {
namespace {

constexpr double kTol = 1e-9;      // relative to the step
constexpr int kMaxTicks = 1000;

struct Step {
    int mantissa = 0;   // 1, 2 or 5
    int exponent = 0;   // step = mantissa * 10^exponent
    double value = 0;
};

// i * step, computed so that decimal steps give the closest double (3 * 0.1 -> 0.3, not 0.30000000000000004).
double tick_value(double i, const Step& s) {
    if (s.exponent < 0) return i * s.mantissa / std::pow(10.0, -s.exponent);
    return i * s.mantissa * std::pow(10.0, s.exponent);
}

// Index range [first, last] of the multiples of the step inside [lo, hi].
void tick_range(double lo, double hi, double step, double& first, double& last) {
    first = std::ceil(lo / step - kTol);
    last = std::floor(hi / step + kTol);
}

// The smallest nice step giving at most max_count ticks in [lo, hi]; value 0 when none (bad input).
Step choose_step(double lo, double hi, int max_count) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (lo > hi) std::swap(lo, hi);
    const double span = hi - lo;
    if (!(span >= 1e-300) || !std::isfinite(span)) return {};
    const int n = std::clamp(max_count, 1, kMaxTicks);
    const int k0 = static_cast<int>(std::floor(std::log10(span) - std::log10(n))) - 1;
    for (int k = k0; k <= k0 + 4; ++k)
        for (int m : {1, 2, 5}) {
            Step s{m, k, m * std::pow(10.0, k)};
            if (!(s.value > 0) || !std::isfinite(s.value)) continue;
            double first = 0, last = 0;
            tick_range(lo, hi, s.value, first, last);
            if (last - first + 1 <= n) return s;
        }
    return {};   // unreachable for finite input: a step of 10^(k0+4) > 100 span gives at most one tick
}

}  // namespace

double nice_step(double lo, double hi, int max_count) { return choose_step(lo, hi, max_count).value; }

std::vector<double> nice_ticks(double lo, double hi, int max_count) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (lo > hi) std::swap(lo, hi);
    if (lo == hi) return {lo};
    const Step s = choose_step(lo, hi, max_count);
    if (s.value == 0) return {};
    double first = 0, last = 0;
    tick_range(lo, hi, s.value, first, last);
    std::vector<double> ticks;
    for (double i = first; i <= last; i += 1) {
        double v = tick_value(i, s);
        if (std::abs(v) < kTol * s.value) v = 0.0;   // also turns -0 into 0
        ticks.push_back(v);
    }
    return ticks;
}

std::vector<std::string> format_ticks(const std::vector<double>& ticks, double step) {
    double maxabs = 0;
    for (double v : ticks)
        if (std::isfinite(v)) maxabs = std::max(maxabs, std::abs(v));
    if (!(step > 0) || !std::isfinite(step)) step = maxabs > 0 ? maxabs : 1.0;
    if (maxabs < kTol * step) maxabs = 0;   // only (rounded) zeros
    const int k = static_cast<int>(std::floor(std::log10(step) + 1e-9));
    const bool sci = maxabs >= 1e5 || (maxabs > 0 && maxabs < 1e-2);

    std::vector<std::string> out;
    out.reserve(ticks.size());
    char buf[64];
    for (double v : ticks) {
        if (!std::isfinite(v)) {
            out.emplace_back(std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
            continue;
        }
        if (std::abs(v) < kTol * step) v = 0.0;
        if (!sci) {
            std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -k), v);
        } else if (v == 0.0) {
            std::snprintf(buf, sizeof buf, "0");
        } else {
            int e = static_cast<int>(std::floor(std::log10(std::abs(v))));
            for (int attempt = 0; attempt < 2; ++attempt) {
                const int decimals = std::clamp(e - k, 0, 15);
                std::snprintf(buf, sizeof buf, "%.*f", decimals, v / std::pow(10.0, e));
                if (std::abs(std::atof(buf)) < 10.0) break;
                ++e;   // the mantissa rounded up to 10
            }
            std::string mant(buf);
            if (mant.find('.') != std::string::npos) {
                while (mant.back() == '0') mant.pop_back();
                if (mant.back() == '.') mant.pop_back();
            }
            std::snprintf(buf, sizeof buf, "%se%d", mant.c_str(), e);
        }
        std::string s(buf);
        // No "-0", "-0.00": a negative sign in front of nothing but zeros goes.
        if (s.front() == '-' && s.find_first_not_of("0.", 1) == std::string::npos) s.erase(0, 1);
        out.push_back(std::move(s));
    }
    return out;
}

}  // namespace impactlab::plot
