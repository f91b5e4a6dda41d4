#pragma once
/// @file
/// A time stepper whose step sizes do not depend on how often the caller asks for reports.

#include <Simbody.h>

namespace SimbodyReeving {

/// Drives a SimTK::Integrator from report time to report time like SimTK::TimeStepper, with one
/// difference: the integrator may step *past* a report time and return an interpolated state there.
///
/// Why: Simbody 3.7's TimeStepper passes min(next scheduled event, report time) to
/// Integrator::stepTo as the event time (TimeStepperRep::stepTo in SimTKmath's TimeStepper.cpp),
/// and an integrator never steps past an event time, so every report interval ends a step: the
/// step count grows with the report rate (measured on the Table 1 pendulum, n_a = 0, RK-Merson
/// 1e-6, 20 s: 2 000 steps with reports every 0.01 s, 20 000 with 0.001 s, 1 122 with 1 s).
/// This stepper passes the next scheduled event time only; reports inside a step are Hermite
/// interpolations (cubic, Simbody's AbstractIntegratorRep::createInterpolatedState) of the step's
/// end points and derivatives, realized to Stage::Velocity, Z included. Events (scheduled,
/// triggered, time-advanced, termination) are handled as TimeStepper handles them.
///
/// Interpolated reports are exact at step ends and third-order accurate between them; a report
/// that must be exactly on the integrated trajectory can use SimTK::TimeStepper instead (or
/// Integrator::setAllowInterpolation(false), which makes the integrator stop at every report).
class InterpolatingTimeStepper {
public:
    /// The integrator must outlive the stepper.
    InterpolatingTimeStepper(const SimTK::System& system, SimTK::Integrator& integrator);

    /// Initializes the integrator with `initialState`.
    void initialize(const SimTK::State& initialState);

    /// Advances to `reportTime` [s] (>= the current time) and leaves the (possibly interpolated)
    /// state there in getState(). Returns the integrator's last status (EndOfSimulation once the
    /// integrator's final time was reached).
    /// @throws SimTK::Exception from the integrator (e.g. Integrator::StepFailed).
    SimTK::Integrator::SuccessfulStepStatus stepTo(double reportTime);

    /// true: stepTo also returns (status ReachedStepLimit, before reportTime) when the integrator
    /// has taken Integrator::setInternalStepLimit steps, so a caller can watch the wall clock.
    /// Default false.
    void setReturnAtStepLimit(bool returnAtLimit) { returnAtStepLimit_ = returnAtLimit; }

    const SimTK::State& getState() const { return integrator_.getState(); }
    const SimTK::Integrator& getIntegrator() const { return integrator_; }

private:
    const SimTK::System& system_;
    SimTK::Integrator& integrator_;
    double lastEventTime_ = -SimTK::Infinity, lastReportTime_ = -SimTK::Infinity;
    bool returnAtStepLimit_ = false;
};

}  // namespace SimbodyReeving
