// The extension impactlab._impactlab: the exception map and the helpers the bindings share.
#include <cstdio>
#include <sstream>

#include "common.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/scan.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::py_binding {

std::string fspath(const py::handle& path) {
    return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

Params model_arg(const py::handle& model) {
    Params p;
    if (py::isinstance<py::str>(model) || py::hasattr(model, "__fspath__")) p = resolve_model(fspath(model));
    else if (py::isinstance<Params>(model)) p = model.cast<Params>();
    else throw py::type_error("model: expected an impactlab.Model, a version name (\"A1H\") or a parameter file (*.json)");
    validate(p, p.name);
    return p;
}

void check_range(const char* command, const char* name, double value, double lo, double hi) {
    if (value >= lo && value <= hi) return;   // NaN fails both
    std::ostringstream msg;
    msg << command << ": " << name << ": " << value << " is outside [" << lo << ", " << hi << "]";
    throw py::value_error(msg.str());
}

void check_range_int(const char* command, const char* name, long value, long lo, long hi) {
    if (value >= lo && value <= hi) return;
    throw py::value_error(std::string(command) + ": " + name + ": " + std::to_string(value) + " is outside [" +
                          std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

void check_start(const Params& p, double x, const char* command, const char* name) {
    if (!p.has_bumper() || !p.rigid() || x <= p.xI) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s: %s: x = %.6g m lies beyond the bumper at xI = %.6g m (%s); start at x <= xI", command,
                  name, x, p.xI, p.name.substr(0, 60).c_str());
    throw py::value_error(buf);
}

void check_rows(const char* command, double rows, const char* names) {
    constexpr double kMaxRows = 5e7;   // the CLI's cap (app/cli/common.hpp)
    if (rows <= kMaxRows) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s: %s asks for %.3g output rows, more than the %.0e an output may have: change one of them",
                  command, names, rows, kMaxRows);
    throw py::value_error(buf);
}

Tolerances tolerances(const char* command, double rtol) {
    check_range(command, "rtol", rtol, 1e-13, 1e-2);
    Tolerances t;
    t.rtol = rtol;
    return t;
}

py::object make_result(const py::dict& columns, const py::dict& extras) {
    return py::module_::import("impactlab._result").attr("Result")(columns, extras);
}

}  // namespace impactlab::py_binding

namespace ipb = impactlab::py_binding;

PYBIND11_MODULE(_impactlab, m) {
    m.doc() = "impactlab's core (simulator, sweeps, analysis, fit) for Python; import impactlab, not this module.";
    // Bad input raises ValueError subclasses carrying the core's (and so the CLI's) messages.
    ipb::py::register_exception<impactlab::ParamError>(m, "ParamError", PyExc_ValueError);
    ipb::py::register_exception<impactlab::identify::DataError>(m, "DataError", PyExc_ValueError);
    ipb::py::register_exception<impactlab::ScanError>(m, "ScanError", PyExc_ValueError);
    ipb::py::register_exception<impactlab::SimulationStalled>(m, "SimulationStalled", PyExc_RuntimeError);
    ipb::bind_model(m);
    ipb::bind_sim(m);
    ipb::bind_analysis(m);
    ipb::bind_fit(m);
}
