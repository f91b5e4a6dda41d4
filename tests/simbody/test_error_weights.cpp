// The integrator error weights of a span's axial modal coordinates follow that
// span's own current material length l: w = i pi / (l eps_ref), eps_ref = 1e-3 (see
// ReevingRealization.cpp, setZWeights); rates 1 / (eps_ref sqrt(EA / rhoA)); transverse 1.
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using SimTK::MobilizedBody;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;
using namespace SimbodyReeving;

namespace {

const double kPi = std::acos(-1.0);

SimTK::Transform vertical(const Vec3& p) {
    // x -> y: a quarter turn about z written out (see test_hoisting.cpp).
    const SimTK::Mat33 R(0, -1, 0, 1, 0, 0, 0, 0, 1);
    return SimTK::Transform(SimTK::Rotation(R, true), p);
}

}  // namespace

// A winch drum (radius 0.25 m) on Ground at height 10 m, 3 m across to a Ground sheave, then down
// to a hook on a vertical Slider: span 0 about 3 m, span 1 20 m, then the drum hauls 19.5 m in.
TEST(ErrorWeights, AxialWeightsFollowEachSpansCurrentLength) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    SimTK::Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    MobilizedBody::Pin drum(matter.Ground(), SimTK::Transform(Vec3(0, 10, 0)),
                            SimTK::Body::Rigid(SimTK::MassProperties(1, Vec3(0), SimTK::Inertia(2))),
                            SimTK::Transform());
    MobilizedBody::Slider hook(matter.Ground(), vertical(Vec3(3, 10, 0)),
                               SimTK::Body::Rigid(SimTK::MassProperties(50, Vec3(0), SimTK::Inertia(1))),
                               vertical(Vec3(0)));
    ReevingSubsystem reeving(system);
    RopeSpec r;
    const double R = 0.25;
    r.start = WinchDrum{drum, R, 100.0, 1};
    r.sheaves = {DeviationSheave{matter.Ground(), Vec3(3, 10, 0), 0.1}};
    r.end = RopeAnchor{hook, Vec3(0)};
    r.properties = {0.6, 1.65e7, 0};
    r.unstretchedLength = 23 / 1.001;  // taut: strain about 1e-3
    r.spanDefaults.axialModes = 2;
    r.spanDefaults.axialDynamics = AxialDynamics::Dynamic;
    r.spanDefaults.transverseModes = 1;
    r.planeNormal = Vec3(0, 0, 1);
    reeving.addRope(r);
    system.realizeTopology();
    State s = system.getDefaultState();
    ASSERT_EQ(reeving.getNumModalCoordinates(0), 6);  // per span: 2 axial, 1 transverse

    const double wave = std::sqrt(1.65e7 / 0.6);
    auto check = [&](double hookDrop, double theta) {
        hook.setOneQ(s, 0, -hookDrop);
        drum.setOneQ(s, 0, theta);
        system.realize(s, Stage::Position);
        const SimTK::Vector& w = reeving.getZWeights(s);
        for (int span = 0; span < 2; ++span) {
            const auto [s1, s2] = reeving.getSpanMaterialRange(s, 0, span);
            const double l = s2 - s1;
            for (int i = 1; i <= 2; ++i) {
                EXPECT_DOUBLE_EQ(w[3 * span + i - 1], i * kPi / (l * 1e-3)) << "span " << span << " mode " << i;
                EXPECT_DOUBLE_EQ(w[6 + 3 * span + i - 1], 1.0 / (1e-3 * wave));
            }
            EXPECT_EQ(w[3 * span + 2], 1.0);
            EXPECT_EQ(w[6 + 3 * span + 2], 1.0);
        }
        const auto [a, b] = reeving.getSpanMaterialRange(s, 0, 0);
        const auto [c, d] = reeving.getSpanMaterialRange(s, 0, 1);
        return std::make_pair(b - a, d - c);
    };
    // Drum at 0: spans of about 3 m and 20 m (the mean, 11.5 m, was used for both before).
    const auto [l0, l1] = check(20.0, 0.0);
    EXPECT_NEAR(l0, 3.0, 0.05);
    EXPECT_NEAR(l1, 20.0, 0.05);
    // Hauled in by R theta = 19.5 m, hook raised with it: span 1 is 40x shorter, its weight 40x larger.
    const auto [m0, m1] = check(0.5, -19.5 / R);
    EXPECT_NEAR(m0, 3.0, 0.05);
    EXPECT_NEAR(m1, 0.5, 0.05);
    EXPECT_GT(l1 / m1, 39.0);
}
