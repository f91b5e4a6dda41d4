// TractionSlip::RopeMomentum: in slip the rope on the traction sheave is a dynamic coordinate Y
// (its material coordinate over the groove's top; s_k at a point sheave) with the rope's reduced
// inertia, driven by the span end forces and the friction F = max(P_tight - rhoA v^2, 0)(1 - e^(-mu alpha)),
// v = Ydot the rope's speed over the groove relative to the sheave's centre.
// Two winch drums run a rope over a traction sheave in zero gravity: one hauls in, the other pays out
// at the same surface speed (after a smooth ramp to 10 m/s), so the spans keep their chords and
// material and the slip becomes steady. The end forces at the sheave then follow Euler-Eytelwein
// with the centrifugal term, (P_tight - rhoA v^2) = e^(mu alpha) (P_slack - rhoA v^2). Every reference
// is computed here: alpha from the geometry (the chords' turning angle at a point sheave, from the
// drums' and the sheave's centres; at a wrapped sheave the angle between the radius vectors to the
// two tangent points, the spans' end positions), e^(mu alpha) from mu and that alpha, v the drums'
// material rate, the rope's reduced inertia at the groove from the spans' velocity field.
#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

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
    sr::SheaveModel model = sr::SheaveModel::Point;
    double direction = 1;  // +1: the drums move the rope towards its start (drum 1 hauls in), -1 towards its end
    double groove = 0;     // the groove's surface speed towards the rope's start over the drums' (0: held)
    double stretch = kStretch;  // the spans' initial stretch (1 - l / chord)
    double retardation = 2e-3;  // Kelvin-Voigt c [s]: damps the rope's axial motion at the sheave
    int transverseModes = 1;
    double sheaveInertia = 0;  // > 0: the sheave turns freely (no Motion) with this inertia [kg m^2]
    double lean = 0;  // drum 2 this much further out in x [m]: span 1 leans, the wrap angle is not pi
    // Drum 2's surface speed over drum 1's. A wrapped drum grips the rope (RopeModel::setGrip): it
    // moves material at its surface speed over the stretch lambda of its span, so a steady slip
    // needs lambda_b / lambda_a here (steadied()); 1 with point drums, which move material at their
    // surface speed.
    double drum2Speed = 1;
    // The rope's speed towards its start over the groove's, in units of the drums' speed: its sign is
    // the side the rope slides to (+1: span 0 tight).
    double sigma() const { return direction - groove > 0 ? 1.0 : -1.0; }
};

// Point model: drum 1 at (-R, -8), the sheave at the origin, drum 2 at (R, -16) (chords to the
// centres). Wrapped: the drums stand a drum radius further out, so both spans hang vertical from
// the groove's tangent points, 8 m and 16 m long.
struct DrumsOverASheave {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    std::unique_ptr<sr::MotionWorkMeter> meter;  // the prescribed motions (drums, sheave) are the drive
    MobilizedBody::Pin sheave, drum1, drum2;
    State state;

