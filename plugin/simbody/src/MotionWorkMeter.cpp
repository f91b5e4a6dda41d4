#include "SimbodyReeving/simbody/MotionWorkMeter.h"

#include "ForceFreeSubsystem.h"

#include <stdexcept>

namespace SimbodyReeving {

/// One Z entry: the work; its derivative is the motion power, computed at Stage::Acceleration
/// (force subsystems are realized after the matter subsystem there, so the prescribed motions'
/// generalized forces are known).
class MotionWorkMeter::Guts : public detail::ForceFreeSubsystemGuts {
public:
    Guts() : detail::ForceFreeSubsystemGuts("MotionWorkMeter", "0.1") {}
    Guts* cloneImpl() const override { return new Guts(*this); }
    SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }  // no force, no energy

    int realizeSubsystemTopologyImpl(SimTK::State& s) const override {
        allocateZ(s, SimTK::Vector(1, 0.0));
        return 0;
    }
    int realizeSubsystemAccelerationImpl(const SimTK::State& s) const override {
        const auto& mbs = SimTK::MultibodySystem::downcast(getSystem());
        updZDot(s)[0] = mbs.getMatterSubsystem().calcMotionPower(s);
        return 0;
    }
};

namespace {
class MotionWorkMeterSubsystem : public SimTK::ForceSubsystem {
public:
    explicit MotionWorkMeterSubsystem(SimTK::MultibodySystem& system) {
        adoptSubsystemGuts(new MotionWorkMeter::Guts());
        system.addForceSubsystem(*this);
    }
};
}  // namespace

MotionWorkMeter::MotionWorkMeter(SimTK::MultibodySystem& system) : system_(&system) {
    if (!system.hasMatterSubsystem())
        throw std::invalid_argument("MotionWorkMeter: the system has no SimbodyMatterSubsystem");
    MotionWorkMeterSubsystem sub(system);  // the system keeps the guts; the handle may go
    index_ = sub.getMySubsystemIndex();
}

double MotionWorkMeter::getWork(const SimTK::State& state) const {
    return system_->getSubsystem(index_).getZ(state)[0];
}

void MotionWorkMeter::setWork(SimTK::State& state, double work) const {
    system_->getSubsystem(index_).updZ(state)[0] = work;
}

double MotionWorkMeter::getPower(const SimTK::State& state) const {
    return system_->getMatterSubsystem().calcMotionPower(state);
}

}  // namespace SimbodyReeving
