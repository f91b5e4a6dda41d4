// Hoisting with driven rope nodes: a locked winch drum is a fixed anchor; a drum at
// constant speed lifts a hook block on n falls at R omega / n with the motor's work equal to the
// change of mechanical energy; after hoisting and braking the bounce frequency is the one of the
// shortened rope; an Atwood machine over an idler with inertia; rope limits end the run cleanly;
// bad drum and sheave input is rejected naming it.
#include "SimbodyReeving/simbody/InterpolatingTimeStepper.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <Simbody.h>

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

using namespace SimbodyReeving;
using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace {

constexpr double kG = 9.81;

SimTK::Body::Rigid pointMass(double m) { return SimTK::Body::Rigid(SimTK::MassProperties(m, Vec3(0), SimTK::Inertia(1e-3 * m))); }
SimTK::Body::Rigid wheel(double J) { return SimTK::Body::Rigid(SimTK::MassProperties(1.0, Vec3(0), SimTK::Inertia(J, J, J))); }
// Frames whose x axis is Ground's y: a Slider along them moves vertically.
SimTK::Transform vertical(const Vec3& p) {
    // x -> y, y -> -x, z -> z: a quarter turn about z, written out (the Rotation(angle, axis)
    // constructor trips a false -Warray-bounds inside Simbody's headers in the sanitizer build).
    const SimTK::Mat33 R(0, -1, 0,  //
                         1, 0, 0,   //
                         0, 0, 1);
    return SimTK::Transform(SimTK::Rotation(R, true), p);
}

/// A hoist: a winch drum (Pin about z on Ground at height H, radius R) at the rope's start, n falls
/// zigzagging between Ground sheaves (top) and a hook block of mass M on a vertical Slider
/// (bottom), the dead end on Ground (n even) or on the hook block (n odd). Falls about `fall` m long,
/// sheave pitch 0.1 m. The drum's speed is prescribed (Motion::Steady, rate set per state).
struct Hoist {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -kG, 0)};
    std::unique_ptr<ReevingSubsystem> reeving;
    std::unique_ptr<MotionWorkMeter> meter;
    std::unique_ptr<MobilizedBody::Pin> drum;
    std::unique_ptr<MobilizedBody::Slider> hook;
    SimTK::Motion::Steady drumMotion;
    int n;
    double M, R = 0.25, H = 10.0, pitch = 0.1;

    Hoist(int falls, double mass, const RopeProperties& rope, double fall, double ropeOnDrum = 100.0,
          double minimumSpan = 0.2, int payoutSense = 1)
        : n(falls), M(mass) {
        drum = std::make_unique<MobilizedBody::Pin>(matter.Ground(), SimTK::Transform(Vec3(0, H, 0)), wheel(2.0),
                                                    SimTK::Transform());
        drumMotion = SimTK::Motion::Steady(*drum, 0.0);
        const double xHook = 0.5 * n * pitch;
        hook = std::make_unique<MobilizedBody::Slider>(matter.Ground(), vertical(Vec3(xHook, H - fall, 0)),
                                                       pointMass(M), vertical(Vec3(0)));
        reeving = std::make_unique<ReevingSubsystem>(system, Vec3(0, -kG, 0));
        RopeSpec spec;
        spec.name = "hoist";
        spec.start = WinchDrum{*drum, R, ropeOnDrum, payoutSense};
        for (int k = 1; k <= n; ++k) {
            const bool bottom = k % 2 == 1;
            const double x = k * pitch;
            if (k < n)
                spec.sheaves.push_back(bottom ? DeviationSheave{*hook, Vec3(x - xHook, 0, 0), 0.1}
                                              : DeviationSheave{matter.Ground(), Vec3(x, H, 0), 0.1});
            else
                spec.end = bottom ? RopeAnchor{*hook, Vec3(x - xHook, 0, 0)} : RopeAnchor{matter.Ground(), Vec3(x, H, 0)};
        }
        spec.properties = rope;
        spec.unstretchedLength = n * fall;
        spec.spanDefaults.axialModes = 0;
        spec.spanDefaults.transverseModes = 0;
        spec.planeNormal = Vec3(0, 0, 1);
        spec.minimumSpanLength = minimumSpan;
        reeving->addRope(spec);
        meter = std::make_unique<MotionWorkMeter>(system);
        system.realizeTopology();
    }
    /// Static equilibrium with the drum held; then the drum turning at omega [rad/s] and the hook
    /// moving at the speed that goes with it (steady hoisting, no start transient).
    State start(double omega) {
        State s = system.getDefaultState();
        drumMotion.setRate(s, 0.0);
        reeving->findStaticEquilibrium(s, 1e-12);
        drumMotion.setRate(s, omega);
        system.realize(s, Stage::Position);
        system.prescribeU(s);  // the drum's u from its Motion (integrators do this; a set-up must too)
        hook->setRate(s, hookSpeed(omega));
        system.realize(s, Stage::Acceleration);
        return s;
    }
    /// Hook speed that goes with drum rate omega: -dsdTheta omega / n (hauling in lifts).
    double hookSpeed(double omega) const { return -R * omega / n; }
    double y(const State& s) const { return hook->getOneQ(s, 0); }
    double ropeLength(const State& s) const {
        return reeving->getMaterialCoordinate(s, 0, n) - reeving->getMaterialCoordinate(s, 0, 0);
    }
};

