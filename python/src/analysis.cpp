// orbit, continue_, lyapunov, basins, scan: the CLI's analysis commands, as dicts of arrays.
#include <algorithm>
#include <complex>
#include <cstdio>
#include <optional>
#include <sstream>
#include <thread>

#include "common.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/scan.hpp"

namespace impactlab::py_binding {

namespace {

using analysis::ContParam;

// orbit and continue default to the analysis tolerance 1e-10, as the CLI does without --rtol.
Tolerances analysis_tol(const char* command, std::optional<double> rtol) {
    return rtol ? tolerances(command, *rtol) : analysis::analysis_tolerances(1e-10);
}

py::array_t<std::complex<double>> multipliers(const analysis::Floquet& f) {
    std::vector<std::complex<double>> mu(f.mu.begin(), f.mu.end());
    return array_of(mu);
}

py::array_t<double> points2(const std::vector<Vec2>& ys) {
    py::array_t<double> a({static_cast<py::ssize_t>(ys.size()), py::ssize_t{2}});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < ys.size(); ++i) {
        w(static_cast<py::ssize_t>(i), 0) = ys[i][0];
        w(static_cast<py::ssize_t>(i), 1) = ys[i][1];
    }
    return a;
}

py::object orbit(const py::handle& model, double omega, int period, std::optional<std::pair<double, double>> start, double dt,
                 std::optional<double> rtol) {
    const Params p = model_arg(model);
    check_range("orbit", "omega", omega, 1e-2, 1000.0);
    check_range_int("orbit", "period", period, 1, 64);
    check_range("orbit", "dt", dt, 1e-7, 1.0);
    check_rows("orbit", kTwoPi * period / omega / dt, "period x 2 pi / omega / dt");
    const Tolerances tol = analysis_tol("orbit", rtol);
    if (start) check_start(p, start->first, "orbit", "start");
    std::atomic<double> fraction{0.0};
    std::atomic<bool> cancel{false};
    struct Out {
        Vec2 guess;
        analysis::Orbit o;
        std::vector<double> t, x, v, phi;
    };
    Out r = run_long(
        [&] {
            Out out;
            analysis::OrbitOptions opt;
            opt.period = period;
            opt.sim = tol;
            out.guess = start ? Vec2(start->first, start->second)
                              : analysis::settle(p, omega, Vec2(analysis::left_well(p), 0.0), 200, tol);
            out.o = analysis::find_orbit(p, omega, out.guess, opt);
            if (!out.o.converged) return out;
            // The orbit itself, sampled from its section point over k periods (the CLI's orbit.csv).
            Simulator sim(tol);
            const Drive d(omega);
            State s;
            s.x = out.o.y[0];
            s.v = out.o.y[1];
            Simulator::make_consistent(p, d, s);
            UniformSampler sampler(d, dt, 0.0, [&](const Sample& smp) {
                out.t.push_back(smp.t);
                out.x.push_back(smp.x);
                out.v.push_back(smp.v);
                out.phi.push_back(smp.phi);
            });
            sim.advance(p, d, s, d.time_of_phase(kTwoPi * period), &sampler);
            return out;
        },
        fraction, cancel, py::none());
    const analysis::Orbit& o = r.o;
    if (!o.converged) {
        char buf[400];
        std::snprintf(buf, sizeof buf, "orbit: no period-%d orbit found from (%g, %g): %s (residual %.3g)", period, r.guess[0],
                      r.guess[1], o.message.c_str(), o.residual);
        throw py::value_error(buf);
    }
    py::dict cols;
    cols["t"] = array(r.t);
    cols["x"] = array(r.x);
    cols["v"] = array(r.v);
    cols["phi"] = array(r.phi);
    py::dict e;
    e["model"] = p.name;
    e["omega"] = omega;
    e["period"] = period;
    e["section"] = py::make_tuple(o.y[0], o.y[1]);
    e["multipliers"] = multipliers(o.floquet);
    e["stable"] = o.floquet.stable;
    e["monodromy"] = py::make_tuple(py::make_tuple(o.M(0, 0), o.M(0, 1)), py::make_tuple(o.M(1, 0), o.M(1, 1)));
    e["residual"] = o.residual;
    e["iterations"] = o.iterations;
    e["impacts"] = o.impacts;
    e["max_x"] = o.max_x;
    e["sections"] = points2(o.sections);
    return make_result(cols, e);
}

py::object continue_orbits(const py::handle& model, const std::string& param, std::optional<std::pair<double, double>> range,
                           std::optional<double> omega, std::optional<double> start,
                           std::optional<std::pair<double, double>> guess, int period, int max_period,
                           std::optional<double> rtol, const py::object& progress) {
    const Params p = model_arg(model);
    analysis::ContinuationSpec spec;
    if (param == "omega") {
        if (omega) throw py::value_error("continue: omega is the fixed frequency of --param xI or m0e (for omega: range)");
        spec.param = ContParam::Omega;
        spec.lo = range ? range->first : 5.0;
        spec.hi = range ? range->second : 25.0;
        check_range("continue", "range[0]", spec.lo, 0.05, 1000.0);
        check_range("continue", "range[1]", spec.hi, 0.05, 1000.0);
        if (spec.hi <= spec.lo) throw py::value_error("continue: range: the upper end is not above the lower");
        spec.start = start.value_or(spec.lo);
        check_range("continue", "start", spec.start, spec.lo, spec.hi);
    } else if (param == "xI" || param == "m0e") {
        spec.param = param == "xI" ? ContParam::XI : ContParam::M0e;
        if (!omega) throw py::value_error("continue: param " + param + " needs 'omega'");
        if (!range) throw py::value_error("continue: param " + param + " needs 'range' (min, max)");
        spec.omega = *omega;
        check_range("continue", "omega", spec.omega, 1e-2, 1000.0);
        spec.lo = range->first;
        spec.hi = range->second;
        check_range("continue", "range[0]", spec.lo, -0.1, 1.0);
        check_range("continue", "range[1]", spec.hi, -0.1, 1.0);
        if (spec.hi <= spec.lo) throw py::value_error("continue: range: the upper end is not above the lower");
        spec.start = start.value_or(spec.lo);
    } else {
        throw py::value_error("continue: param: '" + param + "' is not one of omega, xI, m0e");
    }
    if (guess) {
        spec.guess = Vec2(guess->first, guess->second);
        check_start(p, guess->first, "continue", "guess");
    }
    check_range_int("continue", "period", period, 1, 64);
    check_range_int("continue", "max_period", max_period, 1, 256);
    spec.period = period;
    spec.max_period = max_period;
    spec.sim = analysis_tol("continue", rtol);
    Progress pr;
    const analysis::ContinuationResult r =
        run_long([&] { return analysis::continue_orbits(p, spec, &pr); }, pr.fraction, pr.cancel, progress);
    if (r.branches.size() == 1 && r.branches[0].points.empty())
        throw py::value_error("continue: no period-" + std::to_string(period) + " orbit to continue: " + r.branches[0].end);
    const char* pname = sweep_param_name(spec.param);
    // branches.csv: branch,<param>,x,v,period,stable; points.csv: kind,<param>,x,v,period (+ precision).
    std::vector<long> bid, bper;
    std::vector<double> bq, bx, bv;
    std::vector<bool> bst;
    for (const auto& b : r.branches)
        for (const auto& q : b.points) {
            bid.push_back(b.id);
            bq.push_back(q.param);
            bx.push_back(q.y[0]);
            bv.push_back(q.y[1]);
            bper.push_back(q.period);
            bst.push_back(q.stable);
        }
    py::dict cols;
    cols["branch"] = array_of(bid);
    cols[pname] = array(bq);
    cols["x"] = array(bx);
    cols["v"] = array(bv);
    cols["period"] = array_of(bper);
    py::array_t<bool> st(static_cast<py::ssize_t>(bst.size()));
    for (std::size_t i = 0; i < bst.size(); ++i) st.mutable_at(static_cast<py::ssize_t>(i)) = bst[i];
    cols["stable"] = st;
    py::list kind;
    std::vector<double> pq, px, pv, prec, mu_exp, speed_exp;
    std::vector<long> pper, pbr;
    py::list scenario;
    for (const auto& q : r.points) {
        kind.append(analysis::bif_kind_name(q.kind));
        pq.push_back(q.param);
        px.push_back(q.y[0]);
        pv.push_back(q.y[1]);
        pper.push_back(q.period);
        pbr.push_back(q.branch);
        prec.push_back(q.precision);
        scenario.append(q.scenario);
        mu_exp.push_back(q.mu_exponent);
        speed_exp.push_back(q.speed_exponent);
    }
    py::dict pcols;
    pcols["kind"] = py::module_::import("numpy").attr("array")(kind);
    pcols[pname] = array(pq);
    pcols["x"] = array(px);
    pcols["v"] = array(pv);
    pcols["period"] = array_of(pper);
    pcols["branch"] = array_of(pbr);
    pcols["precision"] = array(prec);
    pcols["scenario"] = py::module_::import("numpy").attr("array")(scenario);
    pcols["mu_exponent"] = array(mu_exp);
    pcols["speed_exponent"] = array(speed_exp);
    py::list info;
    for (const auto& b : r.branches)
        info.append(py::dict(py::arg("id") = b.id, py::arg("period") = b.period, py::arg("parent") = b.parent,
                             py::arg("points") = b.points.size(), py::arg("end") = b.end));
    py::dict e;
    e["model"] = p.name;
    e["param"] = std::string(pname);
    e["points"] = make_result(pcols, py::dict());
    e["branches"] = info;
    e["seconds"] = r.seconds;
    e["map_evaluations"] = r.map_evaluations;
    return make_result(cols, e);
}

py::object lyapunov(const py::handle& model, std::optional<double> omega, int periods, std::optional<int> transient,
                    std::optional<double> x0, double v0, std::optional<std::string> sweep,
                    std::optional<std::pair<double, double>> range, int steps, int record, double rtol,
                    const py::object& progress) {
    const Params p = model_arg(model);
    const Tolerances tol = tolerances("lyapunov", rtol);
    Progress pr;
    if (sweep) {
        if (*sweep != "up" && *sweep != "down") throw py::value_error("lyapunov: sweep: '" + *sweep + "' is not one of up, down");
        if (omega || x0) throw py::value_error("lyapunov: omega and x0 are for one omega, not with sweep");
        CfSpec spec;
        check_range_int("lyapunov", "steps", steps, 1, 100000);
        spec.steps = steps;
        spec.omega_min = range ? range->first : 25.0 / steps;
        spec.omega_max = range ? range->second : spec.omega_max;
        check_range("lyapunov", "range[0]", spec.omega_min, 1e-3, 1000.0);
        check_range("lyapunov", "range[1]", spec.omega_max, 1e-3, 1000.0);
        if (spec.omega_max < spec.omega_min) throw py::value_error("lyapunov: range: the upper end is below the lower");
        spec.transient = transient.value_or(spec.transient);
        check_range_int("lyapunov", "transient", spec.transient, 0, 1000000);
        check_range_int("lyapunov", "record", record, 1, 1000000);
        spec.record = record;
        spec.direction = *sweep == "up" ? SweepDirection::Up : SweepDirection::Down;
        const auto pts = run_long([&] { return analysis::lyapunov_sweep(p, spec, &pr, tol); }, pr.fraction, pr.cancel, progress);
        std::vector<double> w, lmax, lmin;
        std::vector<long> per;
        for (const auto& q : pts) {
            w.push_back(q.omega);
            lmax.push_back(q.lambda_max);
            lmin.push_back(q.lambda_min);
            per.push_back(q.period);
        }
        py::dict cols;
        cols["omega"] = array(w);
        cols["lambda_max"] = array(lmax);
        cols["lambda_min"] = array(lmin);
        cols["period"] = array_of(per);
        return make_result(cols, py::dict(py::arg("model") = p.name));
    }
    if (!omega) throw py::value_error("lyapunov: missing 'omega' (or 'sweep')");
    check_range("lyapunov", "omega", *omega, 1e-2, 1000.0);
    check_range_int("lyapunov", "periods", periods, 1, 100000000);
    const int tr = transient.value_or(100);
    check_range_int("lyapunov", "transient", tr, 0, 100000000);
    State s;
    s.x = x0.value_or(analysis::left_well(p));
    check_range("lyapunov", "x0", s.x, -0.1, 0.1);
    check_start(p, s.x, "lyapunov", "x0");
    check_range("lyapunov", "v0", v0, -10.0, 10.0);
    s.v = v0;
    const analysis::LyapunovResult r =
        run_long([&] { return analysis::lyapunov(p, *omega, s, tr, periods, tol, &pr); }, pr.fraction, pr.cancel, progress);
    py::dict out;
    out["lambda_max"] = r.lambda_max;
    out["lambda_min"] = r.lambda_min;
    out["seconds"] = r.seconds;
    out["sections"] = points2(r.sections);
    return out;
}

py::object basins(const py::handle& model, double omega, int grid, std::optional<std::pair<double, double>> x_range,
                  std::optional<std::pair<double, double>> v_range, std::optional<int> transient, std::optional<int> periods,
                  std::optional<int> max_period, int threads, std::optional<double> rtol, const py::object& progress) {
    const Params p = model_arg(model);
    analysis::BasinSpec spec;
    check_range("basins", "omega", omega, 1e-2, 1000.0);
    check_range_int("basins", "grid", grid, 1, 4000);
    spec.omega = omega;
    spec.nx = spec.nv = grid;
    analysis::set_default_window(p, spec);
    if (x_range) std::tie(spec.x_min, spec.x_max) = *x_range;
    if (v_range) std::tie(spec.v_min, spec.v_max) = *v_range;
    check_start(p, spec.x_max, "basins", "x_range (its upper end)");
    spec.transient = transient.value_or(spec.transient);
    spec.periods = periods.value_or(spec.periods);
    spec.max_period = max_period.value_or(spec.max_period);
    check_range_int("basins", "transient", spec.transient, 0, 1000000);
    check_range_int("basins", "periods", spec.periods, 1, 1000000);
    check_range_int("basins", "max_period", spec.max_period, 1, 256);
    check_range_int("basins", "threads", threads, 0, 1024);
    spec.threads = threads;
    if (rtol) spec.sim = tolerances("basins", *rtol);
    Progress pr;
    const analysis::BasinResult r =
        run_long([&] { return analysis::compute_basins(p, spec, &pr); }, pr.fraction, pr.cancel, progress);
    // x0,v0,label with x fastest, as the CLI's basins.csv.
    std::vector<double> x0, v0;
    for (int j = 0; j < spec.nv; ++j)
        for (int i = 0; i < spec.nx; ++i) {
            x0.push_back(r.x0(i));
            v0.push_back(r.v0(j));
        }
    py::dict cols;
    cols["x0"] = array(x0);
    cols["v0"] = array(v0);
    cols["label"] = array_of(r.label);
    py::list atts;
    for (const auto& a : r.attractors)
        atts.append(py::dict(py::arg("id") = a.id, py::arg("kind") = analysis::attractor_kind_name(a.kind),
                             py::arg("period") = a.period, py::arg("well") = a.well, py::arg("points") = points2(a.points),
                             py::arg("cells") = a.cells, py::arg("mean_periods") = a.mean_periods));
    py::dict e;
    e["model"] = p.name;
    e["attractors"] = atts;
    e["shape"] = py::make_tuple(spec.nv, spec.nx);
    e["threads"] = r.threads;
    e["seconds"] = r.seconds;
    return make_result(cols, e);
}

ScanAxis axis_arg(const py::handle& h, const char* name) {
    std::string spec;
    if (py::isinstance<py::str>(h)) {
        spec = h.cast<std::string>();
    } else {
        const auto t = h.cast<std::tuple<std::string, double, double, int>>();
        std::ostringstream s;
        s.precision(17);
        s << std::get<0>(t) << ':' << std::get<1>(t) << ':' << std::get<2>(t) << ':' << std::get<3>(t);
        spec = s.str();
    }
    try {
        return parse_scan_axis(spec);
    } catch (const ScanError& e) {
        throw ScanError(std::string("scan: ") + name + ": " + e.what());
    }
}

py::object scan(const py::handle& model, const py::handle& x, const py::handle& y, const std::string& measures,
                const std::string& start, std::optional<double> omega, int transient, int record, int threads, double rtol,
                const py::object& progress) {
    const Params p = model_arg(model);
    ScanSpec spec;
    spec.x = axis_arg(x, "x");
    spec.y = axis_arg(y, "y");
    if (spec.x.param == spec.y.param) throw py::value_error("scan: x and y vary the same parameter");
    check_rows("scan", static_cast<double>(spec.x.n) * spec.y.n, "x N x y N");
    try {
        spec.measures = parse_scan_measures(measures);
    } catch (const ScanError& e) {
        throw ScanError(std::string("scan: measures: ") + e.what());
    }
    const bool omega_axis = spec.x.param == ScanParam::Omega || spec.y.param == ScanParam::Omega;
    if (!omega_axis && !omega) throw py::value_error("scan: neither axis is omega: give omega");
    if (omega_axis && omega) throw py::value_error("scan: omega is an axis already");
    if (omega) check_range("scan", "omega", *omega, 1e-3, 1000.0);
    spec.omega = omega.value_or(0.0);
    if (start != "continue" && start != "fresh") throw py::value_error("scan: start: '" + start + "' is not continue or fresh");
    spec.start = start == "continue" ? ScanStart::Continue : ScanStart::Fresh;
    check_range_int("scan", "transient", transient, 0, 1000000);
    check_range_int("scan", "record", record, 1, 1000000);
    check_range_int("scan", "threads", threads, 0, 1024);
    spec.transient = transient;
    spec.record = record;
    for (int j : {0, spec.y.n - 1})   // every parameter of the plane must be one the model accepts: its corners
        for (int i : {0, spec.x.n - 1}) {
            Params q = p;
            for (const ScanAxis* ax : {&spec.x, &spec.y}) {
                const double v = ax->at(ax == &spec.x ? i : j);
                if (ax->param == ScanParam::XI) q.xI = v;
                if (ax->param == ScanParam::M0e) q.m0e = v;
            }
            validate(q, "scan plane corner");
        }
    const Tolerances tol = tolerances("scan", rtol);
    const int nthreads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    Progress pr;
    const auto rows = run_long(
        [&] {
            std::vector<std::vector<ScanPoint>> out(static_cast<std::size_t>(spec.y.n));
            std::vector<int> todo;
            for (int j = 0; j < spec.y.n; ++j) todo.push_back(j);
            scan_rows(p, spec, todo, nthreads, &pr, tol,
                      [&](int row, const std::vector<ScanPoint>& pts) { out[static_cast<std::size_t>(row)] = pts; });
            return out;
        },
        pr.fraction, pr.cancel, progress);
    // The CLI's CSV as columns: the same writer, read back (its numbers round-trip exactly).
    std::ostringstream csv;
    write_scan_csv(spec, rows, csv);
    std::istringstream in(csv.str());
    std::string line;
    std::getline(in, line);
    std::vector<std::string> names;
    for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
    std::vector<std::vector<double>> values(names.size());
    while (std::getline(in, line)) {
        std::istringstream r(line);
        std::string field;
        for (std::size_t c = 0; c < names.size() && std::getline(r, field, ','); ++c) values[c].push_back(std::stod(field));
    }
    py::dict cols;
    for (std::size_t c = 0; c < names.size(); ++c) cols[py::str(names[c])] = array(values[c]);
    py::dict e;
    e["model"] = p.name;
    e["shape"] = py::make_tuple(spec.y.n, spec.x.n);
    e["threads"] = nthreads;
    return make_result(cols, e);
}

}  // namespace

