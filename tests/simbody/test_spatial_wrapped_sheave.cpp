// A spatial rope over a wrapped deviation sheave whose groove is tilted out of the rope's plane:
// the rope comes from an anchor off the groove's plane (a fleet angle of a few degrees where it
// arrives on the groove), runs on the groove and falls to a load free to move in 3D. Static
// forces against the closed form of a weightless rope over a frictionless groove, energy of a load
// swinging in 3D, and the planar model reproduced when nothing leaves the plane.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include "support/ExpectThrowMessage.h"
#include "support/GripCreep.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <memory>

using namespace SimTK;
namespace sr = SimbodyReeving;

namespace {

constexpr double kG = 9.81;
constexpr double kLoad = 500.0;  // [kg]
constexpr double kR = 0.3;       // groove radius [m]

Eigen::Vector3d toEigen(const Vec3& v) { return {v[0], v[1], v[2]}; }

struct Options {
    Vec3 axis = Vec3(0.1, 0, 1).normalize();  // the groove's axis (tilted about y)
    Vec3 anchor = Vec3(-3, 0.3, -0.1);          // off the groove's plane
    sr::RopeProperties properties{1e-9, 16.5e6, 0.0};  // weightless (1e-9 kg/m): the closed form's rope
    int axialModes = 0, transverseModes = 0;
    bool planar = false;  // a planar rope (planeNormal +z) instead
    bool wrapped = true;  // false: SheaveModel::Point
    double unstretchedLength = 3.0 + 0.5 * Pi * kR + 5.0;  // [m]
    Vec3 loadStart = Vec3(kR, -5.0, 0);                    // [m]
};

// Anchor -> over the top of a Ground sheave at the origin (clockwise about its axis, sense -1)
// -> down its right-hand side 5 m to the load (a Translation body, the rope at its centre).
struct Scene {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    Force::Gravity gravity{forces, matter, -YAxis, kG};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Translation load;
    State state;

