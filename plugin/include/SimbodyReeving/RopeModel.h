#pragma once
/// @file
/// A rope made of ALE spans in series over frictionless deviation sheaves (pure C++/Eigen): the
/// sheave tension-equality constraint (paper eq 32) by coordinate partitioning, and the rope's
/// dynamics reduced to its node accelerations (for an exact coupling with rigid bodies).

#include "SimbodyReeving/SpanModel.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <vector>

namespace SimbodyReeving {

/// The rope's evaluation workspace ("Data" of a RopeModel).
template <int Dim>
struct RopeData {
    // ---- position level
    Eigen::VectorXd materialCoordinates;  ///< s_0..s_N at the nodes [m] (s_0 = 0, s_N = L)
    int newtonIterations = 0;             ///< of the last tension-equality solve
    // ---- dynamics (filled by RopeModel::computeDynamics)
    Eigen::VectorXd materialRates;  ///< sdot_0..sdot_N [m/s]
    /// Effective mass of the rope at its nodes, S = Mbar_nn - Mbar_nm Mbar_mm^-1 Mbar_mn, and the
    /// matching force h: the force the nodes' supports must apply to the rope is f = S rddot - h.
    Eigen::MatrixXd nodeMass;
    Eigen::VectorXd nodeForce;
    double kineticEnergy = 0;    ///< T of all spans [J]
    double strainEnergy = 0;     ///< [J]
    double gravityEnergy = 0;    ///< [J]

    // internals
    std::vector<SpanData<Dim>> spans;
    std::vector<EndStrain<Dim>> firstEnd, secondEnd;
    std::vector<Eigen::VectorXd> spanQ, spanQdot;
    Eigen::VectorXd w;                    ///< independent velocities [rdot; qdot_m]
    Eigen::MatrixXd Mz, Mbar, Cs, Cw;
    Eigen::MatrixXd Gs;                   ///< sdot of the sheaves = Gs w
    Eigen::MatrixXd MwdGs, MddGs;         ///< products in G^T Mz G
    Eigen::VectorXd Qz, Qbar, Qd, bias;
    Eigen::VectorXd cd;                   ///< sddot of the sheaves at wdot = 0
    Eigen::PartialPivLU<Eigen::MatrixXd> constraintLu;  ///< of C_s
    Eigen::VectorXd newtonResidual, newtonStep;         ///< tension-equality Newton
    Eigen::MatrixXd newtonJacobian;
    Eigen::PartialPivLU<Eigen::MatrixXd> newtonLu;
    Eigen::LDLT<Eigen::MatrixXd> modalMass;
    Eigen::MatrixXd modalCoupling;  ///< Mbar_mm^-1 Mbar_mn
    Eigen::VectorXd modalFree;      ///< Mbar_mm^-1 Qbar_m
};

/// A rope of N spans between N + 1 nodes: node 0 is the start anchor, nodes 1..N-1 are deviation
/// sheaves (frictionless, point contact: both spans meet at the node and share its material
/// coordinate), node N is the end anchor. Node positions are given from outside each evaluation
/// (they are tied to bodies); the modal coordinates q_m of all spans are the rope's own
/// independent coordinates; the material coordinates s_1..s_{N-1} at the sheaves are dependent,
/// solved from the tension equality EA eps_{k-1}(s_k) = EA eps_k(s_k) (paper eq 32), with
/// s_0 = 0 and s_N = L (unstretched rope length) fixed.
///
/// Rope coordinates z = [r_0..r_N, q_m, s_0..s_N]; independent velocities w = [rdot_0..rdot_N, qdot_m];
/// zdot = G w, zddot = G wdot + c. The reduced equations Mbar wdot = Qbar with Mbar = G^T M G,
/// Qbar = G^T (Q - M c) keep T + U invariant (the constraint is holonomic and its reaction does no
/// work along admissible motions).
template <int Dim>
class RopeModel {
public:
    using Vec = Eigen::Matrix<double, Dim, 1>;
    using Mat = Eigen::Matrix<double, Dim, Dim>;
    using NodeMatrix = Eigen::Matrix<double, Dim, Eigen::Dynamic>;

    /// @param spans one SpanModel per span, in path order (all with the same RopeProperties).
    /// @param unstretchedLength L [m] > 0: material coordinate of the end anchor.
    /// @throws std::invalid_argument for no spans, spans with different rope properties, or L not
    ///         finite and > 0.
    RopeModel(std::vector<SpanModel<Dim>> spans, double unstretchedLength);

    int numSpans() const { return static_cast<int>(spans_.size()); }
    int numNodes() const { return numSpans() + 1; }
    int numModalCoordinates() const { return numModal_; }
    int modalOffset(int span) const { return modalOffset_[span]; }
    double unstretchedLength() const { return length_; }
    const SpanModel<Dim>& span(int j) const { return spans_[j]; }
    const RopeProperties& properties() const { return spans_.front().properties(); }

    /// Solves the tension-equality constraints for s_1..s_{N-1} by Newton's method (starting from
    /// data.materialCoordinates if it holds an admissible guess, else from a split proportional to
    /// the chord lengths) to |eps_a - eps_b| <= 1e-15, or until it stagnates at round-off below 1e-12.
    /// @throws std::runtime_error if Newton does not converge in 50 iterations or a span length
    ///         would become non-positive (the rope cannot carry the configuration).
    void solveMaterialCoordinates(const NodeMatrix& nodes, const Eigen::VectorXd& qm, RopeData<Dim>& data) const;

    /// The coordinates q of span j (SpanModel layout) from node positions, modal coordinates and s.
    void spanCoordinates(int j, const NodeMatrix& nodes, const Eigen::VectorXd& qm, const Eigen::VectorXd& s,
                         Eigen::VectorXd& q) const;

    /// Velocity and dynamics level: material rates, span evaluations, and the rope reduced to its
    /// nodes (nodeMass, nodeForce), energies. Reuses the position-level work of the last
    /// solveMaterialCoordinates on data when it was done at these positions (nodes and qm compared
    /// exactly), and calls solveMaterialCoordinates first otherwise.
    /// @throws std::runtime_error as solveMaterialCoordinates, when it has to solve.
    void computeDynamics(const NodeMatrix& nodes, const NodeMatrix& nodeVelocities, const Eigen::VectorXd& qm,
                         const Eigen::VectorXd& qmdot, RopeData<Dim>& data) const;

    /// Modal accelerations for given node accelerations: qddot_m = Mbar_mm^-1 (Qbar_m - Mbar_mn rddot).
    void modalAccelerations(const RopeData<Dim>& data, const Eigen::VectorXd& nodeAccelerations,
                            Eigen::VectorXd& qmddot) const;

    /// Axial force difference F_a - F_b at sheave node k (1..N-1) [N].
    double constraintError(const RopeData<Dim>& data, int k) const;

private:
    void endStrains(const NodeMatrix& nodes, const Eigen::VectorXd& qm, const Eigen::VectorXd& s,
                    RopeData<Dim>& data) const;

    std::vector<SpanModel<Dim>> spans_;
    std::vector<std::vector<int>> spanToRope_;  // span-local coordinate -> index in z
    std::vector<int> modalOffset_;
    int numModal_ = 0;
    double length_ = 0;
};

}  // namespace SimbodyReeving