RopeProperties stiffRope() { return RopeProperties{0.05, 1e7, 0.0}; }

}  // namespace

// A drum held by its motion (theta fixed) is a fixed anchor.
TEST(Hoisting, LockedDrumReproducesTheFixedAnchor) {
  for (bool planar : {true, false}) {
    auto run = [planar](bool withDrum) {
        SimTK::MultibodySystem system;
        SimTK::SimbodyMatterSubsystem matter(system);
        SimTK::GeneralForceSubsystem forces(system);
        SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -kG, 0));
        MobilizedBody::Free payload(matter.Ground(), SimTK::Transform(Vec3(3, -20, 0)),
                                    SimTK::Body::Rigid(SimTK::MassProperties(1000, Vec3(0), SimTK::Inertia(36))),
                                    SimTK::Transform(Vec3(0, 0.3, 0)));
        MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(), wheel(5.0), SimTK::Transform());
        SimTK::Motion::Steady(drum, 0.0);
        ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
        RopeSpec spec;
        spec.start = withDrum ? RopeEnd(WinchDrum{drum, 0.3, 50.0}) : RopeEnd(RopeAnchor{matter.Ground(), Vec3(0)});
        spec.sheaves = {DeviationSheave{matter.Ground(), Vec3(3, 0, 0), 0.1}};
        spec.end = RopeAnchor{payload, Vec3(0, 0.3, 0)};
        spec.properties = RopeProperties{0.6205, 16.5e6, 30.9};
        spec.unstretchedLength = 23.0;
        spec.spanDefaults.axialModes = 1;
        spec.spanDefaults.transverseModes = 1;
        spec.spanDefaults.axialDynamics = AxialDynamics::Dynamic;
        spec.spanDefaults.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
        spec.planeNormal = planar ? Vec3(0, 0, 1) : Vec3(0);
        reeving.addRope(spec);
        system.realizeTopology();
        State s = system.getDefaultState();
        reeving.findStaticEquilibrium(s, 1e-11);  // its round-off floor here: 1.3e-12 (measured)
        payload.setUToFitLinearVelocity(s, Vec3(1, 0, 0.2));
        SimTK::RungeKuttaMersonIntegrator integ(system);
        integ.setAccuracy(1e-10);
        SimTK::TimeStepper ts(system, integ);
        ts.initialize(s);
        std::vector<Vec3> path;
        for (int k = 1; k <= 20; ++k) {
            ts.stepTo(0.1 * k);
            path.push_back(payload.getBodyOriginLocation(integ.getState()));
        }
        return path;
    };
    const auto anchored = run(false), drummed = run(true);
    double worst = 0;
    for (size_t k = 0; k < anchored.size(); ++k) worst = std::max(worst, (anchored[k] - drummed[k]).norm());
    std::printf("[ hoist ] locked drum vs fixed anchor, %s rope, 2 s, n_a = 1 Dynamic: max payload distance %.3e m\n",
                planar ? "planar" : "spatial", worst);
    // Measured 0 (bit-identical paths); bound at round-off of a 20 m position.
    EXPECT_LE(worst, 1e-12);
  }
}

