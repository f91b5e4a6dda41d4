// Wrapped deviation sheaves in Simbody scenes (RopeSpec::sheaveModel = SheaveModel::Wrapped): a
// free hook block hung in two falls from Ground anchors a diameter apart. Its static equilibrium
// centres it under the anchors (the falls vertical) where a point sheave would hang it at the same
// place with both falls leaning; pushed, it swings and bounces with the rope on its groove (wrap
// angle, tangent points and arc moving with it) and the system's T + U is conserved.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>

using SimbodyReeving::DeviationSheave;
using SimbodyReeving::ReevingSubsystem;
using SimbodyReeving::RopeAnchor;
using SimbodyReeving::RopeProperties;
using SimbodyReeving::RopeSpec;
using SimbodyReeving::SheaveModel;
using SimbodyReeving::SpanOptions;
using SimTK::Inertia;
using SimTK::MassProperties;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Transform;
using SimTK::Vec3;

namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;
const RopeProperties kTable1{0.6205, 16.5e6, 30.9};  // rhoA [kg/m], EA [N], EI [N m^2]

struct World {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -kG, 0)};
    ReevingSubsystem reeving{system, Vec3(0, -kG, 0)};
};

// A 1000 kg block (translating and turning in the plane) on a sheave of radius R at its origin,
// hung from Ground anchors at (0, 0) and (2R, 0): rope anchor -> under the sheave -> anchor.
struct TwoFallBlock {
    World w;
    MobilizedBody::Planar block;
    static constexpr double R = 0.5, M = 1000.0, depth = 20.0;
    explicit TwoFallBlock(SheaveModel model, SimbodyReeving::AxialDynamics axial)
        : block(w.matter.updGround(), Transform(), SimTK::Body::Rigid(MassProperties(M, Vec3(0), Inertia(20))),
                Transform()) {
        RopeSpec rope;
        rope.name = "two falls";
        rope.start = RopeAnchor{w.matter.Ground(), Vec3(0)};
        DeviationSheave sheave{block, Vec3(0), R};
        sheave.wrapSense = 1;  // left fall down, under the groove, right fall up: counter-clockwise about +z
        rope.sheaves = {sheave};
        rope.end = RopeAnchor{w.matter.Ground(), Vec3(2 * R, 0, 0)};
        rope.properties = kTable1;
        rope.unstretchedLength = model == SheaveModel::Wrapped ? 2 * depth + kPi * R : 2 * depth + 2 * R;
        SpanOptions o;
        o.axialModes = 1;
        o.transverseModes = 1;
        o.axialDynamics = axial;
        rope.spanDefaults = o;
        rope.planeNormal = Vec3(0, 0, 1);
        rope.sheaveModel = model;
        w.reeving.addRope(rope);
        w.system.realizeTopology();
    }
};

}  // namespace

// The block's depth from the rope's stretch and weight, computed here (the falls straight; their
// transverse sag changes a fall's length by 8 f^2 / (3 h) ~ 3e-7 m at most). The energy EA eps^2 / 2
// per metre of material, eps = (lambda^2 - 1) / 2 the Green strain, makes the force in the rope
// T = EA eps lambda; a fall of material length sigma_f with the force T_b at its lower end and the
// weight rhoA g c of each metre of material above it (c the cosine of its lean) is
//   h = int_0^sigma_f lambda(T_b + rhoA g c sigma) dsigma  long,  lambda(T) solving EA eps lambda = T
// (Newton at each of Simpson's 401 points; lambda is nearly linear in sigma, so the rule's error
// lies far below the bounds).
//  - Wrapped: two vertical falls (c = 1) of sigma_f = h0 (L = 2 h0 + pi R: the half-turn on the
//    groove is pi R of material) carry the block and the rope on its groove, 2 T_b = (M + rhoA pi R) g;
//    the centre lies h below the anchors.
//  - Point: each fall leans by theta = atan(R / d) to the block's origin at depth d, sigma_f =
//    h0 + R, 2 T_b cos(theta) = M g, and sags under rhoA g sin(theta) across it (its chord
//    shorter than h by w^2 h^3 / (24 T^2), 3.2e-7 m); d = sqrt(chord^2 - R^2) by fixed point.
// Depths 20.0060 m wrapped (6 mm of stretch) and 20.5001 m with the point sheave. The model against
// them (static equilibrium to 1e-10 relative, measured 1e-13): wrapped 2.2e-12 m (bound 1e-10 m);
// point 5.1e-8 m, what one sine mode leaves of the parabolic sag (bound 1e-6 m). Taking the force
// as EA eps (without lambda) puts the depths 1.8e-6 m off; the sag 2.7e-7 m. The sideways
// position: midway by symmetry, to 1e-9 m.
double stretchUnderForce(double force) {
    const double EA = kTable1.axialStiffness;
    double lambda = 1 + force / EA;
    for (int i = 0; i < 30; ++i) {  // f(lambda) = EA (lambda^3 - lambda) / 2 - T, f' = EA (3 lambda^2 - 1) / 2
        const double f = 0.5 * EA * (lambda * lambda * lambda - lambda) - force;
        lambda -= f / (0.5 * EA * (3 * lambda * lambda - 1));
    }
    return lambda;
}

