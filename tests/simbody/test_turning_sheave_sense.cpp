// TurningSheave::sense as documented: s_k = s_ref + sense R theta, so with sense = +1 a positive pin
// angle moves rope from the end side of the sheave to its start side (the start-side span gains
// material and slackens, the end-side span loses material and stretches); sense = -1 reverses it.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <Simbody.h>

using namespace SimTK;

namespace {

struct Result {
    double sheaveS;       // material coordinate at the sheave [m]
    double startStrain;   // largest strain of the start-side span
    double endStrain;     // largest strain of the end-side span
};

// Rope anchored on Ground at (0, 0) and (2, 0), over a turning sheave of radius 0.1 m at (1, 0.5),
// pin angle theta; rhoA small so the spans are near straight.
Result evaluate(int sense, double theta) {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    SimbodyReeving::ReevingSubsystem reeving(system, Vec3(0, -9.81, 0));
    MobilizedBody::Pin sheave(matter.Ground(), Transform(Vec3(1, 0.5, 0)),
                              Body::Rigid(MassProperties(1, Vec3(0), Inertia(0.01))), Transform());
    SimbodyReeving::RopeSpec rope;
    rope.start = SimbodyReeving::RopeAnchor{matter.Ground(), Vec3(0)};
    rope.sheaves = {SimbodyReeving::TurningSheave{sheave, 0.1, 1.1, sense}};
    rope.end = SimbodyReeving::RopeAnchor{matter.Ground(), Vec3(2, 0, 0)};
    rope.properties = {1e-3, 1e6, 0.0, false};
    rope.unstretchedLength = 2.2;  // each chord is sqrt(1.25) = 1.118 m: both spans stretched
    rope.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(rope);
    system.realizeTopology();
    State s = system.getDefaultState();
    sheave.setOneQ(s, 0, theta);
    system.realize(s, Stage::Position);
    return {reeving.getMaterialCoordinate(s, 0, 1), reeving.getSpanMaxStrain(s, 0, 0),
            reeving.getSpanMaxStrain(s, 0, 1)};
}

TEST(TurningSheaveSense, PositiveAngleMovesRopeFromTheEndSideToTheStartSide) {
    const Result rest = evaluate(+1, 0.0);
    const Result turned = evaluate(+1, 0.1);
    EXPECT_NEAR(rest.sheaveS, 1.1, 1e-15);
    EXPECT_NEAR(turned.sheaveS, 1.1 + 0.1 * 0.1, 1e-15);  // s_ref + R theta
    EXPECT_LT(turned.startStrain, rest.startStrain);      // start side gained material
    EXPECT_GT(turned.endStrain, rest.endStrain);          // end side lost it
}

TEST(TurningSheaveSense, NegativeSenseReverses) {
    const Result rest = evaluate(-1, 0.0);
    const Result turned = evaluate(-1, 0.1);
    EXPECT_NEAR(turned.sheaveS, 1.1 - 0.1 * 0.1, 1e-15);
    EXPECT_GT(turned.startStrain, rest.startStrain);
    EXPECT_LT(turned.endStrain, rest.endStrain);
}

}  // namespace
