#pragma once
/// @file
/// The axial constitutive law of one span: axial force P(eps) and strain energy density as functions
/// of the Green strain (pure C++17, no Eigen or Simbody include).

#include "SimbodyReeving/element/RopeProperties.h"

namespace SimbodyReeving {

/// Axial force P = EA f(eps) [N] and strain energy per unit unstretched length EA F(eps) [J/m],
/// F' = f, for one of three laws:
/// - linear (the paper, eq 21): f = eps, F = eps^2 / 2; compression allowed;
/// - tension-only (RopeProperties::tensionOnly): f = max(eps, 0), F = max(eps, 0)^2 / 2; the
///   energy is C1 in the strain;
/// - tension-only with a transition strain eps_s > 0 (quasi-static axial modes,
///   SpanOptions::quasiStaticSlackTransitionStrain): f = 0 for eps <= 0, f = eps for eps >= eps_s
///   and in between the quintic f = eps_s p(x), x = eps / eps_s, p = 6 x^3 - 8 x^4 + 3 x^5, the
///   polynomial matching value, slope and curvature at both ends; so the force is C2 and the
///   energy C3 in the strain. 0 <= f <= max(eps, 0) (eps - f = eps_s x (1 - x)^3 (1 + 3 x)), the
///   largest shortfall 0.1975 eps_s at x = 0.34; f is increasing. F = eps_s^2 (3/2 x^4 - 8/5 x^5 +
///   1/2 x^6) in between, eps^2 / 2 - eps_s^2 / 10 above.
/// The templated forms take the strain as a Scalar (double, or a Taylor number for exact
/// derivatives) together with its plain value, which selects the branch.
// mutation-site: linear-strain
struct AxialLaw {
    double EA = 0;              ///< axial stiffness [N]
    bool tensionOnly = false;   ///< false: linear law
    double transition = 0;      ///< eps_s [-]: 0 = the plain clamp max(eps, 0)

    AxialLaw() = default;
    /// The law of a rope (EA, tensionOnly) with transition strain eps_s (used if tension-only).
    AxialLaw(const RopeProperties& properties, double transitionStrain)
        : EA(properties.axialStiffness), tensionOnly(properties.tensionOnly),
          transition(properties.tensionOnly ? transitionStrain : 0.0) {}

    /// true if eps carries no force (slack point of a tension-only rope).
    bool slack(double eps) const { return tensionOnly && !(eps > 0); }

    /// f(eps) [-]: P = EA f.
    template <class Scalar>
    Scalar f(const Scalar& eps, double primal) const {
        if (!tensionOnly || primal >= transition) return eps;  // mutation-site: linear-strain
        if (!(primal > 0)) return Scalar(0.0);
        const double c = 1.0 / transition;
        const Scalar x = c * eps;
        // eps_s (6 x^3 - 8 x^4 + 3 x^5)
        return (transition * (x * x)) * (x * (Scalar(6.0) + x * (Scalar(-8.0) + 3.0 * x)));
    }
    /// F(eps) [-]: energy density EA F, F' = f.
    template <class Scalar>
    Scalar F(const Scalar& eps, double primal) const {
        if (!tensionOnly) return 0.5 * (eps * eps);  // mutation-site: linear-strain
        if (!(primal > 0)) return Scalar(0.0);
        // mutation-site: linear-strain
        if (primal >= transition) return 0.5 * (eps * eps) - Scalar(0.1 * transition * transition);
        const Scalar x = (1.0 / transition) * eps;
        const Scalar x2 = x * x;
        // eps_s^2 (3/2 x^4 - 8/5 x^5 + 1/2 x^6)
        return (transition * transition) * ((x2 * x2) * (Scalar(1.5) + x * (Scalar(-1.6) + 0.5 * x)));
    }
    /// f'(eps) [-]: the tangent stiffness EA f'.
    double fPrime(double eps) const {
        if (!tensionOnly || eps >= transition) return 1.0;  // mutation-site: linear-strain
        if (!(eps > 0)) return 0.0;
        const double x = eps / transition;
        return x * x * (18.0 + x * (-32.0 + 15.0 * x));
    }

    double f(double eps) const { return f<double>(eps, eps); }  ///< f(eps) [-] for a plain strain
    double F(double eps) const { return F<double>(eps, eps); }  ///< F(eps) [-] for a plain strain
    /// Axial force P = EA f(eps) [N].
    double force(double eps) const { return EA * f(eps); }
};

}  // namespace SimbodyReeving
