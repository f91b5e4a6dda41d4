// The rope on a groove arc: its kinetic and gravity energies against quadratures of its material
// points, its kinematics against finite differences of its positions, its Lagrange terms
// (mass matrix, quadratic-velocity forces, gravity forces) against finite differences of its
// energies, and closed forms (a sheave with sliding rope, a translating or turning sheave, the
// centroid of a semicircle).
#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/GaussLegendre.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace SimbodyReeving;

namespace {

constexpr double kPi = 3.14159265358979323846;
const RopeProperties kRope{2.5, 1e7, 0.0};  // rhoA [kg/m], EA [N], EI [N m^2]

template <int Dim>
typename GrooveArc<Dim>::Vec gravityVector() {
    typename GrooveArc<Dim>::Vec g = GrooveArc<Dim>::Vec::Zero();
    g[1] = -9.81;
    return g;
}

// A state with the arrival point on the groove circle (|T - c| = R, T - c normal to n) and every
// rate non-zero: the axis tilted and turning in 3D.
template <int Dim>
void randomState(std::mt19937& rng, double R, typename GrooveArc<Dim>::Coordinates& x,
                 typename GrooveArc<Dim>::Coordinates& xdot) {
    using Arc = GrooveArc<Dim>;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < Arc::kNumCoordinates; ++i) {
        x[i] = u(rng);
        xdot[i] = u(rng);
    }
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    if constexpr (Dim == 3) {
        n = Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 1.0).normalized();
        x.template segment<3>(Arc::axisIndex()) = n;
        Eigen::Vector3d ndot(u(rng), u(rng), u(rng));
        xdot.template segment<3>(Arc::axisIndex()) = ndot - n * n.dot(ndot);
    }
    Eigen::Vector3d e(u(rng), u(rng), u(rng));
    e -= n * n.dot(e);
    e.normalize();
    x.template segment<Dim>(Arc::tangentPointIndex()) =
        x.template segment<Dim>(Arc::centreIndex()) + R * e.template head<Dim>();
    x[Arc::lengthIndex()] = R * (0.5 + 2.5 * std::abs(u(rng)));  // wrap angle 0.5..3 rad
}

// int_0^l f(a) da by a 60-point Gauss-Legendre rule (the integrands are trigonometric in a / R over
// at most 3 rad: the rule is exact to round-off).
template <class F>
double integrateOverArc(double l, F f) {
    static const GaussLegendreRule rule = makeGaussLegendreRule(60);
    double sum = 0;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) sum += rule.weights[k] * f(l * rule.nodes[k]);
    return sum * l;
}

// The closed forms agree with 60-point quadratures of the material points to at most 1.3e-15
// relative (measured over these states): 1e-13 is a 77x margin.
constexpr double kQuadratureTolerance = 1e-13;

template <int Dim>
void checkEnergiesAgainstQuadrature() {
    using Arc = GrooveArc<Dim>;
    const double R = 0.35;
    const Arc arc(kRope, R, -1, gravityVector<Dim>());
    std::mt19937 rng(7 + Dim);
    for (int trial = 0; trial < 20; ++trial) {
        typename Arc::Coordinates x, xdot;
        randomState<Dim>(rng, R, x, xdot);
        const double l = x[Arc::lengthIndex()];
        const double T = integrateOverArc(l, [&](double a) {
            return 0.5 * kRope.massPerLength * arc.materialVelocity(x, xdot, a).squaredNorm();
        });
        const double U = integrateOverArc(l, [&](double a) {
            return -kRope.massPerLength * arc.gravity().dot(arc.materialPosition(x, a));
        });
        typename Arc::Data data;
        arc.evaluate(x, xdot, data);
        EXPECT_NEAR(data.kineticEnergy, T, kQuadratureTolerance * T);
        EXPECT_NEAR(arc.kineticEnergy(x, xdot), T, kQuadratureTolerance * T);
        EXPECT_NEAR(0.5 * xdot.dot(data.massMatrix * xdot), T, kQuadratureTolerance * T);
        EXPECT_NEAR(data.gravityEnergy, U, kQuadratureTolerance * std::abs(U));
        EXPECT_NEAR(arc.gravityEnergy(x), U, kQuadratureTolerance * std::abs(U));
        EXPECT_LT((data.massMatrix - data.massMatrix.transpose()).norm(), 1e-15 * data.massMatrix.norm());
    }
}

