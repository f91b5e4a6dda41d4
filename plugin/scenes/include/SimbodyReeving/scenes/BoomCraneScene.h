#pragma once
/// @file
/// A slewing, luffing boom crane as a ready Simbody scene: a superstructure slewing on Ground, a
/// boom held by its own luffing rope over sheaves on the A-frame and the boom tip, a hoist rope
/// from a drum on the superstructure over the boom's foot and tip sheaves to a two-fall hook block,
/// and a payload hanging from the hook block on a ball joint. Both ropes are spatial: when the
/// superstructure slews, the hook block and the payload swing out of the boom's plane and the
/// falls leave the grooves' planes at fleet angles.

#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <memory>
#include <string>
#include <vector>

namespace SimbodyReeving {

/// Physical parameters of the boom crane (SI units; y up, gravity -y). The defaults describe a
/// small lattice-boom crane: a 22 m boom at 55 degrees, a 4 t payload on two falls of a 16 mm
/// hoist rope, the boom held by three falls of a 16 mm luffing rope.
struct BoomCraneParameters {
    double g = 9.81;                 ///< gravitational acceleration [m/s^2], > 0
    // ---- superstructure (a Pin about Ground's y through the origin, prescribed slew)
    double superstructureMass = 20000.0;     ///< [kg], > 0 (prescribed: enters the slewing torque only)
    double superstructureInertia = 60000.0;  ///< about the slewing axis [kg m^2], > 0
    // ---- boom (a Pin about the superstructure's z at its foot)
    SimTK::Vec3 boomFoot{1.0, 2.0, 0.0};  ///< boom foot pin, superstructure frame [m], finite
    double boomLength = 22.0;        ///< foot pin to the tip sheaves' axle [m], > 2
    double boomMass = 2500.0;        ///< [kg], > 0 (centre of mass half-way along the boom)
    double boomAngle = 55.0 * SimTK::Pi / 180.0;  ///< nominal angle above horizontal at t = 0 [rad], in (10, 85) degrees
    // ---- luffing rope: drum -> A-frame sheave 1 -> tip sheave -> A-frame sheave 2 -> dead end at the tip
    SimTK::Vec3 aFrameTop{-2.0, 6.5, 0.0};  ///< A-frame sheaves' axle centre, superstructure frame [m], finite
    SimTK::Vec3 luffDrumCentre{-3.5, 2.5, 0.0};  ///< luffing drum axis point, superstructure frame [m], finite
    double luffSheaveRadius = 0.3;   ///< A-frame and boom-tip luffing sheaves' groove radius [m], > 0
    double luffSheaveSpacing = 0.25; ///< the two A-frame sheaves sit at z = -+ this [m], > 0
    // ---- hoist rope: drum -> boom foot sheave -> tip sheave -> hook sheave -> dead end at the tip
    SimTK::Vec3 hoistDrumCentre{-0.3, 0.9, 0.0};  ///< hoist drum axis point, superstructure frame [m], finite
    double footSheaveOffset = 0.8;   ///< foot sheave centre along the boom from the foot pin [m], > 0
    double footSheaveHeight = 0.7;   ///< foot sheave centre above the boom's axis [m], > 0
    double hoistSheaveRadius = 0.3;  ///< foot, tip and hook sheaves' groove radius [m], > 0
    double drumRadius = 0.35;        ///< both drums [m], > 0
    double drumMass = 300.0;         ///< each drum [kg], > 0
    double drumInertia = 30.0;       ///< each drum about its axis [kg m^2], > 0
    double ropeOnDrum = 60.0;        ///< rope stored on each drum at t = 0 [m], > 0
    /// Wrapped: both drums spool across their width, the rope's exit point walking one pitch
    /// along the drum's axis (+z) per turn stored (WinchDrum::pitch), from the rope's plane at
    /// t = 0 [m]; the rope's diameter on a grooved drum. 0: the rope leaves in the plane. Finite,
    /// in [0, 2 pi drumRadius). Not read with point sheaves.
    double drumPitch = 0.016;
    // ---- hook block (a Free body; frame origin at its sheave's centre) and payload (a Ball joint)
    double hookMass = 150.0;         ///< [kg], > 0
    double hookInertia = 8.0;        ///< about each axis through its centre of mass [kg m^2], > 0
    double hookComBelow = 0.3;       ///< centre of mass below the sheave centre [m], >= 0
    double hookPinBelow = 0.6;       ///< payload's ball joint below the sheave centre [m], >= 0
    double initialHookDepth = 14.0;  ///< hook sheave centre below the boom tip at t = 0 [m], > 2
    double payloadMass = 4000.0;     ///< [kg], > 0
    double payloadInertia = 1500.0;  ///< about each axis through its centre of mass [kg m^2], > 0
    double slingLength = 2.0;        ///< ball joint to the payload's centre of mass [m], > 0
    // ---- ropes (d = 16 mm steel wire rope)
    double rhoA = 1.0;               ///< mass per unstretched length [kg/m], > 0
    double EA = 1.6e7;               ///< axial stiffness [N], > 0
    double EI = 0.0;                 ///< bending stiffness [N m^2], >= 0 (0 skips the bending term)
    double minimumSpanLength = 0.3;  ///< a span this short ends the run (two-blocking) [m], > 0
    /// How the ropes meet the sheaves: SheaveModel::Wrapped (the default: tangent points in 3D, the
    /// rope's mass on the grooves, fleet angles; the drums wrapped too, the rope leaving each at
    /// its groove's tangent point) or SheaveModel::Point (the paper's point sheave; point drums,
    /// the rope leaving from the drum's axis with lever arm R).
    SheaveModel sheaveModel = SheaveModel::Wrapped;

