#pragma once
/// @file
/// One ALE wire-rope span element (Mohammadi & Escalona, "Dynamic simulation of reeving systems with
/// the extension of the modal approach in the axial direction", sections 2.1-2.2, eqs 1-22).
/// Pure C++17/Eigen: no Simbody include.

#include "SimbodyReeving/element/AxialLaw.h"
#include "SimbodyReeving/element/ChordFrame.h"
#include "SimbodyReeving/element/RopeProperties.h"

#include <Eigen/Core>

#include <cmath>

namespace SimbodyReeving {

/// Largest number of sine modes per direction (axial or transverse) a span may carry.
inline constexpr int kMaxModesPerDirection = 16;

/// The bound of SpanModel::strainTautEverywhere (without its rule check): true if a span with chord
/// length |e| [m], material length l [m] and axial amplitudes a_1..a_na [m] has its strain above
/// law.transition everywhere, or the law is linear.
inline bool strainAboveTransitionEverywhere(const AxialLaw& law, int numAxialModes, double chordLength,
                                            double spanLength, const double* axialAmplitudes) {
    if (!law.tensionOnly) return true;
    double lambdaMin = chordLength;
    for (int i = 0; i < numAxialModes; ++i) lambdaMin -= (i + 1) * 3.14159265358979323846 * std::abs(axialAmplitudes[i]);
    return lambdaMin > 0 && lambdaMin * lambdaMin > spanLength * spanLength * (1.0 + 2.0 * law.transition);
}

/// Which velocity field of the span defines its kinetic energy T = 1/2 int rhoA |rdot|^2 ds (eq 15).
///
/// The default is Complete: it is exact, for a somewhat higher cost per span evaluation than
/// Simplified (docs/performance.md), and Simplified misses the transport of the transverse motion
/// by rope flowing through a span (hoisting, a drum paying out, a belt) at a speed v that is not
/// small against the wave speed c = sqrt(P / rhoA). The reference is the axially moving string (a
/// taut span between fixed nodes, both material coordinates moving at v;
/// tests/element/test_axially_moving_string.cpp), whose frequencies are
/// omega_n = (n pi c / l)(1 - v^2 / c^2) (Wickert & Mote 1990); docs/verification.md compares both
/// models with it.
enum class VelocityModel {
    /// Paper eq 13: rdot = Ndot q_a + N qdot_a + A_e S qdot_m. Drops the frame-rotation term
    /// Adot_e S q_m and the mode-convection term A_e Sdot q_m of eq 12. Consequences:
    /// - rope flowing through a span leaves its transverse modes at the frequencies of a rope at
    ///   rest, n pi c / l at every speed: a factor 1 / (1 - v^2/c^2) above the moving string's
    ///   (+33 % at v/c = 0.5, +96 % at 0.7);
    /// - with axial modes, the force the rope puts on a swinging payload carries an inertial
    ///   model error (docs/verification.md, against the lumped-mass chain); Complete removes it at
    ///   the same step count.
    /// Use it to reproduce the paper's eq 13.
    Simplified,
    /// Default. Paper eq 12 with no term dropped: the exact material velocity of the discretised
    /// rope. On the axially moving string its linearised modal equations are the string's Galerkin
    /// system on the same sine modes (the Coriolis and centripetal transport terms are exact), so
    /// its frequencies converge to Wickert & Mote's as n_t grows, about like n_t^-3, the highest
    /// modes of a basis last (docs/verification.md, "The axially moving string").
    Complete,
};

/// Which strain energy the span uses (eq 19-20).
enum class ElasticEnergyModel {
    /// Default. U = 1/2 int EA eps^2 ds + 1/2 int EI kappa^2 ds with the Green strain
    /// eps = 1/2 (|dr/ds|^2 - 1) of the *full* position r (axial and transverse modes), and the
    /// bending curvature of the transverse displacement, kappa = |d^2 u_perp / ds^2| (linear in the
    /// modes). The taut-string energy of eq 19 is *not* added: expanding EA eps^2/2 about a
    /// tension P already contains P (du_t/ds)^2 / 2, so the small-vibration transverse frequencies
    /// of a taut span are the string's, n/(2L) sqrt(P/rhoA).
    Consistent,
    /// Eq 19-20 literally, to reproduce the paper: the Consistent energy plus
    /// U_str = 1/2 int P (du_perp/ds)^2 ds with P = EA eps (signed, so U stays differentiable), and
    /// kappa = |d^2 r/ds^2| including the axial modes. U_str counts the geometric stiffness twice:
    /// taut-string transverse frequencies come out sqrt(2) too high.
    PaperLiteral,
};

/// How a span's axial modal amplitudes q_a (the paper's axial part of q_m, eq 3 and 10) evolve.
///
/// The default is QuasiStatic: without axial waves, whose frequencies limit the step of explicit
/// integrators, it takes far fewer steps than Dynamic, while the bodies' motion and the slow part
/// of the axial force agree with Dynamic's; what it leaves out is the axial-wave part of the force
/// (docs/verification.md, "Quasi-static against dynamic axial modes"). Choose Dynamic for axial waves (snap loads
/// travelling along a long rope, axial resonance) or with ElasticEnergyModel::PaperLiteral. With
/// n_a = 0 (the default mode count) there are no axial amplitudes and the choice has no effect.
/// The transverse modes do not care: on the axially moving string (see VelocityModel) n_a = 2
/// gives the n_a = 0 transverse frequencies with either choice.
enum class AxialDynamics {
    /// The paper's model: the axial amplitudes are generalized coordinates with their own
    /// inertia, so the span carries axial waves. Their frequencies, i pi / l sqrt(EA / rhoA) for a
    /// span of length l (5 400 rad/s per mode number for the Table 1 rope on a 3 m span), limit
    /// the step of every explicit integrator.
    Dynamic,
    /// Default. The axial amplitudes are not states: at every configuration they take the values that make
    /// the rope's potential energy (axial strain + bending + gravity) stationary with respect to
    /// them, for the current nodes and transverse modes, on the manifold of the sheave
    /// tension-equality constraints (the material coordinates at the sheaves follow the amplitudes;
    /// see RopeModel). The condition is a holonomic constraint, solved by Newton's method together
    /// with the sheave coordinates (coordinate partitioning): the amplitudes' rates and
    /// accelerations follow exactly from the implicit function theorem, and the kinetic energy
    /// keeps the rope mass carried along by the quasi-static axial displacement field (the axial
    /// inertia of the slow motion). So:
    /// - T + U stays an exact invariant;
    /// - static equilibria equal the Dynamic model's;
    /// - the axial waves are gone, and with them the explicit-step limit: the integrator steps at
    ///   the pace of the slow motion.
    /// Force queries at Stage::Dynamics or later add the mode-acceleration correction, the strain
    /// of the rope's own inertial load (RopeModel::recoverInertialStrain); with it the slow part of
    /// the axial force agrees with the Dynamic model's to O((omega_slow / omega_axial)^2) of the
    /// inertial load; what is left out is the axial-wave part. The slow difference grows about
    /// linearly in time (a small shift of the payload's bounce frequency), so compare over the
    /// horizon you need (docs/verification.md, "Quasi-static against dynamic axial modes").
    /// Requires ElasticEnergyModel::Consistent on every span of the rope that has axial modes (the
    /// SpanModel constructor throws otherwise: set Dynamic for PaperLiteral). With a tension-only rope
    /// (RopeProperties::tensionOnly) the condensation uses the clamped law and a slack span's
    /// amplitudes are held by SpanOptions::quasiStaticSlackStiffness (a fully slack span has no
    /// axial stiffness of its own).
    QuasiStatic,
};

/// How a span's transverse modal amplitudes q_t (the transverse part of q_m, eq 3) evolve.
///
/// Dynamic (the default, the paper's) keeps them as states: the span vibrates as a string, and
/// its first transverse frequency (about pi / l sqrt(P / rhoA): 21 Hz for the Table 1 pendulum's
/// 3 m span at 9.8 kN) limits the step of explicit integrators. QuasiStatic condenses them exactly
/// as AxialDynamics::QuasiStatic condenses the axial amplitudes: at every configuration they take
/// the values that make the span's potential energy (axial Green strain, which holds the taut-string
/// stiffness P (du_t/ds)^2 / 2, + bending + gravity) stationary, dU/dq_t = 0, together with the
/// condensed axial amplitudes and the sheave constraints (RopeModel). The span then keeps its static
/// sag under its own weight at its current tension, and the kinetic energy keeps the rope mass
/// carried by that sag as the span moves, but it has no string vibration. T + U stays an exact
/// invariant. Use it when the transverse vibration of a span is not of interest and its frequency is
/// well above the motion of the bodies (the rope's sag is quasi-static; docs/performance.md,
/// "Quasi-static transverse modes"). A span that is slack and straight has no transverse stiffness from its
/// tension; a tension-only rope's condensed transverse amplitudes are then held by
/// SpanOptions::quasiStaticTransverseSlackStiffness.
/// Requires ElasticEnergyModel::Consistent, AxialDynamics::QuasiStatic when n_a > 0 (transverse
/// modes condensed under dynamic axial modes would be the stiffer ones left as states) and
/// transverseDampingRatio = 0 (nothing vibrates to damp); the SpanModel constructor throws
/// otherwise. No effect when n_t = 0.
enum class TransverseDynamics {
    Dynamic,      ///< Default: the transverse amplitudes are states (string vibration).
    QuasiStatic,  ///< Condensed: dU/dq_t = 0 at every configuration (static sag, no vibration).
};

/// Which integrals of a span a quadrature rule serves.
enum class Integrand {
    Kinetic,  ///< M, Q_v and T
    Strain,   ///< axial (and PaperLiteral string) strain energy and its gradient
};

/// Mode counts and numerical options of one span.
struct SpanOptions {
    /// n_a: number of axial sine modes, 0..16.
    int axialModes = 0;
    /// n_t: number of transverse sine modes per transverse direction, 0..16 (one direction in a
    /// planar span, two in a spatial one).
    int transverseModes = 1;
    /// Complete (default: exact, a little more costly) or Simplified (the paper's eq 13: misses
    /// the transport of transverse motion by rope flowing through the span; see VelocityModel).
    VelocityModel velocityModel = VelocityModel::Complete;
    /// Axial amplitudes condensed (QuasiStatic, default: no axial waves, far fewer steps) or states (Dynamic, the paper's; needed for axial waves and
    /// for ElasticEnergyModel::PaperLiteral with n_a > 0); no effect when n_a = 0. See AxialDynamics.
    AxialDynamics axialDynamics = AxialDynamics::QuasiStatic;
    ElasticEnergyModel elasticModel = ElasticEnergyModel::Consistent;  ///< see ElasticEnergyModel
    /// Transverse amplitudes as states (Dynamic, default) or condensed (QuasiStatic: the span's
    /// static sag without its string vibration). See TransverseDynamics.
    TransverseDynamics transverseDynamics = TransverseDynamics::Dynamic;
    /// delta [-], finite, in [1e-9, 1]; used only by a tension-only rope's (RopeProperties::tensionOnly)
    /// spans with AxialDynamics::QuasiStatic axial modes. A fully slack span has no axial
    /// stiffness, so the quasi-static condition dU/dq_a = 0 alone would leave its axial amplitudes
    /// undetermined (or, with gravity along the span, pile all its material at the lower end).
    /// Such spans therefore carry the extra potential
    ///     U_delta = 1/2 delta EA int (du_a/ds)^2 ds = delta EA / (4 l) sum_i (i pi)^2 q_a,i^2,
    /// u_a the axial modal displacement, l the span's material length: a weak resistance to
    /// redistributing material along the span. It acts on the axial amplitudes (and, through l,
    /// on the material coordinates), not on the chord, so it transmits no force between the
    /// span's ends: the axial force stays EA max(eps, 0) >= 0. In a taut span it stiffens the
    /// axial modes by the factor 1 + delta, so the amplitudes (the strain's variation along the
    /// span from its own weight and inertia) come out smaller by delta / (1 + delta) relative;
    /// in a fully slack span it keeps the material near its uniform distribution (the default,
    /// 1e-3: the Table 1 rope's 3 m span hanging slack shifts its material by about 0.5 mm). It is
    /// part of the potential energy (SpanData::slackRegularisationEnergy), so T + U stays an
    /// invariant.
    double quasiStaticSlackStiffness = 1e-3;
    /// eps_s [-], finite, in [1e-12, 1e-3]; used by the same spans as quasiStaticSlackStiffness:
    /// their tension-only law is rounded over strains in (0, eps_s) by a quintic (see AxialLaw)
    /// so that the force is C2 in the strain rather than only C0. The quasi-static amplitudes solve
    /// dU/dq_a = 0; their rates (the Hessian of U) enter the rope's kinetic energy and their
    /// acceleration bias (third derivatives of U) the equations of motion. With the plain clamp
    /// max(eps, 0) the rates jump whenever a strain quadrature point goes slack or taut, and each
    /// jump changes T at fixed velocities; with a C1 rounding the accelerations still
    /// jump, and an adaptive step shrinks towards round-off at each jump. With the quintic T + U is an invariant
    /// again, provided the integrator resolves the rounding: a step that carries a span's strain
    /// across (0, eps_s) at once can fool its error estimate, the more so the smaller eps_s
    /// (docs/stability.md, "Slack and snap: the rounding of the tension-only law"). Outside (0, eps_s) the law is exact; inside,
    /// 0 <= P <= EA eps and P falls short of EA eps by at most 0.1975 EA eps_s (33 N for the
    /// Table 1 rope, EA = 16.5 MN, at the default 1e-5: the force of a rope carrying less than
    /// EA eps_s = 165 N is rounded down by up to a fifth of that).
    double quasiStaticSlackTransitionStrain = 1e-5;
    /// delta_t [-], finite, in [1e-12, 1e-3]; used only by a tension-only rope's spans with
    /// TransverseDynamics::QuasiStatic. A slack, straight span has no transverse stiffness (its
    /// tension is zero and EI may be), so dU/dq_t = 0 would not determine its transverse
    /// amplitudes. Such spans carry
    ///     U_delta,t = 1/2 delta_t EA int |du_t/ds|^2 ds = delta_t EA / (4 l) sum_i (i pi)^2 |q_t,i|^2,
    /// the energy of a string at tension delta_t EA (1.65 N for the Table 1 rope at the default
    /// 1e-7), part of SpanData::slackRegularisationEnergy. In a taut span at tension P it reduces the
    /// static sag by the factor 1 / (1 + delta_t EA / P) (1.7e-4 relative at the Table 1 pendulum's
    /// 9.8 kN); a slack span sags until its Green strain tightens it.
    double quasiStaticTransverseSlackStiffness = 1e-7;
    /// 0 (default) selects the automatic rule: Gauss-Legendre with
    /// SpanModel::automaticQuadraturePoints points for the kinetic and for the strain integrals
    /// (exact to round-off). Otherwise 1..200: that many Gauss-Legendre points for both.
    int quadraturePoints = 0;
    /// zeta_t [-], finite, in [0, 1]; default 0: modal damping of the transverse modes. Mode i of
    /// each transverse direction feels
    ///     Q_i = -2 zeta_t omega_i m_i qdot_i,   m_i = rhoA l / 2,
    ///     omega_i^2 = (i pi / l)^2 P / rhoA + (i pi / l)^4 EI / rhoA,
    /// the span's taut-string (and bending) frequency at its mean axial force P = EA mean(eps) >= 0
    /// over the strain points, evaluated at each state: a free transverse vibration decays with
    /// damping ratio zeta_t. Its power -sum Q_i qdot_i >= 0 is part of SpanData::dampingPower.
    double transverseDampingRatio = 0;
};

/// Generalized forces, mass matrix and energies of one span at one state: the per-evaluation
/// workspace ("Data") of a SpanModel. Fixed maximum sizes: evaluating never allocates.
template <int Dim>
struct SpanData {
    static constexpr int kMaxModal = Dim * kMaxModesPerDirection;    ///< most modal coordinates of a span
    static constexpr int kMaxCoordinates = 2 * Dim + kMaxModal + 2;  ///< most coordinates of a span
    /// A vector over the span's coordinates (fixed maximum size).
    using CoordVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCoordinates, 1>;
    /// A matrix over the span's coordinates (fixed maximum size).
    using CoordMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxCoordinates>;
    /// Dim rows, one column per span coordinate (fixed maximum size).
    using Jacobian = Eigen::Matrix<double, Dim, Eigen::Dynamic, 0, Dim, kMaxCoordinates>;