    // sRef: the traction sheave's s_ref; length: the rope's unstretched length.
    DrumsOverASheave(const Options& o, double sRef, double length) {
        const bool wrapped = o.model == sr::SheaveModel::Wrapped;
        const double out = wrapped ? kR + kDrum : kR;
        const Body::Rigid wheel(MassProperties(5, Vec3(0), Inertia(0.5)));
        const Body::Rigid free(MassProperties(5, Vec3(0), Inertia(o.sheaveInertia)));
        sheave = MobilizedBody::Pin(matter.Ground(), Transform(), o.sheaveInertia > 0 ? free : wheel, Transform());
        drum1 = MobilizedBody::Pin(matter.Ground(), Transform(Vec3(-out, -8, 0)), wheel, Transform());
        drum2 = MobilizedBody::Pin(matter.Ground(), Transform(Vec3(out + o.lean, -16, 0)), wheel, Transform());
        // s = s_ref + R theta at the sheave: theta = groove x / R moves its surface at groove xdot
        // towards the rope's start.
        // A free sheave (sheaveInertia > 0) has no Motion.
        if (o.sheaveInertia == 0 && o.groove == 0) {
            Motion::Steady(sheave, 0.0);  // held
        } else if (o.sheaveInertia == 0) {
            sr::prescribeProfile(sheave, drumMove(), o.groove / kR);
        }
        // Drum 1 (payout sense +1): s_0 = -R theta = direction x; drum 2 (payout sense -1, its rope
        // leaves it on the side that faces the sheave): s_N = L + R (-theta) = L + direction x.
        sr::prescribeProfile(drum1, drumMove(), -o.direction / kDrum);
        sr::prescribeProfile(drum2, drumMove(), -o.direction * o.drum2Speed / kDrum);
        reeving = std::make_unique<sr::ReevingSubsystem>(system);  // no gravity force: g = 0
        sr::RopeSpec rope;
        rope.sheaveModel = o.model;
        rope.start = sr::WinchDrum{drum1, kDrum, 20.0, 1, Vec3(0)};
        sr::TractionSheave ts{sheave, kR, kMu, 0.0, sRef, 1, Vec3(0)};
        ts.slipModel = o.slip;
        rope.sheaves = {ts};
        rope.end = sr::WinchDrum{drum2, kDrum, 20.0, -1, Vec3(0)};
        rope.properties = {kRhoA, kEA, 0.0, false};
        rope.properties.axialRetardationTime = o.retardation;
        rope.unstretchedLength = length;
        rope.spanDefaults.axialModes = 2;
        rope.spanDefaults.axialDynamics = sr::AxialDynamics::QuasiStatic;
        rope.spanDefaults.transverseModes = o.transverseModes;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        meter = std::make_unique<sr::MotionWorkMeter>(system);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

// Wrapped: each span is the crossed tangent of the groove circle (centre 0, radius R) and its drum's
// (centre D, radius R_d), touching the groove at R n with n . D = R + R_d, |n| = 1:
// n = k D / |D| + h J D / |D| (J: +90 degrees about z), k = (R + R_d) / |D|, h = -+sqrt(1 - k^2) (drum 1
// on the left, drum 2 on the right); the span's length is sqrt(|D|^2 - (R + R_d)^2).
Vec3 grooveNormal(const Vec3& D, double h) {
    const double k = (kR + kDrum) / D.norm();
    const Vec3 u = D / D.norm(), ju(-u[1], u[0], 0);
    return k * u + h * std::sqrt(1 - k * k) * ju;
}
Vec3 drumCentre(const Options& o, int drum) {
    const double out = o.model == sr::SheaveModel::Wrapped ? kR + kDrum : kR;
    return drum == 1 ? Vec3(-out, -8, 0) : Vec3(out + o.lean, -16, 0);
}
Vec3 tangentNormal(const Options& o, int drum) { return grooveNormal(drumCentre(o, drum), drum == 1 ? -1.0 : 1.0); }
double chordLength(const Options& o, int drum) {
    const Vec3 D = drumCentre(o, drum);
    if (o.model == sr::SheaveModel::Point) return D.norm();
    return std::sqrt(D.normSqr() - (kR + kDrum) * (kR + kDrum));
}
// The closed-form wrap angle at the wrapped groove: clockwise from n_1 to n_2 (the rope runs up the
// left side, over the top and down the right side).
double clockwiseAngle(const Vec3& a, const Vec3& b) {
    double alpha = std::atan2(-cross(a, b)[2], dot(a, b));
    if (alpha <= 0) alpha += 2 * Pi;
    return alpha;
}

// Both spans stretched by o.stretch at the start: s_ref and L from the geometry (a probe of the
// wrapped machine gives the material coordinates at the drums' and the groove's tangent points).
DrumsOverASheave* build(const Options& o) {
    const double stretch = 1 - o.stretch;
    const double a = chordLength(o, 1), b = chordLength(o, 2);
    if (o.model == sr::SheaveModel::Point) return new DrumsOverASheave(o, a * stretch, (a + b) * stretch);
    const double sProbe = 9.0, lProbe = 30.0;
    DrumsOverASheave probe(o, sProbe, lProbe);
    probe.system.realize(probe.state, Stage::Position);
    const auto ra = probe.reeving->getSpanMaterialRange(probe.state, 0, 0);
    const auto rb = probe.reeving->getSpanMaterialRange(probe.state, 0, 1);
    const double sIn = ra.first + a * stretch;  // s_k at the arrival tangent point
    const double sRef = sIn - (ra.second - sProbe);
    const double arc = rb.first - ra.second;  // R alpha
    const double length = sIn + arc + b * stretch - (rb.second - lProbe);
    return new DrumsOverASheave(o, sRef, length);
}

// The wrap angle from the geometry. Point sheave: the chords' turning angle at the sheave's centre,
// pi - angle(p_a - r_k, p_b - r_k), from the drums' and the sheave's body origins (Simbody).
// Wrapped: the angle the rope turns through on the groove (clockwise about +z: it runs up the left
// side, over the top and down the right side), between the radius vectors from the sheave's centre
// to the arrival tangent point (the end of span 0) and the departure one (the start of span 1).
// tangentOff: the worst distance of those points from the closed-form tangent points R n [m].
// A span's stretch lambda from the geometry: its chord (chordLength) over its material length
// (zero gravity: straight and uniformly strained).
double spanStretch(const DrumsOverASheave& p, const State& s, const Options& o, int span) {
    const auto r = p.reeving->getSpanMaterialRange(s, 0, span);
    return chordLength(o, span + 1) / (r.second - r.first);
}

double geometricWrapAngle(const DrumsOverASheave& p, const State& s, const Options& o, double* tangentOff) {
    const sr::SheaveModel model = o.model;
    const Vec3 c = p.sheave.getBodyOriginLocation(s);
    if (model == sr::SheaveModel::Point) {
        const Vec3 u = p.drum1.getBodyOriginLocation(s) - c, w = p.drum2.getBodyOriginLocation(s) - c;
        return Pi - std::atan2(cross(u, w).norm(), dot(u, w));
    }
    const Vec3 ra = p.reeving->sampleSpan(s, 0, 0, 2)[1] - c, rb = p.reeving->sampleSpan(s, 0, 1, 2)[0] - c;
    if (tangentOff) *tangentOff = std::max((ra - kR * tangentNormal(o, 1)).norm(), (rb - kR * tangentNormal(o, 2)).norm());
    return clockwiseAngle(ra, rb);
}

const char* name(const Options& o) {
    static char buf[160];
    std::snprintf(buf, sizeof buf, "%s %s, rope %s, groove %+.1f of its speed",
                  o.model == sr::SheaveModel::Wrapped ? "wrapped" : "point",
                  o.slip == sr::TractionSlip::RopeMomentum ? "RopeMomentum" : "CapstanConstraint",
                  o.direction > 0 ? "towards its start" : "towards its end", o.groove);
    return buf;
}

// Steady slip, t in [0.5, 0.6] s. With K = e^(mu alpha) (alpha geometricWrapAngle), c = rhoA u^2
// (u the rope's material rate: 10 m/s at point drums, 10 m/s / lambda_a at wrapped ones, which grip
// the rope; lambda_a = spanStretch of span 0) and the tight / slack sides by Options::sigma:
struct Measured {
    double withTerm = 0;     // worst |(P_t - c) / (P_s - c) / K - 1|
    double withoutTerm = 0;  // worst |P_t / P_s / K - 1|, the plain capstan ratio
    double slipSpeedTerm = 0;  // worst |(P_t - c') / (P_s - c') / K - 1|, c' = rhoA (slip rate)^2
    double slipRateOff = 0;  // worst |slip rate - (direction u - groove 10 m/s)| [m/s]
    double alphaOff = 0;     // worst |alpha - clockwiseAngle(n_1, n_2)| (wrapped; pi with lean 0)
    double tangentOff = 0;   // worst distance of the tangent points from R n_1, R n_2 [m]
    double wrapAngleOff = 0;  // worst |getWrapAngle - alpha|: the angle the code's law uses [rad]
    double energy = 0, largest = 0;
    double pTight = 0, pSlack = 0, alpha = 0, slipRate = 0;  // at 0.6 s
    double lambdaA = 1, lambdaB = 1;  // the spans' stretches at 0.6 s (spanStretch)
    bool modeAsExpected = true;
};

Measured run(const Options& o, bool report = true) {
    const std::unique_ptr<DrumsOverASheave> machine(build(o));
    DrumsOverASheave& p = *machine;
    RungeKuttaMersonIntegrator integ(p.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(p.system, integ);
    ts.initialize(p.state);
    p.system.realize(integ.getState(), Stage::Velocity);
    const double e0 = p.reeving->calcMechanicalEnergy(integ.getState());
    const sr::TractionMode expected = o.sigma() > 0 ? sr::TractionMode::SlipTowardStart : sr::TractionMode::SlipTowardEnd;
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
        if (s.getTime() < 0.5 - 1e-12) continue;
        if (p.reeving->getRope(0).getTractionSheave(1).getTractionMode(s) != expected) w.modeAsExpected = false;
        // The end forces at Stage::Position (the condensed strain, what the law acts on).
        State sv = s;
        sv.invalidateAllCacheAtOrAbove(Stage::Dynamics);
        p.system.realize(sv, Stage::Velocity);
        const double pa = p.reeving->getAxialForce(sv, 0, 0, p.reeving->getSpanMaterialRange(sv, 0, 0).second);
        const double pb = p.reeving->getAxialForce(sv, 0, 1, p.reeving->getSpanMaterialRange(sv, 0, 1).first);
        const double tight = o.sigma() > 0 ? pa : pb, slack = o.sigma() > 0 ? pb : pa;
        double off = 0;
        const double alpha = geometricWrapAngle(p, sv, o, &off), K = std::exp(kMu * alpha);
        const bool grips = o.model == sr::SheaveModel::Wrapped;
        const double lambdaA = spanStretch(p, sv, o, 0), u = grips ? kSpeed / lambdaA : kSpeed;
        const double c = kRhoA * u * u, v = p.reeving->getRope(0).getTractionSheave(1).getSlipRate(sv), c2 = kRhoA * v * v;
        w.withTerm = std::max(w.withTerm, std::abs((tight - c) / (slack - c) / K - 1));
        w.withoutTerm = std::max(w.withoutTerm, std::abs(tight / slack / K - 1));
        w.slipSpeedTerm = std::max(w.slipSpeedTerm, std::abs((tight - c2) / (slack - c2) / K - 1));
        w.slipRateOff = std::max(w.slipRateOff, std::abs(v - (o.direction * u - o.groove * kSpeed)));
        if (o.model == sr::SheaveModel::Wrapped)
            w.alphaOff = std::max(w.alphaOff, std::abs(alpha - clockwiseAngle(tangentNormal(o, 1), tangentNormal(o, 2))));
        w.tangentOff = std::max(w.tangentOff, off);
        w.wrapAngleOff = std::max(w.wrapAngleOff, std::abs(p.reeving->getWrapAngle(sv, 0, 1) - alpha));
        w.pTight = tight, w.pSlack = slack, w.alpha = alpha, w.slipRate = v;
        w.lambdaA = lambdaA, w.lambdaB = spanStretch(p, sv, o, 1);
    }
    w.energy = worst / w.largest;
    if (!report) return w;
    std::printf("[ steady ] %s: alpha %.12f, v_slip %+.4f m/s (off %.1e), P_tight %.6e N, P_slack %.6e N;\n"
                "           law with rhoA v^2 off by %.2e, without it %.2e, with the slip rate's square %.2e; "
                "alpha off the closed form %.1e, tangent points off it %.1e m, getWrapAngle off %.1e; energy %.2e of "
                "%.3e J; drum 2 at %.12f of drum 1's speed\n",
                name(o), w.alpha, w.slipRate, w.slipRateOff, w.pTight, w.pSlack, w.withTerm, w.withoutTerm,
                w.slipSpeedTerm, w.alphaOff, w.tangentOff, w.wrapAngleOff, w.energy, w.largest, o.drum2Speed);
    return w;
}

// o with drum 2's speed set for a steady slip: wrapped drums move material at (surface speed) /
// lambda of their span, so the material rates at both drums agree when g = drum2Speed / lambda_b -
// 1 / lambda_a is zero. The stretches depend on drum2Speed through the material the ramp moves, so
// drum2Speed comes from two preliminary runs (g at 0.6 s): the first at 1, the second at its
// lambda_b / lambda_a, then the secant step through both (g is close to linear in drum2Speed). With
// slackTarget > 0 the spans' initial stretch is also shifted after each run by (slackTarget -
// P_slack) / EA, so the slack side's force reaches slackTarget in steady slip (the ramp moves
// different amounts of material at the two drums while the tight side's inertial force pulls, and
// so changes the rope's force level by of order rhoA v^2 at small forces). Point drums: o unchanged.
Options steadied(Options o, double slackTarget = 0) {
    if (o.model != sr::SheaveModel::Wrapped) return o;
    double f[2], g[2];
    for (int pass = 0; pass < 2; ++pass) {
        const Measured m = run(o, false);
        f[pass] = o.drum2Speed, g[pass] = o.drum2Speed / m.lambdaB - 1 / m.lambdaA;
        o.drum2Speed = m.lambdaB / m.lambdaA;
        if (slackTarget > 0) o.stretch += (slackTarget - m.pSlack) / kEA;
    }
    if (g[1] != g[0]) o.drum2Speed = f[1] - g[1] * (f[1] - f[0]) / (g[1] - g[0]);
    return o;
}

}  // namespace

// Steady slip at 10 m/s over a held sheave from t = 0.5 s to 0.6 s (rhoA v^2 = 200 N against end
// forces of about 1e5 N, so the centrifugal term moves the ratio by 6e-4). The wrapped drums grip the
// rope, so drum 2 runs at lambda_b / lambda_a of drum 1's surface speed (steadied: 0.99993) and
// the rope's material rate is u = 10 m/s / lambda_a (9.9976 m/s). alpha from the geometry:
// 3.0853624 rad at the point sheave (pi - atan(0.3 / 8) - atan(0.3 / 16)), pi at the wrapped one: the
// tangent points (the spans' end positions) at the closed-form ones, (-R, 0) and (R, 0), to 5.6e-17 m
// (bound 5e-15 m, 90x), the angle between their radius vectors pi to 0 (bound 1e-14 rad, a few ulps
// of pi). The wrap angle the code's law uses (getWrapAngle) equals it to 0 (bound 1e-14 rad).
//  - RopeMomentum: (P_a - rhoA u^2) / (P_b - rhoA u^2) = e^(mu alpha) to 2.8e-10 (point) and
//    3.6e-10 (wrapped), relative; bound 1e-8 (28x). The plain capstan ratio misses it by 6.0e-4: the
//    check sees the term. The slip rate is u to 3.0e-9 m/s and 3.5e-9 m/s (bound 1e-7 m/s, 29x).
//  - CapstanConstraint (the massless contact point): P_a / P_b = e^(mu alpha) to 2.6e-12 and 1.9e-12
//    (bound 1e-9), and so misses the centrifugal law by 6.0e-4.
//  - Energy: E - E0 + W_friction + W_damping = W_drives (MotionWorkMeter) to 1.4e-14 / 2.6e-14
//    (RopeMomentum) and 3.3e-12 / 3.7e-12 (CapstanConstraint) of the largest term, 1.7e5 J;
//    bound 1e-10 (27x).
TEST(TractionRopeMomentum, SteadySlipFollowsEulerEytelweinWithTheCentrifugalTerm) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        Options o;
        o.model = model;
        const Measured m = run(steadied(o));
        EXPECT_TRUE(m.modeAsExpected);
        EXPECT_LE(m.withTerm, 1e-8);
        EXPECT_GT(m.withoutTerm, 1e-4);
        EXPECT_LE(m.energy, 1e-10);
        EXPECT_LE(m.slipRateOff, 1e-7);
        EXPECT_LE(m.alphaOff, 1e-14);
        EXPECT_LE(m.tangentOff, 5e-15);
        EXPECT_LE(m.wrapAngleOff, 1e-14);
        o.slip = sr::TractionSlip::CapstanConstraint;
        const Measured c = run(steadied(o));
        EXPECT_TRUE(c.modeAsExpected);
        EXPECT_LE(c.withoutTerm, 1e-9);
        EXPECT_GT(c.withTerm, 1e-4);
        EXPECT_LE(c.energy, 1e-10);
    }
}

