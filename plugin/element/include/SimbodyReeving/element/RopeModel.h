#pragma once
/// @file
/// A rope made of ALE spans in series over frictionless deviation sheaves (pure C++/Eigen): the
/// sheave tension-equality constraint (paper eq 32) by coordinate partitioning, and the rope's
/// dynamics reduced to its node accelerations (for an exact coupling with rigid bodies).

#include "SimbodyReeving/element/GroovePlacement.h"
#include "SimbodyReeving/element/SpanModel.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace SimbodyReeving {

/// How the material coordinate s_k of a rope node is determined: the tag of a node law. RopeModel
/// turns each into its law type once, at construction (and withNodeLaw), and its evaluations call
/// the laws (one type per kind, behind one interface, in the element layer's sources): new node
/// physics is a new law type registered with a new tag, not a new branch in the rope.
enum class MaterialNode {
    /// A constant: the rope's end is fastened there (start: s_0 = 0; end: s_N = L, the unstretched
    /// length). End nodes only.
    Fixed,
    /// Dependent: a frictionless, massless point sheave; s_k is solved from the tension equality of
    /// the two spans meeting there (paper eq 32). Interior nodes only.
    Sliding,
    /// An external coordinate, given with its rate at every evaluation like the node positions: the
    /// rope is gripped there by something that moves it (a winch drum at an end, a drive or idler
    /// sheave in the path, s_k = s_ref + R theta). The rope's generalized force on it (the axial
    /// force difference across the node, or the force at an end) is part of the node reduction, so
    /// a coupled solve with the body that drives it is exact. Any node.
    Driven,
    /// Dependent, with friction: rope sliding over a sheave whose groove grips it (a traction
    /// sheave in slip). s_k is solved from the capstan law of the slip, P_{k-1}(s_k) = kappa P_k(s_k)
    /// with kappa = RopeModel::setSlipRatio's (e^(mu alpha) when the rope slides towards span k - 1,
    /// e^(-mu alpha) towards span k), and the friction force F_f = P_k - P_{k-1} [N] acts on the
    /// material there (the massless material point at the node is in balance). The node also has an
    /// external coordinate, like a Driven node (the sheave's surface, s_sheave = s_ref + R theta):
    /// the friction's reaction -F_f acts there (h = P_{k-1} - P_k, S has zero rows and columns there),
    /// so a Simbody layer can switch a sheave between Driven (stick) and Slipping (slip) without
    /// changing the external coordinates. The friction power on the rope's material and the sheave
    /// together is -(P_{k-1} - P_k)(sdot_k - sdot_sheave) <= 0 when kappa is chosen on the side the
    /// rope slides towards. With AxialDynamics::QuasiStatic spans the capstan row alone fixes s_k:
    /// no multiplier of it enters the condensed amplitudes' stationarity, so they solve the same
    /// equations as with the node Driven (stick), and switching between the two kinds at a
    /// configuration where the ratio holds keeps every dependent coordinate continuous. kappa = 1 is
    /// then a Sliding node plus an unloaded sheave coordinate exactly with AxialDynamics::Dynamic
    /// spans, and to the modal truncation with QuasiStatic ones (a Sliding node's amplitudes carry
    /// the tension equality's multiplier). Interior nodes only.
    Slipping,
};

/// How the rope meets the sheave at an interior node: at a point (radius 0: both spans end at the
/// node's position and share its material coordinate, the paper's eq 30) or wrapped on the groove
/// of a sheave of radius R: the arriving span ends at its tangent point T_in, the rope lies on the
/// groove arc of length l = R alpha (a GrooveArc, with its mass), and the departing span starts at
/// the tangent point T_out with the material coordinate s_k + l (s_k the node's material
/// coordinate, at T_in). The tangent points, the groove's centre (and axis in 3D) and l are
/// external coordinates given by the caller, as a point node's position is (the wrap geometry
/// computes them from the bodies, computeSpanTangency and wrapAngle; WrapStationMap from the
/// node stations, the NodeMatrix forms below). A wrapped interior node may be
/// Sliding (a frictionless sheave: s_k solved from the tension equality), Driven (a sheave that
/// grips the rope: s_k given, WrapStationMap carries it around the groove with the sheave's
/// rotation) or Slipping (a traction sheave in slip; its capstan law may follow the arc,
/// setSlipLaw). A wrapped end node must be Driven: a winch drum, the rope leaving it at one tangent
/// point (T_in = T_out there, l = 0: the rope beyond it is the drum's stored rope, setStoredRope).
struct NodeWrap {
    /// R [m] of the rope's centre line on the groove; 0 (the default): a point node. A wrapped
    /// end node must be Driven; R finite and >= 0.
    double radius = 0;
    /// sigma: +1 or -1 (GrooveCircle::wrapSense): the sense the rope turns about the axis.
    int wrapSense = 1;
    /// n [-]: the groove's unit axis in a spatial rope (Dim = 3), in the frame of the node
    /// positions; a finite unit vector (|n| within 1e-12 of 1). A planar rope's grooves turn
    /// about +z, and this field is not read. With turningAxis, the axis at the reference
    /// configuration (not read by the evaluations).
    Eigen::Vector3d axis{0.0, 0.0, 1.0};
    /// Dim = 3: the groove's axis turns with the body that carries the groove (a sheave on a
    /// slewing or luffing boom). It is then given per evaluation, as the node's position is: by an
    /// axis station, a point on the same body at unit distance from the groove's centre along the
    /// axis, n = p_axis - c, an extra column of the NodeMatrix forms' node arguments (after the
    /// N + 1 nodes, one per such node in node order: RopeModel::axisStation). Its velocity then
    /// carries the body's angular velocity, ndot = omega x n, into the rope's Lagrange equations
    /// (WrapStationMap), and the rope's generalized force on it is the couple the groove's axis
    /// carries. Sliding and Driven nodes (a Driven node's grip angle phi is measured from "up"
    /// projected onto the turning groove plane, WrapStationMap), drums included (their stored
    /// rope turns and tumbles with the drum, setStoredRope); not a Slipping node. Not for planar
    /// ropes.
    bool turningAxis = false;
    /// Where the groove circle lies along n from the node's position: x(Y) [m], Y the node's
    /// driven coordinate (the material coordinate at the groove's "up", RopeModel's s_driven); one
    /// of the units of GroovePlacement (GroovePlacement.h), checked by the unit. The default,
    /// CentredGroove: x = 0. A unit off the centre needs a wrapped Driven end node of a spatial
    /// rope (a drum: its one tangent point leaves the groove at c + x n; the stored rope's ring
    /// stays at the node's position).
    GroovePlacement groove{};
};