    /// M(q) = int rhoA B^T B ds with rdot = B(q) qdot; symmetric positive definite [kg, kg m, ...].
    CoordMatrix massMatrix;
    /// Q_v = -Mdot qdot + dT/dq (eq 17), so that M qddot = Q_v + Q_elastic + Q_gravity + Q_other.
    CoordVector velocityForces;
    /// Q_elas = -dU/dq (eq 22) [N for positions and material coordinates, N m for modes].
    CoordVector elasticForces;
    /// Q_g = -dU_g/dq with U_g = -int rhoA g . r ds.
    CoordVector gravityForces;
    /// Q_d = -dD/dqdot of the Kelvin-Voigt damping (RopeProperties::axialRetardationTime; zero
    /// without it) [N, N m]: not part of Q_elastic, so energies stay conservative-only.
    CoordVector dampingForces;
    /// Power dissipated by the damping, -Q_d . qdot = 2 D >= 0 [W].
    double dampingPower = 0;

    double kineticEnergy = 0;   ///< T [J]
    double axialEnergy = 0;     ///< 1/2 int EA eps^2 ds [J]
    double bendingEnergy = 0;   ///< 1/2 int EI kappa^2 ds [J] (0 when EI = 0)
    double stringEnergy = 0;    ///< taut-string energy [J], PaperLiteral only
    double gravityEnergy = 0;   ///< U_g = -int rhoA g . r ds [J]
    /// U_delta [J] of SpanOptions::quasiStaticSlackStiffness (tension-only rope, QuasiStatic axial
    /// modes; 0 otherwise).
    double slackRegularisationEnergy = 0;

