#pragma once
/// @file
/// Internal to the plugin: what a Driven node's kind adds at run time to its driven relation
/// s = s_ref + g(theta) (DrivenLaw.h, DrivenAngle.h), one unit per kind:
///   - GripRole (TurningSheave): nothing: the rope moves with the groove at all times;
///   - StoredRopeRole (WinchDrum): the rope stored on the drum, l = ropeOnDrum + s_0 at a start
///     drum, ropeOnDrum + L - s_N at an end drum [m]: declared to the rope model
///     (RopeModel::setStoredRope), a rope limit (the drum out of rope) and the drum's query;
///   - TractionRole (TractionSheave): friction: stick is the driven relation with its offset s_ref
///     the state's TractionNodeState::sStick; slip the capstan law (TractionSlip::CapstanConstraint:
///     the node MaterialNode::Slipping in the phase's rope model) or the rope's momentum on the
///     groove (TractionSlip::RopeMomentum: the state Y, Ydot); its Z entries (friction work, Y,
///     Ydot: their layout and reading), its events (stick <-> slip), its condensation in the
///     coupled solve and its queries (nodes/TractionSheaveRun.cpp).
/// Each unit has every hook of the interface below (DrivenRoleDefaults: the hooks a unit does not
/// own do nothing); DrivenRole holds one of them (std::variant, dispatched by std::visit: no
/// virtual call, no heap) and the generic code calls the hooks through it, never asking which kind
/// a node is. A new kind is one new unit plus its entry in DrivenRole::Unit.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