// Constant drum speed, 4 falls: hook speed R omega / n, fall tensions (M g) / n plus
// the fall's weight share, motor work = change of mechanical energy. The tension at mid-fall is
// compared with the closed form T_mid = M (g + a) / sum_k cos(alpha_k) + 1/2 rhoA g l cos(alpha)
// (every fall's bottom carries the same pull over frictionless sheaves; a the hook's acceleration,
// the small bounce the start leaves; alpha the fall's angle from the vertical; the weight of half
// the fall, l its unstretched length): the rope-weight term is 1.0e-3 of the tension here, and
// the bound is set well below it, so a model without the rope's weight fails.
TEST(Hoisting, ConstantDrumSpeedLiftsAtROmegaOverN) {
    Hoist h(4, 1000.0, stiffRope(), 10.0);
    const double omega = -4.0;  // hauling in: the start drum's s_0 = -R theta grows
    State s = h.start(omega);
    const double E0 = h.reeving->calcMechanicalEnergy(s);
    SimTK::RungeKuttaMersonIntegrator integ(h.system);
    integ.setAccuracy(1e-10);
    SimTK::TimeStepper ts(h.system, integ);
    ts.initialize(s);
    double y1 = 0, worstEnergy = 0, worstTension = 0, worstWithoutWeight = INFINITY, work = 0;
    for (int k = 1; k <= 30; ++k) {
        ts.stepTo(0.1 * k);
        const State& st = integ.getState();
        h.system.realize(st, Stage::Acceleration);
        work = h.meter->getWork(st);
        worstEnergy = std::max(worstEnergy, std::abs(h.reeving->calcMechanicalEnergy(st) - E0 - work));
        if (std::getenv("HOIST_DEBUG"))
            std::printf("t %.2f W %.6f dE %.6f Urope %.6f Trope %.6f KEb %.6f PEall %.6f Pmotion %.6f Prope %.6f s0 %.6f\n",
                        st.getTime(), work, h.reeving->calcMechanicalEnergy(st) - E0,
                        h.reeving->calcRopePotentialEnergy(st), h.reeving->calcRopeKineticEnergy(st),
                        h.system.calcKineticEnergy(st), h.system.calcPotentialEnergy(st), h.meter->getPower(st),
                        h.reeving->getRope(0).getWinchDrum(0).getPower(st), h.reeving->getMaterialCoordinate(st, 0, 0));
        if (k == 10) y1 = h.y(st);
        // Each fall's bottom carries the same pull T_b: the hook's balance M (g + a) = T_b sum cos(alpha_k).
        std::vector<double> cosAlpha;
        double sumCos = 0;
        for (int j = 0; j < h.n; ++j) {
            const auto ends = h.reeving->sampleSpan(st, 0, j, 2);
            const Vec3 chord = ends[1] - ends[0];
            cosAlpha.push_back(std::abs(chord[1]) / chord.norm());
            sumCos += cosAlpha.back();
        }
        const double bottom = h.M * (kG + h.hook->getOneUDot(st, 0)) / sumCos;
        for (int j = 0; j < h.n; ++j) {
            const auto [s1, s2] = h.reeving->getSpanMaterialRange(st, 0, j);
            // The physical tension T = EA eps |dr/ds| (the axial force P = EA eps is 2.5e-4 smaller
            // here, the fall's stretch): the mid-point carries T_b plus the weight of half the fall
            // along it (rope hanging from the top sheave or drum).
            const double mid = h.reeving->getTension(st, 0, j, 0.5 * (s1 + s2));
            const double weight = 0.5 * 0.05 * kG * (s2 - s1) * cosAlpha[static_cast<size_t>(j)];
            worstTension = std::max(worstTension, std::abs(mid - (bottom + weight)) / (bottom + weight));
            // The same check for a model without the rope's weight (the closed form without it).
            worstWithoutWeight = std::min(worstWithoutWeight, std::abs(mid - bottom) / bottom);
        }
    }
    const State& end = integ.getState();
    const double speed = (h.y(end) - y1) / 2.0;
    const double expectedSpeed = -h.R * omega / h.n;
    std::printf("[ hoist ] 4 falls: hook speed %.9f m/s (R omega / n = %.9f), worst fall tension error %.2e "
                "(closed form without the rope's weight: smallest error %.2e), motor work %.6f J, "
                "max |E - E0 - W| %.3e J\n",
                speed, expectedSpeed, worstTension, worstWithoutWeight, work, worstEnergy);
    // Measured: speed 3.0e-4 relative (the stretch change), margin 3.3x; energy balance 3.8e-11 ..
    // 4.5e-11 J of W = 7 373 J (6.2e-15 relative, round-off of 1e4 J energies; Newton at 1e-14),
    // margin 81x.
    EXPECT_NEAR(speed, expectedSpeed, 1e-3 * expectedSpeed);
    // Fall tension against the closed form with the rope's weight: measured 6.8e-6 relative; it grows
    // with the square of the rope speed (1.9e-6 at half and 2.6e-5 at twice this drum speed): the
    // rope's momentum flux through the sheaves, rhoA v^2 = 0.05 N = 2e-5 of T at 1 m/s, which the
    // closed form leaves out. Bound 1e-4, margin 15x. The effect it verifies, half a fall's
    // weight, is 1.0e-3 of T: the closed form without it misses by at least 9.3e-4 (measured),
    // 9.3x the bound, so a model without the rope's weight fails. (Against the axial force P
    // instead of T and without the hook's bounce the error was 6.8e-4, most of the effect.)
    EXPECT_LE(worstTension, 1e-4);
    EXPECT_GT(worstWithoutWeight, 5 * 1e-4);  // the bound separates the models
    EXPECT_GT(work, 0.9 * h.M * kG * expectedSpeed * 3.0);
    EXPECT_LE(worstEnergy, 5e-13 * work);
}

// Hoist 3 m of rope in, brake (drum stopped), measure the bounce: the frequency of
// k = n^2 EA / L_rope (all falls share the tension over frictionless sheaves) with L_rope the rope
// left between drum and dead end, within 0.5 %.
TEST(Hoisting, BounceFrequencyAfterHoistingMatchesTheShortenedRope) {
    const RopeProperties rope{0.01, 1e7, 0.0, false};  // linear law: the bounce dips below zero strain
    Hoist h(4, 1000.0, rope, 10.0);
    const double omega = -4.0;
    State s = h.start(omega);
    SimTK::RungeKuttaMersonIntegrator integ(h.system);
    integ.setAccuracy(1e-10);
    SimTK::TimeStepper ts(h.system, integ);
    ts.initialize(s);
    ts.stepTo(3.0);
    State braked = integ.getState();
    const double L0 = h.n * 10.0;
    h.drumMotion.setRate(braked, 0.0);  // brake: the drum stops
    h.system.realize(braked, Stage::Position);
    h.system.prescribeU(braked);
    h.system.realize(braked, Stage::Velocity);
    const double L = h.ropeLength(braked);
    ts.initialize(braked);
    std::vector<double> t, y;
    for (int k = 1; k <= 2000; ++k) {
        ts.stepTo(3.0 + 1e-3 * k);
        t.push_back(3.0 + 1e-3 * k);
        y.push_back(h.y(integ.getState()));
    }
    double mean = 0;
    for (double v : y) mean += v;
    mean /= static_cast<double>(y.size());
    std::vector<double> up;  // upward zero crossings of y - mean
    for (size_t k = 1; k < y.size(); ++k)
        if (y[k - 1] < mean && y[k] >= mean)
            up.push_back(t[k - 1] + (mean - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1]));
    ASSERT_GE(up.size(), 5u);
    const double f = (static_cast<double>(up.size()) - 1) / (up.back() - up.front());
    const double k = h.n * h.n * rope.axialStiffness / L;
    const double expected = std::sqrt(k / h.M) / (2 * SimTK::Pi);
    const double before = std::sqrt(h.n * h.n * rope.axialStiffness / L0 / h.M) / (2 * SimTK::Pi);
    std::printf("[ hoist ] bounce after hoisting: rope %.4f m (was %.1f), f = %.5f Hz, spring of the current rope "
                "%.5f Hz (error %.2e), of the initial rope %.5f Hz\n",
                L, L0, f, expected, (f - expected) / expected, before);
    EXPECT_LT(L, L0 - 2.9);
    // Measured 2.5e-4 relative; margin 20x.
    EXPECT_NEAR(f, expected, 5e-3 * expected);
    EXPECT_GT(std::abs(f - before), 2 * 5e-3 * expected);  // the shortened rope is distinguishable
}

