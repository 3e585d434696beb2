// fit: impactlab fit on measured records (identify::run_fit), its report as a dict and the model it writes.
#include <optional>

#include "common.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"

namespace impactlab::py_binding {

namespace {

std::vector<std::string> paths_arg(const py::handle& records) {
    std::vector<std::string> paths;
    if (py::isinstance<py::str>(records) || py::hasattr(records, "__fspath__")) paths.push_back(fspath(records));
    else
        for (const auto& r : records) paths.push_back(fspath(r));
    if (paths.empty()) throw py::value_error("fit: no record given");
    return paths;
}

py::object fit(const py::handle& records, const py::handle& model, std::optional<std::string> baseline,
               const std::vector<std::string>& only, const std::vector<std::string>& exclude, int max_effects, bool generic,
               double rtol, double x_highpass, const py::object& report, bool plots, const py::object& progress) {
    const std::vector<std::string> paths = paths_arg(records);
    identify::LoadOptions lo;
    std::vector<identify::MeasuredData> runs;
    for (const auto& p : paths) runs.push_back(identify::load_measured(p, lo));
    const identify::MeasuredData data = identify::join_records(runs);
    const identify::Forcing forcing = identify::forcing_of(data);
    identify::Model m;
    if (py::isinstance<py::str>(model)) {
        m = identify::resolve_fit_model(model.cast<std::string>(), forcing);   // also "duffing"
    } else {
        m.p = model_arg(model);
        m.forcing = forcing;
    }
    if (forcing == identify::Forcing::Input) m.forcing = identify::Forcing::Input;
    identify::FitOptions o;
    const std::string b = baseline.value_or(m.bumper() ? "fixed" : "fit");
    if (b != "fixed" && b != "fit") throw py::value_error("fit: baseline must be 'fixed' or 'fit'");
    o.fit_baseline = b == "fit";
    check_range_int("fit", "max_effects", max_effects, 0, 20);
    o.max_effects = max_effects;
    o.only = only;
    o.exclude = exclude;
    o.generic = generic;
    check_range("fit", "rtol", rtol, 1e-13, 1e-2);
    o.rtol = rtol;
    check_range("fit", "x_highpass", x_highpass, 0.0, 1e9);
    o.x_highpass_hz = x_highpass;
    const std::optional<std::string> dir = report.is_none() ? std::nullopt : std::optional<std::string>(fspath(report));
    o.plots = plots && dir.has_value();
    for (const auto& id : o.only)
        if (!identify::find_catalogue_effect(id)) throw py::value_error("fit: only: unknown effect '" + id + "'");
    for (const auto& id : o.exclude)
        if (!identify::find_catalogue_effect(id)) throw py::value_error("fit: exclude: unknown effect '" + id + "'");
    identify::FitProgress pr;
    const identify::FitReport r =
        run_long([&] { return identify::run_fit(data, m, o, nullptr, &pr); }, pr.fraction, pr.cancel, progress);
    if (dir) identify::write_report(r, *dir, o.plots);
    py::dict out(py::module_::import("json").attr("loads")(identify::report_json_text(r)));
    out["model_before"] = py::cast(r.before.p);
    out["model_after"] = py::cast(r.after.p);
    // What the report's PNGs plot: measured and simulated x(t), and the equation error before and after.
    py::dict trace;
    trace["t"] = array(r.trace.t);
    trace["measured"] = array(r.trace.measured);
    trace["before"] = array(r.trace.before);
    trace["after"] = array(r.trace.after);
    out["trace"] = make_result(trace, py::dict());
    py::dict residual;
    residual["x"] = array(r.residual.x);
    residual["v"] = array(r.residual.v);
    residual["phi"] = array(r.residual.phi);
    residual["before"] = array(r.residual.before);
    residual["after"] = array(r.residual.after);
    out["residual"] = make_result(residual, py::dict());
    return out;
}

}  // namespace

void bind_fit(py::module_& m) {
    using namespace pybind11::literals;
    m.def("fit", &fit, "records"_a, "model"_a = "A1H", py::kw_only(), "baseline"_a = py::none(),
          "only"_a = std::vector<std::string>{}, "exclude"_a = std::vector<std::string>{}, "max_effects"_a = 4, "generic"_a = true,
          "rtol"_a = 1e-8, "x_highpass"_a = 0.0, "report"_a = py::none(), "plots"_a = true, "progress"_a = py::none(),
          R"(Fits the model to measured records: `impactlab fit`. records: a CSV file (plain or .gz, the MODEL.md layout)
or a list of runs of one rig fitted together. model: an impactlab.Model, a version name, a parameter file or
"duffing". baseline: "fixed" (default with a bumper) or "fit". only / exclude: effect ids. x_highpass: the cut [Hz] of
a high-pass the record's x went through (as `--x-highpass`), applied to the model's free runs. report: a directory to
write report.json, report.md, model_after.json (and the PNGs unless plots=False), as the CLI does. Returns the
report as a dict (report.json's keys) with model_before and model_after as impactlab.Model, and trace (t,
measured, before, after: x(t) as the report plots it) and residual (x, v, phi, before, after: the equation
error [N]) as Results.)");
}

}  // namespace impactlab::py_binding
