// A TractionSheave with SheaveModel::Wrapped: the rope arrives and leaves at the groove's tangent
// points, and the capstan law uses the wrap angle of the current geometry, alpha = l / R
// (RopeModel::setSlipLaw), not one frozen at the start. A capstan Atwood machine over a held
// sheave: mass 1 hangs on a rail outside the sheave's tangent, so its fall leans by psi and
// alpha = pi - psi changes as it slips down. Checked against the closed-form tangent: the wrap
// angle, the stick limit e^(mu alpha), the force ratio in slip, and the energy balance with the
// friction work (which needs the law's derivative in l in the coupled solve). With
// SheaveModel::Point the same law takes the chords' turning angle of the current geometry.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <memory>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kMu = 0.2;
constexpr double kR = 0.3;       // the traction sheave's groove [m]
constexpr double kOffset = 0.6;  // mass 1's rail, this far outside the sheave's tangent x = -R [m]

// The lean psi of a fall from P = (-(R + e), y) up to its tangent point on a groove of radius R
// about the origin, turning clockwise over the top: (R + e) cos psi - |y| sin psi = R.
double lean(double e, double y) {
    const double rho = std::hypot(kR + e, y);
    return std::acos(kR / rho) - std::atan2(-y, kR + e);
}

struct WrappedAtwood {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Pin sheave;
    MobilizedBody::Slider mass1, mass2;  // along Ground's y: q is the height [m]
    State state;

    sr::SheaveModel model;

    WrappedAtwood(double m1, double m2, double givenWrapAngle = 0, sr::SheaveModel sheaveModel = sr::SheaveModel::Wrapped)
        : model(sheaveModel) {
        const Rotation slideUp(Pi / 2, ZAxis);
        sheave = MobilizedBody::Pin(matter.Ground(), Transform(), Body::Rigid(MassProperties(5, Vec3(0), Inertia(0.2))),
                                    Transform());
        mass1 = MobilizedBody::Slider(matter.Ground(), Transform(slideUp, Vec3(-(kR + kOffset), 0, 0)),
                                      Body::Rigid(MassProperties(m1, Vec3(0), Inertia(1))), Transform(slideUp));
        mass2 = MobilizedBody::Slider(matter.Ground(), Transform(slideUp, Vec3(kR, 0, 0)),
                                      Body::Rigid(MassProperties(m2, Vec3(0), Inertia(1))), Transform(slideUp));
        Motion::Steady(sheave, 0.0);  // held: its motion does no work
        reeving = std::make_unique<sr::ReevingSubsystem>(system);
        sr::RopeSpec rope;
        rope.sheaveModel = model;
        rope.start = sr::RopeAnchor{mass1, Vec3(0)};
        // Both masses at y = -5: mass 1's fall sqrt(rho^2 - R^2) to its tangent point, a quarter
        // turn less psi to the groove's top (s_ref, the material coordinate there), the rest of the
        // half turn and mass 2's vertical fall; 1e-4 shorter, so the rope starts taut.
        const double y0 = -5.0, psi = lean(kOffset, y0), rho = std::hypot(kR + kOffset, y0);
        const double fall1 = std::sqrt(rho * rho - kR * kR);
        double sRef = fall1 + kR * (0.5 * Pi - psi), length = fall1 + kR * (Pi - psi) - y0;
        if (model == sr::SheaveModel::Point) {  // both falls end at the sheave's centre
            sRef = rho;
            length = rho + std::hypot(kR, y0);
        }
        rope.sheaves = {sr::TractionSheave{sheave, kR, kMu, givenWrapAngle, sRef, 1, Vec3(0)}};
        rope.end = sr::RopeAnchor{mass2, Vec3(0)};
        rope.properties = {0.05, 1e7, 0.0, false};
        rope.unstretchedLength = length * (1 - 1e-4);
        rope.spanDefaults.axialModes = 1;
        rope.spanDefaults.transverseModes = 1;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        mass1.setOneQ(state, 0, y0);
        mass2.setOneQ(state, 0, y0);
        reeving->findStaticEquilibrium(state);  // in stick
    }
    double analyticWrapAngle(const State& s) const {
        const double y = mass1.getOneQ(s, 0);
        if (model == sr::SheaveModel::Wrapped) return Pi - lean(kOffset, y);
        // pi less the angle between the chords to the masses: atan((R + e) / |y|) + atan(R / |y2|).
        return Pi - std::atan2(kR + kOffset, -y) - std::atan2(kR, -mass2.getOneQ(s, 0));
    }
};

}  // namespace

