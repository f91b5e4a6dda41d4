// The rope stored on a winch drum (StoredRope, internal to the element layer): its mass block and
// force are Lagrange's equations of its own energies, checked by central differences of T and U
// written out in this test from the geometry (the stored material integrated point by point over
// the drum, not the law's closed form); a held drum's stored rope has no kinetic energy whatever
// its tangent point does.
#include "StoredRope.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>

using SimbodyReeving::detail::StoredRope;
using SimbodyReeving::detail::StoredRopeTerms;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRhoA = 2.5, kR = 0.4, kL0 = 3.1;
const Eigen::Vector2d kGravity(0.3, -9.81);  // a little off -y: "up" is not an axis

// x = [c (2), T (2), s]: the layout the law is given below.
StoredRope<2> wrappedLaw(int node, double slope, int sigma) {
    StoredRope<2> law(node, kL0, slope, kRhoA, kGravity);
    law.setWrapped(kR, sigma, 0, 2);
    law.setMaterialOffset(4);
    return law;
}

// The energies by quadrature over the stored material, from the definition: material s on the
// drum sits at angle psi(s) = sigma (s - Y_s) / R from up (Y_s = s_k - sigma R phi), at
// c + R u(psi), moving with the drum (psidot = -sigma v / R, v = sdot - sigma R phidot).
struct Quadrature {
    double kinetic = 0, gravity = 0;
};
Quadrature byQuadrature(double slope, int sigma, const Eigen::VectorXd& x, const Eigen::VectorXd& xdot) {
    const Eigen::Vector2d up = -kGravity.normalized(), perp(-up[1], up[0]);
    const Eigen::Vector2d c = x.segment<2>(0), cdot = xdot.segment<2>(0);
    const Eigen::Vector2d r = x.segment<2>(2) - c, rdot = xdot.segment<2>(2) - cdot;
    const double phi = std::atan2(up[0] * r[1] - up[1] * r[0], up.dot(r));
    const double phidot = (r[0] * rdot[1] - r[1] * rdot[0]) / r.squaredNorm();
    const double s = x[4], sdot = xdot[4], l = kL0 + slope * s;
    const double Ys = s - sigma * kR * phi, v = sdot - sigma * kR * phidot;
    const double from = slope > 0 ? s - l : s, to = slope > 0 ? s : s + l;
    Quadrature q;
    const int n = 20000;  // midpoint rule: error ~ (l / n)^2 / 24 of the integrands' curvature
    for (int i = 0; i < n; ++i) {
        const double sm = from + (to - from) * (i + 0.5) / n, ds = (to - from) / n;
        const double psi = sigma * (sm - Ys) / kR;
        const Eigen::Vector2d u = std::cos(psi) * up + std::sin(psi) * perp;
        const Eigen::Vector2d du = -std::sin(psi) * up + std::cos(psi) * perp;
        const Eigen::Vector2d vel = cdot + kR * (-sigma * v / kR) * du;
        q.kinetic += 0.5 * kRhoA * vel.squaredNorm() * ds;
        q.gravity -= kRhoA * kGravity.dot(c + kR * u) * ds;
    }
    return q;
}

double lagrangian(const StoredRope<2>& law, const Eigen::VectorXd& x, const Eigen::VectorXd& xdot) {
    StoredRopeTerms<2> t;
    law.evaluate(x, xdot, x[4], xdot[4], t);
    return t.kineticEnergy - t.gravityEnergy;
}

// A state on the drum: centre, tangent point at angle phi from up (|T - c| = R), s; rates.
void state(double phi, Eigen::VectorXd& x, Eigen::VectorXd& xdot) {
    const Eigen::Vector2d up = -kGravity.normalized(), perp(-up[1], up[0]);
    const Eigen::Vector2d c(0.7, -1.2), cdot(0.9, -0.4);
    const double phidot = 1.7;
    const Eigen::Vector2d u = std::cos(phi) * up + std::sin(phi) * perp, du = -std::sin(phi) * up + std::cos(phi) * perp;
    x.resize(5);
    xdot.resize(5);
    x << c, c + kR * u, 0.35;
    xdot << cdot, cdot + kR * phidot * du, -0.8;
}

}  // namespace