    /// Elastic energy [J]: axial + bending + string + U_delta.
    double strainEnergy() const { return axialEnergy + bendingEnergy + stringEnergy + slackRegularisationEnergy; }
    double potentialEnergy() const { return strainEnergy() + gravityEnergy; }  ///< strain + gravity [J]

    ChordFrame<Dim> frame;  ///< A_e and its derivatives at this state
    /// B(q) of rdot = B qdot at one point: not written by evaluate() (M is assembled in closed form
    /// and Q_v without forming B).
    Jacobian velocityJacobian;
};

/// The two ends of a span: node 1 at s1 (xi = 0) and node 2 at s2 (xi = 1).
enum class SpanEnd { First, Second };

/// Green strain at a span end with its first and second time derivatives, for constraints on the
/// axial force there (the sheave tension equality).
template <int Dim>
struct EndStrain {
    double strain = 0;          ///< eps at the end [-]
    double rate = 0;            ///< d eps/dt = gradient . qdot [1/s]
    double accelerationBias = 0;  ///< d^2 eps/dt^2 with qddot = 0, i.e. qdot^T (d^2 eps/dq^2) qdot [1/s^2]
    typename SpanData<Dim>::CoordVector gradient;  ///< d eps/dq [1/m]
};

/// One ALE wire-rope span: the fixed part of the element ("Model": parameters, mode layout,
/// quadrature tables). Evaluation results go into a SpanData.
///
/// **Coordinates** (eq 1-3), in this order, n = 2 Dim + n_a + (Dim-1) n_t + 2 of them:
/// - q_a = [r1; r2]: absolute positions of the end nodes [m] (Dim each);
/// - q_m = [a_1..a_na, b_1..b_nt, (c_1..c_nt)]: modal amplitudes [m] of the axial displacement
///   (along i_e), and of the transverse displacements along j_e (and k_e in 3D);
/// - q_s = [s1, s2]: material (unstretched arc-length) coordinates of the end nodes [m], s2 > s1.
///
/// **Kinematics** (eq 4-11). With xi = (s - s1)/(s2 - s1) in [0, 1] and l = s2 - s1,
///     r(s, q) = (1 - xi) r1 + xi r2 + A_e(r2 - r1) S(xi) q_m,
/// N = [(1-xi) I, xi I] the linear shape functions (eq 6-8), A_e the element frame (ChordFrame),
/// and S the sine modes S_i(xi) = sin(i pi xi) (eq 11) arranged as in eq 10.
///
/// **Dynamics** (eq 14-18). T = 1/2 int_0^1 rhoA l |v|^2 dxi with the material velocity
/// v = B(xi, q) qdot of the chosen VelocityModel (the s-dependence of xi through s1, s2 included,
/// so the span may gain or lose material over its ends). M and Q_v are derived from this same T,
/// with the same quadrature (M assembled in closed form from the kinetic rule's moments: the
/// quadrature sum rearranged), so T + U is an exact invariant of M qddot = Q_v + Q_elastic +
/// Q_gravity for either velocity model.
///
/// **Elastic energy** (eq 19-22): see ElasticEnergyModel. Axial and string energies are integrated
/// by Gauss-Legendre (automaticQuadraturePoints, or the count SpanOptions::quadraturePoints asks
/// for); the bending energy (quadratic in q_m with constant coefficients)
/// and the gravity energy are integrated in closed form.
///
/// **Axial force** (eq 21): P(s) = EA eps(s), eps = 1/2 (|dr/ds|^2 - 1).
///
/// @tparam Dim 2 for a planar span (x-y plane, one transverse direction: no out-of-plane work at
///             all), 3 for a spatial span.
template <int Dim>
class SpanModel {
public:
    using Vec = Eigen::Matrix<double, Dim, 1>;    ///< a point or direction
    using Mat = Eigen::Matrix<double, Dim, Dim>;  ///< a frame or rotation
    using Data = SpanData<Dim>;                   ///< the results of one evaluation

