// A WinchDrum with SheaveModel::Wrapped: the rope leaves the drum at its groove's tangent point
// and rolls on and off the drum as its fall swings. A held drum (Motion::Steady 0: no work) with a
// payload swinging on the rope: the rope's length (the span's material plus the rope stored on the
// drum) is conserved while the tangent point rolls, and so is the energy.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "support/GripCreep.h"
#include "support/PlanarRopeGeometry.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.25;       // drum radius [m]
constexpr double kStored = 5.0;   // rope stored up to the drum's top at pin angle 0 [m]

struct SwingingLoad {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Pin drum;
    MobilizedBody::Planar load;
    State state;

    SwingingLoad() {
        drum = MobilizedBody::Pin(matter.Ground(), Transform(), Body::Rigid(MassProperties(20, Vec3(0), Inertia(0.6))),
                                  Transform());
        Motion::Steady(drum, 0.0);
        load = MobilizedBody::Planar(matter.Ground(), Transform(),
                                     Body::Rigid(MassProperties(150, Vec3(0), Inertia(4))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system);
        sr::RopeSpec rope;
        rope.sheaveModel = sr::SheaveModel::Wrapped;
        sr::WinchDrum d;
        d.body = drum;
        d.radius = kR;
        d.ropeOnDrum = kStored;
        d.payoutSense = 1;  // sigma = +1: the rope unwinds counter-clockwise off the drum's left side
        rope.start = d;
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        rope.properties = {1.2, 2e7, 0.0, false};
        rope.unstretchedLength = 0.5 * Pi * kR + 4.0;  // a quarter turn to the left tangent point, 4 m down
        rope.spanDefaults.axialModes = 1;
        rope.spanDefaults.transverseModes = 2;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        // The load 4 m under the drum's left side, pulled 0.8 m out to the left (the rope's chord
        // about its length: taut to within the tangent point's roll), at rest: it swings, and the
        // rope rolls on and off the held drum with its fall.
        load.setQ(state, Vec3(0, -kR - 0.8, -std::sqrt(16.0 - 0.64)));
        system.realize(state, Stage::Velocity);
    }
};

// The rope's length from the geometry, independently of the model's material bookkeeping: the
// tangent point T where the fall leaves the held drum follows in closed form from the load's
// position (the straight tangent from the load to the groove circle, the rope running counter-
// clockwise on it: support/PlanarRopeGeometry.h); the rope on the drum beyond its top is
// R (phi_T - pi / 2) (phi_T the tangent point's polar angle), and the span's material is its
// sampled length over the stretch sqrt(1 + 2 P / EA). Together they make the rope's length L.
struct DrumGeometry {
    double arcFromTop = 0;     // R (phi_T - pi / 2) [m]
    double spanMaterial = 0;   // [m]
    double tangentAngle = 0;   // phi_T [rad]
    double stretch = 1;        // lambda = sqrt(1 + 2 eps) at the tangent point [-]
};

DrumGeometry measureDrumGeometry(const SwingingLoad& s, const State& st) {
    namespace t = SimbodyReevingTest;
    State c = st;  // below Stage::Dynamics: the condensed axial strain without its inertial correction
    c.invalidateAllCacheAtOrAbove(Stage::Dynamics);
    s.system.realize(c, Stage::Position);
    const Vec3 p = s.load.getBodyOriginLocation(c);
    const t::PlanarGroove drum{Eigen::Vector2d(0, 0), kR, 1}, load{Eigen::Vector2d(p[0], p[1]), 0.0, 1};
    const Eigen::Vector2d T = t::spanTangentPoints(drum, load).first;
    DrumGeometry g;
    g.tangentAngle = t::polarAngle(drum.centre, T);
    if (g.tangentAngle < 0) g.tangentAngle += 2 * Pi;
    g.arcFromTop = kR * (g.tangentAngle - 0.5 * Pi);
    const int n = 401;
    const std::vector<Vec3> r = s.reeving->sampleSpan(c, 0, 0, n);
    const auto range = s.reeving->getSpanMaterialRange(c, 0, 0);
    const double EA = s.reeving->getRopeSpec(0).properties.axialStiffness;
    std::vector<Eigen::Vector2d> points(n);
    std::vector<double> strains(n);
    for (int i = 0; i < n; ++i) {
        points[i] = Eigen::Vector2d(r[i][0], r[i][1]);
        strains[i] = s.reeving->getAxialForce(c, 0, 0, range.first + (range.second - range.first) * i / (n - 1)) / EA;
    }
    g.spanMaterial = t::materialLengthFromGeometry(points, strains);
    g.stretch = std::sqrt(1 + 2 * strains.front());
    return g;
}

}  // namespace

