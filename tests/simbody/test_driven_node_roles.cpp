// The Driven nodes' run-time roles (plugin/simbody/src/nodes/DrivenRole.h) on their own: a
// WinchDrum's stored rope (what it declares to the rope model, the rope on the drum against the
// closed form ropeOnDrum + s_0 or ropeOnDrum + L - s_N, and through WinchDrumHandle against
// ropeOnDrum - sense R theta); a TractionSheave's phase key entries (0 in stick and for
// TractionSlip::RopeMomentum, e^(+-mu alpha) with a given wrap angle, +-1 with the geometry's),
// the phase model's material kinds and its Z entries (friction work, Y and Ydot: laid out among
// the rope's other driven nodes by DrivenRole::layoutZ, read and compared by the role itself); a
// TurningSheave's role adds nothing. And the power a pinned node's query reports: torque times the node's angle
// rate, which on a wrapped groove carried by a turning parent is the sheave body's own rate.
#include "../../plugin/simbody/src/ReevingSubsystemGuts.h"

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <variant>
#include <vector>

// (Using-declarations, not the namespace: SimTK's generic operator!= would capture Eigen's
// compile-time comparisons of the internal header's Eigen types.)
using SimTK::Body;
using SimTK::GeneralForceSubsystem;
using SimTK::Inertia;
using SimTK::MassProperties;
using SimTK::MobilizedBody;
using SimTK::MultibodySystem;
using SimTK::Pi;
using SimTK::Rotation;
using SimTK::SimbodyMatterSubsystem;
using SimTK::Stage;
using SimTK::State;
using SimTK::Transform;
using SimTK::Vec3;
using SimTK::Vector;
using SimTK::ZAxis;
namespace sr = SimbodyReeving;
using sr::detail::DrivenZBlock;
using sr::detail::DrivenRole;
using sr::detail::GripRole;
using sr::detail::StoredRopeRole;
using sr::detail::TractionNodeState;
using sr::detail::TractionRole;

namespace {

// What a role declares to a rope model (RopeModel::setStoredRope's (node, lengthAtZero)).
struct StoredRopeRecorder {
    std::vector<std::pair<int, double>> declared;
    std::vector<int> grips;
    void setStoredRope(int node, double lengthAtZero) { declared.emplace_back(node, lengthAtZero); }
    void setGrip(int node) { grips.push_back(node); }
};

std::vector<TractionNodeState> phases(std::vector<sr::TractionMode> modes) {
    std::vector<TractionNodeState> out(modes.size());
    for (std::size_t i = 0; i < modes.size(); ++i) out[i].mode = modes[i];
    return out;
}

TractionRole tractionRole(int index, double mu, double wrapAngle, sr::TractionSlip slip) {
    TractionRole t;
    t.index = index;
    t.frictionCoefficient = mu;
    t.givenWrapAngle = wrapAngle;
    t.geometricWrap = wrapAngle == 0;
    t.slipModel = slip;
    return t;
}

}  // namespace

TEST(DrivenRole, StoredRopeIsTheDrumsRopeBeyondTheExit) {
    const double L = 40.0, onDrum = 12.5;
    StoredRopeRole drum;
    drum.ropeOnDrum = onDrum;
    // Declared at zero exit coordinate (RopeModel::setStoredRope): ropeOnDrum at a start drum,
    // ropeOnDrum + L at an end drum (its l = that - s_N).
    StoredRopeRecorder model;
    DrivenRole{drum}.declareStoredRope(model, 0, L);
    DrivenRole{drum}.declareStoredRope(model, 5, L);
    ASSERT_EQ(model.declared.size(), 2u);
    EXPECT_EQ(model.declared[0], (std::pair<int, double>{0, onDrum}));
    EXPECT_EQ(model.declared[1], (std::pair<int, double>{5, onDrum + L}));
    // The rope on the drum from the exit's material coordinate: ropeOnDrum + s_0 at the start
    // (s_0 = -0.75 m: 0.75 m paid out), ropeOnDrum + L - s_N at the end (s_N = 41 m: 1 m paid out).
    EXPECT_EQ(drum.onDrum(0, -0.75, L), onDrum - 0.75);
    EXPECT_EQ(drum.onDrum(5, 41.0, L), onDrum - 1.0);
    // The other roles declare nothing.
    DrivenRole{GripRole{}}.declareStoredRope(model, 0, L);
    DrivenRole{tractionRole(0, 0.2, Pi, sr::TractionSlip::CapstanConstraint)}.declareStoredRope(model, 1, L);
    EXPECT_EQ(model.declared.size(), 2u);
    EXPECT_TRUE(model.grips.empty());  // a point drum does not grip
}