    explicit Scene(const Options& o) {
        load = MobilizedBody::Translation(matter.Ground(), Transform(),
                                          Body::Rigid(MassProperties(kLoad, Vec3(0), Inertia(1))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0, -kG, 0));
        sr::RopeSpec rope;
        rope.sheaveModel = o.wrapped ? sr::SheaveModel::Wrapped : sr::SheaveModel::Point;
        rope.properties = o.properties;
        rope.spanDefaults.axialModes = o.axialModes;
        rope.spanDefaults.transverseModes = o.transverseModes;
        if (o.planar) rope.planeNormal = Vec3(0, 0, 1);
        rope.start = sr::RopeAnchor{matter.Ground(), o.anchor};
        sr::DeviationSheave sheave{matter.Ground(), Vec3(0), kR};
        sheave.wrapSense = -1;
        sheave.axis = o.axis;
        rope.sheaves = {sheave};
        rope.end = sr::RopeAnchor{load, Vec3(0)};
        rope.unstretchedLength = o.unstretchedLength;
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
        load.setQToFitTranslation(state, o.loadStart);
    }
};

// The closed form of the weightless rope over a frictionless groove at rest: the load hangs
// straight down from the departing tangent point, the rope's force P = M g everywhere, the anchor
// pulled towards the arriving tangent point T_in, the sheave by P (u_out - u_in). T_in from the
// geometry: the point c + R e of the groove circle (e in the groove's plane) whose tangent passes
// through the anchor A, e . (A - c) = R, on the side the rope wraps (sigma (n x e) . u_in > 0).
struct ClosedForm {
    Eigen::Vector3d tangentIn, tangentOut, anchorForce, sheaveForce, loadForce;
    double fleetIn = 0;  // asin(u_in . n)
    double wrapAngle = 0;  // from T_in to T_out about n, in the rope's sense
};
ClosedForm closedForm(const Options& o) {
    const Eigen::Vector3d n = toEigen(o.axis).normalized(), A = toEigen(o.anchor), c(0, 0, 0);
    const Eigen::Vector3d a1 = n.unitOrthogonal(), a2 = n.cross(a1);
    // e = cos(b) a1 + sin(b) a2 with e . d = R, d = A - c: k cos(b - b0) = R.
    const Eigen::Vector3d d = A - c;
    const double k = std::hypot(a1.dot(d), a2.dot(d)), b0 = std::atan2(a2.dot(d), a1.dot(d));
    ClosedForm out;
    for (double sign : {1.0, -1.0}) {
        const double b = b0 + sign * std::acos(kR / k);
        const Eigen::Vector3d e = std::cos(b) * a1 + std::sin(b) * a2, T = c + kR * e;
        const Eigen::Vector3d u = (T - A).normalized();
        if (-1.0 * n.cross(e).dot(u) > 0) {  // sigma = -1
            out.tangentIn = T;
            // The fall leaves vertically: e_out normal to n and to the vertical, on the +x side.
            Eigen::Vector3d eOut = n.cross(Eigen::Vector3d(0, 1, 0)).normalized();
            if (eOut[0] < 0) eOut = -eOut;
            out.tangentOut = c + kR * eOut;
            out.wrapAngle = -std::atan2(n.dot(e.cross(eOut)), e.dot(eOut));
            if (out.wrapAngle < 0) out.wrapAngle += 2 * Pi;
            out.fleetIn = std::asin(u.dot(n));
            const double P = kLoad * kG;
            const Eigen::Vector3d down(0, -1, 0);
            out.anchorForce = P * u;
            out.sheaveForce = P * (down - u);
            out.loadForce = P * Eigen::Vector3d(0, 1, 0);
        }
    }
    return out;
}

// The anchor's force in closed form for the model's groove: the arriving span's projection onto
// the groove's plane touches the pitch circle at T_in (the usual fleet-angle geometry, ClosedForm
// above), the rope lies on the pitch circle from T_in to T_out, and the rope on that arc is
// inextensible (R alpha of unstretched rope). At rest the anchor's force is then -dV/dA at the
// sheave's material coordinate s_k (stationary: the tension equality) and the load's position:
//     F_A = -P_l grad l_in(A) + R (dV/ds)_out grad alpha(A),
// l_in = |T_in(A) - A|, alpha(A) the wrap angle, the departing span's unstretched length
// L - s_k - R alpha; per unstretched length V = EA eps^2 / 2 (eps = (lambda^2 - 1) / 2, lambda =
// l / s the stretch), so the span's pull P_l = dV/dl = EA eps lambda and dV/ds = EA (eps^2 / 2 -
// eps lambda^2). lambda from P_l = M g (lambda^3 - lambda = 2 M g / EA); the gradients of the
// closed-form geometry by central differences (h = 1e-5 m: truncation and round-off below 1e-10).
struct AnchorForce {
    Eigen::Vector3d force;  // [N]
    double lambda = 1;      // the rope's stretch
};
AnchorForce anchorForceOfTheModelsGroove(const Options& o) {
    const double P = kLoad * kG, EA = o.properties.axialStiffness;
    double lambda = 1;
    for (int i = 0; i < 50; ++i) lambda -= (lambda * lambda * lambda - lambda - 2 * P / EA) / (3 * lambda * lambda - 1);
    const double eps = 0.5 * (lambda * lambda - 1);
    const double pull = EA * eps * lambda, dVds = EA * (0.5 * eps * eps - eps * lambda * lambda);
    auto geometry = [&](const Eigen::Vector3d& A) {
        Options moved = o;
        moved.anchor = Vec3(A[0], A[1], A[2]);
        const ClosedForm cf = closedForm(moved);
        return std::pair<double, double>((cf.tangentIn - A).norm(), cf.wrapAngle);
    };
    const Eigen::Vector3d A = toEigen(o.anchor);
    const double h = 1e-5;
    Eigen::Vector3d gradLength, gradAlpha;
    for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e[i] = h;
        const auto [lp, ap] = geometry(A + e);
        const auto [lm, am] = geometry(A - e);
        gradLength[i] = (lp - lm) / (2 * h);
        gradAlpha[i] = (ap - am) / (2 * h);
    }
    return {-pull * gradLength + kR * dVds * gradAlpha, lambda};
}