    /// @throws std::invalid_argument naming the first parameter out of range or not finite.
    void validate() const;
};

/// The machine's program: hoist, luff and slew over time.
struct BoomCraneCycle {
    /// Hook lift [m] (up positive): the hoist drum hauls in 2 x this rope (two falls).
    MotionProfile hoist;
    /// Luffing rope hauled in [m] (positive: the boom rises, the radius shrinks). The luffing drum
    /// turns by -(this) / drumRadius.
    MotionProfile luff;
    /// Slewing angle of the superstructure about +y [rad].
    MotionProfile slew;
    /// End of the cycle [s], > 0.
    double duration = 40.0;

    /// The default cycle: at rest until 1 s; lift `lift` [m] in 8 s (2 s ramps); from 10 s slew
    /// `slewAngle` [rad] in 16 s (4 s ramps) while luffing the boom up by `luffAngle` [rad] (the
    /// luffing rope's change for that angle, BoomCraneScene::luffingRopeLength, hauled in over the
    /// same 16 s with 4 s ramps); lower `lift` from 28 s in 8 s; settle until 40 s.
    /// @throws std::invalid_argument for invalid parameters or a luff that leaves the boom's range.
    static BoomCraneCycle liftSlewLower(const BoomCraneParameters& parameters, double lift = 4.0,
                                        double slewAngle = 0.5 * SimTK::Pi, double luffAngle = 10.0 * SimTK::Pi / 180.0);
    /// @throws std::invalid_argument for an invalid move or a non-positive duration.
    void validate() const;
};

/// The boom crane (y up, gravity -y; the slewing axis is Ground's y through the origin).
///
/// Bodies: the superstructure, a MobilizedBody::Pin about Ground's y, prescribed by
/// BoomCraneCycle::slew; the boom, a MobilizedBody::Pin about the superstructure's z at boomFoot,
/// its frame's x along the boom (its angle free: the luffing rope holds it); the luffing and hoist
/// drums, MobilizedBody::Pins about the superstructure's z, prescribed by BoomCraneCycle::luff and
/// BoomCraneCycle::hoist; the hook block, a MobilizedBody::Free (frame origin at its sheave's centre, its centre
/// of mass hookComBelow under it); the payload, a MobilizedBody::Ball hookPinBelow under the hook
/// block's origin, its centre of mass slingLength under the joint.
///
/// Ropes (both spatial, RopeSpec::planeNormal zero):
///   - rope 0, the luffing rope: node 0 the luffing drum (WinchDrum), node 1 A-frame sheave 1
///     (superstructure, at aFrameTop - spacing z), node 2 the boom tip's luffing sheave (boom, on
///     the boom's axis at its tip), node 3 A-frame sheave 2 (at aFrameTop + spacing z), node 4 the
///     dead end (boom tip, a sheave radius above the tip). Three falls hold the boom.
///   - rope 1, the hoist rope: node 0 the hoist drum, node 1 the foot sheave (boom), node 2 the tip
///     sheave (boom tip, at z = -R_h), node 3 the hook sheave (hook block, its axis the hook's x),
///     node 4 the dead end (boom, above the hook sheave's other side at z = +R_h). Two falls.
/// Every sheave is a DeviationSheave whose groove axis is its body's z (the hook sheave: x), so
/// every groove turns with its body (RopeModel's NodeWrap::turningAxis); wrap senses are those of
/// the reeving at rest (the path's deflection; half a turn round the tip's luffing sheave and
/// A-frame sheave 2, clockwise about z). The ropes' unstretched lengths make the boom stand at about boomAngle and
/// the hook hang about initialHookDepth under the tip at static equilibrium.
///
/// A MotionWorkMeter integrates the work of the three prescribed motions (slew, luff, hoist), so
///     energy residual = E_mech(t) - E_mech(0) - W_motion(t)
/// checks the run (ReevingSubsystem::calcMechanicalEnergy).
class BoomCraneScene {
public:
    static constexpr int kLuffingRope = 0;  ///< the luffing rope's index in reeving()
    static constexpr int kHoistRope = 1;    ///< the hoist rope's index in reeving()
    static constexpr int kSpans = 4;        ///< spans per rope (nodes 0..4)

