// TractionSlip::RopeMomentum: in slip the rope on the traction sheave is a dynamic coordinate Y
// (its material coordinate over the groove's top; s_k at a point sheave) with the rope's reduced
// inertia, driven by the span end forces and the friction F = (P_tight - rhoA v^2)(1 - e^(-mu alpha)).
// Two winch drums run a rope over a held traction sheave in zero gravity: the first hauls in, the
// second pays out at the same surface speed (after a smooth ramp to 10 m/s), so the spans keep
// their chords and material and the slip becomes steady. The end forces at the sheave then follow
// Euler-Eytelwein with the centrifugal term, (P_a - rhoA v^2) = e^(mu alpha) (P_b - rhoA v^2),
// alpha the chords' angle (the point sheave's geometric wrap angle).
#include "SimbodyReeving/scenes/MotionProfile.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

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

// Point model: drum 1 at (-R, -8), the sheave at the origin, drum 2 at (R, -16) (chords to the
// centres). Wrapped: the drums stand a drum radius further out, so both spans hang vertical from
// the groove's tangent points, 8 m and 16 m long.
struct DrumsOverASheave {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    std::unique_ptr<sr::MotionWorkMeter> meter;  // the drums' prescribed motion is the drive
    MobilizedBody::Pin sheave, drum1, drum2;
    State state;