namespace SimbodyReeving {
namespace detail {

struct DrivenNode;         // ReevingSubsystemGuts.h
struct RopeRecord;         // ReevingSubsystemGuts.h
struct RopeCache;          // ReevingSubsystemGuts.h
struct CouplingWorkspace;  // ReevingSubsystemGuts.h

/// State (part of the subsystem's discrete variable TractionStates) of a TractionSheave: its
/// phase, the material coordinate offset of its current stick phase [m] (s_k = sStick + g(theta))
/// and the count of its transitions.
struct TractionNodeState {
    TractionMode mode = TractionMode::Stick;
    double sStick = 0;
    int transitions = 0;
};

/// A Driven node at run time: the subsystem, the node's rope, its record and its index among the
/// rope's driven nodes (RopeRecord::driven).
struct DrivenRun {
    const ReevingSubsystem::Guts& guts;
    const RopeRecord& rope;
    const DrivenNode& node;
    int driven;
};

/// The blocks of a rope's Z entries its driven nodes take (DrivenRole::layoutZ), laid out one
/// after the other, each over the rope's driven nodes in node order: Work, integrals of a power
/// [J] that no law reads (a traction sheave's friction work); States, states the rope's
/// evaluation reads, each followed by its rate (a TractionSlip::RopeMomentum sheave's Y [m] and
/// Ydot [m/s]).
enum class DrivenZBlock { Work, States };

/// The hooks of the interface, each doing nothing (or, for materialCoordinate, the plain driven
/// relation): a unit replaces those it owns.
struct DrivenRoleDefaults {
    /// Declares the node's stored rope to a RopeModel<2> or <3> (none).
    template <class Model>
    void declareStoredRope(Model&, int /*node*/, double /*ropeLength*/) const {}
    /// Takes the node's Z entries of `block` from entry z on, advancing z past them (none).
    void layoutZ(DrivenZBlock /*block*/, int& /*z*/) {}
    /// Copies the node's Z state (DrivenZBlock::States; its rate if `rates`) from z into `entry`,
    /// its element of the rope cache's RopeCache::drivenZStates (drivenZRates) (none: unchanged).
    void readZState(const SimTK::Vector& /*z*/, bool /*rates*/, double& /*entry*/) const {}
    /// True if `entry` holds the node's Z state (its rate if `rates`) of z (none: true).
    bool zStateMatches(const SimTK::Vector& /*z*/, bool /*rates*/, double /*entry*/) const { return true; }
    /// The rope stored at the node [m] (Stage::Position, from its rope's cache c): none, 0.
    double storedRope(const DrivenRun&, const RopeCache& /*c*/) const { return 0.0; }
    /// Sets the node's part of its rope's initial TractionStates from the spec's s_ref [m] (none).
    void initialPhase(std::vector<TractionNodeState>&, double /*sRef*/) const {}
    /// The node's material coordinate s [m] at angle theta [rad] in state s, with its rate sdot
    /// [m/s] for thetadot [rad/s] if `rates`: s = s_ref + g(theta), sdot = g'(theta) thetadot.
    void materialCoordinate(const DrivenRun& run, const SimTK::State& state, double theta, double thetaDot, bool rates,
                            double& s, double& sdot) const;
    /// True if the node makes the rope's traction phase model differ from its stick model in the
    /// phases `ropePhases` (its rope's TractionStates entry) (never).
    bool slipsInPhase(const std::vector<TractionNodeState>& /*ropePhases*/) const { return false; }
    /// True if a phase model's key agrees with `ropePhases` at the node's entry (no entry: true).
    bool phaseKeyMatches(const std::vector<double>& /*key*/, const std::vector<TractionNodeState>&) const {
        return true;
    }
    /// Writes the node's entry of a phase model's key (none).
    void writePhaseKey(const std::vector<TractionNodeState>&, std::vector<double>& /*key*/) const {}
    /// The node's MaterialNode in the phase model of `key` (unchanged).
    void phaseMaterialKind(const std::vector<double>& /*key*/, MaterialNode&) const {}
    /// Sets the node's slip law in the phase model of `key` (none).
    void setPhaseLaw(const std::vector<double>& /*key*/, RopeModel<2>&, int /*node*/) const {}
    void setPhaseLaw(const std::vector<double>& /*key*/, RopeModel<3>&, int /*node*/) const {}
    /// Before the coupled solve: registers the node's coordinates that move by their own balance
    /// (CouplingWorkspace::freeSlips) and applies their reactions to the bodies (none).
    void condense(const DrivenRun&, const SimTK::State&, CouplingWorkspace&, SimTK::Vector& /*mobilityForces*/,
                  SimTK::Vector_<SimTK::SpatialVec>& /*bodyForces*/) const {}
    /// After it: the rates of the node's Z entries into zdot (none), from the rope's cache c.
    void zDerivatives(const DrivenRun&, const SimTK::State&, const RopeCache& /*c*/, const CouplingWorkspace&,
                      const SimTK::Vector& /*z*/, SimTK::Vector& /*zdot*/) const {}
    /// Lowers `margin` [m] to the node's own rope limit if that is smaller, describing it in
    /// `which` when given (none).
    void limitMargin(const DrivenRun&, const RopeCache&, double& /*margin*/, std::string* /*which*/) const {}
    /// Adds the node's event handlers to `system` (none).
    void installEvents(SimTK::System&, SimTK::SubsystemIndex, int /*rope*/, int /*driven*/) const {}
    /// The wrap angle [rad] the node's own law uses, if it has one (Stage::Position): false.
    bool wrapAngle(const DrivenRun&, const SimTK::State&, double& /*alpha*/) const { return false; }
    /// ReevingSubsystem::updateTractionModes: starts the node's slip if its rope is over its limit
    /// in state s (Stage::Position); true if its phase changed (never).
    bool startSlipOverLimit(const DrivenRun&, SimTK::State&) const { return false; }
    /// Adds the node's friction work [J] (a Z entry) to w (none).
    void addFrictionWork(const SimTK::Vector& /*z*/, double& /*w*/) const {}
    /// Adds the potential energy [J] the node holds in a Z entry to u (none).
    void addHeldEnergy(const SimTK::Vector& /*z*/, double& /*u*/) const {}
};

/// TurningSheave: the driven relation alone.
struct GripRole : DrivenRoleDefaults {};

/// WinchDrum: the rope stored on the drum, ropeOnDrum [m] with s at its exit at the drum's
/// reference (s_0 = 0 at a start drum, s_N = L at an end drum).
///
/// A wrapped drum grips the rope where it leaves the groove (RopeModel::setGrip): the material
/// coordinate there is s = s_ref + g(theta) + sigma R phi + c, with c the rope's creep against the
/// unstretched groove, a Z entry of its own (DrivenZBlock::States, no rate entry: its rate comes
/// from the rope's evaluation, RopeData::gripCreepRates); and the energy the wound rope
/// holds (its strain energy U_w and the creep's weight U_c), a Z entry (DrivenZBlock::Work, rate RopeData::gripHeldEnergyRates) that is part of the
/// subsystem's potential energy (addHeldEnergy). Both 0 in a default state.
struct StoredRopeRole : DrivenRoleDefaults {
    double ropeOnDrum = 0;  // [m]
    bool grips = false;     // a wrapped drum (RopeModel::setGrip)
    int creepZ = -1;        // Z entry of its creep c [m] (grips only)
    int heldEnergyZ = -1;   // Z entry of the wound rope's held energy U_w + U_c [J] (grips only)