// A wrapped drum grips the rope (RopeModel::setGrip) and takes two Z entries: the wound rope's
// strain energy among the work integrals, its creep among the states; the energy is potential.
TEST(DrivenRole, WrappedDrumGripsAndHoldsItsCreepAndWoundEnergy) {
    StoredRopeRole drum;
    drum.ropeOnDrum = 3.0;
    drum.grips = true;
    StoredRopeRecorder model;
    DrivenRole role{drum};
    role.declareStoredRope(model, 0, 40.0);
    ASSERT_EQ(model.grips, std::vector<int>{0});
    int z = 7;
    role.layoutZ(DrivenZBlock::Work, z);
    EXPECT_EQ(z, 8);
    role.layoutZ(DrivenZBlock::States, z);
    EXPECT_EQ(z, 9);
    SimTK::Vector zv(9, 0.0);
    zv[7] = 2.5;   // U_w [J]
    zv[8] = 1e-3;  // c [m]
    double u = 1.0;
    role.addHeldEnergy(zv, u);
    EXPECT_EQ(u, 3.5);
    double entry = 0;
    role.readZState(zv, false, entry);
    EXPECT_EQ(entry, 1e-3);
    EXPECT_TRUE(role.zStateMatches(zv, false, 1e-3));
    EXPECT_FALSE(role.zStateMatches(zv, false, 0.0));
}

TEST(DrivenRole, TractionPhaseKeyIsTheCapstanRatioOfTheSlipsDirection) {
    using sr::TractionMode;
    const double mu = 0.3, alpha = 2.5, kappa = std::exp(mu * alpha);  // 2.117
    const TractionRole given = tractionRole(1, mu, alpha, sr::TractionSlip::CapstanConstraint);
    TractionNodeState t;
    EXPECT_EQ(given.phaseKeyEntry(t), 0.0);  // stick
    t.mode = TractionMode::SlipTowardStart;  // span k - 1 tight: P_{k-1} = kappa P_k
    EXPECT_EQ(given.phaseKeyEntry(t), kappa);
    t.mode = TractionMode::SlipTowardEnd;
    EXPECT_EQ(given.phaseKeyEntry(t), 1.0 / kappa);
    // The geometry's wrap angle: the slip's direction alone (the law takes alpha each evaluation).
    const TractionRole geometric = tractionRole(1, mu, 0.0, sr::TractionSlip::CapstanConstraint);
    EXPECT_TRUE(geometric.geometricWrap);
    t.mode = TractionMode::SlipTowardStart;
    EXPECT_EQ(geometric.phaseKeyEntry(t), 1.0);
    t.mode = TractionMode::SlipTowardEnd;
    EXPECT_EQ(geometric.phaseKeyEntry(t), -1.0);
    // RopeMomentum: Driven by its slip state Y in slip too, so its rope keeps the stick model.
    const TractionRole momentum = tractionRole(1, mu, alpha, sr::TractionSlip::RopeMomentum);
    for (TractionMode m : {TractionMode::Stick, TractionMode::SlipTowardStart, TractionMode::SlipTowardEnd}) {
        t.mode = m;
        EXPECT_EQ(momentum.phaseKeyEntry(t), 0.0);
    }
}

