// A wrapped DeviationSheave of a spatial rope on a body that turns about another axis than the
// groove's (a jib head sheave on a slewing tower): the groove's axis turns with the body, the rope's
// Lagrange equations carry the body's angular velocity (RopeModel's NodeWrap::turningAxis) and
// its reaction on the sheave is a force at the centre plus a couple.
//  - A conical pendulum: the tower slews at a constant rate Omega, the load whirls with it under
//    the sheave. Its steady whirl, solved in the test from the rope's length and EA (massless
//    rope), holds: tan(beta) = Omega^2 r / g with r the load's distance from the slewing axis.
//  - A tower slewing back and forth with a tilted sheave (fleet angles of several degrees): the
//    rope's length from the geometry and the energy balance with the drive's work, for a
//    frictionless DeviationSheave and for a TurningSheave that grips the rope (the rope stays put
//    on its groove).
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.3;       // sheave radius [m]
constexpr double kLoad = 100.0;  // [kg]

// A tower turning about Ground's y (its frame aligned with Ground at q = 0), a wrapped sheave on
// it at `centre` with axis `axis` (tower frame), the rope from `anchor` (on the tower or on
// Ground) over the sheave to a load on a Translation mobilizer.
struct SlewingTower {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    std::unique_ptr<sr::MotionWorkMeter> meter;
    MobilizedBody::Pin tower, sheave;  // sheave: a TurningSheave's (gripping), else empty
    MobilizedBody::Translation load;
    State state;