// The closed-form energies equal the quadrature of the stored material (relative 1e-7: the
// midpoint rule's error at n = 20000 is about 1e-9 of the integrands; measured below), for the
// rope's start and end, both wrap senses, several turns stored.
TEST(StoredRope, EnergiesAreTheStoredMaterialsIntegrals) {
    double worst = 0;
    for (double slope : {1.0, -1.0})
        for (int sigma : {1, -1})
            for (double phi : {0.3, 2.0, -2.6}) {
                Eigen::VectorXd x, xdot;
                state(phi, x, xdot);
                StoredRopeTerms<2> t;
                wrappedLaw(slope > 0 ? 0 : 5, slope, sigma).evaluate(x, xdot, x[4], xdot[4], t);
                const Quadrature q = byQuadrature(slope, sigma, x, xdot);
                worst = std::max({worst, std::abs(t.kineticEnergy - q.kinetic) / std::abs(q.kinetic),
                                  std::abs(t.gravityEnergy - q.gravity) / std::abs(q.gravity)});
            }
    std::printf("stored rope energies vs quadrature: %.2e relative\n", worst);
    EXPECT_LT(worst, 1e-7);
}

// S = d^2 T / dxdot^2 and h = dL/dx - d/deps [S(x + eps xdot) xdot] by central differences of
// the law's own energies (relative 1e-6 of the largest entry; T is quadratic in xdot, so its
// differences with step 0.1 are exact to round-off, measured 1e-14; those in x with step 1e-5
// have truncation ~1e-10 relative, measured 3e-10); and T = 1/2 xdot^T S xdot.
TEST(StoredRope, MassAndForceAreLagrangesEquationsOfItsEnergies) {
    double worstMass = 0, worstForce = 0, worstKinetic = 0;
    for (double slope : {1.0, -1.0})
        for (int sigma : {1, -1})
            for (double phi : {0.3, 2.0, -2.6}) {
                const StoredRope<2> law = wrappedLaw(slope > 0 ? 0 : 5, slope, sigma);
                Eigen::VectorXd x, xdot;
                state(phi, x, xdot);
                StoredRopeTerms<2> t;
                law.evaluate(x, xdot, x[4], xdot[4], t);
                Eigen::MatrixXd S = t.mass.topLeftCorner(5, 5);
                worstKinetic = std::max(worstKinetic, std::abs(0.5 * xdot.dot(S * xdot) - t.kineticEnergy) / t.kineticEnergy);
                const double hv = 0.1, h = 1e-5;
                Eigen::MatrixXd Sfd(5, 5);
                for (int a = 0; a < 5; ++a)
                    for (int b = 0; b < 5; ++b) {
                        auto T = [&](double da, double db) {
                            Eigen::VectorXd v = xdot;
                            v[a] += da;
                            v[b] += db;
                            StoredRopeTerms<2> tt;
                            law.evaluate(x, v, x[4], v[4], tt);
                            return tt.kineticEnergy;
                        };
                        Sfd(a, b) = (T(hv, hv) - T(hv, -hv) - T(-hv, hv) + T(-hv, -hv)) / (4 * hv * hv);
                    }
                worstMass = std::max(worstMass, (Sfd - S).cwiseAbs().maxCoeff() / S.cwiseAbs().maxCoeff());
                Eigen::VectorXd dLdx(5), dpdt(5);
                for (int a = 0; a < 5; ++a) {
                    Eigen::VectorXd xp = x, xm = x;
                    xp[a] += h;
                    xm[a] -= h;
                    dLdx[a] = (lagrangian(law, xp, xdot) - lagrangian(law, xm, xdot)) / (2 * h);
                }
                auto momentum = [&](double eps) {
                    const Eigen::VectorXd xe = x + eps * xdot;
                    StoredRopeTerms<2> tt;
                    law.evaluate(xe, xdot, xe[4], xdot[4], tt);
                    return Eigen::VectorXd(tt.mass.topLeftCorner(5, 5) * xdot);
                };
                dpdt = (momentum(h) - momentum(-h)) / (2 * h);
                const Eigen::VectorXd hfd = dLdx - dpdt;
                Eigen::VectorXd force = t.force.head(5);
                worstForce = std::max(worstForce, (hfd - force).cwiseAbs().maxCoeff() / force.cwiseAbs().maxCoeff());
            }
    std::printf("stored rope: mass %.2e, force %.2e, T = 1/2 xdot S xdot %.2e (relative)\n", worstMass, worstForce,
                worstKinetic);
    EXPECT_LT(worstMass, 1e-6);
    EXPECT_LT(worstForce, 1e-6);
    EXPECT_LT(worstKinetic, 1e-12);
}

