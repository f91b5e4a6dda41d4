// A traction sheave on a spatial rope whose spans leave the groove's plane. Two winch drums run the
// rope over a held traction sheave in zero gravity (after a smooth ramp to 10 m/s), so the slip
// becomes steady. The machine is built in a local frame L (x, y, z_L) and placed in Ground turned
// by Q (the groove's plane tilted against Ground's x-y plane): the sheave's pin axis and the
// drums' are Q z_L, and the drums stand out of the sheave's plane along z_L (drum 1 by -0.4 m,
// drum 2 by +0.8 m, drum 2 also leaning 2 m further out in x), so both spans arrive and leave at a
// fleet angle of about 2.9 degrees.
//
// Every reference is computed here from the machine's dimensions. A span between two grooves
// whose planes are parallel (normal z_L) touches each at R u with u in its plane and
// (T_b - T_a) . u = 0 at both ends: the offset along z_L drops out, so the tangent points are the
// planar crossed tangents of the circles projected onto the groove's plane (u = k D + h J D over
// |D|, k = (R + R_d) / |D|, h = -+sqrt(1 - k^2), D the drum's centre projected), the span's length
// is sqrt(|D|^2 - (R + R_d)^2 + dz^2) and its fleet angle atan(|dz| / sqrt(|D|^2 - (R + R_d)^2)).
// The wrap angle at the wrapped sheave is the angle in the groove's plane between the radius
// vectors to the two tangent points (clockwise about z_L: the rope runs up drum 1's side, over
// the top and down drum 2's side); at a point sheave the turning angle of the 3D chords to the
// drums' centres, pi - angle(D_1, D_2). The slip speed v is the drums' material rate.
#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

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

constexpr double kMu = 0.1;
constexpr double kR = 0.3;       // the traction sheave [m]
constexpr double kDrum = 0.5;    // the drums' radius [m]
constexpr double kRhoA = 2.0;    // [kg/m]: rhoA v^2 = 200 N at 10 m/s
constexpr double kEA = 5e8;      // [N]
constexpr double kStretch = 2e-4;
constexpr double kSpeed = 10.0;  // the drums' material rate after the ramp [m/s]

// 8 m of rope at 10 m/s after 0.2 s ramps (decelerating from 0.8 s).
sr::MotionProfile drumMove() {
    sr::MotionProfile move;
    move.moves = {sr::SmoothMove{0.0, 1.0, 0.2, 8.0}};
    return move;
}

struct Options {
    sr::TractionSlip slip = sr::TractionSlip::RopeMomentum;
    sr::SheaveModel model = sr::SheaveModel::Wrapped;
    bool tilted = true;     // Q = Rx(0.5) Ry(0.3); else Q = identity
    double dz1 = -0.4;      // drum 1 out of the sheave's plane along z_L [m]
    double dz2 = 0.8;       // drum 2 likewise [m]
    double lean = 2.0;      // drum 2 this much further out in x [m]
    bool planar = false;    // a planar rope (plane normal z_L): needs dz1 = dz2 = 0
    // Drum 2's surface speed over drum 1's: wrapped drums grip the rope (RopeModel::setGrip) and
    // move material at their surface speed over their span's stretch, so a steady slip needs
    // lambda_b / lambda_a (steadied()); 1 with point drums.
    double drum2Speed = 1;
};

Rotation tilt(const Options& o) {
    return o.tilted ? Rotation(0.5, XAxis) * Rotation(0.3, YAxis) : Rotation();
}

// Drum i's centre in L, from the sheave's centre (the origin).
Vec3 drumCentre(const Options& o, int drum) {
    const double out = o.model == sr::SheaveModel::Wrapped ? kR + kDrum : kR;
    return drum == 1 ? Vec3(-out, -8, o.dz1) : Vec3(out + o.lean, -16, o.dz2);
}

// The crossed tangent's unit radius vector at the sheave, in L (z_L = 0): drum 1 on the left
// (h = -1), drum 2 on the right (h = +1).
Vec3 tangentNormal(const Options& o, int drum) {
    const Vec3 c = drumCentre(o, drum), D(c[0], c[1], 0);
    const double k = (kR + kDrum) / D.norm(), h = drum == 1 ? -1.0 : 1.0;
    const Vec3 u = D / D.norm(), ju(-u[1], u[0], 0);
    return k * u + h * std::sqrt(1 - k * k) * ju;
}

