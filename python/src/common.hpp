// What the bindings share: long calls on a worker thread with the GIL released (progress callback, Ctrl-C),
// the model argument, the CLI's range checks, and results as dicts of NumPy arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <future>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"

namespace impactlab::py_binding {

namespace py = pybind11;

// Runs job() on a worker thread while the caller waits with the GIL released, waking every 50 ms to call
// progress(fraction) (if not None) and to see Ctrl-C. On KeyboardInterrupt, or an exception from the callback,
// it sets `cancel` (the core's flag), waits for the job to stop and re-raises. The job's own exception
// propagates as the core threw it (translated by the module's exception map).
template <class Job>
auto run_long(Job&& job, const std::atomic<double>& fraction, std::atomic<bool>& cancel, const py::object& progress)
    -> decltype(job()) {
    using R = decltype(job());
    std::packaged_task<R()> task(std::forward<Job>(job));
    std::future<R> done = task.get_future();
    std::thread worker(std::move(task));
    const auto stop = [&] {
        cancel.store(true);
        py::gil_scoped_release nogil;
        worker.join();
    };
    double reported = -1.0;
    for (;;) {
        bool ready;
        {
            py::gil_scoped_release nogil;
            ready = done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
        }
        if (PyErr_CheckSignals() != 0) {
            py::error_already_set interrupted;
            stop();
            throw interrupted;
        }
        if (!progress.is_none()) {
            const double f = ready ? 1.0 : fraction.load();
            if (f != reported) {
                reported = f;
                try {
                    progress(f);
                } catch (...) {
                    stop();
                    throw;
                }
            }
        }
        if (ready) break;
    }
    worker.join();
    return done.get();
}

// A file name given as str or os.PathLike (pathlib.Path).
std::string fspath(const py::handle& path);
// A model argument: an impactlab.Model, or a version name / parameter file path (str or os.PathLike) as the
// CLI's --model takes;
// validated (ParamError naming the key otherwise).
Params model_arg(const py::handle& model);

// The CLI's range check of a flag's value, with the argument's name: "simulate: omega: 2000 is outside [0, 1000]".
void check_range(const char* command, const char* name, double value, double lo, double hi);
void check_range_int(const char* command, const char* name, long value, long lo, long hi);
// The CLI's refusal of a start beyond a rigid bumper (common.cpp's check_start).
void check_start(const Params& p, double x, const char* command, const char* name);
// The CLI's cap on output rows (5e7), naming the arguments that multiply to it.
void check_rows(const char* command, double rows, const char* names);
// The simulator's tolerances at relative tolerance rtol (checked as --rtol is: [1e-13, 1e-2]).
Tolerances tolerances(const char* command, double rtol);

inline py::array_t<double> array(const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}
template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
    return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}
// An impactlab.Result: a dict of the columns (the CLI's CSV names, so pandas.DataFrame(r) is the CSV) with
// the rest of the result as attributes.
py::object make_result(const py::dict& columns, const py::dict& extras);

void bind_model(py::module_& m);
void bind_sim(py::module_& m);
void bind_analysis(py::module_& m);
void bind_fit(py::module_& m);

}  // namespace impactlab::py_binding
