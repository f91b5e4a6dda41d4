// A TurningSheave with SheaveModel::Wrapped: the rope grips its groove (no slip), the spans end at
// the tangent points and the rope on the arc turns with the sheave. The Atwood machine over it with
// a rope of mass rhoA: the masses hang 2R apart and accelerate as
//     (m1 + m2 + rhoA L + J / R^2) a = (m1 - m2) g + rhoA g (x1 - x2),
// the same over a frictionless wrapped DeviationSheave without J / R^2; energy is conserved; the
// material coordinate at the groove's top follows s_ref + sense R theta; bad input is rejected.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <memory>

using namespace SimbodyReeving;
using SimTK::MobilizedBody;
using SimTK::State;
using SimTK::Vec3;

namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

SimTK::Body::Rigid pointMass(double m) { return SimTK::Body::Rigid(SimTK::MassProperties(m, Vec3(0), SimTK::Inertia(1e-3 * m))); }
SimTK::Body::Rigid wheel(double J) { return SimTK::Body::Rigid(SimTK::MassProperties(1.0, Vec3(0), SimTK::Inertia(J, J, J))); }
// Frames whose x axis is Ground's y: a Slider along them moves vertically.
SimTK::Transform vertical(const Vec3& p) {
    const SimTK::Mat33 R(0, -1, 0,  //
                         1, 0, 0,   //
                         0, 0, 1);
    return SimTK::Transform(SimTK::Rotation(R, true), p);
}

/// Atwood machine over a wrapped sheave of radius R at the origin: m1 on a vertical slider at
/// x = -R hanging x1 below the centre (the rope's start), m2 at x = +R hanging x2 below (its end);
/// the rope runs up the left side, over the top (wrap sense -1 about +z) and down the right side.
/// J >= 0: a TurningSheave on a Ground Pin with inertia J, sense +1 (s_ref, the material
/// coordinate at the groove's top at pin angle 0, puts the masses there unstretched-consistently);
/// J < 0: a frictionless wrapped DeviationSheave on Ground.
struct Atwood {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -kG, 0)};
    std::unique_ptr<MobilizedBody::Slider> a, b;
    std::unique_ptr<MobilizedBody::Pin> pin;
    std::unique_ptr<ReevingSubsystem> reeving;
    double L = 0;

    Atwood(double m1, double m2, double J, double R, double x1, double x2, double rhoA, double EA,
           bool spatial = false) {
        a = std::make_unique<MobilizedBody::Slider>(matter.Ground(), vertical(Vec3(-R, -x1, 0)), pointMass(m1),
                                                    vertical(Vec3(0)));
        b = std::make_unique<MobilizedBody::Slider>(matter.Ground(), vertical(Vec3(R, -x2, 0)), pointMass(m2),
                                                    vertical(Vec3(0)));
        reeving = std::make_unique<ReevingSubsystem>(system, Vec3(0, -kG, 0));
        // The unstretched rope: its length stretched by the mean static tension (m1 + m2) g / 2.
        const double stretch = 1 + 0.5 * (m1 + m2) * kG / 2 / EA;
        L = (x1 + x2 + kPi * R) / stretch;
        RopeSpec spec;
        spec.start = RopeAnchor{*a, Vec3(0)};
        if (J >= 0) {
            pin = std::make_unique<MobilizedBody::Pin>(matter.Ground(), SimTK::Transform(), wheel(J), SimTK::Transform());
            spec.sheaves = {TurningSheave{*pin, R, (x1 + 0.5 * kPi * R) / stretch, 1}};
        } else {
            DeviationSheave d{matter.Ground(), Vec3(0), R};
            d.wrapSense = -1;
            d.axis = Vec3(0, 0, 1);  // (read for a spatial rope)
            spec.sheaves = {d};
        }
        spec.end = RopeAnchor{*b, Vec3(0)};
        spec.properties = RopeProperties{rhoA, EA, 0.0};
        spec.unstretchedLength = L;
        spec.spanDefaults.axialModes = 0;
        spec.spanDefaults.transverseModes = 0;
        spec.planeNormal = spatial ? Vec3(0) : Vec3(0, 0, 1);  // spatial: the groove turns about the pin axis
        spec.sheaveModel = SheaveModel::Wrapped;
        reeving->addRope(spec);
        system.realizeTopology();
    }
};

}  // namespace