double fallLength(double lowerForce, double leanCosine, double materialLength) {
    const int n = 400;  // Simpson's rule over n intervals
    const double w = kTable1.massPerLength * kG * leanCosine, step = materialLength / n;
    double sum = 0;
    for (int i = 0; i <= n; ++i)
        sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * stretchUnderForce(lowerForce + w * step * i);
    return sum * step / 3;
}

TEST(WrappedSheaves, BlockHungInTwoFallsHangsAtTheClosedFormDepth) {
    const double R = TwoFallBlock::R, h0 = TwoFallBlock::depth, M = TwoFallBlock::M, rhoA = kTable1.massPerLength;
    for (SheaveModel model : {SheaveModel::Wrapped, SheaveModel::Point}) {
        TwoFallBlock scene(model, SimbodyReeving::AxialDynamics::QuasiStatic);
        State s = scene.w.system.getDefaultState();
        scene.block.setQToFitTranslation(s, Vec3(0.45, -20.05, 0));
        const double residual = scene.w.reeving.findStaticEquilibrium(s, 1e-10);
        scene.w.system.realize(s, Stage::Position);
        const Vec3 p = scene.block.getBodyOriginLocation(s);
        double depth = 0;
        if (model == SheaveModel::Wrapped) {
            depth = fallLength(0.5 * (M + rhoA * kPi * R) * kG, 1.0, h0);
        } else {
            depth = h0 + R;
            for (int i = 0; i < 50; ++i) {
                const double c = depth / std::hypot(R, depth);
                const double lowerForce = 0.5 * M * kG / c, h = fallLength(lowerForce, c, h0 + R);
                // The fall sags under its weight across it, w = rhoA g sin(theta): its chord is
                // shorter than its length by w^2 h^3 / (24 T^2) (a shallow parabola, T the mean force).
                const double across = rhoA * kG * R / std::hypot(R, depth),
                             meanForce = lowerForce + 0.5 * rhoA * kG * c * (h0 + R),
                             chord = h - across * across * h * h * h / (24 * meanForce * meanForce);
                depth = std::sqrt(chord * chord - R * R);
            }
        }
        std::printf("[ two falls, %s ] residual %.2e, block at (%.12f, %.9f), closed-form depth %.9f (%.1e m off), "
                    "angle %.3e rad\n",
                    model == SheaveModel::Wrapped ? "wrapped" : "point", residual, p[0], p[1], depth,
                    std::abs(-p[1] - depth), scene.block.getQ(s)[0]);
        ASSERT_LE(residual, 1e-10);
        EXPECT_NEAR(p[0], TwoFallBlock::R, 1e-9);  // symmetric either way
        EXPECT_NEAR(-p[1], depth, model == SheaveModel::Wrapped ? 1e-10 : 1e-6);
    }
}

