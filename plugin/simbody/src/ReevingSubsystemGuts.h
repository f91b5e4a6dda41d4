#pragma once
/// @file
/// Internal to the plugin (not installed): the implementation of ReevingSubsystem, shared by
/// ReevingSubsystem.cpp (construction, validation, state accessors), ReevingRealization.cpp
/// (realization, rope caches, energy, decorations), ReevingCoupling.cpp (the coupled rope/body
/// solve), ReevingPhases.cpp (the traction phases' models), ReevingQueries.cpp (public queries),
/// ReevingStaticEquilibrium.cpp, and the node kinds' units in nodes/.

#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "nodes/DrivenAngle.h"
#include "nodes/DrivenLaw.h"
#include "nodes/DrivenRole.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace SimbodyReeving {
namespace detail {

/// Helper: SimTK::Vec3 to Eigen.
inline Eigen::Vector3d toEigen(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }
/// Helper: Eigen to SimTK::Vec3.
inline SimTK::Vec3 toSimTK(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

/// Helper: true if every component is finite.
inline bool finite(const SimTK::Vec3& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/// Helper: throws std::invalid_argument("ReevingSubsystem: " + what).
[[noreturn]] inline void invalid(const std::string& what) {
    throw std::invalid_argument("ReevingSubsystem: " + what);
}

/// Helper: "(x, y, z)" for messages.
inline std::string str(const SimTK::Vec3& v) {
    std::ostringstream o;
    o << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return o.str();
}

/// The kind of a rope node (the alternative of its RopeNode): the closed set the internals dispatch
/// on (nodes/NodeKinds.h).
enum class NodeKind { Anchor, DeviationSheave, WinchDrum, TurningSheave, TractionSheave };

/// A rope node's spec as one flat record, converted once from its kind's struct at addRope: the
/// fields its kind does not have keep their defaults.
struct NodeSpec {
    NodeKind kind = NodeKind::Anchor;
    SimTK::MobilizedBody body;  // Ground allowed for Anchor and DeviationSheave; a Pin for the others
    SimTK::Vec3 point{0};       // station (Anchor) or centre, in the body frame [m]
    double radius = 0;          // sheaves and drums [m]
    int sense = 1;              // WinchDrum: payoutSense; TurningSheave, TractionSheave: sense;
                                // DeviationSheave: wrapSense
    double ropeOnDrum = 0;      // WinchDrum [m]
    double materialCoordinateAtZeroAngle = 0;  // TurningSheave, TractionSheave [m]
    double frictionCoefficient = 0;            // TractionSheave [-]
    double wrapAngle = 0;                      // TractionSheave [rad]; 0: from the geometry
    TractionSlip slipModel = TractionSlip::CapstanConstraint;  // TractionSheave
    SimTK::Vec3 axis{0};        // DeviationSheave of a spatial wrapped rope: the groove's axis
};

/// The flat record of a node (see NodeSpec).
NodeSpec toNodeSpec(const RopeNode& node);

/// A node whose material coordinate turns with a pin (WinchDrum, TurningSheave, TractionSheave):
/// s_k = sRef + g(theta) (RopeModel's Driven nodes), g the node's DrivenLaw and theta its
/// DrivenAngle (nodes/DrivenLaw.h, nodes/DrivenAngle.h); what its kind adds at run time (stored
/// rope, friction) is its DrivenRole (nodes/DrivenRole.h).
struct DrivenNode {
    int node = 0;
    double sRef = 0;  // [m]
    DrivenLaw law;
    DrivenAngle angle;
    DrivenRole role;
};

/// Model (fixed for a simulation; the planar model is built at realizeTopology, the spatial one is
/// state, see SpatialFrames):
/// One rope: its spec, its model (planar or spatial) and where its state lives.
struct RopeRecord {
    RopeSpec spec;
    std::vector<NodeSpec> nodeSpecs;  // per node: its spec as a flat record (toNodeSpec)
    bool planar = false;
    Eigen::Vector3d e1, e2, normal;  // plane basis (planar ropes)
    Eigen::Matrix<double, 3, 2> planeBasis = Eigen::Matrix<double, 3, 2>::Zero();  // [e1 e2]
    std::vector<SpanOptions> spanOptions;
    std::shared_ptr<const RopeModel<2>> planarModel;  // built at realizeTopology
    // Spatial ropes: the model (its spans' reference frames A0) is part of the State, see
    // SpatialFrames.
    int index = 0;  // in ReevingSubsystem::Guts::ropes
    int numModal = 0;
    int zOffset = 0;  // first Z entry (modal coordinates), rates follow

    /// The nodes whose material coordinate turns with a pin, in node order (DrivenNode).
    using DrivenNode = detail::DrivenNode;
    /// Nodes whose law changes with the rope's phase (a TractionSheave: TractionRole::index
    /// 0..numPhaseNodes-1), each an entry of the rope's TractionStates and of its phase models'
    /// keys; 0: the rope has one phase, its stick model. (The driven nodes' Z entries follow
    /// its modal coordinates' block: DrivenRole::layoutZ.)
    int numPhaseNodes = 0;
    int dampingZOffset = -1;  // Z entry of the rope's damping work (ropes with axialRetardationTime > 0)
    /// A rope model of one traction phase: the stick model `base` (a planar rope's planarModel,
    /// a spatial rope's model of the state's span frames, SpatialFrames) with the node of each
    /// slipping TractionSheave Slipping. key = per traction sheave 0 (stick, or a
    /// TractionSlip::RopeMomentum sheave, Driven by its slip state in slip too), its slip ratio
    /// kappa (a given wrap angle) or +-1 (the slip's direction, with the geometry's wrap angle).
    template <int Dim>
    struct TractionPhaseModel {
        std::shared_ptr<const RopeModel<Dim>> base;  // held: its address identifies it
        std::vector<double> key;
        std::shared_ptr<const RopeModel<Dim>> model;
    };
    /// The traction phases' models of ropes with TractionSheaves, built on first use (the set of
    /// phases a run visits is small; a spatial rope's also per set of span frames, those of frames
    /// no state holds any more dropped when a new one is built).
    mutable std::vector<TractionPhaseModel<2>> tractionModels;
    mutable std::vector<TractionPhaseModel<3>> spatialTractionModels;
    std::vector<DrivenNode> driven;
    std::vector<MaterialNode> materialKinds;  // per node, for the RopeModel
    std::vector<NodeWrap> wraps;              // per node: a wrapped deviation sheave's groove (RopeModel)
    /// Per node whose groove axis turns with its body (NodeWrap::turningAxis), in node order: the
    /// node and its axis station, the point of its body at unit distance from the groove's
    /// centre along the axis (RopeModel::axisStation: station numNodes() + i).
    std::vector<std::pair<int, SimTK::Vec3>> axisStations;
    std::vector<int> nodeSlot;  // per station (nodes, then axis stations): its body's slot in Guts::bodySlots

    int numSpans() const { return static_cast<int>(spec.sheaves.size()) + 1; }
    int numNodes() const { return numSpans() + 1; }
    const NodeSpec& nodeSpec(int k) const { return nodeSpecs[static_cast<std::size_t>(k)]; }
    // Node k: (body, station)
    std::pair<const SimTK::MobilizedBody*, SimTK::Vec3> node(int k) const {
        const NodeSpec& n = nodeSpec(k);
        return {&n.body, n.point};
    }
    /// Number of stations the rope's model takes: its nodes, then its axis stations.
    int numStations() const { return numNodes() + static_cast<int>(axisStations.size()); }
    /// Station i: node i (i < numNodes()), or an axis station on its node's body.
    std::pair<const SimTK::MobilizedBody*, SimTK::Vec3> station(int i) const {
        if (i < numNodes()) return node(i);
        const auto& [k, point] = axisStations[static_cast<std::size_t>(i - numNodes())];
        return {&nodeSpec(k).body, point};
    }
    /// The groove axis of wrapped node k in Ground [-]: its own, or (turning with its body) from
    /// the centre to its axis station in `stations` (the cache's nodes3).
    Eigen::Vector3d grooveAxis(int k, const Eigen::Matrix3Xd& stations) const {
        for (std::size_t i = 0; i < axisStations.size(); ++i)
            if (axisStations[i].first == k)
                return stations.col(numNodes() + static_cast<int>(i)) - stations.col(k);
        return wraps[static_cast<std::size_t>(k)].axis;
    }
    /// The rope's external coordinate (station coordinate) of its d-th driven material coordinate.
    int drivenExternal(int d) const { return dim() * numStations() + d; }
    /// Index of node k among the driven nodes, or -1.
    int drivenIndex(int k) const {
        for (size_t d = 0; d < driven.size(); ++d)
            if (driven[d].node == k) return static_cast<int>(d);
        return -1;
    }
    /// Driven node d of this rope at run time in subsystem g (DrivenRole's hooks).
    DrivenRun drivenRun(const ReevingSubsystem::Guts& g, int d) const {
        return {g, *this, driven[static_cast<std::size_t>(d)], d};
    }
    int dim() const { return planar ? 2 : 3; }
    /// Declares the rope stored on its driven nodes to the model (DrivenRole::declareStoredRope:
    /// a WinchDrum's, RopeModel::setStoredRope).
    template <int Dim>
    void addStoredRope(RopeModel<Dim>& model) const {
        for (const DrivenNode& d : driven) d.role.declareStoredRope(model, d.node, spec.unstretchedLength);
    }
    /// The nodes on Ground (RopeModel::setStationaryNodes: their columns of the node mass are skipped).
    std::vector<bool> stationaryNodes() const {
        std::vector<bool> out(numNodes());
        for (int k = 0; k < numNodes(); ++k) out[k] = nodeSpec(k).body.isGround();
        return out;
    }
    /// Number of the rope's external coordinates (RopeModel::numExternalCoordinates).
    int numExternal() const { return dim() * numStations() + static_cast<int>(driven.size()); }
};

/// State (a discrete variable of the subsystem, invalidating Stage::Position): the spatial ropes'
/// models, which carry their spans' reference frames A0 (ChordFrame). Per rope (nullptr for planar
/// ropes, and for spatial ones until the state is first realized to Stage::Position, when the
/// frames are built from the chords of that configuration: makeReferenceFrame(chord)). An event
/// (or ReevingSubsystem::resetSpanFrames) replaces a rope's model by one whose references are the
/// current element frames, rotating the transverse modal coordinates and rates with it.
/// State (a discrete variable, invalidating Stage::Position): per rope, per TractionSheave its phase
/// and the material coordinate offset of its current stick phase (s_k = sStick + g(theta))
/// and the count of transitions. (A wrap angle taken from the geometry is not state: it is a
/// function of the positions, RopeModel::wrapAngle of the position cache's evaluation.)
/// (TractionNodeState: nodes/DrivenRole.h.)
struct TractionStates {
    std::vector<std::vector<TractionNodeState>> ropes;
};

struct SpatialFrames {
    std::vector<std::shared_ptr<const RopeModel<3>>> models;
    std::vector<int> changes;  // per rope: reference changes since the frames were first built
};

/// Cache (per evaluation) of one rope:
/// Per-rope evaluation cache, allocated at Stage::Position. realizeVelocity refreshes its
/// velocity-level part (material rates, span evaluations, the rope reduced to its nodes) every time
/// velocities are realized; velocity-level queries check the stage.
struct RopeCache {
    Eigen::Matrix3Xd nodes3, nodeVelocities3;
    Eigen::Matrix2Xd nodes2, nodeVelocities2;  // planar ropes: in the plane basis
    Eigen::VectorXd modalCoordinates, modalRates;
    RopeData<2> planar;
    RopeData<3> spatial;
    const RopeModel<2>* planarModel = nullptr;  // the model `planar` was computed with (traction phases)
    const RopeModel<3>* spatialModel = nullptr;  // the model `spatial` was computed with (frames, traction phases)
    // With TractionSlip::RopeMomentum sheaves in slip: S and h with their Y condensed out (rows and
    // columns of Y zero), for the coupled solve.
    Eigen::MatrixXd condensedMass;
    Eigen::VectorXd condensedForce;
    bool condensed = false;
    // Per driven node: the Z state its role reads, and its rate (DrivenRole::readZState: a
    // TractionSlip::RopeMomentum sheave's Y, Ydot; unused entries 0) these were computed from.
    Eigen::VectorXd drivenZStates, drivenZRates;
    Eigen::VectorXd drivenS, drivenSdot;  // material coordinates and rates of the driven nodes
    Eigen::VectorXd drivenAngles, drivenAngleRates;  // their angles theta [rad] and rates [rad/s]
    // dynamics
    Eigen::VectorXd externalAccelerations;  // xddot of RopeModel's external coordinates (node positions
                                            // in the plane basis for planar ropes, driven s)
    Eigen::Matrix3Xd nodeAccelerations3;    // in Ground
    Eigen::VectorXd modalAccelerations;
};

/// Cache (per evaluation, scratch of realizeSubsystemDynamicsImpl):
/// Workspace of the coupled rope/body solve (sized at the first evaluation of a state, reused:
/// no heap allocation per evaluation once the sizes are reached).
struct CouplingWorkspace {
    Eigen::MatrixXd S, Lambda, lhs;
    // Lambda = J_U Minv_UU J_U^T: J_U the Jacobian of y restricted to the mobilities U the coupled
    // coordinates depend on (ancestors of their bodies), Minv_UU that block of M^-1.
    Eigen::MatrixXd JU, MinvUU, JUMinv;
    // Product route (k <= n, no constraint): SJ = [S J_U | S a0] over all ropes (n x (k + 1)), from
    // each rope's multiplyByNodeMass of X = its rows of [J_U | a0] (ropeX, ropeSX: per rope, scratch).
    Eigen::MatrixXd SJ, ropeX, ropeSX;
    Eigen::VectorXd h, f, rdd, a0, aUnit, rhs, responseU;
    Eigen::VectorXd reducedRhs, reducedSolution;  // the product route's k x k system (Woodbury)
    Eigen::VectorXd productWeights;  // [-z; 1]: rdd = [J_U | a0] productWeights (product route)
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    std::vector<int> U;                    // mobilities (u indices), ascending
    std::vector<DrivenAngleRow> angleRows;  // per MobileAngle: its angle's row this evaluation
    std::vector<double> angleSlopes;        // per MobileAngle: g'(theta) of its law this evaluation [m/rad]
    std::vector<SimTK::Vec3> nodeOffsets;  // per MobileNode: R_GB station [m], in Ground
    SimTK::Vector udot, generalizedForce, udotUnit, mobilityForcesUnit;
    SimTK::Vector_<SimTK::SpatialVec> A_GB, bodyForcesUnit, bodyVelocities, bodyForces;
    // Traction sheaves in TractionSlip::RopeMomentum slip: Y is a coordinate of the rope alone (no
    // body), condensed out of the rope's S and h before the coupled solve (RopeCache::condensed*),
    // its acceleration recovered after it.
    struct FreeSlip {
        int rope = 0, driven = 0, external = 0;
        double drive = 0, workRate = 0;
    };
    std::vector<FreeSlip> freeSlips;
    std::vector<int> freeIndex;                   // one rope's Y indices (scratch)
    Eigen::VectorXd freeDrive, freeAcceleration;  // its g_F, Yddot (scratch)
    Eigen::MatrixXd freeSxF, freeSFF, freeSolve;  // S_xF, S_FF, S_FF^-1 S_Fx (scratch)
    // Factored once at construction: a default-constructed LDLT leaves its info member
    // uninitialized, and the workspace is copied with the State's cache (UBSan reads it there).
    Eigen::LDLT<Eigen::MatrixXd> freeLdlt{Eigen::MatrixXd::Identity(1, 1)};
};

/// Cache (per evaluation): the subsystem's cache entry (Stage::Position), every rope's RopeCache,
/// the kinematics of the bodies that carry rope nodes (one Simbody query per body and stage, not
/// per node) and the coupling workspace.
struct PositionCache {
    std::vector<RopeCache> ropes;
    std::vector<SimTK::Transform> bodyX;   // per body slot: X_GB (Stage::Position)
    std::vector<SimTK::SpatialVec> bodyV;  // per body slot: V_GB (set at Stage::Velocity)
    CouplingWorkspace coupling;
};

/// Model (fixed at realizeTopology):
/// A rope node on a body other than Ground: it takes part in the coupled solve with one row per
/// direction its rope can pull in (3 for a spatial rope; 2, the plane's, for a planar one).
struct MobileNode {
    int rope = 0, node = 0;
    const SimTK::MobilizedBody* body = nullptr;
    SimTK::Vec3 station{0};
    int slot = 0;                                             // body slot (Guts::bodySlots)
    SimTK::MobilizedBodyIndex bodyIndex = SimTK::MobilizedBodyIndex();
    int row = 0, dims = 3;                                    // rows row..row+dims-1 of y
    Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();  // column d: row d's direction in Ground
};

/// Model (fixed at realizeTopology): a driven material coordinate in the coupled solve (1 row):
/// s = sRef + g(theta) of rope `rope`'s driven node `driven` (its DrivenLaw g and DrivenAngle
/// theta, whose row in each evaluation is CouplingWorkspace::angleRows, scaled by g'(theta)).
struct MobileAngle {
    int rope = 0, driven = 0;
    const SimTK::MobilizedBody* body = nullptr;  // the node's pin
};

/// Model (fixed at realizeTopology): where a rope sits in the coupled solve: its rows of the
/// coupled vector y = [2 or 3 per MobileNode | 1 per MobileAngle] and, for each, the rope's
/// external coordinate it is (a node's rows are its rope's own node coordinates, in the plane basis
/// for planar ropes): y[rows[a]] = x[external[a]]; Ground nodes have no rows. So
/// S_y(rows[a], rows[b]) = S_x(external[a], external[b]) and h_y likewise.
struct RopeCoupling {
    std::vector<int> rows;      // coupled rows of this rope, in y order
    std::vector<int> external;  // the rope's external coordinate of each row
};

}  // namespace detail

/// Model (the ropes, fixed for a simulation) and evaluation (realization into the PositionCache
/// cache entry) of a ReevingSubsystem: the SimTK::ForceSubsystem::Guts behind the handle.
class ReevingSubsystem::Guts : public SimTK::ForceSubsystem::Guts {
public:
    /// gravityFromSystem: the ropes' gravity is the system's (taken at realizeTopology);
    /// otherwise `gravity`, checked against the system's there.
    Guts(const SimTK::Vec3& gravity, bool gravityFromSystem)
        : SimTK::ForceSubsystem::Guts("ReevingSubsystem", "0.1"), gravity_(gravity),
          gravityFromSystem_(gravityFromSystem) {}
    Guts* cloneImpl() const override {
        Guts* copy = new Guts(*this);
        copy->system_ = nullptr;  // a clone belongs to another System
        copy->matter_ = nullptr;
        return copy;
    }

    std::vector<detail::RopeRecord> ropes;
    int decorationPoints = 20;
    double decorationForceScale = 0;  // ReevingSubsystem::setDecorationForceScale [N], 0: per frame

    // Cached at realizeTopology (MultibodySystem::downcast is a dynamic_cast: not per evaluation).
    const SimTK::MultibodySystem& mbs() const {
        if (!system_) system_ = &SimTK::MultibodySystem::downcast(getSystem());
        return *system_;
    }
    const SimTK::SimbodyMatterSubsystem& matter() const {
        if (!matter_) matter_ = &mbs().getMatterSubsystem();
        return *matter_;
    }
    const SimTK::Vec3& gravity() const { return gravity_; }
    /// "Up" of a gripping groove's angle: -g / |g|, +y without gravity (WrapStationMap's).
    SimTK::Vec3 gripUp() const { return gravity_.norm() > 0 ? SimTK::Vec3(-gravity_ / gravity_.norm()) : SimTK::Vec3(0, 1, 0); }
    bool gravityFromSystem() const { return gravityFromSystem_; }
    /// Finds the Force::Gravity and Force::UniformGravity elements of the system's
    /// GeneralForceSubsystems (at realizeTopology; their handles live as long as the topology).
    void findGravityForces();
    /// The gravity the bodies feel: the sum of the gravity vectors of those elements, with their
    /// defaults (state == nullptr: elements not disabled by default) or as set in `state`
    /// (elements not disabled there; Force::Gravity's magnitude and direction there, parameters
    /// that invalidate Stage::Dynamics). Returns how many elements were summed. Does not allocate.
    int systemGravity(const SimTK::State* state, SimTK::Vec3& sum) const;
    /// Throws std::logic_error (both vectors in the message) unless systemGravity(&s) equals the
    /// ropes' gravity (checked at every realizeDynamics when the system has gravity forces).
    void checkStateGravity(const SimTK::State& s) const;

    // ---- realization (ReevingRealization.cpp) ----------------------------------------------
    int realizeSubsystemTopologyImpl(SimTK::State& s) const override;
    int realizeSubsystemInstanceImpl(const SimTK::State& s) const override;
    int realizeSubsystemPositionImpl(const SimTK::State& s) const override;
    /// Strain scale eps_ref of the axial modal coordinates' error weights (see setZWeights) [-].
    static constexpr double kAxialWeightStrain = 1e-3;
    /// Sets rope r's integrator error weights of Z (State::updZWeights) from its spans' material
    /// lengths l_j = s_{j+1} - s_j (materialCoordinates: the rope's s at its nodes), or from the mean
    /// span length L / (number of spans) when materialCoordinates is nullptr.
    void setZWeights(const SimTK::State& s, const detail::RopeRecord& r,
                     const Eigen::VectorXd* materialCoordinates) const;
    int realizeSubsystemVelocityImpl(const SimTK::State& s) const override;

    /// Starts the next dependent-coordinate Newton of `to` (each rope's sheave material
    /// coordinates, condensed amplitudes and multipliers) from the solution cached in `from`, a
    /// state realized to Stage::Position near `to`: for a report interpolated inside the last step,
    /// the integrator's advanced state is a step away, the report's own cache a report interval
    /// (measured on the 12-fall crane: 6.4 Newton iterations per report from its own cache, half of
    /// them damped, against 1.4 per integrator evaluation). Only the Newton's start changes: it
    /// converges to the same tolerance. No-op for ropes whose traction phase differs between the
    /// two states, or when `from` is not realized to Stage::Position.
    void seedDependentCoordinates(const SimTK::State& from, const SimTK::State& to) const;
    /// Refreshes rope i's cache if Z changed after it was computed (see realizeSubsystemPositionImpl).
    void refreshFromZ(const SimTK::State& s, detail::PositionCache& pc, bool velocityLevel) const;
    /// True if c was computed from the current Z: the modal coordinates (rates) and the traction
    /// sheaves' slip states Y (Ydot).
    bool matchesZ(const SimTK::State& s, const detail::RopeRecord& r, const detail::RopeCache& c, bool rates) const;
    /// Node positions from the body transforms of pc (set by realizeSubsystemPositionImpl), then
    /// the rope's dependent coordinates.
    void updatePositionPart(const SimTK::State& s, const detail::RopeRecord& r, const detail::PositionCache& pc,
                            detail::RopeCache& c) const;
    /// Records an evaluation failure of rope r and rethrows it as std::runtime_error naming the
    /// rope and the time.
    [[noreturn]] void failEvaluation(const SimTK::State& s, const detail::RopeRecord& r,
                                     const std::exception& e) const;
    /// Node velocities from the body velocities of pc (set by realizeSubsystemVelocityImpl), then
    /// the rope's dynamics.
    void updateVelocityPart(const SimTK::State& s, const detail::RopeRecord& r, const detail::PositionCache& pc,
                            detail::RopeCache& c) const;
    /// Sets pc.bodyX (velocities: pc.bodyV) of every body slot from the state.
    void updateBodyKinematics(const SimTK::State& s, detail::PositionCache& pc, bool velocities) const;

    SimTK::Real calcPotentialEnergy(const SimTK::State& s) const override;
    int calcDecorativeGeometryAndAppendImpl(const SimTK::State& s, SimTK::Stage stage,
                                            SimTK::Array_<SimTK::DecorativeGeometry>& geometry) const override;

    /// The planar rope r's model in state s: r.planarModel, or for a rope with TractionSheaves the
    /// model of the state's traction phases (Stage::Model or later).
    const RopeModel<2>& planarModel(const SimTK::State& s, const detail::RopeRecord& r) const;
    /// The model of the traction phases of state s derived from `base` (the rope's stick model):
    /// base itself while no TractionSheave slips with TractionSlip::CapstanConstraint, else the
    /// phase's model from `models` (built there on first use; RopeRecord::TractionPhaseModel).
    template <int Dim>
    const RopeModel<Dim>& tractionPhaseModel(const SimTK::State& s, const detail::RopeRecord& r,
                                             const std::shared_ptr<const RopeModel<Dim>>& base,
                                             std::vector<detail::RopeRecord::TractionPhaseModel<Dim>>& models) const;
    /// Calls f(model, data) with rope r's model and evaluation data in cache c (RopeModel<2> and
    /// RopeData<2> for a planar rope, RopeModel<3> and RopeData<3> for a spatial one; the model
    /// the data were computed with) and returns what it returns: the traction code is written
    /// once for both.
    template <class Cache, class F>
    static decltype(auto) withRope(const detail::RopeRecord& r, Cache& c, F&& f) {
        if (r.planar) return f(*c.planarModel, c.planar);
        return f(*c.spatialModel, c.spatial);
    }
    const detail::TractionStates& tractionStates(const SimTK::State& s) const;
    detail::TractionStates& updTractionStates(SimTK::State& s) const;
    /// Axial forces P_a, P_b of the spans before and after node k at the node [N] (Stage::Position).
    std::pair<double, double> nodeAxialForces(const SimTK::State& s, const detail::RopeRecord& r, int node) const;
    /// The total axial forces EA (eps + c epsdot) at node k's two span ends [N] (Stage::Velocity):
    /// what TractionSlip::RopeMomentum's balance and friction act on.
    std::pair<double, double> nodeTotalForces(const SimTK::State& s, const detail::RopeRecord& r, int node) const;
    /// Before the coupled solve (realizeSubsystemDynamicsImpl, ReevingCoupling.cpp): every driven
    /// node registers its coordinates that move by their own balance (DrivenRole::condense: a
    /// TractionSlip::RopeMomentum sheave in slip its Y, applying its friction's reaction to its
    /// pin on its angle's row, mobilityForces or bodyForces), which are condensed out of their
    /// rope's S and h (RopeCache::condensed*; CouplingWorkspace::freeSlips).
    void condenseMomentumSlips(const SimTK::State& s, detail::PositionCache& pc, SimTK::Vector& mobilityForces,
                               SimTK::Vector_<SimTK::SpatialVec>& bodyForces) const;
    /// After it: rope i's Y accelerations from their rows, S_FF Yddot = g_F - S_Fx xddot, into its
    /// externalAccelerations.
    void recoverMomentumSlips(detail::PositionCache& pc, int rope) const;
    /// The largest fleet angle [rad] a span of a spatial rope may reach at a wrapped node: 85
    /// degrees; past it the run ends (limitMargin), short of the tangency's singularity at 90.
    static constexpr double kMaxFleetAngle = 85.0 * 3.14159265358979323846 / 180.0;

    /// The spatial rope r's model in state s (its span frames; with TractionSheaves, of the
    /// state's traction phases, tractionPhaseModel); if the state has no frames yet, builds them
    /// from the chords of `nodes` (the state's configuration) and stores them in the state (see
    /// SpatialFrames).
    const RopeModel<3>& spatialModel(const SimTK::State& s, const detail::RopeRecord& r,
                                     const Eigen::Matrix3Xd& nodes) const;
    /// The spatial rope r's model in state s (Stage::Position or later), as above.
    const RopeModel<3>& spatialModel(const SimTK::State& s, const detail::RopeRecord& r) const;
    const detail::SpatialFrames& spatialFrames(const SimTK::State& s) const;
    /// Builds a spatial rope model with these span reference frames.
    std::shared_ptr<const RopeModel<3>> makeSpatialModel(const detail::RopeRecord& r,
                                                         const std::vector<Eigen::Matrix3d>& references) const;
    /// Changes the reference frames of rope `rope`'s spans to their current element frames (all
    /// spans, or only those with 1 + i0 . i_e <= frameChangeAlignment when onlyDue), rotating
    /// their transverse modal coordinates and rates so that the rope's configuration and velocity
    /// field stay the same (reReferenceTransverseModes). Realizes s to Stage::Velocity first.
    /// Returns the number of spans changed.
    int changeSpanFrames(SimTK::State& s, int rope, bool onlyDue) const;
    /// Smallest 1 + i0 . i_e over rope r's spans in state s, minus frameChangeAlignment (the
    /// witness of the frame-change event; Stage::Position).
    double frameChangeMargin(const SimTK::State& s, int rope) const;
    double frameChangeAlignment = 0.5;

    // Defined in ReevingRealization.cpp, its only user (calcPotentialEnergy).
    template <int Dim>
    double potential(const RopeModel<Dim>& model, const RopeData<Dim>& data,
                     const Eigen::Matrix<double, Dim, Eigen::Dynamic>& nodes, const Eigen::VectorXd& qm) const;

    // ---- coupled rope/body solve (ReevingCoupling.cpp) -------------------------------------
    int realizeSubsystemDynamicsImpl(const SimTK::State& s) const override;

    bool anyConstraintEnabled(const SimTK::State& s) const;

    /// The generalized force the rope exerts on its supports at its external coordinates,
    /// h - S xddot (the reaction of the coupled solve; Stage::Dynamics): rows Dim k.. for node k
    /// (plane basis for planar ropes), Dim (N + 1) + d for driven node d.
    Eigen::VectorXd ropeReaction(const SimTK::State& s, const detail::RopeRecord& r, const detail::RopeCache& c) const;

    /// Accelerations of the coupled vector y (mobile nodes in Ground, then driven material
    /// coordinates) from the bodies' spatial accelerations and the mobilities' udot.
    /// Needs pc.coupling.nodeOffsets, angleRows and angleSlopes (set by realizeSubsystemDynamicsImpl).
    void couplingAccelerations(const detail::PositionCache& pc, const SimTK::Vector_<SimTK::SpatialVec>& A_GB,
                               const SimTK::Vector& udot, Eigen::VectorXd& a) const;
    /// The mobility Lambda of the coupled vector y (no Simbody constraint enabled), into ws.Lambda
    /// (sized n x n by the caller); see ReevingCoupling.cpp.
    void mobilityLambda(const SimTK::State& s, detail::CouplingWorkspace& ws) const;

    /// Where driven node d of rope r measures its angle in state s (DrivenAngle.h).
    detail::DrivenAngleSite angleSite(const SimTK::State& s, const detail::RopeRecord& r,
                                      const detail::RopeRecord::DrivenNode& d) const {
        return {s, r.nodeSpec(d.node).body, gripUp()};
    }
    /// Rope r's driven nodes in state s into its cache c: their angles theta (DrivenAngle) and
    /// material coordinates s = sRef + g(theta) (DrivenLaw; sRef a TractionSheave's stick offset,
    /// or its slip state Y in TractionSlip::RopeMomentum slip), with rates: their rates too.
    void drivenCoordinates(const SimTK::State& s, const detail::RopeRecord& r, detail::RopeCache& c, bool rates) const;

    // ---- rope limits (ReevingLimits.cpp) ----------------------------------------------------
    /// Smallest margin to a rope limit over all ropes [m] (Stage::Position): span material length
    /// minus RopeSpec::minimumSpanLength, rope left on each drum; and a description of the
    /// limiting one.
    double limitMargin(const SimTK::State& s, std::string* which) const;
    void recordLimit(const std::string& message) const { limitReached_ = message; }
    const std::string& limitReached() const { return limitReached_; }

    // ---- sampling (ReevingQueries.cpp) -----------------------------------------------------
    std::vector<SimTK::Vec3> sample(const SimTK::State& s, int rope, int span, int numPoints) const;
    /// The material coordinate where span j starts [m] (Stage::Position): s_j, or past the arc of a
    /// wrapped sheave at node j (s_j + l_j), from the span's coordinates.
    double spanStartMaterial(const SimTK::State& s, const detail::RopeRecord& r, int span) const;

    // ---- helpers -------------------------------------------------------------------------
    /// The rope cache, valid for the current Z (see realizeSubsystemPositionImpl); velocity-level parts
    /// are refreshed too when the state is realized to Stage::Velocity.
    const detail::PositionCache& positionCache(const SimTK::State& s) const {
        // getCacheEntry throws unless realized to Stage::Position. The entry is the
        // Value<PositionCache> allocated at realizeTopology: a static_cast, not Value::downcast's
        // dynamic_cast.
        detail::PositionCache& pc = const_cast<detail::PositionCache&>(
            static_cast<const SimTK::Value<detail::PositionCache>&>(getCacheEntry(s, positionCache_)).get());
        refreshFromZ(s, pc, s.getSystemStage() >= SimTK::Stage::Velocity);
        return pc;
    }
    /// The cache entry for realize*Impl (no stage check; one lookup per realization).
    detail::PositionCache& updPositionCache(const SimTK::State& s) const {
        return static_cast<SimTK::Value<detail::PositionCache>&>(updCacheEntry(s, positionCache_)).upd();
    }

    void modal(const SimTK::Vector& z, const detail::RopeRecord& r, bool rates, Eigen::VectorXd& q) const {
        q.resize(r.numModal);
        for (int j = 0; j < r.numModal; ++j) q[j] = z[r.zOffset + (rates ? r.numModal : 0) + j];
    }
    Eigen::VectorXd modal(const SimTK::Vector& z, const detail::RopeRecord& r, bool rates) const {
        Eigen::VectorXd q;
        modal(z, r, rates, q);
        return q;
    }

    Eigen::Matrix2Xd planarNodes(const detail::RopeRecord& r, const Eigen::Matrix3Xd& p) const {
        Eigen::Matrix2Xd out(2, p.cols());
        out.row(0) = r.e1.transpose() * p;
        out.row(1) = r.e2.transpose() * p;
        return out;
    }

    /// Evaluation failures (a rope's dependent coordinates not found at a trial state): how many,
    /// and the message of the last one. Integrators usually recover from them (smaller step).
    void recordEvaluationFailure(const std::string& message) const {
        lastEvaluationFailure_ = message;
        ++numEvaluationFailures_;
    }
    int numEvaluationFailures() const { return numEvaluationFailures_; }
    const std::string& lastEvaluationFailure() const { return lastEvaluationFailure_; }

private:
    SimTK::Vec3 gravity_;
    bool gravityFromSystem_ = false;
    // Fixed at realizeTopology: the system's gravity elements (uniform: nullptr for Force::Gravity).
    struct GravityForce {
        const SimTK::Force* force = nullptr;
        const SimTK::Force::Gravity* gravity = nullptr;        // a Force::Gravity, or
        const SimTK::Force::UniformGravity* uniform = nullptr;  // a Force::UniformGravity
    };
    std::vector<GravityForce> gravityForces_;
    // Fixed at realizeTopology: the mobile nodes of all ropes, in rope and node order, then the
    // driven material coordinates, and each rope's place in the coupled vector.
    std::vector<detail::MobileNode> mobileNodes_;
    int numStationRows_ = 0;                 // rows of y taken by the mobile nodes
    std::vector<std::pair<int, int>> rowOwner_;  // y row -> (mobile node, direction), station rows
    std::vector<detail::MobileAngle> mobileAngles_;
    std::vector<detail::RopeCoupling> ropeCoupling_;
    // Fixed at realizeTopology: every body that carries a rope node (Ground included), once; the
    // rope nodes, mobile nodes and angles refer to it by slot.
    std::vector<const SimTK::MobilizedBody*> bodySlots_;
    /// The last realizeDynamics coupled through products S J_U (RopeModel::multiplyByNodeMass): the
    /// next realizeVelocity lets the ropes skip forming S (RopeData::formNodeMass).
    mutable bool productCoupling_ = false;
    mutable std::string limitReached_;
    mutable std::string lastEvaluationFailure_;
    mutable int numEvaluationFailures_ = 0;

    mutable SimTK::CacheEntryIndex positionCache_;
    mutable SimTK::DiscreteVariableIndex framesVariable_;
    mutable SimTK::DiscreteVariableIndex tractionVariable_;
    mutable const SimTK::MultibodySystem* system_ = nullptr;
    mutable const SimTK::SimbodyMatterSubsystem* matter_ = nullptr;
};

namespace detail {

/// Adds to `system` the event handler that ends a run at a rope limit (span at its minimum
/// length, drum out of rope) of the ReevingSubsystem with index `reeving` (ReevingLimits.cpp).
void installLimitHandler(SimTK::System& system, SimTK::SubsystemIndex reeving);

/// Adds to `system` the event handler that changes the span reference frames of spatial rope
/// `rope` when a chord nears reversal against its reference (ReevingRealization.cpp).
void installFrameChangeHandler(SimTK::System& system, SimTK::SubsystemIndex reeving, int rope);

/// Helper: rope `rope` of g; throws std::invalid_argument if the index is out of range.
inline const RopeRecord& ropeAt(const ReevingSubsystem::Guts& g, int rope) {
    if (rope < 0 || rope >= static_cast<int>(g.ropes.size()))
        invalid("rope index = " + std::to_string(rope) + " is outside 0.." + std::to_string(g.ropes.size() - 1));
    return g.ropes[rope];
}

}  // namespace detail
}  // namespace SimbodyReeving
