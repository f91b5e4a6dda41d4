// SpanModel: mass matrix, quadratic-velocity, elastic and gravity forces against finite differences
// of the span's own energies; invariance; the n_a = 0 closed form; bad input.
#include "SimbodyReeving/element/SpanModel.h"
#include "support/ExpectThrowMessage.h"
#include "support/SpanTestSupport.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>

using namespace SimbodyReeving;
using SimbodyReeving::test::centralGradient;
using SimbodyReeving::test::randomState;
using SimbodyReeving::test::randomVelocity;
using SimbodyReeving::test::relativeError;

namespace {

const RopeProperties kRope{0.8, 2.0e4, 3.0, false};  // rhoA [kg/m], EA [N], EI [N m^2], the paper's linear law

template <int Dim>
Eigen::Matrix<double, Dim, 1> someGravity() {
    Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
    g[0] = 1.3;
    g[1] = -9.81;
    return g;
}

template <int Dim>
Eigen::Matrix<double, Dim, Dim> someReference() {
    if constexpr (Dim == 3)
        return makeReferenceFrame(Eigen::Vector3d(0.3, -1.0, 0.2), Eigen::Vector3d(0, 0, 1));
    else
        return Eigen::Matrix2d::Identity();
}

struct Config {
    int na, nt;
    VelocityModel velocity;
    ElasticEnergyModel elastic;
};

std::string describe(int dim, const Config& c) {
    return "Dim=" + std::to_string(dim) + " n_a=" + std::to_string(c.na) + " n_t=" + std::to_string(c.nt) +
           (c.velocity == VelocityModel::Complete ? " complete" : " simplified") +
           (c.elastic == ElasticEnergyModel::PaperLiteral ? " literal" : " consistent");
}

template <int Dim>
SpanModel<Dim> makeModel(const Config& c) {
    SpanOptions o;
    o.axialModes = c.na;
    o.transverseModes = c.nt;
    o.velocityModel = c.velocity;
    o.elasticModel = c.elastic;
    o.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting these bounds were measured with
    return SpanModel<Dim>(kRope, o, someGravity<Dim>(), someReference<Dim>());
}

std::vector<Config> allConfigs() {
    std::vector<Config> out;
    for (int na : {0, 1, 3})
        for (int nt : {0, 1, 2})
            for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete})
                for (auto em : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral})
                    out.push_back({na, nt, vm, em});
    return out;
}

template <int Dim>
double kinetic(const SpanModel<Dim>& m, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
    SpanData<Dim> d;
    m.evaluate(q, qd, d);
    return d.kineticEnergy;
}