// Energy: the block pushed sideways swings and bounces in its falls for 5 s (RK-Merson, accuracy
// 1e-10); T + U of block and rope (spans and arc) stays within 2.5e-12 of the initial kinetic
// energy (measured; bound 1e-10, 40x) while the block swings over a metre.
TEST(WrappedSheaves, SwingingBlockConservesEnergy) {
    TwoFallBlock scene(SheaveModel::Wrapped, SimbodyReeving::AxialDynamics::Dynamic);
    State s = scene.w.system.getDefaultState();
    scene.block.setQToFitTranslation(s, Vec3(0.5, -20.02, 0));
    ASSERT_LE(scene.w.reeving.findStaticEquilibrium(s, 1e-10), 1e-10);
    scene.block.setUToFitLinearVelocity(s, Vec3(0.5, 0.05, 0));
    scene.w.system.realize(s, Stage::Velocity);
    const double KE0 = scene.w.system.calcKineticEnergy(s) + scene.w.reeving.calcRopeKineticEnergy(s);
    const double E0 = scene.w.reeving.calcMechanicalEnergy(s);
    SimTK::RungeKuttaMersonIntegrator integ(scene.w.system);
    integ.setAccuracy(1e-10);
    SimTK::TimeStepper ts(scene.w.system, integ);
    ts.initialize(s);
    double drift = 0, minX = 1e9, maxX = -1e9;
    for (int k = 1; k <= 20; ++k) {
        ts.stepTo(0.25 * k);
        const State& st = ts.getState();
        scene.w.system.realize(st, Stage::Velocity);
        drift = std::max(drift, std::abs(scene.w.reeving.calcMechanicalEnergy(st) - E0));
        const double x = scene.block.getBodyOriginLocation(st)[0];
        minX = std::min(minX, x);
        maxX = std::max(maxX, x);
    }
    std::printf("[ two falls, wrapped ] drift/KE0 = %.3e over 5 s, swing x in [%.4f, %.4f], %d steps\n", drift / KE0,
                minX, maxX, integ.getNumStepsTaken());
    EXPECT_LT(drift / KE0, 1e-10);
    EXPECT_GT(maxX - minX, 0.5);
}

// A spatial rope's wrapped sheave needs its groove's axis (none given here); a wrap sense must be +-1.
TEST(WrappedSheaves, RejectsSpatialSheavesWithoutAnAxisAndBadSenses) {
    World w;
    const MobilizedBody::Planar block(w.matter.updGround(), Transform(),
                                      SimTK::Body::Rigid(MassProperties(10, Vec3(0), Inertia(1))), Transform());
    RopeSpec rope;
    rope.start = RopeAnchor{w.matter.Ground(), Vec3(0)};
    rope.sheaves = {DeviationSheave{block, Vec3(0), 0.2}};
    rope.end = RopeAnchor{w.matter.Ground(), Vec3(0.4, 0, 0)};
    rope.properties = kTable1;
    rope.unstretchedLength = 10;
    rope.sheaveModel = SheaveModel::Wrapped;
    EXPECT_THROW_MESSAGE(w.reeving.addRope(rope), std::invalid_argument,
                         "sheave 1 axis = (0, 0, 0) (|axis| = 0.000000) must be a unit vector");
    rope.planeNormal = Vec3(0, 0, 1);
    DeviationSheave bad{block, Vec3(0), 0.2};
    bad.wrapSense = 0;
    rope.sheaves = {bad};
    EXPECT_THROW_MESSAGE(w.reeving.addRope(rope), std::invalid_argument, "sheave 1 wrap sense = 0 must be +1 or -1");
}