// Drum 2 3 m further out: span 1 leans and the wrap angle is no longer near pi: 2.9007123 rad at the
// point sheave, 2.9570789 rad at the wrapped one, where the tangent points (the spans' end positions)
// lie at the closed-form crossed tangents (grooveNormal) to 5.6e-17 m (bound 5e-15 m, 90x) and the
// angle between their radius vectors is the closed form's to 0 (bound 1e-14 rad), as is getWrapAngle.
// The law with e^(mu alpha) from that angle holds to 3.4e-10 (point) and 3.6e-10 (wrapped, drum 2
// steadied), bound 1e-8 (28x); energy 8.4e-15 and 6.1e-15 of 1.6e5 J (bound 1e-10).
TEST(TractionRopeMomentum, SteadySlipOverALeaningSpanFollowsTheGeometrysWrapAngle) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        Options o;
        o.model = model;
        o.lean = 3.0;
        const Measured m = run(steadied(o));
        EXPECT_TRUE(m.modeAsExpected);
        EXPECT_LT(m.alpha, Pi - 0.1);
        EXPECT_LE(m.withTerm, 1e-8);
        EXPECT_GT(m.withoutTerm, 1e-4);
        EXPECT_LE(m.energy, 1e-10);
        EXPECT_LE(m.alphaOff, 1e-14);
        EXPECT_LE(m.tangentOff, 5e-15);
        EXPECT_LE(m.wrapAngleOff, 1e-14);
    }
}