    /// @param properties rope properties (see RopeProperties for units and ranges).
    /// @param options    mode counts and numerical options.
    /// @param gravity    gravitational acceleration [m/s^2], finite (may be zero).
    /// @param referenceFrame (Dim = 3 only) orthonormal right-handed [i0 j0 k0], typically
    ///        makeReferenceFrame(initial chord, plane normal); ignored for Dim = 2.
    /// @throws std::invalid_argument for rhoA or EA not finite and > 0, EI not finite and >= 0,
    ///         mode counts outside 0..16, quadraturePoints outside 0..200, non-finite gravity, a
    ///         reference frame that is not orthonormal and right-handed, or AxialDynamics::QuasiStatic
    ///         (the default) with n_a > 0 and ElasticEnergyModel::PaperLiteral (its string energy
    ///         makes the axial stiffness depend on the transverse slope twice; the condensation is
    ///         defined for Consistent only),
    ///         RopeProperties::tensionOnly with PaperLiteral, quasiStaticSlackStiffness outside
    ///         [1e-9, 1] or quasiStaticSlackTransitionStrain outside [1e-12, 1e-3] (or not finite),
    ///         TransverseDynamics::QuasiStatic (with n_t > 0) with PaperLiteral, with
    ///         AxialDynamics::Dynamic and n_a > 0, or with transverseDampingRatio > 0, and
    ///         quasiStaticTransverseSlackStiffness outside [1e-12, 1e-3] (or not finite).
    SpanModel(const RopeProperties& properties, const SpanOptions& options, const Vec& gravity,
              const Mat& referenceFrame = Mat::Identity());