namespace {

// The paper's pendulum (rope from a Ground anchor at the origin over a Ground sheave at (3, 0, 0),
// 1000 kg payload 20 m below, pushed at 1 m/s) with a sheave of radius R, wrapped or a point:
// the payload's position at rest (static equilibrium) and after 2 s.
struct PendulumRun {
    Vec3 atRest, after;
};

PendulumRun pendulumOverTwoSeconds(SheaveModel model, double R) {
    World w;
    MobilizedBody::Planar payload(w.matter.updGround(), Transform(),
                                  SimTK::Body::Rigid(MassProperties(1000, Vec3(0), Inertia(36))), Transform());
    RopeSpec rope;
    rope.start = RopeAnchor{w.matter.Ground(), Vec3(0)};
    DeviationSheave sheave{w.matter.Ground(), Vec3(3, 0, 0), R};
    sheave.wrapSense = -1;  // along the top and down the far side: clockwise about +z
    rope.sheaves = {sheave};
    rope.end = RopeAnchor{payload, Vec3(0)};
    rope.properties = kTable1;
    rope.unstretchedLength = 23.0;
    SpanOptions o;
    o.axialModes = 1;
    o.transverseModes = 1;
    rope.spanDefaults = o;
    rope.planeNormal = Vec3(0, 0, 1);
    rope.sheaveModel = model;
    w.reeving.addRope(rope);
    w.system.realizeTopology();
    State s = w.system.getDefaultState();
    payload.setQToFitTranslation(s, Vec3(3 + (model == SheaveModel::Wrapped ? R : 0.0), -20.02, 0));
    EXPECT_LE(w.reeving.findStaticEquilibrium(s, 1e-10), 1e-10);
    w.system.realize(s, Stage::Position);
    PendulumRun run;
    run.atRest = payload.getBodyOriginLocation(s);
    payload.setUToFitLinearVelocity(s, Vec3(1, 0, 0));
    SimTK::RungeKuttaMersonIntegrator integ(w.system);
    integ.setAccuracy(1e-9);
    SimTK::TimeStepper ts(w.system, integ);
    ts.initialize(s);
    ts.stepTo(2.0);
    w.system.realize(ts.getState(), Stage::Position);
    run.after = payload.getBodyOriginLocation(ts.getState());
    return run;
}

// The same pendulum with a massless inextensible rope, computed here: the fall leaves the groove
// (centre c, radius R; R = 0 a point) at the angle phi from the vertical, at the tangent point
// T = c + R (cos phi, sin phi), with the free length l0 + R phi (the rope unwinding as the payload
// swings towards +x); p = T + (l0 + R phi)(sin phi, -cos phi) moves at (l0 + R phi) phidot
// (cos phi, sin phi), so T = m l^2 phidot^2 / 2, V = m g (R sin phi - l cos phi), and Lagrange
// gives phiddot = -(R phidot^2 + g sin phi) / l. Classical RK4, 2e4 steps of 1e-4 s (error far
// below 1e-9 m).
Vec3 involutePendulumAfterTwoSeconds(double R, double l0) {
    auto accel = [&](double phi, double rate) { return -(R * rate * rate + kG * std::sin(phi)) / (l0 + R * phi); };
    double phi = 0, rate = 1.0 / l0;  // pushed at 1 m/s
    const double h = 1e-4;
    for (int i = 0; i < 20000; ++i) {
        const double k1 = rate, a1 = accel(phi, rate);
        const double k2 = rate + 0.5 * h * a1, a2 = accel(phi + 0.5 * h * k1, k2);
        const double k3 = rate + 0.5 * h * a2, a3 = accel(phi + 0.5 * h * k2, k3);
        const double k4 = rate + h * a3, a4 = accel(phi + h * k3, k4);
        phi += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        rate += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    }
    const double l = l0 + R * phi;
    return Vec3(3 + R * std::cos(phi) + l * std::sin(phi), R * std::sin(phi) - l * std::cos(phi), 0);
}

}  // namespace

