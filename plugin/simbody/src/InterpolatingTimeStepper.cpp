#include "SimbodyReeving/simbody/InterpolatingTimeStepper.h"

#include "ReevingSubsystemGuts.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {

using SimTK::EventId;
using SimTK::Integrator;
using SimTK::Stage;

InterpolatingTimeStepper::InterpolatingTimeStepper(const SimTK::System& system, Integrator& integrator)
    : system_(system), integrator_(integrator) {
    for (SimTK::SubsystemIndex i(0); i < system.getNumSubsystems(); ++i)
        if (const auto* guts = dynamic_cast<const ReevingSubsystem::Guts*>(&system.getSubsystem(i).getSubsystemGuts()))
            reeving_.push_back(guts);
}

void InterpolatingTimeStepper::initialize(const SimTK::State& initialState) {
    // Control returns after every internal step, so this stepper sees every step's end points and
    // interpolates reports itself (see the class comment for why not Simbody's interpolation).
    integrator_.setReturnEveryInternalStep(true);
    integrator_.initialize(initialState);
    ownRealizations_ = 0;
    lastStepSize_ = 0;
    cursor_ = initialState.getTime();
    pending_ = false;
    lastEventTime_ = lastReportTime_ = -SimTK::Infinity;
    report_ = integrator_.getAdvancedState();  // the one full State copy; later reports only set t and Y
    reportIsInterpolated_ = false;
    rememberStepStart();
}

void InterpolatingTimeStepper::setReportStage(Stage stage) {
    if (stage < Stage::Position || stage > Stage::Acceleration)
        throw std::invalid_argument("InterpolatingTimeStepper::setReportStage: stage " + stage.getName() +
                                    " must be Position, Velocity, Dynamics or Acceleration");
    reportStage_ = stage;
}

void InterpolatingTimeStepper::setStepLimit(int n) {
    if (n < 0) throw std::invalid_argument("InterpolatingTimeStepper::setStepLimit: n = " + std::to_string(n) + " must be >= 0");
    stepLimit_ = n;
}

const SimTK::State& InterpolatingTimeStepper::getState() const {
    return reportIsInterpolated_ ? report_ : integrator_.getAdvancedState();
}

void InterpolatingTimeStepper::realizeDerivatives(const SimTK::State& advanced) {
    // The derivatives at a step end, which the integrator's next step needs too and then finds
    // realized (Simbody's integrators count only the realizations they do themselves).
    if (advanced.getSystemStage() < Stage::Acceleration) {
        system_.realize(advanced, Stage::Acceleration);
        ++ownRealizations_;
    }
}

void InterpolatingTimeStepper::rememberStepStart() {
    const SimTK::State& a = integrator_.getAdvancedState();
    realizeDerivatives(a);
    startTime_ = a.getTime();
    startY_ = a.getY();
    startYDot_ = a.getYDot();
}

void InterpolatingTimeStepper::interpolateReport(double t) {
    const SimTK::State& a = integrator_.getAdvancedState();
    realizeDerivatives(a);
    const double t0 = startTime_, t1 = a.getTime(), h = t1 - t0;
    // Cubic Hermite interpolation of y between the step's ends (value and derivative at both).
    const double th = h > 0 ? (t - t0) / h : 1.0, th2 = th * th, th3 = th2 * th;
    const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th, h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
    report_.updTime() = t;
    SimTK::Vector& y = report_.updY();
    const SimTK::Vector &y0 = startY_, &d0 = startYDot_, &y1 = a.getY(), &d1 = a.getYDot();
    for (int i = 0; i < y.size(); ++i) y[i] = h00 * y0[i] + h10 * h * d0[i] + h01 * y1[i] + h11 * h * d1[i];
    // As Simbody does for its interpolated states: prescribed motion, then the constraint
    // manifold (quaternion norms included) at the integrator's constraint tolerance. Each stage is
    // prescribed and realized once: the convenience overloads System::projectQ(State&, Real) and
    // projectU(State&, Real) prescribe again, and with prescribed motion that invalidates the
    // stage just realized (measured on the 12-fall crane: every report realized Position and
    // Velocity twice, 1.6 M instructions of 4 M per report).
    const SimTK::ProjectOptions options(integrator_.getConstraintToleranceInUse());
    SimTK::ProjectResults results;
    system_.realize(report_, Stage::Time);
    // The ropes' dependent-coordinate Newton starts from the advanced state's solution, a step
    // away, not from the last report's (ReevingSubsystem::Guts::seedDependentCoordinates).
    for (const ReevingSubsystem::Guts* guts : reeving_) guts->seedDependentCoordinates(a, report_);
    system_.prescribeQ(report_);
    system_.realize(report_, Stage::Position);
    system_.projectQ(report_, noErrorEstimate_, options, results);
    system_.prescribeU(report_);  // needs Stage::Position (realized again by projectQ if q moved)
    if (reportStage_ >= Stage::Velocity) {
        system_.realize(report_, Stage::Velocity);
        system_.projectU(report_, noErrorEstimate_, options, results);
    }
    system_.realize(report_, reportStage_);
    reportIsInterpolated_ = true;
}