// The span's length between the tangent points (wrapped) or the centres (point) [m].
double chordLength(const Options& o, int drum) {
    const Vec3 c = drumCentre(o, drum);
    if (o.model == sr::SheaveModel::Point) return c.norm();
    const double planar = c[0] * c[0] + c[1] * c[1] - (kR + kDrum) * (kR + kDrum);
    return std::sqrt(planar + c[2] * c[2]);
}

// The span's fleet angle at the wrapped sheave (and at its drum) [rad].
double fleetAngle(const Options& o, int drum) {
    const Vec3 c = drumCentre(o, drum);
    return std::atan2(std::abs(c[2]), std::sqrt(c[0] * c[0] + c[1] * c[1] - (kR + kDrum) * (kR + kDrum)));
}

// Clockwise about z_L from a to b (their x, y), in (0, 2 pi].
double clockwiseAngle(const Vec3& a, const Vec3& b) {
    double alpha = std::atan2(-(a[0] * b[1] - a[1] * b[0]), a[0] * b[0] + a[1] * b[1]);
    if (alpha <= 0) alpha += 2 * Pi;
    return alpha;
}

// The closed-form wrap angle.
double closedFormWrapAngle(const Options& o) {
    if (o.model == sr::SheaveModel::Wrapped) return clockwiseAngle(tangentNormal(o, 1), tangentNormal(o, 2));
    const Vec3 a = drumCentre(o, 1), b = drumCentre(o, 2);
    return Pi - std::atan2(cross(a, b).norm(), dot(a, b));
}

struct DrumsOverASheave {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    std::unique_ptr<sr::MotionWorkMeter> meter;
    MobilizedBody::Pin sheave, drum1, drum2;
    State state;