    // rhoA [kg/m], EA [N]; anchorOnTower: the rope's start on the tower (else on Ground);
    // gripping: a TurningSheave pinned to the tower about `axis` (its wrap sense then follows
    // from its sense, +1: s = s_ref + R theta, and s_ref = sRef), else a DeviationSheave.
    SlewingTower(double rhoA, double EA, const Vec3& centre, const Vec3& axis, const Vec3& anchor, bool anchorOnTower,
                 double length, int sense, const std::function<void(MobilizedBody::Pin&)>& drive,
                 bool gripping = false, double sRef = 0) {
        const Transform aboutY(Rotation(-0.5 * Pi, XAxis), Vec3(0));  // the pin's z along Ground's y
        tower = MobilizedBody::Pin(matter.Ground(), aboutY,
                                   Body::Rigid(MassProperties(2000, Vec3(0, 3, 0), Inertia(Vec3(30000, 500, 30000)))),
                                   aboutY);
        drive(tower);
        load = MobilizedBody::Translation(matter.Ground(), Transform(),
                                          Body::Rigid(MassProperties(kLoad, Vec3(0), Inertia(1))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0, -kG, 0));
        meter = std::make_unique<sr::MotionWorkMeter>(system);
        sr::RopeSpec rope;
        rope.sheaveModel = sr::SheaveModel::Wrapped;
        rope.properties = {rhoA, EA, 0.0};
        rope.spanDefaults.axialModes = 0;       // straight spans of uniform strain: their material
        rope.spanDefaults.transverseModes = 0;  // is their length over their stretch
        rope.start = anchorOnTower ? sr::RopeAnchor{tower, anchor} : sr::RopeAnchor{matter.Ground(), anchor};
        if (gripping) {
            sheave = MobilizedBody::Pin(tower, Transform(Rotation(UnitVec3(axis), ZAxis), centre),
                                        Body::Rigid(MassProperties(40, Vec3(0), Inertia(0.9, 0.9, 1.8))), Transform());
            sr::TurningSheave groove;
            groove.body = sheave;
            groove.radius = kR;
            groove.sense = 1;
            groove.materialCoordinateAtZeroAngle = sRef;
            rope.sheaves = {groove};
        } else {
            sr::DeviationSheave groove{tower, centre, kR};
            groove.axis = axis;
            groove.wrapSense = sense;
            rope.sheaves = {groove};
        }
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        rope.unstretchedLength = length;
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

// The rope's length from the geometry: each straight span's length over its stretch
// sqrt(1 + 2 eps) (eps = P / EA, Green's strain, uniform without modes) plus R alpha, alpha the
// angle from T_in to T_out about the groove's axis as the tower carries it now (wrap sense
// `sense`).
double ropeLengthFromGeometry(const SlewingTower& t, const State& s, double EA, const Vec3& centre, const Vec3& axis,
                              int sense) {
    double length = 0;
    for (int j = 0; j < 2; ++j) {
        const std::vector<Vec3> ends = t.reeving->sampleSpan(s, 0, j, 2);
        const auto range = t.reeving->getSpanMaterialRange(s, 0, j);
        const double eps = t.reeving->getAxialForce(s, 0, j, 0.5 * (range.first + range.second)) / EA;
        length += (ends[1] - ends[0]).norm() / std::sqrt(1 + 2 * eps);
    }
    const Vec3 c = t.tower.findStationLocationInGround(s, centre);
    const Vec3 n = t.tower.getBodyRotation(s) * axis;
    const Vec3 in = t.reeving->sampleSpan(s, 0, 0, 2).back() - c, out = t.reeving->sampleSpan(s, 0, 1, 2).front() - c;
    double alpha = sense * std::atan2(dot(n, cross(in, out)), dot(in, out));
    if (alpha < 0) alpha += 2 * Pi;
    return length + kR * alpha;
}

}  // namespace

// The conical pendulum. The tower slews at Omega = 1.2 rad/s (Motion::Steady); its sheave, centre
// (a, h) = (4, 6) m, axis z of the tower (horizontal, turning with it), takes the rope from an
// anchor on the tower at (0, h + R), horizontal to the groove's top, and lets it fall to the load
// at an angle beta outwards. With a massless rope (rhoA = 1e-6 kg/m against a 100 kg load) the
// steady whirl is, in the tower's frame, an equilibrium: T cos(beta) = m g, T sin(beta) =
// m Omega^2 r, r = a + R cos(beta) + l sin(beta), the free span's length l = lambda (L - a / lambda
// - R (pi/2 - beta)), lambda = sqrt(1 + 2 T / EA) (Green's strain; the groove holds R alpha of
// unstretched rope). Solved here for beta; the load starts there, moving at Omega r. Over one
// revolution (RK-Merson 1e-10) its distance from the slewing axis, its height (relative to r) and
// its azimuth against Omega t (the whirl's rate) stay within 1e-6 of the
// closed form: measured 3.9e-8, 5.1e-8, 4.0e-8 rad. What remains is the groove's rope at its
// unstretched length (a load rests eps R off the tangent point's vertical: docs/verification.md,
// "What a wrapped groove does not model"): it scales with 1 / EA (4.1e-6 at EA = 1e7, also with
// the tower at rest), so EA = 1e9 here (eps = 1.6e-6).
TEST(WrappedSheaveOnSlewingBody, ConicalPendulumWhirlsAtTheClosedFormRate) {
    const double omega = 1.2, a = 4.0, h = 6.0, L = 10.0;
    const double m = kLoad, EA = 1e9;
    // beta from tan(beta) = Omega^2 r(beta) / g (bisection on [0, pi/2)).
    auto geometry = [&](double beta, double& r, double& y) {
        const double T = m * kG / std::cos(beta), lambda = std::sqrt(1 + 2 * T / EA);
        const double l = lambda * (L - a / lambda - kR * (0.5 * Pi - beta));
        r = a + kR * std::cos(beta) + l * std::sin(beta);
        y = h + kR * std::sin(beta) - l * std::cos(beta);
    };
    double lo = 0, hi = 1.5;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        double r, y;
        geometry(mid, r, y);
        (std::tan(mid) - omega * omega * r / kG > 0 ? hi : lo) = mid;
    }
    const double beta = 0.5 * (lo + hi);
    double r0, y0;
    geometry(beta, r0, y0);
    SlewingTower t(1e-6, EA, Vec3(a, h, 0), Vec3(0, 0, 1), Vec3(0, h + kR, 0), true, L, -1,
                   [&](MobilizedBody::Pin& tower) { Motion::Steady(tower, omega); });
    t.load.setQToFitTranslation(t.state, Vec3(r0, y0, 0));
    t.load.setUToFitLinearVelocity(t.state, Vec3(0, 0, -omega * r0));  // Omega y x r
    RungeKuttaMersonIntegrator integ(t.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(t.system, integ);
    ts.initialize(t.state);
    double radius = 0, height = 0, azimuth = 0;
    const double period = 2 * Pi / omega;
    for (int i = 1; i <= 40; ++i) {
        ts.stepTo(period * i / 40);
        const State& s = integ.getState();
        const Vec3 p = t.load.getBodyOriginLocation(s);
        radius = std::max(radius, std::abs(std::hypot(p[0], p[2]) - r0) / r0);
        height = std::max(height, std::abs(p[1] - y0) / r0);
        const double expected = omega * s.getTime();
        azimuth = std::max(azimuth, std::abs(std::remainder(std::atan2(-p[2], p[0]) - expected, 2 * Pi)));
    }
    std::printf("conical pendulum under a slewing wrapped sheave: beta = %.4f rad, r = %.4f m; over one revolution "
                "radius %.2e, height %.2e (of r), azimuth %.2e rad from Omega t\n",
                beta, r0, radius, height, azimuth);
    EXPECT_GT(beta, 0.3);
    EXPECT_LT(radius, 1e-6);
    EXPECT_LT(height, 1e-6);
    EXPECT_LT(azimuth, 1e-6);
}

// A tower slewing by 1.2 rad over 4 s, from rest to rest (Motion::Sinusoid), its sheave's axis
// tilted in the tower's frame, the rope from an anchor on Ground beside the slewing axis (fleet
// angles up to 31 degrees, changing as the tower turns) to a 100 kg load that swings in 3D, from
// its static equilibrium (the guess hangs the load 4 m under the groove's side on a 3.95 m free
// span: a taut rope for the static solve's Newton steps). The rope's length from the geometry
// stays L (both spans taut; measured 2.2e-16 relative, bound 1e-14) and T + U changes by the
// drive's work (MotionWorkMeter; measured 1.6e-10 J of 1354 J, 1.2e-13, bound 1e-11 of the work).
TEST(WrappedSheaveOnSlewingBody, SlewingTiltedSheaveKeepsTheRopesLengthAndTheEnergyBalance) {
    const Vec3 centre(4, 6, 0), axis = Vec3(0.15, 0.1, 1).normalize();
    const Vec3 anchor(0.2, 6.5, 0.5);
    const Rotation start(-0.6, YAxis);  // the tower's orientation at t = 0
    const double L = (start * (centre + Vec3(0, kR, 0)) - anchor).norm() + 0.5 * Pi * kR + 3.95;
    const double EA = 1e7;
    SlewingTower t(1.6, EA, centre, axis, anchor, false, L, -1, [](MobilizedBody::Pin& tower) {
        Motion::Sinusoid(tower, Motion::Position, 0.6, Pi / 4.0, -0.5 * Pi);
    });
    t.tower.setOneQ(t.state, 0, -0.6);
    t.system.realize(t.state, Stage::Position);
    t.load.setQToFitTranslation(t.state, t.tower.findStationLocationInGround(t.state, centre + Vec3(kR, -4.0, 0)));
    ASSERT_LE(t.reeving->findStaticEquilibrium(t.state, 1e-12), 1e-12);
    RungeKuttaMersonIntegrator integ(t.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(t.system, integ);
    ts.initialize(t.state);
    const State& s0 = integ.getState();
    t.system.realize(s0, Stage::Velocity);
    const double e0 = t.reeving->calcMechanicalEnergy(s0), w0 = t.meter->getWork(s0);
    double length = 0, energy = 0, work = 0, fleet = 0, swing = 0;
    const Vec3 p0 = t.load.getBodyOriginLocation(s0);
    for (int i = 1; i <= 50; ++i) {
        ts.stepTo(0.1 * i);
        const State& s = integ.getState();
        t.system.realize(s, Stage::Velocity);
        length = std::max(length, std::abs(ropeLengthFromGeometry(t, s, EA, centre, axis, -1) - L) / L);
        work = t.meter->getWork(s) - w0;
        energy = std::max(energy, std::abs(t.reeving->calcMechanicalEnergy(s) - e0 - work));
        for (int j = 0; j < 2; ++j) {
            const auto angles = t.reeving->getFleetAngles(s, 0, j);
            fleet = std::max({fleet, std::abs(angles.first), std::abs(angles.second)});
        }
        swing = std::max(swing, (t.load.getBodyOriginLocation(s) - p0).norm());
    }
    std::printf("slewing tower, tilted wrapped sheave: rope length from the geometry %.2e of L; E - E0 - W %.2e J of "
                "W = %.1f J; largest fleet angle %.1f deg; load moved %.2f m\n",
                length, energy, std::abs(work), fleet * 180 / Pi, swing);
    EXPECT_GT(fleet, 3 * Pi / 180);
    EXPECT_GT(swing, 1.0);
    EXPECT_LT(length, 1e-14);
    EXPECT_LT(energy, 1e-11 * std::abs(work));
}

namespace {

// The point of the groove that holds rope material `material`: from the arriving tangent point
// T_in (material s_in), R per unit of material about sigma n (sigma = -1: the rope turns
// clockwise about the pin axis n, the sheave's z), in the sheave's frame.
Vec3 materialPointOnSheave(const SlewingTower& t, const State& s, double material) {
    const std::vector<Vec3> arc = t.reeving->sampleArc(s, 0, 1, 2);
    const double sIn = t.reeving->getMaterialCoordinate(s, 0, 1);
    const Vec3 c = t.sheave.getBodyOriginLocation(s);
    const Vec3 n = t.sheave.getBodyRotation(s).z();
    const Vec3 d = arc.front() - c;
    const double theta = (material - sIn) / kR;
    const Vec3 p = c + std::cos(theta) * d + std::sin(theta) * cross(-n, d);
    return t.sheave.findStationAtGroundPoint(s, p);
}

}  // namespace

// A TurningSheave (gripping the rope, free on its pin) on the tower slewing 1.2 rad in 4 s, its pin
// axis tilted in the tower's frame (so the groove's axis turns with the tower), the rope from an
// anchor on Ground to a load swinging in 3D, from static equilibrium. The grip holds: the rope's
// material at the middle of the arc stays at its place on the sheave (the sheave's angle is
// measured about the turning axis from "up" projected onto the groove's plane, as the rope
// model's grip: a wrong rate of that angle slides the rope on the groove); the rope's length from
// the geometry stays L; T + U changes by the drive's work. Measured: 1.7e-15 m (bound 1e-12 m),
// 2.2e-16 of L (bound 1e-14), 1.1e-10 J of 1390 J (bound 1e-11 of the work); fleet angles up to
// 31 degrees, the sheave turning 1.95 rad on its pin.
TEST(WrappedSheaveOnSlewingBody, GrippingSheaveOnASlewingTowerCarriesTheRope) {
    const Vec3 centre(4, 6, 0), axis = Vec3(0.15, 0.1, 1).normalize();
    const Vec3 anchor(0.2, 6.5, 0.5);
    const Rotation start(-0.6, YAxis);
    const double anchorSpan = (start * (centre + Vec3(0, kR, 0)) - anchor).norm();
    const double L = anchorSpan + 0.5 * Pi * kR + 3.95;
    const double EA = 1e7;
    SlewingTower t(1.6, EA, centre, axis, anchor, false, L, -1, [](MobilizedBody::Pin& tower) {
        Motion::Sinusoid(tower, Motion::Position, 0.6, Pi / 4.0, -0.5 * Pi);
    }, true, anchorSpan);
    t.tower.setOneQ(t.state, 0, -0.6);
    t.system.realize(t.state, Stage::Position);
    t.load.setQToFitTranslation(t.state, t.tower.findStationLocationInGround(t.state, centre + Vec3(kR, -4.0, 0)));
    ASSERT_LE(t.reeving->findStaticEquilibrium(t.state, 1e-11), 1e-11);  // (1.4e-12 reached: the free sheave)
    RungeKuttaMersonIntegrator integ(t.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(t.system, integ);
    ts.initialize(t.state);
    const State& s0 = integ.getState();
    t.system.realize(s0, Stage::Velocity);
    const double e0 = t.reeving->calcMechanicalEnergy(s0), w0 = t.meter->getWork(s0);
    const double sMid = 0.5 * (t.reeving->getMaterialCoordinate(s0, 0, 1) + t.reeving->getSpanMaterialRange(s0, 0, 1).first);
    const Vec3 point0 = materialPointOnSheave(t, s0, sMid);
    double slide = 0, length = 0, energy = 0, work = 0, fleet = 0, spin = 0;
    const double q0 = t.sheave.getOneQ(s0, 0);
    for (int i = 1; i <= 50; ++i) {
        ts.stepTo(0.1 * i);
        const State& s = integ.getState();
        t.system.realize(s, Stage::Velocity);
        slide = std::max(slide, (materialPointOnSheave(t, s, sMid) - point0).norm());
        length = std::max(length, std::abs(ropeLengthFromGeometry(t, s, EA, centre, axis, -1) - L) / L);
        work = t.meter->getWork(s) - w0;
        energy = std::max(energy, std::abs(t.reeving->calcMechanicalEnergy(s) - e0 - work));
        for (int j = 0; j < 2; ++j) {
            const auto angles = t.reeving->getFleetAngles(s, 0, j);
            fleet = std::max({fleet, std::abs(angles.first), std::abs(angles.second)});
        }
        spin = std::max(spin, std::abs(t.sheave.getOneQ(s, 0) - q0));
    }
    std::printf("slewing tower, gripping sheave: rope point on the groove moved %.2e m; rope length from the geometry "
                "%.2e of L; E - E0 - W %.2e J of W = %.1f J; largest fleet angle %.1f deg; sheave turned %.2f rad\n",
                slide, length, energy, std::abs(work), fleet * 180 / Pi, spin);
    EXPECT_GT(fleet, 3 * Pi / 180);
    EXPECT_GT(spin, 0.1);
    EXPECT_LT(slide, 1e-12);
    EXPECT_LT(length, 1e-14);
    EXPECT_LT(energy, 1e-11 * std::abs(work));
}
