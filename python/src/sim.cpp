// simulate, poincare, bifurcation: the CLI's commands of the same names, as dicts of arrays.
#include <cmath>
#include <optional>

#include "common.hpp"
#include "impactlab/drive.hpp"
#include "impactlab/identify_data.hpp"
#include "impactlab/simulator.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::py_binding {

namespace {

py::object simulate(const py::handle& model, std::optional<double> omega_arg, std::optional<double> duration_arg,
                    std::optional<double> dt_arg, double x0, double v0, double rtol, const py::object& input,
                    const std::string& u_col, double u_scale, const py::object& progress) {
    const Params p = model_arg(model);
    // An input-forced run (the CLI's --input): the record's u drives the model through its input_gain; then
    // omega defaults to 0 and the duration and step to the record's.
    std::optional<identify::MeasuredData> rec;
    double in_dt = 0;
    if (!input.is_none()) {
        identify::LoadOptions lo;
        lo.columns.u = u_col;
        lo.u_scale = u_scale;
        lo.min_samples = 2;
        rec = identify::load_measured(fspath(input), lo);
        if (!rec->has_u()) throw py::value_error("simulate: input: " + rec->source + " has no input column u (map one with u_col)");
        in_dt = (rec->t.back() - rec->t.front()) / static_cast<double>(rec->size() - 1);
    } else if (!u_col.empty() || u_scale != 1.0) {
        throw py::value_error("simulate: u_col and u_scale need input");
    }
    if (!omega_arg && !rec) throw py::value_error("simulate: missing 'omega'");
    if (!duration_arg && !rec) throw py::value_error("simulate: missing 'duration'");
    const double omega = omega_arg.value_or(0.0);
    const double duration = duration_arg.value_or(in_dt * static_cast<double>(rec ? rec->size() - 1 : 0));
    const double dt = dt_arg.value_or(rec ? in_dt : 1e-3);
    check_range("simulate", "omega", omega, 0.0, 1000.0);
    check_range("simulate", "duration", duration, 1e-6, 1e6);
    check_range("simulate", "dt", dt, 1e-7, 1e3);
    check_range("simulate", "x0", x0, -0.1, 0.1);
    check_range("simulate", "v0", v0, -10.0, 10.0);
    check_rows("simulate", duration / dt, "duration / dt");
    check_start(p, x0, "simulate", "x0");
    const Tolerances tol = tolerances("simulate", rtol);
    struct Out {
        std::vector<double> t, x, v, phi;
        std::vector<int> regime;
        State s;
    };
    Progress pr;
    Out r = run_long(
        [&] {
            Out o;
            o.s.x = x0;
            o.s.v = v0;
            Drive d(omega);
            if (rec) d.set_input(0.0, in_dt, rec->u);
            simulate_sampled(p, d, o.s, duration, dt, tol, &pr, [&](const Sample& smp) {
                o.t.push_back(smp.t);
                o.x.push_back(smp.x);
                o.v.push_back(smp.v);
                o.phi.push_back(rec ? d.input(smp.t) : smp.phi);
                o.regime.push_back(static_cast<int>(smp.regime));
            });
            return o;
        },
        pr.fraction, pr.cancel, progress);
    py::dict cols;
    cols["t"] = array(r.t);
    cols["x"] = array(r.x);
    cols["v"] = array(r.v);
    cols[rec ? "u" : "phi"] = array(r.phi);
    cols["regime"] = array_of(r.regime);
    py::dict extras;
    extras["model"] = p.name;
    extras["steps"] = r.s.steps;
    extras["impacts"] = r.s.impacts;
    extras["state"] = py::make_tuple(r.s.t, r.s.x, r.s.v);
    return make_result(cols, extras);
}

py::object poincare(const py::handle& model, double omega, int periods, int transient, double phi0, double x0, double v0,
                    double rtol, const py::object& progress) {
    const Params p = model_arg(model);
    check_range("poincare", "omega", omega, 1e-3, 1000.0);
    check_range_int("poincare", "periods", periods, 1, 10000000);
    check_range_int("poincare", "transient", transient, 0, 10000000);
    check_range("poincare", "phi0", phi0, 0.0, kTwoPi);
    check_range("poincare", "x0", x0, -0.1, 0.1);
    check_range("poincare", "v0", v0, -10.0, 10.0);
    check_start(p, x0, "poincare", "x0");
    const Tolerances tol = tolerances("poincare", rtol);
    Progress pr;
    const auto pts = run_long(
        [&] {
            State s;
            s.x = x0;
            s.v = v0;
            return poincare_section(p, omega, periods, transient, s, tol, &pr, phi0);
        },
        pr.fraction, pr.cancel, progress);
    std::vector<long> n;
    std::vector<double> x, v, t;
    for (const auto& sp : pts) {
        n.push_back(static_cast<long>(sp.n - transient));
        x.push_back(sp.x);
        v.push_back(sp.v);
        t.push_back(sp.t);
    }
    py::dict cols;
    cols["n"] = array_of(n);
    cols["x"] = array(x);
    cols["v"] = array(v);
    py::dict extras;
    extras["t"] = array(t);
    extras["model"] = p.name;
    return make_result(cols, extras);
}

py::object bifurcation(const py::handle& model, const std::string& sweep, const std::string& over,
                       std::optional<std::pair<double, double>> range, std::optional<double> omega, int steps, int transient,
                       int record, double omega_max, double ramp_time, double rtol, int settle, const py::object& progress) {
    const Params p = model_arg(model);
    if (sweep != "up" && sweep != "down" && sweep != "ramp")
        throw py::value_error("bifurcation: sweep: '" + sweep + "' is not one of up, down, ramp");
    const Tolerances tol = tolerances("bifurcation", rtol);
    Progress pr;
    Diagram d;
    if (sweep == "ramp") {
        if (over != "omega" || range || omega)
            throw py::value_error("bifurcation: over, range and omega are for the CF sweeps (up, down), not the ramp");
        if (settle != 10) throw py::value_error("bifurcation: settle is for the CF sweeps (up, down), not the ramp");
        EfSpec spec;
        check_range("bifurcation", "omega_max", omega_max, 0.01, 1000.0);
        check_range("bifurcation", "ramp_time", ramp_time, 1.0, 1e6);
        spec.omega_max = omega_max;
        spec.t_ramp = ramp_time;
        check_rows("bifurcation", spec.omega_max * spec.t_ramp / (2 * kTwoPi), "omega_max x ramp_time / 4 pi");
        d = run_long([&] { return run_ef_ramp(p, spec, &pr, tol); }, pr.fraction, pr.cancel, progress);
    } else {
        ParamSweep s;
        const auto which = parse_sweep_param(over);
        if (!which) throw py::value_error("bifurcation: over: '" + over + "' is not one of omega, xI, m0e");
        s.over = *which;
        s.direction = sweep == "up" ? SweepDirection::Up : SweepDirection::Down;
        check_range_int("bifurcation", "steps", steps, 1, 100000);
        check_range_int("bifurcation", "transient", transient, 0, 1000000);
        check_range_int("bifurcation", "record", record, 1, 1000000);
        s.steps = steps;
        if (s.over == SweepParam::Omega) {
            if (omega) throw py::value_error("bifurcation: omega is the fixed frequency of an xI or m0e sweep; over omega give range");
            s.lo = range ? range->first : 25.0 / steps;
            s.hi = range ? range->second : 25.0;
        } else {
            if (!range) throw py::value_error("bifurcation: over " + over + " needs range=(A, B) [" + sweep_param_unit(s.over) + "]");
            if (!omega) throw py::value_error("bifurcation: over " + over + " needs the fixed forcing frequency omega [rad/s]");
            s.omega = *omega;
            s.lo = range->first;
            s.hi = range->second;
        }
        if (const std::string why = check_sweep(p, s); !why.empty()) throw py::value_error("bifurcation: " + why);
        check_range_int("bifurcation", "settle", settle, 0, 1000);
        check_rows("bifurcation", static_cast<double>(steps) * record, "steps x record");
        d = run_long([&] { return run_cf_param_sweep(p, s, transient, record, &pr, tol, nullptr, settle); }, pr.fraction,
                     pr.cancel, progress);
    }
    std::vector<double> q, x, v, period;
    for (const auto& pt : d.points) {
        q.push_back(pt.omega);
        x.push_back(pt.x);
        v.push_back(pt.v);
    }
    for (const DiagramLevel& lv : d.levels) period.insert(period.end(), lv.count, static_cast<double>(lv.period));
    py::dict cols;
    cols[sweep_param_name(d.over)] = array(q);
    cols["x"] = array(x);
    cols["v"] = array(v);
    if (!d.levels.empty()) cols["period"] = array(period);
    py::dict extras;
    extras["model"] = d.model;
    extras["protocol"] = d.protocol;
    extras["over"] = std::string(sweep_param_name(d.over));
    extras["simulated_seconds"] = d.simulated_seconds;
    extras["steps"] = d.steps;
    extras["impacts"] = d.impacts;
    if (d.over == SweepParam::Omega && sweep != "ramp") {
        const Transitions tr = find_transitions(d);
        py::dict t;
        t["jump"] = tr.jump;
        t["period_doubling"] = tr.period_doubling;
        t["chaos_start"] = tr.chaos_start;
        t["chaos_end"] = tr.chaos_end;
        t["period1_return"] = tr.period1_return;
        t["windows"] = tr.windows;
        extras["transitions"] = t;
    }
    return make_result(cols, extras);
}

}  // namespace