// The largest entry of the antisymmetric part of du_in/dA [1/m], u_in(A) the unit vector from the
// anchor to T_in (central differences, h = 1e-5 m): not 0, so u_in(A) is no gradient.
double curlOfTheArrivingDirection(const Options& o) {
    const double h = 1e-5;
    double dudA[3][3];  // (no Eigen::Matrix3d beside SimTK's operators)
    for (int i = 0; i < 3; ++i) {
        Options plus = o, minus = o;
        plus.anchor[i] += h;
        minus.anchor[i] -= h;
        const Eigen::Vector3d up = closedForm(plus).anchorForce.normalized(), um = closedForm(minus).anchorForce.normalized();
        for (int r = 0; r < 3; ++r) dudA[r][i] = (up[r] - um[r]) / (2 * h);
    }
    double worst = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) worst = std::max(worst, std::abs(0.5 * (dudA[i][j] - dudA[j][i])));
    return worst;
}

}  // namespace

// Static forces of the weightless rope against the closed form (the rope's weight is 1e-9 kg/m:
// 8e-9 N against M g = 4905 N, 2e-12): the load's force, the arriving tangent point and the
// fleet angle there, asin(u_in . n), and the anchor's force (anchorForceOfTheModelsGroove) within
// 1e-9 (of M g, m, rad; measured below).
// The anchor's force is not along the arriving span u_in: it is tilted from it by (1 - cos
// gamma_in) R / l_in plus eps R / l_in (to first order; gamma_in the fleet angle, l_in the
// arriving span's length), 9.05e-4 rad here. The second part is the inextensible arc's: the rope
// that the tangent point's roll takes off the arc carries no stretch. The first is the pitch
// circle's: moving the anchor by dA moves T_in along the groove by R dalpha, which changes l_in by
// R cos gamma dalpha only, so grad (l_in + R alpha) = -u_in + (1 - cos gamma) R grad alpha. No
// rope length function of A has -u_in as its gradient here (the field u_in(A) has a curl: the
// antisymmetric part of du/dA is 2.2e-3 1/m at this anchor, curlOfTheArrivingDirection, printed),
// so no conservative model that puts the rope on the pitch circle from the projected tangent point
// can pull the anchor along u_in. A real rope entering at a fleet angle first touches the groove's
// flank: its pull along the span needs a model of the groove's profile (docs/verification.md).
TEST(SpatialWrappedSheave, StaticForcesMatchTheClosedForm) {
    Options o;
    Scene sc(o);
    ASSERT_LE(sc.reeving->findStaticEquilibrium(sc.state, 1e-12), 1e-12);
    sc.system.realize(sc.state, Stage::Dynamics);
    const ClosedForm cf = closedForm(o);
    const AnchorForce expected = anchorForceOfTheModelsGroove(o);
    const double P = kLoad * kG, eps = P / o.properties.axialStiffness;
    const double lin = (cf.tangentIn - toEigen(o.anchor)).norm();
    const Eigen::Vector3d anchorForce = toEigen(sc.reeving->getNodeForce(sc.state, 0, 0));
    const double anchor = (anchorForce - expected.force).norm() / P;
    const double anchorTilt = std::acos(std::min(1.0, anchorForce.normalized().dot(cf.anchorForce.normalized())));
    const double load = (toEigen(sc.reeving->getNodeForce(sc.state, 0, 2)) - cf.loadForce).norm() / P;
    const double tangent = (toEigen(sc.reeving->sampleSpan(sc.state, 0, 0, 2).back()) - cf.tangentIn).norm();
    const auto [fleetStart, fleetIn] = sc.reeving->getFleetAngles(sc.state, 0, 0);
    const auto [fleetOut, fleetEnd] = sc.reeving->getFleetAngles(sc.state, 0, 1);
    std::printf("spatial wrapped sheave at rest: load %.2e, anchor %.2e of M g off the closed form (its tilt from u_in "
                "%.3e rad; (1 - cos gamma) R / l_in %.3e, eps R / l_in %.2e; curl of u_in(A) %.2e 1/m); T_in %.2e m; "
                "fleet angle in %.4f deg (closed form %.4f), out %.2e rad\n",
                load, anchor, anchorTilt, (1 - std::cos(cf.fleetIn)) * kR / lin, eps * kR / lin,
                curlOfTheArrivingDirection(o), tangent, fleetIn * 180 / Pi, cf.fleetIn * 180 / Pi, fleetOut);
    EXPECT_GT(std::abs(cf.fleetIn), 3 * Pi / 180);  // a fleet angle of a few degrees
    EXPECT_LT(load, 1e-9);
    EXPECT_LT(anchor, 1e-9);
    EXPECT_LT(tangent, 1e-9);
    EXPECT_NEAR(fleetIn, cf.fleetIn, 1e-9);
    EXPECT_EQ(fleetStart, 0.0);  // the anchor is a point
    EXPECT_EQ(fleetEnd, 0.0);
    EXPECT_LT(std::abs(fleetOut), 1e-9);  // the fall lies in the tilted groove's plane (the tilt is about y)
}

