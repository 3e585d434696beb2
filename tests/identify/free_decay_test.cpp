// A free decay as a user records it: t and x only, no forcing column. It is read as a free run (u = 0), its
// gain is no parameter, and the base parameters refined on the free run, which the held-out tail prefers,
// are what the final gate keeps: the equation-error fit, biased by the smoothed acceleration, is the
// reference there only in-sample and must not undo a model whose trajectories are at the noise.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"

namespace id = impactlab::identify;

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kK = (kTwoPi * 13.0) * (kTwoPi * 13.0);   // [1/s^2] per unit mass
constexpr double kA3 = 4e6;                                // [1/(m^2 s^2)]
constexpr double kC = 0.8;                                 // [1/s]

// A Duffing oscillator's free decay from x0 (at rest), simulated by the core and sampled with white noise.
struct Decay {
    double k, a3, c, extent, duration, rate, noise, x0;
    unsigned seed;
};

id::MeasuredData decay(const Decay& g) {
    id::Model truth = id::resolve_fit_model("duffing", id::Forcing::Input);
    truth.p.k = g.k;
    truth.p.a[1] = g.a3;
    truth.p.c = g.c;
    truth.p.x_extent = g.extent;
    id::SynthOptions so;
    so.duration = g.duration;
    so.rate = g.rate;
    so.noise = g.noise;
    so.quantum = 0.0;
    so.x0 = g.x0;
    so.v0 = 0.0;
    so.seed = g.seed;
    so.input.assign(static_cast<std::size_t>(std::lround(g.duration * g.rate)) + 1, 0.0);
    so.input_dt = 1.0 / so.rate;
    return id::synthesize(truth, so);
}

// The loop as `impactlab fit REC --model duffing` runs it, without plots.
id::FitReport fit_duffing(const id::MeasuredData& d) {
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    return id::run_fit(d, id::resolve_fit_model("duffing", id::Forcing::Input), fo);
}

// 4 s at 1 kHz from 6 mm, 5 um of noise, written as a two-column CSV in mm and ms.
std::string decay_csv() {
    const id::MeasuredData d = decay({kK, kA3, kC, 0.012, 4.0, 1000.0, 5e-6, 6e-3, 3});
    std::string csv = "time_ms,disp_mm\n";
    char buf[64];
    for (std::size_t i = 0; i < d.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.6f,%.9f\n", d.t[i] * 1e3, d.x[i] * 1e3);
        csv += buf;
    }
    return csv;
}

// Every pair reported as unseparated pins its combination far better than either value alone.
void pinned_better_than_alone(const id::FitReport& r) {
    for (const auto& u : r.unseparated) {
        double rel_min = INFINITY;
        for (const auto& b : r.base_estimates)
            if (b.name == u.a || b.name == u.b) rel_min = std::min(rel_min, b.sigma / std::abs(b.value));
        CHECK(u.sigma / std::abs(u.value) < 0.5 * rel_min);
    }
}


// x = x_off + 3 cos(60 t) exp(-t) in data units, 2 s at 1 kHz (a linear spring; noise `noise`, seeded).
id::MeasuredData linear_decay(double x_off, double noise, const char* name) {
    std::string csv = "t,x\n";
    char buf[64];
    unsigned s = 12345;
    for (int i = 0; i < 2000; ++i) {
        const double t = i * 1e-3;
        double e = 0;   // a sum of 12 uniforms: near-normal noise without <random>'s distributions, which differ by library
        for (int k = 0; k < 12; ++k) {
            s = s * 1664525u + 1013904223u;
            e += static_cast<double>(s >> 8) / 16777216.0;
        }
        std::snprintf(buf, sizeof buf, "%.4f,%.6f\n", t, x_off + 3.0 * std::cos(60.0 * t) * std::exp(-t) + noise * (e - 6.0));
        csv += buf;
    }
    return id::parse_measured(csv, name, {});
}

double sigma_of(const id::FitReport& r, const char* name) {
    for (const auto& b : r.base_estimates)
        if (b.name == name) return b.sigma;
    return 0.0;
}

}  // namespace