    int numCoordinates() const { return 2 * Dim + numModal_ + 2; }  ///< r1, r2, modal, s1, s2
    /// true if the span carries U_delta (SpanOptions::quasiStaticSlackStiffness on condensed axial
    /// amplitudes, quasiStaticTransverseSlackStiffness on condensed transverse ones): a tension-only
    /// rope with condensed modes (numCondensedModes() > 0).
    bool slackRegularised() const { return properties_.tensionOnly && numCondensedModes() > 0; }
    /// Axial amplitudes condensed: AxialDynamics::QuasiStatic with n_a > 0.
    bool condensesAxialModes() const {
        return options_.axialDynamics == AxialDynamics::QuasiStatic && options_.axialModes > 0;
    }
    /// Transverse amplitudes condensed: TransverseDynamics::QuasiStatic with n_t > 0.
    bool condensesTransverseModes() const {
        return options_.transverseDynamics == TransverseDynamics::QuasiStatic && options_.transverseModes > 0;
    }
    /// Number of condensed modal coordinates (dependent, not states): n_a if condensesAxialModes(),
    /// plus (Dim - 1) n_t if condensesTransverseModes(). They are the first numCondensedModes()
    /// modal coordinates of the span (axial, then transverse direction by direction).
    int numCondensedModes() const {
        return (condensesAxialModes() ? options_.axialModes : 0) +
               (condensesTransverseModes() ? (Dim - 1) * options_.transverseModes : 0);
    }
    /// The span's axial law: linear, tension-only, or (slackRegularised()) tension-only rounded
    /// over (0, quasiStaticSlackTransitionStrain).
    const AxialLaw& axialLaw() const { return law_; }
    /// (i pi)^2 of axial mode i = 0..n_a-1 (mode number i + 1).
    static double axialModeWavenumberSquared(int i) {
        const double k = (i + 1) * 3.14159265358979323846;
        return k * k;
    }
    int numModalCoordinates() const { return numModal_; }  ///< n_a + (Dim - 1) n_t
    int axialModes() const { return options_.axialModes; }  ///< n_a
    int transverseModes() const { return options_.transverseModes; }  ///< n_t per transverse direction
    /// Quadrature points used for the kinetic (M, Q_v, T) or strain (U_ax, U_str) integrals.
    int quadraturePoints(Integrand integrand) const {
        return static_cast<int>((integrand == Integrand::Kinetic ? kineticTable_ : strainTable_).xi.size());
    }
    /// Nodes xi_k in (0, 1) and weights w_k of the rule used for the kinetic or strain integrals
    /// (int_0^1 f dxi ~ sum_k w_k f(xi_k)); AxialCondensation integrates with the strain rule.
    const Eigen::VectorXd& quadratureNodes(Integrand integrand) const {
        return (integrand == Integrand::Kinetic ? kineticTable_ : strainTable_).xi;
    }
    /// The weights w_k of that rule (they sum to 1).
    const Eigen::VectorXd& quadratureWeights(Integrand integrand) const {
        return (integrand == Integrand::Kinetic ? kineticTable_ : strainTable_).w;
    }
    const RopeProperties& properties() const { return properties_; }  ///< as constructed
    const SpanOptions& options() const { return options_; }            ///< as constructed
    const Vec& gravity() const { return gravity_; }                    ///< g [m/s^2]
    const Mat& referenceFrame() const { return referenceFrame_; }      ///< A0 (Dim = 3; identity for Dim = 2)

