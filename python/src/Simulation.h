#pragma once
// A run of a scene: a Simbody integrator (by name, SimbodyReeving::makeIntegrator) driven report
// by report by SimbodyReeving::InterpolatingTimeStepper, the scene's observer reading each report.
// The loop is the demos' (examples/pendulum/main.cpp runCase): the same integrator settings, the
// same report times n * interval, the same stepper calls and realizations, so a run from Python
// gives the demo's numbers to the last bit.

#include "Errors.h"

#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace simbody_reeving_python {

/// What a scene reports at each report time: named columns, filled from a state.
struct Observer {
    std::vector<std::string> columns;
    std::function<void(const SimTK::State&, std::vector<double>&)> observe;
};

/// The reports of a run, one row per report (the initial state first).
struct Reports {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
};

class Simulation {
public:
    /// @param accuracy in (0, 1); @param fixedStep > 0: the integrator's fixed step size [s] (0: variable).
    /// @throws std::invalid_argument for an unknown integrator or an accuracy or step out of range.
    Simulation(const SimTK::MultibodySystem& system, const SimbodyReeving::ReevingSubsystem& reeving,
               const SimTK::State& initial, const std::string& integrator, double accuracy, double fixedStep,
               Observer observer);

    /// Advances to report time t (>= the time reached): the demo's loop body. maxSteps > 0: stops with
    /// std::runtime_error once the integrator has taken that many steps in all. A failed step's
    /// message gets the rope's last evaluation failure appended (as the demos do).
    void stepTo(double t, long maxSteps = 0);
    /// The report state at the time reached (interpolated), realized to Stage::Velocity at least.
    const SimTK::State& state() const { return stepper_->getState(); }
    double time() const { return state().getTime(); }
    /// The observer's row at the current report.
    std::vector<double> observe() const;
    const std::vector<std::string>& columns() const { return observer_.columns; }
    /// "" or what ended the run early: a rope limit (ReevingSubsystem::getLimitReached) or the
    /// integrator's end of simulation.
    std::string limitReached() const;

    /// The demo's whole loop: reports at n * reportInterval, n = 1 .. floor(tEnd / reportInterval
    /// + 1e-9), after the row of the current state; stops early at a rope limit (limitReached()).
    /// Without the GIL; `poll` is called between reports and stops the run (returning with
    /// `interrupted` set) when it returns true.
    Reports run(double tEnd, double reportInterval, long maxSteps, InterruptPoll& poll, bool& interrupted);

    long steps() const { return integrator_->getNumStepsTaken(); }
    /// Right-hand-side evaluations (InterpolatingTimeStepper::getNumRealizations).
    long rhsEvaluations() const { return stepper_->getNumRealizations(); }
    /// The integrator's own count of realizations (the elevator demo's rhs_evaluations).
    long integratorRealizations() const { return integrator_->getNumRealizations(); }
    const std::string& integratorName() const { return integratorName_; }
    double accuracy() const { return accuracy_; }

private:
    const SimTK::MultibodySystem& system_;
    const SimbodyReeving::ReevingSubsystem& reeving_;
    std::string integratorName_;
    double accuracy_;
    std::unique_ptr<SimTK::Integrator> integrator_;
    std::unique_ptr<SimbodyReeving::InterpolatingTimeStepper> stepper_;
    Observer observer_;
};

/// Reports as a dict of numpy arrays, one per column.
pybind11::dict reportsToDict(const Reports& reports);

/// Binds Simulation (created by the scenes' simulation() methods) and integrator_names().
void bindSimulation(pybind11::module_& m);

}  // namespace simbody_reeving_python