    /// The stored rope at zero exit coordinate (RopeModel::setStoredRope: l = that + s_0 at the
    /// start, that - s_N at the end): ropeOnDrum at a start drum, ropeOnDrum + L at an end drum;
    /// and the grip of a wrapped drum.
    template <class Model>
    void declareStoredRope(Model& model, int node, double ropeLength) const {
        model.setStoredRope(node, node == 0 ? ropeOnDrum : ropeOnDrum + ropeLength);
        if (grips) model.setGrip(node);
    }
    /// Work: the wound rope's held energy U_w + U_c; States: the creep c (a wrapped drum).
    void layoutZ(DrivenZBlock block, int& z) {
        if (grips && block == DrivenZBlock::Work) heldEnergyZ = z++;
        if (grips && block == DrivenZBlock::States) creepZ = z++;
    }
    /// U_w + U_c [J].
    void addHeldEnergy(const SimTK::Vector& z, double& u) const {
        if (heldEnergyZ >= 0) u += z[heldEnergyZ];
    }
    /// c (positions; its rate is not a Z entry: unchanged).
    void readZState(const SimTK::Vector& z, bool rates, double& entry) const {
        if (creepZ >= 0 && !rates) entry = z[creepZ];
    }
    bool zStateMatches(const SimTK::Vector& z, bool rates, double entry) const {
        return creepZ < 0 || rates || entry == z[creepZ];
    }
    /// s = s_ref + g(theta) + c, sdot = g'(theta) thetadot (the creep's rate is the rope's, inside
    /// its evaluation).
    void materialCoordinate(const DrivenRun& run, const SimTK::State& state, double theta, double thetaDot, bool rates,
                            double& s, double& sdot) const;
    /// cdot and d(U_w + U_c)/dt from the rope's evaluation in c (RopeData::gripCreepRates,
    /// gripHeldEnergyRates).
    void zDerivatives(const DrivenRun& run, const SimTK::State& state, const RopeCache& c, const CouplingWorkspace& ws,
                      const SimTK::Vector& z, SimTK::Vector& zdot) const;
    /// The rope on the drum [m] with the rope's material coordinate s [m] where it leaves it:
    /// ropeOnDrum + s at a start drum (node 0), ropeOnDrum + L - s at an end drum.
    double onDrum(int node, double s, double ropeLength) const {
        return node == 0 ? ropeOnDrum + s : ropeOnDrum + ropeLength - s;
    }
    /// The drum out of rope: margin onDrum [m] (from the rope's evaluation in c).
    void limitMargin(const DrivenRun& run, const RopeCache& c, double& margin, std::string* which) const;
    /// onDrum at the rope's material coordinate s_k where it leaves the drum (from c).
    double storedRope(const DrivenRun& run, const RopeCache& c) const;
};

/// TractionSheave: index among its rope's traction sheaves (its TractionStates entry and its
/// phase models' key entry), its Z entries (layoutZ), friction coefficient mu [-], wrap angle
/// alpha [rad] (given, or the geometry's, RopeModel::wrapAngle, when geometricWrap) and slip model.
struct TractionRole : DrivenRoleDefaults {
    int index = -1;
    int workZ = -1;   // Z entry of its friction work [J] (DrivenZBlock::Work)
    int stateZ = -1;  // Z entry of its slip state Y [m], Ydot [m/s] at stateZ + 1 (DrivenZBlock::States)
    double frictionCoefficient = 0;  // [-]
    double givenWrapAngle = 0;       // [rad]; unused when geometricWrap
    bool geometricWrap = false;
    TractionSlip slipModel = TractionSlip::CapstanConstraint;