    DrumsOverASheave(const Options& o, double sRef, double length) {
        const Rotation Q = tilt(o);
        const Body::Rigid wheel(MassProperties(5, Vec3(0), Inertia(0.5)));
        sheave = MobilizedBody::Pin(matter.Ground(), Transform(Q, Vec3(0)), wheel, Transform());
        drum1 = MobilizedBody::Pin(matter.Ground(), Transform(Q, Q * drumCentre(o, 1)), wheel, Transform());
        drum2 = MobilizedBody::Pin(matter.Ground(), Transform(Q, Q * drumCentre(o, 2)), wheel, Transform());
        Motion::Steady(sheave, 0.0);  // held
        // Drum 1 (payout sense +1) and drum 2 (-1) move the rope towards its start.
        sr::prescribeProfile(drum1, drumMove(), -1.0 / kDrum);
        sr::prescribeProfile(drum2, drumMove(), -o.drum2Speed / kDrum);
        reeving = std::make_unique<sr::ReevingSubsystem>(system);  // no gravity force: g = 0
        sr::RopeSpec rope;
        rope.sheaveModel = o.model;
        rope.start = sr::WinchDrum{drum1, kDrum, 20.0, 1, Vec3(0)};
        sr::TractionSheave ts{sheave, kR, kMu, 0.0, sRef, 1, Vec3(0)};
        ts.slipModel = o.slip;
        rope.sheaves = {ts};
        rope.end = sr::WinchDrum{drum2, kDrum, 20.0, -1, Vec3(0)};
        rope.properties = {kRhoA, kEA, 0.0, false};
        rope.properties.axialRetardationTime = 2e-3;
        rope.unstretchedLength = length;
        rope.spanDefaults.axialModes = 2;
        rope.spanDefaults.axialDynamics = sr::AxialDynamics::QuasiStatic;
        rope.spanDefaults.transverseModes = 1;
        if (o.planar) rope.planeNormal = Q * Vec3(0, 0, 1);
        reeving->addRope(rope);
        meter = std::make_unique<sr::MotionWorkMeter>(system);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

// Both spans stretched by kStretch at the start: s_ref and L from the geometry (a probe of the
// wrapped machine gives the material coordinates at the drums' and the groove's tangent points).
std::unique_ptr<DrumsOverASheave> build(const Options& o) {
    const double stretch = 1 - kStretch;
    const double a = chordLength(o, 1), b = chordLength(o, 2);
    if (o.model == sr::SheaveModel::Point)
        return std::make_unique<DrumsOverASheave>(o, a * stretch, (a + b) * stretch);
    const double sProbe = 9.0, lProbe = 30.0;
    DrumsOverASheave probe(o, sProbe, lProbe);
    probe.system.realize(probe.state, Stage::Position);
    const auto ra = probe.reeving->getSpanMaterialRange(probe.state, 0, 0);
    const auto rb = probe.reeving->getSpanMaterialRange(probe.state, 0, 1);
    const double sIn = ra.first + a * stretch;  // s_k at the arrival tangent point
    const double sRef = sIn - (ra.second - sProbe);
    const double arc = rb.first - ra.second;  // R alpha
    const double length = sIn + arc + b * stretch - (rb.second - lProbe);
    return std::make_unique<DrumsOverASheave>(o, sRef, length);
}

// Measured over the steady slip, t in [0.5, 0.6] s, with K = e^(mu alpha), alpha from the
// geometry (below), c = rhoA v^2, v = 10 m/s; span 0 is the tight side.
struct Measured {
    double withTerm = 0;      // worst |(P_a - c) / (P_b - c) / K - 1|
    double withoutTerm = 0;   // worst |P_a / P_b / K - 1|
    double alphaOff = 0;      // worst |alpha measured - closed form| [rad]
    double tangentOff = 0;    // worst distance of the tangent points from R u (closed form) [m]
    double fleetOff = 0;      // worst |getFleetAngles - closed form| at the sheave [rad]
    double slipRateOff = 0;   // worst |slip rate - 10 m/s| [m/s]
    double energy = 0, largest = 0;
    double alpha = 0, fleet = 0;
    bool modeAsExpected = true;
    std::vector<double> pa, pb, rate;  // at every report from 0.01 s on: the histories
    double lambdaA = 1, lambdaB = 1;   // the spans' stretches at 0.6 s (spanStretch)
};

// A span's stretch lambda from the geometry: its chord over its material length (zero gravity: a
// straight, uniformly strained span).
double spanStretch(const DrumsOverASheave& p, const State& s, const Options& o, int span) {
    const auto r = p.reeving->getSpanMaterialRange(s, 0, span);
    return chordLength(o, span + 1) / (r.second - r.first);
}

Measured run(const Options& o, bool report = true) {
    const std::unique_ptr<DrumsOverASheave> machine = build(o);
    DrumsOverASheave& p = *machine;
    const Rotation Q = tilt(o);
    RungeKuttaMersonIntegrator integ(p.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(p.system, integ);
    ts.initialize(p.state);
    p.system.realize(integ.getState(), Stage::Velocity);
    const double e0 = p.reeving->calcMechanicalEnergy(integ.getState());
    Measured w;
    double worst = 0;
    for (int i = 1; i <= 60; ++i) {
        ts.stepTo(0.01 * i);
        const State& s = integ.getState();
        p.system.realize(s, Stage::Velocity);
        // E - E0 + W_friction + W_damping = W_drives, against the largest term.
        const double de = p.reeving->calcMechanicalEnergy(s) - e0, wf = p.reeving->getRope(0).getTractionSheave(1).getFrictionWork(s);
        const double wd = p.reeving->getDampingWork(s), wm = p.meter->getWork(s);
        worst = std::max(worst, std::abs(de + wf + wd - wm));
        w.largest = std::max({w.largest, std::abs(de), std::abs(wf), std::abs(wd), std::abs(wm)});
        // The end forces at Stage::Position (the condensed strain, what the law acts on).
        State sv = s;
        sv.invalidateAllCacheAtOrAbove(Stage::Dynamics);
        p.system.realize(sv, Stage::Velocity);
        const double pa = p.reeving->getAxialForce(sv, 0, 0, p.reeving->getSpanMaterialRange(sv, 0, 0).second);
        const double pb = p.reeving->getAxialForce(sv, 0, 1, p.reeving->getSpanMaterialRange(sv, 0, 1).first);
        const double v = p.reeving->getRope(0).getTractionSheave(1).getSlipRate(sv);
        w.pa.push_back(pa);
        w.pb.push_back(pb);
        w.rate.push_back(v);
        if (s.getTime() < 0.5 - 1e-12) continue;
        if (p.reeving->getRope(0).getTractionSheave(1).getTractionMode(s) != sr::TractionMode::SlipTowardStart) w.modeAsExpected = false;
        // alpha measured from the tangent points (the spans' end positions, in L).
        double alpha = closedFormWrapAngle(o);
        if (o.model == sr::SheaveModel::Wrapped) {
            const Vec3 c = p.sheave.getBodyOriginLocation(sv);
            const Vec3 ta = ~Q * (p.reeving->sampleSpan(sv, 0, 0, 2)[1] - c);
            const Vec3 tb = ~Q * (p.reeving->sampleSpan(sv, 0, 1, 2)[0] - c);
            w.tangentOff = std::max({w.tangentOff, (ta - kR * tangentNormal(o, 1)).norm(),
                                     (tb - kR * tangentNormal(o, 2)).norm()});
            alpha = clockwiseAngle(ta, tb);
            const double f0 = p.reeving->getFleetAngles(sv, 0, 0).second, f1 = p.reeving->getFleetAngles(sv, 0, 1).first;
            w.fleetOff = std::max({w.fleetOff, std::abs(f0 - fleetAngle(o, 1)), std::abs(f1 - fleetAngle(o, 2))});
            w.fleet = std::max(f0, f1);
        } else {
            // The chords from the sheave's centre to the drums' (Simbody's positions), in L.
            const Vec3 c = p.sheave.getBodyOriginLocation(sv);
            const Vec3 a = p.drum1.getBodyOriginLocation(sv) - c, b = p.drum2.getBodyOriginLocation(sv) - c;
            alpha = Pi - std::atan2(cross(a, b).norm(), dot(a, b));
        }
        w.alphaOff = std::max(w.alphaOff, std::abs(alpha - closedFormWrapAngle(o)));
        // The rope's material rate: 10 m/s at point drums, 10 m/s / lambda_a at wrapped ones.
        const double lambdaA = spanStretch(p, sv, o, 0);
        const double u = o.model == sr::SheaveModel::Wrapped ? kSpeed / lambdaA : kSpeed;
        const double K = std::exp(kMu * alpha), cf = kRhoA * u * u;
        w.withTerm = std::max(w.withTerm, std::abs((pa - cf) / (pb - cf) / K - 1));
        w.withoutTerm = std::max(w.withoutTerm, std::abs(pa / pb / K - 1));
        w.slipRateOff = std::max(w.slipRateOff, std::abs(v - u));
        w.alpha = alpha;
        w.lambdaA = lambdaA, w.lambdaB = spanStretch(p, sv, o, 1);
    }
    w.energy = worst / w.largest;
    if (!report) return w;
    std::printf("[ spatial ] %s %s%s: alpha %.12f rad (off the closed form %.1e), fleet %.4f deg (off %.1e rad), "
                "tangent points off %.1e m;\n            law with rhoA v^2 off by %.2e, plain ratio %.2e; slip rate "
                "off %.1e m/s; energy %.2e of %.3e J\n",
                o.model == sr::SheaveModel::Wrapped ? "wrapped" : "point",
                o.slip == sr::TractionSlip::RopeMomentum ? "RopeMomentum" : "CapstanConstraint",
                o.planar ? " (planar rope)" : "", w.alpha, w.alphaOff, w.fleet * 180 / Pi, w.fleetOff, w.tangentOff,
                w.withTerm, w.withoutTerm, w.slipRateOff, w.energy, w.largest);
    return w;
}

// o with drum 2's speed set for a steady slip (wrapped drums): the material rates at both drums
// agree when g = drum2Speed / lambda_b - 1 / lambda_a is zero; drum2Speed from two preliminary runs
// (g at 0.6 s; the first at 1, the second at its lambda_b / lambda_a) and the secant step through
// both. Point drums: o unchanged.
Options steadied(Options o) {
    if (o.model != sr::SheaveModel::Wrapped) return o;
    double f[2], g[2];
    for (int pass = 0; pass < 2; ++pass) {
        const Measured m = run(o, false);
        f[pass] = o.drum2Speed, g[pass] = o.drum2Speed / m.lambdaB - 1 / m.lambdaA;
        o.drum2Speed = m.lambdaB / m.lambdaA;
    }
    if (g[1] != g[0]) o.drum2Speed = f[1] - g[1] * (f[1] - f[0]) / (g[1] - g[0]);
    return o;
}

}  // namespace

// RopeMomentum, steady slip at 10 m/s with the spans 2.86 and 2.82 degrees out of the groove's
// plane (rhoA v^2 = 200 N against end forces of about 1e5 N: the centrifugal term moves the ratio
// by 6e-4). The wrapped drums grip the rope: drum 2 runs at lambda_b / lambda_a of drum 1's surface
// speed (steadied) and the rope's material rate is u = 10 m/s / lambda_a. Measured (point sheave;
// wrapped):
//  - alpha 2.9358255 rad (the 3D chords' turning angle, from Simbody's positions) and 3.0176184 rad:
//    the tangent points (the spans' end positions, in L) at the closed-form ones to 0 and 5.6e-17 m
//    (bound 5e-15 m), the angle between their radius vectors the closed form's to 0 (bound 1e-14
//    rad, a few ulps of pi), the fleet angles reported (getFleetAngles) the closed form's to
//    5.6e-17 rad (bound 5e-15 rad);
//  - (P_a - rhoA u^2) / (P_b - rhoA u^2) = e^(mu alpha) to 4.5e-10 and 2.5e-10 relative (bound 1e-8);
//    the plain capstan ratio misses it by 5.7e-4 and 5.8e-4 (the check sees the term);
//  - slip rate u to 4.7e-9 and 2.5e-9 m/s (bound 1e-7 m/s);
//  - E - E0 + W_friction + W_damping = W_drives (MotionWorkMeter) to 1.3e-14 and 1.6e-14 of the
//    largest term, 1.6e5 J (bound 1e-12).
TEST(SpatialTraction, RopeMomentumSlipFollowsTheLawWithTheCentrifugalTerm) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        Options o;
        o.model = model;
        const Measured m = run(steadied(o));
        EXPECT_TRUE(m.modeAsExpected);
        EXPECT_LE(m.withTerm, 1e-8);
        EXPECT_GT(m.withoutTerm, 1e-4);
        EXPECT_LE(m.alphaOff, 1e-14);
        EXPECT_LE(m.tangentOff, 5e-15);
        EXPECT_LE(m.fleetOff, 5e-15);
        EXPECT_LE(m.slipRateOff, 1e-7);
        EXPECT_LE(m.energy, 1e-12);
        if (model == sr::SheaveModel::Wrapped) {
            EXPECT_GT(m.fleet, 0.045);  // the spans leave the plane
        }
    }
}

