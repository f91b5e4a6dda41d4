#include "SimbodyReeving/InterpolatingTimeStepper.h"

#include <stdexcept>
#include <string>

namespace SimbodyReeving {

using SimTK::EventId;
using SimTK::Integrator;
using SimTK::Stage;

InterpolatingTimeStepper::InterpolatingTimeStepper(const SimTK::System& system, Integrator& integrator)
    : system_(system), integrator_(integrator) {}

void InterpolatingTimeStepper::initialize(const SimTK::State& initialState) {
    integrator_.initialize(initialState);
    lastEventTime_ = lastReportTime_ = -SimTK::Infinity;
}

Integrator::SuccessfulStepStatus InterpolatingTimeStepper::stepTo(double reportTime) {
    Integrator& integ = integrator_;
    while (!integ.isSimulationOver()) {
        SimTK::Array_<EventId> eventIds, reportIds;
        double nextEvent = SimTK::Infinity, nextReport = SimTK::Infinity;
        const double now = integ.getTime();
        system_.realize(integ.getState(), Stage::Time);
        system_.realize(integ.getAdvancedState(), Stage::Time);
        system_.calcTimeOfNextScheduledEvent(integ.getState(), nextEvent, eventIds, lastEventTime_ != now);
        system_.calcTimeOfNextScheduledReport(integ.getState(), nextReport, reportIds, lastReportTime_ != now);
        // The one change from SimTK::TimeStepper: the event time is the next scheduled event, not
        // min(next event, report time), so the integrator may step past the report time.
        const Integrator::SuccessfulStepStatus status = integ.stepTo(std::min(nextReport, reportTime), nextEvent);
        SimTK::Event::Cause cause;
        SimTK::Array_<EventId> handled;
        switch (status) {
        case Integrator::ReachedStepLimit:
            if (returnAtStepLimit_) return status;
            continue;
        case Integrator::StartOfContinuousInterval:
            continue;
        case Integrator::ReachedReportTime:
            if (integ.getTime() >= nextReport) {
                system_.reportEvents(integ.getState(), SimTK::Event::Cause::Scheduled, reportIds);
                lastReportTime_ = integ.getTime();
            }
            if (integ.getTime() >= reportTime) return status;
            continue;
        case Integrator::ReachedScheduledEvent:
            cause = SimTK::Event::Cause::Scheduled;
            handled = eventIds;
            lastEventTime_ = integ.getTime();
            break;
        case Integrator::TimeHasAdvanced:
            cause = SimTK::Event::Cause::TimeAdvanced;
            break;
        case Integrator::ReachedEventTrigger:
            cause = SimTK::Event::Cause::Triggered;
            handled = integ.getTriggeredEvents();
            break;
        case Integrator::EndOfSimulation:
            cause = SimTK::Event::Cause::Termination;
            break;
        default:
            continue;
        }
        SimTK::HandleEventsResults results;
        system_.handleEvents(integ.updAdvancedState(), cause, handled, SimTK::HandleEventsOptions(integ.getAccuracyInUse()),
                             results);
        const Stage lowestModified = results.getLowestModifiedStage();
        const bool terminate = results.getExitStatus() == SimTK::HandleEventsResults::ShouldTerminate;
        if (results.getExitStatus() == SimTK::HandleEventsResults::Failed)
            throw std::runtime_error("InterpolatingTimeStepper: an event handler failed at t = " +
                                     std::to_string(integ.getTime()) + " s: " + results.getMessage());
        integ.reinitialize(lowestModified, terminate);
    }
    return Integrator::EndOfSimulation;
}

}  // namespace SimbodyReeving
