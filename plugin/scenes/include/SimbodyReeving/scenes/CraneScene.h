#pragma once
/// @file
/// An overhead (gantry) crane as a ready Simbody scene: a trolley with a prescribed traverse, a
/// winch drum with a prescribed hoist profile, n falls of wire rope between trolley sheaves and a
/// hook block, and a payload slung under the hook block. Two scenarios: the payload hanging from
/// the rope (a lift-traverse-lower cycle) or resting on the floor (lift-off of a grounded load).

#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <memory>
#include <string>
#include <vector>

namespace SimbodyReeving {

/// What the crane starts from (CraneParameters::scenario):
///   - Cycle: the payload hangs from the rope at static equilibrium, pinned under the hook block
///     (the default; the machine's program is a CraneCycle, e.g. CraneCycle::liftTraverseLower).
///   - LiftOff: lift-off of a grounded load. The payload rests on a compliant floor; the hook block
///     hangs from the rope above it, its sling slack (see CraneScene, "Lift-off"). The hoist
///     (CraneCycle::liftOff) accelerates the hook from rest to the steady hoisting speed
///     v_h = hoistSpeed in hoistRamp and hoists slackTime at v_h while it takes up the slack; then
///     the sling is taut, the hook block stops on it, and the rope stretches at v_h until it
///     carries hook block and payload, which lift off the floor and bounce on the rope. Reference:
///     a mass M picked up by a spring k at speed v_h, peak force M g + v_h sqrt(k M), i.e. the
///     dynamic factor phi = 1 + v_h sqrt(k / M) / g (CraneScene::springMassDynamicFactor).
enum class CraneScenario { Cycle, LiftOff };

/// "cycle", "lift-off".
const char* toString(CraneScenario scenario);
/// @throws std::invalid_argument for any other name.
CraneScenario craneScenarioFromString(const std::string& name);

/// Physical parameters of the crane (SI units). The defaults describe a 5 t overhead crane with a
/// 20 mm wire rope reeved in 4 falls, the hook 11 m below the trolley.
struct CraneParameters {
    int falls = 4;                 ///< n: rope parts between trolley and hook block, 1..12
    double g = 9.81;               ///< gravitational acceleration [m/s^2], >= 0
    // ---- trolley and its sheaves
    double railHeight = 15.0;      ///< height of the trolley's sheave centres above the ground (y = 0) [m], > 0
    double trolleyX0 = 0.0;        ///< trolley position at t = 0 [m], finite
    double trolleyMass = 2000.0;   ///< [kg], > 0 (prescribed: enters the traverse force only)
    /// Horizontal distance between neighbouring rope nodes [m], > 0 (SheaveModel::Point only: with
    /// wrapped sheaves the falls hang a sheave diameter apart).
    double sheavePitch = 0.2;
    /// Radius of every sheave's groove (the rope's centre line on it) [m], > 0; with
    /// SheaveModel::Point it serves validation and drawing only.
    double sheaveRadius = 0.09;
    /// How the rope meets the trolley and hook sheaves: SheaveModel::Wrapped (the default: the rope
    /// leaves at tangent points and lies on the grooves, the falls parallel) or SheaveModel::Point
    /// (the paper's point sheave: every fall ends at sheave centres sheavePitch apart).
    SheaveModel sheaveModel = SheaveModel::Wrapped;
    // ---- winch drum (a Pin on the trolley, axis z)
    double drumRadius = 0.3;       ///< [m], > 0
    double drumHeight = 0.8;       ///< drum axis above the trolley's sheave centres [m], finite
    double drumMass = 400.0;       ///< [kg], > 0
    double drumInertia = 40.0;     ///< moment of inertia about the drum axis [kg m^2], > 0
    double ropeOnDrum = 40.0;      ///< rope stored on the drum at t = 0 [m], > 0
    // ---- hook block (a Planar body: x, y, rotation about z)
    double hookMass = 200.0;       ///< [kg], > 0
    double hookInertia = 15.0;     ///< about z through its centre of mass [kg m^2], > 0
    double hookComBelow = 0.3;     ///< centre of mass below the hook sheave centres [m], >= 0
    double hookPinBelow = 0.5;     ///< sling pin below the hook sheave centres [m], >= 0
    double initialHookDepth = 11.0;  ///< hook sheave centres below the trolley's at t = 0 [m], > 0
    // ---- payload (Cycle: a Pin on the hook block, axis z; LiftOff: planar, on the floor, see CraneScene)
    double payloadMass = 5000.0;   ///< [kg], > 0
    double payloadInertia = 2600.0;  ///< about z through its centre of mass [kg m^2], > 0 (2 m x 1.5 m block)
    double slingLength = 2.0;      ///< sling pin to payload centre of mass [m], > 0 (LiftOff: > payloadHeight / 2 + the slack)
    double payloadWidth = 2.0;     ///< drawing; LiftOff: its bottom corners rest on the floor [m], > 0
    double payloadHeight = 1.5;    ///< drawing; LiftOff: its bottom is this below its top [m], > 0
    // ---- rope (d = 20 mm steel wire rope)
    double rhoA = 1.6;             ///< mass per unstretched length [kg/m], > 0
    double EA = 2.5e7;             ///< axial stiffness [N], > 0
    double EI = 0.0;               ///< bending stiffness [N m^2], >= 0 (0 skips the bending term)
    bool tensionOnly = true;       ///< RopeProperties::tensionOnly (false: the linear law, ropes may push)
    double minimumSpanLength = 0.2;  ///< a span this short ends the run (two-blocking) [m], > 0
    // ---- scenario
    CraneScenario scenario = CraneScenario::Cycle;  ///< what the crane starts from
    // ---- lift-off (used by CraneScenario::LiftOff and CraneCycle::liftOff only)
    double hoistSpeed = 0.3;       ///< v_h: steady hoisting speed of the hook (drum: falls x v_h) [m/s], > 0
    double hoistRamp = 0.5;        ///< time the hoist takes from rest to v_h (quintic speed ramp) [s], > 0
    /// Time the hoist has run at v_h when the sling becomes taut [s], >= 0. It sets the slack: the
    /// hook lift v_h (hoistRamp / 2 + slackTime) that the hoist makes before the sling is taut
    /// (CraneScene::ropeSlack; the drum hauls in falls times that rope).
    double slackTime = 0.5;
    /// How long the run goes on after the estimated lift-off, in periods of the load's bounce on
    /// the rope, 2 pi sqrt((payloadMass + hookMass) / k) (k: CraneScene::hookStiffness) [-], > 0.
    /// The default 0.5 ends it past the first force peak (a quarter period after lift-off) where
    /// the force is back at its static value. Beyond 0.75 a load with a dynamic factor above 2
    /// is thrown up and the rope goes slack: slack falls hauled over sheaves are outside what the
    /// scene is checked for.
    double afterLiftOff = 0.5;
    double floorStiffness = 2e9;   ///< the floor's contact stiffness under the payload, both corners together [N/m], > 0
    /// Damping ratio of the payload bouncing on the floor's stiffness [-], >= 0: the floor's
    /// dashpot is c_f = 2 zeta sqrt(floorStiffness payloadMass).
    double floorDampingRatio = 1.0;
    double slingStiffness = 2e9;   ///< the sling's axial stiffness while taut [N/m], > 0
    /// Damping ratio of the hook block bouncing on the taut sling [-], >= 0: the sling's dashpot is
    /// c_s = 2 zeta sqrt(slingStiffness hookMass).
    double slingDampingRatio = 1.0;