// A held drum (c still, the surface still: sdot = sigma R phidot) stores rope that does not move:
// its kinetic energy is zero however fast the tangent point rolls (1e-15 J of 1/2 rhoA l (R phidot)^2 =
// the energy a ring at the rope's rate would have).
TEST(StoredRope, HeldDrumsRopeDoesNotMove) {
    for (int sigma : {1, -1}) {
        const StoredRope<2> law = wrappedLaw(0, 1.0, sigma);
        Eigen::VectorXd x, xdot;
        state(0.9, x, xdot);
        xdot.head<2>().setZero();
        const Eigen::Vector2d r = x.segment<2>(2) - x.head<2>();
        const double phidot = 2.0;
        xdot.segment<2>(2) = phidot * Eigen::Vector2d(-r[1], r[0]);
        xdot[4] = sigma * kR * phidot;
        StoredRopeTerms<2> t;
        law.evaluate(x, xdot, x[4], xdot[4], t);
        EXPECT_LT(std::abs(t.kineticEnergy), 1e-15);
        EXPECT_GT(0.5 * kRhoA * law.length(x[4]) * std::pow(kR * phidot, 2), 1.0);
    }
}

namespace {

// The spatial law: x = [c (3), T (3), s, n (3)], the groove's axis tilted off gravity's plane.
const Eigen::Vector3d kGravity3(0.3, -9.81, 0.5);
const Eigen::Vector3d kAxis3 = Eigen::Vector3d(0.2, 0.3, 1.0).normalized();

StoredRope<3> wrappedLaw3(int node, double slope, int sigma) {
    StoredRope<3> law(node, kL0, slope, kRhoA, kGravity3);
    law.setWrapped(kR, sigma, 0, 3, 7);
    law.setMaterialOffset(6);
    return law;
}

// In-plane "up" (gravity projected onto the groove's plane, reversed) and its normal n x up.
void planeBasis3(Eigen::Vector3d& up, Eigen::Vector3d& w) {
    const Eigen::Vector3d gp = kGravity3 - kAxis3 * kAxis3.dot(kGravity3);
    up = -gp.normalized();
    w = kAxis3.cross(up);
}

void state3(double phi, Eigen::VectorXd& x, Eigen::VectorXd& xdot) {
    Eigen::Vector3d up, w;
    planeBasis3(up, w);
    const Eigen::Vector3d c(0.7, -1.2, 0.4), cdot(0.9, -0.4, 0.3);
    const double phidot = 1.7;
    x.resize(10);
    xdot.resize(10);
    x << c, c + kR * (std::cos(phi) * up + std::sin(phi) * w), 0.35, kAxis3;
    xdot << cdot, cdot + kR * phidot * (-std::sin(phi) * up + std::cos(phi) * w), -0.8, 0, 0, 0;
}

Quadrature byQuadrature3(double slope, int sigma, const Eigen::VectorXd& x, const Eigen::VectorXd& xdot) {
    Eigen::Vector3d up, w;
    planeBasis3(up, w);
    const Eigen::Vector3d c = x.segment<3>(0), cdot = xdot.segment<3>(0);
    const Eigen::Vector3d r = x.segment<3>(3) - c, rdot = xdot.segment<3>(3) - cdot;
    const double phi = std::atan2(w.dot(r), up.dot(r));
    const double phidot = (up.dot(r) * w.dot(rdot) - w.dot(r) * up.dot(rdot)) / r.squaredNorm();
    const double s = x[6], sdot = xdot[6], l = kL0 + slope * s;
    const double Ys = s - sigma * kR * phi, v = sdot - sigma * kR * phidot;
    const double from = slope > 0 ? s - l : s, to = slope > 0 ? s : s + l;
    Quadrature q;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double sm = from + (to - from) * (i + 0.5) / n, ds = (to - from) / n;
        const double psi = sigma * (sm - Ys) / kR;
        const Eigen::Vector3d u = std::cos(psi) * up + std::sin(psi) * w, du = -std::sin(psi) * up + std::cos(psi) * w;
        q.kinetic += 0.5 * kRhoA * (cdot - sigma * v * du).squaredNorm() * ds;
        q.gravity -= kRhoA * kGravity3.dot(c + kR * u) * ds;
    }
    return q;
}

}  // namespace