    /// Relative force margin past the capstan limit at which a sticking sheave starts to slip, and
    /// the slip rate past zero at which a slipping one sticks: a zero witness right after a
    /// transition would otherwise leave the event's direction to round-off.
    static constexpr double kTractionHysteresis = 1e-9;
    static constexpr double kSlipRateHysteresis = 1e-9;  // [m/s]

    bool momentum() const { return slipModel == TractionSlip::RopeMomentum; }
    /// Its Z entries: the friction work [J], and the slip state Y [m] with its rate Ydot [m/s]
    /// right after it (TractionSlip::RopeMomentum; zero rates otherwise).
    int frictionWorkZ() const { return workZ; }
    int slipStateZ() const { return stateZ; }
    /// Its entry of its rope's phase key (RopeRecord::TractionPhaseModel) in phase t: 0 in stick
    /// and with TractionSlip::RopeMomentum (Driven by Y), +-1 (the slip's direction) with the
    /// geometry's wrap angle, else kappa = P_{k-1} / P_k = e^(+-mu alpha): the tight side is the
    /// one the rope slides towards.
    double phaseKeyEntry(const TractionNodeState& t) const;

    // ---- the interface ----
    /// Work: the friction work, one entry; States: Y and Ydot, two.
    void layoutZ(DrivenZBlock block, int& z) {
        if (block == DrivenZBlock::Work) {
            workZ = z++;
        } else {
            stateZ = z;
            z += 2;
        }
    }
    /// Y (Ydot if `rates`).
    void readZState(const SimTK::Vector& z, bool rates, double& entry) const { entry = z[stateZ + (rates ? 1 : 0)]; }
    bool zStateMatches(const SimTK::Vector& z, bool rates, double entry) const {
        return entry == z[stateZ + (rates ? 1 : 0)];
    }
    /// Its entry of the rope's phases (grown to hold it), sStick = s_ref.
    void initialPhase(std::vector<TractionNodeState>& ropePhases, double sRef) const {
        if (ropePhases.size() <= static_cast<std::size_t>(index)) ropePhases.resize(static_cast<std::size_t>(index) + 1);
        ropePhases[index].sStick = sRef;
    }
    /// Stick: s = sStick + g(theta); TractionSlip::RopeMomentum slip: s = Y, sdot = Ydot (Z); in
    /// CapstanConstraint slip the groove's coordinate sStick + g(theta) (no span reads it).
    void materialCoordinate(const DrivenRun& run, const SimTK::State& state, double theta, double thetaDot, bool rates,
                            double& s, double& sdot) const;
    bool slipsInPhase(const std::vector<TractionNodeState>& ropePhases) const {
        return phaseKeyEntry(ropePhases[index]) != 0;
    }
    bool phaseKeyMatches(const std::vector<double>& key, const std::vector<TractionNodeState>& ropePhases) const {
        return key[index] == phaseKeyEntry(ropePhases[index]);
    }
    void writePhaseKey(const std::vector<TractionNodeState>& ropePhases, std::vector<double>& key) const {
        key[index] = phaseKeyEntry(ropePhases[index]);
    }
    /// MaterialNode::Slipping where its key entry is not 0.
    void phaseMaterialKind(const std::vector<double>& key, MaterialNode& kind) const {
        if (key[index] != 0) kind = MaterialNode::Slipping;
    }
    /// Its key entry's law: the slip ratio kappa (given wrap angle) or kappa = e^(+-mu alpha) of
    /// the geometry's alpha (RopeModel::setSlipLaw).
    void setPhaseLaw(const std::vector<double>& key, RopeModel<2>& model, int node) const;
    void setPhaseLaw(const std::vector<double>& key, RopeModel<3>& model, int node) const;
    /// In TractionSlip::RopeMomentum slip: Y is free (its momentum balance), the friction's
    /// reaction sigma F g'(theta) [N m] acts on the angle's row.
    void condense(const DrivenRun& run, const SimTK::State& state, CouplingWorkspace& ws, SimTK::Vector& mobilityForces,
                  SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const;
    /// The friction work's rate [W] ((P_a - P_b) v_slip, 0 in stick; RopeMomentum slip: the
    /// FreeSlip's workRate) and Y's rates (Ydot, Yddot in RopeMomentum slip; 0 otherwise).
    void zDerivatives(const DrivenRun& run, const SimTK::State& state, const RopeCache& c, const CouplingWorkspace& ws,
                      const SimTK::Vector& z, SimTK::Vector& zdot) const;
    /// A TractionSheave's stick/slip event (TractionEvent; at Stage::Dynamics with RopeMomentum,
    /// whose stick witness reads the coupled solve's accelerations).
    void installEvents(SimTK::System& system, SimTK::SubsystemIndex reeving, int rope, int driven) const;
    /// The capstan law's alpha (wrapAngle(run, state) below; realizes nothing, needs Stage::Position).
    bool wrapAngle(const DrivenRun& run, const SimTK::State& state, double& alpha) const;
    bool startSlipOverLimit(const DrivenRun& run, SimTK::State& state) const;
    void addFrictionWork(const SimTK::Vector& z, double& w) const;

    // ---- its run time (nodes/TractionSheaveRun.cpp) ----
    /// True if in TractionSlip::RopeMomentum slip in state s.
    bool inMomentumSlip(const DrivenRun& run, const SimTK::State& state) const;
    /// The wrap angle alpha [rad] its capstan law uses (Stage::Position): the current geometry's
    /// (RopeModel::wrapAngle: l / R wrapped, the chords' turning angle at a point sheave) for a
    /// geometricWrap sheave, else the given one.
    double wrapAngle(const DrivenRun& run, const SimTK::State& state) const;
    /// e^(mu alpha) [-] (Stage::Position).
    double limit(const DrivenRun& run, const SimTK::State& state) const;
    /// Slip rate sdot_k - g'(theta) thetadot [m/s] (Stage::Velocity; 0 in stick).
    double slipRate(const DrivenRun& run, const SimTK::State& state) const;
    /// The slip of a TractionSlip::RopeMomentum sheave in slip (Stage::Velocity): the rope's speed
    /// over the groove v = Ydot [m/s], the friction on the groove sigma F [N] (along s; the rope
    /// receives -sigma F), the momentum balance's right side P_a - P_b - sigma F [N], the
    /// correction P_a - P_b - h_Y [N] (h_Y the rope's own generalized force on Y), the slip rate
    /// v - g'(theta) thetadot [m/s] and the rate of the friction work sigma F v_slip - c v [W].
    struct MomentumSlip {
        double speed = 0, friction = 0, drive = 0, correction = 0, slipRate = 0, workRate = 0;
        int external = -1;  // Y's index among the rope's external coordinates (stations)
    };
    MomentumSlip momentumSlip(const DrivenRun& run, const SimTK::State& state) const;
    /// F_max = max(tight - rhoA v^2, 0)(1 - e^(-mu alpha)) [N] of a RopeMomentum sheave in stick
    /// (v the groove's speed) with tight the force on the side it would slide to [N].
    double maxFriction(const DrivenRun& run, double tight, const SimTK::State& state) const;
    /// The friction that holds a RopeMomentum sheave's rope in stick (Stage::Dynamics),
    /// Phi = P_a - P_b - (S xddot)_Y [N] (positive: it would slide towards the rope's start).
    double stickFriction(const DrivenRun& run, const SimTK::State& state) const;
    /// Sets its slip states Y, Ydot from its stick phase (stick's sStick) in s.
    void startMomentumSlip(const DrivenRun& run, SimTK::State& state, const TractionNodeState& stick) const;
    /// Witness of its next transition (Stage::Velocity; RopeMomentum stick: Stage::Dynamics),
    /// positive until it is due: stick: the smaller of P_b - P_a e^(-mu alpha) and
    /// P_a - P_b e^(-mu alpha) (the capstan margins divided by e^(mu alpha), so a large limit does
    /// not amplify round-off), plus a hysteresis of kTractionHysteresis (|P_a| + |P_b|) [N]; slip:
    /// the slip rate in the slip's direction plus kSlipRateHysteresis [m/s].
    double witness(const DrivenRun& run, const SimTK::State& state) const;
    /// Its transition (its witness fell through zero): stick -> slip towards the tight side,
    /// slip -> stick with sStick = s_k - g(theta) (s_k continuous).
    void changeMode(const DrivenRun& run, SimTK::State& state) const;
};

/// A Driven node's run-time role: one of the units above (GripRole unless its kind sets another).
struct DrivenRole {
    using Unit = std::variant<GripRole, StoredRopeRole, TractionRole>;
    Unit unit;