TEST_CASE("fit: a free decay in mm and ms, no forcing column, keeps the refinement its trajectories prefer") {
    id::LoadOptions lo;
    lo.columns.t = "time_ms";
    lo.columns.x = "disp_mm";
    lo.t_scale = 1e-3;
    lo.x_scale = 1e-3;
    const id::MeasuredData d = id::parse_measured(decay_csv(), "decay.csv", lo);
    REQUIRE(d.free_run);
    const id::FitReport r = fit_duffing(d);
    for (const auto& n : r.notes) MESSAGE(n);
    for (const auto& g : r.gate) MESSAGE(g);
    double sk = 0, sa3 = 0;
    for (const auto& b : r.base_estimates) {
        CHECK(b.name != "gain");   // nothing drove the record: no gain to write
        if (b.name == "k") sk = b.sigma;
        if (b.name == "a3") sa3 = b.sigma;
    }
    REQUIRE(sk > 0);
    REQUIRE(sa3 > 0);
    CHECK(r.gate.empty());   // nothing undone
    // The written model: the truth within two of its standard errors (the equation error's k lies 2.7 of them
    // low), its free run 10 times closer than the equation-error fit's, 10 periods shot to the noise.
    CHECK(std::abs(r.after.p.k - kK) < 2.0 * sk);
    CHECK(std::abs(r.after.p.a[1] - kA3) < 2.0 * sa3);
    CHECK(r.error_after.simulation_rms_m < 0.25 * r.error_before.simulation_rms_m);
    CHECK(r.error_after.shooting_rms_10_m < 2.5 * r.sigma_x);
}

TEST_CASE("fit: a free decay is never judged chaotic, however its hardening spring parts its returns") {
    // Strain units, 36.5 -> 41.6 Hz over the decay: returns at other amplitudes part within 1.4 periods.
    const id::FitReport r = fit_duffing(decay({(kTwoPi * 36.5) * (kTwoPi * 36.5), 5.2e11, 1.4, 1e-3, 3.0, 2000.0, 4e-7, 2e-4, 7}));
    CHECK(r.data_regular);
    CHECK(r.data_free_run);
    CHECK_FALSE(r.past_horizon(10.0));
    bool said = false;
    for (const auto& n : r.notes) {
        CHECK(n.find("chaotic (its returns part") == std::string::npos);
        said = said || n.find("a free run (no input)") != std::string::npos;
    }
    CHECK(said);
}

TEST_CASE("fit: a decay far from the sensor's zero is fitted about its own centre; no phantom well at the zero") {
    // 500 data units from the zero and 3 wide: a cubic about the zero once wrote k = -1800 and a well the mirror
    // image away. The spring is centred on the record (x0, fitted), and the answer is the record's 500 units
    // nearer: the same k, a3 = 0 within its error, the well's frequency pinned.
    const id::FitReport r = fit_duffing(linear_decay(500.0, 0.005, "offset.csv"));
    const id::FitReport r0 = fit_duffing(linear_decay(0.0, 0.005, "centred.csv"));
    for (const auto& n : r.notes) MESSAGE(n);
    pinned_better_than_alone(r);
    REQUIRE_FALSE(r.data_wells.empty());
    CHECK(std::abs(r.data_wells.front().omega - std::sqrt(3601.0 - 1.0)) < 3.0 * r.data_wells.front().somega);   // damped
    CHECK(r.well_frequency.find("not identifiable") == std::string::npos);
    CHECK(r.well_frequency.find("steady forcing") == std::string::npos);
    const double sk = sigma_of(r, "k"), sa3 = sigma_of(r, "a3"), sx0 = sigma_of(r, "x0");
    REQUIRE(sk > 0);
    REQUIRE(sa3 > 0);
    REQUIRE(sx0 > 0);
    CHECK(r.after.p.k > 0);   // one well, where the record is
    CHECK(std::abs(r.after.p.k - 3601.0) < 3.0 * sk);   // 60^2 + 1 (the damping's 1/s)
    CHECK(std::abs(r.after.p.a[1]) < 3.0 * sa3);
    CHECK(std::abs(r.after.sensor_offset() - 500.0) < 3.0 * sx0 + 1e-3);
    // Metamorphic: the same decay about zero gives the same spring (the model's origin moved with the record).
    CHECK(std::abs(r.after.p.k - r0.after.p.k) < 3.0 * sk);
    CHECK(std::abs(r.after.p.a[1] - r0.after.p.a[1]) < 3.0 * sa3);
    CHECK(r0.after.sensor_offset() == 0.0);   // a record about its zero keeps the zero
    bool said = false;
    for (const auto& n : r.notes) said = said || n.find("centred on the record") != std::string::npos;
    CHECK(said);
}