// The drums reversed: the rope runs towards its end over the held sheave, span 1 is the tight side
// (SlipTowardEnd) and (P_b - rhoA u^2) = e^(mu alpha) (P_a - rhoA u^2): measured 3.0e-10 (point) and
// 2.7e-10 (wrapped, drum 2 steadied), bound 1e-8 (33x); the plain ratio misses it by 6.6e-4; slip
// rate -u to 2.8e-9 and 2.4e-9 m/s (bound 1e-7 m/s); energy 5.4e-15 of 1.5e5 J (bound 1e-10).
TEST(TractionRopeMomentum, SlipTowardsTheRopesEndHasTheEndSideTight) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        Options o;
        o.model = model;
        o.direction = -1;
        const Measured m = run(steadied(o));
        EXPECT_TRUE(m.modeAsExpected);
        EXPECT_GT(m.pTight, m.pSlack);
        EXPECT_LE(m.withTerm, 1e-8);
        EXPECT_GT(m.withoutTerm, 1e-4);
        EXPECT_LE(m.energy, 1e-10);
        EXPECT_LE(m.slipRateOff, 1e-7);
    }
}

// A turning sheave (prescribed) under the slipping rope. rhoA v^2 is the rope's speed over the
// groove relative to the sheave's centre (10 m/s), not its slip over the turning groove:
//  - groove at 0.6 of the rope's speed towards the start: slip 4 m/s, still towards the start;
//  - groove at 1.5 of it: the groove outruns the rope, which slips towards its end at 5 m/s while
//    it moves towards its start (span 1 tight).
// The sheave's prescribed motion is a drive too (MotionWorkMeter), so the balance checks the
// friction's reaction torque on it (wrapped: drum 2 steadied, u = 10 m/s / lambda_a). Measured: the
// law to 1.5e-10 .. 5.5e-10 (bound 1e-8, 18x); with the slip rate's square in place of the rope's
// speed's it misses by 4.9e-4 .. 5.1e-4, without the term by 6.0e-4 .. 6.7e-4; slip rate 4 and
// -5 m/s (u - 6 m/s and u - 15 m/s wrapped) to 5.3e-9 m/s (bound 1e-7 m/s); energy 2.8e-14 of 8e4 J
// (bound 1e-10).
TEST(TractionRopeMomentum, TurningSheaveSlipsWithTheRopesSpeedInTheCentrifugalTerm) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped})
        for (double groove : {0.6, 1.5}) {
            Options o;
            o.model = model;
            o.groove = groove;
            const Measured m = run(steadied(o));
            EXPECT_TRUE(m.modeAsExpected);
            EXPECT_GT(m.pTight, m.pSlack);
            EXPECT_LE(m.withTerm, 1e-8);
            EXPECT_GT(m.withoutTerm, 1e-4);
            EXPECT_GT(m.slipSpeedTerm, 1e-4);
            EXPECT_LE(m.energy, 1e-10);
            EXPECT_LE(m.slipRateOff, 1e-7);
        }
}