// Rope on the groove at rest: the spans end at the tangent points (-R, 0) and (R, 0), the arc is
// half a turn, and the material coordinate where the rope arrives on the groove is
// s_ref + sense R theta - R pi / 2 (s_ref at the groove's top) at several pin angles, up to 9 rad
// (measured 0 m; bound 1e-12 m, the round-off of s at 1e-13 relative).
TEST(WrappedTurningSheave, RopeOnTheGrooveTurnsWithTheSheave) {
    const double R = 0.3;
    Atwood m(30, 20, 0.5, R, 5.0, 3.0, 1.0, 1e9);
    State s = m.system.getDefaultState();
    double worst = 0;
    for (double theta : {0.0, 0.7, -2.0, 9.0}) {
        m.pin->setAngle(s, theta);
        m.system.realize(s, SimTK::Stage::Position);
        const double sRef = std::get<TurningSheave>(m.reeving->getRopeSpec(0).sheaves[0]).materialCoordinateAtZeroAngle;
        worst = std::max(worst, std::abs(m.reeving->getMaterialCoordinate(s, 0, 1) - (sRef + R * theta - R * kPi / 2)));
        EXPECT_NEAR(m.reeving->getArcLength(s, 0, 1), kPi * R, 1e-12);
        EXPECT_NEAR(m.reeving->getWrapAngle(s, 0, 1), kPi, 1e-12);
    }
    EXPECT_LT(worst, 1e-12);
}

// Atwood machine, rope of 1 kg/m (8.9 kg, 0.94 kg of it on the arc) and EA = 1e9 N, from rest.
// Inextensible, m2's rise y obeys M y'' = F0 + k y with M = m1 + m2 + rhoA L (+ J / R^2 for a
// TurningSheave), F0 = (m1 - m2) g + rhoA g (x1 - x2) and k = 2 rhoA g (the rope's weight moving
// to the longer side), so y(t) = (F0 / k) (cosh(sqrt(k / M) t) - 1), whose initial acceleration is
// F0 / M. The simulated y at 0.5, 0.75 and 1 s against it, for a TurningSheave
// with J = 0.5 kg m^2 (J / R^2 = 5.6 kg) and a frictionless DeviationSheave: measured 2.0e-6 and
// 1.0e-6 relative (the stiff rope's bounce, about 1e-6 m); bound 1e-4 (50x).
// Without the arc's rope in the inertia y would be off by about 1.5e-2, without J / R^2 by 8.6e-2.
// The same with the rope spatial (no plane normal: two transverse directions, the grooves'
// axes their pin's or +z): the same bound.
TEST(WrappedTurningSheave, AtwoodMachineHasTheArcsRopeAndTheSheavesInertia) {
    const double m1 = 30, m2 = 20, R = 0.3, x1 = 5.0, x2 = 3.0, rhoA = 1.0, EA = 1e9;
    for (bool spatial : {false, true})
    for (double J : {0.5, -1.0}) {
        Atwood m(m1, m2, J, R, x1, x2, rhoA, EA, spatial);
        State s = m.system.getDefaultState();
        SimTK::RungeKuttaMersonIntegrator integ(m.system);
        integ.setAccuracy(1e-10);
        SimTK::TimeStepper ts(m.system, integ);
        ts.initialize(s);
        const double M = m1 + m2 + rhoA * m.L + (J >= 0 ? J / (R * R) : 0.0);
        const double F0 = (m1 - m2) * kG + rhoA * kG * (x1 - x2), k = 2 * rhoA * kG;
        double worst = 0;
        for (double t : {0.5, 0.75, 1.0}) {
            ts.stepTo(t);
            const double y = m.b->getOneQ(integ.getState(), 0);
            const double expected = F0 / k * (std::cosh(std::sqrt(k / M) * t) - 1);
            worst = std::max(worst, std::abs(y - expected) / expected);
        }
        std::printf("[ wrapped turning sheave ] %s J = %.1f: initial acceleration F0 / M = %.6f m/s^2, m2's rise "
                    "against the formula: %.2e relative at worst\n",
                    spatial ? "spatial" : "planar", J, F0 / M, worst);
        EXPECT_LT(worst, 1e-4) << "J = " << J << (spatial ? " spatial" : " planar");
    }
}