    /// @throws std::invalid_argument for bad parameters, cycle or span options.
    BoomCraneScene(const BoomCraneParameters& parameters, const BoomCraneCycle& cycle, const SpanOptions& spans);

    SimTK::MultibodySystem& system() { return *system_; }  ///< the scene's system (the scene owns it)
    const SimTK::MultibodySystem& system() const { return *system_; }  ///< the scene's system
    const ReevingSubsystem& reeving() const { return *reeving_; }  ///< the two ropes
    const MotionWorkMeter& workMeter() const { return *workMeter_; }  ///< work of slew, luff and hoist drives
    const BoomCraneParameters& parameters() const { return parameters_; }  ///< as given, validated
    const BoomCraneCycle& cycle() const { return cycle_; }  ///< the machine's program, as given
    const SimTK::MobilizedBody::Pin& superstructure() const { return *superstructure_; }  ///< slewing Pin
    const SimTK::MobilizedBody::Pin& boom() const { return *boom_; }       ///< the boom's Pin
    const SimTK::MobilizedBody::Pin& luffDrum() const { return *luffDrum_; }  ///< luffing drum
    const SimTK::MobilizedBody::Pin& hoistDrum() const { return *hoistDrum_; }  ///< hoist drum
    const SimTK::MobilizedBody::Free& hookBlock() const { return *hook_; }  ///< hook block
    const SimTK::MobilizedBody::Ball& payload() const { return *payload_; }  ///< payload

    /// The state at t = 0: prescribed motions applied, boom, hook block, payload and ropes at static
    /// equilibrium (ReevingSubsystem::findStaticEquilibrium, relative residual <= 1e-9), motion
    /// work 0, realized to Stage::Velocity.
    /// @throws std::runtime_error if the equilibrium is not found.
    SimTK::State makeInitialState() const;

    /// The luffing rope's three falls' summed length, A-frame sheave centres to the boom tip, at
    /// boom angle `angle` [rad] (point geometry) [m]: BoomCraneCycle::liftSlewLower hauls in the
    /// difference between two angles.
    double luffingRopeLength(double angle) const;