template <int Dim>
class RopeModel;
// Implementation types of the element layer (not installed): named here, defined in its sources.
struct WrapStationMapData;
class BandedLU;
template <int Dim>
class AxialCondensation;
template <int Dim>
class GrooveArc;
namespace detail {
template <int Dim>
struct RopeWorkspace;  // the scratch of an evaluation
template <int Dim>
struct RopeElements;  // the spans, their condensation kernels and the groove arcs (shared)
struct NodeLaw;       // a node's law (FixedLaw, SlidingLaw, DrivenLaw, SlippingLaw)
template <int Dim>
struct SlipAngle;  // a node's wrap angle and its derivatives in the external coordinates
}  // namespace detail

/// The results of a RopeModel's evaluation ("Data" of a RopeModel, as Pinocchio's Model/Data): what
/// changes every evaluation. Its scratch (span evaluations, the rope's mass and constraint
/// Jacobians, factorizations, Newton iterates) is private to the element layer, sized on first use
/// and reused, so repeated evaluations do not allocate.
template <int Dim>
struct RopeData {
    // ---- position level
    /// s_0..s_N at the nodes [m] (s_0 = 0, s_N = L); at a wrapped node, where the rope arrives on
    /// the groove (the departing span starts at s_k + l_k, NodeWrap).
    Eigen::VectorXd materialCoordinates;
    /// Condensed amplitudes [m] (SpanModel::numCondensedModes per span: the axial amplitudes of
    /// AxialDynamics::QuasiStatic spans, then the transverse ones of TransverseDynamics::QuasiStatic
    /// spans), span by span (also the warm start of the next solve).
    Eigen::VectorXd condensedAmplitudes;
    /// Multipliers nu_k of the sheave constraints in the condensation's stationarity conditions
    /// (only with condensed spans): dU/ds_k / EA + sum_m nu_m dC_m/ds_k = 0.
    Eigen::VectorXd multipliers;
    int newtonIterations = 0;             ///< of the last dependent-coordinate solve
    // ---- dynamics (filled by RopeModel::computeDynamics)
    /// sdot_0..sdot_N [m/s] (Driven nodes: as given; a gripping node (setGrip): the groove's rate
    /// over the stretch there, (Ydot_s + sigma R phidot) / lambda_k)
    Eigen::VectorXd materialRates;
    Eigen::VectorXd condensedRates; ///< rates of condensedAmplitudes [m/s]
    Eigen::VectorXd multiplierRates;  ///< rates of multipliers
    /// Per Driven node, the rate of its creep state c_k [m/s] (setGrip): (Ydot_s + sigma R phidot)
    /// (1 / lambda_k - 1) at a gripping node, 0 elsewhere (empty for a rope without grips).
    Eigen::VectorXd gripCreepRates;
    /// Input (set by the caller before solveDependentCoordinates): per Driven node, the creep c_k
    /// [m] its drivenS entry includes (setGrip), read at gripping nodes only; empty: 0. The stored
    /// ring (its energies, mass and forces) and a walking groove's exit point (WalkingGroove) are
    /// laid from the groove's own coordinate s_k - c_k.
    Eigen::VectorXd gripCreep;
    /// Per Driven node, the rate [W] of the energy held by the rope wound on it (setGrip): its
    /// strain energy U_w, kappa EA F(eps_k) sdot_k, plus, with a stored ring, the creep's weight
    /// U_c, kappa rhoA phi_T cdot_k (phi_T = -g . r_T at the tangent point); 0 elsewhere (empty for
    /// a rope without grips).
    Eigen::VectorXd gripHeldEnergyRates;
    /// Mode-acceleration correction of the dependent coordinates [q_condensed, s_1..s_{N-1}, nu]
    /// (see RopeModel::recoverInertialStrain); valid once computed for the current accelerations.
    Eigen::VectorXd inertialCorrection;
    bool inertialCorrectionValid = false;  ///< inertialCorrection belongs to the last computeDynamics
    /// Effective mass of the rope at its external coordinates x = [node blocks, s at the Driven nodes]
    /// (RopeModel::numExternalCoordinates), S = Mbar_xx - Mbar_xm Mbar_mm^-1 Mbar_mx, and the
    /// matching force h: the generalized force the supports must apply to the rope is
    /// f = S xddot - h (for a Driven s_k: the force [N] that holds the rope's material there).
    Eigen::MatrixXd nodeMass;
    Eigen::VectorXd nodeForce;  ///< h [N] (see nodeMass)
    /// The inertia of the station map's bias in h: h = Q - J^T M b, with b the external
    /// coordinates' accelerations at zero station accelerations (a wrapped node's rolling tangent
    /// point, a gripping drum's stretch rate, RopeModel::setGrip); this is J^T M b [N], at the
    /// stations. A law that replaces the rope's forces Q on one coordinate (a traction sheave's
    /// momentum balance) keeps it. Empty when the rope's nodes are not stations (no wrapped node).
    Eigen::VectorXd nodeMassBias;
    /// Set false before computeDynamics to skip forming nodeMass (left empty; one solve per moving
    /// external coordinate saved): RopeModel::multiplyByNodeMass gives S X, and modalAccelerations
    /// solves for its accelerations instead. Default true.
    bool formNodeMass = true;
    double kineticEnergy = 0;    ///< T of all spans, groove arcs and stored rope [J]
    double strainEnergy = 0;     ///< [J]
    double gravityEnergy = 0;    ///< of all spans, groove arcs and stored rope [J]
    /// Power dissipated by the spans' Kelvin-Voigt damping (RopeProperties::axialRetardationTime)
    /// [W], >= 0: sum of SpanData::dampingPower. The damping forces are part of nodeForce.
    double dampingPower = 0;


    /// Reduced mass Mbar = G^T M G of the last computeDynamics, on the independent velocities
    /// w = [xdot, qdot_m] (external coordinates, then modal state coordinates). Dense, O(n^3): formed
    /// on first request after each computeDynamics (static equilibrium, tests), not by the dynamics
    /// themselves, which solve the rope's chain-structured equations directly. The model that ran
    /// computeDynamics must still exist.
    const Eigen::MatrixXd& reducedMass() const;
    /// Reduced force Qbar = G^T (Q - M c) of the last computeDynamics, on w [N] (as reducedMass).
    const Eigen::VectorXd& reducedForce() const;
    /// Coordinates q of span j (SpanModel layout) at the last evaluation.
    const Eigen::VectorXd& spanCoordinates(int span) const;
    /// Their rates qdot (SpanModel layout) at the last computeDynamics.
    const Eigen::VectorXd& spanRates(int span) const;

    RopeData();                                      ///< empty: sized by the first evaluation
    ~RopeData();                                     ///< (the workspace's type is complete in the .cpp)
    RopeData(const RopeData& other);                 ///< deep copy, scratch included
    RopeData& operator=(const RopeData& other);      ///< deep copy, scratch included
    RopeData(RopeData&& other) noexcept;             ///< move
    RopeData& operator=(RopeData&& other) noexcept;  ///< move

private:
    friend class RopeModel<Dim>;
    /// Owns the scratch; its copies deep-copy it (members defined where the type is complete).
    class Scratch {
    public:
        Scratch();
        ~Scratch();
        Scratch(const Scratch& other);
        Scratch& operator=(const Scratch& other);
        Scratch(Scratch&& other) noexcept;
        Scratch& operator=(Scratch&& other) noexcept;
        detail::RopeWorkspace<Dim>& operator*() const { return *p_; }

