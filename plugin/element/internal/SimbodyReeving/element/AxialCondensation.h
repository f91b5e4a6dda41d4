#pragma once
/// @file
/// What the condensation of quasi-static modes (AxialDynamics::QuasiStatic axial,
/// TransverseDynamics::QuasiStatic transverse) needs from one span: the derivatives of its potential
/// energy with respect to its condensed modal amplitudes and its material length, and its end
/// strains, each with gradient and exact second time derivative (pure C++17/Eigen, no Simbody
/// include).

#include "SimbodyReeving/element/ChordFrame.h"
#include "SimbodyReeving/element/SpanModel.h"

#include <Eigen/Core>

namespace SimbodyReeving {

/// Per-evaluation results of AxialCondensation (fixed maximum sizes: evaluating never allocates).
/// Each quantity f (see AxialCondensation::Quantity) comes with its value, its gradient df/dq over
/// the span coordinates (SpanModel layout), its rate df/dt = df/dq qdot and its acceleration bias
/// qdot^T (d^2 f/dq^2) qdot (the second time derivative with qddot = 0).
template <int Dim>
struct AxialCondensationData {
    static constexpr int kMaxQuantities = 3 * Dim * kMaxModesPerDirection + 5;  ///< most quantities of any span
    /// One entry per quantity (fixed maximum size).
    using Values = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxQuantities, 1>;
    /// One row per quantity, one column per span coordinate (fixed maximum size).
    using Gradients = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxQuantities,
                                    SpanData<Dim>::kMaxCoordinates>;
    Values value;             ///< f
    Values rate;              ///< df/dt = df/dq qdot
    Values accelerationBias;  ///< qdot^T (d^2 f/dq^2) qdot
    Gradients gradient;       ///< df/dq
    ChordFrame<Dim> frame;  ///< scratch
};

/// Derivatives of one span's potential energy U = U_ax + U_bend + U_g (ElasticEnergyModel::Consistent)
/// and of its end strains, as needed by the quasi-static condensation of axial modes (RopeModel):
/// - Phi_i = dU/da_i, i = 1..n_c (a = the span's condensed amplitudes, SpanModel::numCondensedModes:
///   the axial amplitudes q_a if condensed, then the transverse ones q_t if condensed): zero when
///   the condensed modes are stationary at fixed material coordinates;
/// - dU/dl at fixed nodes and modes, l = s2 - s1 the span's material length: the energy change when
///   material enters the span over its second end (dU/ds2 = dU/dl = -dU/ds1);
/// - the Green strain at both ends, eps_E, and its partial derivatives d eps_E / da_i and
///   d eps_E / dl (the sheave tension equality's Jacobian on the dependent coordinates).
///
/// In the element frame the tangent is A_e^T r_xi = (lambda, tau) with lambda = |e| + sum S_i' a_i
/// along the chord and tau the transverse slopes, eps = (lambda^2 + |tau|^2) / (2 l^2) - 1/2, so
///     Phi_i   = (EA / l) int eps lambda S_i' dxi - rhoA l (g . i_e) m_i           (axial a_i),
///     Phi_dj  = (EA / l) int eps tau_d S_j' dxi + EI (j pi)^4 b_dj / (2 l^3)
///               - rhoA l (g . A_e col d) m_j                                      (transverse b_dj),
///     dU/dl   = EA int (-3/2 eps^2 - eps) dxi - 3 U_bend / l - rhoA g . (r_mean + A_e ubar),
///     d eps_E / da_i = lambda_E S_i'(xi_E) / l^2,   d eps_E / db_dj = tau_d,E S_j'(xi_E) / l^2,
///     d eps_E / dl = -(2 eps_E + 1) / l,
/// with m_i = int S_i dxi, ubar = int S q_m dxi and r_mean = (r1 + r2)/2. Under the span's axial
/// law P = EA f(eps), U_ax = EA l int F(eps) dxi (AxialLaw; linear: f = eps, F = eps^2/2) these read
///     Phi_i (axial part) = (EA / l) int f(eps) lambda S_i' dxi,
///     dU_ax/dl = EA int (F(eps) - f(eps) (2 eps + 1)) dxi,
/// so a tension-only rope's slack points drop out, and a span with SpanModel::slackRegularised()
/// adds the derivatives of
/// U_delta = delta EA / (4 l) sum_i (i pi)^2 a_i^2 (SpanOptions::quasiStaticSlackStiffness):
/// Phi_i += delta EA (i pi)^2 a_i / (2 l), dU/dl -= U_delta / l (and the same with delta_t,
/// SpanOptions::quasiStaticTransverseSlackStiffness, on condensed transverse amplitudes). The end strains stay the unclamped
/// eps (the sheave condition is strain equality). Everything depends on
/// the configuration through |e|, g . A_e (the frame's columns projected on gravity), g . r_mean,
/// l and the modal amplitudes; it is written once for a generic scalar and evaluated with
/// second-order Taylor numbers, which gives gradients (one directional pass per independent input)
/// and second time derivatives (one pass along qdot) exactly, without step sizes. Integrals use the
/// span's own strain rule (SpanModel::quadratureNodes / quadratureWeights of Integrand::Strain: the
/// exact midpoint rule by default), so they are the derivatives of the energy SpanModel::evaluate
/// computes.
template <int Dim>
class AxialCondensation {
public:
    using Data = AxialCondensationData<Dim>;  ///< the results of one evaluation