    /// @throws std::invalid_argument naming the first parameter out of range or not finite.
    void validate() const;
};

/// The machine's program: what the hoist and the trolley do over time.
struct CraneCycle {
    /// Hook lift above its initial height [m] (up positive): the drum hauls in falls x this rope
    /// (drum angle theta = -falls / drumRadius x lift, rope paid out for positive theta), so the
    /// hook's actual height differs from it by the rope's change of stretch and the sway.
    MotionProfile hoist;
    /// Trolley displacement along x from CraneParameters::trolleyX0 [m].
    MotionProfile traverse;
    /// End of the cycle [s], > 0.
    double duration = 36.0;

    /// The default lift-traverse-lower cycle: at rest until 1 s; lift `lift` [m] in 9 s (2 s
    /// speed ramps); traverse `traverse` [m] from 10.5 s in 12 s (3 s ramps); lower `lift` from
    /// 23.5 s in 9 s (2 s ramps); settle until 36 s. Defaults: 5 m and 10 m, hook speed
    /// 0.71 m/s, trolley speed 1.11 m/s, trolley acceleration at most 0.69 m/s^2.
    static CraneCycle liftTraverseLower(double lift = 5.0, double traverse = 10.0);
    /// The lift-off program of CraneScenario::LiftOff for `parameters` (hoistSpeed, hoistRamp,
    /// slackTime, afterLiftOff; no traverse): the hoist starts at t = 0 and reaches v_h at hoistRamp
    /// (one SmoothMove), the sling becomes taut at t_taut = hoistRamp + slackTime, the load lifts
    /// off at about t_lift = t_taut + payloadMass g / (k v_h) (k: CraneScene::hookStiffness) and the
    /// cycle ends afterLiftOff bounce periods later, still hoisting at v_h (the move's deceleration
    /// ramp begins there: a run past `duration` stops the hoist in hoistRamp).
    /// @throws std::invalid_argument for invalid parameters (CraneParameters::validate).
    static CraneCycle liftOff(const CraneParameters& parameters);
    /// @throws std::invalid_argument for an invalid move or a non-positive duration.
    void validate() const;
};

/// The crane in the x-y plane (y up, gravity -y); every rope node and body moves in that plane.
///
/// Bodies: the trolley, a MobilizedBody::Slider along x from Ground at railHeight, prescribed by
/// CraneCycle::traverse; the winch drum, a MobilizedBody::Pin (axis z) on the trolley at
/// drumHeight above the first rope node, prescribed by CraneCycle::hoist; the hook block, a
/// MobilizedBody::Planar from Ground (x, y, rotation about z), frame origin at its sheave centres;
/// the payload, a MobilizedBody::Pin (axis z) hanging slingLength below the hook block's sling pin.
///
/// Reeving: one planar rope of n = falls spans (falls). With SheaveModel::Point, rope nodes
/// k = 0..n sit at horizontal offsets (k - n/2) sheavePitch. With SheaveModel::Wrapped the falls
/// hang vertical at X_j = (j - (n - 1)/2) 2 R (R = sheaveRadius), a diameter apart as in a real
/// block: sheave k sits between falls k - 1 and k (the rope passes under the hook sheaves,
/// counter-clockwise about +z, and over the trolley sheaves, clockwise), the drum's node above
/// fall 0 and the dead end on fall n - 1. The drum is a point node in both models (the rope leaves
/// it from its axis; its lever arm is the drum radius). Node 0 is the WinchDrum (start), odd nodes are DeviationSheaves
/// on the hook block, even ones on the trolley, and node n is the dead end (RopeAnchor) on the
/// trolley for even n, on the hook block for odd n. Span k (fall k + 1) joins nodes k and k + 1;
/// its top is node k for even k, node k + 1 for odd k. The hook block's nodes are shifted so that
/// their load centroid (2 per sheave, 1 for a dead end) is its frame origin: with vertical falls
/// it hangs level. The rope's unstretched length is chosen so that the hook hangs about
/// initialHookDepth below the trolley sheaves when loaded.
///
/// Drawing (any SimTK::Visualizer): the trolley with its frame, wheels and rails, the hook block,
/// the payload block on its sling legs; the rope coloured blue (slack) ... red (twice the static
/// load of a fall, (payloadMass + hookMass) g / falls: ReevingSubsystem::setDecorationForceScale).
///
/// A MotionWorkMeter integrates the work of the two prescribed motions, so
///     energy residual = E_mech(t) - E_mech(0) - W_motion(t)
/// checks the simulation (ReevingSubsystem::calcMechanicalEnergy).
///
/// Lift-off (CraneScenario::LiftOff). The payload is a MobilizedBody::Planar from Ground (x, y,
/// rotation about z; frame origin at its centre of mass) instead of a Pin under the hook block,
/// joined to it by the sling and resting on the floor:
///   - Floor: a horizontal plane at floorHeight() (any sign: only relative heights matter),
///     touched by the payload's two bottom corners (x = +-payloadWidth / 2, y = -payloadHeight / 2
///     in its frame). Corner i at penetration d_i > 0 gets the vertical force
///         F_i = max(0, k_c d_i + c_c d_i'),  k_c = floorStiffness / 2,  c_c = c_f / 2
///     (a linear spring-dashpot that only pushes: frictionless, no adhesion; 0 for d_i <= 0).
///   - Sling: a straight link of length l_s = slingLength - payloadHeight / 2 from the hook
///     block's sling pin (hookPinBelow below its sheave centres) to the payload's lifting point
///     (the middle of its top, payloadHeight / 2 above its centre of mass); at distance d > l_s it
///     pulls both points together with f = max(0, slingStiffness e + c_s e'), e = d - l_s (a
///     spring-dashpot that only pulls); slack (no force) for d <= l_s. Taut and straight, the
///     payload's centre of mass hangs slingLength below the pin, as in Cycle.
/// At t = 0 the hook hangs from the rope at static equilibrium about initialHookDepth below the
/// trolley (the rope's unstretched length is set for the hook block's weight alone), the payload
/// stands on the floor, its lifting point l_s - ropeSlack() straight below the pin: the hoist must
/// lift the hook by ropeSlack() before the sling is taut. Energy: the floor's and the sling's
/// elastic energies, sum 1/2 k_c d_i^2 + 1/2 slingStiffness e^2, are part of the system's
/// potential energy (so of ReevingSubsystem::calcMechanicalEnergy), and the power their dashpots
/// dissipate,
///     P = sum (F_i - k_c d_i) d_i' + (f - slingStiffness e) e' >= 0
/// (c d'^2 while a dashpot pushes or pulls; where the clamp at 0 acts, the elastic force's power,
/// also >= 0), is integrated with the state (contactDissipation), so that
///     energy residual = E_mech(t) - E_mech(0) + W_contact(t) - W_motion(t)
/// (energyResidual) checks the run.
class CraneScene {
public:
    /// @throws std::invalid_argument for bad parameters, cycle or span options.
    CraneScene(const CraneParameters& parameters, const CraneCycle& cycle, const SpanOptions& spans);