    /// Index of r1 (first of Dim), r2, of axial mode i (0-based), of transverse mode i in direction
    /// dir (0: j_e, 1: k_e), and of s1, s2 in the coordinate vector.
    static constexpr int r1Index() { return 0; }
    static constexpr int r2Index() { return Dim; }                 ///< index of r2 (first of Dim)
    int axialModeIndex(int i) const { return 2 * Dim + i; }          ///< index of axial mode i (0-based)
    /// Index of transverse mode i (0-based) in direction dir (0: j_e, 1: k_e).
    int transverseModeIndex(int dir, int i) const {
        return 2 * Dim + options_.axialModes + dir * options_.transverseModes + i;
    }
    int s1Index() const { return 2 * Dim + numModal_; }      ///< index of s1
    int s2Index() const { return 2 * Dim + numModal_ + 1; }  ///< index of s2

    /// The Gauss-Legendre count that integrates the span's integrands to round-off (tested against
    /// 150 points): with n_max = max(n_a, n_t) and k the integrand's largest number of half-waves
    /// on [0, 1] (k = 2 n_max for kinetic, 4 n_max for strain integrals), N = ceil(1.15 k) + 12;
    /// without modes N = 2 (kinetic) and 1 (strain). The automatic rule (SpanOptions::quadraturePoints
    /// = 0) uses it for both. Where strainTautEverywhere proves a span taut, the strain integrals are
    /// evaluated by the exact midpoint rule of automaticStrainPoints instead (7 points instead of 26
    /// at n_max = 3, 3 instead of 17 at n_max = 1): the same integrals to round-off, so the model is
    /// this Gauss-Legendre rule's either way (tautStrainRule).
    static int automaticQuadraturePoints(int axialModes, int transverseModes, Integrand integrand);