// CapstanConstraint (the massless contact point) with the same geometry: P_a / P_b = e^(mu alpha)
// at every report in the slip, alpha from the geometry as above. Measured 1.1e-12 (point) and
// 2.4e-12 (wrapped) relative, bound 1e-10; it misses the centrifugal law by 5.7e-4 and 5.8e-4.
// Energy 4.3e-12 and 5.9e-12 of 1.6e5 J (bound 1e-10: the stick -> slip jump of the rope's kinetic
// energy is booked as friction work).
TEST(SpatialTraction, CapstanConstraintSlipHoldsTheRatioAtTheLimit) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        Options o;
        o.model = model;
        o.slip = sr::TractionSlip::CapstanConstraint;
        const Measured m = run(o);
        EXPECT_TRUE(m.modeAsExpected);
        EXPECT_LE(m.withoutTerm, 1e-10);
        EXPECT_GT(m.withTerm, 1e-4);
        EXPECT_LE(m.alphaOff, 1e-14);
        EXPECT_LE(m.tangentOff, 5e-15);
        EXPECT_LE(m.energy, 1e-10);
    }
}

// Without the tilt and the offsets the spatial rope is the planar one: the same machine with
// RopeSpec::planeNormal gives the same end forces and slip rate at every report from 0.01 s to
// 0.6 s (through the ramp, the stick -> slip transition and the steady slip), to the integrators'
// error (accuracy 1e-10: the two take different steps). Measured, worst over the four runs: end
// forces 3.1e-10 relative (bound 1e-8), slip rate 4.8e-9 m/s (bound 1e-7 m/s); the wrap angles
// equal to 0 (bound 1e-14 rad).
TEST(SpatialTraction, WithoutTiltTheSpatialRopeIsThePlanarOne) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped})
        for (sr::TractionSlip slip : {sr::TractionSlip::RopeMomentum, sr::TractionSlip::CapstanConstraint}) {
            Options o;
            o.model = model;
            o.slip = slip;
            o.tilted = false;
            o.dz1 = o.dz2 = 0;
            const Measured spatial = run(o);
            o.planar = true;
            const Measured planar = run(o);
            ASSERT_EQ(spatial.pa.size(), planar.pa.size());
            double force = 0, rate = 0;
            for (std::size_t i = 0; i < planar.pa.size(); ++i) {
                force = std::max({force, std::abs(spatial.pa[i] - planar.pa[i]) / planar.pa[i],
                                  std::abs(spatial.pb[i] - planar.pb[i]) / planar.pb[i]});
                rate = std::max(rate, std::abs(spatial.rate[i] - planar.rate[i]));
            }
            std::printf("[ planar ] spatial against planar: forces %.2e relative, slip rate %.2e m/s\n", force, rate);
            EXPECT_LE(force, 1e-8);
            EXPECT_LE(rate, 1e-7);
            EXPECT_NEAR(spatial.alpha, planar.alpha, 1e-14);
        }
}