// In stick at static equilibrium: the reported wrap angle is the closed form's pi - psi (measured
// 8.9e-16 rad; bound 1e-12), the stick limit e^(mu alpha) with it (4.4e-16; bound 1e-12), and the
// masses slip exactly when the force ratio exceeds that limit.
TEST(WrappedTractionSheave, StickLimitUsesTheGeometrysWrapAngle) {
    for (double m1 : {160.0, 200.0}) {
        WrappedAtwood a(m1, 100.0);
        a.system.realize(a.state, Stage::Position);
        const double alpha = a.analyticWrapAngle(a.state);
        EXPECT_LT(alpha, Pi - 0.05);  // the lean is real: 0.12 rad
        EXPECT_NEAR(a.reeving->getWrapAngle(a.state, 0, 1), alpha, 1e-12);
        EXPECT_NEAR(a.reeving->getRope(0).getTractionSheave(1).getTractionLimit(a.state), std::exp(kMu * alpha), 1e-12);
        const double ratio = a.reeving->getRope(0).getTractionSheave(1).getTractionRatio(a.state);
        const int slipping = a.reeving->updateTractionModes(a.state);
        EXPECT_EQ(slipping, ratio > std::exp(kMu * alpha) ? 1 : 0) << "m1 " << m1 << " ratio " << ratio;
        EXPECT_EQ(slipping, m1 > 180 ? 1 : 0);  // e^(mu alpha) = 1.83: 1.6 holds, 2.0 slips
    }
}

// Slipping for 1 s (mass 1 falls 0.77 m, its lean and so alpha change by 0.016 rad): at every
// report the ratio of the axial forces at the tangent points is e^(mu alpha) of that instant's
// geometry (measured 2.8e-11 relative; bound 1e-9) and the reported alpha the closed form's
// (measured 1.8e-15 rad; bound 1e-12). Energy: E(t) - E(0) + W_friction closes to 1.6e-10 of the
// friction work (RK-Merson 1e-9; bound 1e-8): without the law's column at l in the constraint
// Jacobian it misses by 1.7e-6.
TEST(WrappedTractionSheave, SlipKeepsTheCapstanRatioOfTheChangingWrapAngle) {
    WrappedAtwood a(250.0, 100.0);
    ASSERT_EQ(a.reeving->updateTractionModes(a.state), 1);
    a.system.realize(a.state, Stage::Velocity);
    const double e0 = a.reeving->calcMechanicalEnergy(a.state);
    RungeKuttaMersonIntegrator integ(a.system);
    integ.setAccuracy(1e-9);
    TimeStepper ts(a.system, integ);
    ts.initialize(a.state);
    double worstRatio = 0, worstAngle = 0, worstEnergy = 0, firstAlpha = NaN, lastAlpha = NaN;
    for (int i = 1; i <= 20; ++i) {
        ts.stepTo(0.05 * i);
        const State& s = integ.getState();
        a.system.realize(s, Stage::Velocity);
        ASSERT_EQ(a.reeving->getRope(0).getTractionSheave(1).getTractionMode(s), sr::TractionMode::SlipTowardStart) << s.getTime();
        const double alpha = a.analyticWrapAngle(s);
        if (i == 1) firstAlpha = alpha;
        lastAlpha = alpha;
        worstAngle = std::max(worstAngle, std::abs(a.reeving->getWrapAngle(s, 0, 1) - alpha));
        worstRatio = std::max(worstRatio, std::abs(a.reeving->getRope(0).getTractionSheave(1).getTractionRatio(s) / std::exp(kMu * alpha) - 1));
        const double wf = a.reeving->getRope(0).getTractionSheave(1).getFrictionWork(s), de = a.reeving->calcMechanicalEnergy(s) - e0;
        worstEnergy = std::max(worstEnergy, std::abs(de + wf) / wf);
        EXPECT_GT(a.reeving->getRope(0).getTractionSheave(1).getSlipRate(s), 0);
    }
    const State& s = integ.getState();
    std::printf("slip: alpha %.6f -> %.6f rad, mass 1 at %.3f m; worst ratio %.2e, angle %.2e rad, energy %.2e of "
                "W_friction %.3f J\n",
                firstAlpha, lastAlpha, a.mass1.getOneQ(s, 0), worstRatio, worstAngle, worstEnergy,
                a.reeving->getRope(0).getTractionSheave(1).getFrictionWork(s));
    EXPECT_GT(std::abs(lastAlpha - firstAlpha), 0.01);  // the geometry did change the law
    EXPECT_LE(worstRatio, 1e-9);
    EXPECT_LE(worstAngle, 1e-12);
    EXPECT_LE(worstEnergy, 1e-8);
}