// A load swinging in 3D under the tilted groove on a real rope (Table 1's, with one axial and
// one transverse mode per direction), pushed out of the rope's plane and along it: the rope wraps
// more and less of the groove at changing fleet angles. Energy drift over 10 s below 1e-9 of the
// initial kinetic energy (RK-Merson 1e-10; measured below).
TEST(SpatialWrappedSheave, SwingingLoadConservesEnergy) {
    Options o;
    o.properties = {0.6205, 16.5e6, 30.9};
    o.axialModes = 1;
    o.transverseModes = 1;
    Scene sc(o);
    ASSERT_LE(sc.reeving->findStaticEquilibrium(sc.state, 1e-12), 1e-12);
    sc.load.setUToFitLinearVelocity(sc.state, Vec3(0.6, 0, 0.5));
    sc.system.realize(sc.state, Stage::Velocity);
    const double kinetic0 = sc.system.calcKineticEnergy(sc.state) + sc.reeving->calcRopeKineticEnergy(sc.state);
    const double e0 = sc.reeving->calcMechanicalEnergy(sc.state);
    RungeKuttaMersonIntegrator integ(sc.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(sc.system, integ);
    ts.initialize(sc.state);
    double drift = 0, fleetLow = 1e9, fleetHigh = -1e9, wrapLow = 1e9, wrapHigh = -1e9;
    for (int i = 1; i <= 100; ++i) {
        ts.stepTo(0.1 * i);
        const State& s = integ.getState();
        sc.system.realize(s, Stage::Velocity);
        drift = std::max(drift, std::abs(sc.reeving->calcMechanicalEnergy(s) - e0));
        const double fleet = sc.reeving->getFleetAngles(s, 0, 1).first;
        fleetLow = std::min(fleetLow, fleet);
        fleetHigh = std::max(fleetHigh, fleet);
        const double wrap = sc.reeving->getWrapAngle(s, 0, 1);
        wrapLow = std::min(wrapLow, wrap);
        wrapHigh = std::max(wrapHigh, wrap);
    }
    std::printf("spatial wrapped sheave, swinging load: drift %.2e of KE0 %.1f J over 10 s (%d steps); fall's fleet "
                "angle %.2f..%.2f deg, wrap angle %.3f..%.3f rad\n",
                drift / kinetic0, kinetic0, integ.getNumStepsTaken(), fleetLow * 180 / Pi, fleetHigh * 180 / Pi, wrapLow,
                wrapHigh);
    EXPECT_GT(fleetHigh - fleetLow, 2 * Pi / 180);  // the fall swings out of the groove's plane
    EXPECT_LT(drift, 1e-9 * kinetic0);
}

// With the groove's axis +z and the anchor in the plane z = 0, the spatial rope is the planar
// one: at static equilibrium and along a swing (the states of a planar run set on the spatial
// scene), the load's acceleration and every node force agree to round-off (measured 4.5e-13 of
// g and M g; bound 1e-11). (No modes: the two ropes' states are then the load's alone.)
TEST(SpatialWrappedSheave, InThePlaneReproducesThePlanarRope) {
    Options o;
    o.axis = Vec3(0, 0, 1);
    o.anchor = Vec3(-3, 0.3, 0);
    o.properties = {0.6205, 16.5e6, 0.0};
    Options p = o;
    p.planar = true;
    Scene spatial(o), planar(p);
    ASSERT_LE(planar.reeving->findStaticEquilibrium(planar.state, 1e-12), 1e-12);
    planar.load.setUToFitLinearVelocity(planar.state, Vec3(0.8, 0.1, 0));
    RungeKuttaMersonIntegrator integ(planar.system);
    integ.setAccuracy(1e-8);
    TimeStepper ts(planar.system, integ);
    ts.initialize(planar.state);
    double worst = 0;
    for (int i = 0; i <= 10; ++i) {
        if (i > 0) ts.stepTo(0.2 * i);
        const State& s = integ.getState();
        planar.system.realize(s, Stage::Acceleration);
        spatial.state.updQ() = s.getQ();
        spatial.state.updU() = s.getU();
        spatial.state.setTime(s.getTime());
        spatial.system.realize(spatial.state, Stage::Acceleration);
        worst = std::max(worst, (spatial.load.getBodyOriginAcceleration(spatial.state) -
                                 planar.load.getBodyOriginAcceleration(s)).norm() / kG);
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, (spatial.reeving->getNodeForce(spatial.state, 0, k) -
                                     planar.reeving->getNodeForce(s, 0, k)).norm() / (kLoad * kG));
    }
    std::printf("spatial rope in the plane vs planar rope: %.2e\n", worst);
    EXPECT_LT(worst, 1e-11);
}

