#include "SimbodyReeving/simbody/SlackMonitor.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {

namespace {

/// Witness: the span's largest strain; a sign change in either direction is a transition.
class SpanSlackEvent : public SimTK::TriggeredEventHandler {
public:
    SpanSlackEvent(const ReevingSubsystem& reeving, int rope, int span, double window,
                   std::shared_ptr<std::vector<SlackTransition>> log)
        : SimTK::TriggeredEventHandler(SimTK::Stage::Position), reeving_(reeving), rope_(rope), span_(span),
          log_(std::move(log)) {
        getTriggerInfo().setTriggerOnRisingSignTransition(true);
        getTriggerInfo().setTriggerOnFallingSignTransition(true);
        getTriggerInfo().setRequiredLocalizationTimeWindow(window);
    }
    SimTK::Real getValue(const SimTK::State& s) const override { return reeving_.getSpanMaxStrain(s, rope_, span_); }
    void handleEvent(SimTK::State& s, SimTK::Real, bool&) const override {
        // Called just after the crossing: the sign now is the new regime.
        log_->push_back({s.getTime(), rope_, span_, getValue(s) <= 0.0});
    }

private:
    const ReevingSubsystem& reeving_;
    int rope_, span_;
    std::shared_ptr<std::vector<SlackTransition>> log_;
};

}  // namespace

SlackMonitor::SlackMonitor(SimTK::MultibodySystem& system, const ReevingSubsystem& reeving, double eventWindow)
    : log_(std::make_shared<std::vector<SlackTransition>>()) {
    if (!std::isfinite(eventWindow) || !(eventWindow > 0)) {
        std::ostringstream msg;
        msg << "SlackMonitor: eventWindow [s] = " << eventWindow << " must be finite and > 0";
        throw std::invalid_argument(msg.str());
    }
    for (int rope = 0; rope < reeving.getNumRopes(); ++rope) {
        if (!reeving.getRopeSpec(rope).properties.tensionOnly) continue;
        for (int span = 0; span < reeving.getNumSpans(rope); ++span) {
            system.addEventHandler(new SpanSlackEvent(reeving, rope, span, eventWindow, log_));  // system owns it
            ++watched_;
        }
    }
}

}  // namespace SimbodyReeving