// M symmetric positive definite and equal to the Hessian of T in the velocities;
// plus T = 1/2 qdot^T M qdot.
// Positive definiteness holds on every coordinate set a span is used with: nodes and modes with the
// material coordinates held (free ends), and modes and material coordinates with the nodes held
// (a span between sheaves). With *both* nodes and material coordinates free, the ALE description
// has a gauge direction: sliding the material along the chord while the nodes follow it
// (rdot1 = rdot2 = c e/l, sdot1 = sdot2 = c) moves no material point in the Simplified model (and
// only the transverse displacement in the Complete one), so the full M may be singular there.
template <int Dim>
void checkMassMatrix(const Config& c, int seed) {
    SCOPED_TRACE(describe(Dim, c));
    const auto model = makeModel<Dim>(c);
    std::mt19937 rng(seed);
    const Eigen::VectorXd q = randomState(model, rng);
    const Eigen::VectorXd qd = randomVelocity(model, rng);
    SpanData<Dim> d;
    model.evaluate(q, qd, d);
    const Eigen::MatrixXd M = d.massMatrix;
    const int n = model.numCoordinates();
    EXPECT_EQ((M - M.transpose()).cwiseAbs().maxCoeff(), 0.0);
    const int nq = model.s1Index();  // nodes and modes
    for (const Eigen::MatrixXd& sub :
         {Eigen::MatrixXd(M.topLeftCorner(nq, nq)), Eigen::MatrixXd(M.bottomRightCorner(n - 2 * Dim, n - 2 * Dim))}) {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sub);
        EXPECT_GT(eig.eigenvalues().minCoeff(), 1e-6 * eig.eigenvalues().maxCoeff());
    }
    {  // the gauge direction
        Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
        const Eigen::VectorXd e = q.segment<Dim>(Dim) - q.segment<Dim>(0);
        const double l = q[model.s2Index()] - q[model.s1Index()];
        g.segment<Dim>(0) = g.segment<Dim>(Dim) = e / l;
        g[model.s1Index()] = g[model.s2Index()] = 1.0;
        if (c.velocity == VelocityModel::Simplified) {
            EXPECT_LT(g.dot(M * g), 1e-14 * M.norm());  // measured 3.6e-16 |M|, margin 28x
        }
    }
    // Measured 5.9e-16 relative; margin 51x.
    EXPECT_NEAR(d.kineticEnergy, 0.5 * qd.dot(M * qd), 3e-14 * d.kineticEnergy);

    const double h = 1e-2;  // T is exactly quadratic in qdot: the difference is exact but for round-off
    Eigen::MatrixXd H(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Eigen::VectorXd v = qd;
            auto T = [&](double di, double dj) {
                v = qd;
                v[i] += di;
                v[j] += dj;
                return kinetic(model, q, v);
            };
            H(i, j) = (T(h, h) - T(h, -h) - T(-h, h) + T(-h, -h)) / (4 * h * h);
        }
    // Measured 8.7e-12; margin 57x.
    EXPECT_LT((H - M).cwiseAbs().maxCoeff() / M.cwiseAbs().maxCoeff(), 5e-10);
}

// Q_v = -Mdot qdot + dT/dq (eq 17): the Lagrangian consistency that makes T + U invariant.
template <int Dim>
void checkVelocityForces(const Config& c, int seed) {
    SCOPED_TRACE(describe(Dim, c));
    const auto model = makeModel<Dim>(c);
    std::mt19937 rng(seed);
    const Eigen::VectorXd q = randomState(model, rng);
    const Eigen::VectorXd qd = randomVelocity(model, rng);
    SpanData<Dim> d, dp, dm;
    model.evaluate(q, qd, d);
    const double h = 1e-6;
    model.evaluate(q + h * qd, qd, dp);
    model.evaluate(q - h * qd, qd, dm);
    const Eigen::VectorXd MdotQd = (dp.massMatrix - dm.massMatrix) * qd / (2 * h);
    const Eigen::VectorXd dTdq = centralGradient([&](const Eigen::VectorXd& x) { return kinetic(model, x, qd); }, q, h);
    const Eigen::VectorXd expected = -MdotQd + dTdq;
    // Measured 1.1e-9; margin 46x.
    EXPECT_LT(relativeError(Eigen::VectorXd(d.velocityForces), expected), 5e-8)
        << "Q_v   = " << d.velocityForces.transpose() << "\nFD    = " << expected.transpose();
}

// Q_elastic = -dU/dq and Q_gravity = -dU_g/dq by central differences.
template <int Dim>
void checkConservativeForces(const Config& c, int seed) {
    SCOPED_TRACE(describe(Dim, c));
    const auto model = makeModel<Dim>(c);
    std::mt19937 rng(seed);
    const Eigen::VectorXd q = randomState(model, rng);
    const Eigen::VectorXd qd = Eigen::VectorXd::Zero(model.numCoordinates());
    SpanData<Dim> d;
    model.evaluate(q, qd, d);
    auto energy = [&](bool strain) {
        return [&, strain](const Eigen::VectorXd& x) {
            SpanData<Dim> dd;
            model.evaluate(x, qd, dd);
            return strain ? dd.strainEnergy() : dd.gravityEnergy;
        };
    };
    const double h = 1e-5;
    const Eigen::VectorXd gradU = centralGradient(energy(true), q, h);
    const Eigen::VectorXd gradUg = centralGradient(energy(false), q, h);
    EXPECT_LT(relativeError(Eigen::VectorXd(d.elasticForces), -gradU), 1e-6)
        << "Q_el = " << d.elasticForces.transpose() << "\n-dU  = " << -gradU.transpose();
    // Measured 4.8e-11; margin 41x.
    EXPECT_LT(relativeError(Eigen::VectorXd(d.gravityForces), -gradUg), 2e-9)
        << "Q_g  = " << d.gravityForces.transpose() << "\n-dUg = " << -gradUg.transpose();
}

}  // namespace