// Over 3 s of swing (three quarters of a period; the fall turning by about 0.2 rad each way, the
// tangent point rolling round the drum with it). The drum grips the rope (RopeModel::setGrip): the
// rope rolls on and off at the groove's surface, so the material on the drum beyond its top is
// R (phi_T - pi / 2) plus the creep c = integral of (1 / lambda - 1) R dphi_T, integrated here
// from the samples (GripCreep: every 1.25 ms, fourth order; its error falls from 3.0e-10 m at
// 5 ms to 1.8e-11 m at 2.5 ms and 1.1e-12 m at 1.25 ms, the rope's axial vibration, 34 ms, in lambda
// setting the step); the largest creep is 7.8e-6 m:
//  - the rope's length from the geometry (DrumGeometry: span sampled at 401 points, the drum's
//    rope from the tangent point's angle, plus c) equals L: measured 4.2e-11 m of 4.39 m; bound
//    1e-9 m (24x);
//  - getRopeOnDrum equals ropeOnDrum plus R (phi_T - pi / 2) of the geometry plus c: measured
//    1.1e-12 m; bound 2e-11 m (18x, the quadrature's error);
//  - the rope rolls onto the drum as the tangent point moves forward (counter-clockwise, the
//    rope's sense on the groove), signed: stored - stored_0 = +R (phi_T - phi_T0) + c, measured to
//    1.1e-12 m (bound 2e-11 m) while 0.10 m rolls on and 0.05 m back off; without c it would be
//    off by the creep, 7.8e-6 m;
//  - the energy drifts by 4.5e-10 of the largest kinetic energy (RK-Merson 1e-9; bound 1e-8).
TEST(WrappedDrum, HeldDrumAndSwingingLoadKeepLengthAndEnergy) {
    SwingingLoad s;
    const double e0 = s.reeving->calcMechanicalEnergy(s.state);
    const double L = s.reeving->getRopeSpec(0).unstretchedLength;
    RungeKuttaMersonIntegrator integ(s.system);
    integ.setAccuracy(1e-9);
    TimeStepper ts(s.system, integ);
    ts.initialize(s.state);
    double worstLength = 0, worstStored = 0, worstEnergy = 0, largestKinetic = 0, rolledOn = 0, rolledOff = 0,
           worstRoll = 0;
    const double stored0 = s.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(s.state);
    const DrumGeometry g0 = measureDrumGeometry(s, s.state);
    const double phi0 = g0.tangentAngle;
    // The held drum grips the rope: the creep c against its groove, from the geometry's samples
    // (the groove covered R phi_T, the stretch at the tangent point).
    SimbodyReevingTest::GripCreep creep(g0.stretch, kR * phi0);
    double largestCreep = 0;
    for (int i = 1; i <= 2400; ++i) {
        ts.stepTo(1.25e-3 * i);
        const State& st = integ.getState();
        s.system.realize(st, Stage::Velocity);
        const DrumGeometry g = measureDrumGeometry(s, st);
        creep.add(g.stretch, kR * g.tangentAngle);
        const double kinetic = s.system.calcKineticEnergy(st) + s.reeving->calcRopeKineticEnergy(st);
        largestKinetic = std::max(largestKinetic, kinetic);
        worstEnergy = std::max(worstEnergy, std::abs(s.reeving->calcMechanicalEnergy(st) - e0));
        if (!creep.ready()) continue;
        const double c = creep.value();
        largestCreep = std::max(largestCreep, std::abs(c));
        worstLength = std::max(worstLength, std::abs(g.arcFromTop + c + g.spanMaterial - L));
        const double stored = s.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(st);
        worstStored = std::max(worstStored, std::abs(stored - (kStored + g.arcFromTop + c)));
        rolledOn = std::max(rolledOn, stored - stored0);
        rolledOff = std::max(rolledOff, rolledOn - (stored - stored0));  // back off after the peak
        worstRoll = std::max(worstRoll, std::abs((stored - stored0) - kR * (g.tangentAngle - phi0) - c));
    }
    std::printf("wrapped drum: length from the geometry %.1e m, stored vs geometry %.1e m, energy %.1e of KE %.2f J; "
                "rope rolled on %.4f m and back off %.4f m (R times the tangent point's turn plus the creep to %.1e m; "
                "largest creep %.2e m)\n",
                worstLength, worstStored, worstEnergy / largestKinetic, largestKinetic, rolledOn, rolledOff,
                worstRoll, largestCreep);
    EXPECT_LE(worstLength, 1e-9);
    EXPECT_LE(worstStored, 2e-11);
    EXPECT_GT(largestCreep, 1e5 * 2e-11);  // the creep is seen: without it the checks fail
    EXPECT_LE(worstEnergy, 1e-8 * largestKinetic);
    EXPECT_GT(rolledOn, 0.02);  // the swing rolls rope on the drum and back off it
    EXPECT_GT(rolledOff, 0.02);
    EXPECT_LE(worstRoll, 2e-11);
}