    /// The span's fast strain rule for taut states: true if the automatic rule is in use
    /// (SpanOptions::quadraturePoints = 0), and then tautStrainNodes / tautStrainWeights are the
    /// midpoint rule of automaticStrainPoints.
    bool tautStrainRule() const { return tautStrainTable_.xi.size() > 0; }
    const Eigen::VectorXd& tautStrainNodes() const { return tautStrainTable_.xi; }   ///< xi_j of the taut rule
    const Eigen::VectorXd& tautStrainWeights() const { return tautStrainTable_.w; }  ///< w_j of the taut rule
    /// True if the strain of the span at these coordinates is above the axial law's transition
    /// strain at every point (or the law is linear), by the bound
    ///     lambda(xi) = |e| + sum_i S_i'(xi) a_i >= |e| - sum_i i pi |a_i| = lambda_min,
    ///     eps(xi) >= lambda_min^2 / (2 l^2) - 1/2  (the transverse slopes only add to eps),
    /// i.e. lambda_min > 0 and lambda_min^2 > l^2 (1 + 2 eps_s). Then every strain integrand is a
    /// cosine series with at most 4 n_max half-waves, which both the Gauss-Legendre rule and the
    /// midpoint rule of automaticStrainPoints integrate to round-off, and SpanModel::evaluate and
    /// AxialCondensation use the cheaper one. False also without tautStrainRule().
    /// @param chordLength |e| = |r2 - r1| [m].
    /// @param spanLength l = s2 - s1 [m].
    /// @param axialAmplitudes a_i [m], n_a of them.
    bool strainTautEverywhere(double chordLength, double spanLength, const double* axialAmplitudes) const {
        return tautStrainRule() &&
               strainAboveTransitionEverywhere(law_, options_.axialModes, chordLength, spanLength, axialAmplitudes);
    }

    /// Points of the exact strain rule, the N-point midpoint rule xi_j = (j + 1/2) / N, w = 1/N
    /// (makeMidpointRule), N = 2 n_max + 1 with n_max = max(n_a, n_t) (1 without modes).
    ///
    /// Exact for a taut span: in the element frame the tangent r_xi has the components
    /// lambda = |e| + sum_i S_i' a_i and tau = sum_i S_i' b_i, S_i' = i pi cos(i pi xi), so the
    /// strain eps = (lambda^2 + |tau|^2) / (2 l^2) - 1/2 and its gradient are cosine series with
    /// at most 2 n_max half-waves, and every strain integrand (eps^2, eps d eps/dq and, for the
    /// linear law or a strain above the tension-only transition, F(eps) and f(eps) d eps/dq; the
    /// PaperLiteral eps |u_perp'|^2 and its gradient; AxialCondensation's Phi_i, dU/dl and their
    /// derivatives) is a cosine series with at most 4 n_max < 2N half-waves, which the midpoint
    /// rule integrates exactly.
    ///
    /// Where a tension-only span has slack points (strain below the transition strain somewhere),
    /// the clamped integrand is not a cosine series and neither rule is exact: the span then keeps
    /// its Gauss-Legendre rule (strainTautEverywhere is false), whose many points resolve the slack
    /// region better.
    /// The switch between the rules is continuous to round-off: where the bound holds, both rules
    /// give the same integrals. maxStrain() looks at the Gauss-Legendre points.
    static int automaticStrainPoints(int axialModes, int transverseModes);

    /// Evaluates M, Q_v, Q_elastic, Q_gravity and all energies at (q, qdot).
    /// @throws std::invalid_argument if q or qdot has the wrong size or a non-finite entry, if
    ///         s2 <= s1 (span length l = s2 - s1 must be > 0), or if the end nodes coincide.
    /// @throws std::domain_error (Dim = 3) if the chord is reversed against the reference frame, or
    ///         if the result overflows (non-finite) although the inputs are finite.
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                  Data& data) const;