TEST(SpanModel, MassMatrixIsSpdAndTheVelocityHessianOfT) {
    int seed = 1;
    for (const Config& c : allConfigs()) {
        checkMassMatrix<2>(c, seed++);
        checkMassMatrix<3>(c, seed++);
    }
}

TEST(SpanModel, VelocityForcesAreMinusMdotQdotPlusDTdq) {
    int seed = 100;
    for (const Config& c : allConfigs()) {
        checkVelocityForces<2>(c, seed++);
        checkVelocityForces<3>(c, seed++);
    }
}

TEST(SpanModel, ElasticAndGravityForcesAreMinusEnergyGradients) {
    int seed = 200;
    for (const Config& c : allConfigs()) {
        checkConservativeForces<2>(c, seed++);
        checkConservativeForces<3>(c, seed++);
    }
}

// Rigid translation and rotation of an unstrained span: zero elastic force.
TEST(SpanModel, RigidMotionOfUnstrainedSpanGivesZeroElasticForce) {
    for (const Config& c : allConfigs()) {
        SCOPED_TRACE(describe(3, c));
        const auto model = makeModel<3>(c);
        const double L = 2.5;
        Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates());
        const Eigen::Vector3d i0 = model.referenceFrame().col(0);
        for (int trial = 0; trial < 8; ++trial) {
            const Eigen::Matrix3d R =
                Eigen::AngleAxisd(0.35 * trial, Eigen::Vector3d(1, 2 - trial, 0.5 * trial).normalized())
                    .toRotationMatrix();
            const Eigen::Vector3d r1(1.0 - trial, 2.0 + 0.5 * trial, -3.0 * trial);
            q.segment<3>(0) = r1;
            q.segment<3>(3) = r1 + L * (R * i0);
            q[model.s1Index()] = 0.7 * trial;
            q[model.s2Index()] = 0.7 * trial + L;
            SpanData<3> d;
            model.evaluate(q, Eigen::VectorXd::Zero(model.numCoordinates()), d);
            // Measured 1.1e-11 N = 5.6e-16 EA; margin 54x.
            EXPECT_LE(d.elasticForces.cwiseAbs().maxCoeff(), 3e-14 * kRope.axialStiffness);
        }
    }
    for (const Config& c : allConfigs()) {  // planar
        SCOPED_TRACE(describe(2, c));
        const auto model = makeModel<2>(c);
        Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates());
        for (int trial = 0; trial < 8; ++trial) {
            const double th = 0.8 * trial;
            q.segment<2>(0) = Eigen::Vector2d(trial, -2.0 * trial);
            q.segment<2>(2) = q.segment<2>(0) + 1.5 * Eigen::Vector2d(std::cos(th), std::sin(th));
            q[model.s2Index()] = 1.5;
            SpanData<2> d;
            model.evaluate(q, Eigen::VectorXd::Zero(model.numCoordinates()), d);
            // Measured 7.8e-12 N = 3.9e-16 EA; margin 77x.
            EXPECT_LE(d.elasticForces.cwiseAbs().maxCoeff(), 3e-14 * kRope.axialStiffness);
        }
    }
}