void bind_analysis(py::module_& m) {
    using namespace pybind11::literals;
    m.def("orbit", &orbit, "model"_a, "omega"_a, "period"_a = 1, py::kw_only(), "start"_a = py::none(), "dt"_a = 1e-3,
          "rtol"_a = py::none(),
          R"(A period-k orbit by Newton on the k-th Poincare map with its Floquet multipliers: `impactlab orbit`.
start: (x [m], v [m/s]) for Newton (default: settled for 200 periods from the left well's bottom). rtol defaults to
1e-10. Columns t, x, v, phi (the orbit over k periods, every dt [s]); attributes section (x, v), multipliers
(complex, largest first), stable, monodromy, residual, iterations, impacts, max_x, sections. No orbit: ValueError.)");
    m.def("continue_", &continue_orbits, "model"_a, py::kw_only(), "param"_a = "omega", "range"_a = py::none(),
          "omega"_a = py::none(), "start"_a = py::none(), "guess"_a = py::none(), "period"_a = 1, "max_period"_a = 8,
          "rtol"_a = py::none(), "progress"_a = py::none(),
          R"(Pseudo-arclength continuation of periodic orbits with fold, period-doubling, Neimark-Sacker and grazing
points: `impactlab continue`. param "omega" (range (min, max) [rad/s], default (5, 25); start the value to start
at) or "xI" / "m0e" at the fixed omega. guess: (x, v) of the first orbit. Columns as branches.csv: branch, the
parameter, x, v, period, stable; attribute points (a Result as points.csv: kind, the parameter, x, v, period,
branch, precision, scenario, ...) and branches (id, period, parent, points, end).)");
    m.def("lyapunov", &lyapunov, "model"_a, "omega"_a = py::none(), py::kw_only(), "periods"_a = 500, "transient"_a = py::none(),
          "x0"_a = py::none(), "v0"_a = 0.0, "sweep"_a = py::none(), "range"_a = py::none(), "steps"_a = 300, "record"_a = 70,
          "rtol"_a = 1e-8, "progress"_a = py::none(),
          R"(Lyapunov exponents (Benettin, tangent with saltation): `impactlab lyapunov`. At one omega: a dict
lambda_max, lambda_min [1/s], seconds, sections (transient default 100 periods, x0 default the left well).
With sweep="up" or "down": along the CF sweep over range (default (25/steps, 25)), a Result with columns omega,
lambda_max, lambda_min, period (transient default 20).)");
    m.def("basins", &basins, "model"_a, "omega"_a, py::kw_only(), "grid"_a = 200, "x_range"_a = py::none(),
          "v_range"_a = py::none(), "transient"_a = py::none(), "periods"_a = py::none(), "max_period"_a = py::none(),
          "threads"_a = 0, "rtol"_a = py::none(), "progress"_a = py::none(),
          R"(Basins of attraction on a grid x grid of starts (x0, v0) at t = 0: `impactlab basins`. threads: 0 for all
cores (the labels do not depend on it). Columns x0, v0, label (x fastest, as basins.csv; label.reshape(shape) is
the image); attributes attractors (id, kind, period, well, points, cells), shape (nv, nx).)");
    m.def("scan", &scan, "model"_a, "x"_a, "y"_a, py::kw_only(), "measures"_a = "period", "start"_a = "continue",
          "omega"_a = py::none(), "transient"_a = 20, "record"_a = 70, "threads"_a = 0, "rtol"_a = 1e-8,
          "progress"_a = py::none(),
          R"(A parameter plane: `impactlab scan`. x, y: "omega:6:25:190" or ("xI", -0.01, 0.01, 80); each row (fixed y) a
CF sweep along x (start="continue") or each point from rest ("fresh"). measures: "period,lyapunov,impacts,xrange".
Columns as the CLI's CSV (the axes' names, then period, lyapunov, impacts, xmin, xmax as asked), x fastest, the
same numbers bit for bit whatever `threads` (0: all cores); attribute shape (ny, nx).)");
}

}  // namespace impactlab::py_binding