// The spatial law (a groove tilted out of gravity's plane): energies against the quadrature of
// the stored material, and mass and force against differences of those energies, as the planar
// tests above (same bounds; measured below).
TEST(StoredRope, SpatialLawIsLagrangesEquationsOfTheStoredMaterial) {
    double worstEnergy = 0, worstMass = 0, worstForce = 0;
    const int cols[7] = {0, 1, 2, 3, 4, 5, 6};
    for (double slope : {1.0, -1.0})
        for (int sigma : {1, -1})
            for (double phi : {0.3, 2.0, -2.6}) {
                const StoredRope<3> law = wrappedLaw3(slope > 0 ? 0 : 5, slope, sigma);
                Eigen::VectorXd x, xdot;
                state3(phi, x, xdot);
                StoredRopeTerms<3> t;
                law.evaluate(x, xdot, x[6], xdot[6], t);
                const Quadrature q = byQuadrature3(slope, sigma, x, xdot);
                worstEnergy = std::max({worstEnergy, std::abs(t.kineticEnergy - q.kinetic) / std::abs(q.kinetic),
                                        std::abs(t.gravityEnergy - q.gravity) / std::abs(q.gravity)});
                auto energies = [&](const Eigen::VectorXd& xe, const Eigen::VectorXd& ve) {
                    StoredRopeTerms<3> tt;
                    law.evaluate(xe, ve, xe[6], ve[6], tt);
                    return tt;
                };
                const double hv = 0.1, h = 1e-5;
                Eigen::MatrixXd S = t.mass.topLeftCorner(7, 7), Sfd(7, 7);
                for (int a = 0; a < 7; ++a)
                    for (int b = 0; b < 7; ++b) {
                        auto T = [&](double da, double db) {
                            Eigen::VectorXd v = xdot;
                            v[cols[a]] += da;
                            v[cols[b]] += db;
                            return energies(x, v).kineticEnergy;
                        };
                        Sfd(a, b) = (T(hv, hv) - T(hv, -hv) - T(-hv, hv) + T(-hv, -hv)) / (4 * hv * hv);
                    }
                worstMass = std::max(worstMass, (Sfd - S).cwiseAbs().maxCoeff() / S.cwiseAbs().maxCoeff());
                Eigen::VectorXd dLdx(7);
                for (int a = 0; a < 7; ++a) {
                    Eigen::VectorXd xp = x, xm = x;
                    xp[cols[a]] += h;
                    xm[cols[a]] -= h;
                    const StoredRopeTerms<3> tp = energies(xp, xdot), tm = energies(xm, xdot);
                    dLdx[a] = ((tp.kineticEnergy - tp.gravityEnergy) - (tm.kineticEnergy - tm.gravityEnergy)) / (2 * h);
                }
                auto momentum = [&](double eps) {
                    Eigen::VectorXd xe = x;
                    xe.head(7) += eps * xdot.head(7);
                    return Eigen::VectorXd(energies(xe, xdot).mass.topLeftCorner(7, 7) * xdot.head(7));
                };
                const Eigen::VectorXd hfd = dLdx - (momentum(h) - momentum(-h)) / (2 * h);
                worstForce = std::max(worstForce, (hfd - t.force.head(7)).cwiseAbs().maxCoeff() /
                                                      t.force.head(7).cwiseAbs().maxCoeff());
            }
    std::printf("spatial stored rope: energies %.2e, mass %.2e, force %.2e (relative)\n", worstEnergy, worstMass,
                worstForce);
    EXPECT_LT(worstEnergy, 1e-7);
    EXPECT_LT(worstMass, 1e-6);
    EXPECT_LT(worstForce, 1e-6);
}