// Point-sheave limit and its first-order term: the wrapped pendulum differs from the point one by
// d = p_wrapped - p_point after 2 s, of order R (the fall hangs R further out and winds on and off
// the groove as it swings). The same difference of the involute and the simple pendulum computed
// here (massless inextensible rope, each with the free length the model hangs at rest) gives the
// first-order term independently: |d - d_ref| / |d_ref| = 1.68e-4, 1.69e-4, 1.70e-4 at R = 0.1,
// 0.01, 0.001 m (|d| = 0.19, 0.019, 0.0019 m; the 1.7e-4 is the elastic, massive rope's own
// share, the same at every R); bound 5e-3. An arc length or a free length off by a fraction of
// R alpha changes d by a fraction of itself.
TEST(WrappedSheaves, PendulumDiffersFromThePointSheaveAsTheInvolutePendulumDoes) {
    for (double R : {0.1, 0.01, 0.001}) {
        const PendulumRun wrapped = pendulumOverTwoSeconds(SheaveModel::Wrapped, R);
        const PendulumRun point = pendulumOverTwoSeconds(SheaveModel::Point, R);
        const Vec3 d = wrapped.after - point.after;
        const Vec3 dRef = involutePendulumAfterTwoSeconds(R, -wrapped.atRest[1]) -
                          involutePendulumAfterTwoSeconds(0.0, -point.atRest[1]);
        const double relative = (d - dRef).norm() / dRef.norm();
        std::printf("[ pendulum R = %g ] d = (%.6e, %.6e) m, involute reference (%.6e, %.6e) m, relative %.2e\n", R,
                    d[0], d[1], dRef[0], dRef[1], relative);
        EXPECT_LE(relative, 5e-3) << "R = " << R;
    }
}

// A wrapped sheave on Ground (its centre stationary, its departure tangent point and arc length
// moving with the swinging payload): the paper's pendulum over it, quasi-static axial modes
// (n_a = 3) as the demo runs it, keeps T + U for 4 s (RK-Merson 1e-9) to 6.1e-12 of its initial
// kinetic energy (measured; bound 2e-10, 33x). Treating the tangent points as stationary with the
// centre (skipping their columns of the rope's effective mass) drifts by 9.5e-7.
TEST(WrappedSheaves, PendulumOverAWrappedGroundSheaveConservesEnergy) {
    World w;
    MobilizedBody::Planar payload(w.matter.updGround(), Transform(),
                                  SimTK::Body::Rigid(MassProperties(1000, Vec3(0), Inertia(36))), Transform());
    RopeSpec rope;
    rope.start = RopeAnchor{w.matter.Ground(), Vec3(0)};
    DeviationSheave sheave{w.matter.Ground(), Vec3(3, 0, 0), 0.1};
    sheave.wrapSense = -1;
    rope.sheaves = {sheave};
    rope.end = RopeAnchor{payload, Vec3(0, 0.3, 0)};
    rope.properties = kTable1;
    rope.unstretchedLength = 23.0;
    SpanOptions o;
    o.axialModes = 3;
    o.transverseModes = 1;
    rope.spanDefaults = o;
    rope.planeNormal = Vec3(0, 0, 1);
    rope.sheaveModel = SheaveModel::Wrapped;
    w.reeving.addRope(rope);
    w.system.realizeTopology();
    State s = w.system.getDefaultState();
    payload.setQToFitTranslation(s, Vec3(3.1, -20.3, 0));
    ASSERT_LE(w.reeving.findStaticEquilibrium(s, 1e-10), 1e-10);
    payload.setUToFitLinearVelocity(s, Vec3(1, 0, 0));
    w.system.realize(s, Stage::Velocity);
    const double KE0 = w.system.calcKineticEnergy(s) + w.reeving.calcRopeKineticEnergy(s);
    const double E0 = w.reeving.calcMechanicalEnergy(s);
    SimTK::RungeKuttaMersonIntegrator integ(w.system);
    integ.setAccuracy(1e-9);
    SimTK::TimeStepper ts(w.system, integ);
    ts.initialize(s);
    double drift = 0;
    for (int k = 1; k <= 16; ++k) {
        ts.stepTo(0.25 * k);
        w.system.realize(ts.getState(), Stage::Velocity);
        drift = std::max(drift, std::abs(w.reeving.calcMechanicalEnergy(ts.getState()) - E0));
    }
    std::printf("[ pendulum, wrapped Ground sheave ] drift/KE0 = %.3e over 4 s, %d steps\n", drift / KE0,
                integ.getNumStepsTaken());
    EXPECT_LT(drift / KE0, 2e-10);
}
