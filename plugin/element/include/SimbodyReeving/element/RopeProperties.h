#pragma once
/// @file
/// Cross-section properties of a wire rope, in SI units.

namespace SimbodyReeving {

/// Mechanical properties of a wire rope per unit unstretched length (SI units).
struct RopeProperties {
    /// rhoA: mass per unit unstretched length [kg/m]; finite, > 0.
    double massPerLength = 0.0;
    /// EA: axial stiffness [N]; finite, > 0. Axial force P = EA * epsilon (Green strain).
    double axialStiffness = 0.0;
    /// EI: bending stiffness [N m^2]; finite, >= 0. EI = 0 skips the bending term entirely.
    double bendingStiffness = 0.0;
    /// Tension-only axial law: a wire rope cannot push. true (default): P = EA max(eps, 0),
    /// U_ax = 1/2 EA int max(eps, 0)^2 ds, which is C1 in the coordinates, so its forces are still
    /// exact gradients and T + U stays an invariant. false: the paper's linear law P = EA eps,
    /// U_ax = 1/2 EA int eps^2 ds, compression allowed (reproduces the paper; no difference while
    /// every span stays taut). Where a span is slack (eps <= 0) it carries no axial force and its
    /// transverse modes lose their taut-string stiffness (bending EI remains). Sheaves keep the
    /// strains on their two sides equal (the tension equality when taut; between two slack spans it
    /// selects equal slack strains), so the sheave coordinates stay determined. With
    /// AxialDynamics::QuasiStatic axial modes the law is rounded over strains (0, eps_s) and slack
    /// spans carry a small regularising energy (SpanOptions::quasiStaticSlackTransitionStrain and
    /// quasiStaticSlackStiffness). Brace initialisation {rhoA, EA, EI} keeps this default.
    bool tensionOnly = true;
    /// c: Kelvin-Voigt retardation time of the axial law [s]; finite, >= 0; default 0 (the paper's
    /// conservative rope). The axial force becomes P = EA (eps + c Deps/Dt), Deps/Dt the material
    /// rate of the strain (at a fixed material point s, so rope that merely flows through a span or
    /// over a sheave at uniform strain dissipates nothing), from the Rayleigh dissipation function
    ///     D = 1/2 EA c int_{s1}^{s2} (Deps/Dt)^2 ds,   Q_damping = -dD/dqdot,
    /// so the dissipated power is 2 D >= 0 (SpanData::dampingPower). A uniformly stretched span of
    /// stiffness k = EA / l carrying a mass m is then a Kelvin-Voigt spring: damping ratio
    /// zeta = c omega / 2 at omega = sqrt(k / m) (retardationTimeForDampingRatio). Tension-only
    /// ropes: damping acts where the rope is taut (eps > 0), like its stiffness. With
    /// AxialDynamics::QuasiStatic spans the condensed amplitudes follow the static (undamped) strain
    /// distribution; the damping forces act through their rates, i.e. on the motions the rope's
    /// stretch follows (the bodies', the sheaves'), not on the span's own axial vibration, which is
    /// not a state there.
    double axialRetardationTime = 0.0;
};

/// The Kelvin-Voigt retardation time c [s] that gives damping ratio zeta [-] at angular frequency
/// omega [rad/s]: c = 2 zeta / omega.
/// @throws std::invalid_argument unless zeta >= 0 and omega > 0 are finite.
double retardationTimeForDampingRatio(double zeta, double omega);

/// Axial force [N] for Green strain eps under `properties`' law: EA eps, or EA max(eps, 0) when
/// RopeProperties::tensionOnly.
inline double axialForce(const RopeProperties& properties, double eps) {
    return properties.axialStiffness * (properties.tensionOnly && eps < 0 ? 0.0 : eps);
}

/// Checks the ranges documented on RopeProperties.
/// @throws std::invalid_argument naming the offending parameter and its value.
void validate(const RopeProperties& properties);

}  // namespace SimbodyReeving