namespace {

// An accelerating slip: the held sheave's rope while the drums ramp up, undamped (c = 0: the end
// forces are the elastic ones, EA eps), reports every 0.5 ms over the first 0.3 s. The momentum
// balance at the groove, derived here: with both ends of a span fixed in space (held sheave, drum
// centres on Ground), the span between material coordinates s1 and s2, chord d and material length
// l = s2 - s1 has the ALE velocity field rdot(s) = -(d / l)(s1dot (1 - xi) + s2dot xi),
// xi = (s - s1) / l (zero gravity: straight spans, uniform strain, the condensed axial amplitudes and
// the transverse modes stay zero), so T = rhoA |d|^2 / (6 l) (s1dot^2 + s1dot s2dot + s2dot^2):
//     m_s = rhoA (|d_a|^2 / l_a + |d_b|^2 / l_b) / 3 + rhoA R alpha (the rope on a wrapped groove,
//     moving at Ydot),
// and the drums' material accelerations couple in with rhoA |d_a|^2 / (6 l_a) and rhoA |d_b|^2 /
// (6 l_b). Point drums move material at the profile's rate: s_0ddot = s_Nddot = xddot. Wrapped drums
// grip the rope (RopeModel::setGrip): s_0dot = xdot / lambda_a, lambda_a = d_a / l_a, so
// s_0ddot = xddot / lambda_a + xdot (Ydot - s_0dot) / d_a, and s_Nddot = xddot / lambda_b +
// xdot (s_Ndot - Ydot) / d_b (the stretch rate's share: the grip's bias in the station map, which the
// balance keeps). The balance the slip model states,
//     m_s Yddot + rhoA (|d_a|^2 / l_a s_0ddot + |d_b|^2 / l_b s_Nddot) / 6 = P_a - P_b - sigma F,
//     F = max(P_tight - rhoA v^2, 0)(1 - e^(-mu alpha)),
// with Yddot read from the state's derivative (the Z entry whose value is the slip rate Ydot and
// which is the derivative of the entry before it), P the span end forces (getAxialForce) and alpha
// geometricWrapAngle.
struct Transient {
    double worst = 0;           // worst |residual|
    double largest = 0;         // largest |m_s Yddot|
    double largestForce = 0;    // largest |P_a - P_b|
    double withoutInertia = 0;  // worst |P_a - P_b - sigma F - coupling| (m_s = 0)
    double withoutArc = 0;      // worst residual with m_s less the groove arc's rhoA R alpha
    double withoutStretchRate = 0;  // wrapped: worst residual with s_0ddot = xddot / lambda_a (s_N's alike)
    double pinWorst = 0;        // free sheave: worst |I thetaddot - sigma F R| [N m]
    double pinLargest = 0;      // largest |sigma F R| [N m]
    double energy = 0;          // worst |E - E0 + W_friction + W_damping - W_drives| over the largest term
    double grooveSpeed = 0, ropeSpeed = 0;  // at the end [m/s]
    double ms = 0, arc = 0;
    int samples = 0, zMatches = 0;
};

Transient runTransient(sr::SheaveModel model, double sheaveInertia) {
    Options o;
    o.model = model;
    o.retardation = 0;
    o.sheaveInertia = sheaveInertia;
    const std::unique_ptr<DrumsOverASheave> machine(build(o));
    DrumsOverASheave& p = *machine;
    RungeKuttaMersonIntegrator integ(p.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(p.system, integ);
    ts.initialize(p.state);
    const sr::MotionProfile move = drumMove();
    Transient w;
    p.system.realize(integ.getState(), Stage::Velocity);
    const double e0 = p.reeving->calcMechanicalEnergy(integ.getState());
    double worstEnergy = 0, largestEnergy = 0;
    for (int i = 1; i <= 600; ++i) {
        ts.stepTo(5e-4 * i);
        const State& s = integ.getState();
        p.system.realize(s, Stage::Acceleration);
        const double de = p.reeving->calcMechanicalEnergy(s) - e0, wf = p.reeving->getRope(0).getTractionSheave(1).getFrictionWork(s);
        const double wd = p.reeving->getDampingWork(s), wm = p.meter->getWork(s);
        worstEnergy = std::max(worstEnergy, std::abs(de + wf + wd - wm));
        largestEnergy = std::max({largestEnergy, std::abs(de), std::abs(wf), std::abs(wd), std::abs(wm)});
        const sr::TractionMode mode = p.reeving->getRope(0).getTractionSheave(1).getTractionMode(s);
        if (mode == sr::TractionMode::Stick) continue;
        // Ydot: the slip rate plus the groove's surface speed R thetadot (sense +1).
        const double thetaDot = p.sheave.getOneU(s, 0), v = p.reeving->getRope(0).getTractionSheave(1).getSlipRate(s) + kR * thetaDot;
        w.grooveSpeed = kR * thetaDot, w.ropeSpeed = v;
        const Vector& z = s.getZ();
        const Vector& zdot = s.getZDot();
        int found = -1, matches = 0;
        for (int j = 1; j < z.size(); ++j)
            if (zdot[j - 1] == z[j] && std::abs(z[j] - v) <= 1e-12 * (1 + std::abs(v))) found = j, ++matches;
        w.zMatches = std::max(w.zMatches, matches);
        if (matches != 1) continue;
        const double yddot = zdot[found];
        State sv = s;  // the end forces at Stage::Position: the condensed strain, what the balance acts on
        sv.invalidateAllCacheAtOrAbove(Stage::Dynamics);
        p.system.realize(sv, Stage::Velocity);
        const auto ra = p.reeving->getSpanMaterialRange(sv, 0, 0), rb = p.reeving->getSpanMaterialRange(sv, 0, 1);
        const double pa = p.reeving->getAxialForce(sv, 0, 0, ra.second);
        const double pb = p.reeving->getAxialForce(sv, 0, 1, rb.first);
        const double alpha = geometricWrapAngle(p, sv, o, nullptr);
        const double sigma = mode == sr::TractionMode::SlipTowardStart ? 1.0 : -1.0;
        const double tight = sigma > 0 ? pa : pb;
        const double F = std::max(tight - kRhoA * v * v, 0.0) * (1 - std::exp(-kMu * alpha));
        const double da = chordLength(o, 1), db = chordLength(o, 2);
        const double spans = kRhoA * (da * da / (ra.second - ra.first) + db * db / (rb.second - rb.first));
        const double arc = model == sr::SheaveModel::Wrapped ? kRhoA * kR * alpha : 0.0;
        // The drums' material accelerations. Point drums: the profile's, xddot. Wrapped drums grip
        // the rope: s_0dot = xdot / lambda_a, s_Ndot = xdot / lambda_b, lambda = d / l (a straight,
        // uniformly strained span), so with ldot_a = Ydot - s_0dot and ldot_b = s_Ndot - Ydot:
        //     s_0ddot = xddot / lambda_a + xdot (Ydot - s_0dot) / d_a,
        //     s_Nddot = xddot / lambda_b + xdot (s_Ndot - Ydot) / d_b.
        const double t = s.getTime(), xd = move.velocity(t), xdd = move.acceleration(t);
        const double la = da / (ra.second - ra.first), lb = db / (rb.second - rb.first);
        double s0dd = xdd, sNdd = xdd;
        if (model == sr::SheaveModel::Wrapped) {
            s0dd = xdd / la + xd * (v - xd / la) / da;
            sNdd = xdd / lb + xd * (xd / lb - v) / db;
        }
        const double ms = spans / 3 + arc, ka = kRhoA * da * da / (ra.second - ra.first) / 6;
        const double kb = kRhoA * db * db / (rb.second - rb.first) / 6;
        const double coupling = ka * s0dd + kb * sNdd;
        if (model == sr::SheaveModel::Wrapped)
            w.withoutStretchRate = std::max(w.withoutStretchRate,
                                            std::abs(ms * yddot + ka * xdd / la + kb * xdd / lb - (pa - pb - sigma * F)));
        const double rhs = pa - pb - sigma * F;
        w.worst = std::max(w.worst, std::abs(ms * yddot + coupling - rhs));
        w.withoutInertia = std::max(w.withoutInertia, std::abs(coupling - rhs));
        w.withoutArc = std::max(w.withoutArc, std::abs((ms - arc) * yddot + coupling - rhs));
        w.largest = std::max(w.largest, std::abs(ms * yddot));
        w.largestForce = std::max(w.largestForce, std::abs(pa - pb));
        if (sheaveInertia > 0) {  // the friction's reaction turns the free sheave: I thetaddot = sigma F R
            w.pinWorst = std::max(w.pinWorst, std::abs(sheaveInertia * p.sheave.getOneUDot(s, 0) - sigma * F * kR));
            w.pinLargest = std::max(w.pinLargest, std::abs(sigma * F * kR));
        }
        w.ms = ms, w.arc = arc;
        ++w.samples;
    }
    w.energy = worstEnergy / largestEnergy;
    std::printf("[ transient ] %s, sheave %s: %d slip samples, m_s %.6f kg (arc %.4f kg), largest m_s Yddot "
                "%.4e N, largest |P_a - P_b| %.4e N;\n               balance off by %.3e N (%.2e), without the "
                "inertia %.3e N, without the arc's mass %.3e N; pin: I thetaddot off sigma F R by %.3e N m of "
                "%.4e N m; at 0.3 s groove %.4f m/s, rope %.4f m/s; energy %.2e of %.3e J\n",
                model == sr::SheaveModel::Wrapped ? "wrapped" : "point", sheaveInertia > 0 ? "free" : "held",
                w.samples, w.ms, w.arc, w.largest, w.largestForce, w.worst, w.worst / w.largest, w.withoutInertia,
                w.withoutArc, w.pinWorst, w.pinLargest, w.grooveSpeed, w.ropeSpeed, w.energy, largestEnergy);
    return w;
}

}  // namespace

// Measured: m_s 16.009 kg (point), 17.888 kg (wrapped, of which the arc's 1.885 kg); the balance holds
// to 1.4e-12 N and 1.8e-12 N, 3.4e-16 and 4.2e-16 of the largest inertia term m_s Yddot (4.0e3 N,
// 4.4e3 N), over 563 slip samples each; bound 2e-14 of it (48x). Without the inertia the balance
// misses by the whole term (4.0e3 N), without the groove arc's mass by 458 N, without the gripping
// drums' stretch rate in their material accelerations by 2.4e-3 N (what the balance missed before
// it kept the grip's bias). Energy (the drums the drive) to 7.0e-12 and 8.1e-12 of 7.1e4 J (bound
// 1e-10, 12x).
TEST(TractionRopeMomentum, AcceleratingSlipFollowsTheMomentumBalanceAtTheGroove) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        const Transient t = runTransient(model, 0.0);
        EXPECT_EQ(t.zMatches, 1);  // Ydot is found in the state, once
        EXPECT_GE(t.samples, 300);
        EXPECT_LE(t.worst, 2e-14 * t.largest);
        EXPECT_GT(t.withoutInertia, 1e6 * 2e-14 * t.largest);
        EXPECT_LE(t.energy, 1e-10);
        if (model == sr::SheaveModel::Wrapped) {
            EXPECT_GT(t.withoutArc, 1e6 * 2e-14 * t.largest);
            EXPECT_GT(t.withoutStretchRate, 1e6 * 2e-14 * t.largest);
        }
    }
}