namespace {

// A drum whose axis turns (StoredRope::setTurningAxis), in the spatial layout above: the drum
// turning rigidly at omega (across and along its axis) while its centre moves at cdot; the
// tangent point at angle phi from "up", spinning about n at rho relative to Ground's directions
// (the rope rolling on or off), so that the stored material's own spin about n is omega . n:
// sdot = sigma R (rho - omega . n) (the law's Omega_s = f . (Tdot - cdot) / R - sigma sdot / R).
StoredRope<3> turningLaw3(int node, double slope, int sigma) {
    StoredRope<3> law = wrappedLaw3(node, slope, sigma);
    law.setTurningAxis();
    return law;
}

// With axial != 0 the tangent point lies that far along n from c's plane, walking at axialRate (a
// drum that spools across its width): T = c + r + axial n, Tdot = cdot + omega_across x
// (r + axial n) + rho n x r + axialRate n.
void turningState3(double phi, int sigma, const Eigen::Vector3d& omega, Eigen::VectorXd& x, Eigen::VectorXd& xdot,
                   double axial = 0, double axialRate = 0) {
    Eigen::Vector3d up, w;
    planeBasis3(up, w);
    const Eigen::Vector3d c(0.7, -1.2, 0.4), cdot(0.9, -0.4, 0.3), n = kAxis3;
    const Eigen::Vector3d r = kR * (std::cos(phi) * up + std::sin(phi) * w);
    const Eigen::Vector3d across = omega - n * n.dot(omega);
    const double rho = 1.7;
    x.resize(10);
    xdot.resize(10);
    x << c, c + r + axial * n, 0.35, n;
    xdot << cdot, cdot + across.cross(r + axial * n) + rho * n.cross(r) + axialRate * n, sigma * kR * (rho - omega.dot(n)),
        omega.cross(n);
}

// The stored material moving rigidly with the drum: material lambda from the tangent point at
// c + R u, u turned from e (T - c projected onto the groove's plane, over R) by -sigma kappa
// lambda / R about n, velocity cdot + omega x (R u).
Quadrature rigidQuadrature3(double slope, int sigma, const Eigen::Vector3d& omega, const Eigen::VectorXd& x,
                            const Eigen::VectorXd& xdot) {
    const Eigen::Vector3d c = x.segment<3>(0), cdot = xdot.segment<3>(0), n = x.segment<3>(7);
    const Eigen::Vector3d r = x.segment<3>(3) - c, e = (r - n * n.dot(r)) / kR, f = n.cross(e);
    const double l = kL0 + slope * x[6];
    Quadrature q;
    const int steps = 20000;
    for (int i = 0; i < steps; ++i) {
        const double lambda = l * (i + 0.5) / steps, dl = l / steps, t = -sigma * slope * lambda / kR;
        const Eigen::Vector3d u = std::cos(t) * e + std::sin(t) * f;
        q.kinetic += 0.5 * kRhoA * (cdot + omega.cross(kR * u)).squaredNorm() * dl;
        q.gravity -= kRhoA * kGravity3.dot(c + kR * u) * dl;
    }
    return q;
}

}  // namespace

