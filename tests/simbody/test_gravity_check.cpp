// The ropes' gravity is given once. ReevingSubsystem(system) takes the system's
// gravity forces at realizeTopology; ReevingSubsystem(system, g) must agree with them; a per-state
// change of Force::Gravity (a State parameter) is an error at realizeDynamics.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;
using namespace SimbodyReeving;

namespace {

SimTK::Transform vertical(const Vec3& p) {
    // x -> y: a quarter turn about z written out (see test_hoisting.cpp).
    const SimTK::Mat33 R(0, -1, 0, 1, 0, 0, 0, 0, 1);
    return SimTK::Transform(SimTK::Rotation(R, true), p);
}

/// A 100 kg payload on a vertical Slider hanging from a Ground anchor by a 5 m planar rope.
struct Hang {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    std::unique_ptr<MobilizedBody::Slider> payload;
    std::unique_ptr<ReevingSubsystem> reeving;
    Hang() {
        payload = std::make_unique<MobilizedBody::Slider>(
            matter.Ground(), vertical(Vec3(0, -5, 0)),
            SimTK::Body::Rigid(SimTK::MassProperties(100, Vec3(0), SimTK::Inertia(1))), vertical(Vec3(0)));
    }
    void addRope(Vec3 planeNormal = Vec3(0, 0, 1)) {
        RopeSpec r;
        r.start = RopeAnchor{matter.Ground(), Vec3(0)};
        r.end = RopeAnchor{*payload, Vec3(0)};
        r.properties = {0.6, 1e7, 0};
        r.unstretchedLength = 5;
        r.spanDefaults.axialModes = 1;
        r.spanDefaults.transverseModes = 1;
        r.planeNormal = planeNormal;
        reeving->addRope(r);
    }
};

}  // namespace

TEST(GravityCheck, GivenGravityDisagreeingWithForceGravityIsALogicErrorNamingBoth) {
    Hang h;
    SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, -9.81, 0));
    h.reeving = std::make_unique<ReevingSubsystem>(h.system, Vec3(0, -9.80665, 0));
    h.addRope();
    EXPECT_THROW_MESSAGE(h.system.realizeTopology(), std::logic_error,
                         "ReevingSubsystem: the ropes' gravity (0, -9.80665, 0) m/s^2 (constructor argument) differs "
                         "from the gravity the bodies feel, (0, -9.81, 0) m/s^2 (the sum of the system's 1 "
                         "Force::Gravity / Force::UniformGravity defaults)");
}

TEST(GravityCheck, GivenGravityAgreeingWithTheSystemIsAccepted) {
    Hang h;
    SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, -9.81, 0));
    h.reeving = std::make_unique<ReevingSubsystem>(h.system, Vec3(0, -9.81, 0));
    h.addRope();
    EXPECT_NO_THROW(h.system.realizeTopology());
}

TEST(GravityCheck, GivenGravityWithoutAnyGravityForceIsUsedAsIs) {
    Hang h;  // bodies loaded some other way: nothing to compare with
    h.reeving = std::make_unique<ReevingSubsystem>(h.system, Vec3(0, -9.81, 0));
    h.addRope();
    EXPECT_NO_THROW(h.system.realizeTopology());
    EXPECT_EQ(h.reeving->getGravity(), Vec3(0, -9.81, 0));
}

TEST(GravityCheck, SystemGravityIsTheSumOfTheEnabledGravityForces) {
    {
        Hang h;
        SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, -9.81, 0));
        h.reeving = std::make_unique<ReevingSubsystem>(h.system);
        h.addRope();
        EXPECT_EQ(h.reeving->getGravity(), Vec3(0));  // not known before realizeTopology
        h.system.realizeTopology();
        EXPECT_EQ(h.reeving->getGravity(), Vec3(0, -9.81, 0));
    }
    {
        Hang h;  // two forces add up on the bodies, so on the rope too; a disabled one does not count
        SimTK::Force::Gravity a(h.forces, h.matter, Vec3(0, -6, 0));
        SimTK::Force::UniformGravity b(h.forces, h.matter, Vec3(0, -3, 0));
        SimTK::Force::Gravity off(h.forces, h.matter, Vec3(0, -100, 0));
        off.setDisabledByDefault(true);
        h.reeving = std::make_unique<ReevingSubsystem>(h.system);
        h.addRope();
        h.system.realizeTopology();
        EXPECT_EQ(h.reeving->getGravity(), Vec3(0, -9, 0));
    }
    {
        Hang h;  // no gravity force: no gravity on the bodies, none on the rope
        h.reeving = std::make_unique<ReevingSubsystem>(h.system);
        h.addRope();
        h.system.realizeTopology();
        EXPECT_EQ(h.reeving->getGravity(), Vec3(0));
    }
}