    private:
        std::unique_ptr<detail::RopeWorkspace<Dim>> p_;
    };
    detail::RopeWorkspace<Dim>& ws() { return *workspace_; }
    detail::RopeWorkspace<Dim>& scratch() const { return *workspace_; }  // (evaluation scratch)
    const detail::RopeWorkspace<Dim>& ws() const { return *workspace_; }
    Scratch workspace_;
};

/// A rope of N spans between N + 1 nodes: node 0 is the rope's start, nodes 1..N-1 are sheaves
/// (point contact: both spans meet at the node and share its material coordinate), node N is its
/// end. Each node's material coordinate is Fixed, Sliding or Driven (MaterialNode; by default the
/// ends are Fixed anchors and the sheaves Sliding, frictionless). Node positions are given from outside each evaluation
/// (they are tied to bodies); the modal coordinates q_m of all spans are the rope's own
/// independent coordinates ("modal state"), except the condensed amplitudes (the axial ones of
/// spans with AxialDynamics::QuasiStatic, the transverse ones of spans with
/// TransverseDynamics::QuasiStatic), which are dependent, solved from dU/dq = 0 (AxialCondensation);
/// the material coordinates s_1..s_{N-1} at the sheaves are dependent, solved from the tension
/// equality EA eps_{k-1}(s_k) = EA eps_k(s_k) (paper eq 32), with s_0 = 0 and s_N = L (unstretched
/// rope length) fixed.
///
/// Rope coordinates z = [x | q_free | q_condensed, s_sliding, nu | s_fixed] with the external
/// coordinates x = [r_0..r_N, s_driven]; independent velocities w = [xdot, qdot_free]; dependents
/// d = [q_condensed, s_sliding, nu] (one multiplier per Sliding node, with condensed spans only) with
/// constraints C(z) = 0; zdot = G w, zddot = G wdot + c. The reduced equations
/// Mbar wdot = Qbar with Mbar = G^T M G, Qbar = G^T (Q - M c) keep T + U invariant (the constraints
/// are holonomic and their reactions do no work along admissible motions).
///
/// **Quasi-static condensation.** The condensed amplitudes make U stationary on the manifold of the
/// sheave constraints C_k = eps_{k-1}(s_k) - eps_k(s_k) = 0 (at fixed nodes and modal states), i.e.
/// with multipliers nu_k (no inertia: zero rows in M):
///     dU/da / EA + sum_k nu_k dC_k/da = 0,   dU/ds_k / EA + sum_m nu_m dC_m/ds_k = 0,   C = 0.
/// This is exactly the condition d(U restricted to the sheave constraints)/da = 0 that the Dynamic
/// model's static equilibrium satisfies, so both models share their static equilibria. (dU/ds_k
/// is not zero at equal end strains: material moved over a sheave changes the spans' gravity
/// energy through their mean positions.) Without condensed spans there are no multipliers and the
/// rows are the paper's tension equalities alone.
template <int Dim>
class RopeModel {
public:
    using Vec = Eigen::Matrix<double, Dim, 1>;                      ///< a point or vector [m]
    using Mat = Eigen::Matrix<double, Dim, Dim>;                    ///< a Dim x Dim matrix
    using NodeMatrix = Eigen::Matrix<double, Dim, Eigen::Dynamic>;  ///< node positions or velocities, one column each

    /// @param spans one SpanModel per span, in path order (all with the same RopeProperties).
    /// @param unstretchedLength L [m] > 0: material coordinate of a Fixed end node.
    /// @param nodeKinds one MaterialNode per node (N + 1); empty: Fixed ends, Sliding sheaves.
    /// @param wraps one NodeWrap per node (N + 1); empty: every node a point.
    /// @throws std::invalid_argument for no spans, spans with different rope properties, L not
    ///         finite and > 0, nodeKinds or wraps of the wrong size, a Fixed interior node or a
    ///         Sliding end, a wrapped end node that is not Driven, a wrap radius not finite and >= 0, a wrap sense
    ///         other than +1 or -1, or (Dim = 3) a wrapped node's axis that is not a finite unit vector;
    ///         NodeWrap::turningAxis on a point node, a Slipping node or a planar rope.
    RopeModel(std::vector<SpanModel<Dim>> spans, double unstretchedLength, std::vector<MaterialNode> nodeKinds = {},
              std::vector<NodeWrap> wraps = {});
    ~RopeModel();                                      ///< (its parts' types are complete in the .cpp)
    RopeModel(const RopeModel& other);                 ///< copy (sharing the spans, kernels and arcs: immutable)
    RopeModel& operator=(const RopeModel& other);      ///< copy (as the copy constructor)
    RopeModel(RopeModel&& other) noexcept;             ///< move
    RopeModel& operator=(RopeModel&& other) noexcept;  ///< move