namespace {

/// Atwood machine: masses m1 (start) and m2 (end) on vertical sliders, 5 m below a sheave at the
/// origin; the sheave is a TurningSheave on a Pin with inertia J (radius R) or, J < 0, a
/// frictionless DeviationSheave. Returns the acceleration of m2 (up positive) from a quadratic fit
/// over 1 s.
double atwoodAcceleration(double m1, double m2, double J, double R, double* sheaveSlip = nullptr) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -kG, 0));
    MobilizedBody::Slider a(matter.Ground(), vertical(Vec3(-0.01, -5, 0)), pointMass(m1), vertical(Vec3(0)));
    MobilizedBody::Slider b(matter.Ground(), vertical(Vec3(0.01, -5, 0)), pointMass(m2), vertical(Vec3(0)));
    std::unique_ptr<MobilizedBody::Pin> pin;
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    RopeSpec spec;
    spec.start = RopeAnchor{a, Vec3(0)};
    const double L = 10.0 * (1 - 0.5 * (m1 + m2) * kG / 2 / 1e7);
    if (J >= 0) {
        pin = std::make_unique<MobilizedBody::Pin>(matter.Ground(), SimTK::Transform(), wheel(J), SimTK::Transform());
        spec.sheaves = {TurningSheave{*pin, R, 0.5 * L}};
    } else {
        spec.sheaves = {DeviationSheave{matter.Ground(), Vec3(0), R}};
    }
    spec.end = RopeAnchor{b, Vec3(0)};
    spec.properties = RopeProperties{1e-4, 1e7, 0.0};
    spec.unstretchedLength = L;
    spec.spanDefaults.axialModes = 0;
    spec.spanDefaults.transverseModes = 0;
    spec.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(spec);
    system.realizeTopology();
    State s = system.getDefaultState();
    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-9);
    SimTK::TimeStepper ts(system, integ);
    ts.initialize(s);
    // Least-squares y = c0 + c1 t + c2 t^2 over 1 s (the stiff rope's bounce averages out).
    Eigen::MatrixXd A(200, 3);
    Eigen::VectorXd yv(200);
    double slip = 0;
    for (int k = 1; k <= 200; ++k) {
        const double t = 0.005 * k;
        ts.stepTo(t);
        A.row(k - 1) << 1, t, t * t;
        yv[k - 1] = b.getOneQ(integ.getState(), 0);
        if (pin) {  // no slip: s at the sheave moves with R theta
            const double sk = reeving.getMaterialCoordinate(integ.getState(), 0, 1);
            slip = std::max(slip, std::abs(sk - 0.5 * L - R * pin->getAngle(integ.getState())));
        }
    }
    if (sheaveSlip) *sheaveSlip = slip;
    const Eigen::Vector3d c = A.colPivHouseholderQr().solve(yv);
    return 2 * c[2];
}

}  // namespace

// Atwood machine over an idler with inertia, and over a frictionless sheave.
TEST(Hoisting, AtwoodMachineOverAnIdlerWithInertia) {
    const double m1 = 30, m2 = 20, J = 0.5, R = 0.2;
    double slip = 0;
    const double withInertia = atwoodAcceleration(m1, m2, J, R, &slip);
    const double expected = (m1 - m2) * kG / (m1 + m2 + J / (R * R));
    const double frictionless = atwoodAcceleration(m1, m2, -1, R);
    const double expected0 = (m1 - m2) * kG / (m1 + m2);
    std::printf("[ hoist ] Atwood: J = %.2f: a = %.6f m/s^2 (formula %.6f, error %.2e), slip %.1e m; point sheave: "
                "a = %.6f (formula %.6f, error %.2e)\n",
                J, withInertia, expected, (withInertia - expected) / expected, slip, frictionless, expected0,
                (frictionless - expected0) / expected0);
    // Measured: 1.4e-5 and 1.6e-5 relative (margins 72x, 61x); slip 4.4e-16 m (round-off
    // of s = 5 m), margin 23x.
    EXPECT_NEAR(withInertia, expected, 1e-3 * expected);
    EXPECT_NEAR(frictionless, expected0, 1e-3 * expected0);
    EXPECT_LE(slip, 1e-14);
}