// The material velocity is the time derivative of the material position at a fixed material
// point (arc length a - sdot t from the arrival point): 4th-order central differences agree to at
// most 3.1e-11 relative (h = 1e-3 s; truncation ~h^4); the bound 1e-9 is a 32x margin.
template <int Dim>
void checkVelocityAgainstPositions() {
    using Arc = GrooveArc<Dim>;
    const double R = 0.5;
    const Arc arc(kRope, R, 1, gravityVector<Dim>());
    std::mt19937 rng(11 + Dim);
    double worst = 0;
    for (int trial = 0; trial < 20; ++trial) {
        typename Arc::Coordinates x, xdot;
        randomState<Dim>(rng, R, x, xdot);
        const double sdot = xdot[Arc::materialIndex()];
        for (double a : {0.0, 0.3 * x[Arc::lengthIndex()], x[Arc::lengthIndex()]}) {
            auto position = [&](double t) {
                typename Arc::Coordinates xt = x + t * xdot;
                return arc.materialPosition(xt, a - sdot * t);
            };
            const double h = 1e-3;
            const typename Arc::Vec fd =
                (-position(2 * h) + 8 * position(h) - 8 * position(-h) + position(-2 * h)) / (12 * h);
            const typename Arc::Vec v = arc.materialVelocity(x, xdot, a);
            worst = std::max(worst, (fd - v).norm() / v.norm());
        }
    }
    EXPECT_LT(worst, 1e-9);
}

// Lagrange's equations of the arc: d/dt(dT/dxdot) - dT/dx = M xddot - Q_v along the trajectory
// x(t) = x + xdot t + xddot t^2 / 2, and Q_g = -dU/dx, against 4th-order central differences of
// the energies (h = 1e-4). Measured agreement <= 2.6e-12 relative to the largest term (gravity
// 1.7e-12); the bound 1e-10 is a 38x margin.
template <int Dim>
void checkLagrangeTermsAgainstEnergies() {
    using Arc = GrooveArc<Dim>;
    constexpr int n = Arc::kNumCoordinates;
    const double R = 0.4;
    const Arc arc(kRope, R, -1, gravityVector<Dim>());
    std::mt19937 rng(23 + Dim);
    double worstInertia = 0, worstGravity = 0;
    for (int trial = 0; trial < 20; ++trial) {
        typename Arc::Coordinates x, xdot, xddot;
        randomState<Dim>(rng, R, x, xdot);
        typename Arc::Coordinates dummy;
        randomState<Dim>(rng, R, dummy, xddot);
        const double h = 1e-4;
        auto momentum = [&](double t) {
            typename Arc::Data d;
            const typename Arc::Coordinates xt = x + t * xdot + 0.5 * t * t * xddot, vt = xdot + t * xddot;
            arc.evaluate(xt, vt, d);
            return typename Arc::Coordinates(d.massMatrix * vt);
        };
        const typename Arc::Coordinates dpdt =
            (-momentum(2 * h) + 8 * momentum(h) - 8 * momentum(-h) + momentum(-2 * h)) / (12 * h);
        typename Arc::Coordinates dTdx, dUdx;
        for (int i = 0; i < n; ++i) {
            auto shifted = [&](double e) {
                typename Arc::Coordinates xi = x;
                xi[i] += e;
                return xi;
            };
            auto T = [&](double e) { return arc.kineticEnergy(shifted(e), xdot); };
            auto U = [&](double e) { return arc.gravityEnergy(shifted(e)); };
            dTdx[i] = (-T(2 * h) + 8 * T(h) - 8 * T(-h) + T(-2 * h)) / (12 * h);
            dUdx[i] = (-U(2 * h) + 8 * U(h) - 8 * U(-h) + U(-2 * h)) / (12 * h);
        }
        typename Arc::Data data;
        arc.evaluate(x, xdot, data);
        const typename Arc::Coordinates fd = dpdt - dTdx, model = data.massMatrix * xddot - data.velocityForces;
        worstInertia = std::max(worstInertia, (fd - model).norm() / std::max(fd.norm(), dpdt.norm()));
        worstGravity = std::max(worstGravity, (data.gravityForces + dUdx).norm() / dUdx.norm());
    }
    EXPECT_LT(worstInertia, 1e-10);
    EXPECT_LT(worstGravity, 1e-10);
}

}  // namespace

