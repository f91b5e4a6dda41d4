#pragma once
/// @file
/// The Simbody side of SimbodyReeving: ropes of ALE spans over frictionless sheaves, attached to
/// Simbody bodies, inside an ordinary SimTK::MultibodySystem and integrated by any Simbody
/// integrator.

#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/SpanModel.h"

#include <Simbody.h>

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace SimbodyReeving {


/// How a rope meets its deviation sheaves (RopeSpec::sheaveModel).
enum class SheaveModel {
    /// The paper's point sheave (eq 30): both spans end at the sheave's centre and share its
    /// material coordinate; the rope on the groove has no length and no mass.
    Point,
    /// The rope wraps the groove: the spans end at the tangent points of the groove circle (radius
    /// DeviationSheave::radius, in the rope's plane) and the rope on the arc between them, of length
    /// R alpha, carries its mass (RopeModel's NodeWrap, GrooveArc; WrapStationMap maps the bodies'
    /// motion to the tangent points and arc lengths). The wrap sense is
    /// DeviationSheave::wrapSense: +1 when the rope, running from its start to its end, turns
    /// counter-clockwise about the plane normal on the groove, -1 clockwise. Applies to the DeviationSheave, TurningSheave and
    /// TractionSheave nodes of planar ropes (a TurningSheave's or TractionSheave's wrap sense follows
    /// from its sense and pin axis, see TurningSheave; a TractionSheave without a given wrap angle
    /// then takes the geometry's, see TractionSheave) and WinchDrum nodes (see WinchDrum). On a
    /// spatial rope (no plane normal) it applies to DeviationSheave nodes, each with its groove's
    /// axis (DeviationSheave::axis), and to TurningSheave and WinchDrum nodes, whose grooves turn
    /// about their pin axes: the spans arrive and leave at the 3D tangent points, out of the
    /// groove's plane by their fleet angles (getFleetAngles), and the arc lies in that plane (a
    /// gripping groove's material coordinate is measured from "up", gravity projected onto its
    /// plane: its axis must not be vertical). TractionSheave nodes too: their grooves turn about
    /// their pin axes, their pins' parents keeping Ground's orientation (see TractionSheave).
    Wrapped,
};

/// How a TractionSheave's rope moves over the groove in slip (TractionSheave::slipModel).
enum class TractionSlip {
    /// The rope's material at the sheave is a massless contact point: its material coordinate s_k
    /// is solved from the positions so that the capstan law P_{k-1} = e^(+-mu alpha) P_k holds at
    /// every instant (RopeModel's MaterialNode::Slipping). Without the centrifugal load of the rope
    /// on the groove (it would make the law depend on the rope's speed, which a coordinate solved
    /// from the positions cannot carry). mu = 0 is then exactly a DeviationSheave.
    CapstanConstraint,
    /// The rope on the groove is a dynamic coordinate in slip: Y (the rope's material coordinate at
    /// the groove's top; s_k itself at a point sheave) and its rate v = Ydot, the rope's speed over
    /// the groove relative to the sheave's centre, are states (Z entries), with the momentum balance
    ///     m_s Yddot + (S Y-row) yddot = P_{k-1} - P_k - sigma F,
    ///     F = max(P_tight - rhoA v^2, 0) (1 - e^(-mu alpha)),
    /// m_s the rope's reduced inertia at Y (RopeModel's nodeMass, spans and groove arc), sigma = +1
    /// while the rope slides towards its start (span k - 1 tight), -1 towards its end, alpha the wrap
    /// angle the law uses. In steady slip this is Euler-Eytelwein with the centrifugal term,
    /// (P_tight - rhoA v^2) = e^(mu alpha) (P_slack - rhoA v^2), for the span end forces exactly;
    /// the sheave receives the friction's reaction sigma F R. P are the total end forces,
    /// EA (eps + c epsdot) with the rope's Kelvin-Voigt damping c (which damps this coordinate's
    /// motion; RopeProperties::axialRetardationTime). The end-force difference stands in
    /// for the rope's own generalized force on Y (RopeModel's nodeForce there), as the tension
    /// equality does at a DeviationSheave (paper eq 32): they differ by O(eps P) (energy density
    /// and weight redistribution terms of the ALE spans) and by the groove arc's tangential weight
    /// and the spans' quadratic-velocity terms at Y; that difference's power is booked in the
    /// friction work, so E - E0 + W_friction = W_drives still closes. The s_k motion adds the
    /// rope's axial mode at the sheave (frequency about sqrt((EA / l_a + EA / l_b) / m_s)) to slip
    /// phases, and the transitions keep s_k and its rate continuous: stick ends when the friction
    /// that holds the rope, P_a - P_b - (S xddot)_Y (inertia included), reaches F of the side it
    /// would slide to (an event at Stage::Dynamics); slip ends when the slip rate returns to zero.
    /// Without damping that mode rings after each stick -> slip transition.
    RopeMomentum,
};

/// The phase of a TractionSheave (TractionSheaveHandle::getTractionMode).
enum class TractionMode {
    Stick,            ///< the rope moves with the groove
    SlipTowardStart,  ///< the rope slides over the groove towards the rope's start (span k - 1 tight)
    SlipTowardEnd,    ///< towards the rope's end (span k tight)
};

/// A station (point fixed on a body) where a rope end is fastened: a MobilizedBody (Ground allowed)
/// and the point's location in that body's frame [m].
struct RopeAnchor {
    SimTK::MobilizedBody body;  ///< the body the end is fastened to (Ground allowed)
    SimTK::Vec3 station{0};     ///< the point in the body's frame [m]
};

/// A frictionless deviation sheave: its centre on a body (Ground allowed) [m] and its radius [m].
/// With SheaveModel::Point (the paper's eq 30) the two spans meet at the sheave's centre and share
/// the material coordinate there: the wrap arc and the motion of the tangent points are neglected
/// (an O(radius / span length) geometric approximation) and the radius is used for validation and
/// drawing. With SheaveModel::Wrapped the spans end at the groove's tangent points and the rope on
/// the arc between them, R alpha long, carries its mass (see SheaveModel).
struct DeviationSheave {
    SimTK::MobilizedBody body;  ///< the body carrying the sheave (Ground allowed)
    SimTK::Vec3 centre{0};      ///< the sheave's centre in the body's frame [m]
    double radius = 0;          ///< [m], > 0
    /// With SheaveModel::Wrapped: +1 if the rope turns counter-clockwise about the plane normal
    /// (a spatial rope: about `axis`) on the groove (running from the rope's start to its end), -1
    /// clockwise.
    int wrapSense = 1;
    /// With SheaveModel::Wrapped on a spatial rope: the groove's axis in the body's frame [-], a
    /// unit vector. The rope arrives and leaves at any fleet angle (the angle between a span and
    /// the groove's plane). The body may turn in any way (a sheave on a slewing or luffing boom):
    /// the axis then turns with it, the rope's Lagrange equations carry the body's angular
    /// velocity (RopeModel's NodeWrap::turningAxis) and the rope's reaction on the sheave is a
    /// force at its centre and a couple. Not read for planar ropes.
    SimTK::Vec3 axis{0};
};

/// A winch drum at a rope end: a MobilizedBody::Pin (drive it with a Motion, a torque, a brake...),
/// its radius R [m] > 0, the rope stored on it at pin angle 0 [m] >= 0 (the stored rope is
/// ropeOnDrum - sense R theta at a point drum, plus the tangent point's roll and the grip's creep
/// at a wrapped one, below; the run ends when it reaches 0), the payout sense (+1: a positive
/// pin angle pays rope out) and the point on the pin axis where the rope node sits (drum body
/// frame, default its origin).
///
/// With SheaveModel::Wrapped the rope leaves the drum at the tangent point of its groove circle
/// (radius R, about the plane normal), not at its centre: s_0 = -sense R theta (s_N = L + sense R
/// theta) is then the material coordinate at the drum's top (against gravity), the rope leaves at
/// that plus sigma R phi (phi the tangent point's angle from the top, sigma = -sign(dsdTheta)
/// (pin axis . n)), and the stored rope, ropeOnDrum + s_0 (ropeOnDrum + L - s_N), counts the rope
/// up to the tangent point: ropeOnDrum is the rope stored up to the top at pin angle 0. Its parent
/// may turn about the plane normal (a drum on a rotating superstructure), as a wrapped
/// TurningSheave's (theta is then the drum's own angle, see there). The stored rope lies on
/// the groove and turns with the drum (its kinetic and gravity energies are those of one layer of
/// it, the partial turn included; RopeModel::setStoredRope), whatever the tangent point does.
/// A wrapped drum grips the rope where it leaves the groove (RopeModel::setGrip): the material
/// there moves with the groove's surface, sdot = v / lambda with v = Ydot_s + sigma R phidot the
/// groove's rate at the tangent point (the drum's surface speed plus the tangent point's roll) and lambda =
/// sqrt(1 + 2 eps) the fall's stretch there, so the rope is wound on at its strain and a load
/// hoisted straight up is not pulled sideways; the relation is not holonomic, so the state holds
/// the rope's creep c against the unstretched groove (s = s_ref - sense R theta + sigma R phi + c
/// at a start drum; c = 0 in the default state) and the strain energy U_w the wound rope keeps
/// (EA eps^2 / 2 per metre wound on since the start: part of the subsystem's potential energy,
/// so the drive's work still balances the mechanical energy). The drum then holds the rope with
/// its true force EA eps lambda. The stored ring turns with the groove and covers the groove the
/// rope was wound on; its amount is short of the rope wound on by the creep c (of order eps of
/// it), whose mass is held at the height where it was wound (its weight's energy is part of the
/// held energy too: the rope's mass is conserved and the drum's torque does not depend on the
/// height datum; the creep's mass does not turn with the drum). The stored ring's mass is
/// counted per metre of groove it covers.
struct WinchDrum {
    SimTK::MobilizedBody body;  ///< the drum: a MobilizedBody::Pin
    double radius = 0;          ///< R [m], > 0
    double ropeOnDrum = 0;      ///< rope stored on the drum at pin angle 0 [m], >= 0
    int payoutSense = 1;        ///< +1: a positive pin angle pays rope out; -1: it hauls rope in
    SimTK::Vec3 centre{0};      ///< the rope node's point on the pin axis, drum body frame [m]
    /// A drum that spools across its width (a spatial rope with SheaveModel::Wrapped): the axial
    /// advance of the rope's exit point per turn of rope stored, p [m] (about the rope's diameter
    /// on a grooved drum); p > 0 walks along the pin's +z (the drum's axis) as rope is stored,
    /// p < 0 along -z. The groove circle the rope leaves lies x = p (s_top - s_top,0) / (2 pi R)
    /// along the axis from `centre`, s_top the groove's coordinate at the drum's top (the drum's
    /// turns: s_0 = -sense R theta at the start, s_N = L + sense R theta at the end, the sign
    /// such that stored rope walks along +p); the tangent point's roll as the fall swings
    /// (sigma R phi) does not move it (the element layer's WalkingGroove). One layer, of
    /// unbounded width: the flanges and a second layer are not modelled. The stored rope stays a
    /// ring at `centre`.
    /// 0 (the default): the rope leaves the drum in `centre`'s plane. Finite, |p| < 2 pi R.
    double pitch = 0;
};

/// A sheave the rope turns without slip (drive sheave, idler with inertia): a MobilizedBody::Pin,
/// its radius R [m] > 0, the material coordinate at the sheave at pin angle 0 [m] (sets how the
/// rope is distributed on both sides: with no slip, that is history, not equilibrium), the sense
/// (s = s_ref + sense R theta: with +1 a positive pin angle moves rope from the end side of the
/// sheave to its start side, i.e. towards the rope's start) and the point on the pin axis
/// (body frame, default origin).
///
/// With SheaveModel::Wrapped the rope lies on the groove between its tangent points and moves with
/// it: s_ref is then the material coordinate at the groove's top (the point of the groove circle
/// against gravity, +y of the rope's plane without gravity) at pin angle 0, so the rope arrives on
/// the groove at s = s_ref + sense R theta + sigma R phi_in and leaves it at
/// s_ref + sense R theta + sigma R phi_out (phi the tangent points' angles from the top,
/// counter-clockwise about the plane normal n; WrapStationMap). Its wrap sense is
/// sigma = -sense (pin axis . n): the rope must turn on the groove that way, and the pin axis must be
/// along n (addRope throws otherwise). The pin's parent may turn about n (a jib head sheave on a
/// luffing boom): theta is then the sheave's own angle, its pin angle plus the parent's turn about
/// the pin axis from Ground's orientation (within half a turn: a run ends with a message when the
/// parent passes it), so the rope on the groove turns with the parent too. On a spatial rope the
/// groove turns about the pin axis n and the parent may turn in any way (a sheave on a slewing
/// and luffing boom): where it turns the axis too, theta is the sheave's angle about n measured
/// from "up" (-g) projected onto the groove's plane, its pin angle plus the turn of a parent
/// direction measured so, from the parent at Ground's orientation (its rate omega . m,
/// m = (n - a g_up) / (1 - a^2), a = n . g_up; gravity along n is refused by the rope model).
struct TurningSheave {
    SimTK::MobilizedBody body;                 ///< the sheave: a MobilizedBody::Pin
    double radius = 0;                         ///< R [m], > 0
    double materialCoordinateAtZeroAngle = 0;  ///< s_ref, the material coordinate at the sheave at pin angle 0 [m]
    int sense = 1;                             ///< +1 or -1: s = s_ref + sense R theta
    SimTK::Vec3 centre{0};                     ///< the rope node's point on the pin axis, body frame [m]
};

/// A traction sheave (see RopeNode): a MobilizedBody::Pin, radius R [m] > 0,
/// the groove's friction coefficient mu [-] >= 0 (an effective one: a V or undercut groove's
/// wedge factor included), the wrap angle alpha [rad] (0, the default: from the geometry), the
/// material coordinate at the sheave at pin angle 0 with no slip yet [m] (as for a TurningSheave;
/// TractionSheaveHandle::getSlipDistance counts from it), the sense (as for a TurningSheave) and
/// the point on the pin axis (body frame). It starts in stick.
///
/// The wrap angle from the geometry (wrapAngle 0), at every evaluation: with SheaveModel::Point the
/// turning angle between the two chords at the sheave's centre, alpha = pi - angle(p_a - r_k,
/// p_b - r_k) [rad] (p_a, p_b the spans' far ends; 0 for a rope running straight over it, where
/// the sheave has no traction; on a spatial rope the angle of the 3D chords, in the plane they
/// span); with SheaveModel::Wrapped, where the rope arrives and leaves at the groove's tangent
/// points (the pin's parent must keep Ground's orientation, addRope throws otherwise; on a planar
/// rope the pin axis must be along the plane normal, as for a wrapped TurningSheave), alpha = l / R,
/// the arc on the groove between the tangent points. On a spatial rope the groove turns about the
/// pin axis n and the spans arrive and leave at the 3D tangent points, out of the groove's plane
/// by their fleet angles (getFleetAngles): alpha is then the angle in the groove's plane between
/// the radius vectors to the two tangent points (the fleet angles do not add to it), and s_ref is
/// measured from "up" (-g, +y without gravity) projected onto that plane. The stick limit e^(mu alpha)
/// and, in slip, the capstan law P_{k-1} = e^(+-mu alpha) P_k (RopeModel::setSlipLaw, whose
/// derivatives in the positions or in l enter the coupled solve) follow a deflector, a moving car
/// or a leaning fall. A given alpha (double wrap, an arrangement the geometry does not show) is
/// used as given with either model. In stick
/// s_k = s_stick + sense R theta is the material coordinate at the groove's top (WrapStationMap).
///
/// Two slip models (slipModel, TractionSlip): the default CapstanConstraint solves s_k from the
/// positions (a massless contact point, the law without the rope's speed); RopeMomentum makes the
/// rope on the groove a state of its own in slip, with the rope's inertia there, the
/// centrifugal load rhoA v^2 in the law, (P_tight - rhoA v^2) = e^(mu alpha) (P_slack - rhoA v^2)
/// in steady slip, and a stick limit on the friction that holds the rope (inertia included). Its
/// cost: the rope's axial mode at the sheave joins the slip phases, and an explicit integrator's
/// steps follow it (docs/elevator.md).
///
/// What it does not model: the tension varies along the wrap arc (P e^(mu phi) in slip, and the
/// creep of an elastic rope in stick: the whole arc sticks here); groove wear and pressure limits. A slack span at the sheave (tension-only rope) leaves P_a / P_b
/// undefined: both forces at or below 0 keep the sheave in its mode. On a spatial rope, the rope
/// on the groove does not walk across it (the fleet angles' side load is not modelled), and at a
/// point sheave whose chords are parallel (alpha = pi or 0) the plane of the chords, and so alpha's
/// derivative across it, is undefined (a kink): its derivative is then taken in Ground's x-y plane
/// (RopeModel::wrapAngle; a point node has no groove axis).
///
/// With Kelvin-Voigt rope damping (RopeProperties::axialRetardationTime c > 0) CapstanConstraint's
/// law and stick limit act on the elastic forces P = EA eps at the node, not on EA (eps + c Deps/Dt)
/// (RopeMomentum's act on the total forces, EA (eps + c epsdot) at the span ends).
/// In slip the elastic ratio is held at e^(mu alpha) at every instant, so the strain rates at
/// the node keep that ratio too and the total forces follow it (exactly for uniform strain along
/// the spans; otherwise up to c EA times the strain gradient times the slip rate). What differs is
/// the onset of slip, which waits until the elastic ratio reaches e^(mu alpha): about c later than
/// the total force ratio does. RopeMomentum has the total forces' law.
///
/// Chatter: where neither mode is consistent, the sheave switches at the scale of the events'
/// hysteresis (1e-9 of the rope force, 1e-9 m/s). With a slack side and a huge mu alpha, slip
/// decelerates to zero rate while the slack side is at zero force, and stick lets the slack side
/// go slack at once. The motion is the Filippov average of both (rope at the groove's speed, slack
/// side at zero force) and the energy still closes, but every switch is an event; larger
/// hystereses would break the mu = 0 = DeviationSheave equivalence. Whether a run enters it depends
/// on round-off (the slack side's force is round-off there); docs/elevator.md has the elevator's
/// transition counts and costs.
struct TractionSheave {
    SimTK::MobilizedBody body;                 ///< the sheave: a MobilizedBody::Pin
    double radius = 0;                         ///< R [m], > 0
    double frictionCoefficient = 0;            ///< mu [-], >= 0 (effective: groove shape included)
    double wrapAngle = 0;                      ///< alpha [rad]; 0: from the geometry (see above)
    double materialCoordinateAtZeroAngle = 0;  ///< s_ref at pin angle 0 with no slip yet [m]
    int sense = 1;                             ///< +1 or -1, as for a TurningSheave
    SimTK::Vec3 centre{0};                     ///< the rope node's point on the pin axis, body frame [m]
    /// How the rope slips (TractionSlip; the default keeps the paper-style massless contact point).
    TractionSlip slipModel = TractionSlip::CapstanConstraint;
};

/// A node of a rope's path: one of the five kinds, each its own struct, so a node carries only its
/// kind's fields. Each kind fixes how the node's position and its material coordinate s are
/// determined (RopeModel's MaterialNode in brackets):
///   - RopeAnchor: a rope end fastened to a station of a body [Fixed: s_0 = 0, s_N = L].
///   - DeviationSheave: a frictionless, massless sheave in the path [Sliding: the axial forces of
///     both spans are equal there, paper eq 32].
///   - WinchDrum: a rope end wound on a drum that turns with a MobilizedBody::Pin [Driven]:
///     at the rope's end node s_N = L + sense R theta, at its start node s_0 = -sense R theta, with
///     theta the pin angle (its q) and sense = +1 when a positive theta pays rope out.
///   - TurningSheave: a sheave in the path on a MobilizedBody::Pin that the rope turns without slip,
///     a drive sheave (motor on the pin) or an idler with inertia [Driven]:
///     s_k = s_ref + sense R theta. With sense = +1 a positive theta raises s_k: material that was
///     on the end side of the sheave passes to the start side (the rope moves from the end side
///     towards the start); sense = -1 reverses that.
///   - TractionSheave: a sheave in the path on a MobilizedBody::Pin whose groove drives the rope by
///     friction (an elevator's machine sheave), coefficient mu, wrap angle alpha; with P_a, P_b the
///     axial forces of the spans before and after it:
///       stick [Driven]: s_k = s_stick + sense R theta while e^(-mu alpha) <= P_a / P_b <= e^(mu alpha);
///       slip [Slipping]: s_k is free, P_tight = e^(mu alpha) P_slack (Euler-Eytelwein), the tight
///       side the one the rope slides towards relative to the groove; the friction force P_a - P_b
///       turns the pin (torque sense R (P_a - P_b)) and dissipates (P_a - P_b) v_slip >= 0.
///     Transitions are events (TractionMode): stick -> slip when the ratio reaches a limit, slip ->
///     stick when the slip rate returns to zero; s_k is continuous through both.
/// Driven nodes (all but a wrapped WinchDrum, see the end of this paragraph): the material
/// coordinate tracks R theta exactly (a holonomic tie), i.e. the rope on the drum or sheave is
/// taken as inextensible. Rope leaves a span at the strain it has there;
/// its strain energy leaves the model with it, through the rope's generalized force on s, so the
/// energy balance stays exact: the work of whatever drives the pin equals the change of the
/// system's mechanical energy (MotionWorkMeter, PinnedNodeHandle::getPower). Tracking
/// R theta / stretch instead (rope wound at its strain) would make s depend on the strain: not
/// holonomic, and different by the strain in the hoisting speed; a wrapped WinchDrum does so all
/// the same (it grips the rope at its tangent point: see WinchDrum). The rope stored on a WinchDrum
/// keeps its mass: a ring of rhoA (ropeOnDrum - sense R theta) at radius R on the node, whose
/// weight and inertia load the drum's body and whose kinetic and gravity energy are part of the
/// rope's (RopeModel::setStoredRope; without it the drum torque would depend on the height datum).
/// Do not add that rope to the drum body's mass as well. The node's position is the point on the
/// pin axis; with SheaveModel::Point the wrap arc is not modelled (point sheaves, as the paper).
///
/// A rope's ends are RopeEnd and the nodes of its path RopeSheave (RopeSpec), so a sheave at a
/// rope's end or a drum in its path does not compile. Every kind's struct converts implicitly to
/// the variants that hold it (rope.start = RopeAnchor{...}; rope.sheaves = {DeviationSheave{...}}).
using RopeNode = std::variant<RopeAnchor, DeviationSheave, WinchDrum, TurningSheave, TractionSheave>;
/// A rope end: fastened to a body or wound on a drum.
using RopeEnd = std::variant<RopeAnchor, WinchDrum>;
/// A node inside a rope's path: a sheave with a span on both sides.
using RopeSheave = std::variant<DeviationSheave, TurningSheave, TractionSheave>;

/// Everything that describes one rope. SI units.
struct RopeSpec {
    std::string name = "rope";       ///< names the rope in messages (limits, failed evaluations)
    RopeEnd start;                   ///< a RopeAnchor or a WinchDrum
    std::vector<RopeSheave> sheaves; ///< DeviationSheave, TurningSheave or TractionSheave, in path order
    RopeEnd end;                     ///< a RopeAnchor or a WinchDrum
    RopeProperties properties;       ///< rhoA, EA, EI (see RopeProperties)
    /// Unstretched length L of the rope between its start and end nodes at pin angles 0 [m], > 0
    /// (material coordinates: s = 0 at an anchored start, s = L at an anchored end).
    double unstretchedLength = 0;
    /// Shortest unstretched span length the run accepts [m], > 0: a span whose material length
    /// reaches it (two-blocking: the hook block at the trolley sheaves; a drum hauling the last
    /// span in) ends the run cleanly, as does a drum running out of rope or, with
    /// SheaveModel::Wrapped, a sheave's wrap angle falling to 0 (the rope leaving its groove) or,
    /// on a spatial rope, a span's fleet angle at a groove reaching 85 degrees (towards the groove's
    /// axis, where the span has no tangent point): the
    /// subsystem's event handler requests termination (Integrator::EventHandlerRequestedTermination)
    /// and getLimitReached() names the rope, span, drum or sheave and the time.
    double minimumSpanLength = 0.2;
    SpanOptions spanDefaults;               ///< mode counts and options of every span...
    std::vector<std::pair<int, SpanOptions>> spanOverrides;  ///< ...except these (span index, options)
    /// Non-zero: the rope is planar, all its nodes stay in the plane through the start anchor with
    /// this normal (gravity must lie in it); spans are then planar (no out-of-plane modes or work).
    /// Zero: spatial spans.
    SimTK::Vec3 planeNormal{0};
    /// The sheaves' and drums' model: SheaveModel::Point (the paper's) or SheaveModel::Wrapped.
    SheaveModel sheaveModel = SheaveModel::Point;

    /// Number of nodes: the sheaves and both ends.
    int numNodes() const { return static_cast<int>(sheaves.size()) + 2; }
    /// Node k (0: start, numNodes() - 1: end, else sheaves[k - 1]) as a RopeNode.
    /// @throws std::out_of_range if k is outside 0..numNodes() - 1.
    RopeNode node(int k) const;
};

class RopeHandle;

/// A SimTK::ForceSubsystem holding every rope of a MultibodySystem.
///
/// Rope state: the modal coordinates q_m of all spans and their rates live in Z (two entries per
/// modal coordinate: value, rate). Node positions come from the bodies each evaluation; the
/// material coordinates at sheaves are dependent, solved from the tension equality (RopeModel).
///
/// Coupling: in realizeDynamics the subsystem reads the rigid-body and mobility forces already
/// applied by earlier force subsystems, asks SimbodyMatterSubsystem::calcAcceleration for the
/// bodies' free accelerations and their response to unit forces at the rope nodes, and solves the
/// rope's reduced equations together with those (a Schur complement on the node forces f):
///     (I + S Lambda) f = S a0 - h,
/// S, h the rope reduced to its external coordinates (node positions on bodies other than Ground,
/// and the material coordinates of WinchDrum / TurningSheave nodes, s = s_ref + sense R theta), a0
/// their free accelerations, Lambda the bodies' mobility at them (for a driven s: the pin's, scaled
/// by (sense R)^2). -f is applied to the bodies (forces at the stations, torques sense R f_s on the
/// pins) and the rope's modal accelerations follow. The solve honours Simbody's constraints and
/// prescribed motion (a drum on a speed profile) because calcAcceleration does.
///
/// Must be constructed after every other force subsystem of the system that applies forces
/// (GeneralForceSubsystem included; a MotionWorkMeter may come later): realizeTopology throws
/// std::logic_error otherwise.
///
/// Energy: the rope's strain and gravity energy are this subsystem's potential energy (so
/// MultibodySystem::calcPotentialEnergy includes them); its kinetic energy is calcRopeKineticEnergy;
/// calcMechanicalEnergy returns the whole system's T + U.
class ReevingSubsystem : public SimTK::ForceSubsystem {
public:
    /// Gravity on the ropes (both constructors): the ropes must feel the gravity the bodies feel,
    /// the sum g_sys of the gravity vectors of every Force::Gravity and Force::UniformGravity in the
    /// system's GeneralForceSubsystems that is not disabled (several such forces add up on the
    /// bodies, so they add up here too). The rope models are built with one gravity vector, fixed
    /// at realizeTopology; Force::Gravity's magnitude and direction can also be set per State
    /// (parameters that invalidate Stage::Dynamics) and forces disabled per State, so every
    /// realizeDynamics checks that the state's g_sys (enabled forces, their current magnitude and
    /// direction) still equals it and throws std::logic_error (both vectors in the message) if it
    /// does not: change gravity through the defaults (Force::Gravity::setDefaultGravityVector, ...)
    /// and realizeTopology again, not per state.
    ///
    /// This constructor takes the ropes' gravity from the system: g_sys of the forces' defaults at
    /// realizeTopology (zero when the system has no gravity force, as its bodies then feel none).
    explicit ReevingSubsystem(SimTK::MultibodySystem& system);
    /// This constructor gives the ropes' gravity explicitly [m/s^2]. If the system has a gravity
    /// force (see above), realizeTopology throws std::logic_error unless `gravity` equals g_sys of
    /// the defaults (to 1e-12 |g|, round-off of a sum); with no gravity force in the system the
    /// given vector is used as is (bodies loaded by some other force).
    /// @throws std::invalid_argument for non-finite gravity.
    ReevingSubsystem(SimTK::MultibodySystem& system, const SimTK::Vec3& gravity);

    /// The gravitational acceleration acting on the ropes [m/s^2]: the constructor's, or (the
    /// one-argument constructor) the system's, taken at realizeTopology (zero before).
    SimTK::Vec3 getGravity() const;

    /// Adds a rope; returns its handle, which converts to the rope's index (0, 1, ... in the order
    /// the ropes are added) for the queries that take one. Must be called before realizeTopology.
    /// @throws std::invalid_argument naming the problem: empty node body, a body of another
    ///         system, non-finite station, a WinchDrum or TurningSheave whose body is not a MobilizedBody::Pin or whose point is
    ///         off the pin axis, sense not +-1, negative ropeOnDrum, non-positive or non-finite
    ///         radius, rope length or minimumSpanLength, bad rope properties or mode counts, a span
    ///         override index out of range, non-finite plane normal, gravity out of the rope plane
    ///         (gravity given to the constructor; with the system's gravity, realizeTopology checks
    ///         the plane and throws std::logic_error); with SheaveModel::Wrapped, a
    ///         wrap sense not +-1, a TractionSheave whose pin's parent turns relative to Ground, a
    ///         WinchDrum (or a planar rope's TurningSheave) whose pin's parent turns about another
    ///         axis than the pin's, a planar rope's TurningSheave, TractionSheave or WinchDrum whose
    ///         pin axis is not the plane normal, or a spatial rope's DeviationSheave without a unit
    ///         axis.
    RopeHandle addRope(const RopeSpec& spec);

    /// Number of ropes added.
    int getNumRopes() const;
    /// The handle of rope `rope` (its index from addRope): the way to its nodes' kind-specific
    /// queries (RopeHandle::getWinchDrum, getTurningSheave, getTractionSheave).
    /// @throws std::invalid_argument if rope is out of range.
    RopeHandle getRope(int rope) const;
    /// The spec a rope was added with (rope index from addRope).
    const RopeSpec& getRopeSpec(int rope) const;
    /// Number of spans of a rope: its nodes less one.
    int getNumSpans(int rope) const;
    /// True if the rope is planar (RopeSpec::planeNormal non-zero).
    bool isPlanar(int rope) const;
    /// Number of modal coordinates of a rope (its Z holds these and as many rates).
    int getNumModalCoordinates(int rope) const;

    /// The rope's modal coordinates [m] (Stage::Model or later).
    SimTK::Vector getModalCoordinates(const SimTK::State& state, int rope) const;
    /// Sets the rope's modal coordinates [m], getNumModalCoordinates(rope) of them.
    void setModalCoordinates(SimTK::State& state, int rope, const SimTK::Vector& q) const;
    /// The rates of the rope's modal coordinates [m/s] (Stage::Model or later).
    SimTK::Vector getModalRates(const SimTK::State& state, int rope) const;
    /// Sets the rates of the rope's modal coordinates [m/s].
    void setModalRates(SimTK::State& state, int rope, const SimTK::Vector& qdot) const;

    // ---- queries (Stage::Position unless said otherwise) ------------------------------------
    /// Axial force P = EA eps at material point s of a span [N] (EA max(eps, 0) for a tension-only
    /// rope, RopeProperties::tensionOnly).
    /// For spans with AxialDynamics::QuasiStatic, at Stage::Dynamics or later the strain includes the
    /// mode-acceleration correction (the quasi-static response to the rope's inertial load, see
    /// RopeModel::recoverInertialStrain; the point is taken at the same relative position of the
    /// corrected span); below Stage::Dynamics it is the condensed (stationary) strain.
    /// @throws std::invalid_argument if rope, span or s is out of range.
    double getAxialForce(const SimTK::State& state, int rope, int span, double s) const;
    /// Physical tension T = EA eps |dr/ds| at material point s of a span [N] (see SpanModel::tension).
    /// @throws std::invalid_argument if rope, span or s is out of range.
    double getTension(const SimTK::State& state, int rope, int span, double s) const;
    /// Largest Green strain of a span [-] (SpanModel::maxStrain: both ends and the strain
    /// quadrature points), from the position-level span coordinates.
    /// @throws std::invalid_argument if rope or span is out of range.
    double getSpanMaxStrain(const SimTK::State& state, int rope, int span) const;
    /// true if the rope is tension-only (RopeProperties::tensionOnly) and the span is slack
    /// everywhere: getSpanMaxStrain <= 0, so the span carries no axial force. SlackMonitor records
    /// when spans go slack and taut during a simulation.
    /// @throws std::invalid_argument if rope or span is out of range.
    bool isSpanSlack(const SimTK::State& state, int rope, int span) const;
    /// Force the rope exerts on the body at node k, in Ground [N] (Stage::Dynamics): the reaction
    /// of the coupled solve, F_k = h_k - sum_b S_kb a_b, with S, h the rope reduced to its nodes
    /// (the modal and sheave coordinates eliminated) and a_b the node accelerations (zero on Ground).
    /// k = 0 is the start anchor, 1..N-1 the sheaves (there F_k is the bearing load, the resultant of
    /// both spans), N the end anchor. Unlike getAxialForce at a span end, which carries the sine
    /// series' O(1/n_a) truncation bias of the strain, F_k is the force the bodies actually receive:
    /// at static equilibrium it balances the attached body exactly (payload: F_N = -M g), and it
    /// includes the rope's inertia and weight lumped consistently at the node.
    /// @throws std::invalid_argument if rope or node is out of range.
    /// @throws std::logic_error if the state is not realized to Stage::Dynamics.
    SimTK::Vec3 getNodeForce(const SimTK::State& state, int rope, int node) const;
    /// The wrap angle alpha [rad] (Stage::Position): at a TractionSheave the one its capstan law
    /// uses (the given one, else the current geometry's as below); at any other sheave the current
    /// geometry's: l / R with l = getArcLength with SheaveModel::Wrapped (planar or spatial), the
    /// turning angle between the chords of the two spans at a point sheave (pi - the angle between
    /// them at the node, in [0, pi]; of a spatial rope in the plane the two chords span;
    /// RopeModel::wrapAngle).
    /// @throws std::invalid_argument if rope or node is out of range, or the node is an end node.
    double getWrapAngle(const SimTK::State& state, int rope, int node) const;
    /// Length l = R alpha of the rope on node k's groove [m] (Stage::Position): > 0 at a wrapped
    /// DeviationSheave, TurningSheave or TractionSheave, 0 at every point node and at a wrapped
    /// WinchDrum (the rope beyond its tangent point is stored rope, WinchDrumHandle::getRopeOnDrum). The rope's
    /// length is the sum over its spans of s2 - s1 (getSpanMaterialRange), over its nodes of l and
    /// of the rope on its drums.
    /// @throws std::invalid_argument if rope or node is out of range.
    double getArcLength(const SimTK::State& state, int rope, int node) const;
    /// Radius R of the groove or drum the rope bends over at node k [m]: the node's radius
    /// (DeviationSheave, TurningSheave, TractionSheave, WinchDrum; > 0), 0 at a RopeAnchor (the
    /// rope ends there unbent). A rope of diameter d bends at D/d = 2 R / d there (RopeLifeMonitor).
    /// Fixed at addRope: needs no state.
    /// @throws std::invalid_argument if rope or node is out of range.
    double getNodeRadius(int rope, int node) const;
    /// The material interval [s_a, s_b] of rope on node k [m] (Stage::Position), s_a <= s_b: at a
    /// sheave (k = 1..N-1) from where the rope arrives on it (s_a, the end of span k - 1,
    /// getSpanMaterialRange) to where it leaves (s_b, the start of span k): one point (s_a = s_b =
    /// getMaterialCoordinate) at a point sheave, the arc s_b - s_a = getArcLength at a wrapped one;
    /// at a WinchDrum the rope on it, unbounded on its stored side: (-inf, s_0] at a start drum,
    /// [s_N, +inf) at an end drum, s_0 and s_N the material coordinates where the rope leaves it
    /// (getStoredRope gives the stored rope's length); at a RopeAnchor the rope's end, s_a = s_b =
    /// 0 at the start, L at the end (the unstretched length).
    /// @throws std::invalid_argument if rope or node is out of range.
    /// @throws std::logic_error if the state is not realized to Stage::Position.
    std::pair<double, double> getNodeMaterialInterval(const SimTK::State& state, int rope, int node) const;
    /// The unit axis in Ground [-] the rope turns about over node k as it runs from its start
    /// towards its end (right hand; Stage::Position): at a wrapped sheave its wrap sense about its
    /// groove's axis (DeviationSheave::wrapSense times its axis in Ground; a TurningSheave or
    /// TractionSheave: -sense times its pin axis); at a point sheave the turn between the chords
    /// of spans k - 1 and k (their cross product, normalized; zero if they are parallel); at a
    /// WinchDrum, point or wrapped, payoutSense times its pin axis at a start drum, -payoutSense
    /// times it at an end drum; zero at a RopeAnchor. On a planar rope it is the plane normal or
    /// its opposite (RopeSpec::planeNormal normalized; zero where the axis is in the plane). Two
    /// bends of a rope section about opposite axes bend it to opposite sides (a reverse bend,
    /// RopeLifeMonitor).
    /// @throws std::invalid_argument if rope or node is out of range.
    /// @throws std::logic_error if the state is not realized to Stage::Position.
    SimTK::Vec3 getNodeBendAxis(const SimTK::State& state, int rope, int node) const;
    /// The rope stored at node k [m] (Stage::Position), >= 0 while the drum has rope: at a
    /// WinchDrum the rope on it beyond its tangent point (WinchDrumHandle::getRopeOnDrum:
    /// ropeOnDrum + s_0 at a start drum, ropeOnDrum + L - s_N at an end drum); 0 at every other
    /// node. The rope's material runs from s_0 - getStoredRope(0) to s_N + getStoredRope(N).
    /// @throws std::invalid_argument if rope or node is out of range.
    /// @throws std::logic_error if the state is not realized to Stage::Position.
    double getStoredRope(const SimTK::State& state, int rope, int node) const;
    /// The fleet angles gamma [rad] of a span (Stage::Position): at its start and at its end, the
    /// angle between the span and the groove's plane of the wrapped sheave it leaves or reaches
    /// (positive towards the groove's axis), asin(u . n) with u the span's direction; 0 at point
    /// nodes and anchors and on planar ropes (the span lies in every groove's plane).
    /// @throws std::invalid_argument if rope or span is out of range.
    std::pair<double, double> getFleetAngles(const SimTK::State& state, int rope, int span) const;
    /// Work dissipated by friction in every TractionSheave of every rope [J].
    double getTotalFrictionWork(const SimTK::State& state) const;
    /// Puts every sticking TractionSheave whose force ratio is outside [e^(-mu alpha), e^(mu alpha)]
    /// into slip towards its tight side (realizes the state to Stage::Position first). The events
    /// only see a ratio that crosses the limit during a step; call this on an initial state that may
    /// start beyond it (e.g. a static equilibrium found in stick, which holds any ratio), before the
    /// integrator is initialized. Returns the number of sheaves put into slip. The material
    /// coordinate at such a sheave moves to where the capstan ratio holds (a new initial condition).
    int updateTractionModes(SimTK::State& state) const;

    /// The rope limit that ended the last run ("" if none): a span reaching
    /// RopeSpec::minimumSpanLength, a drum running out of rope, a wrapped sheave's wrap angle
    /// reaching 0 or a span's fleet angle reaching 85 degrees, with rope, span or node, and time.
    /// Cleared when a state is realized to Stage::Instance afresh (an integrator's initialize).
    const std::string& getLimitReached() const;

    /// Material coordinate s at node k (0 = start anchor, N = end anchor) [m]; at a wrapped sheave,
    /// where the rope arrives on the groove.
    double getMaterialCoordinate(const SimTK::State& state, int rope, int node) const;
    /// Material coordinate range [s1, s2] of a span [m] (a span leaving a wrapped sheave starts at
    /// the sheave's s plus the arc's length R alpha).
    std::pair<double, double> getSpanMaterialRange(const SimTK::State& state, int rope, int span) const;
    /// F_a - F_b at sheave k (1..N-1) [N]: the tension-equality residual at a DeviationSheave; at a
    /// TurningSheave the force its grip carries (not a residual).
    double getConstraintError(const SimTK::State& state, int rope, int sheave) const;
    /// Largest |F_a - F_b| over all DeviationSheaves of all ropes [N].
    double getMaxConstraintError(const SimTK::State& state) const;
    /// Positions in Ground of numPoints >= 2 equally spaced material points of a span [m].
    std::vector<SimTK::Vec3> sampleSpan(const SimTK::State& state, int rope, int span, int numPoints) const;
    /// Positions in Ground of numPoints >= 2 equally spaced material points of the rope on the
    /// groove of node k, a wrapped DeviationSheave or TurningSheave (SheaveModel::Wrapped) [m]
    /// (Stage::Position): from the arrival tangent point (the end of span k - 1, sampleSpan's last
    /// point) along the groove circle (radius R about the sheave's centre, the node's station on its
    /// body, in the rope plane) in the wrap sense (DeviationSheave::wrapSense; for a TurningSheave
    /// -sense (pin axis . n)) through the wrap angle getWrapAngle, to the
    /// departure tangent point (the start of span k, to round-off). With sampleSpan it draws the
    /// rope without a gap at its sheaves.
    /// @throws std::invalid_argument if rope or node is out of range, the node is not a wrapped
    ///         sheave (a point node or a wrapped drum has no arc), or numPoints < 2.
    std::vector<SimTK::Vec3> sampleArc(const SimTK::State& state, int rope, int node, int numPoints) const;
    /// Power dissipated by the ropes' Kelvin-Voigt damping (RopeProperties::axialRetardationTime)
    /// [W], >= 0 (Stage::Velocity).
    double getDampingPower(const SimTK::State& state) const;
    /// Work dissipated by the ropes' damping since the start [J] (the integral of getDampingPower:
    /// a Z entry per damped rope). With getTotalFrictionWork and the drives' work (MotionWorkMeter)
    /// it closes the energy balance E(t) - E(0) + W_friction + W_damping = W_drives.
    double getDampingWork(const SimTK::State& state) const;
    /// Rope kinetic energy [J] (Stage::Velocity).
    double calcRopeKineticEnergy(const SimTK::State& state) const;
    /// Rope strain + gravity energy [J].
    double calcRopePotentialEnergy(const SimTK::State& state) const;
    /// Whole-system mechanical energy: bodies' kinetic energy + every force subsystem's potential
    /// energy (this one's included) + rope kinetic energy [J] (Stage::Velocity).
    double calcMechanicalEnergy(const SimTK::State& state) const;

    /// Evaluation failures since construction: realizations at which a rope's dependent coordinates
    /// (sheave material coordinates, quasi-static axial amplitudes) could not be solved, each thrown
    /// as std::runtime_error naming the rope, the time and the equation (sheave or span). They
    /// happen at integrator trial states that extrapolate too far; Simbody 3.7's integrators catch
    /// the exception, reject the step and retry with a smaller one, so most never end a run. When
    /// one does, the integrator's own message may not carry the cause (CPodes: "CPodes::step()
    /// returned an error"): getLastEvaluationFailure has it.
    int getNumEvaluationFailures() const;
    /// The message of the last evaluation failure ("" if none).
    const std::string& getLastEvaluationFailure() const;

    /// Moves `state` to static equilibrium of bodies and ropes together (velocities and modal
    /// rates set to zero): Newton's method on the accelerations, until the generalized force
    /// residual is <= relativeTolerance times the largest applied generalized force. Mobilities
    /// with prescribed motion (SimTK::Motion) keep it: they are neither unknowns nor residuals
    /// (a drum held by its motion is a fixed drum here). The balance is that of a system at rest:
    /// it is evaluated with every speed zero, the prescribed ones included, so velocity-dependent
    /// forces (Kelvin-Voigt rope damping, a rope dragged over a sheave prescribed to turn) do not
    /// enter it; on return the prescribed mobilities have their motion's speeds again (the state is
    /// ready for a run that starts in steady motion: set the free speeds after this call). Each
    /// iteration moves a mobility or modal coordinate by at most 0.5 (m or rad), so a body hanging
    /// from a slack tension-only rope (no stiffness) falls until the rope takes it; trial states
    /// the rope cannot evaluate are rejected by the line search.
    /// Returns the achieved relative residual.
    /// @throws std::runtime_error if it does not converge in maxIterations.
    double findStaticEquilibrium(SimTK::State& state, double relativeTolerance = 1e-10, int maxIterations = 50) const;

    // ---- span frames of spatial ropes ---------------------------------------------------------
    // A spatial span's transverse modes are expressed in its element frame A_e = R(i0 -> i_e) A0,
    // the minimal rotation of a reference frame A0 = [i0 j0 k0] onto the chord (ChordFrame); A0 is
    // part of the State (a discrete variable of this subsystem):
    //   - defined when the state is first realized to Stage::Position, from that configuration:
    //     A0 = makeReferenceFrame(chord) for every span (i0 along the chord, j0 the world axis least
    //     aligned with it). A state from getDefaultState() has none yet; copies of a state keep
    //     its frames. So a run's frames come from its initial state's configuration (set the
    //     initial q before realizing; findStaticEquilibrium keeps the frames of the configuration
    //     it starts from). resetSpanFrames redefines them from the current chords at any time.
    //   - changed by an event when a chord turns far from its reference: when 1 + i0 . i_e falls to
    //     getFrameChangeAlignment() (default 0.5: 120 degrees), A0 becomes the current element
    //     frame and the span's transverse modal coordinates and rates are rotated into it, so the
    //     rope's configuration and velocity field are unchanged (exactly, to round-off; with
    //     VelocityModel::Simplified the field of that model). Chords may thus turn without limit
    //     (a slewing crane); without the change ChordFrame is singular at chord reversal.
    //   Planar ropes have no reference frame (their frame is the plane's).

    /// Sets the alignment a = 1 + i0 . i_e at which a spatial span's reference frame is changed
    /// [-], in [0.01, 1.99] (0.01: the chord about 172 degrees from its reference; 1.99: 8 degrees).
    /// The frame's twist rate about the chord grows like tan(theta / 2) with the angle theta
    /// between chord and reference, so small values let it grow (14 per radian at 0.01).
    /// @throws std::invalid_argument outside the range.
    void setFrameChangeAlignment(double alignment);
    /// The alignment set by setFrameChangeAlignment [-] (default 0.5).
    double getFrameChangeAlignment() const;
    /// Number of reference-frame changes of a rope's spans in this state's history (0 for planar
    /// ropes and before the first change).
    /// @throws std::invalid_argument if rope is out of range.
    int getNumFrameChanges(const SimTK::State& state, int rope) const;
    /// The reference frame A0 = [i0 j0 k0] of a spatial rope's span in this state (Stage::Position).
    /// @throws std::invalid_argument if rope or span is out of range or the rope is planar.
    SimTK::Mat33 getSpanReferenceFrame(const SimTK::State& state, int rope, int span) const;
    /// Redefines the reference frames of every spatial span from the current chords (A0 = the
    /// current element frame), rotating the transverse modal coordinates and rates so that the
    /// ropes' configuration and velocity field are unchanged. Realizes the state to Stage::Velocity.
    void resetSpanFrames(SimTK::State& state) const;

    /// Number of rope node pairs drawn per span by the decorations (default 20).
    void setDecorationResolution(int pointsPerSpan);
    /// What the decorations draw (any SimTK::Visualizer, at Stage::Position): each span as a
    /// polyline coloured by its axial force P = EA eps at each segment's midpoint, through the
    /// colour map c(x) = (1 - x) blue (0.1, 0.3, 1) + x red (1, 0.1, 0.05), x = clamp(P / P_ref, 0, 1)
    /// (blue: slack or P = 0; red: P >= P_ref); the rope on the groove of every wrapped
    /// DeviationSheave (sampleArc, as many points as a span) in the colour of the axial force at
    /// the end of the span arriving there; every DeviationSheave and TurningSheave as a disc of
    /// its radius in the plane of its spans (a TurningSheave with a spoke that turns with its pin);
    /// every WinchDrum as a drum of its radius with the stored rope (WinchDrumHandle::getRopeOnDrum) wound on it as a
    /// helix in layers (rope diameter for drawing only: that of a steel wire rope of the rope's rhoA,
    /// d = sqrt(4 rhoA / (pi 0.6 7850 kg/m^3))); every Anchor as a small sphere.
    /// @param referenceForce P_ref [N], >= 0 and finite; 0 (the default): the largest span axial force
    ///        of the frame being drawn (then the map shows the force distribution, not its level).
    /// @throws std::invalid_argument if referenceForce is negative or not finite.
    void setDecorationForceScale(double referenceForce);
    /// P_ref the decorations use for `state` [N]: the set reference force, or with 0 set the largest
    /// span axial force of the frame (sampled as drawn; 0 if every span is slack) (Stage::Position).
    double getDecorationForceScale(const SimTK::State& state) const;

    /// @cond INTERNAL
    class Guts;
private:
    double strainAt(const SimTK::State& state, int rope, int span, double s) const;

public:
    SimTK_PIMPL_DOWNCAST(ReevingSubsystem, SimTK::ForceSubsystem);
    Guts& updGuts();
    const Guts& getGuts() const;
    /// @endcond
};

/// A node of one rope of a ReevingSubsystem (its rope and node indices): the base of the handles
/// to the nodes whose kind has queries of its own. The queries every node answers take the
/// indices on the ReevingSubsystem (getNodeForce, getMaterialCoordinate, getWrapAngle, ...).
/// A handle refers to the subsystem's implementation, which the System owns: it stays valid as long
/// as the System does (the ReevingSubsystem object it came from may go out of scope).
class RopeNodeHandle {
public:
    /// The rope's index (ReevingSubsystem::addRope's order).
    int getRopeIndex() const { return rope_; }
    /// The node's index on its rope: 0 the start, 1..N-1 the sheaves in path order, N the end.
    int getNodeIndex() const { return node_; }
    /// The subsystem the rope belongs to (the System's handle to it: the same subsystem as the
    /// ReevingSubsystem the rope was added to, not necessarily the same object).
    const ReevingSubsystem& getReevingSubsystem() const;

protected:
    /// @cond INTERNAL
    RopeNodeHandle(const ReevingSubsystem::Guts& guts, int rope, int node) : guts_(&guts), rope_(rope), node_(node) {}
    const ReevingSubsystem::Guts& guts() const { return *guts_; }
    /// @endcond

private:
    const ReevingSubsystem::Guts* guts_;
    int rope_, node_;
};

/// A node on a MobilizedBody::Pin whose material coordinate turns with it: a WinchDrum, a
/// TurningSheave or a TractionSheave.
class PinnedNodeHandle : public RopeNodeHandle {
public:
    /// Torque about the pin axis that the rope applies to the node's body [N m] (Stage::Dynamics):
    /// sense R times the rope's pull on its material at the node (at a drum, about the axial force
    /// of the span there; at a sheave, the difference of both spans' forces), from the coupled solve
    /// (inertia included).
    /// @throws std::logic_error if the state is not realized to Stage::Dynamics.
    double getTorque(const SimTK::State& state) const;
    /// Power the rope delivers to the node's body [W] (Stage::Dynamics): getTorque times the rate
    /// of the node's angle, the pin rate (on a wrapped groove whose pin's parent turns about the
    /// groove's axis, the sheave body's own rate about it: the pin's plus the parent's). Summed
    /// over the nodes and with the bodies' own work it closes the energy balance of a driven
    /// machine.
    /// @throws std::logic_error if the state is not realized to Stage::Dynamics.
    double getPower(const SimTK::State& state) const;

protected:
    /// @cond INTERNAL
    PinnedNodeHandle(const ReevingSubsystem::Guts& guts, int rope, int node) : RopeNodeHandle(guts, rope, node) {}
    /// @endcond
};

/// A WinchDrum at a rope end (RopeHandle::getWinchDrum).
class WinchDrumHandle : public PinnedNodeHandle {
public:
    /// Rope stored on the drum [m] (Stage::Position): ropeOnDrum - sense R theta.
    double getRopeOnDrum(const SimTK::State& state) const;

private:
    friend class RopeHandle;
    WinchDrumHandle(const ReevingSubsystem::Guts& guts, int rope, int node) : PinnedNodeHandle(guts, rope, node) {}
};

/// A TurningSheave in a rope's path (RopeHandle::getTurningSheave).
class TurningSheaveHandle : public PinnedNodeHandle {
private:
    friend class RopeHandle;
    TurningSheaveHandle(const ReevingSubsystem::Guts& guts, int rope, int node) : PinnedNodeHandle(guts, rope, node) {}
};

/// A TractionSheave in a rope's path (RopeHandle::getTractionSheave): its phase, slip and friction.
class TractionSheaveHandle : public PinnedNodeHandle {
public:
    /// Stick or slip (a discrete state variable, changed by the subsystem's traction events).
    TractionMode getTractionMode(const SimTK::State& state) const;
    /// Slip rate v = sdot_k - sense R thetadot [m/s] (Stage::Velocity): the rope's speed over the
    /// groove, positive towards the rope's start; 0 in stick.
    /// @throws std::logic_error if the state is not realized to Stage::Velocity.
    double getSlipRate(const SimTK::State& state) const;
    /// Net slip distance s_k - sense R theta - s_ref [m] (Stage::Position): how far the rope has
    /// slid over the groove since the start (positive towards the rope's start).
    double getSlipDistance(const SimTK::State& state) const;
    /// Force ratio P_a / P_b of the spans before and after the sheave [-] (Stage::Position; NaN if
    /// P_b <= 0).
    double getTractionRatio(const SimTK::State& state) const;
    /// e^(mu alpha) [-]: the ratio at which the rope slips (Stage::Position; alpha as
    /// ReevingSubsystem::getWrapAngle).
    double getTractionLimit(const SimTK::State& state) const;
    /// Friction power dissipated in the groove [W] (Stage::Velocity; 0 in stick): (P_a - P_b) v >= 0
    /// with TractionSlip::CapstanConstraint; with TractionSlip::RopeMomentum sigma F v - c Ydot
    /// (its friction's power plus that of the end-force correction c, see TractionSlip).
    /// @throws std::logic_error if the state is not realized to Stage::Velocity.
    double getFrictionPower(const SimTK::State& state) const;
    /// Work dissipated by friction in the groove since the start [J]: the integral of
    /// getFrictionPower (a Z entry of the subsystem), plus at each stick -> slip transition the
    /// rope's kinetic energy lost there (positive or negative: the point contact changes the
    /// material rate at the node at once, from the groove's speed to the one that keeps the capstan
    /// ratio), so that E(t) - E(0) + W_friction = W_drives closes exactly.
    double getFrictionWork(const SimTK::State& state) const;
    /// Number of stick/slip transitions of this sheave in the state's history.
    int getNumTractionTransitions(const SimTK::State& state) const;

private:
    friend class RopeHandle;
    TractionSheaveHandle(const ReevingSubsystem::Guts& guts, int rope, int node) : PinnedNodeHandle(guts, rope, node) {}
};

/// One rope of a ReevingSubsystem (ReevingSubsystem::addRope, getRope): its index and its nodes'
/// typed handles. It converts to the rope's index, so the queries that take an `int rope` take a
/// RopeHandle too, and `int rope = reeving.addRope(spec);` keeps the index alone. Valid as long as
/// the System (see RopeNodeHandle).
class RopeHandle {
public:
    /// The rope's index (addRope's order).
    int getIndex() const { return index_; }
    /// The rope's index, for the queries that take one.
    operator int() const { return index_; }
    /// The rope's number of nodes: its sheaves and both ends.
    int getNumNodes() const;
    /// Node `node`, a WinchDrum (0 or getNumNodes() - 1).
    /// @throws std::invalid_argument if node is out of range or not a WinchDrum.
    WinchDrumHandle getWinchDrum(int node) const;
    /// Node `node`, a TurningSheave.
    /// @throws std::invalid_argument if node is out of range or not a TurningSheave.
    TurningSheaveHandle getTurningSheave(int node) const;
    /// Node `node`, a TractionSheave.
    /// @throws std::invalid_argument if node is out of range or not a TractionSheave.
    TractionSheaveHandle getTractionSheave(int node) const;

private:
    friend class ReevingSubsystem;
    RopeHandle(const ReevingSubsystem::Guts& guts, int index) : guts_(&guts), index_(index) {}
    const ReevingSubsystem::Guts* guts_;
    int index_;
};

}  // namespace SimbodyReeving