// With n_a = 0 the axial force is the closed form
//   P(s) = EA/2 ((|e|^2 + |u'_perp(xi)|^2) / l^2 - 1)
// (chord length |e| and l = s2 - s1; the transverse slope term vanishes when there are no transverse
// modes), and the quadrature energy equals the closed-form integral.
TEST(SpanModel, AxialForceWithoutAxialModesMatchesClosedForm) {
    const double pi = std::acos(-1.0);
    for (int nt : {0, 1, 2}) {
        SpanOptions o;
        o.axialModes = 0;
        o.transverseModes = nt;
        const SpatialSpanModel model(kRope, o, Eigen::Vector3d::Zero(),
                                     makeReferenceFrame(Eigen::Vector3d(1, 0.2, -0.1)));
        std::mt19937 rng(7 + nt);
        const Eigen::VectorXd q = randomState(model, rng, 3.0);
        const double s1 = q[model.s1Index()], s2 = q[model.s2Index()], l = s2 - s1;
        const double chord2 = (q.segment<3>(3) - q.segment<3>(0)).squaredNorm();
        for (int k = 0; k <= 20; ++k) {
            const double xi = k / 20.0;
            double slope2 = 0;
            for (int dir = 0; dir < 2; ++dir) {
                double sl = 0;
                for (int i = 0; i < nt; ++i)
                    sl += q[model.transverseModeIndex(dir, i)] * (i + 1) * pi * std::cos((i + 1) * pi * xi);
                slope2 += sl * sl;
            }
            const double closed = 0.5 * kRope.axialStiffness * ((chord2 + slope2) / (l * l) - 1.0);
            const double P = model.axialForce(q, s1 + xi * l);
            // Measured 4.4e-15 relative; margin 46x.
            EXPECT_NEAR(P, closed, 2e-13 * std::abs(closed)) << "n_t=" << nt << " xi=" << xi;
        }
        if (nt == 0) {
            SpanData<3> d;
            model.evaluate(q, Eigen::VectorXd::Zero(q.size()), d);
            const double eps = 0.5 * (chord2 / (l * l) - 1.0);
            EXPECT_NEAR(d.axialEnergy, 0.5 * kRope.axialStiffness * eps * eps * l, 1e-12 * d.axialEnergy);
        }
    }
}

// The automatic quadrature rule is exact to round-off: compare with 150 points.
TEST(SpanModel, AutomaticQuadratureMatchesMuchHigherOrder) {
    for (int na : {0, 1, 3, 8, 16})
        for (int nt : {0, 1, 2, 8, 16})
            for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete}) {
                SCOPED_TRACE("n_a=" + std::to_string(na) + " n_t=" + std::to_string(nt));
                SpanOptions o;
                o.axialModes = na;
                o.transverseModes = nt;
                o.velocityModel = vm;
                o.elasticModel = ElasticEnergyModel::PaperLiteral;  // the richest integrand
                o.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting these bounds were measured with
                const SpatialSpanModel autoModel(kRope, o, someGravity<3>(), someReference<3>());
                o.quadraturePoints = 150;
                const SpatialSpanModel refModel(kRope, o, someGravity<3>(), someReference<3>());
                std::mt19937 rng(na * 31 + nt);
                const Eigen::VectorXd q = randomState(autoModel, rng);
                const Eigen::VectorXd qd = randomVelocity(autoModel, rng);
                SpanData<3> a, r;
                autoModel.evaluate(q, qd, a);
                refModel.evaluate(q, qd, r);
                EXPECT_LT((a.massMatrix - r.massMatrix).cwiseAbs().maxCoeff() / r.massMatrix.cwiseAbs().maxCoeff(), 1e-13);
                EXPECT_LT(relativeError(Eigen::VectorXd(a.velocityForces), Eigen::VectorXd(r.velocityForces)), 1e-12);
                EXPECT_LT(relativeError(Eigen::VectorXd(a.elasticForces), Eigen::VectorXd(r.elasticForces)), 1e-12);
                EXPECT_NEAR(a.strainEnergy(), r.strainEnergy(), 1e-13 * r.strainEnergy());
                EXPECT_NEAR(a.kineticEnergy, r.kineticEnergy, 1e-13 * r.kineticEnergy);
            }
}

