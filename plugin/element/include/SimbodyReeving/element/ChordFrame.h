#pragma once
/// @file
/// The span's element frame A_e(q_a) and its first and second derivatives with respect to the chord.

#include <Eigen/Core>

#include <array>

namespace SimbodyReeving {

/// The element frame A_e = [i_e j_e k_e] of a span (paper eq 5) as a function of the chord
/// e = r2 - r1, together with the derivatives the equations of motion need.
///
/// **Orthogonalisation.** i_e = e/|e| always.
/// - Planar (Dim = 2): j_e = z x i_e, the in-plane normal. Smooth and well conditioned for every
///   non-zero chord.
/// - Spatial (Dim = 3): A_e = R(i0 -> i_e) A0, where A0 = [i0 j0 k0] is a reference frame fixed for
///   the simulation (SpanModel builds it from the span's reference chord direction) and R is the
///   minimal rotation taking i0 to i_e about the axis i0 x i_e:
///       R = c I + [a]x + a a^T / (1 + c),   a = i0 x i_e,  c = i0 . i_e.
///   R is a rational function of i_e, smooth and equally well conditioned for any chord direction
///   except chord reversal (c = -1): a vertical span with a vertical reference is as well
///   conditioned as a horizontal one. If the reference lies in the scene plane and k0 is its
///   normal, the frame equals the planar one for in-plane chords.
///   The twist rate of the frame about the chord grows like tan(theta/2) with the angle theta between
///   chord and reference (bounded by 1 + tan(theta/2) per radian of chord rotation), so a span whose
///   chord swings far from its reference should be given a reference near its working direction.
///   Evaluation throws std::domain_error when 1 + c < kMinReferenceAlignment (chord turned more than
///   about 179 degrees away from its reference direction). A span whose chord turns without limit
///   (a slewing crane) therefore changes its reference before that: reReferenceTransverseModes
///   re-expresses its transverse modal coordinates and rates in a new reference exactly (the
///   ReevingSubsystem does it by an event, see ReevingSubsystem::setFrameChangeAlignment).
///
/// Derivatives (all with respect to the chord e):
/// - dA[m]   = dA/de_m
/// - Adot    = sum_m dA[m] edot_m          (time derivative for chord rate edot)
/// - dAdot[m]= d(Adot)/de_m at fixed edot  (= d^2A/de_m de . edot)
/// - Addot   = sum_m dAdot[m] edot_m       (second time derivative with zero chord acceleration)
template <int Dim>
struct ChordFrame {
    using Mat = Eigen::Matrix<double, Dim, Dim>;  ///< a Dim x Dim matrix
    Mat A;                                        ///< the element frame A_e(e), columns [i_e j_e (k_e)]
    std::array<Mat, Dim> dA;                      ///< dA/de_m
    Mat Adot;                                     ///< sum_m dA[m] edot_m
    std::array<Mat, Dim> dAdot;                   ///< d(Adot)/de_m at fixed edot
    Mat Addot;                                    ///< sum_m dAdot[m] edot_m
};

/// 1 + i0 . i_e below this value is treated as a degenerate (reversed) chord in 3D.
inline constexpr double kMinReferenceAlignment = 1e-4;

/// Computes the frame and its derivatives for chord e and chord rate edot. `reference` is A0
/// (ignored for Dim = 2). Uses exact forward-mode hyper-dual arithmetic (no finite differences).
/// @throws std::domain_error for a zero chord or (Dim = 3) a chord reversed against the reference.
template <int Dim>
void computeChordFrame(const Eigen::Matrix<double, Dim, 1>& e, const Eigen::Matrix<double, Dim, 1>& edot,
                       const Eigen::Matrix<double, Dim, Dim>& reference, ChordFrame<Dim>& out);

/// 1 + i0 . i_e for chord e and reference frame A0 (its first column i0) [-], in [0, 2]: 2 when the
/// chord points along the reference direction, 0 when it is reversed (ChordFrame's singularity).
/// @throws std::domain_error for a zero or non-finite chord.
double referenceAlignment(const Eigen::Vector3d& e, const Eigen::Matrix3d& reference);

/// Re-expresses the transverse modal coordinates of a spatial span in a new reference frame, so
/// that the span's configuration and its velocity field stay exactly the same.
///
/// Both transverse directions share the mode shapes S_i, so mode i contributes the displacement
/// w_i = [j_e k_e] (b_i, c_i) normal to the chord, and the element frames A_e, A_e' built from the
/// two references at the same chord differ by a rotation about the chord only: the new amplitudes
/// are (b_i', c_i') = [j_e' k_e']^T w_i, exactly. Rates: the velocity field of the span is
/// continuous if the velocity of w_i is: with VelocityModel::Complete that is
/// d/dt w_i = [jdot_e kdot_e] (b_i, c_i) + [j_e k_e] (bdot_i, cdot_i) (the frames' twist rates
/// about the chord differ, so the rates also change by the difference of twist times the
/// amplitudes); with VelocityModel::Simplified (which drops the frame-rotation term) it is
/// [j_e k_e] (bdot_i, cdot_i). The axial amplitudes (along i_e, the same in both frames) are
/// unchanged.
/// @param e, edot   chord r2 - r1 [m] and its rate [m/s] (non-zero chord).
/// @param oldReference, newReference orthonormal right-handed A0 and A0', neither reversed against
///        the chord (1 + i0 . i_e >= kMinReferenceAlignment).
/// @param completeVelocity the span's VelocityModel is Complete.
/// @param b, c      amplitudes along j_e and k_e [m], n_t each (updated in place).
/// @param bdot, cdot their rates [m/s] (updated in place).
/// @throws std::domain_error as computeChordFrame; std::invalid_argument if the sizes differ.
void reReferenceTransverseModes(const Eigen::Vector3d& e, const Eigen::Vector3d& edot,
                                const Eigen::Matrix3d& oldReference, const Eigen::Matrix3d& newReference,
                                bool completeVelocity, Eigen::Ref<Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> c,
                                Eigen::Ref<Eigen::VectorXd> bdot, Eigen::Ref<Eigen::VectorXd> cdot);

/// Builds a right-handed orthonormal reference frame [i0 j0 k0] whose first column is the unit
/// vector along `chordDirection`. If `normalHint` is non-zero and not parallel to the chord, k0 is
/// its component normal to i0 (so a planar scene keeps k0 = plane normal); otherwise j0 is the
/// world axis least aligned with i0, orthogonalised.
/// @throws std::invalid_argument if chordDirection is zero or not finite.
Eigen::Matrix3d makeReferenceFrame(const Eigen::Vector3d& chordDirection,
                                   const Eigen::Vector3d& normalHint = Eigen::Vector3d::Zero());

}  // namespace SimbodyReeving