// Bad input, one clear error at addRope: a groove axis of zero length or not a unit vector, a
// wrapped TractionSheave whose pin's parent turns (its grip is measured from Ground's angles). (A
// DeviationSheave on a body that turns, a TurningSheave and a WinchDrum whose pin's parent turns
// about another axis than the pin's, and a TractionSheave on a pin whose axis is not the plane's,
// are accepted: their axes turn with it, or the groove is the pin's.)
TEST(SpatialWrappedSheave, RejectsBadAxesAndATractionSheaveOnATurningParent) {
    for (const Vec3& axis : {Vec3(0), Vec3(0, 0, 2), Vec3(NaN, 0, 1)}) {
        Options o;
        o.axis = axis;
        EXPECT_THROW_MESSAGE(Scene{o}, std::invalid_argument, "must be a unit vector");
    }
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    sr::ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    // A pin turning about Ground's x: a groove whose axis is z would turn with it.
    const Transform aboutX(Rotation(0.5 * Pi, YAxis), Vec3(0));
    MobilizedBody::Pin pin(matter.Ground(), aboutX, Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))), aboutX);
    sr::RopeSpec rope;
    rope.sheaveModel = sr::SheaveModel::Wrapped;
    rope.properties = {0.6, 1e6, 0.0};
    rope.unstretchedLength = 10;
    rope.start = sr::RopeAnchor{matter.Ground(), Vec3(-3, 0, 0)};
    sr::DeviationSheave sheave{pin, Vec3(0), kR};
    sheave.axis = Vec3(0, 0, 1);
    rope.sheaves = {sheave};
    rope.end = sr::RopeAnchor{matter.Ground(), Vec3(3, -5, 0)};
    EXPECT_NO_THROW(reeving.addRope(rope));
    // A sheave pinned about z on the pin above: its parent turns about x.
    MobilizedBody::Pin grip(pin, Transform(), Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))), Transform());
    sr::TurningSheave turning;
    turning.body = grip;
    turning.radius = kR;
    rope.sheaves = {turning};
    EXPECT_NO_THROW(reeving.addRope(rope));
    sr::WinchDrum drum;
    drum.body = grip;
    drum.radius = kR;
    rope.sheaves = {};
    rope.start = drum;
    EXPECT_NO_THROW(reeving.addRope(rope));  // a drum whose axis turns (its stored rope tumbles with it)
    rope.start = sr::RopeAnchor{matter.Ground(), Vec3(-3, 0, 0)};
    sr::TractionSheave traction;
    traction.body = pin;
    traction.radius = kR;
    traction.frictionCoefficient = 0.1;
    rope.sheaves = {traction};
    EXPECT_NO_THROW(reeving.addRope(rope));
    traction.body = grip;
    rope.sheaves = {traction};
    EXPECT_THROW_MESSAGE(reeving.addRope(rope), std::invalid_argument,
                         "TractionSheave at node 1: with SheaveModel::Wrapped its pin's parent must be Ground or "
                         "translate without turning");
}