    // sRef: the traction sheave's s_ref; length: the rope's unstretched length.
    DrumsOverASheave(sr::TractionSlip slip, sr::SheaveModel model, double sRef, double length) {
        const bool wrapped = model == sr::SheaveModel::Wrapped;
        const double out = wrapped ? kR + kDrum : kR;
        const Body::Rigid wheel(MassProperties(5, Vec3(0), Inertia(0.5)));
        sheave = MobilizedBody::Pin(matter.Ground(), Transform(), wheel, Transform());
        drum1 = MobilizedBody::Pin(matter.Ground(), Transform(Vec3(-out, -8, 0)), wheel, Transform());
        drum2 = MobilizedBody::Pin(matter.Ground(), Transform(Vec3(out, -16, 0)), wheel, Transform());
        Motion::Steady(sheave, 0.0);  // held
        // 8 m of rope at 10 m/s after 0.2 s ramps: hauled in by drum 1 (payout sense +1, angle
        // down), paid out by drum 2 (payout sense -1, angle down: its rope leaves it on the side
        // that faces the sheave).
        sr::MotionProfile move;
        move.moves = {sr::SmoothMove{0.0, 1.0, 0.2, 8.0}};
        sr::prescribeProfile(drum1, move, -1.0 / kDrum);
        sr::prescribeProfile(drum2, move, -1.0 / kDrum);
        reeving = std::make_unique<sr::ReevingSubsystem>(system);  // no gravity force: g = 0
        sr::RopeSpec rope;
        rope.sheaveModel = model;
        rope.start = sr::WinchDrum{drum1, kDrum, 20.0, 1, Vec3(0)};
        sr::TractionSheave ts{sheave, kR, kMu, 0.0, sRef, 1, Vec3(0)};
        ts.slipModel = slip;
        rope.sheaves = {ts};
        rope.end = sr::WinchDrum{drum2, kDrum, 20.0, -1, Vec3(0)};
        rope.properties = {kRhoA, kEA, 0.0, false};
        rope.properties.axialRetardationTime = 2e-3;  // damps the rope's axial motion at the sheave
        rope.unstretchedLength = length;
        rope.spanDefaults.axialModes = 2;
        rope.spanDefaults.axialDynamics = sr::AxialDynamics::QuasiStatic;
        rope.spanDefaults.transverseModes = 1;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        meter = std::make_unique<sr::MotionWorkMeter>(system);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

// Both spans stretched by kStretch at the start: s_ref and L from the geometry (a probe of the
// wrapped machine gives the material coordinates at the drums' and the groove's tangent points).
DrumsOverASheave* build(sr::TractionSlip slip, sr::SheaveModel model) {
    const double stretch = 1 - kStretch;
    if (model == sr::SheaveModel::Point) {
        const double a = std::hypot(kR, 8.0), b = std::hypot(kR, 16.0);
        return new DrumsOverASheave(slip, model, a * stretch, (a + b) * stretch);
    }
    const double sProbe = 9.0, lProbe = 30.0;
    DrumsOverASheave probe(slip, model, sProbe, lProbe);
    probe.system.realize(probe.state, Stage::Position);
    const auto a = probe.reeving->getSpanMaterialRange(probe.state, 0, 0);
    const auto b = probe.reeving->getSpanMaterialRange(probe.state, 0, 1);
    const double sIn = a.first + 8.0 * stretch;  // s_k at the arrival tangent point
    const double sRef = sIn - (a.second - sProbe);
    const double arc = b.first - a.second;  // R alpha
    const double length = sIn + arc + 16.0 * stretch - (b.second - lProbe);
    return new DrumsOverASheave(slip, model, sRef, length);
}

struct Measured {
    double withTerm = 0, withoutTerm = 0, speed = 0, energy = 0;
    int transitions = 0;
};

Measured run(sr::TractionSlip slip, sr::SheaveModel model) {
    const std::unique_ptr<DrumsOverASheave> machine(build(slip, model));
    DrumsOverASheave& p = *machine;
    RungeKuttaMersonIntegrator integ(p.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(p.system, integ);
    ts.initialize(p.state);
    p.system.realize(integ.getState(), Stage::Velocity);
    const double e0 = p.reeving->calcMechanicalEnergy(integ.getState());
    Measured w;
    double worst = 0, largest = 0;
    for (int i = 1; i <= 60; ++i) {
        ts.stepTo(0.01 * i);
        const State& s = integ.getState();
        p.system.realize(s, Stage::Velocity);
        // E - E0 + W_friction + W_damping = W_drives, against the largest term.
        const double de = p.reeving->calcMechanicalEnergy(s) - e0, wf = p.reeving->getFrictionWork(s, 0, 1);
        const double wd = p.reeving->getDampingWork(s), wm = p.meter->getWork(s);
        worst = std::max(worst, std::abs(de + wf + wd - wm));
        largest = std::max({largest, std::abs(de), std::abs(wf), std::abs(wd), std::abs(wm)});
        if (s.getTime() < 0.5 - 1e-12) continue;
        EXPECT_EQ(p.reeving->getTractionMode(s, 0, 1), sr::TractionMode::SlipTowardStart) << s.getTime();
        const double v = p.reeving->getSlipRate(s, 0, 1), c = kRhoA * v * v;
        const double ratio = p.reeving->getTractionRatio(s, 0, 1);  // P_a / P_b
        const double pb = p.reeving->getAxialForce(s, 0, 1, p.reeving->getSpanMaterialRange(s, 0, 1).first);
        const double pa = ratio * pb;
        const double limit = p.reeving->getTractionLimit(s, 0, 1);
        w.withTerm = std::max(w.withTerm, std::abs((pa - c) / (pb - c) / limit - 1));
        w.withoutTerm = std::max(w.withoutTerm, std::abs(ratio / limit - 1));
        w.speed = v;
    }
    w.transitions = p.reeving->getNumTractionTransitions(integ.getState(), 0, 1);
    w.energy = worst / largest;
    std::printf("[ momentum ] %s %s: v %.4f m/s, Euler-Eytelwein with rhoA v^2 off by %.2e, without it %.2e, "
                "transitions %d, energy balance %.2e of %.3e J\n",
                model == sr::SheaveModel::Wrapped ? "wrapped" : "point",
                slip == sr::TractionSlip::RopeMomentum ? "RopeMomentum" : "CapstanConstraint", w.speed, w.withTerm,
                w.withoutTerm, w.transitions, w.energy, largest);
    return w;
}

}  // namespace

// Steady slip at 10 m/s from t = 0.5 s to 0.6 s (rhoA v^2 = 200 N against end forces of about
// 1e5 N, so the centrifugal term moves the ratio by 6e-4):
//  - RopeMomentum: (P_a - rhoA v^2) / (P_b - rhoA v^2) = e^(mu alpha) to 2.8e-10 (point) and 2.3e-10
//    (wrapped), relative; bound 1e-8 (35x; the acceptance asks 1e-6). The plain capstan
//    ratio misses it by 6.0e-4: the check sees the term.
//  - CapstanConstraint (the massless contact point): P_a / P_b = e^(mu alpha) to 2.6e-12 and 4.1e-11
//    (bound 1e-9), and so misses the centrifugal law by 6.0e-4.
//  - Energy: E - E0 + W_friction + W_damping = W_drives (MotionWorkMeter) to 1.4e-14 / 6.4e-15
//    (RopeMomentum) and 3.3e-12 / 3.5e-12 (CapstanConstraint) of the largest term, 1.7e5 J;
//    bound 1e-10.
TEST(TractionRopeMomentum, SteadySlipFollowsEulerEytelweinWithTheCentrifugalTerm) {
    for (sr::SheaveModel model : {sr::SheaveModel::Point, sr::SheaveModel::Wrapped}) {
        const Measured m = run(sr::TractionSlip::RopeMomentum, model);
        EXPECT_LE(m.withTerm, 1e-8);
        EXPECT_GT(m.withoutTerm, 1e-4);
        EXPECT_LE(m.energy, 1e-10);
        EXPECT_EQ(m.transitions, 1);
        EXPECT_NEAR(m.speed, 10.0, 1e-3);
        const Measured c = run(sr::TractionSlip::CapstanConstraint, model);
        EXPECT_LE(c.withoutTerm, 1e-9);
        EXPECT_GT(c.withTerm, 1e-4);
        EXPECT_LE(c.energy, 1e-10);
        EXPECT_EQ(c.transitions, 1);
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