    template <class Model>
    void declareStoredRope(Model& model, int node, double ropeLength) const {
        std::visit([&](const auto& u) { u.declareStoredRope(model, node, ropeLength); }, unit);
    }
    void layoutZ(DrivenZBlock block, int& z) {
        std::visit([&](auto& u) { u.layoutZ(block, z); }, unit);
    }
    void readZState(const SimTK::Vector& z, bool rates, double& entry) const {
        std::visit([&](const auto& u) { u.readZState(z, rates, entry); }, unit);
    }
    bool zStateMatches(const SimTK::Vector& z, bool rates, double entry) const {
        return std::visit([&](const auto& u) { return u.zStateMatches(z, rates, entry); }, unit);
    }
    double storedRope(const DrivenRun& run, const RopeCache& c) const {
        return std::visit([&](const auto& u) { return u.storedRope(run, c); }, unit);
    }
    void initialPhase(std::vector<TractionNodeState>& ropePhases, double sRef) const {
        std::visit([&](const auto& u) { u.initialPhase(ropePhases, sRef); }, unit);
    }
    void materialCoordinate(const DrivenRun& run, const SimTK::State& state, double theta, double thetaDot, bool rates,
                            double& s, double& sdot) const {
        std::visit([&](const auto& u) { u.materialCoordinate(run, state, theta, thetaDot, rates, s, sdot); }, unit);
    }
    bool slipsInPhase(const std::vector<TractionNodeState>& ropePhases) const {
        return std::visit([&](const auto& u) { return u.slipsInPhase(ropePhases); }, unit);
    }
    bool phaseKeyMatches(const std::vector<double>& key, const std::vector<TractionNodeState>& ropePhases) const {
        return std::visit([&](const auto& u) { return u.phaseKeyMatches(key, ropePhases); }, unit);
    }
    void writePhaseKey(const std::vector<TractionNodeState>& ropePhases, std::vector<double>& key) const {
        std::visit([&](const auto& u) { u.writePhaseKey(ropePhases, key); }, unit);
    }
    void phaseMaterialKind(const std::vector<double>& key, MaterialNode& kind) const {
        std::visit([&](const auto& u) { u.phaseMaterialKind(key, kind); }, unit);
    }
    template <class Model>
    void setPhaseLaw(const std::vector<double>& key, Model& model, int node) const {
        std::visit([&](const auto& u) { u.setPhaseLaw(key, model, node); }, unit);
    }
    void condense(const DrivenRun& run, const SimTK::State& state, CouplingWorkspace& ws, SimTK::Vector& mobilityForces,
                  SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const {
        std::visit([&](const auto& u) { u.condense(run, state, ws, mobilityForces, bodyForces); }, unit);
    }
    void zDerivatives(const DrivenRun& run, const SimTK::State& state, const RopeCache& c, const CouplingWorkspace& ws,
                      const SimTK::Vector& z, SimTK::Vector& zdot) const {
        std::visit([&](const auto& u) { u.zDerivatives(run, state, c, ws, z, zdot); }, unit);
    }
    void limitMargin(const DrivenRun& run, const RopeCache& c, double& margin, std::string* which) const {
        std::visit([&](const auto& u) { u.limitMargin(run, c, margin, which); }, unit);
    }
    void installEvents(SimTK::System& system, SimTK::SubsystemIndex reeving, int rope, int driven) const {
        std::visit([&](const auto& u) { u.installEvents(system, reeving, rope, driven); }, unit);
    }
    bool wrapAngle(const DrivenRun& run, const SimTK::State& state, double& alpha) const {
        return std::visit([&](const auto& u) { return u.wrapAngle(run, state, alpha); }, unit);
    }
    bool startSlipOverLimit(const DrivenRun& run, SimTK::State& state) const {
        return std::visit([&](const auto& u) { return u.startSlipOverLimit(run, state); }, unit);
    }
    void addFrictionWork(const SimTK::Vector& z, double& w) const {
        std::visit([&](const auto& u) { u.addFrictionWork(z, w); }, unit);
    }
    void addHeldEnergy(const SimTK::Vector& z, double& energy) const {
        std::visit([&](const auto& u) { u.addHeldEnergy(z, energy); }, unit);
    }
};

}  // namespace detail
}  // namespace SimbodyReeving