TEST(GrooveArc, EnergiesMatchQuadratureOfTheMaterialPointsPlanar) { checkEnergiesAgainstQuadrature<2>(); }
TEST(GrooveArc, EnergiesMatchQuadratureOfTheMaterialPointsSpatial) { checkEnergiesAgainstQuadrature<3>(); }
TEST(GrooveArc, MaterialVelocityIsTheRateOfTheMaterialPositionPlanar) { checkVelocityAgainstPositions<2>(); }
TEST(GrooveArc, MaterialVelocityIsTheRateOfTheMaterialPositionSpatial) { checkVelocityAgainstPositions<3>(); }
TEST(GrooveArc, LagrangeTermsMatchTheEnergiesPlanar) { checkLagrangeTermsAgainstEnergies<2>(); }
TEST(GrooveArc, LagrangeTermsMatchTheEnergiesSpatial) { checkLagrangeTermsAgainstEnergies<3>(); }

// Rope sliding at speed v over a fixed sheave: T = 1/2 rhoA l v^2 and the arc's mass along the
// rope is rhoA l; a sheave translating at V with the rope at rest on its groove: T = 1/2 rhoA l V^2;
// a sheave turning at omega with the rope stuck to the groove (the arrival point carried along):
// T = 1/2 rhoA l (omega R)^2. Round-off only (bound 1e-14 relative).
TEST(GrooveArc, ClosedFormsOfSlidingTranslatingAndTurning) {
    using Arc = GrooveArc<2>;
    const double R = 0.6, l = 0.75 * kPi * R, v = 3.0, rhoA = kRope.massPerLength;
    for (int sense : {1, -1}) {
        const Arc arc(kRope, R, sense, gravityVector<2>());
        Arc::Coordinates x = Arc::Coordinates::Zero(), xdot = Arc::Coordinates::Zero();
        x.segment<2>(Arc::centreIndex()) << 1.0, 2.0;
        x.segment<2>(Arc::tangentPointIndex()) << 1.0 + R * std::cos(0.4), 2.0 + R * std::sin(0.4);
        x[Arc::lengthIndex()] = l;
        xdot[Arc::materialIndex()] = v;
        Arc::Data data;
        arc.evaluate(x, xdot, data);
        EXPECT_NEAR(data.kineticEnergy, 0.5 * rhoA * l * v * v, 1e-14 * rhoA * l * v * v);
        EXPECT_NEAR(data.massMatrix(Arc::materialIndex(), Arc::materialIndex()), rhoA * l, 1e-14 * rhoA * l);
        EXPECT_EQ(data.massMatrix.row(Arc::lengthIndex()).norm(), 0.0);

        xdot.setZero();
        const Eigen::Vector2d V(-0.7, 1.9);
        xdot.segment<2>(Arc::centreIndex()) = V;
        xdot.segment<2>(Arc::tangentPointIndex()) = V;
        arc.evaluate(x, xdot, data);
        EXPECT_NEAR(data.kineticEnergy, 0.5 * rhoA * l * V.squaredNorm(), 1e-14 * rhoA * l * V.squaredNorm());

        const double omega = 2.3;
        const Eigen::Vector2d d = x.segment<2>(Arc::tangentPointIndex()) - x.segment<2>(Arc::centreIndex());
        xdot.setZero();
        xdot.segment<2>(Arc::tangentPointIndex()) = omega * Eigen::Vector2d(-d[1], d[0]);
        arc.evaluate(x, xdot, data);
        const double expected = 0.5 * rhoA * l * omega * omega * R * R;
        EXPECT_NEAR(data.kineticEnergy, expected, 1e-14 * expected);
    }
}

// A semicircle of rope hanging under a sheave (arriving on the left, leaving on the right,
// clockwise: sense -1 about +z): its centroid lies 2R/pi below the centre, so
// U_g = -rhoA pi R g . (c - (2R/pi) y). Round-off only.
TEST(GrooveArc, SemicircleUnderASheaveHasItsCentroidTwoROverPiBelowTheCentre) {
    using Arc = GrooveArc<2>;
    const double R = 0.45, rhoA = kRope.massPerLength, g = 9.81;
    const Arc arc(kRope, R, 1, gravityVector<2>());  // left -> bottom -> right turns about +z
    Arc::Coordinates x = Arc::Coordinates::Zero();
    x.segment<2>(Arc::centreIndex()) << 0.0, 3.0;
    x.segment<2>(Arc::tangentPointIndex()) << -R, 3.0;
    x[Arc::lengthIndex()] = kPi * R;
    const double expected = rhoA * kPi * R * g * (3.0 - 2.0 * R / kPi);
    EXPECT_NEAR(arc.gravityEnergy(x), expected, 1e-14 * expected);
    EXPECT_LT((arc.materialPosition(x, kPi * R) - Eigen::Vector2d(R, 3.0)).norm(), 1e-15);
    EXPECT_LT((arc.materialPosition(x, 0.5 * kPi * R) - Eigen::Vector2d(0.0, 3.0 - R)).norm(), 1e-15);
}