// A held wrapped WinchDrum on a spatial rope (its pin axis +z, the groove in the x-y plane): a load
// pushed along and out of the drum's plane swings in 3D, the rope rolling on and off the groove at
// a changing fleet angle. Energy drift over 10 s below 1e-9 of the initial kinetic energy
// (RK-Merson 1e-10; measured 2.5e-10), and the stored rope changes by what rolled off the groove:
// R times the tangent point's turn about the axis, measured from the tangent point's position,
// plus the creep of the gripped rope against the groove (GripCreep, from the stretch at the
// tangent point every 20 ms; the largest 6.5e-6 m): measured 7.5e-11 m of 0.022 m rolled; bound
// 1e-9 m (13x).
TEST(SpatialWrappedSheave, HeldDrumWithALoadSwingingInSpace) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, -YAxis, kG);
    MobilizedBody::Pin drum(matter.Ground(), Transform(), Body::Rigid(MassProperties(20, Vec3(0), Inertia(0.6))),
                            Transform());
    Motion::Steady(drum, 0.0);
    MobilizedBody::Translation load(matter.Ground(), Transform(),
                                    Body::Rigid(MassProperties(kLoad, Vec3(0), Inertia(1))), Transform());
    sr::ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    sr::RopeSpec rope;
    rope.sheaveModel = sr::SheaveModel::Wrapped;
    rope.properties = {0.6205, 16.5e6, 30.9};
    rope.spanDefaults.axialModes = 1;
    rope.spanDefaults.transverseModes = 1;
    sr::WinchDrum d;
    d.body = drum;
    d.radius = kR;
    d.ropeOnDrum = 2.0;
    d.payoutSense = -1;  // the rope leaves the drum's right-hand side going down: clockwise about +z
    rope.start = d;
    rope.end = sr::RopeAnchor{load, Vec3(0)};
    rope.unstretchedLength = 0.5 * Pi * kR + 5.0;
    reeving.addRope(rope);
    system.realizeTopology();
    State state = system.getDefaultState();
    load.setQToFitTranslation(state, Vec3(kR, -5.0, 0));
    ASSERT_LE(reeving.findStaticEquilibrium(state, 1e-12), 1e-12);
    load.setUToFitLinearVelocity(state, Vec3(0.5, 0, 0.6));
    system.realize(state, Stage::Velocity);
    const double kinetic0 = system.calcKineticEnergy(state) + reeving.calcRopeKineticEnergy(state);
    const double e0 = reeving.calcMechanicalEnergy(state);
    // The tangent point's angle about +z (the drum's axis) from its centre at the origin.
    auto tangentAngle = [&](const State& s) {
        const Vec3 T = reeving.sampleSpan(s, 0, 0, 2).front();
        return std::atan2(T[1], T[0]);
    };
    // The stretch at the tangent point, lambda = sqrt(1 + 2 P / EA) (the condensed strain, below
    // Stage::Dynamics).
    auto tangentStretch = [&](const State& s) {
        State c = s;
        c.invalidateAllCacheAtOrAbove(Stage::Dynamics);
        system.realize(c, Stage::Position);
        const double P = reeving.getAxialForce(c, 0, 0, reeving.getSpanMaterialRange(c, 0, 0).first);
        return std::sqrt(1 + 2 * P / rope.properties.axialStiffness);
    };
    const double stored0 = reeving.getRope(0).getWinchDrum(0).getRopeOnDrum(state), angle0 = tangentAngle(state);
    // The held drum grips the rope (RopeModel::setGrip): its creep c against the groove, integrated
    // here over the groove the tangent point covers in the rope's sense, -R times its turn.
    SimbodyReevingTest::GripCreep creep(tangentStretch(state), -kR * angle0);
    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(system, integ);
    ts.initialize(state);
    double drift = 0, fleetLow = 1e9, fleetHigh = -1e9, rolled = 0, worstRoll = 0, largestCreep = 0;
    for (int i = 1; i <= 500; ++i) {
        ts.stepTo(0.02 * i);
        const State& s = integ.getState();
        system.realize(s, Stage::Velocity);
        creep.add(tangentStretch(s), -kR * tangentAngle(s));
        drift = std::max(drift, std::abs(reeving.calcMechanicalEnergy(s) - e0));
        const double fleet = reeving.getFleetAngles(s, 0, 0).first;
        fleetLow = std::min(fleetLow, fleet);
        fleetHigh = std::max(fleetHigh, fleet);
        if (!creep.ready()) continue;
        const double stored = reeving.getRope(0).getWinchDrum(0).getRopeOnDrum(s), c = creep.value();
        // Clockwise rope (sigma = -1): the tangent point turning counter-clockwise unwinds R per
        // radian of groove, less the creep.
        rolled = std::max(rolled, std::abs(stored - stored0));
        largestCreep = std::max(largestCreep, std::abs(c));
        worstRoll = std::max(worstRoll, std::abs((stored - stored0) + kR * (tangentAngle(s) - angle0) - c));
    }
    std::printf("spatial held drum, swinging load: drift %.2e of KE0 %.1f J (%d steps); fleet angle %.2f..%.2f deg; "
                "stored rope rolled %.4f m, R times the tangent point's turn plus the creep to %.1e m (largest creep "
                "%.2e m)\n",
                drift / kinetic0, kinetic0, integ.getNumStepsTaken(), fleetLow * 180 / Pi, fleetHigh * 180 / Pi, rolled,
                worstRoll, largestCreep);
    EXPECT_GT(fleetHigh - fleetLow, 2 * Pi / 180);
    EXPECT_GT(rolled, 0.01);
    EXPECT_LT(worstRoll, 1e-9);
    EXPECT_LT(drift, 1e-9 * kinetic0);
}