// A planar span and a spatial span in the plane z = 0 with k0 = z describe the same physics: the
// planar one just skips the out-of-plane work.
TEST(SpanModel, PlanarSpanEqualsInPlaneSpatialSpan) {
    SpanOptions o;
    o.axialModes = 2;
    o.transverseModes = 2;
    o.velocityModel = VelocityModel::Complete;
    o.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting these bounds were measured with
    const PlanarSpanModel planar(kRope, o, Eigen::Vector2d(0.5, -9.81));
    const SpatialSpanModel spatial(kRope, o, Eigen::Vector3d(0.5, -9.81, 0),
                                   makeReferenceFrame(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1)));
    std::mt19937 rng(3);
    const Eigen::VectorXd q2 = randomState(planar, rng), qd2 = randomVelocity(planar, rng);
    // Map planar -> spatial coordinates (z = 0, out-of-plane modes 0).
    auto lift = [&](const Eigen::VectorXd& x2) {
        Eigen::VectorXd x3 = Eigen::VectorXd::Zero(spatial.numCoordinates());
        x3.segment<2>(0) = x2.segment<2>(0);
        x3.segment<2>(3) = x2.segment<2>(2);
        for (int i = 0; i < 2; ++i) {
            x3[spatial.axialModeIndex(i)] = x2[planar.axialModeIndex(i)];
            x3[spatial.transverseModeIndex(0, i)] = x2[planar.transverseModeIndex(0, i)];
        }
        x3[spatial.s1Index()] = x2[planar.s1Index()];
        x3[spatial.s2Index()] = x2[planar.s2Index()];
        return x3;
    };
    SpanData<2> d2;
    SpanData<3> d3;
    planar.evaluate(q2, qd2, d2);
    spatial.evaluate(lift(q2), lift(qd2), d3);
    EXPECT_NEAR(d2.kineticEnergy, d3.kineticEnergy, 1e-12 * d3.kineticEnergy);
    EXPECT_NEAR(d2.strainEnergy(), d3.strainEnergy(), 1e-12 * d3.strainEnergy());
    EXPECT_NEAR(d2.gravityEnergy, d3.gravityEnergy, 1e-12 * std::abs(d3.gravityEnergy));
    const Eigen::VectorXd Q2 = d2.velocityForces + d2.elasticForces + d2.gravityForces;
    const Eigen::VectorXd Q3 = d3.velocityForces + d3.elasticForces + d3.gravityForces;
    EXPECT_LT(relativeError(lift(Q2), Q3), 1e-12);
}