// The planar arc is the spatial one in the x-y plane with its axis +z at rest: same energies,
// mass matrix and forces to round-off.
TEST(GrooveArc, PlanarArcIsTheSpatialArcInThePlane) {
    const double R = 0.3;
    const GrooveArc<2> planar(kRope, R, -1, gravityVector<2>());
    const GrooveArc<3> spatial(kRope, R, -1, gravityVector<3>());
    std::mt19937 rng(5);
    GrooveArc<2>::Coordinates x2, v2;
    randomState<2>(rng, R, x2, v2);
    GrooveArc<3>::Coordinates x3 = GrooveArc<3>::Coordinates::Zero(), v3 = GrooveArc<3>::Coordinates::Zero();
    for (int block : {0, 1}) {
        x3.segment<2>(3 * block) = x2.segment<2>(2 * block);
        v3.segment<2>(3 * block) = v2.segment<2>(2 * block);
    }
    x3.segment<3>(GrooveArc<3>::axisIndex()) = Eigen::Vector3d::UnitZ();
    x3[GrooveArc<3>::materialIndex()] = x2[GrooveArc<2>::materialIndex()];
    x3[GrooveArc<3>::lengthIndex()] = x2[GrooveArc<2>::lengthIndex()];
    v3[GrooveArc<3>::materialIndex()] = v2[GrooveArc<2>::materialIndex()];
    v3[GrooveArc<3>::lengthIndex()] = v2[GrooveArc<2>::lengthIndex()];
    GrooveArc<2>::Data d2;
    GrooveArc<3>::Data d3;
    planar.evaluate(x2, v2, d2);
    spatial.evaluate(x3, v3, d3);
    EXPECT_NEAR(d2.kineticEnergy, d3.kineticEnergy, 1e-15 * d3.kineticEnergy);
    EXPECT_NEAR(d2.gravityEnergy, d3.gravityEnergy, 1e-15 * std::abs(d3.gravityEnergy));
    // Planar index -> spatial index.
    const int map[6] = {0, 1, 3, 4, GrooveArc<3>::materialIndex(), GrooveArc<3>::lengthIndex()};
    for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(d2.velocityForces[i], d3.velocityForces[map[i]], 1e-13);
        EXPECT_NEAR(d2.gravityForces[i], d3.gravityForces[map[i]], 1e-13);
        for (int j = 0; j < 6; ++j) EXPECT_NEAR(d2.massMatrix(i, j), d3.massMatrix(map[i], map[j]), 1e-14);
    }
}

TEST(GrooveArc, RejectsBadInputWithItsValue) {
    const Eigen::Vector2d g(0.0, -9.81);
    EXPECT_THROW_MESSAGE(GrooveArc<2>(kRope, 0.0, 1, g), std::invalid_argument, "radius R = 0 m must be finite and > 0");
    EXPECT_THROW_MESSAGE(GrooveArc<2>(kRope, -0.2, 1, g), std::invalid_argument, "radius R = -0.2 m");
    EXPECT_THROW_MESSAGE(GrooveArc<2>(kRope, 0.2, 0, g), std::invalid_argument, "wrapSense = 0 must be +1 or -1");
    EXPECT_THROW_MESSAGE(GrooveArc<2>(kRope, 0.2, 1, Eigen::Vector2d(0.0, NAN)), std::invalid_argument,
                         "gravity must be finite");
    EXPECT_THROW_MESSAGE(GrooveArc<2>(RopeProperties{0.0, 1e7, 0.0}, 0.2, 1, g), std::invalid_argument,
                         "massPerLength");
    const GrooveArc<2> arc(kRope, 0.2, 1, g);
    GrooveArc<2>::Coordinates x = GrooveArc<2>::Coordinates::Zero(), xdot = x;
    x[GrooveArc<2>::lengthIndex()] = -0.01;
    GrooveArc<2>::Data data;
    EXPECT_THROW_MESSAGE(arc.evaluate(x, xdot, data), std::invalid_argument, "arc length l = -0.01 m must be >= 0");
    x[GrooveArc<2>::lengthIndex()] = 0.1;
    xdot[0] = INFINITY;
    EXPECT_THROW_MESSAGE(arc.evaluate(x, xdot, data), std::invalid_argument, "must be finite");
}