// A state's first realization lays the stored ring with the grip's creep like any other: a default
// state given the Y of a run's state (say, one read back from a saved trajectory) has that state's
// energy and accelerations. Before the creep was set after the fresh rope data of a first
// realization, it was dropped there: the ring laid from s instead of s - c, the energy off by about
// rhoA c g R. Measured at t = 1.5 s (creep 6.6e-6 m from the geometry, rhoA c g R = 1.9e-5 J): energy
// 9.1e-13 J (bound 1e-10 J; 7.9e-6 J with the creep dropped), state rates 6.1e-12 of their norm (the
// span's Newton solve warm-started from elsewhere; bound 1e-10; the ring's missing mass rhoA c moves
// them no more than that).
TEST(WrappedDrum, FirstRealizationOfAStateKeepsTheGripsCreep) {
    SwingingLoad s;
    RungeKuttaMersonIntegrator integ(s.system);
    integ.setAccuracy(1e-9);
    TimeStepper ts(s.system, integ);
    ts.initialize(s.state);
    ts.stepTo(1.5);
    State run = integ.getState();
    s.system.realize(run, Stage::Acceleration);
    State fresh = s.system.getDefaultState();
    fresh.setTime(run.getTime());
    fresh.updY() = run.getY();
    s.system.realize(fresh, Stage::Acceleration);
    // The creep from the geometry: the stored rope beyond what the tangent point's roll covers.
    const double creep = std::abs(s.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(run) - kStored -
                                  measureDrumGeometry(s, run).arcFromTop);
    const double energyGap = std::abs(s.reeving->calcMechanicalEnergy(fresh) - s.reeving->calcMechanicalEnergy(run));
    const Vector gap = fresh.getYDot() - run.getYDot();
    const double accelerationGap = std::sqrt(gap.normSqr()), largest = std::sqrt(run.getYDot().normSqr());
    std::printf("first realization: energy %.1e J, rates %.1e of %.2e; creep %.2e m (rhoA c g R = %.1e J)\n",
                energyGap, accelerationGap, largest, creep, 1.2 * creep * kG * kR);
    EXPECT_GT(1.2 * creep * kG * kR, 1e4 * 1e-10);  // the creep is large enough to be seen
    EXPECT_LE(energyGap, 1e-10);
    EXPECT_LE(accelerationGap, 1e-10 * largest);
}