    /// Position r(s) of material point s in [s1, s2] [m] (points within 1e-12 l outside an end,
    /// round-off of s1 + (s2 - s1) k / n, are taken at that end).
    /// @throws std::invalid_argument for bad q (as evaluate) or s outside [s1, s2].
    Vec position(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const;
    /// Green strain eps(s) = 1/2 (|dr/ds|^2 - 1) at material point s in [s1, s2] [-].
    /// @throws std::invalid_argument for bad q (as evaluate) or s outside [s1, s2].
    double strain(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const;
    /// Axial force P(s) = EA eps(s) [N] (eq 21); under RopeProperties::tensionOnly EA max(eps(s), 0),
    /// rounded near 0 for slackRegularised() spans (axialLaw()).
    /// @throws std::invalid_argument for bad q (as evaluate) or s outside [s1, s2].
    double axialForce(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const {
        return law_.force(strain(q, s));
    }
    /// Largest Green strain over the span [-]: the maximum over both ends and the strain quadrature
    /// points (the points where the strain energy is evaluated). Under RopeProperties::tensionOnly
    /// the span is slack (carries no axial force anywhere the energy sees) when this is <= 0.
    /// @throws std::invalid_argument for bad q (as evaluate).
    double maxStrain(const Eigen::Ref<const Eigen::VectorXd>& q) const;
    /// Physical tension T(s) = EA eps |dr/ds| [N]: the magnitude of the internal force vector
    /// EA eps dr/ds that balances the loads (a hanging rope has T = weight below). It exceeds the
    /// paper's axial force P = EA eps by the stretch factor |dr/ds| = sqrt(1 + 2 eps).
    /// @throws std::invalid_argument for bad q (as evaluate) or s outside [s1, s2].
    double tension(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const {
        const double eps = strain(q, s);
        return law_.force(eps) * std::sqrt(std::max(1.0 + 2.0 * eps, 0.0));
    }

    /// Strain at a span end, its gradient d eps/dq, its rate and its acceleration bias (exact,
    /// analytic). Does not allocate.
    /// @throws as evaluate().
    void endStrain(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                   SpanEnd end, EndStrain<Dim>& out) const;

private:
    void checkState(const Eigen::Ref<const Eigen::VectorXd>& q, const char* name) const;
    double checkMaterialPoint(const Eigen::Ref<const Eigen::VectorXd>& q, double s) const;

    RopeProperties properties_;
    AxialLaw law_;
    SpanOptions options_;
    Vec gravity_;
    Mat referenceFrame_;
    int numModal_ = 0;
    int maxMode_ = 0;  // max(n_a, n_t)
    // Quadrature table: xi_k, w_k and, per point, S_i(xi_k) and dS_i/dxi (xi_k), i = 1..maxMode_.
    struct QuadratureTable {
        Eigen::VectorXd xi, w;
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> sin, dsin;  // row k: point k
    };
    QuadratureTable kineticTable_, strainTable_;
    QuadratureTable tautStrainTable_;  // midpoint rule of automaticStrainPoints (empty: explicit quadraturePoints)
    using ModeVectors = Eigen::Matrix<double, Dim, kMaxModesPerDirection>;
    /// Adds the Kelvin-Voigt damping forces and power to d (evaluate, with U, Ud the modal
    /// amplitudes and rates per mode number; d.frame already computed).
    /// Adds the transverse modal damping (SpanOptions::transverseDampingRatio) to d.
    void addTransverseDamping(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                              const ModeVectors& U, Data& d) const;
    void addAxialDamping(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qdot,
                         const ModeVectors& U, const ModeVectors& Ud, Data& d) const;
    // Moments of the kinetic rule (sum_k w_k ... over kineticTable_), i, j = 1..maxMode_: the mass
    // matrix is assembled from them in closed form (SpanModel.cpp, "mass matrix"), which is the
    // same sum as sum_k w_k B_k^T B_k rearranged. omega_0 = (1 - xi)^2, omega_1 = xi (1 - xi),
    // omega_2 = xi^2.
    struct KineticMoments {
        double poly[3] = {0, 0, 0};               // sum w omega_p
        Eigen::VectorXd alpha, beta;              // sum w (1 - xi) S_i, sum w xi S_i
        Eigen::VectorXd slope[3];                 // sum w omega_p S_i'
        Eigen::MatrixXd sinSin;                   // sum w S_i S_j
        Eigen::MatrixXd slopeSlope[3];            // sum w omega_p S_i' S_j'
        Eigen::MatrixXd slopeSin[2];              // sum w (1 - xi) S_i' S_j, sum w xi S_i' S_j
    };
    KineticMoments moments_;
    // Closed-form integrals int_0^1 S_i dxi and (i pi)^4 / 2 (bending), i = 1..maxMode_.
    Eigen::VectorXd sinMean_, bendFactor_;
};

using PlanarSpanModel = SpanModel<2>;   ///< a span in the x-y plane
using SpatialSpanModel = SpanModel<3>;  ///< a span in space

}  // namespace SimbodyReeving