// Rope limits end the run cleanly with a message naming rope and span or drum.
TEST(Hoisting, TwoBlockingEndsTheRunAtTheMinimumSpanLength) {
    Hoist h(2, 500.0, stiffRope(), 2.0, 100.0, 0.5);
    State s = h.start(-8.0);  // 2 m/s of rope: the falls shorten at 1 m/s
    SimTK::RungeKuttaMersonIntegrator integ(h.system);
    integ.setAccuracy(1e-8);
    InterpolatingTimeStepper ts(h.system, integ);
    ts.initialize(s);
    ts.stepTo(10.0);
    const State& end = integ.getState();
    EXPECT_EQ(integ.getTerminationReason(), SimTK::Integrator::EventHandlerRequestedTermination);
    const std::string& why = h.reeving->getLimitReached();
    std::printf("[ hoist ] two-blocking: t = %.6f s: %s\n", end.getTime(), why.c_str());
    EXPECT_NE(why.find("rope 'hoist' span"), std::string::npos) << why;
    EXPECT_NE(why.find("minimumSpanLength = 0.5"), std::string::npos) << why;
    EXPECT_LT(end.getTime(), 2.0);
    double shortest = 1e9;
    for (int j = 0; j < h.n; ++j) {
        const auto [s1, s2] = h.reeving->getSpanMaterialRange(end, 0, j);
        shortest = std::min(shortest, s2 - s1);
    }
    EXPECT_NEAR(shortest, 0.5, 1e-12);  // measured 3.0e-14 m, margin 33x
}

TEST(Hoisting, DrumRunningOutOfRopeEndsTheRun) {
    Hoist h(2, 500.0, stiffRope(), 5.0, 1.0);  // 1 m of rope on the drum
    State s = h.start(4.0);                      // paying out at 1 m/s
    SimTK::RungeKuttaMersonIntegrator integ(h.system);
    integ.setAccuracy(1e-8);
    InterpolatingTimeStepper ts(h.system, integ);
    ts.initialize(s);
    ts.stepTo(10.0);
    const State& end = integ.getState();
    const std::string& why = h.reeving->getLimitReached();
    std::printf("[ hoist ] drum empty: t = %.6f s, rope on drum %.2e m: %s\n", end.getTime(),
                h.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(end), why.c_str());
    EXPECT_EQ(integ.getTerminationReason(), SimTK::Integrator::EventHandlerRequestedTermination);
    EXPECT_NE(why.find("winch drum at node 0 ran out of rope"), std::string::npos) << why;
    // 1 m at R omega = 1 m/s: measured 1.2e-14 s and 1.2e-14 m; margins 85x.
    EXPECT_NEAR(end.getTime(), 1.0, 1e-12);
    EXPECT_NEAR(h.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(end), 0.0, 1e-12);
}

// An end drum hauling its single span in: the span reaches its minimum and the run ends.
TEST(Hoisting, EndDrumHaulingItsSpanInEndsAtTheMinimum) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -kG, 0));
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0, -3, 0)), pointMass(100), vertical(Vec3(0)));
    MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(), wheel(1.0), SimTK::Transform());
    SimTK::Motion::Steady(drum, -2.0);  // end drum, payout sense +1: s_N = L + R theta shrinks
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    RopeSpec spec;
    spec.name = "winch";
    spec.start = RopeAnchor{load, Vec3(0)};
    spec.end = WinchDrum{drum, 0.5, 20.0};
    spec.properties = stiffRope();
    // The linear law: the unbalanced start bounces a tension-only rope slack again and again for the
    // whole haul (the same check, 40 s of test time instead of 1 s).
    spec.properties.tensionOnly = false;
    spec.unstretchedLength = 3.0;
    spec.spanDefaults.axialModes = 1;
    spec.spanDefaults.transverseModes = 1;
    spec.spanDefaults.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    spec.spanDefaults.axialDynamics = AxialDynamics::Dynamic;  // not the default: the setting these bounds were measured with
    spec.planeNormal = Vec3(0, 0, 1);
    spec.minimumSpanLength = 0.5;
    reeving.addRope(spec);
    system.realizeTopology();
    State s = system.getDefaultState();
    load.setRate(s, 1.0);  // moving with the rope
    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-8);
    InterpolatingTimeStepper ts(system, integ);
    ts.initialize(s);
    ts.stepTo(10.0);
    const State& end = integ.getState();
    const std::string& why = reeving.getLimitReached();
    std::printf("[ hoist ] end drum: t = %.6f s: %s\n", end.getTime(), why.c_str());
    EXPECT_NE(why.find("rope 'winch' span 0"), std::string::npos) << why;
    const auto [s1, s2] = reeving.getSpanMaterialRange(end, 0, 0);
    // 2.5 m hauled at R omega = 1 m/s: measured 2.5e-14 m and 2.5e-14 s; margins 40x.
    EXPECT_NEAR(s2 - s1, 0.5, 1e-12);
    EXPECT_NEAR(end.getTime(), 2.5, 1e-12);
}