    int numSpans() const { return numSpans_; }       ///< N
    int numNodes() const { return numSpans() + 1; }  ///< N + 1
    MaterialNode nodeKind(int node) const;           ///< how node k's s_k is determined (its law's tag)
    /// Number of Driven and Slipping nodes (each has an external coordinate: the driven material
    /// coordinate, or the slipping sheave's surface coordinate): the length of the drivenS vectors
    /// below (the entries of Slipping nodes are read only for their rates, the sheave's speed).
    int numDrivenNodes() const { return numDriven_; }
    /// Index of node k's external material coordinate among the Driven and Slipping ones (drivenS), or -1.
    int drivenIndex(int node) const { return drivenIndex_[node]; }
    /// Number of external coordinates x = [node blocks 0..N, s_driven]: numNodeCoordinates() +
    /// numDrivenNodes() (Dim (N + 1) + numDrivenNodes() for a rope of point nodes).
    int numExternalCoordinates() const { return numNodeCoordinates_ + numDriven_; }
    /// Number of external coordinates of the nodes: Dim per point node (its position r_k),
    /// wrappedBlockSize() per wrapped node.
    int numNodeCoordinates() const { return numNodeCoordinates_; }
    /// First external coordinate of node k's block: the position r_k of a point node; of a
    /// wrapped node, [c, T_in, T_out, n (Dim = 3 only), l] at the offsets below.
    int nodeCoordinateOffset(int node) const { return nodeOffset_[node]; }
    bool isWrapped(int node) const { return arcIndex_[node] >= 0; }          ///< NodeWrap::radius > 0
    /// The groove's unit axis n of node k (NodeWrap::axis in a spatial rope; +z in a planar one;
    /// at a node with NodeWrap::turningAxis its reference value: the evaluations take it from the
    /// axis station).
    const Eigen::Vector3d& grooveAxis(int node) const { return grooveAxes_[node]; }
    /// Number of station points the NodeMatrix forms take: the N + 1 nodes, then one axis
    /// station per node with NodeWrap::turningAxis.
    int numStations() const { return numNodes() + numAxisStations_; }
    /// The column of node k's axis station in the NodeMatrix forms' node arguments (N + 1 + its
    /// index among the turning nodes), or -1 if its axis does not turn.
    int axisStation(int node) const { return axisStation_[node]; }
    /// Where node k's groove circle lies along its axis (NodeWrap::groove; CentredGroove at
    /// point nodes and where none was given).
    const GroovePlacement& groovePlacement(int node) const { return placements_[node]; }
    int numWrappedNodes() const;  ///< nodes with a groove arc
    /// The rope on the groove of wrapped node k (its mass, radius and sense).
    /// @throws std::invalid_argument if node is not wrapped.
    const GrooveArc<Dim>& arc(int node) const;
    /// Offsets in a wrapped node's block: the groove's centre c [m], the arrival tangent point
    /// T_in [m] (the end of span k - 1), the departure tangent point T_out [m] (the start of span
    /// k), the groove's unit axis n [-] (Dim = 3 only; in the plane it is +z), the arc length
    /// l = R alpha [m].
    static constexpr int wrappedCentreOffset() { return 0; }                                ///< c
    static constexpr int wrappedArrivalOffset() { return Dim; }                             ///< T_in
    static constexpr int wrappedDepartureOffset() { return 2 * Dim; }                       ///< T_out
    static constexpr int wrappedAxisOffset() { return 3 * Dim; }                            ///< n (Dim = 3)
    static constexpr int wrappedArcLengthOffset() { return 3 * Dim + (Dim == 3 ? 3 : 0); }  ///< l
    static constexpr int wrappedBlockSize() { return wrappedArcLengthOffset() + 1; }        ///< coordinates per wrapped node