// A drum whose axis turns: the law's energies are those of the stored material turning rigidly
// with the drum (quadrature, relative 1e-7 as above; measured below), at the rope's start and end,
// both senses, omega across and along the axis, the tangent point in the ring's plane and 0.08 m
// off it along the axis, walking at 0.05 m/s (a drum spooling across its width); its mass and force are Lagrange's equations of
// those energies at all ten coordinates (c, T, n, s), as the tests above check (differences of the
// law's energies, bounds 1e-6; measured below).
TEST(StoredRope, TurningAxisLawIsTheStoredMaterialTumblingWithTheDrum) {
    double worstEnergy = 0, worstMass = 0, worstForce = 0;
    const Eigen::Vector3d omega(0.8, -0.5, 1.3);
    for (double slope : {1.0, -1.0})
        for (int sigma : {1, -1})
            for (double phi : {0.3, 2.0, -2.6})
            for (double axial : {0.0, 0.08}) {
                const StoredRope<3> law = turningLaw3(slope > 0 ? 0 : 5, slope, sigma);
                Eigen::VectorXd x, xdot;
                turningState3(phi, sigma, omega, x, xdot, axial, axial > 0 ? 0.05 : 0.0);
                auto energies = [&](const Eigen::VectorXd& xe, const Eigen::VectorXd& ve) {
                    StoredRopeTerms<3> tt;
                    law.evaluate(xe, ve, xe[6], ve[6], tt);
                    return tt;
                };
                const StoredRopeTerms<3> t = energies(x, xdot);
                ASSERT_EQ(t.count, 10);
                const Quadrature q = rigidQuadrature3(slope, sigma, omega, x, xdot);
                worstEnergy = std::max({worstEnergy, std::abs(t.kineticEnergy - q.kinetic) / std::abs(q.kinetic),
                                        std::abs(t.gravityEnergy - q.gravity) / std::abs(q.gravity)});
                // t's columns in x: c (0..2), T (3..5), n (7..9), s (6).
                const int cols[10] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 6};
                for (int a = 0; a < 10; ++a) ASSERT_EQ(t.cols[a], cols[a]);
                const double hv = 0.1, h = 1e-5;
                Eigen::MatrixXd S = t.mass.topLeftCorner(10, 10), Sfd(10, 10);
                for (int a = 0; a < 10; ++a)
                    for (int b = 0; b < 10; ++b) {
                        auto T = [&](double da, double db) {
                            Eigen::VectorXd v = xdot;
                            v[cols[a]] += da;
                            v[cols[b]] += db;
                            return energies(x, v).kineticEnergy;
                        };
                        Sfd(a, b) = (T(hv, hv) - T(hv, -hv) - T(-hv, hv) + T(-hv, -hv)) / (4 * hv * hv);
                    }
                worstMass = std::max(worstMass, (Sfd - S).cwiseAbs().maxCoeff() / S.cwiseAbs().maxCoeff());
                Eigen::VectorXd dLdx(10), p(10);
                for (int a = 0; a < 10; ++a) {
                    Eigen::VectorXd xp = x, xm = x;
                    xp[cols[a]] += h;
                    xm[cols[a]] -= h;
                    const StoredRopeTerms<3> tp = energies(xp, xdot), tm = energies(xm, xdot);
                    dLdx[a] = ((tp.kineticEnergy - tp.gravityEnergy) - (tm.kineticEnergy - tm.gravityEnergy)) / (2 * h);
                }
                Eigen::VectorXd v(10);
                for (int a = 0; a < 10; ++a) v[a] = xdot[cols[a]];
                auto momentum = [&](double eps) {
                    Eigen::VectorXd xe = x;
                    xe += eps * xdot;
                    return Eigen::VectorXd(energies(xe, xdot).mass.topLeftCorner(10, 10) * v);
                };
                const Eigen::VectorXd hfd = dLdx - (momentum(h) - momentum(-h)) / (2 * h);
                worstForce = std::max(worstForce, (hfd - t.force.head(10)).cwiseAbs().maxCoeff() /
                                                      t.force.head(10).cwiseAbs().maxCoeff());
            }
    std::printf("turning-axis stored rope: energies %.2e, mass %.2e, force %.2e (relative)\n", worstEnergy, worstMass,
                worstForce);
    EXPECT_LT(worstEnergy, 1e-7);
    EXPECT_LT(worstMass, 1e-6);
    EXPECT_LT(worstForce, 1e-6);
}