// A load thrown out of the groove's plane so hard (12 m/s) that its fall swings towards the
// sheave's axis: the run ends where the fall's fleet angle reaches 85 degrees (short of the
// tangency's singularity at 90), with a message naming the rope, span and node, and the state
// there kept (its fleet angle 85 degrees to 1e-6 rad: the event's localization).
TEST(SpatialWrappedSheave, RunEndsWhereAFleetAngleReaches85Degrees) {
    Options o;
    o.properties = {0.6205, 16.5e6, 0.0};
    Scene sc(o);
    ASSERT_LE(sc.reeving->findStaticEquilibrium(sc.state, 1e-12), 1e-12);
    sc.load.setUToFitLinearVelocity(sc.state, Vec3(0, 0, 12));
    RungeKuttaMersonIntegrator integ(sc.system);
    integ.setAccuracy(1e-8);
    TimeStepper ts(sc.system, integ);
    ts.initialize(sc.state);
    const Integrator::SuccessfulStepStatus status = ts.stepTo(5.0);
    const State& s = integ.getState();
    sc.system.realize(s, Stage::Position);
    const double fleet = sc.reeving->getFleetAngles(s, 0, 1).first;
    std::printf("run ended at t = %.4f s: %s (fleet angle %.6f deg)\n", s.getTime(), sc.reeving->getLimitReached().c_str(),
                fleet * 180 / Pi);
    EXPECT_EQ(status, Integrator::EndOfSimulation);
    EXPECT_LT(s.getTime(), 5.0);
    EXPECT_NE(sc.reeving->getLimitReached().find("rope 'rope' span 1: its fleet angle at node 1 reached 85 degrees"),
              std::string::npos)
        << sc.reeving->getLimitReached();
    EXPECT_NEAR(std::abs(fleet), 85 * Pi / 180, 1e-6);
}