TEST(DrivenRole, TractionPhaseModelTakesTheSlippingSheavesOwnEntries) {
    using sr::TractionMode;
    const double mu = 0.2;
    // Sheave 0 given alpha = pi, sheave 1 the geometry's; rope phases: 0 slips towards the start,
    // 1 sticks.
    const DrivenRole a{tractionRole(0, mu, Pi, sr::TractionSlip::CapstanConstraint)};
    const DrivenRole b{tractionRole(1, mu, 0.0, sr::TractionSlip::CapstanConstraint)};
    const DrivenRole grip{GripRole{}};
    const std::vector<TractionNodeState> ts = phases({TractionMode::SlipTowardStart, TractionMode::Stick});
    EXPECT_TRUE(a.slipsInPhase(ts));
    EXPECT_FALSE(b.slipsInPhase(ts));
    EXPECT_FALSE(grip.slipsInPhase(ts));
    std::vector<double> key(2, 0.0);
    for (const DrivenRole* r : {&grip, &a, &b}) r->writePhaseKey(ts, key);
    EXPECT_EQ(key, (std::vector<double>{std::exp(mu * Pi), 0.0}));
    for (const DrivenRole* r : {&grip, &a, &b}) EXPECT_TRUE(r->phaseKeyMatches(key, ts));
    // The other phase (1 slips towards the end): a's entry differs, b's too, the grip has none.
    const std::vector<TractionNodeState> other = phases({TractionMode::Stick, TractionMode::SlipTowardEnd});
    EXPECT_FALSE(a.phaseKeyMatches(key, other));
    EXPECT_FALSE(b.phaseKeyMatches(key, other));
    EXPECT_TRUE(grip.phaseKeyMatches(key, other));
    // Material kinds in the phase model of `key`: only the slipping sheave is Slipping.
    sr::MaterialNode ka = sr::MaterialNode::Driven, kb = sr::MaterialNode::Driven, kg = sr::MaterialNode::Driven;
    a.phaseMaterialKind(key, ka);
    b.phaseMaterialKind(key, kb);
    grip.phaseMaterialKind(key, kg);
    EXPECT_EQ(ka, sr::MaterialNode::Slipping);
    EXPECT_EQ(kb, sr::MaterialNode::Driven);
    EXPECT_EQ(kg, sr::MaterialNode::Driven);
    // Initial phases: each sheave's stick offset is its spec's s_ref; the grip has no entry.
    std::vector<TractionNodeState> initial(2);
    a.initialPhase(initial, 3.25);
    b.initialPhase(initial, -1.5);
    grip.initialPhase(initial, 99.0);
    EXPECT_EQ(initial[0].sStick, 3.25);
    EXPECT_EQ(initial[1].sStick, -1.5);
}