    SimTK::MultibodySystem& system() { return *system_; }  ///< the scene's system (the scene owns it)
    const SimTK::MultibodySystem& system() const { return *system_; }  ///< the scene's system
    const SimTK::SimbodyMatterSubsystem& matter() const { return *matter_; }  ///< its matter subsystem
    const ReevingSubsystem& reeving() const { return *reeving_; }  ///< the rope (rope 0)
    const MotionWorkMeter& workMeter() const { return *workMeter_; }  ///< work of the hoist and traverse drives
    const CraneParameters& parameters() const { return parameters_; }  ///< as given, validated
    const CraneCycle& cycle() const { return cycle_; }  ///< the machine's program, as given
    const SimTK::MobilizedBody::Slider& trolley() const { return *trolley_; }  ///< the trolley, on a Slider along x
    const SimTK::MobilizedBody::Pin& drum() const { return *drum_; }  ///< the winch drum, on a Pin on the trolley
    const SimTK::MobilizedBody::Planar& hookBlock() const { return *hook_; }  ///< the hook block (x, y, rotation)
    /// The payload: a MobilizedBody::Pin on the hook block (Cycle) or a MobilizedBody::Planar from
    /// Ground (LiftOff); its frame origin is its centre of mass.
    const SimTK::MobilizedBody& payload() const { return *payload_; }
    int falls() const { return parameters_.falls; }  ///< number of falls n