// Bad input throws std::invalid_argument naming the parameter and its value ("name = value").
TEST(SpanModel, BadInputThrowsNamingParameterAndValue) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    // Every fragment of the words must be in the message.
    auto expectThrow = [](auto&& f, std::initializer_list<std::string> words) {
        for (const std::string& w : words) EXPECT_THROW_MESSAGE(f(), std::invalid_argument, w);
    };
    const SpanOptions good;
    const Eigen::Vector2d g(0, -9.81);
    for (double bad : {0.0, -1.0, nan, inf}) {
        std::ostringstream v;
        v << bad;
        expectThrow([&] { PlanarSpanModel({bad, 1e4, 1}, good, g); },
                    {"RopeProperties: massPerLength (rhoA) [kg/m] = " + v.str() + " must be finite and > 0"});
        expectThrow([&] { PlanarSpanModel({1, bad, 1}, good, g); },
                    {"RopeProperties: axialStiffness (EA) [N] = " + v.str() + " must be finite and > 0"});
    }
    for (double bad : {-1.0, nan, inf}) {
        std::ostringstream v;
        v << bad;
        expectThrow([&] { PlanarSpanModel({1, 1e4, bad}, good, g); },
                    {"RopeProperties: bendingStiffness (EI) [N m^2] = " + v.str() + " must be finite and >= 0"});
    }
    for (int bad : {-1, 17}) {
        SpanOptions o;
        o.axialModes = bad;
        expectThrow([&] { PlanarSpanModel({1, 1e4, 1}, o, g); },
                    {"SpanModel: SpanOptions::axialModes (n_a) = " + std::to_string(bad) + " is outside 0.."});
        o = SpanOptions{};
        o.transverseModes = bad;
        expectThrow([&] { PlanarSpanModel({1, 1e4, 1}, o, g); },
                    {"SpanModel: SpanOptions::transverseModes (n_t) = " + std::to_string(bad) + " is outside 0.."});
    }
    expectThrow([&] { PlanarSpanModel({1, 1e4, 1}, good, Eigen::Vector2d(0, nan)); },
                {"SpanModel: gravity [m/s^2] = (", "nan) must be finite"});
    expectThrow([&] { SpatialSpanModel({1, 1e4, 1}, good, Eigen::Vector3d::Zero(), 2 * Eigen::Matrix3d::Identity()); },
                {"SpanModel: referenceFrame = [2 0 0; ...]", "must be orthonormal and right-handed"});

    const PlanarSpanModel model({1, 1e4, 1}, good, g);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates());
    const Eigen::VectorXd qd = q;
    q.segment<2>(2) = Eigen::Vector2d(1, 0);
    q[model.s2Index()] = 1.0;
    SpanData<2> d;
    EXPECT_NO_THROW(model.evaluate(q, qd, d));
    for (double bad : {1.0, 1.5}) {  // s2 <= s1: l = 0 and l = -0.5
        Eigen::VectorXd qb = q;
        qb[model.s1Index()] = bad;
        std::ostringstream v;
        v << 1.0 - bad;
        expectThrow([&] { model.evaluate(qb, qd, d); },
                    {"SpanModel::evaluate: span length l = s2 - s1 [m] = " + v.str() + " must be > 0"});
    }
    {
        Eigen::VectorXd qb = q;
        qb.segment<2>(2) = qb.segment<2>(0);
        expectThrow([&] { model.evaluate(qb, qd, d); },
                    {"SpanModel::evaluate: chord r2 - r1 [m] = (0 0) is zero: end nodes coincide"});
    }
    {
        Eigen::VectorXd qb = q;
        qb[1] = nan;
        expectThrow([&] { model.evaluate(qb, qd, d); }, {"SpanModel: q[1] = nan must be finite"});
        expectThrow([&] { model.evaluate(q, qb, d); }, {"SpanModel: qdot[1] = nan must be finite"});
        expectThrow([&] { model.evaluate(q.head(3), qd, d); },
                    {"SpanModel: size of q = 3 differs from numCoordinates() = " +
                     std::to_string(model.numCoordinates())});
    }
    expectThrow([&] { model.axialForce(q, 1.5); },
                {"SpanModel: material coordinate s [m] = 1.5 is outside the span [s1, s2] = [0, 1]"});
}

// End strain: value, gradient, rate and acceleration bias against finite differences.
TEST(SpanModel, EndStrainDerivativesMatchFiniteDifferences) {
    for (const Config& c : allConfigs()) {
        SCOPED_TRACE(describe(3, c));
        const auto model = makeModel<3>(c);
        std::mt19937 rng(77 + c.na * 3 + c.nt);
        const Eigen::VectorXd q = randomState(model, rng), qd = randomVelocity(model, rng);
        for (SpanEnd end : {SpanEnd::First, SpanEnd::Second}) {
            auto eps = [&](const Eigen::VectorXd& x) {
                return model.strain(x, end == SpanEnd::First ? x[model.s1Index()] : x[model.s2Index()]);
            };
            EndStrain<3> es;
            model.endStrain(q, qd, end, es);
            EXPECT_NEAR(es.strain, eps(q), 1e-15);
            const Eigen::VectorXd g = centralGradient(eps, q, 1e-6);
            // Measured 2.2e-10; margin 46x.
            EXPECT_LT(relativeError(Eigen::VectorXd(es.gradient), g), 1e-8);
            EXPECT_NEAR(es.rate, es.gradient.dot(qd), 1e-13 * std::abs(es.rate) + 1e-15);
            const double h = 1e-4;
            const double fd = (eps(q + h * qd) - 2 * eps(q) + eps(q - h * qd)) / (h * h);
            EXPECT_NEAR(es.accelerationBias, fd, 1e-5 * std::abs(fd) + 1e-7);
        }
    }
}