    /// Declares rope stored at a Driven end node (a winch drum): its length is
    ///     l = lengthAtZero + s_0 (start node) or l = lengthAtZero - s_N (end node) [m]
    /// (hauling material out of the spans stores it; at a gripping node (setGrip) s_k - c_k
    /// instead of s_k, c_k the creep, and v below is the groove's rate Ydot_s + sigma R phidot,
    /// carried to sdot_k = v / lambda_k by its rate's map). At a point drum it is held as a ring at the
    /// node moving with it at the rope's rate there (the drum's surface speed):
    ///     T_stored = 1/2 rhoA l (|rdot_k|^2 + sdot_k^2),   U_stored = -rhoA l g . r_k.
    /// At a wrapped drum (NodeWrap) it lies on the groove and turns with the drum, whatever the
    /// tangent point does: with c the groove's centre, v = sdot_k - sigma R phidot the drum's
    /// surface speed (phi the tangent point's angle from "up") and psi_e = phi -+ sigma l / R the
    /// angle of its far end,
    ///     T_stored = 1/2 rhoA [l (|cdot|^2 + v^2) -+ 2 R v cdot . (u(phi) - u(psi_e))],
    ///     U_stored = -rhoA l g . c +- rhoA |g| sigma R^2 (sin phi - sin psi_e)
    /// (upper signs at the rope's start; u(psi) the groove's radial direction at angle psi): the
    /// integrals over the stored material of one layer, the partial turn's terms included. A
    /// spatial drum whose axis turns (NodeWrap::turningAxis) adds the stored rope's tumbling: its
    /// angular velocity gains n x ndot, and T_stored and U_stored are the same integrals for that
    /// rigid motion (the arc's first and second moments, closed form).
    /// Without it the material would vanish from the model at the drum, carrying its potential
    /// energy -rhoA g . r_k per metre out through the span's generalized force on s_k: a drum torque
    /// that depends on the height datum. With it the torque is datum-free, the stored rope's weight
    /// and inertia load the node's body, and T + U (spans + stored rope; with a grip also the held
    /// energy U_w + U_c of setGrip) keeps its invariance.
    /// Added to nodeMass, nodeForce and the energies by computeDynamics.
    /// @throws std::invalid_argument if node is not a Driven end node or lengthAtZero is not finite.
    void setStoredRope(int node, double lengthAtZero);
    /// Declares that the wrapped Driven end node k (a drum, NodeWrap) grips the rope where it
    /// leaves the groove: the material there moves with the groove's surface, whatever the strain,
    ///     sdot_k = (Ydot_s + sigma R phidot) / lambda_k,   lambda_k = sqrt(1 + 2 eps_k),
    /// lambda_k the stretch (spatial length per unstretched length) of the span at its end there,
    /// Ydot_s + sigma R phidot the groove surface's speed past the tangent point [m/s] (the rope's
    /// external coordinate's rate as WrapStationMap writes it, drivenS's rate plus the tangent
    /// point's turn). Without the grip the groove carries R of unstretched rope per radian (sdot_k =
    /// Ydot_s + sigma R phidot): a span stretched by eps then gains eps R of slack material per radian
    /// the tangent point rolls, and the load rests eps R off the vertical under the tangent point.
    /// The relation is not integrable (lambda_k changes with the tension), so it is a velocity
    /// constraint: s_k = Y_s + sigma R phi + c_k with c_k, the creep of the rope against the
    /// unstretched groove, a state of the caller, carried in drivenS (which then holds
    /// Y_s + c_k), and cdot_k = (Ydot_s + sigma R phidot)(1 / lambda_k - 1), which computeDynamics
    /// reports in RopeData::gripCreepRates. computeDynamics scales the node's row of the station
    /// map's Jacobian by 1 / lambda_k and adds d(1/lambda_k)/dt (Ydot_s + sigma R phidot) to its
    /// bias (the span's end-strain rate, SpanModel::endStrain): the rope's equations reduced to the
    /// stations are then Maggi's for the constraint, which does no work.
    /// The wound rope keeps the strain it had at the tangent point: it holds the strain energy
    ///     U_w = int EA F(eps) ds over the material wound on since the start,
    /// whose rate kappa EA F(eps_k) sdot_k (kappa = +1 at a start drum, -1 at an end drum)
    /// computeDynamics reports in RopeData::gripHeldEnergyRates (the caller integrates it: T + U
    /// + U_w is invariant) and whose generalized force -kappa EA F(eps_k) on s_k it adds to h; the
    /// drum then holds the rope with its true force EA eps_k lambda_k. The stored rope's ring
    /// (setStoredRope) turns with the groove: its law is evaluated at the groove's rate Ydot_s +
    /// sigma R phidot and laid from the groove's coordinate s_k - c_k (RopeData::gripCreep, which
    /// the caller sets), so it is a holonomic function of the stations, carried to s_k by the
    /// grip's rate map. The ring's amount is that of s_k - c_k, short of the material wound on by
    /// the creep c_k (of order eps of it): the creep's mass rhoA kappa c_k is held at the height of
    /// the tangent point where it was wound, an energy U_c whose rate, kappa rhoA phi_T cdot_k
    /// (phi_T = -g . r_T), computeDynamics adds to RopeData::gripHeldEnergyRates, with the
    /// generalized force kappa rhoA phi_T (lambda_k - 1) on s_k: the rope's mass is conserved and
    /// no force depends on the height datum. Not modelled: the creep's mass does not turn with
    /// the drum (its kinetic energy, at most rhoA |c_k| v^2 / 2, and its weight's change as the
    /// drum turns, at most rhoA |c_k| g 2 R, are left out), and the stored ring's mass is counted
    /// per metre of groove it covers (rhoA per metre of s_k - c_k), not per metre of the
    /// stretched material on it.
    /// @throws std::invalid_argument if node is not a wrapped Driven end node.
    void setGrip(int node);
    bool grips(int node) const;  ///< true if setGrip(node) was called
    /// Sets the tension ratio kappa = P_{k-1} / P_k [-] of the Slipping node k (see
    /// MaterialNode::Slipping; default 1): setSlipLaw(node, kappa, 0).
    /// @throws std::invalid_argument if node is not Slipping or kappa is not finite and > 0.
    void setSlipRatio(int node, double kappa);
    /// Sets the capstan law of the Slipping node k as a function of its wrap angle alpha in the
    /// current geometry:
    ///     kappa(alpha) = P_{k-1} / P_k = kappa_0 e^(c alpha),
    /// so that with kappa_0 = 1 and c = +-mu the law is Euler-Eytelwein's e^(+-mu alpha) with the
    /// wrap angle of the current geometry (wrapAngle): alpha = l / R at a wrapped node (l an
    /// external coordinate; in a spatial rope the arc in the groove's plane between the 3D tangent
    /// points), the turning angle between the two spans' chords at a point node (from the
    /// positions of node k and of the spans' far ends; in a spatial rope in the plane the two
    /// chords span, see wrapAngle). kappa(alpha) enters
    /// the constraint row's Jacobian (its columns at l, or at the three positions) and its
    /// acceleration bias (the terms in alphadot, and alpha's own quadratic-velocity term at a
    /// point node), so the coupled solve stays exact as alpha changes.
    /// @param node          k, a Slipping node.
    /// @param kappa0        kappa_0 [-], finite and > 0.
    /// @param angleExponent c [1/rad], finite.
    /// @throws std::invalid_argument if node is not Slipping, kappa0 is not finite and > 0, or
    ///         angleExponent is not finite.
    void setSlipLaw(int node, double kappa0, double angleExponent);
    /// The wrap angle alpha [rad] of interior node k in the geometry of data's last evaluation
    /// from node positions or stations (as surfaceCoordinate): l / R at a wrapped node (in a
    /// spatial rope the angle in the groove's plane between the radius vectors to the 3D tangent
    /// points); at a point node the turning angle between the chords of spans k - 1 and k,
    /// atan2(|d_in x d_out|, d_in . d_out) in [0, pi] (d_in from span k - 1's start to r_k, d_out
    /// from r_k to span k's end; in a spatial rope measured in the plane the two chords span,
    /// whose normal is d_in x d_out / |d_in x d_out|): pi for a rope doubling back over the node, 0
    /// for a straight one. (Spatial: where the chords are parallel that plane is undefined and
    /// alpha has a kink; its derivatives are then taken in the plane normal to grooveAxis(node),
    /// +z at a point node.)
    /// @throws std::invalid_argument if node is not interior or data holds no such evaluation.
    double wrapAngle(const RopeData<Dim>& data, int node) const;
    /// The external coordinate of Driven or Slipping node k, the material coordinate of the
    /// sheave's surface where the rope arrives on it [m]: drivenS's entry at a point node,
    /// Y_s + sigma R phi_in at a wrapped one (WrapStationMap; at a gripping drum (setGrip) the
    /// rope's s_k, its creep c_k included, and surfaceRate its sdot_k = v / lambda_k), from the last
    /// solveDependentCoordinates on data from node positions (the NodeMatrix forms).
    /// @throws std::invalid_argument if node is neither Driven nor Slipping or data holds no such evaluation.
    double surfaceCoordinate(const RopeData<Dim>& data, int node) const;
    /// Its rate [m/s], from the last computeDynamics on data. s_k - surfaceCoordinate is the rope's
    /// slip over a Slipping node's groove (0 at a Driven node), sdot_k - surfaceRate its slip rate.
    /// @throws std::invalid_argument as surfaceCoordinate.
    double surfaceRate(const RopeData<Dim>& data, int node) const;
    /// The fleet angles [rad] of span j at its start and its end in the geometry of data's last
    /// evaluation from node positions or stations (WrapStationMapData::startFleetAngles): the angle
    /// between the span and the groove's plane of a wrapped node there, 0 at point nodes and in a
    /// planar rope.
    /// @throws std::invalid_argument if span is out of range or data holds no such evaluation.
    std::pair<double, double> fleetAngles(const RopeData<Dim>& data, int span) const;
    double slipRatio(int node) const;          ///< kappa_0 of a Slipping node (else 1)
    double slipAngleExponent(int node) const;  ///< c [1/rad] of a Slipping node (else 0)
    /// A phase change of a traction sheave without rebuilding the rope: a copy of this model with
    /// interior node k's law changed between Driven (stick: s_k given by drivenS) and Slipping
    /// (slip with the capstan law kappa(alpha) = kappa0 e^(angleExponent alpha), as setSlipLaw), or
    /// a Slipping node given another law. Both kinds have the node's external coordinate, so the
    /// external coordinates x, drivenS and the stations are the same for both models; the
    /// dependent coordinates gain (Slipping) or lose (Driven) s_k, and nu_k with condensed spans.
    /// The result is the model built from scratch with that kind at node k (then setSlipLaw,
    /// the same setStoredRope and setStationaryNodes): every evaluation agrees with it bit for bit.
    /// This model is not changed (a simulation keeps one model per phase). Give the new model a
    /// RopeData of its own, warm-started from the material coordinates and condensed amplitudes of
    /// the last phase's (as the Simbody layer's traction phases do): a RopeData that another model
    /// solved at the same positions is taken as solved (the positions are compared, not the models).
    /// Cost: the spans, their condensation kernels and the groove arcs are shared with this model
    /// (not copied: span(j) is the same object); the node laws and the coordinate layout that
    /// depends on them (index maps, chain order, the band offsets of the mass entries: integers,
    /// linear in the spans) are built anew, with their allocations: a phase change, not an
    /// evaluation (docs/performance.md compares it with building the model anew).
    /// @param node          k, an interior node whose law is Driven or Slipping.
    /// @param kind          MaterialNode::Driven or MaterialNode::Slipping.
    /// @param kappa0        kappa_0 [-] of a Slipping law, finite and > 0; 1 for Driven.
    /// @param angleExponent c [1/rad] of a Slipping law, finite; 0 for Driven.
    /// @throws std::invalid_argument if node is not interior, its law or kind is neither Driven
    ///         nor Slipping, a Slipping node would sit on a turning groove (NodeWrap::turningAxis),
    ///         kappa0 or angleExponent are not valid for the kind.
    RopeModel withNodeLaw(int node, MaterialNode kind, double kappa0 = 1.0, double angleExponent = 0.0) const;
    /// Declares which nodes never move (a node on Ground): their velocities and accelerations are zero
    /// in every evaluation. computeDynamics then skips their columns of nodeMass (left zero, as is
    /// their share in the modal accelerations): one solve less per coordinate. Their rows stay exact
    /// (the reaction h - S xddot at a fixed node is still right). Default: no node is stationary.
    /// @throws std::invalid_argument if stationary does not have numNodes() entries.
    void setStationaryNodes(const std::vector<bool>& stationary);
    /// Gravity energy of the stored rope at these node positions and material coordinates [J].
    double storedRopeGravityEnergy(const NodeMatrix& nodes, const RopeData<Dim>& data) const;
    /// Gravity energy of the rope on the groove arcs [J] at these stations (a rope with wrapped
    /// nodes: WrapStationMap) and data's material coordinates; 0 without wrapped nodes.
    double arcGravityEnergy(const NodeMatrix& nodes, const RopeData<Dim>& data) const;
    /// Number of modal state coordinates (all spans' modes, less the condensed axial amplitudes of
    /// QuasiStatic spans): the length of the qm vectors below.
    int numModalCoordinates() const { return numModal_; }
    /// First entry of span j's modal state coordinates in qm.
    int modalOffset(int span) const { return modalOffset_[span]; }
    /// Number of condensed axial amplitudes (QuasiStatic spans), the length of
    /// RopeData::condensedAmplitudes.
    int numCondensedCoordinates() const { return numCondensed_; }
    /// First entry of span j's condensed amplitudes in RopeData::condensedAmplitudes, or -1.
    int condensedOffset(int span) const { return condensedOffset_[span]; }
    /// True if span j's axial amplitudes are condensed (AxialDynamics::QuasiStatic and n_a > 0).
    bool isCondensed(int span) const { return condensedOffset_[span] >= 0; }
    double unstretchedLength() const { return length_; }                              ///< L [m]
    const SpanModel<Dim>& span(int j) const;      ///< span j's element
    const RopeProperties& properties() const;    ///< of every span

