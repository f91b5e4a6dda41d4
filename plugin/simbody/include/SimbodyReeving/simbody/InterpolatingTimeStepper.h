#pragma once
/// @file
/// A time stepper whose step sizes do not depend on how often the caller asks for reports.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <vector>

namespace SimbodyReeving {

/// Drives a SimTK::Integrator from report time to report time like SimTK::TimeStepper, with one
/// difference: the integrator may step *past* a report time and return an interpolated state there.
///
/// Why: Simbody 3.7's TimeStepper passes min(next scheduled event, report time) to
/// Integrator::stepTo as the event time (TimeStepperRep::stepTo in SimTKmath's TimeStepper.cpp),
/// and an integrator never steps past an event time, so every report interval ends a step: the
/// step count grows with the report rate once reports are more frequent than the steps.
/// This stepper passes the next scheduled event time only, and interpolates the reports itself:
/// the integrator returns after every internal step (initialize() sets
/// Integrator::setReturnEveryInternalStep(true)), and a report time inside the last step gets the
/// cubic Hermite interpolation of y from the step's end values and derivatives (the same
/// interpolation as Simbody's AbstractIntegratorRep::createInterpolatedState), with prescribed
/// motion applied and q and u projected onto the constraint manifold at the integrator's
/// constraint tolerance, realized to Stage::Velocity (Z included; see setReportStage). Unlike
/// Simbody's interpolation, which copies the whole advanced State into its interpolated State at
/// every report (on a small system that costs more than the steps themselves at frequent
/// reports), the report State here is copied once and then only gets t
/// and Y. Events (scheduled, triggered, time-advanced, termination) are handled as TimeStepper
/// handles them; the report State is refreshed by a full copy after each handled event. The
/// ReevingSubsystems of the system start the Newton solve of their ropes' dependent coordinates
/// (sheave material coordinates, quasi-static amplitudes) at a report from the advanced state's
/// solution, a step away, rather than from the last report's, a report interval away (fewer
/// Newton iterations per report); the solution is the same to the Newton's tolerance.
///
/// Interpolated reports are exact at step ends and third-order accurate between them; a report
/// that must be exactly on the integrated trajectory can use SimTK::TimeStepper instead.
/// Read reports from getState(), not from the integrator: Integrator::getState() is the advanced
/// state, past the report time.
class InterpolatingTimeStepper {
public:
    /// The integrator must outlive the stepper.
    InterpolatingTimeStepper(const SimTK::System& system, SimTK::Integrator& integrator);

    /// Initializes the integrator with `initialState`.
    void initialize(const SimTK::State& initialState);

    /// Advances to `reportTime` [s] (>= the current time) and leaves the (possibly interpolated)
    /// state there in getState(). Returns the integrator's last status (EndOfSimulation once the
    /// integrator's final time was reached).
    /// @throws std::invalid_argument if reportTime is before the time already reached.
    /// @throws SimTK::Exception from the integrator (e.g. Integrator::StepFailed).
    SimTK::Integrator::SuccessfulStepStatus stepTo(double reportTime);

    /// n > 0: stepTo also returns (status Integrator::ReachedStepLimit, before the report time)
    /// after every n internal steps, so a caller can watch the wall clock; 0 (default): no limit.
    /// (The integrator's own Integrator::setInternalStepLimit has no effect here: the stepper
    /// takes one internal step per Integrator::stepTo call.)
    /// @throws std::invalid_argument if n < 0.
    void setStepLimit(int n);

    /// The stage an interpolated report is realized to (default Stage::Velocity): the stage the
    /// reporters read, so that reading costs no realization beyond it.
    /// - Stage::Position: q is prescribed and projected onto the position constraints (quaternion
    ///   norms included) and realized to Position; u is interpolated and prescribed but *not*
    ///   projected onto the velocity constraints (that needs Stage::Velocity). For reporters that
    ///   read positions only (drawing, animation frames); a reporter that realizes such a report
    ///   further sees unprojected velocities (they differ from projected ones by the
    ///   interpolation's error, and not at all without constraints).
    /// - Stage::Velocity: q and u prescribed and projected, realized to Velocity.
    /// - Stage::Dynamics, Stage::Acceleration: as Velocity, then realized to that stage (forces,
    ///   accelerations), as reporters reading forces would otherwise do themselves.
    /// A report time on a step end gives the integrator's advanced state, realized to this stage
    /// too (its next step needs Stage::Acceleration of it anyway).
    /// @throws std::invalid_argument for a stage before Position or after Acceleration.
    void setReportStage(SimTK::Stage stage);
    /// The stage reports are realized to (setReportStage; default Stage::Velocity).
    SimTK::Stage getReportStage() const { return reportStage_; }

    /// The state at the last report time reached by stepTo (interpolated, or the integrator's
    /// advanced state when the report fell on a step end), realized to getReportStage() (default
    /// Stage::Velocity).
    const SimTK::State& getState() const;
    /// The integrator the stepper drives.
    const SimTK::Integrator& getIntegrator() const { return integrator_; }
    /// Right-hand-side evaluations (realizations through Stage::Acceleration) since initialize():
    /// the integrator's Integrator::getNumRealizations() plus those this stepper did at step
    /// starts, which the integrator then found done and did not count. Reports are not counted.
    int getNumRealizations() const { return integrator_.getNumRealizations() + ownRealizations_; }

private:
    void realizeDerivatives(const SimTK::State& advanced);
    void rememberStepStart();
    void handlePendingEvent();
    void interpolateReport(double t);

    const SimTK::System& system_;
    SimTK::Integrator& integrator_;
    double lastEventTime_ = -SimTK::Infinity, lastReportTime_ = -SimTK::Infinity;
    int stepLimit_ = 0;
    SimTK::Stage reportStage_ = SimTK::Stage::Velocity;  // see setReportStage
    SimTK::Vector noErrorEstimate_;     // empty: System::projectQ/projectU without an error estimate
    int ownRealizations_ = 0;           // realizations at step starts, see getNumRealizations
    SimTK::State report_;               // the reported state when reportIsInterpolated_
    bool reportIsInterpolated_ = false;
    bool pending_ = false;              // an event at the advanced time waits for earlier reports
    SimTK::Event::Cause pendingCause_ = SimTK::Event::Cause::Scheduled;
    SimTK::Array_<SimTK::EventId> pendingIds_;
    double cursor_ = 0;                 // [s] the time reached by the last return (reports delivered up to it)
    double lastStepSize_ = 0;           // [s]; 0 after (re)initialization
    double startTime_ = 0;              // the last step's start: time, y and dy/dt
    SimTK::Vector startY_, startYDot_;
    std::vector<const ReevingSubsystem::Guts*> reeving_;  // the system's ReevingSubsystems (warm starts)
};

}  // namespace SimbodyReeving