// With the axis momentarily still (omega along n) the turning law is the fixed-axis law: the same
// energies, and the same mass and force along every motion the drum's rope can make (the centre
// and tangent point translating together, the tangent point rolling round the groove, s): the
// laws differ only off the groove circle, which no motion reaches (relative 1e-12; measured below).
TEST(StoredRope, TurningAxisLawIsTheFixedAxisLawWhenTheAxisIsStill) {
    double worst = 0;
    for (double slope : {1.0, -1.0})
        for (int sigma : {1, -1})
            for (double phi : {0.3, 2.0, -2.6}) {
                Eigen::VectorXd x, xdot;
                turningState3(phi, sigma, 1.1 * kAxis3, x, xdot);
                StoredRopeTerms<3> turning, fixed;
                turningLaw3(slope > 0 ? 0 : 5, slope, sigma).evaluate(x, xdot, x[6], xdot[6], turning);
                wrappedLaw3(slope > 0 ? 0 : 5, slope, sigma).evaluate(x, xdot, x[6], xdot[6], fixed);
                // Both as 10 x 10 / 10 blocks in x's order.
                auto dense = [](const StoredRopeTerms<3>& t, Eigen::MatrixXd& S, Eigen::VectorXd& h) {
                    S.setZero(10, 10);
                    h.setZero(10);
                    for (int a = 0; a < t.count; ++a) {
                        h[t.cols[a]] += t.force[a];
                        for (int b = 0; b < t.count; ++b) S(t.cols[a], t.cols[b]) += t.mass(a, b);
                    }
                };
                Eigen::MatrixXd St, Sf;
                Eigen::VectorXd ht, hf;
                dense(turning, St, ht);
                dense(fixed, Sf, hf);
                const Eigen::Vector3d r = x.segment<3>(3) - x.segment<3>(0);
                Eigen::MatrixXd D = Eigen::MatrixXd::Zero(10, 5);
                for (int i = 0; i < 3; ++i) D(i, i) = D(3 + i, i) = 1.0;
                D.block<3, 1>(3, 3) = kAxis3.cross(r);
                D(6, 4) = 1.0;
                const Eigen::MatrixXd dS = D.transpose() * (St - Sf) * D;
                const Eigen::VectorXd dh = D.transpose() * (ht - hf);
                worst = std::max({worst, dS.cwiseAbs().maxCoeff() / (D.transpose() * Sf * D).cwiseAbs().maxCoeff(),
                                  dh.cwiseAbs().maxCoeff() / (D.transpose() * hf).cwiseAbs().maxCoeff(),
                                  std::abs(turning.kineticEnergy - fixed.kineticEnergy) / fixed.kineticEnergy,
                                  std::abs(turning.gravityEnergy - fixed.gravityEnergy) / std::abs(fixed.gravityEnergy)});
            }
    std::printf("turning-axis law vs fixed-axis law, axis still: %.2e relative\n", worst);
    EXPECT_LT(worst, 1e-12);
}