// The same accelerating slip over a free sheave (no Motion, I = 200 kg m^2, zero gravity): the only
// torque on it is the friction's reaction, so I thetaddot = sigma F R (F from the end forces and the
// geometry's alpha as above), and it spins up while the rope slips over it (groove 4.1 m/s, rope
// 10.0 m/s at 0.3 s). Measured: the pin's balance to 1.8e-12 N m of 9.9e3 N m (point) and 1.0e4 N m
// (wrapped), 1.8e-16; bound 1e-14 of it (55x). The rope's balance at the groove (with Ydot = slip rate
// + R thetadot) to 3.2e-16 and 3.0e-16 of m_s Yddot (bound 2e-14, 62x); energy, the sheave's kinetic
// energy included, to 3.0e-12 and 2.8e-12 of 7.1e4 J (bound 1e-10, 33x).
TEST(TractionRopeMomentum, FreeSheaveIsTurnedByTheFrictionWhileTheRopeSlips) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        const Transient t = runTransient(model, 200.0);
        EXPECT_EQ(t.zMatches, 1);
        EXPECT_GE(t.samples, 300);
        EXPECT_GT(t.grooveSpeed, 1.0);               // the sheave turns...
        EXPECT_GT(t.ropeSpeed - t.grooveSpeed, 1.0);  // ...slower than the rope: it slips
        EXPECT_LE(t.worst, 2e-14 * t.largest);
        EXPECT_LE(t.pinWorst, 1e-14 * t.pinLargest);
        EXPECT_LE(t.energy, 1e-10);
    }
}