// Energy: the Atwood machine over the wrapped TurningSheave, started with the masses moving, for
// 2 s (RK-Merson, accuracy 1e-10): T + U of masses, sheave and rope (spans and the arc turning
// with the sheave) stays within 1.1e-12 of the initial kinetic energy (measured; bound 1e-10, 90x).
TEST(WrappedTurningSheave, AtwoodMachineConservesEnergy) {
    const double R = 0.3;
    Atwood m(30, 20, 0.5, R, 5.0, 3.0, 1.0, 1e7);
    State s = m.system.getDefaultState();
    m.b->setOneU(s, 0, 0.8);
    m.a->setOneU(s, 0, -0.8);
    m.pin->setOneU(s, 0, 0.8 / R);
    SimTK::RungeKuttaMersonIntegrator integ(m.system);
    integ.setAccuracy(1e-10);
    SimTK::TimeStepper ts(m.system, integ);
    ts.initialize(s);
    const double E0 = m.reeving->calcMechanicalEnergy(integ.getState());
    const double KE0 = m.system.calcKineticEnergy(integ.getState()) + m.reeving->calcRopeKineticEnergy(integ.getState());
    double worst = 0;
    for (int k = 1; k <= 200; ++k) {
        ts.stepTo(0.01 * k);
        worst = std::max(worst, std::abs(m.reeving->calcMechanicalEnergy(integ.getState()) - E0));
    }
    std::printf("[ wrapped turning sheave ] energy drift %.2e of KE0 = %.3f J over 2 s\n", worst / KE0, KE0);
    EXPECT_LT(worst, 1e-10 * KE0);
}

// Bad input: a wrapped TurningSheave whose pin axis is not the plane's normal, a wrapped
// TractionSheave whose pin's parent turns (here a rocker on a pin). A TurningSheave may sit on the
// rocker (its groove turns with it: test_wrapped_sheave_on_turning_body.cpp), and on a parent that
// only translates (a Slider carriage).
TEST(WrappedTurningSheave, RejectsPinsAcrossThePlaneAndTractionOnTurningParents) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    MobilizedBody::Pin rocker(matter.Ground(), SimTK::Transform(Vec3(0, 1, 0)), pointMass(10), SimTK::Transform());
    MobilizedBody::Pin onCarriage(rocker, SimTK::Transform(), wheel(0.1), SimTK::Transform());
    MobilizedBody::Slider carriage(matter.Ground(), SimTK::Transform(), pointMass(10), SimTK::Transform());
    MobilizedBody::Pin onSlider(carriage, SimTK::Transform(), wheel(0.1), SimTK::Transform());
    // A pin turning about Ground's x (its frames' z along x).
    const SimTK::Transform aboutX(SimTK::Rotation(SimTK::Mat33(0, 0, 1, 0, 1, 0, -1, 0, 0), true), Vec3(0));
    MobilizedBody::Pin tilted(matter.Ground(), aboutX, wheel(0.1), aboutX);
    RopeSpec spec;
    spec.start = RopeAnchor{matter.Ground(), Vec3(-0.2, -3, 0)};
    spec.end = RopeAnchor{matter.Ground(), Vec3(0.2, -3, 0)};
    spec.properties = RopeProperties{1.0, 1e7, 0.0};
    spec.unstretchedLength = 6.5;
    spec.planeNormal = Vec3(0, 0, 1);
    spec.sheaveModel = SheaveModel::Wrapped;
    TractionSheave traction;
    traction.body = onCarriage;
    traction.radius = 0.2;
    traction.frictionCoefficient = 0.2;
    spec.sheaves = {traction};
    EXPECT_THROW_MESSAGE(reeving.addRope(spec), std::invalid_argument,
                         "TractionSheave at node 1: with SheaveModel::Wrapped its pin's parent must be Ground or "
                         "translate without turning");
    spec.sheaves = {TurningSheave{tilted, 0.2, 3.3, 1}};
    EXPECT_THROW_MESSAGE(reeving.addRope(spec), std::invalid_argument,
                         "TurningSheave at node 1: with SheaveModel::Wrapped its pin axis (1, 0, 0) must be along the "
                         "rope's plane normal (0, 0, 1)");
    spec.sheaves = {TurningSheave{onSlider, 0.2, 3.3, 1}};
    EXPECT_NO_THROW(reeving.addRope(spec));
    spec.sheaves = {TurningSheave{onCarriage, 0.2, 3.3, 1}};
    EXPECT_NO_THROW(reeving.addRope(spec));
}