    /// The state at t = 0: prescribed motions applied, hook block, payload and rope at static
    /// equilibrium (ReevingSubsystem::findStaticEquilibrium, relative residual <= 1e-9; LiftOff: the
    /// payload on the floor, the sling slack), motion work 0 (and contact dissipation 0), realized
    /// to Stage::Velocity.
    /// @throws std::runtime_error if the equilibrium is not found.
    SimTK::State makeInitialState() const;

    // ---- observables (Stage::Position unless said otherwise)
    double trolleyX(const SimTK::State& s) const;        ///< trolley position [m]
    SimTK::Vec3 hookPosition(const SimTK::State& s) const;  ///< hook block frame origin (its sheave centres) [m]
    /// The largest angle of a fall from the vertical [rad], >= 0: over the falls, of the chord
    /// between the fall's two ends (tangent points with wrapped sheaves, sheave centres with point
    /// sheaves). Vertical falls give 0; point sheaves lean by up to atan(sheavePitch / depth).
    double largestFallLean(const SimTK::State& s) const;
    /// Wrap angle of the rope on sheave k = 1..n-1 [rad] (ReevingSubsystem::getWrapAngle):
    /// pi at rest with wrapped sheaves, 0 with point sheaves (no rope on the groove).
    /// @throws std::invalid_argument if k is outside 1..n-1.
    double sheaveWrapAngle(const SimTK::State& s, int k) const;
    /// Length of rope on the sheaves' grooves [m]: the sum of R alpha over the sheaves (0 with
    /// point sheaves).
    double ropeOnSheaves(const SimTK::State& s) const;
    /// Rope conservation residual [m]: the spans' material lengths s2 - s1 plus the rope on the
    /// sheaves' grooves and on the drum, less the rope's length plus ropeOnDrum (what they sum to
    /// at drum angle 0). Zero up to round-off in either sheave model.
    double ropeLengthError(const SimTK::State& s) const;
    /// Angle of the falls from the vertical [rad]: of the line from the trolley to the hook block,
    /// measured from the hook's rest offset below the trolley; positive when the hook is on the +x
    /// side (0 at rest up to O(sheavePitch^2 / depth)).
    double swayAngle(const SimTK::State& s) const;
    /// Angle of the sling (hook block's pin to payload centre of mass) from the vertical [rad],
    /// positive when the payload is on the +x side of the pin.
    double payloadAngle(const SimTK::State& s) const;
    /// Axial force at the top (trolley end) of fall `fall` = 0..n-1 [N] (Stage::Dynamics for the
    /// QuasiStatic mode-acceleration correction, see ReevingSubsystem::getAxialForce).
    double fallTopForce(const SimTK::State& s, int fall) const;
    double drumSpeed(const SimTK::State& s) const;       ///< theta dot [rad/s] (Stage::Velocity)
    double ropeOnDrum(const SimTK::State& s) const;      ///< [m] (WinchDrumHandle::getRopeOnDrum)
    /// Torque the hoist motor applies to the drum about its axis [N m] (Stage::Acceleration): the
    /// generalized force that enforces the hoist profile.
    double motorTorque(const SimTK::State& s) const;
    /// Force the traverse drive applies to the trolley along x [N] (Stage::Acceleration).
    double trolleyForce(const SimTK::State& s) const;
    /// Ground positions of the rope's nodes 0..n (drum axis, sheave centres, dead end) [m].
    std::vector<SimTK::Vec3> nodePositions(const SimTK::State& s) const;
    /// Node k's location in its body's frame [m] (k = 0: the drum axis, drum frame).
    SimTK::Vec3 nodeStation(int k) const { return stations_.at(k); }
    /// true if node k is on the hook block, false if on the trolley or the drum.
    bool nodeOnHook(int k) const { return k % 2 == 1; }
    /// Horizontal offset of the hook block below the trolley at rest, in the trolley frame [m].
    double hookRestOffset() const { return hookRestOffset_; }

