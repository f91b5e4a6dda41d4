#include "Simulation.h"

#include <SimbodyReeving/simbody/Integrators.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace py = pybind11;
using SimbodyReeving::InterpolatingTimeStepper;

namespace simbody_reeving_python {
namespace {

// The shortest text that reads back to v.
std::string numberText(double v) {
    std::string text;
    for (int p = 1; p <= 17; ++p) {
        std::ostringstream o;
        o.precision(p);
        o << v;
        text = o.str();
        if (!std::isfinite(v) || std::stod(text) == v) break;
    }
    return text;
}

struct StepLimitReached : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace

Simulation::Simulation(const SimTK::MultibodySystem& system, const SimbodyReeving::ReevingSubsystem& reeving,
                       const SimTK::State& initial, const std::string& integrator, double accuracy, double fixedStep,
                       Observer observer)
    : system_(system), reeving_(reeving), integratorName_(integrator), accuracy_(accuracy),
      observer_(std::move(observer)) {
    require(std::isfinite(accuracy) && accuracy > 0 && accuracy < 1,
            "accuracy = " + numberText(accuracy) + " must be in (0, 1)");
    require(std::isfinite(fixedStep) && fixedStep >= 0,
            "fixed_step = " + numberText(fixedStep) + " must be >= 0 (0: variable step)");
    integrator_ = SimbodyReeving::makeIntegrator(integrator, system_);
    integrator_->setAccuracy(accuracy);
    if (fixedStep > 0) integrator_->setFixedStepSize(fixedStep);
    stepper_ = std::make_unique<InterpolatingTimeStepper>(system_, *integrator_);
    stepper_->initialize(initial);
}

void Simulation::stepTo(double t, long maxSteps) {
    require(std::isfinite(t), "step_to: the time " + numberText(t) + " is not finite");
    try {
        // As the demos' --max-steps: the stepper returns once the integrator has taken the steps left.
        for (;;) {
            if (maxSteps > 0) {
                const long left = maxSteps - integrator_->getNumStepsTaken();
                if (left <= 0)
                    throw StepLimitReached("the integrator took max_steps = " + std::to_string(maxSteps) +
                                             " steps at t = " + numberText(stepper_->getState().getTime()) +
                                             " s, before " + numberText(t) + " s");
                stepper_->setStepLimit(static_cast<int>(std::min<long>(left, 1000000000L)));
            }
            if (stepper_->stepTo(t) != SimTK::Integrator::ReachedStepLimit) break;
        }
    } catch (const StepLimitReached&) {
        throw;
    } catch (const std::invalid_argument&) {
        throw;
    } catch (const std::exception& e) {
        // Simbody's integrators drop the cause of a failed step; the rope keeps the last one.
        const std::string& cause = reeving_.getLastEvaluationFailure();
        const std::string what = e.what();
        throw std::runtime_error(what + (cause.empty() || what.find(cause) != std::string::npos
                                             ? ""
                                             : "\n  last rope evaluation failure: " + cause));
    }
}

std::vector<double> Simulation::observe() const {
    std::vector<double> row;
    observer_.observe(stepper_->getState(), row);
    return row;
}

std::string Simulation::limitReached() const {
    std::string limit = reeving_.getLimitReached();
    if (limit.empty() && integrator_->isSimulationOver())
        limit = "the integrator ended the simulation at t = " + std::to_string(state().getTime()) + " s";
    return limit;
}

Reports Simulation::run(double tEnd, double reportInterval, long maxSteps, InterruptPoll& poll, bool& interrupted) {
    require(std::isfinite(tEnd) && tEnd > 0, "t_end = " + numberText(tEnd) + " must be > 0");
    require(std::isfinite(reportInterval) && reportInterval > 0,
            "report_interval = " + numberText(reportInterval) + " must be > 0");
    require(reportInterval <= tEnd, "report_interval: " + numberText(reportInterval) +
                                        " s must not exceed t_end (" + numberText(tEnd) + " s)");
    require(maxSteps >= 0, "max_steps = " + std::to_string(maxSteps) + " must be >= 0 (0: no limit)");
    interrupted = false;
    Reports r;
    r.columns = observer_.columns;
    r.rows.push_back(observe());
    const int reports = static_cast<int>(std::floor(tEnd / reportInterval + 1e-9));
    for (int n = 1; n <= reports; ++n) {
        if (poll()) {
            interrupted = true;
            return r;
        }
        stepTo(n * reportInterval, maxSteps);
        r.rows.push_back(observe());
        if (!limitReached().empty()) break;
    }
    return r;
}

py::dict reportsToDict(const Reports& reports) {
    py::dict out;
    const std::size_t n = reports.rows.size();
    for (std::size_t c = 0; c < reports.columns.size(); ++c) {
        py::array_t<double> a(static_cast<py::ssize_t>(n));
        double* data = a.mutable_data();
        for (std::size_t i = 0; i < n; ++i) data[i] = reports.rows[i][c];
        out[py::str(reports.columns[c])] = a;
    }
    return out;
}

void bindSimulation(py::module_& m) {
    m.def("integrator_names", &SimbodyReeving::integratorNames,
          "The integrators a simulation accepts by name: rk-merson, rk3, rk-feldberg, cpodes, verlet, "
          "semi-explicit-euler2, explicit-euler.");

    py::class_<Simulation>(m, "Simulation",
                           "A scene's run: a Simbody integrator driven from report to report by "
                           "SimbodyReeving::InterpolatingTimeStepper (made by a scene's simulation() method).")
        .def(
            "step_to",
            [](Simulation& s, double t, long maxSteps) {
                py::gil_scoped_release release;
                s.stepTo(t, maxSteps);
            },
            py::arg("t"), py::arg("max_steps") = 0,
            "Advances to report time t [s] (not before the time reached), without the GIL.")
        .def("observe", [](const Simulation& s) {
                const std::vector<double> row = s.observe();
                py::dict d;
                for (std::size_t c = 0; c < row.size(); ++c) d[py::str(s.columns()[c])] = row[c];
                return d;
            },
            "The scene's observables at the current report, as a dict (the run()'s columns).")
        .def("observe_row", &Simulation::observe,
             "The same as a list, in the order of columns (cheaper than observe()).")
        .def(
            "run",
            [](Simulation& s, double tEnd, double reportInterval, long maxSteps) {
                InterruptPoll poll;
                bool interrupted = false;
                Reports r;
                {
                    py::gil_scoped_release release;
                    r = s.run(tEnd, reportInterval, maxSteps, poll, interrupted);
                }
                if (interrupted) throw py::error_already_set();
                return reportsToDict(r);
            },
            py::arg("t_end"), py::arg("report_interval") = 0.01, py::arg("max_steps") = 0,
            "Reports every report_interval up to t_end (reckoned from t = 0, as the demos do), the "
            "current report first; stops early at a rope limit (limit_reached). Returns a dict of "
            "numpy arrays, one per column. Runs without the GIL; Ctrl-C raises KeyboardInterrupt "
            "(the simulation stays at its last report).")
        .def_property_readonly("columns", &Simulation::columns)
        .def_property_readonly("state", &Simulation::state, py::return_value_policy::reference_internal,
                               "The report state at the time reached (valid until the next step).")
        .def_property_readonly("time", &Simulation::time)
        .def_property_readonly("steps", &Simulation::steps, "Integrator steps taken.")
        .def_property_readonly("rhs_evaluations", &Simulation::rhsEvaluations,
                               "Right-hand-side evaluations (InterpolatingTimeStepper::getNumRealizations).")
        .def_property_readonly("limit_reached", &Simulation::limitReached,
                               "'' or what ended the run early (a rope limit, the integrator's end).")
        .def_property_readonly("integrator", &Simulation::integratorName)
        .def_property_readonly("accuracy", &Simulation::accuracy);
}

}  // namespace simbody_reeving_python