// Bad drum and sheave input names the node and the problem.
TEST(Hoisting, BadDrumAndSheaveInputIsAnInvalidArgument) {
    SimTK::MultibodySystem other;
    SimTK::SimbodyMatterSubsystem otherMatter(other);
    MobilizedBody::Pin alienDrum(otherMatter.Ground(), SimTK::Transform(), wheel(1), SimTK::Transform());
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(), wheel(1), SimTK::Transform());
    MobilizedBody::Free freeBody(matter.Ground(), SimTK::Transform(), pointMass(1), SimTK::Transform());
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0, -3, 0)), pointMass(100), vertical(Vec3(0)));
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    auto good = [&] {
        RopeSpec r;
        r.start = WinchDrum{drum, 0.3, 10.0};
        r.sheaves = {DeviationSheave{matter.Ground(), Vec3(1, 0, 0), 0.1}};
        r.end = RopeAnchor{load, Vec3(0)};
        r.properties = {0.6, 1e6, 0};
        r.unstretchedLength = 5;
        r.planeNormal = Vec3(0, 0, 1);
        return r;
    };
    // addRope(r) must throw std::invalid_argument naming the rope, then the node and the problem.
    auto expectInvalid = [&](const RopeSpec& r, const std::string& words) {
        EXPECT_THROW_MESSAGE(reeving.addRope(r), std::invalid_argument, "ReevingSubsystem: rope 'rope': " + words);
    };
    RopeSpec r = good();
    for (const auto& [bad, text] : {std::pair{0.0, "0"}, std::pair{-0.3, "-0.3"}, std::pair{SimTK::NaN, "nan"}}) {
        r = good();
        std::get<WinchDrum>(r.start).radius = bad;
        expectInvalid(r, std::string("start node (WinchDrum, node 0) radius [m] = ") + text + " must be finite and > 0");
    }
    r = good();
    r.start = WinchDrum{alienDrum, 0.3, 10.0};
    expectInvalid(r, "start node (WinchDrum, node 0) is on a body of another system's matter subsystem");
    r = good();
    r.start = WinchDrum{freeBody, 0.3, 10.0};
    expectInvalid(r, "start node (WinchDrum, node 0): its body must be a MobilizedBody::Pin");
    r = good();
    r.start = WinchDrum{drum, 0.3, 10.0, 1, Vec3(0.2, 0, 0)};
    expectInvalid(r, "start node (WinchDrum, node 0) point (0.2, 0, 0) is off the pin axis");
    r = good();
    r.start = WinchDrum{drum, 0.3, 10.0, 0};
    expectInvalid(r, "start node (WinchDrum, node 0) sense = 0 must be +1 or -1");
    r = good();
    r.start = WinchDrum{drum, 0.3, -1.0};
    expectInvalid(r, "start node (WinchDrum, node 0) ropeOnDrum [m] = -1 must be finite and >= 0");
    r = good();
    r.minimumSpanLength = 0;
    expectInvalid(r, "minimumSpanLength [m] = 0 must be finite and > 0");
    r = good();
    EXPECT_NO_THROW(reeving.addRope(r));
}

// Where each node kind may stand is a type: a rope's ends are RopeEnd (RopeAnchor, WinchDrum), its
// path RopeSheave (DeviationSheave, TurningSheave, TractionSheave); a kind elsewhere does not compile
// (tests/api also builds such sources and expects them to fail). Every kind where it may stand is
// accepted.
static_assert(std::is_assignable_v<RopeEnd&, RopeAnchor> && std::is_assignable_v<RopeEnd&, WinchDrum>);
static_assert(!std::is_assignable_v<RopeEnd&, DeviationSheave> && !std::is_assignable_v<RopeEnd&, TurningSheave> &&
              !std::is_assignable_v<RopeEnd&, TractionSheave>);
static_assert(std::is_assignable_v<RopeSheave&, DeviationSheave> && std::is_assignable_v<RopeSheave&, TurningSheave> &&
              std::is_assignable_v<RopeSheave&, TractionSheave>);
static_assert(!std::is_assignable_v<RopeSheave&, RopeAnchor> && !std::is_assignable_v<RopeSheave&, WinchDrum>);