// The point sheave (the paper's eq 30) takes the chords' turning angle of the current geometry:
// alpha = pi - atan((R + e) / |y1|) - atan(R / |y2|) (closed form). In stick the reported angle and
// limit match it (measured 4.4e-16 rad and 0; bound 1e-14) and the masses slip exactly past it;
// slipping for 1 s (alpha changes by 0.013 rad) the force ratio at the sheave is e^(mu alpha) of
// each instant (measured 8.1e-12; bound 1e-9), alpha the closed form's (measured 4.4e-16 rad; bound
// 1e-14), and E - E0 + W_friction closes to 1.7e-10 of W_friction (bound 1e-8); without the law's
// columns at the three node positions in the constraint Jacobian it misses by 1.7e-6.
TEST(WrappedTractionSheave, PointSheaveTakesTheChordsAngleOfTheCurrentGeometry) {
    for (double m1 : {160.0, 200.0}) {
        WrappedAtwood a(m1, 100.0, 0.0, sr::SheaveModel::Point);
        a.system.realize(a.state, Stage::Position);
        const double alpha = a.analyticWrapAngle(a.state);
        EXPECT_LT(alpha, Pi - 0.1);  // the chords lean: 0.24 rad
        EXPECT_NEAR(a.reeving->getWrapAngle(a.state, 0, 1), alpha, 1e-14);
        EXPECT_NEAR(a.reeving->getRope(0).getTractionSheave(1).getTractionLimit(a.state), std::exp(kMu * alpha), 1e-14);
        const double ratio = a.reeving->getRope(0).getTractionSheave(1).getTractionRatio(a.state);
        EXPECT_EQ(a.reeving->updateTractionModes(a.state), ratio > std::exp(kMu * alpha) ? 1 : 0) << ratio;
    }
    WrappedAtwood a(250.0, 100.0, 0.0, sr::SheaveModel::Point);
    ASSERT_EQ(a.reeving->updateTractionModes(a.state), 1);
    a.system.realize(a.state, Stage::Velocity);
    const double e0 = a.reeving->calcMechanicalEnergy(a.state);
    RungeKuttaMersonIntegrator integ(a.system);
    integ.setAccuracy(1e-9);
    TimeStepper ts(a.system, integ);
    ts.initialize(a.state);
    double worstRatio = 0, worstAngle = 0, worstEnergy = 0, firstAlpha = NaN, lastAlpha = NaN;
    for (int i = 1; i <= 20; ++i) {
        ts.stepTo(0.05 * i);
        const State& s = integ.getState();
        a.system.realize(s, Stage::Velocity);
        ASSERT_EQ(a.reeving->getRope(0).getTractionSheave(1).getTractionMode(s), sr::TractionMode::SlipTowardStart) << s.getTime();
        const double alpha = a.analyticWrapAngle(s);
        if (i == 1) firstAlpha = alpha;
        lastAlpha = alpha;
        worstAngle = std::max(worstAngle, std::abs(a.reeving->getWrapAngle(s, 0, 1) - alpha));
        worstRatio = std::max(worstRatio, std::abs(a.reeving->getRope(0).getTractionSheave(1).getTractionRatio(s) / std::exp(kMu * alpha) - 1));
        const double wf = a.reeving->getRope(0).getTractionSheave(1).getFrictionWork(s), de = a.reeving->calcMechanicalEnergy(s) - e0;
        worstEnergy = std::max(worstEnergy, std::abs(de + wf) / wf);
    }
    std::printf("point slip: alpha %.6f -> %.6f rad; worst ratio %.2e, angle %.2e rad, energy %.2e of W_friction\n",
                firstAlpha, lastAlpha, worstRatio, worstAngle, worstEnergy);
    EXPECT_GT(std::abs(lastAlpha - firstAlpha), 0.01);
    EXPECT_LE(worstRatio, 1e-9);
    EXPECT_LE(worstAngle, 1e-14);
    EXPECT_LE(worstEnergy, 1e-8);
}

// A given wrap angle (a double wrap, an arrangement the geometry does not show) stays the law's:
// 2.5 pi here, whatever the tangent points say.
TEST(WrappedTractionSheave, GivenWrapAngleOverridesTheGeometry) {
    WrappedAtwood a(250.0, 100.0, 2.5 * Pi);
    a.system.realize(a.state, Stage::Position);
    EXPECT_EQ(a.reeving->getWrapAngle(a.state, 0, 1), 2.5 * Pi);
    EXPECT_NEAR(a.reeving->getRope(0).getTractionSheave(1).getTractionLimit(a.state), std::exp(kMu * 2.5 * Pi), 1e-12);
    EXPECT_EQ(a.reeving->updateTractionModes(a.state), 0);  // 2.5 < e^(0.5 pi) = 4.8: holds
}

// The pin of a wrapped traction sheave must turn about the rope plane's normal relative to a body
// that keeps Ground's orientation (the groove's angles are measured in Ground): not on a rocker.
TEST(WrappedTractionSheave, PinOnAMovingBodyIsRejected) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Pin carrier(matter.Ground(), Transform(Vec3(0, 1, 0)), Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))),
                               Transform());
    MobilizedBody::Pin sheave(carrier, Transform(), Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))), Transform());
    MobilizedBody::Slider mass(matter.Ground(), Transform(Vec3(-1, -3, 0)),
                               Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))), Transform());
    sr::ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    sr::RopeSpec rope;
    rope.sheaveModel = sr::SheaveModel::Wrapped;
    rope.start = sr::RopeAnchor{mass, Vec3(0)};
    rope.sheaves = {sr::TractionSheave{sheave, kR, kMu, 0.0, 3.0, 1, Vec3(0)}};
    rope.end = sr::RopeAnchor{matter.Ground(), Vec3(1, -3, 0)};
    rope.properties = {0.05, 1e7, 0.0, false};
    rope.unstretchedLength = 7;
    rope.planeNormal = Vec3(0, 0, 1);
    EXPECT_THROW_MESSAGE(reeving.addRope(rope), std::invalid_argument,
                         "TractionSheave at node 1: with SheaveModel::Wrapped its pin's parent must be Ground or "
                         "translate without turning");
}
