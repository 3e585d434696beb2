// The wells of a fitted model, left against right: what several runs of one rig make identifiable.
#include <algorithm>
#include <cmath>

#include "identify/internal.hpp"
#include "impactlab/equilibria.hpp"
#include "impactlab/forces.hpp"

namespace impactlab::identify::detail {

namespace {

// Restoring force R(x) = F_SA(x) - (effects at v = 0, averaged over the forcing phase) [N]: the static
// force law whose zeros are the equilibria.
double restoring(const Model& m, double x) {
    double R = spring_magnet(m.p, x).F;
    constexpr int kPhases = 8;
    for (const auto& e : m.p.effects) {
        double F = 0;
        for (int k = 0; k < kPhases; ++k) {
            const ForceContext c{0.0, x, 0.0, kTwoPi * k / kPhases, 0.0, 0.0, m.p.m0e, m.p.xI};
            F += e.law->force(e.p.data(), c).F;
        }
        R -= F / kPhases;
    }
    return R;
}

struct Shape {
    std::vector<double> wells, depth, omega;
    double hill = kNaN;
};

// Equilibria on [lo, hi] by a fine scan and bisection; depth by Simpson on R between well and hill.
Shape shape(const Model& m, double lo, double hi) {
    Shape s;
    constexpr int kGrid = 4000;
    std::vector<double> roots;
    std::vector<bool> stable;
    for (const Equilibrium& e : equilibria([&](double x) { return restoring(m, x); }, lo, hi, kGrid)) {
        roots.push_back(e.x);
        stable.push_back(e.stable);
    }
    auto integral = [&](double a, double b) {   // int_a^b R dx, Simpson
        constexpr int kN = 200;
        const double dx = (b - a) / kN;
        double sum = restoring(m, a) + restoring(m, b);
        for (int k = 1; k < kN; ++k) sum += (k % 2 ? 4.0 : 2.0) * restoring(m, a + dx * k);
        return sum * dx / 3.0;
    };
    for (std::size_t k = 0; k < roots.size(); ++k)
        if (!stable[k] && k > 0 && k + 1 < roots.size() && stable[k - 1] && stable[k + 1]) s.hill = roots[k];
    for (std::size_t k = 0; k < roots.size(); ++k) {
        if (!stable[k]) continue;
        const double x = roots[k], dx = 1e-6 * std::max(1.0, std::abs(hi - lo) * 10);
        const double slope = (restoring(m, x + dx) - restoring(m, x - dx)) / (2 * dx);
        s.wells.push_back(x);
        s.omega.push_back(std::sqrt(std::max(0.0, slope / m.p.m)));
        // Depth: the work to climb from the well to the hill (V(hill) - V(well), V' = R).
        s.depth.push_back(std::isfinite(s.hill) ? integral(x, s.hill) : kNaN);
    }
    return s;
}

}  // namespace

WellReport well_report(const Model& m, const std::vector<FoundEffect>& found, const Prep& pr) {
    WellReport w;
    const MeasuredData& d = *pr.data;
    const auto [xmin_it, xmax_it] = std::minmax_element(d.x.begin(), d.x.end());
    const double a = m.true_x(*xmin_it), b = m.true_x(*xmax_it), span = std::max(b - a, 1e-9);
    const double lo = a - 0.5 * span, hi = b + 0.5 * span;
    const Shape s0 = shape(m, lo, hi);
    if (s0.wells.empty()) return w;
    w.hill_x = s0.hill;
    for (std::size_t k = 0; k < s0.wells.size(); ++k) {
        Well e;
        e.x = s0.wells[k];
        e.depth = s0.depth[k];
        e.omega = s0.omega[k];
        e.beyond_bumper = m.bumper() && e.x > m.p.xI;
        w.wells.push_back(e);
    }
    const bool two = s0.wells.size() == 2 && std::isfinite(s0.hill);
    if (two) {
        w.depth_asym = s0.depth[1] - s0.depth[0];
        w.omega_asym = s0.omega[1] - s0.omega[0];
    }
    // Uncertainties: each found effect parameter moved by its standard error, the changes added in squares.
    std::vector<double> vx(w.wells.size(), 0.0), vd(w.wells.size(), 0.0), vo(w.wells.size(), 0.0);
    double vda = 0, voa = 0;
    for (const auto& f : found) {
        for (const auto& [name, sigma] : f.sigma) {
            if (!(sigma > 0) || !std::isfinite(sigma)) continue;
            Model mp = m;
            bool moved = false;
            for (auto& e : mp.p.effects) {
                if (f.id != e.law->id) continue;
                for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i)
                    if (name == e.law->names[i]) {
                        e.p[i] += sigma;
                        moved = true;
                    }
            }
            if (!moved) continue;
            const Shape s1 = shape(mp, lo, hi);
            if (s1.wells.size() != s0.wells.size()) continue;
            for (std::size_t k = 0; k < s0.wells.size(); ++k) {
                vx[k] += std::pow(s1.wells[k] - s0.wells[k], 2);
                if (std::isfinite(s1.depth[k]) && std::isfinite(s0.depth[k])) vd[k] += std::pow(s1.depth[k] - s0.depth[k], 2);
                vo[k] += std::pow(s1.omega[k] - s0.omega[k], 2);
            }
            if (two && std::isfinite(s1.hill)) {
                vda += std::pow((s1.depth[1] - s1.depth[0]) - w.depth_asym, 2);
                voa += std::pow((s1.omega[1] - s1.omega[0]) - w.omega_asym, 2);
            }
        }
    }
    for (std::size_t k = 0; k < w.wells.size(); ++k) {
        w.wells[k].sx = std::sqrt(vx[k]);
        w.wells[k].sdepth = std::sqrt(vd[k]);
        w.wells[k].somega = std::sqrt(vo[k]);
    }
    w.sdepth_asym = std::sqrt(vda);
    w.somega_asym = std::sqrt(voa);
    // Which well each run visits (by the hilltop, in measured coordinates).
    for (std::size_t r = 0; r < pr.run_start.size(); ++r) {
        const std::size_t first = pr.run_start[r], last = pr.run_last(first);
        if (!two) {
            w.run_wells.push_back(s0.wells.size() == 1 ? "the well" : "-");
            continue;
        }
        std::size_t left = 0, right = 0;
        for (std::size_t i = first; i <= last; ++i) (m.true_x(d.x[i]) < s0.hill ? left : right)++;
        const double n = static_cast<double>(last - first + 1);
        w.run_wells.push_back(left > 0.95 * n ? "left" : right > 0.95 * n ? "right" : "both");
    }
    return w;
}

}  // namespace impactlab::identify::detail