void bind_sim(py::module_& m) {
    using namespace pybind11::literals;
    m.def("simulate", &simulate, "model"_a, "omega"_a = py::none(), "duration"_a = py::none(), py::kw_only(), "dt"_a = py::none(),
          "x0"_a = 0.0, "v0"_a = 0.0, "rtol"_a = 1e-8, "input"_a = py::none(), "u_col"_a = "", "u_scale"_a = 1.0,
          "progress"_a = py::none(),
          R"(One run at constant omega [rad/s] for `duration` [s] from (x0 [m], v0 [m/s]) at rest phase phi = 0,
sampled every dt [s]: `impactlab simulate`. Returns a Result with columns t [s], x [m], v [m/s], phi [rad],
regime (1 free flight, 2 sticking, 3 permanent contact) and attributes steps, impacts, state (t, x, v at the end).
input: a record (CSV, plain or .gz) whose input column u (u_col: its name or 1-based number; u_scale multiplies
it) drives the model by input_gain * u(t), as `simulate --input`: then omega defaults to 0, duration and dt to the
record's; the columns are t, x, v, u, regime.
progress: called with the fraction done (0..1) about every 50 ms. Ctrl-C stops it (KeyboardInterrupt).)");
    m.def("poincare", &poincare, "model"_a, "omega"_a, "periods"_a, py::kw_only(), "transient"_a = 0, "phi0"_a = 0.0, "x0"_a = 0.0,
          "v0"_a = 0.0, "rtol"_a = 1e-8, "progress"_a = py::none(),
          R"(The Poincare section at phi = phi0 + 2 pi k [rad] at constant omega: `impactlab poincare`. `transient`
periods are dropped, then `periods` points recorded. Columns n, x [m], v [m/s]; attribute t (the instants) [s].)");
    m.def("bifurcation", &bifurcation, "model"_a, "sweep"_a = "up", py::kw_only(), "over"_a = "omega", "range"_a = py::none(),
          "omega"_a = py::none(), "steps"_a = 300, "transient"_a = 20, "record"_a = 70, "omega_max"_a = 25.1,
          "ramp_time"_a = 2800.0, "rtol"_a = 1e-8, "settle"_a = 10, "progress"_a = py::none(),
          R"(A bifurcation diagram: `impactlab bifurcation`. sweep "up" or "down" is the CF sweep (each level from the
previous level's final state, `transient` periods dropped and `record` section points kept per level) over
`over` = "omega" (range (min, max) [rad/s], default (25/steps, 25)), "xI" [m] or "m0e" [kg m] (then range and the
fixed omega are required); "ramp" is the EF ramp to omega_max [rad/s] over ramp_time [s]. Columns: the swept
parameter's name (omega, xI or m0e), x [m], v [m/s], and for a CF sweep with settle > 0 (default 10) period: each
level judged by the map's own test, run on up to `settle` more records, its period or -1 (not settled: no period
up to 32, chaos or a longer transient); settle = 0 is the paper's protocol alone. Attributes protocol,
transitions (CF over omega), steps.)");
}

}  // namespace impactlab::py_binding