    /// Solves the constraints for the dependent coordinates, s_1..s_{N-1} and the condensed axial
    /// amplitudes, by Newton's method (starting from data if it holds an admissible guess, else
    /// from s split in proportion to the chord lengths and zero amplitudes) to a residual <= 1e-14
    /// (strain units), or until it stagnates at round-off below 1e-12. Steps that do not reduce
    /// |C|_2 are halved (damped Newton; the rounded tension-only law of quasi-static spans changes
    /// curvature sharply where points go slack); a failed warm start is retried once from the
    /// cold guess.
    /// @throws std::runtime_error if Newton does not converge in 100 iterations (each damped
    ///         halving counts as one), from the warm and the cold start, or a span length
    ///         would become non-positive (the rope cannot carry the configuration).
    /// @param nodes positions of the rope's nodes [m], one column per node.
    /// @param drivenS material coordinates of the Driven nodes [m], in node order.
    /// @param qm the modal state coordinates, numModalCoordinates() of them (span j from modalOffset(j)).
    /// @param data receives the dependent coordinates; its previous ones are the warm start.
    /// @throws std::runtime_error also if the given material coordinates leave a span without
    ///         material (s_{k+1} <= s_k between Fixed/Driven nodes: a drum hauled the rope in).
    void solveDependentCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS, const Eigen::VectorXd& qm,
                                   RopeData<Dim>& data) const;
    /// As above for ropes without Driven nodes.
    void solveDependentCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& qm, RopeData<Dim>& data) const;
    /// As above, with all external coordinates x (numExternalCoordinates(): the node blocks, then
    /// the Driven material coordinates). The NodeMatrix forms pack x from their arguments for a
    /// rope of point nodes, and map it from the node stations (WrapStationMap) for a rope with
    /// wrapped nodes.
    /// @throws std::invalid_argument if x has the wrong size.
    void solveDependentCoordinatesFromExternal(const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                               RopeData<Dim>& data) const;

    /// The coordinates q of span j (SpanModel layout) from node positions, modal state coordinates
    /// and the dependent coordinates held by data (material coordinates, condensed amplitudes).
    void spanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm, const RopeData<Dim>& data,
                         Eigen::VectorXd& q) const;
    /// As spanCoordinates from all external coordinates x.
    void spanCoordinatesFromExternal(int j, const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                     const RopeData<Dim>& data, Eigen::VectorXd& q) const;

    /// Velocity and dynamics level: material rates, span evaluations, and the rope reduced to its
    /// nodes (nodeMass, nodeForce), energies. Reuses the position-level work of the last
    /// solveDependentCoordinates on data when it was done at these positions (nodes and qm compared
    /// exactly), and calls solveDependentCoordinates first otherwise.
    /// @throws std::runtime_error as solveDependentCoordinates, when it has to solve.
    void computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities, const Eigen::VectorXd& drivenS,
                         const Eigen::VectorXd& drivenSdot, const Eigen::VectorXd& qm, const Eigen::VectorXd& qmdot,
                         RopeData<Dim>& data) const;
    /// As above for ropes without Driven nodes.
    void computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities, const Eigen::VectorXd& qm,
                         const Eigen::VectorXd& qmdot, RopeData<Dim>& data) const;
    /// As above from all external coordinates x and their rates xdot (see
    /// solveDependentCoordinatesFromExternal). The groove arcs of wrapped nodes add their mass
    /// matrices, quadratic-velocity and gravity forces and energies (GrooveArc).
    /// @throws std::invalid_argument if x or xdot has the wrong size.
    void computeDynamicsFromExternal(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, const Eigen::VectorXd& qm,
                                     const Eigen::VectorXd& qmdot, RopeData<Dim>& data) const;

    /// S X for the effective mass S (RopeData::nodeMass) of the last computeDynamics on data and
    /// X (numExternalCoordinates() rows, any number of columns): one block solve of the rope's
    /// chain-structured equations, O(spans) per column, without forming S. For a coupling that
    /// needs S only along a few directions (the motions of the bodies that carry the nodes).
    /// Stored rope (setStoredRope) included.
    /// @throws std::invalid_argument if X has the wrong number of rows.
    void multiplyByNodeMass(const RopeData<Dim>& data, const Eigen::Ref<const Eigen::MatrixXd>& X, Eigen::MatrixXd& SX) const;

    /// Modal accelerations for given accelerations of the external coordinates x (node positions,
    /// then Driven material coordinates): qddot_m = Mbar_mm^-1 (Qbar_m - Mbar_mx xddot).
    void modalAccelerations(const RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                            Eigen::VectorXd& qmddot) const;

    /// As modalAccelerations for xddot = X c, X the matrix of the last multiplyByNodeMass on data and
    /// c its column weights (X.cols() entries): the solutions of that product's block solve are
    /// combined, no further solve (a coupling that formed S X along the bodies' motions and a0 finds
    /// xddot = a0 - J z as such a combination). Same result as modalAccelerations(data, X c) to
    /// round-off.
    /// @throws std::invalid_argument if c does not have as many entries as that X had columns.
    void modalAccelerationsFromLastProduct(const RopeData<Dim>& data, const Eigen::VectorXd& columnWeights,
                                           Eigen::VectorXd& qmddot) const;

    /// Mode-acceleration recovery for ropes with condensed (QuasiStatic) spans. The condensation
    /// makes U stationary, so the strain field it gives carries no share of the rope's own inertial
    /// load (rhoA times the acceleration of each material point). Given the accelerations of the
    /// coupled solve, this adds the quasi-static response to that load, to first order: with
    /// z_ddot = G w_ddot + c and the inertial generalized force f = M z_ddot - Q_v,
    ///     C_d delta_d = -[f_condensed / EA; 0; f_s / EA],
    /// the same linear system as the condensation's Newton step (the stationarity rows gain f).
    /// The result, data.inertialCorrection, feeds recoveredSpanCoordinates: strain and
    /// force queries then agree with the Dynamic model's slow response up to O((omega_slow /
    /// omega_axial)^2) instead of O(acceleration / g) (docs/verification.md, "Quasi-static against dynamic axial modes"). The dynamics
    /// themselves are not changed (they stay conservative). No-op without condensed spans.
    void recoverInertialStrain(RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                               const Eigen::VectorXd& qmddot) const;

    /// As spanCoordinates, with the mode-acceleration correction added to the condensed amplitudes
    /// and material coordinates when data holds one.
    void recoveredSpanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm, const RopeData<Dim>& data,
                                  Eigen::VectorXd& q) const;
    /// As recoveredSpanCoordinates from all external coordinates x.
    void recoveredSpanCoordinatesFromExternal(int j, const Eigen::VectorXd& x, const Eigen::VectorXd& qm,
                                              const RopeData<Dim>& data, Eigen::VectorXd& q) const;

    /// Axial force difference F_a - F_b at interior node k (1..N-1) [N]: the tension-equality
    /// residual at a Sliding node; at a Driven node, the force the rope's grip there carries; at a
    /// Slipping node, the friction force the sheave carries (P_{k-1} - P_k, i.e. -F_f).
    double constraintError(const RopeData<Dim>& data, int k) const;

