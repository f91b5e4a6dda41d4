#pragma once
/// @file
/// The work done on a MultibodySystem by its prescribed motions (the motors that enforce them),
/// integrated with the state: the input side of an energy balance for driven machines.

#include <Simbody.h>

namespace SimbodyReeving {

/// Work of every prescribed motion (SimTK::Motion on any mobilizer: a winch drum's speed profile, a
/// trolley's traverse) since the state was initialized:
///     W(t) = integral from t0 to t of P_motion dt,   P_motion = SimbodyMatterSubsystem::calcMotionPower,
/// held as one auxiliary state variable (Z, integrated under the integrator's error control, weight
/// 1/(1 J)). For a system whose other forces are conservative (gravity, springs, ropes),
///     E_mech(t) - E_mech(t0) = W(t)
/// with E_mech = ReevingSubsystem::calcMechanicalEnergy: the residual checks a simulation. Take
/// E_mech(t0) from a state whose prescribed motion is applied (System::prescribeQ/prescribeU, as an
/// integrator's initialize does): a freshly set-up state may still hold u = 0 on a velocity-level
/// Motion, and its E_mech then misses the driven bodies' kinetic energy.
///
/// It is a force subsystem that applies no force; construct it any time before realizeTopology (the
/// ReevingSubsystem accepts it after itself). The system owns it.
class MotionWorkMeter {
public:
    /// @throws std::invalid_argument if the system has no matter subsystem.
    explicit MotionWorkMeter(SimTK::MultibodySystem& system);

    /// Work of the prescribed motions since t0 [J] (Stage::Model or later).
    double getWork(const SimTK::State& state) const;
    /// Sets the accumulated work (e.g. to 0 when a new energy balance starts) [J].
    void setWork(SimTK::State& state, double work) const;
    /// Power of the prescribed motions now [W] (Stage::Acceleration).
    double getPower(const SimTK::State& state) const;

    class Guts;

private:
    SimTK::MultibodySystem* system_;
    SimTK::SubsystemIndex index_;
};

}  // namespace SimbodyReeving