TEST_CASE("fit: a double-well rig's decay within one well keeps the zero its own well's asymmetry points to") {
    // Wells at +-8 mm, 4 Hz at the hilltop, the sensor's zero there; from 9.2 mm the decay stays in [6.6, 9.2] mm,
    // far from the zero, but its local even term is the one the symmetric spring has at that well.
    constexpr double kW = kTwoPi * 4.0;
    const id::FitReport r = fit_duffing(decay({-kW * kW, kW * kW / (8e-3 * 8e-3), 0.5, 0.04, 20.0, 500.0, 2e-6, 0.0092, 9}));
    CHECK(r.after.sensor_offset() == 0.0);
    CHECK(std::abs(r.after.p.k + kW * kW) < 3.0 * sigma_of(r, "k"));
    CHECK(std::abs(r.after.p.a[1] - kW * kW / (8e-3 * 8e-3)) < 3.0 * sigma_of(r, "a3"));
}

TEST_CASE("fit: a decay a sixth of its swing off the zero is shifted by a named force, not a generic curve") {
    // x = 0.5 + 3 cos(60 t) exp(-t): a constant force and a sensor offset are the same thing on a linear spring,
    // so the data cannot tell them; a smooth force of x in their place once predicted held-out data
    // thousands of times worse and was kept. One of the two stays, unresolved; the spring is the truth.
    const id::FitReport r = fit_duffing(linear_decay(0.5, 0.005, "offset_small.csv"));
    for (const auto& n : r.notes) MESSAGE(n);
    REQUIRE(r.effects_found.size() == 1);
    const auto& f = r.effects_found.front();
    CHECK((f.id == "constant_force" || f.id == "sensor_offset"));
    CHECK_FALSE(f.not_told_from.empty());   // no finding of which
    CHECK(std::abs(r.after.p.k - 3601.0) < 3.0 * sigma_of(r, "k"));
    CHECK(std::abs(r.after.p.a[1]) < 3.0 * sigma_of(r, "a3"));
    CHECK(r.error_after.shooting_rms_10_m < 2.5 * r.sigma_x);
}

TEST_CASE("fit: a bistable rig's decay across its wells into one, in inches, is judged over its own oscillation") {
    // Wells at +-8 mm, 4 Hz at the hilltop; from 16 mm it crosses 24 times, then settles in the right well. The
    // settling is a step in x whose spectrum once outweighed the oscillation: a 20 s "period", one window.
    constexpr double kW = kTwoPi * 4.0;
    const id::MeasuredData m = decay({-kW * kW, kW * kW / (8e-3 * 8e-3), 0.5, 0.04, 20.0, 500.0, 1e-6, 0.016, 5});
    std::string csv = "t,x_in\n";
    char buf[64];
    for (std::size_t i = 0; i < m.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.4f,%.9f\n", m.t[i], m.x[i] / 0.0254);
        csv += buf;
    }
    id::LoadOptions lo;
    lo.columns.x = "x_in";
    lo.x_scale = 0.0254;
    const id::MeasuredData d = id::parse_measured(csv, "decay_in.csv", lo);
    const id::FitReport r = fit_duffing(d);
    CHECK(r.period_s == doctest::Approx(0.177).epsilon(0.1));   // the well's 5.66 Hz, not the record's length
    CHECK(r.validation_windows >= 20);
    CHECK(std::abs(r.after.p.c - 0.5) < 3.0 * sigma_of(r, "c"));
    CHECK(std::abs(r.after.p.k + kW * kW) < 3.0 * sigma_of(r, "k"));
    CHECK(r.error_after.simulation_rms_m < 3.0 * r.sigma_x);
    pinned_better_than_alone(r);
}