private:
    friend struct RopeData<Dim>;
    /// Orders the dependent coordinates, the constraint rows and the modal state coordinates along
    /// the rope (span j, then node j + 1, ...) so that C_d and the dynamics' KKT matrix are band
    /// matrices, and finds their bandwidths (constructor).
    void buildChainOrder();
    /// Band LU of C_d from data's Jacobian entries into lu.
    /// @throws std::runtime_error if C_d is singular.
    void factorDependentJacobian(RopeData<Dim>& data, BandedLU& lu) const;
    /// out = C_d^-1 rows with lu (rows indexed as the constraint rows, out as the dependents d).
    void solveDependent(RopeData<Dim>& data, const BandedLU& lu, const Eigen::VectorXd& rows, Eigen::VectorXd& out) const;
    /// The dense Mbar, Qbar of the last computeDynamics (RopeData::reducedMass).
    void assembleReduced(RopeData<Dim>& data) const;
    void fillSpanCoordinates(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, RopeData<Dim>& data) const;
    /// Evaluates the constraint functions at data.spanQ (and data.spanQdot when withRates): values
    /// into data.newtonResidual, Jacobians into data.Cw / data.Cd, biases into data.bias.
    void evaluateConstraints(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, RopeData<Dim>& data,
                             bool withRates) const;
    bool positionsMatch(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, const RopeData<Dim>& data) const;
    /// [node positions or stations, drivenS] into data's scratch.
    const Eigen::VectorXd& packExternal(const NodeMatrix& nodes, const Eigen::VectorXd& drivenS, RopeData<Dim>& data,
                                        bool rates) const;
    /// The external coordinates from the NodeMatrix forms' arguments: packed as they are for a
    /// rope of point nodes; for a rope with wrapped nodes, mapped from the stations
    /// (WrapStationMap, rates optional) into data's scratch.
    const Eigen::VectorXd& stationsToExternal(const NodeMatrix& nodes, const NodeMatrix* nodeVelocities,
                                              const Eigen::VectorXd& drivenS, const Eigen::VectorXd* drivenSdot,
                                              RopeData<Dim>& data) const;
    /// Carries nodeMass, nodeForce and the modal reduction of the last computeDynamics over to the
    /// stations (S_Y = J^T S J, h_Y = J^T (h - S b); the modal accelerations' share of b).
    void dynamicsToStations(RopeData<Dim>& data) const;
    /// Swaps data's x-level nodeMass, nodeForce and modal coupling buffers back from the station
    /// forms' last reduction (no allocation: each buffer keeps its shape), before an evaluation
    /// forms them afresh.
    void externalBuffersBack(RopeData<Dim>& data) const;
    /// S X at the external coordinates (multiplyByNodeMass without the stations).
    void multiplyByExternalMass(const RopeData<Dim>& data, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                Eigen::MatrixXd& SX) const;
    /// The station map's positions at these stations (WrapStationMap::evaluatePositions: no J, b),
    /// its wrap angles continued from data's.
    WrapStationMapData stationMapAt(const NodeMatrix& nodes, const RopeData<Dim>& data) const;
    /// The external coordinates x of a rope with wrapped nodes at these node stations (the
    /// driven entries aside): the last solve's or dynamics' map when its stations are these, else
    /// a positions-only map in data's scratch.
    const Eigen::VectorXd& mappedPositions(const NodeMatrix& nodes, const RopeData<Dim>& data) const;
    /// First external coordinate of where span k - 1 ends at node k (arrival) and span k starts
    /// (departure): the node's position, or its tangent points.
    int arrivalOffset(int node) const {
        return nodeOffset_[node] + (arcIndex_[node] >= 0 ? wrappedArrivalOffset() : 0);
    }
    int departureOffset(int node) const {
        return nodeOffset_[node] + (arcIndex_[node] >= 0 ? wrappedDepartureOffset() : 0);
    }
    /// The arc length l_k [m] of node k in x (0 at a point node).
    double arcLengthAt(const Eigen::VectorXd& x, int node) const {
        return arcIndex_[node] >= 0 ? x[nodeOffset_[node] + wrappedArcLengthOffset()] : 0.0;
    }
    /// The coordinates of node k's groove arc (GrooveArc layout) from x and the node's s.
    template <class Coordinates>
    void arcCoordinates(int node, const Eigen::VectorXd& x, double s, Coordinates& a) const;
    /// Adds the mode-acceleration correction (recoverInertialStrain) to span j's coordinates q.
    void addInertialCorrection(int j, const RopeData<Dim>& data, Eigen::VectorXd& q) const;
    /// Element e's mass matrix storage in data (spans 0..N-1, then the arcs) and its size.
    const double* elementMass(const RopeData<Dim>& data, int e, int& n) const;
    int numDependent() const { return numCondensed_ + numSliding_ + numMultipliers_; }
    /// Writes the Fixed and Driven material coordinates into data.materialCoordinates (keeping the
    /// Sliding ones as a warm start when they stay ordered, else a chord-proportional guess).
    void setKnownMaterialCoordinates(const Eigen::VectorXd& x, RopeData<Dim>& data) const;

    // The spans, their condensation kernels (one per span when some span is condensed) and the
    // groove arcs: immutable, shared by copies and by withNodeLaw's models.
    std::shared_ptr<const detail::RopeElements<Dim>> elements_;
    int numSpans_ = 0;
    std::vector<std::vector<int>> spanToRope_;  // span-local coordinate -> index in z
    // The rope's elements: the spans, then the groove arcs (element N + i: arc i). elementToRope_[e]
    // maps element e's local coordinates into z (spanToRope_ for the spans); a span that starts at
    // a wrapped node also moves with that node's arc length (s1 = s_k + l_k): elementExtra_[e] is
    // the z index of l_k (the second target of its local s1), or -1.
    std::vector<std::vector<int>> elementToRope_;
    std::vector<int> elementExtra_, elementExtraLocal_;
    std::vector<int> arcIndex_, arcNode_;  // node -> arc index or -1; arc -> node
    std::vector<int> nodeOffset_;          // node -> first external coordinate of its block
    std::vector<Eigen::Vector3d> grooveAxes_;  // node -> its groove's axis (+z at point nodes and in 2D)
    std::vector<GroovePlacement> placements_;  // node -> NodeWrap::groove
    std::vector<int> axisStation_;             // node -> its axis station's column, or -1 (NodeWrap::turningAxis)
    int numAxisStations_ = 0;
    int numNodeCoordinates_ = 0;
    std::vector<int> modalOffset_;      // span -> first modal state coordinate in qm
    std::vector<int> condensedOffset_;  // span -> first condensed amplitude, or -1
    // Node k's law (NodeLaw.h: its registration from the MaterialNode tag, at construction and
    // withNodeLaw), and the layout it gives (layOutNodes).
    std::vector<detail::NodeLaw> laws_;
    std::vector<int> slidingIndex_, drivenIndex_;  // node -> index among its kind, or -1
    std::vector<int> slidingNode_;                 // sliding index -> node (Sliding and Slipping nodes)
    /// The coordinate layout of the node laws: the nodes' indices among the solved and the
    /// external material coordinates, the laws' columns, the elements' maps into z, the chain
    /// order and a new structureId_ (constructor, withNodeLaw).
    void layOutNodes();
    /// Node k's wrap angle alpha in x as a function of the external coordinates (detail::SlipAngle;
    /// with rates xdot also its rate and bias).
    detail::SlipAngle<Dim> slipAngle(int node, const Eigen::VectorXd& x, const Eigen::VectorXd* xdot) const;
    int numFixed_ = 0;
    struct Storage {
        int node = -1;
        double lengthAtZero = 0, slope = 0;  // l = lengthAtZero + slope s_node
    };
    std::vector<Storage> storage_;                 // rope stored at Driven end nodes (drums)
    std::vector<int> gripNodes_;                   // wrapped Driven end nodes that grip (setGrip)
    void applyGripRates(const Eigen::VectorXd& x, const Eigen::VectorXd& qm, RopeData<Dim>& data) const;
    void applyGripTerms(const Eigen::VectorXd& x, const Eigen::VectorXd& xdot, bool repeated, RopeData<Dim>& data) const;
    // Chain order (buildChainOrder): positions in the KKT system of the coordinates z (-1: external
    // or Fixed) and of the constraint rows; positions in C_d of its rows and of the dependents.
    std::vector<int> kktPos_, kktRowPos_, dependentRowPos_, dependentColPos_;
    int kktSize_ = 0, kktBand_ = 0, dependentKl_ = 0, dependentKu_ = 0;
    // External coordinate i -> the (element, local coordinate) pairs it is, up to 3 (-1: none): a
    // point's position is in two spans, a wrapped node's T_in and l in a span and its arc, a Driven
    // s at a wrapped node in two spans and the arc.
    std::vector<std::array<int, 6>> externalSpans_;
    // Per span: its local coordinates that are columns of the constraint Jacobian (z < nw + nd),
    // in order; and where each entry (a, b) of its mass matrix lands in the KKT band (M's storage
    // index a + n b, band offset; entries on external or Fixed coordinates left out), in the order
    // the assembly adds them.
    std::vector<std::vector<int>> jacobianSpanCoordinates_;
    struct BandTarget {
        int source = 0;
        std::ptrdiff_t offset = 0;
    };
    std::vector<std::vector<BandTarget>> kktMassTargets_;
    // The span mass entries multiplyByNodeMass applies, in its order: M(dest, from) times row `from`
    // (a row of X, or of the KKT solution) into row `dest` (of the KKT right-hand side, or of S X).
    struct RowTerm {
        int source = 0, dest = 0, from = 0;  // source: M's storage index
    };
    std::vector<RowTerm> massTimesExternalIntoKkt_;       // B[pb] -= M_yx(b, a) X[a]
    std::vector<RowTerm> massTimesExternalIntoExternal_;  // SX[b] += M_xx(b, a) X[a]
    std::vector<RowTerm> massTimesKktIntoExternal_;       // SX[a] += M_xy(a, b) Y[pb]
    std::vector<int> massTermSpanStart_;  // span j's terms of the three lists start at 3 j, 3 j + 1, 3 j + 2
    // Identifies this model's structure (a copy shares it): a RopeData's recorded Jacobian
    // structure and band offsets are replayed only for the structure they were recorded for.
    std::uint64_t structureId_ = 0;
    std::vector<char> stationaryColumn_;  // per external coordinate: its node never moves
    int numModal_ = 0, numCondensed_ = 0, numMultipliers_ = 0, numSliding_ = 0, numDriven_ = 0;
    double length_ = 0;
};

}  // namespace SimbodyReeving
