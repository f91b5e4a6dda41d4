#pragma once
/// @file
/// The Simbody side of SimbodyReeving: ropes of ALE spans over frictionless sheaves, attached to
/// Simbody bodies, inside an ordinary SimTK::MultibodySystem and integrated by any Simbody
/// integrator.

#include "SimbodyReeving/RopeModel.h"
#include "SimbodyReeving/SpanModel.h"

#include <Simbody.h>

#include <string>
#include <utility>
#include <vector>

namespace SimbodyReeving {

/// A station (point fixed on a body) where a rope is attached: a MobilizedBody (Ground allowed)
/// and the point's location in that body's frame [m].
struct RopeAnchor {
    SimTK::MobilizedBody body;
    SimTK::Vec3 station{0};
};

/// A frictionless deviation sheave: its centre on a body (Ground allowed) [m] and its radius [m].
/// Point-sheave idealisation, as in the paper (eq 30: both spans share the node at the sheave): the
/// two spans meet at the sheave centre and share the material coordinate there; the wrap arc and
/// the motion of the tangent points are neglected (an O(radius/span length) geometric
/// approximation). The radius is used for validation and drawing.
struct DeviationSheave {
    SimTK::MobilizedBody body;
    SimTK::Vec3 centre{0};
    double radius = 0;
};

/// Everything that describes one rope. SI units.
struct RopeSpec {
    std::string name = "rope";
    RopeAnchor start;                       ///< material coordinate s = 0
    std::vector<DeviationSheave> sheaves;   ///< in path order
    RopeAnchor end;                         ///< material coordinate s = unstretchedLength
    RopeProperties properties;              ///< rhoA, EA, EI (see RopeProperties)
    double unstretchedLength = 0;           ///< total unstretched length L of the rope [m], > 0
    SpanOptions spanDefaults;               ///< mode counts and options of every span...
    std::vector<std::pair<int, SpanOptions>> spanOverrides;  ///< ...except these (span index, options)
    /// Non-zero: the rope is planar, all its nodes stay in the plane through the start anchor with
    /// this normal (gravity must lie in it); spans are then planar (no out-of-plane modes or work).
    /// Zero: spatial spans.
    SimTK::Vec3 planeNormal{0};
};

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
/// S, h the rope reduced to its nodes, a0 the free node accelerations, Lambda the bodies' node
/// mobility. -f is applied to the bodies and the rope's modal accelerations follow. The solve honours
/// Simbody's constraints and prescribed motion because calcAcceleration does.
///
/// Must be constructed after every other force subsystem of the system (GeneralForceSubsystem
/// included): realizeTopology throws std::logic_error otherwise.
///
/// Energy: the rope's strain and gravity energy are this subsystem's potential energy (so
/// MultibodySystem::calcPotentialEnergy includes them); its kinetic energy is calcRopeKineticEnergy;
/// calcMechanicalEnergy returns the whole system's T + U.
class ReevingSubsystem : public SimTK::ForceSubsystem {
public:
    /// @param gravity the gravitational acceleration acting on the ropes [m/s^2] (give the same
    ///        vector as the system's Force::Gravity).
    /// @throws std::invalid_argument for non-finite gravity.
    ReevingSubsystem(SimTK::MultibodySystem& system, const SimTK::Vec3& gravity);

    /// Adds a rope; returns its index. Must be called before realizeTopology.
    /// @throws std::invalid_argument naming the problem: empty anchor body, non-finite station,
    ///         non-positive or non-finite sheave radius or rope length, bad rope properties or mode
    ///         counts, a span override index out of range, non-finite plane normal, gravity out of
    ///         the rope plane.
    int addRope(const RopeSpec& spec);

    int getNumRopes() const;
    const RopeSpec& getRopeSpec(int rope) const;
    int getNumSpans(int rope) const;
    bool isPlanar(int rope) const;
    /// Number of modal coordinates of a rope (its Z holds these and as many rates).
    int getNumModalCoordinates(int rope) const;

    /// Modal coordinates of a rope [m] and their rates [m/s] (Stage::Model or later).
    SimTK::Vector getModalCoordinates(const SimTK::State& state, int rope) const;
    void setModalCoordinates(SimTK::State& state, int rope, const SimTK::Vector& q) const;
    SimTK::Vector getModalRates(const SimTK::State& state, int rope) const;
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
    /// Material coordinate s at node k (0 = start anchor, N = end anchor) [m].
    double getMaterialCoordinate(const SimTK::State& state, int rope, int node) const;
    /// Material coordinate range [s1, s2] of a span [m].
    std::pair<double, double> getSpanMaterialRange(const SimTK::State& state, int rope, int span) const;
    /// F_a - F_b at sheave k (1..N-1): the tension-equality residual [N].
    double getConstraintError(const SimTK::State& state, int rope, int sheave) const;
    /// Largest |F_a - F_b| over all sheaves of all ropes [N].
    double getMaxConstraintError(const SimTK::State& state) const;
    /// Positions in Ground of numPoints >= 2 equally spaced material points of a span [m].
    std::vector<SimTK::Vec3> sampleSpan(const SimTK::State& state, int rope, int span, int numPoints) const;
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
    /// residual is <= relativeTolerance times the largest applied generalized force.
    /// Returns the achieved relative residual.
    /// @throws std::runtime_error if it does not converge in maxIterations.
    double findStaticEquilibrium(SimTK::State& state, double relativeTolerance = 1e-10, int maxIterations = 50) const;

    /// Number of rope node pairs drawn per span by the decorations (default 20).
    void setDecorationResolution(int pointsPerSpan);

    class Guts;
private:
    double strainAt(const SimTK::State& state, int rope, int span, double s) const;

public:
    SimTK_PIMPL_DOWNCAST(ReevingSubsystem, SimTK::ForceSubsystem);
    Guts& updGuts();
    const Guts& getGuts() const;
};

}  // namespace SimbodyReeving