TEST(Hoisting, EachNodeKindStandsWhereItsTypeAllows) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    MobilizedBody::Pin pin(matter.Ground(), SimTK::Transform(Vec3(1, 0, 0)), wheel(1), SimTK::Transform());
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0, -3, 0)), pointMass(100), vertical(Vec3(0)));
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    auto rope = [&](const char* name, RopeEnd start, RopeSheave sheave) {
        RopeSpec r;
        r.name = name;
        r.start = std::move(start);
        r.sheaves = {std::move(sheave)};
        r.end = RopeAnchor{load, Vec3(0)};
        r.properties = {0.6, 1e6, 0};
        r.unstretchedLength = 5;
        r.planeNormal = Vec3(0, 0, 1);
        return r;
    };
    const RopeEnd anchor = RopeAnchor{matter.Ground(), Vec3(-1, 0, 0)};
    const RopeSheave idler = DeviationSheave{matter.Ground(), Vec3(1, 0.5, 0), 0.1};
    EXPECT_NO_THROW(reeving.addRope(rope("Anchor", RopeAnchor{matter.Ground(), Vec3(0, 1, 0)}, idler)));
    EXPECT_NO_THROW(reeving.addRope(rope("WinchDrum", WinchDrum{pin, 0.3, 10.0}, idler)));
    EXPECT_NO_THROW(reeving.addRope(rope("DeviationSheave", anchor, DeviationSheave{matter.Ground(), Vec3(0, 1, 0), 0.1})));
    EXPECT_NO_THROW(reeving.addRope(rope("TurningSheave", anchor, TurningSheave{pin, 0.3, 1.0})));
    EXPECT_NO_THROW(reeving.addRope(rope("TractionSheave", anchor, TractionSheave{pin, 0.3, 0.2, 0.0, 1.0, 1, Vec3(0)})));
    EXPECT_EQ(reeving.getNumRopes(), 5);
    // The kind-specific handles: the right kind, or std::invalid_argument naming both kinds.
    EXPECT_EQ(reeving.getRope(1).getWinchDrum(0).getNodeIndex(), 0);
    EXPECT_EQ(reeving.getRope(3).getTurningSheave(1).getRopeIndex(), 3);
    EXPECT_EQ(&reeving.getRope(4).getTractionSheave(1).getReevingSubsystem().getGuts(), &reeving.getGuts());
    EXPECT_THROW_MESSAGE(reeving.getRope(0).getWinchDrum(0), std::invalid_argument,
                         "ReevingSubsystem: rope 'Anchor': node 0 (Anchor) is not a WinchDrum");
    EXPECT_THROW_MESSAGE(reeving.getRope(3).getTractionSheave(1), std::invalid_argument,
                         "ReevingSubsystem: rope 'TurningSheave': node 1 (TurningSheave) is not a TractionSheave");
    EXPECT_THROW_MESSAGE(reeving.getRope(1).getWinchDrum(3), std::invalid_argument,
                         "ReevingSubsystem: rope 'WinchDrum': node index = 3 is outside 0..2");
    EXPECT_THROW(reeving.getRope(5), std::invalid_argument);
}

// Long hauls: one span hauled in from 100 m to its 0.5 m minimum by an end drum, with
// quasi-static axial modes and transverse modes: every evaluation succeeds (Newton, quadrature and
// modes stay conditioned over the 200x length range), the run ends at the limit, and the motor's
// work equals the change of mechanical energy.
TEST(Hoisting, SpanFromOneHundredMetresToHalfAMetre) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -kG, 0));
    const double M = 2000, R = 0.5, omega = -20.0;  // 10 m/s of rope
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0.02, -100, 0)), pointMass(M), vertical(Vec3(0)));
    MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(), wheel(3.0), SimTK::Transform());
    SimTK::Motion::Steady motion(drum, 0.0);
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    RopeSpec spec;
    spec.name = "winch";
    spec.start = RopeAnchor{load, Vec3(0)};
    spec.end = WinchDrum{drum, R, 200.0};
    spec.properties = RopeProperties{1.6, 2.5e7, 0.0};
    spec.unstretchedLength = 100.0;
    spec.spanDefaults.axialModes = 2;
    spec.spanDefaults.transverseModes = 2;
    spec.spanDefaults.axialDynamics = AxialDynamics::QuasiStatic;
    spec.spanDefaults.velocityModel = VelocityModel::Simplified;  // not the default: the setting these bounds were measured with
    spec.planeNormal = Vec3(0, 0, 1);
    spec.minimumSpanLength = 0.5;
    reeving.addRope(spec);
    MotionWorkMeter meter(system);
    system.realizeTopology();
    State s = system.getDefaultState();
    reeving.findStaticEquilibrium(s, 1e-12);
    motion.setRate(s, omega);
    system.realize(s, Stage::Position);
    system.prescribeU(s);
    load.setRate(s, -R * omega);
    system.realize(s, Stage::Acceleration);
    const double E0 = reeving.calcMechanicalEnergy(s);
    const int failures0 = reeving.getNumEvaluationFailures();
    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-9);
    InterpolatingTimeStepper ts(system, integ);
    ts.initialize(s);
    double worst = 0, work = 0, tension = 0;
    for (int k = 1; k <= 120 && !integ.isSimulationOver(); ++k) {
        ts.stepTo(0.1 * k);
        const State& st = ts.getState();
        system.realize(st, Stage::Acceleration);
        work = meter.getWork(st);
        worst = std::max(worst, std::abs(reeving.calcMechanicalEnergy(st) - E0 - work));
        const auto [s1, s2] = reeving.getSpanMaterialRange(st, 0, 0);
        tension = reeving.getAxialForce(st, 0, 0, s1);
    }
    const State& end = integ.getState();
    const auto [s1, s2] = reeving.getSpanMaterialRange(end, 0, 0);
    std::printf("[ hoist ] 100 m -> 0.5 m, n_a = 2 quasi-static, n_t = 2: ended at t = %.6f s, span %.6f m, %d steps, "
                "%d evaluation failures, tension at the load %.2f N (M g = %.2f), max |E - E0 - W| %.3e J of W = %.1f J\n",
                end.getTime(), s2 - s1, integ.getNumStepsTaken(), reeving.getNumEvaluationFailures() - failures0,
                tension, M * kG, worst, work);
    ASSERT_TRUE(integ.isSimulationOver());
    EXPECT_EQ(integ.getTerminationReason(), SimTK::Integrator::EventHandlerRequestedTermination);
    EXPECT_NE(reeving.getLimitReached().find("rope 'winch' span 0"), std::string::npos);
    // Measured 1.1e-12 m and 7.1e-14 s; margins 94x and 70x.
    EXPECT_NEAR(s2 - s1, 0.5, 1e-10);
    EXPECT_NEAR(end.getTime(), 99.5 / (-R * omega), 5e-12);
    EXPECT_EQ(reeving.getNumEvaluationFailures(), failures0);
    // The load bounces on the shortening rope (the stretch M g L / EA shrinks as it is hauled in;
    // the bounce's force amplitude grows with the stiffness): the tension is a sanity check only.
    EXPECT_NEAR(tension, M * kG, 0.25 * M * kG);  // measured 12.7 % off, margin 2x
    // Measured 1.0e-5 J of W = 2.03e6 J (5.0e-12 relative); margin 40x.
    EXPECT_LE(worst, 2e-10 * work);
}