Integrator::SuccessfulStepStatus InterpolatingTimeStepper::stepTo(double reportTime) {
    Integrator& integ = integrator_;
    int steps = 0;
    if (reportTime < cursor_) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "InterpolatingTimeStepper::stepTo: report time " << reportTime
            << " s is before the time already reached, " << cursor_ << " s";
        throw std::invalid_argument(msg.str());
    }
    while (pending_ || !integ.isSimulationOver()) {
        const SimTK::State& advanced = integ.getAdvancedState();
        const double now = advanced.getTime();
        SimTK::Array_<EventId> eventIds, reportIds;
        double nextEvent = SimTK::Infinity, nextReport = SimTK::Infinity;
        system_.realize(advanced, Stage::Time);
        system_.calcTimeOfNextScheduledEvent(advanced, nextEvent, eventIds, lastEventTime_ != now);
        // Scheduled reports are due from the time already reported (cursor_), which may lie
        // before the advanced time: the report State, moved to that time, asks for them.
        if (report_.getTime() != cursor_) {
            report_.updTime() = cursor_;
            reportIsInterpolated_ = false;
        }
        system_.realize(report_, Stage::Time);
        system_.calcTimeOfNextScheduledReport(report_, nextReport, reportIds, lastReportTime_ != cursor_);
        // A report time inside the last step: interpolate it, without stepping. While an event
        // at the step end waits to be handled, only reports before it (the step's states are
        // those before the event).
        const double due = std::min(reportTime, nextReport);
        if (pending_ ? due < now : due <= now) {
            if (due == now) {
                reportIsInterpolated_ = false;  // exactly a step end: the advanced state itself
                system_.realize(advanced, reportStage_);  // as far as the next step needs it anyway
            } else {
                interpolateReport(due);
            }
            cursor_ = due;
            if (due == nextReport) {
                system_.reportEvents(getState(), SimTK::Event::Cause::Scheduled, reportIds);
                lastReportTime_ = due;
            }
            if (due >= reportTime) return Integrator::ReachedReportTime;
            continue;
        }
        if (pending_) {
            handlePendingEvent();
            continue;
        }
        // Every report up to the advanced time is delivered: a step-limit return may show it.
        if (stepLimit_ > 0 && steps >= stepLimit_) {
            cursor_ = now;
            reportIsInterpolated_ = false;
            return Integrator::ReachedStepLimit;
        }
        // The event time passed to the integrator is the next scheduled event only (the one change
        // from SimTK::TimeStepper); it returns after every internal step
        // (setReturnEveryInternalStep), at an event, or at its final time. The report time passed
        // lies beyond where the step can end (100 x the last step; a step grows by at most 10x in
        // Simbody's integrators), so the integrator does not build an interpolated State of its
        // own. The first step after (re)initialization gets the true report time: CPodes sizes its
        // first step from it (with an infinite one it fails at t = 0).
        rememberStepStart();
        const double horizon = lastStepSize_ > 0 ? std::max(due, now + 100.0 * lastStepSize_) : due;
        const Integrator::SuccessfulStepStatus status = integ.stepTo(horizon, nextEvent);
        lastStepSize_ = integ.getAdvancedTime() - now;
        reportIsInterpolated_ = false;
        switch (status) {
        case Integrator::ReachedStepLimit:
        case Integrator::TimeHasAdvanced:
        case Integrator::ReachedReportTime:  // at a step end: reports are handled at the loop top
            ++steps;
            break;
        case Integrator::ReachedScheduledEvent:
            pending_ = true;
            pendingCause_ = SimTK::Event::Cause::Scheduled;
            pendingIds_ = eventIds;
            lastEventTime_ = integ.getAdvancedTime();
            break;
        case Integrator::ReachedEventTrigger:
            pending_ = true;
            pendingCause_ = SimTK::Event::Cause::Triggered;
            pendingIds_ = integ.getTriggeredEvents();
            break;
        case Integrator::EndOfSimulation:
            pending_ = true;
            pendingCause_ = SimTK::Event::Cause::Termination;
            pendingIds_.clear();
            break;
        default:  // StartOfContinuousInterval
            break;
        }
    }
    reportIsInterpolated_ = false;
    cursor_ = integ.getAdvancedTime();
    return Integrator::EndOfSimulation;
}

void InterpolatingTimeStepper::handlePendingEvent() {
    Integrator& integ = integrator_;
    pending_ = false;
    SimTK::HandleEventsResults results;
    system_.handleEvents(integ.updAdvancedState(), pendingCause_, pendingIds_,
                         SimTK::HandleEventsOptions(integ.getAccuracyInUse()), results);
    if (results.getExitStatus() == SimTK::HandleEventsResults::Failed) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "InterpolatingTimeStepper: an event handler failed at t = " << integ.getAdvancedTime()
            << " s: " << results.getMessage();
        throw std::runtime_error(msg.str());
    }
    const bool terminate = results.getExitStatus() == SimTK::HandleEventsResults::ShouldTerminate;
    integ.reinitialize(results.getLowestModifiedStage(), terminate);
    lastStepSize_ = 0;
    // An event may have changed discrete variables or the state's structure: refresh the report
    // State from the advanced one (a full copy, once per handled event).
    report_ = integ.getAdvancedState();
    reportIsInterpolated_ = false;
}

}  // namespace SimbodyReeving