// rhoA v^2 comparable to the slack side's force: a rope pre-stretched so that its force, about
// P0 = (1 + delta) rhoA v^2, sits near the centrifugal load at 10 m/s (no transverse modes: an
// axially moving span near P = rhoA v^2 is at its critical speed).
// Wrapped: the gripping drums move different amounts of material while the ramp's inertial force
// pulls the tight side (of order rhoA v^2 of force level lost), so the initial stretch is steadied to
// reach P_slack = (1 + delta) rhoA v^2 after the ramp (steadied's slackTarget).
//  - delta = +0.05: P_slack - rhoA v^2 = 8.9 N (point) and 9.6 N (wrapped), P_tight - P_slack = 3.2 N
//    and 3.5 N; the law (P_tight - rhoA v^2) = e^(mu alpha)(P_slack - rhoA v^2) holds to 6.8e-7 and
//    1.2e-6, relative, i.e. 2e-5 N, the end forces' resolution (the Newton's 1e-14 strain tolerance
//    is 5e-6 N at EA = 5e8 N); bound 5e-5 (42x). The plain ratio P_tight / P_slack = 1.015 misses
//    e^(mu alpha) = 1.37 by 0.25.
//  - delta = -0.2: both sides 40 N below rhoA v^2: the rope lifts off the groove, the friction
//    vanishes (the clamp max(P_tight - rhoA v^2, 0)), and P_a = P_b to 1.8e-6 N and 1.3e-5 N (1.1e-8
//    and 7.8e-8 of them: a few times the end forces' resolution, 2e-5 N = 1.2e-7 of them), bound 1e-6
//    of them (13x over the wrapped rope's, 8x over that resolution); the law without the clamp would
//    need P_a - P_b = (e^(mu alpha) - 1)(P_b - rhoA v^2) = -15 N (asserted beyond 5e4 bounds).
// Energy to 3.4e-14 of 6.9e3 J (bound 1e-10).
TEST(TractionRopeMomentum, CentrifugalLoadNearTheSlackSidesForceLiftsTheRopeOff) {
    const double c = kRhoA * kSpeed * kSpeed;
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped})
        for (double delta : {0.05, -0.2}) {
            Options o;
            o.model = model;
            o.stretch = (1 + delta) * c / kEA;
            o.transverseModes = 0;
            const Measured m = run(steadied(o, (1 + delta) * c));
            const double K = std::exp(kMu * m.alpha);
            std::printf("           delta %+.2f: P_slack - rhoA v^2 = %.4e N, P_tight - P_slack = %.4e N "
                        "(%.2e of P_slack)\n",
                        delta, m.pSlack - c, m.pTight - m.pSlack, (m.pTight - m.pSlack) / m.pSlack);
            EXPECT_TRUE(m.modeAsExpected);
            EXPECT_LE(m.energy, 1e-10);
            if (delta > 0) {
                EXPECT_GT(m.pSlack - c, 0);
                EXPECT_LT(m.pSlack - c, 0.1 * c);
                EXPECT_LE(m.withTerm, 5e-5);
                EXPECT_GT(m.withoutTerm, 0.1 * (K - 1));
            } else {
                EXPECT_LT(m.pTight, c);
                EXPECT_GT(m.pSlack, 0);
                EXPECT_LE(std::abs(m.pTight - m.pSlack), 1e-6 * m.pSlack);
                EXPECT_GT(std::abs((K - 1) * (m.pSlack - c)), 5e4 * 1e-6 * m.pSlack);
            }
        }
}

// The slip model is checked when the rope is added.
TEST(TractionRopeMomentum, UnknownSlipModelIsAnInvalidArgument) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Pin sheave(matter.Ground(), Transform(), Body::Rigid(MassProperties(1, Vec3(0), Inertia(1))),
                              Transform());
    sr::ReevingSubsystem reeving(system);
    sr::RopeSpec rope;
    rope.start = sr::RopeAnchor{matter.Ground(), Vec3(-1, -3, 0)};
    sr::TractionSheave ts{sheave, kR, kMu, 0.0, 3.0, 1, Vec3(0)};
    ts.slipModel = static_cast<sr::TractionSlip>(7);
    rope.sheaves = {ts};
    rope.end = sr::RopeAnchor{matter.Ground(), Vec3(1, -3, 0)};
    rope.properties = {kRhoA, kEA, 0.0, false};
    rope.unstretchedLength = 6.3;
    rope.planeNormal = Vec3(0, 0, 1);
    try {
        reeving.addRope(rope);
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "ReevingSubsystem: rope 'rope': sheave 0 (TractionSheave, node 1) slipModel = 7 is not a "
                               "TractionSlip");
    }
}