TEST(DrivenRole, TractionOwnsItsFrictionWorkAndSlipStateEntries) {
    // Laid out as its rope lays them out (DrivenRole::layoutZ: each block over the rope's driven
    // nodes in node order) from Z entry 10, a grip, traction sheaves a and b and a drum: the
    // friction work of a at 10 and of b at 11 (DrivenZBlock::Work), then Y, Ydot of a at 12, 13
    // and of b at 14, 15 (DrivenZBlock::States); the grip and the drum take none.
    std::vector<DrivenRole> roles = {DrivenRole{GripRole{}},
                                     DrivenRole{tractionRole(0, 0.2, Pi, sr::TractionSlip::RopeMomentum)},
                                     DrivenRole{tractionRole(1, 0.2, Pi, sr::TractionSlip::RopeMomentum)},
                                     DrivenRole{StoredRopeRole{}}};
    int next = 10;
    for (const sr::detail::DrivenZBlock block : {sr::detail::DrivenZBlock::Work, sr::detail::DrivenZBlock::States})
        for (DrivenRole& role : roles) role.layoutZ(block, next);
    EXPECT_EQ(next, 16);
    const TractionRole& a = std::get<TractionRole>(roles[1].unit);
    const TractionRole& b = std::get<TractionRole>(roles[2].unit);
    EXPECT_EQ(a.frictionWorkZ(), 10);
    EXPECT_EQ(b.frictionWorkZ(), 11);
    EXPECT_EQ(a.slipStateZ(), 12);
    EXPECT_EQ(b.slipStateZ(), 14);
    Vector z(20, 0.0);
    z[10] = 100.0;  // a's friction work [J]
    z[11] = 3.5;    // b's
    z[14] = 2.5;    // b's Y [m]
    z[15] = -0.75;  // its Ydot [m/s]
    // Each reads and compares its own state entries; the others have none.
    double y = 0, yDot = 0, none = 7.0;
    roles[2].readZState(z, false, y);
    roles[2].readZState(z, true, yDot);
    roles[0].readZState(z, false, none);
    roles[3].readZState(z, true, none);
    EXPECT_EQ(y, 2.5);
    EXPECT_EQ(yDot, -0.75);
    EXPECT_EQ(none, 7.0);
    EXPECT_TRUE(roles[2].zStateMatches(z, false, 2.5));
    EXPECT_FALSE(roles[2].zStateMatches(z, true, 2.5));
    EXPECT_TRUE(roles[1].zStateMatches(z, false, 0.0));
    EXPECT_FALSE(roles[1].zStateMatches(z, false, 2.5));
    EXPECT_TRUE(roles[0].zStateMatches(z, false, 1e9));
    EXPECT_TRUE(roles[3].zStateMatches(z, true, 1e9));
    double w = 0.25;
    for (const DrivenRole& role : roles) role.addFrictionWork(z, w);
    EXPECT_EQ(w, 0.25 + 100.0 + 3.5);
}

