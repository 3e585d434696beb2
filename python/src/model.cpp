// impactlab.Model (a parameter set, the core's Params), models() and effects().
#include <string>

#include "common.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab::py_binding {

namespace {

// A setter that leaves the model as it was when the new value is refused (validate's message names the key).
template <class Set>
void set_checked(Params& p, Set&& set) {
    Params q = p;
    set(q);
    validate(q, "Model");
    p = std::move(q);
}

void scalar(py::class_<Params>& c, const char* name, double Params::*field, const char* doc) {
    c.def_property(
        name, [field](const Params& p) { return p.*field; },
        [field](Params& p, double v) { set_checked(p, [&](Params& q) { q.*field = v; }); }, doc);
}

py::dict impact_params(const Params& p) {
    py::dict d;
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i) d[p.impact->names[i]] = p.ip[i];
    return d;
}

}  // namespace

void bind_model(py::module_& m) {
    py::class_<Params> c(m, "Model", R"(A model version: the rig's parameters in SI units (a copy; editing it changes no other).

Model.from_name("A1H") is a version of the paper (stiffness A1 or A3, bumper C, C1, G, H, or none);
Model.from_json(path) reads a parameter file as every --model FILE.json of the CLI does. A value outside its
physical range is refused with the CLI's message (ParamError, a ValueError).)");
    c.def_static("from_name", &make_version, py::arg("name"), "The built-in version NAME (\"A1H\", \"A3C1\", ...); see models().")
        .def_static("from_json", [](const py::object& path) { return load_params(fspath(path)); }, py::arg("path"),
                    "A parameter file (JSON, as `impactlab models --json A1H` writes; \"base\" starts from a version).")
        .def_static("from_json_text", &params_from_json_text, py::arg("text"), py::arg("source") = "text",
                    "A parameter set from JSON text; `source` names it in messages.")
        .def("to_json", &params_to_json_text, "The parameter file's text (Model.from_json_text reads it back).")
        .def("save", [](const Params& p, const py::object& path) { save_params(p, fspath(path)); }, py::arg("path"),
             "Writes the parameter file (whole or not at all).")
        .def("copy", [](const Params& p) { return p; })
        .def("__copy__", [](const Params& p) { return p; })
        .def("__deepcopy__", [](const Params& p, py::dict) { return p; }, py::arg("memo"))
        .def("__eq__", [](const Params& a, const Params& b) { return params_to_json_text(a) == params_to_json_text(b); })
        .def("__repr__", [](const Params& p) { return "impactlab.Model('" + p.name + "')"; })
        .def_readwrite("name", &Params::name, "The model's label (a version name or the user's).")
        .def_property_readonly("stiffness", [](const Params& p) { return p.stiffness_id; }, "The stiffness law's id (A1, A3).")
        .def_property_readonly("impact", [](const Params& p) { return std::string(p.impact->id); },
                               "The impact law's id: C, C1 (compliant Hunt-Crossley), G, H (rigid), none.")
        .def_property_readonly("has_bumper", &Params::has_bumper, "Whether the rail has a bumper at xI.")
        .def_property_readonly("rigid", &Params::rigid, "Whether the bumper is rigid (G, H: event-driven impacts).");
    scalar(c, "m", &Params::m, "Cart mass m [kg].");
    scalar(c, "m0e", &Params::m0e, "Unbalance m0 e [kg m]: the forcing amplitude m0e omega^2.");
    scalar(c, "k", &Params::k, "Mechanical springs' stiffness k [N/m].");
    scalar(c, "c", &Params::c, "Viscous bearing resistance c [N s/m].");
    scalar(c, "T", &Params::T, "Dry rolling resistance T [N].");
    scalar(c, "eps", &Params::eps, "Dry friction's smoothing speed eps [m/s].");
    scalar(c, "xI", &Params::xI, "Bumper position xI [m] (on the rail's travel, |xI| <= 0.1).");
    scalar(c, "input_gain", &Params::input_gain, "Force per unit of a sampled input u(t) [N per unit of u].");
    c.def_property(
         "a", [](const Params& p) { return p.a; },
         [](Params& p, const std::array<double, 4>& v) { set_checked(p, [&](Params& q) { q.a = v; }); },
         "Numerator coefficients of F_SA (a1 [N/m], a3 [N/m^3], a5 [N/m^5], a7 [N/m^7]).")
        .def_property(
            "b", [](const Params& p) { return p.b; },
            [](Params& p, const std::array<double, 4>& v) { set_checked(p, [&](Params& q) { q.b = v; }); },
            "Denominator coefficients of F_SA (b2 [1/m^2], b4 [1/m^4], b6 [1/m^6], b8 [1/m^8]).")
        .def_property_readonly("impact_params", &impact_params,
                               "The impact law's parameters by name (model['kI'] reads and sets one), SI units.")
        .def_property_readonly(
            "effects",
            [](const Params& p) {
                py::list out;
                for (const auto& e : p.effects) {
                    py::dict values;
                    for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i) values[e.law->names[i]] = e.p[i];
                    out.append(py::dict(py::arg("id") = e.law->id, py::arg("params") = values));
                }
                return out;
            },
            "The extra effects (id and parameters) the model carries, e.g. after a fit.")
        .def("__getitem__", [](const Params& p, const std::string& key) { return impact_param(p, key); }, py::arg("key"),
             "An impact-law parameter by name (kI, b, n1, ... for C and C1; kappa0, Ti0, ... for G and H).")
        .def(
            "__setitem__",
            [](Params& p, const std::string& key, double v) { set_checked(p, [&](Params& q) { set_impact_param(q, key, v); }); },
            py::arg("key"), py::arg("value"));

    m.def("models", &version_names, "Every version name XY (stiffness X, impact Y), the paper's five first.");
    m.def(
        "effects",
        [] {
            py::dict out;
            for (const auto& e : effect_laws()) out[e.id] = e.meaning;
            return out;
        },
        "The extra effects a parameter file may carry (and impactlab fit looks for): id -> meaning.");
}

}  // namespace impactlab::py_binding