    // ---- observables (Stage::Position unless said otherwise)
    double slewAngle(const SimTK::State& s) const;  ///< superstructure's angle about +y [rad]
    double boomAngle(const SimTK::State& s) const;  ///< boom above horizontal [rad]
    /// Horizontal distance from the slewing axis to the hook block's sheave centre [m].
    double hookRadius(const SimTK::State& s) const;
    SimTK::Vec3 hookPosition(const SimTK::State& s) const;  ///< hook sheave centre in Ground [m]
    SimTK::Vec3 payloadPosition(const SimTK::State& s) const;  ///< payload centre of mass in Ground [m]
    /// The payload's swing out of the boom's vertical plane [rad]: the angle of the line from the
    /// boom tip to the payload's centre of mass, about the boom's plane, positive towards the
    /// superstructure's +z.
    double outOfPlaneSwing(const SimTK::State& s) const;
    /// The payload's swing in the boom's plane [rad] (positive away from the slewing axis).
    double inPlaneSwing(const SimTK::State& s) const;
    /// Largest |fleet angle| of any span of rope `rope` at any groove [rad] (0 with point sheaves).
    double largestFleetAngle(const SimTK::State& s, int rope) const;
    /// |Fleet angle| of rope `rope` where it leaves its drum [rad]: the angle between span 0 and
    /// the drum's groove plane, which the exit point's walk (drumPitch) changes through a lift
    /// (0 with point sheaves). Crane practice keeps it below 1.5 degrees on plain and 2 degrees on
    /// grooved drums (kPlainDrumFleetLimit, kGroovedDrumFleetLimit).
    /// @throws std::invalid_argument for a rope other than 0, 1.
    double drumFleetAngle(const SimTK::State& s, int rope) const;
    /// The usual largest fleet angle at a plain (ungrooved) drum [rad]: 1.5 degrees.
    static constexpr double kPlainDrumFleetLimit = 1.5 * 3.14159265358979323846 / 180.0;
    /// The usual largest fleet angle at a grooved drum [rad]: 2 degrees.
    static constexpr double kGroovedDrumFleetLimit = 2.0 * 3.14159265358979323846 / 180.0;
    /// Wrap angle on node k = 1..3 of rope `rope` [rad] (0 with point sheaves).
    /// @throws std::invalid_argument for a rope other than 0, 1 or k outside 1..3.
    double wrapAngle(const SimTK::State& s, int rope, int k) const;
    /// Axial force at the top of span `span` of rope `rope` [N] (its start for the falls leaving
    /// the A-frame and the tip, its end for the falls rising to them; Stage::Dynamics).
    /// @throws std::invalid_argument for a rope other than 0, 1 or a span outside 0..3.
    double spanForce(const SimTK::State& s, int rope, int span) const;
    /// Torque the slewing drive applies to the superstructure about +y [N m] (Stage::Acceleration).
    double slewTorque(const SimTK::State& s) const;
    /// Torque the luffing drum's motor applies about its axis [N m] (Stage::Acceleration).
    double luffTorque(const SimTK::State& s) const;
    /// Torque the hoist drum's motor applies about its axis [N m] (Stage::Acceleration).
    double hoistTorque(const SimTK::State& s) const;
    double ropeOnDrum(const SimTK::State& s, int rope) const;  ///< [m] (WinchDrumHandle::getRopeOnDrum)
    /// E_mech(t) - e0 - W_motion(t) [J] (Stage::Velocity; e0 = E_mech of the initial state).
    double energyResidual(const SimTK::State& s, double e0) const;
    /// Ground positions of rope `rope`'s nodes 0..4 (drum axis points, sheave centres, dead end) [m].
    std::vector<SimTK::Vec3> nodePositions(const SimTK::State& s, int rope) const;

private:
    void addDecorations();
    BoomCraneParameters parameters_;
    BoomCraneCycle cycle_;
    std::unique_ptr<SimTK::MultibodySystem> system_;
    std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
    std::unique_ptr<SimTK::GeneralForceSubsystem> forces_;
    std::unique_ptr<SimTK::Force::Gravity> gravity_;
    std::unique_ptr<ReevingSubsystem> reeving_;
    std::unique_ptr<MotionWorkMeter> workMeter_;
    std::unique_ptr<SimTK::MobilizedBody::Pin> superstructure_, boom_, luffDrum_, hoistDrum_;
    std::unique_ptr<SimTK::MobilizedBody::Free> hook_;
    std::unique_ptr<SimTK::MobilizedBody::Ball> payload_;
    // Node k of rope r: its body and station.
    std::vector<std::vector<std::pair<const SimTK::MobilizedBody*, SimTK::Vec3>>> nodes_;
    SimTK::Vec3 hookStart_{0};  // hook sheave centre at t = 0, superstructure frame (the equilibrium's first guess)
};

}  // namespace SimbodyReeving