namespace {

// A WinchDrum (R = 0.4 m, 30 m stored) on a Pin at the origin paying out to an anchor 10 m below;
// planar, point drum: s_0 = -sense R theta.
struct Drum {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Pin pin;
    State state;
    explicit Drum(int sense) {
        pin = MobilizedBody::Pin(matter.Ground(), Transform(), Body::Rigid(MassProperties(10, Vec3(0), Inertia(1))),
                                 Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0));
        sr::RopeSpec rope;
        sr::WinchDrum drum;
        drum.body = pin;
        drum.radius = 0.4;
        drum.ropeOnDrum = 30.0;
        drum.payoutSense = sense;
        rope.start = drum;
        rope.end = sr::RopeAnchor{matter.Ground(), Vec3(0, -10, 0)};
        rope.properties = {0.5, 1e7, 0.0};
        rope.unstretchedLength = 10.0;
        rope.planeNormal = Vec3(0, 0, 1);
        rope.spanDefaults.axialModes = 0;
        rope.spanDefaults.transverseModes = 0;
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

}  // namespace

TEST(DrivenRole, WinchDrumRopeOnDrumIsTheStoredRopeLessThePayout) {
    for (int sense : {1, -1}) {
        Drum d(sense);
        const double theta = 1.7;  // [rad]
        d.pin.setOneQ(d.state, 0, theta);
        d.system.realize(d.state, Stage::Position);
        const double onDrum = d.reeving->getRope(0).getWinchDrum(0).getRopeOnDrum(d.state);
        // ropeOnDrum - sense R theta: one product and one sum of values of order 10 (round-off).
        EXPECT_NEAR(onDrum, 30.0 - sense * 0.4 * theta, 1e-14 * 30.0) << "sense " << sense;
        EXPECT_EQ(onDrum, 30.0 + d.reeving->getMaterialCoordinate(d.state, 0, 0));
    }
}

namespace {

constexpr double kR = 0.3;     // sheave radius [m]
constexpr double kBoom = 6.0;  // [m]

// A wrapped TurningSheave at the tip of a boom on a Pin (free, turning about the plane normal z):
// the sheave's angle theta is its pin's plus the boom's turn (ParentTurnAngle), thetadot its
// body's angular velocity about z, u_boom + u_sheave. The rope runs from an anchor at the boom's
// foot over the groove down to an anchor 5 m under the far side; the anchor's span holds 2 mm less
// material than its chord, so the spans pull unequally and the rope turns the sheave.
struct BoomTipSheave {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    std::unique_ptr<sr::ReevingSubsystem> reeving;
    MobilizedBody::Pin boom, sheave;
    State state;
    BoomTipSheave() {
        boom = MobilizedBody::Pin(matter.Ground(), Transform(Rotation(0.6, ZAxis)),
                                  Body::Rigid(MassProperties(800, Vec3(0.5 * kBoom, 0, 0), Inertia(Vec3(1, 7201, 7201)))),
                                  Transform());
        sheave = MobilizedBody::Pin(boom, Transform(Vec3(kBoom, 0, 0)),
                                    Body::Rigid(MassProperties(30, Vec3(0), Inertia(0.5))), Transform());
        reeving = std::make_unique<sr::ReevingSubsystem>(system, Vec3(0, -9.81, 0));
        sr::RopeSpec rope;
        rope.sheaveModel = sr::SheaveModel::Wrapped;
        rope.planeNormal = Vec3(0, 0, 1);
        const Vec3 anchor(0, 0.8, 0);
        const Vec3 tipPoint(kBoom * std::cos(0.6), kBoom * std::sin(0.6), 0);
        rope.properties = {0.6205, 16.5e6, 0.0};
        rope.spanDefaults.axialModes = 0;
        rope.spanDefaults.transverseModes = 0;
        rope.start = sr::RopeAnchor{matter.Ground(), anchor};
        rope.end = sr::RopeAnchor{matter.Ground(), tipPoint + Vec3(kR, -5.0, 0)};
        sr::TurningSheave tip;
        tip.body = sheave;
        tip.radius = kR;
        tip.sense = 1;
        const double chord = (tipPoint + Vec3(0, kR, 0) - anchor).norm();
        rope.unstretchedLength = chord + 0.5 * Pi * kR + 5.0;
        tip.materialCoordinateAtZeroAngle = chord - tip.sense * kR * 0.6 - 2e-3;
        rope.sheaves = {tip};
        reeving->addRope(rope);
        system.realizeTopology();
        state = system.getDefaultState();
    }
};

}  // namespace

// The torque is the generalized force on theta, a torque about z on the sheave body
// (DrivenAngleRow::bodyTorque): its power is torque (u_boom + u_sheave), not torque u_sheave
// (what the query returned before: 0.3 / -0.4 of it here, the wrong sign).
TEST(DrivenRole, PinnedNodePowerIsTheTorqueTimesTheSheavesOwnRate) {
    BoomTipSheave b;
    const double uBoom = 0.7, uSheave = -0.4;  // [rad/s]
    b.boom.setOneU(b.state, 0, uBoom);
    b.sheave.setOneU(b.state, 0, uSheave);
    b.system.realize(b.state, Stage::Dynamics);
    const sr::TurningSheaveHandle tip = b.reeving->getRope(0).getTurningSheave(1);
    const double torque = tip.getTorque(b.state), power = tip.getPower(b.state);
    const double omega = b.sheave.getBodyAngularVelocity(b.state)[2];  // the sheave body's rate about z
    std::printf("boom tip sheave: torque %.6g N m, power %.6g W, body rate %.6g rad/s (pin rate %.3g)\n", torque, power,
                omega, uSheave);
    EXPECT_GT(std::abs(torque), 100.0);  // the spans pull unequally
    EXPECT_NEAR(omega, uBoom + uSheave, 1e-15);
    // One product: round-off of the torque's order.
    EXPECT_NEAR(power, torque * omega, 1e-14 * std::abs(torque));
}