    /// @throws std::invalid_argument if the span uses ElasticEnergyModel::PaperLiteral.
    explicit AxialCondensation(const SpanModel<Dim>& span);

    int numAxialModes() const { return na_; }  ///< n_a of the span
    /// n_c: the span's condensed amplitudes (SpanModel::numCondensedModes), the first n_c modal coordinates.
    int numCondensedModes() const { return nc_; }
    int numQuantities() const { return 3 * nc_ + 5; }  ///< rows of Data: 3 n_c + 5

    /// Row indices of the quantities in Data.
    int phi(int i) const { return i; }                      ///< dU/da_i, i < n_c [N]
    int lengthDerivative() const { return nc_; }             ///< dU/dl [N]
    int endStrain(SpanEnd end) const { return nc_ + 1 + (end == SpanEnd::Second); }  ///< eps_E [-]
    int endStrainModeSlope(SpanEnd end, int i) const {       ///< d eps_E / da_i, i < n_c [1/m]
        return nc_ + 3 + (end == SpanEnd::Second ? nc_ : 0) + i;
    }
    int endStrainLengthSlope(SpanEnd end) const { return 3 * nc_ + 3 + (end == SpanEnd::Second); }  ///< [1/m]

    /// Values and gradients at q; with qdot (same size as q) also rates and acceleration biases
    /// (pass an empty qdot to skip them). q must be a configuration SpanModel::evaluate accepts.
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                  Data& data) const;
    /// Rates and acceleration biases only (values and gradients in data are left as they are).
    void evaluateRates(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                       Data& data) const;

private:
    /// A strain rule: weights w_k and mode slopes S_i'(xi_k), i = 1..max(n_a, n_t).
    struct StrainRule {
        Eigen::VectorXd weights;
        Eigen::MatrixXd slopes;
    };
    /// The span's Gauss-Legendre strain rule, or its exact midpoint rule where
    /// strainAboveTransitionEverywhere proves the span taut (SpanModel::strainTautEverywhere).
    const StrainRule& strainRule(double chordLength, double spanLength, const double* axialAmplitudes) const {
        return tautRule_.weights.size() > 0 &&
                       strainAboveTransitionEverywhere(law_, na_, chordLength, spanLength, axialAmplitudes)
                   ? tautRule_
                   : rule_;
    }
    template <class Scalar>
    void quantities(const StrainRule& rule, const Scalar& chordLength, const Scalar& spanLength,
                    const Scalar* gravityOnFrame, const Scalar& gravityOnMean, const Scalar* modal, Scalar* out) const;

    int na_ = 0, nt_ = 0, numModal_ = 0, numCoordinates_ = 0;
    // Condensed amplitudes: n_c in all, the axial ones (n_a or 0) and the transverse ones per direction (n_t or 0).
    int nc_ = 0, ncAxial_ = 0, ncTransverse_ = 0;
    double EA_ = 0, rhoA_ = 0, EI_ = 0;
    AxialLaw law_;  // the span's axial law (SpanModel::axialLaw)
    double slackStiffness_ = 0;  // delta EA / 2 when the span is slack-regularised, else 0 (axial)
    double transverseSlackStiffness_ = 0;  // delta_t EA / 2 likewise, on condensed transverse amplitudes
    Eigen::Matrix<double, Dim, 1> gravity_;
    Eigen::Matrix<double, Dim, Dim> referenceFrame_;
    StrainRule rule_;      // the span's strain rule (Gauss-Legendre)
    StrainRule tautRule_;  // its exact midpoint rule for taut states (empty: explicit quadraturePoints)
    Eigen::VectorXd sinMean_;     // m_i = int_0^1 S_i dxi
    Eigen::VectorXd bendFactor_;  // int_0^1 (S_i'')^2 dxi = (i pi)^4 / 2
    Eigen::VectorXd endSlope_[2];  // S_i'(0) = i pi, S_i'(1) = i pi (-1)^i
};

}  // namespace SimbodyReeving