// A wrapped TurningSheave whose pin axis is tilted out of the plane the two loads hang in (0.1 rad
// about x): both falls leave the groove at fleet angles (0.1 rad at rest), the rope gripping the
// groove measured about the tilted axis from "up" projected onto its plane. Two 500 kg loads on
// free translations over the sheave (inertia 2 kg m^2), from static equilibrium, pushed along and
// across: T + U of the loads, the sheave and the rope stays within 1e-9 of the initial kinetic
// energy over 1.5 s (RK-Merson 1e-10; measured below; the sheave turning against the rope's axial
// stiffness, about 87 Hz, sets the step).
TEST(SpatialWrappedSheave, TiltedTurningSheaveConservesEnergy) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, -YAxis, kG);
    const Transform tilted(Rotation(0.1, XAxis), Vec3(0));
    MobilizedBody::Pin pin(matter.Ground(), tilted, Body::Rigid(MassProperties(20, Vec3(0), Inertia(2))), tilted);
    auto load = [&](double m) {
        return MobilizedBody::Translation(matter.Ground(), Transform(), Body::Rigid(MassProperties(m, Vec3(0), Inertia(1))),
                                          Transform());
    };
    MobilizedBody::Translation a = load(500), b = load(500);
    sr::ReevingSubsystem reeving(system, Vec3(0, -kG, 0));
    sr::RopeSpec rope;
    rope.sheaveModel = sr::SheaveModel::Wrapped;
    rope.properties = {0.6205, 16.5e6, 30.9};
    rope.spanDefaults.axialModes = 1;
    rope.spanDefaults.transverseModes = 1;
    rope.start = sr::RopeAnchor{a, Vec3(0)};
    sr::TurningSheave sheave;
    sheave.body = pin;
    sheave.radius = kR;
    sheave.sense = 1;  // up the left fall, over the top, down the right: clockwise about the axis
    sheave.materialCoordinateAtZeroAngle = 5.0 + 0.5 * Pi * kR;
    rope.sheaves = {sheave};
    rope.end = sr::RopeAnchor{b, Vec3(0)};
    rope.unstretchedLength = 9.0 + Pi * kR;
    reeving.addRope(rope);
    system.realizeTopology();
    State state = system.getDefaultState();
    a.setQToFitTranslation(state, Vec3(-kR, -5.0, 0));
    b.setQToFitTranslation(state, Vec3(kR, -4.0, 0));
    ASSERT_LE(reeving.findStaticEquilibrium(state, 1e-12), 1e-12);
    a.setUToFitLinearVelocity(state, Vec3(0.1, -0.3, 0.2));
    b.setUToFitLinearVelocity(state, Vec3(0, 0.3, -0.3));
    RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(system, integ);
    ts.initialize(state);
    system.realize(integ.getState(), Stage::Velocity);
    const double e0 = reeving.calcMechanicalEnergy(integ.getState());
    const double kinetic0 = system.calcKineticEnergy(integ.getState()) + reeving.calcRopeKineticEnergy(integ.getState());
    double drift = 0, fleet = 0;
    for (int i = 1; i <= 15; ++i) {
        ts.stepTo(0.1 * i);
        const State& s = integ.getState();
        system.realize(s, Stage::Velocity);
        drift = std::max(drift, std::abs(reeving.calcMechanicalEnergy(s) - e0));
        fleet = std::max({fleet, std::abs(reeving.getFleetAngles(s, 0, 0).second), std::abs(reeving.getFleetAngles(s, 0, 1).first)});
    }
    std::printf("tilted wrapped turning sheave: drift %.2e of KE0 %.1f J over 1.5 s (%d steps); fleet angles up to %.2f deg\n",
                drift / kinetic0, kinetic0, integ.getNumStepsTaken(), fleet * 180 / Pi);
    EXPECT_GT(fleet, 3 * Pi / 180);
    EXPECT_LT(drift, 1e-9 * kinetic0);
}

// A point sheave of a spatial rope has the turning angle between its two chords as its wrap angle,
// pi minus the angle between them at the node (computed here from the anchor, the sheave's point
// and the load's: measured 0 rad off, bound 1e-14), in the plane the chords span.
TEST(SpatialWrappedSheave, PointSheaveOfASpatialRopeHasTheChordsTurningAngle) {
    Options o;
    o.wrapped = false;
    o.loadStart = Vec3(0.4, -5.0, 0.7);
    Scene sc(o);
    sc.system.realize(sc.state, Stage::Position);
    const Eigen::Vector3d A = toEigen(o.anchor), S(0, 0, 0), B = toEigen(sc.load.getBodyOriginLocation(sc.state));
    const Eigen::Vector3d in = S - A, out = B - S;
    const double expected = std::atan2(in.cross(out).norm(), in.dot(out));
    const double alpha = sc.reeving->getWrapAngle(sc.state, 0, 1);
    std::printf("point sheave of a spatial rope: wrap angle %.6f rad, chords' turning angle %.6f rad (%.1e off)\n",
                alpha, expected, alpha - expected);
    EXPECT_GT(expected, 1.0);
    EXPECT_NEAR(alpha, expected, 1e-14);
    EXPECT_THROW_MESSAGE(sc.reeving->getWrapAngle(sc.state, 0, 0), std::invalid_argument, "end node");
}