TEST(GravityCheck, SystemGravityOutOfAPlanarRopesPlaneIsALogicError) {
    Hang h;
    SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, 0, -9.81));
    h.reeving = std::make_unique<ReevingSubsystem>(h.system);
    h.addRope(Vec3(0, 0, 1));
    EXPECT_THROW_MESSAGE(h.system.realizeTopology(), std::logic_error,
                         "ReevingSubsystem: rope 'rope': gravity (0, 0, -9.81) is not in the rope plane (normal (0, 0, 1))");
}

TEST(GravityCheck, ChangingGravityInAStateIsALogicErrorAtDynamics) {
    Hang h;
    SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, -9.81, 0));
    h.reeving = std::make_unique<ReevingSubsystem>(h.system);
    h.addRope();
    h.system.realizeTopology();
    State s = h.system.getDefaultState();
    EXPECT_NO_THROW(h.system.realize(s, Stage::Dynamics));
    gravity.setMagnitude(s, 1.62);
    EXPECT_THROW_MESSAGE(h.system.realize(s, Stage::Dynamics), std::logic_error,
                         "ReevingSubsystem: the gravity the bodies feel in this state, (0, -1.62, 0) m/s^2 (the "
                         "system's enabled Force::Gravity / Force::UniformGravity), differs from the ropes' gravity "
                         "(0, -9.81, 0) m/s^2 fixed at realizeTopology");
    State t = h.system.getDefaultState();
    gravity.disable(t);  // the bodies feel no gravity, the rope would
    EXPECT_THROW_MESSAGE(h.system.realize(t, Stage::Dynamics), std::logic_error,
                         "ReevingSubsystem: the gravity the bodies feel in this state, (0, 0, 0) m/s^2 (the "
                         "system's enabled Force::Gravity / Force::UniformGravity), differs from the ropes' gravity "
                         "(0, -9.81, 0) m/s^2 fixed at realizeTopology");
}

// The rope takes the system's gravity: the static equilibrium equals the one with the gravity given
// explicitly, and the payload's rope force balances its weight.
TEST(GravityCheck, SystemGravityGivesTheSameEquilibriumAsTheExplicitOne) {
    auto solve = [](bool fromSystem, Vec3* nodeForce) {
        Hang h;
        SimTK::Force::Gravity gravity(h.forces, h.matter, Vec3(0, -9.81, 0));
        h.reeving = fromSystem ? std::make_unique<ReevingSubsystem>(h.system)
                               : std::make_unique<ReevingSubsystem>(h.system, Vec3(0, -9.81, 0));
        h.addRope();
        h.system.realizeTopology();
        State s = h.system.getDefaultState();
        h.reeving->findStaticEquilibrium(s, 1e-12);
        h.system.realize(s, Stage::Acceleration);
        *nodeForce = h.reeving->getNodeForce(s, 0, 1);
        return h.payload->getOneQ(s, 0);
    };
    Vec3 fSystem, fGiven;
    const double ySystem = solve(true, &fSystem), yGiven = solve(false, &fGiven);
    std::printf("[ gravity ] payload at %.12f m, rope force on it %.9f N (M g = 981 N)\n", ySystem, fSystem[1]);
    EXPECT_EQ(ySystem, yGiven);
    EXPECT_EQ(fSystem, fGiven);
    // F on the payload = -M g: measured 981.000000000 N (difference below 1e-9 N).
    EXPECT_NEAR(fSystem[1], 100 * 9.81, 1e-7);
}