    // ---- hoist rope force and the lift-off scenario's references
    /// The hoist rope's force on the trolley: the sum over the falls of fallTopForce [N]
    /// (Stage::Dynamics). At rest with the load hanging it is about staticRopeForce().
    double ropeForce(const SimTK::State& s) const;
    /// Mass the rope lifts: payloadMass + hookMass [kg].
    double liftedMass() const { return parameters_.payloadMass + parameters_.hookMass; }
    /// The falls' length with the hook where the rope takes the load [m]: at initialHookDepth
    /// (Cycle) or ropeSlack() above it (LiftOff), the drum's fall drumHeight longer than the others.
    double fallsLength() const { return fallsLength_; }
    /// The loaded rope's length there [m]: fallsLength() plus, with wrapped sheaves, the half turns
    /// on the n - 1 sheaves, (n - 1) pi R.
    double loadedRopeLength() const { return loadedRopeLength_; }
    /// k: the hook's vertical stiffness through its falls there [N/m], n^2 EA / fallsLength() (a
    /// hook displacement x stretches the falls by n x, at uniform force over frictionless sheaves;
    /// the rope on wrapped sheaves' grooves is inextensible, GrooveArc): n EA / h for n falls of
    /// equal length h.
    double hookStiffness() const;
    /// The rope force that holds the lifted mass at rest [N]: the total over the falls at their
    /// tops, (payloadMass + hookMass) g + rhoA g (fallsLength() + the rope on the hook block's
    /// sheaves, floor(n / 2) pi R when wrapped): the load and the weight of the rope it hangs from.
    /// The reference of the dynamic factor, peak ropeForce / staticRopeForce.
    double staticRopeForce() const;
    /// The dynamic factor of a mass M = liftedMass() picked up by a massless spring k =
    /// hookStiffness() moving at v_h = hoistSpeed: 1 + v_h sqrt(k / M) / g.
    double springMassDynamicFactor() const;
    /// LiftOff: the slack the hoist takes up before the sling is taut, hoistSpeed (hoistRamp / 2 +
    /// slackTime) [m]; 0 in Cycle.
    double ropeSlack() const;
    /// LiftOff: height of the floor plane [m] (NaN in Cycle).
    double floorHeight() const { return floorHeight_; }
    /// LiftOff: the floor's vertical force on the payload, both corners [N] (Stage::Velocity; 0 in Cycle).
    double floorForce(const SimTK::State& s) const;
    /// LiftOff: the sling's force f [N] (Stage::Velocity; 0 while slack and in Cycle).
    double slingForce(const SimTK::State& s) const;
    /// LiftOff: height of the payload's lower bottom corner above the floor [m] (negative while
    /// the compliant floor is pressed in; NaN in Cycle).
    double payloadClearance(const SimTK::State& s) const;
    /// LiftOff: energy the floor's and the sling's dashpots have dissipated since the initial
    /// state, W_contact [J] (0 in Cycle).
    double contactDissipation(const SimTK::State& s) const;
    /// E_mech(t) - e0 + W_contact(t) - W_motion(t) [J] (Stage::Velocity; e0 = E_mech of the initial
    /// state).
    double energyResidual(const SimTK::State& s, double e0) const;

private:
    /// Body and Ground decorations (drawing only): trolley frame and wheels, rails over the
    /// traverse, hook block plate, shank and sling pin, payload block and sling legs.
    void addDecorations();
    CraneParameters parameters_;
    CraneCycle cycle_;
    std::vector<SimTK::Vec3> stations_;
    double hookRestOffset_ = 0;
    double fallsLength_ = 0;
    double loadedRopeLength_ = 0;
    double floorHeight_ = SimTK::NaN;
    std::unique_ptr<SimTK::MultibodySystem> system_;
    std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
    std::unique_ptr<SimTK::GeneralForceSubsystem> forces_;
    std::unique_ptr<SimTK::Force::Gravity> gravity_;
    std::unique_ptr<SimTK::ForceSubsystem> contacts_;  ///< LiftOff: floor and sling (Cycle: none, no state)
    std::unique_ptr<ReevingSubsystem> reeving_;
    std::unique_ptr<MotionWorkMeter> workMeter_;
    std::unique_ptr<SimTK::MobilizedBody::Slider> trolley_;
    std::unique_ptr<SimTK::MobilizedBody::Pin> drum_;
    std::unique_ptr<SimTK::MobilizedBody::Planar> hook_;
    std::unique_ptr<SimTK::MobilizedBody> payload_;
};

}  // namespace SimbodyReeving