// A free winch drum (no motor, no brake) lowering a load: the drum at the rope's end turns as the
// load falls, a = m g / (m + J / R^2 + stored rope), and T + U is conserved (the stored rope's mass
// included).
TEST(Hoisting, FreeDrumLowersTheLoad) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -kG, 0));
    const double m = 50, J = 2.0, R = 0.25, rhoA = 1e-3, onDrum = 20.0;
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0.01, -5, 0)), pointMass(m), vertical(Vec3(0)));
    MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(), wheel(J), SimTK::Transform());
    ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    RopeSpec spec;
    spec.start = RopeAnchor{load, Vec3(0)};
    spec.end = WinchDrum{drum, R, onDrum};  // payout sense +1: the load pulls theta positive
    spec.properties = RopeProperties{rhoA, 1e7, 0.0};
    spec.unstretchedLength = 5.0 * (1 - m * kG / 1e7);
    spec.spanDefaults.axialModes = 0;
    spec.spanDefaults.transverseModes = 0;
    spec.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(spec);
    system.realizeTopology();
    State s = system.getDefaultState();
    system.realize(s, Stage::Acceleration);
    const double E0 = reeving.calcMechanicalEnergy(s);
    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-10);
    SimTK::TimeStepper ts(system, integ);
    ts.initialize(s);
    Eigen::MatrixXd A(100, 3);
    Eigen::VectorXd yv(100);
    double drift = 0;
    for (int k = 1; k <= 100; ++k) {
        const double t = 0.01 * k;
        ts.stepTo(t);
        const State& st = integ.getState();
        system.realize(st, Stage::Acceleration);
        drift = std::max(drift, std::abs(reeving.calcMechanicalEnergy(st) - E0));
        A.row(k - 1) << 1, t, t * t;
        yv[k - 1] = load.getOneQ(st, 0);
    }
    const Eigen::Vector3d c = A.colPivHouseholderQr().solve(yv);
    // Over the second the stored rope grows from 20 m by about 1.6 m: its mass (0.02 kg) is a
    // 4e-4 share of the effective mass m + J / R^2 = 82 kg; the span's own 5 g likewise.
    const double expected = -m * kG / (m + J / (R * R));
    std::printf("[ hoist ] free drum: a = %.6f m/s^2 (m g / (m + J/R^2) = %.6f, error %.2e), |E - E0| max %.3e J\n",
                2 * c[2], expected, (2 * c[2] - expected) / expected, drift);
    // Measured: 1.7e-4 relative (the stored rope's mass share above), margin 5.9x; drift
    // 3.8e-8 J, margin 65x.
    EXPECT_NEAR(2 * c[2], expected, 1e-3 * std::abs(expected));
    EXPECT_LE(drift, 5e-9 * m * kG * 1.0);
}

// findStaticEquilibrium with nothing free (the rope's only body prescribed, no rope mode: n_t = 0
// and quasi-static axial modes) leaves the state as it is and reports 0 (it read an empty residual
// before: a crash).
TEST(Hoisting, StaticEquilibriumWithNothingFreeIsTheStateItself) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, -SimTK::YAxis, kG);
    MobilizedBody::Slider load(matter.Ground(), vertical(Vec3(0, -3, 0)), pointMass(100), vertical(Vec3(0)));
    SimTK::Motion::Steady(load, 0.0);
    ReevingSubsystem reeving(system);
    RopeSpec r;
    r.start = RopeAnchor{matter.Ground(), Vec3(0)};
    r.end = RopeAnchor{load, Vec3(0)};
    r.properties = {0.6, 1e6, 0};
    r.unstretchedLength = 2.999;
    r.spanDefaults.transverseModes = 0;
    r.spanDefaults.axialModes = 2;
    r.spanDefaults.axialDynamics = AxialDynamics::QuasiStatic;
    r.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(r);
    system.realizeTopology();
    State s = system.getDefaultState();
    ASSERT_EQ(reeving.getNumModalCoordinates(0), 0);
    const SimTK::Vector q = s.getQ();
    EXPECT_EQ(reeving.findStaticEquilibrium(s), 0.0);
    EXPECT_EQ((s.getQ() - q).norm(), 0.0);
}
