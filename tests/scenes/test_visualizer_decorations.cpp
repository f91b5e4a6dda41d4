// What ReevingSubsystem's decorations draw: spans coloured by axial force through the
// documented colour map, the rope on the grooves of wrapped sheaves, sheaves at their radius, the
// drum's stored rope following getRopeOnDrum, and the force scale's validation.
#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/scenes/PendulumScene.h>
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace SimbodyReeving;
using SimTK::Array_;
using SimTK::DecorativeGeometry;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace {

struct Drawn : SimTK::DecorativeGeometryImplementation {
    struct Line {
        Vec3 colour;
        double thickness;
        Vec3 from, to;
    };
    std::vector<Line> lines;
    std::vector<double> cylinderRadii, sphereRadii;
    void implementPointGeometry(const SimTK::DecorativePoint&) override {}
    void implementLineGeometry(const SimTK::DecorativeLine& l) override {
        lines.push_back({l.getColor(), l.getLineThickness(), l.getPoint1(), l.getPoint2()});
    }
    void implementBrickGeometry(const SimTK::DecorativeBrick&) override {}
    void implementCylinderGeometry(const SimTK::DecorativeCylinder& c) override { cylinderRadii.push_back(c.getRadius()); }
    void implementCircleGeometry(const SimTK::DecorativeCircle&) override {}
    void implementSphereGeometry(const SimTK::DecorativeSphere& s) override { sphereRadii.push_back(s.getRadius()); }
    void implementEllipsoidGeometry(const SimTK::DecorativeEllipsoid&) override {}
    void implementFrameGeometry(const SimTK::DecorativeFrame&) override {}
    void implementTextGeometry(const SimTK::DecorativeText&) override {}
    void implementMeshGeometry(const SimTK::DecorativeMesh&) override {}
    void implementMeshFileGeometry(const SimTK::DecorativeMeshFile&) override {}
    void implementArrowGeometry(const SimTK::DecorativeArrow&) override {}
    void implementTorusGeometry(const SimTK::DecorativeTorus&) override {}
    void implementConeGeometry(const SimTK::DecorativeCone&) override {}

    int countLines(const Vec3& colour) const {
        return static_cast<int>(std::count_if(lines.begin(), lines.end(),
                                              [&](const Line& l) { return (l.colour - colour).norm() < 1e-12; }));
    }
};

Drawn draw(const ReevingSubsystem& rv, const State& s) {
    Array_<DecorativeGeometry> g;
    rv.getSubsystemGuts().calcDecorativeGeometryAndAppend(s, Stage::Position, g);
    Drawn d;
    for (const DecorativeGeometry& x : g) x.implementGeometry(d);
    return d;
}

// The documented map: (1 - x) (0.1, 0.3, 1) + x (1, 0.1, 0.05), x clamped to [0, 1].
Vec3 mapColour(double x) {
    x = std::min(std::max(x, 0.0), 1.0);
    return Vec3(0.1, 0.3, 1.0) * (1 - x) + Vec3(1.0, 0.1, 0.05) * x;
}

}  // namespace

TEST(VisualizerDecorations, PendulumSpansColouredByAxialForceSheaveAtItsRadius) {
    PendulumScene scene(PendulumParameters{}, SpanOptions{});
    const State s = scene.makeInitialState(0, 0);
    const ReevingSubsystem& rv = scene.reeving();
    const PendulumParameters& p = scene.parameters();
    const double reference = 2 * p.M * p.g;
    EXPECT_DOUBLE_EQ(rv.getDecorationForceScale(s), reference);
    const Drawn d = draw(rv, s);
    // Span segments (thickness 4): 2 spans x (20 points - 1), segment k of span j in the colour of
    // the axial force at its midpoint.
    std::vector<Vec3> segments;
    for (const auto& l : d.lines)
        if (l.thickness == 4) segments.push_back(l.colour);
    ASSERT_EQ(segments.size(), 38u);
    double worst = 0;
    for (int j = 0, i = 0; j < 2; ++j) {
        const auto [s1, s2] = rv.getSpanMaterialRange(s, 0, j);
        for (int k = 0; k < 19; ++k, ++i)
            worst = std::max(worst, (segments[i] - mapColour(rv.getAxialForce(s, 0, j, s1 + (s2 - s1) * (k + 0.5) / 19) /
                                                             reference)).norm());
    }
    EXPECT_LT(worst, 1e-12);  // measured 0: the same formula
    // At rest the rope carries M g plus at most its own weight (122 N, 1.2 %): x about 0.5.
    std::printf("colour distance of the payload-end segment from x = 0.5: %.3g; worst segment %.3g\n",
                (segments.back() - mapColour(0.5)).norm(), worst);
    EXPECT_LT((segments.back() - mapColour(0.5)).norm(), 0.05);  // measured 0.00426 (12x margin)
    // The deviation sheave as a disc of radius r; both anchors (Ground, payload) as spheres.
    ASSERT_EQ(d.cylinderRadii.size(), 1u);
    EXPECT_DOUBLE_EQ(d.cylinderRadii[0], p.r);
    EXPECT_EQ(d.sphereRadii.size(), 2u);
}

// The pendulum over a wrapped sheave: after the two spans' 2 x 19 segments, the rope on the groove
// as 19 more (sampleArc with the spans' 20 points) on the circle of radius r about the sheave,
// from the end of the horizontal span to the start of the hanging one (the rope drawn without a
// gap), in the colour of the axial force where it arrives.
TEST(VisualizerDecorations, WrappedSheaveDrawsTheRopeOnItsGroove) {
    PendulumParameters parameters;
    parameters.sheaveModel = SheaveModel::Wrapped;
    PendulumScene scene(parameters, SpanOptions{});
    const State s = scene.makeInitialState(0.5, 0);
    const ReevingSubsystem& rv = scene.reeving();
    const PendulumParameters& p = scene.parameters();
    const double reference = 2 * p.M * p.g;
    const Drawn d = draw(rv, s);
    std::vector<Drawn::Line> rope;
    for (const auto& l : d.lines)
        if (l.thickness == 4) rope.push_back(l);
    ASSERT_EQ(rope.size(), 57u);
    const Vec3 centre(p.a, 0, 0);
    double radius = 0, chain = 0;
    for (int k = 38; k < 57; ++k) {
        radius = std::max({radius, std::abs((rope[k].from - centre).norm() - p.r),
                           std::abs((rope[k].to - centre).norm() - p.r)});
        if (k > 38) chain = std::max(chain, (rope[k].from - rope[k - 1].to).norm());
    }
    const double gapIn = (rope[38].from - rope[18].to).norm();   // end of span 0 -> the arc
    const double gapOut = (rope[19].from - rope[56].to).norm();  // the arc -> start of span 1
    double drawnLength = 0;
    for (int k = 38; k < 57; ++k) drawnLength += (rope[k].to - rope[k].from).norm();
    const double l = rv.getArcLength(s, 0, 1);
    const double arrival = rv.getAxialForce(s, 0, 0, rv.getSpanMaterialRange(s, 0, 0).second);
    double colour = 0;
    for (int k = 38; k < 57; ++k) colour = std::max(colour, (rope[k].colour - mapColour(arrival / reference)).norm());
    std::printf("wrapped pendulum: wrap angle %.4f rad; arc segments off the groove circle by %.2e m, gaps %.2e "
                "(in) %.2e (out) %.2e (between) m; drawn %.6f of l = %.6f m (%.2e from the chords' %.6f); "
                "colour %.2e\n",
                rv.getWrapAngle(s, 0, 1), radius, gapIn, gapOut, chain, drawnLength, l,
                drawnLength - 38 * p.r * std::sin(l / p.r / 38), 38 * p.r * std::sin(l / p.r / 38), colour);
    EXPECT_LT(radius, 1e-14);  // measured 3.1e-16
    EXPECT_LT(gapIn, 1e-14);   // measured 0
    EXPECT_LT(gapOut, 1e-14);  // measured 5.0e-16
    EXPECT_EQ(chain, 0.0);     // consecutive segments share their points
    // 19 equal chords of the wrap angle alpha = l / r (1.604 rad): 2 19 r sin(alpha / 38), 2.9e-4 l
    // short of l.
    EXPECT_NEAR(drawnLength, 38 * p.r * std::sin(l / p.r / 38), 1e-14);  // measured 0
    EXPECT_LT(colour, 1e-12);  // measured 0: the same formula
    // The sheave is still a disc of radius r (the point-sheave pendulum draws no arc: 38 rope
    // segments, the test above).
    ASSERT_EQ(d.cylinderRadii.size(), 1u);
    EXPECT_DOUBLE_EQ(d.cylinderRadii[0], p.r);
}

TEST(VisualizerDecorations, CraneDrumShowsItsStoredRope) {
    CraneScene scene(CraneParameters{}, CraneCycle::liftTraverseLower(), SpanOptions{});
    State s = scene.makeInitialState();
    const CraneParameters& p = scene.parameters();
    const Vec3 storedRopeColour(0.45, 0.28, 0.12);
    // Drum, two flanges, n - 1 = 3 sheaves; the dead end as a sphere.
    Drawn d = draw(scene.reeving(), s);
    EXPECT_EQ(d.cylinderRadii.size(), 6u);
    EXPECT_EQ(std::count(d.cylinderRadii.begin(), d.cylinderRadii.end(), p.sheaveRadius), 3);
    EXPECT_EQ(std::count(d.cylinderRadii.begin(), d.cylinderRadii.end(), p.drumRadius), 1);
    // The helix: 16 segments per turn at rho = R + d / 2 on the first layer (d = 20.8 mm for 1.6
    // kg/m), until the drawn length reaches the rope stored: ceil(stored / (rho 2 pi / 16)) - 1 lines.
    const double dRope = std::sqrt(4 * p.rhoA / (SimTK::Pi * 0.6 * 7850.0));
    auto helixLines = [&](double stored) {
        const double step = (p.drumRadius + 0.5 * dRope) * 2 * SimTK::Pi / 16;
        return static_cast<int>(std::ceil(stored / step)) - 1;
    };
    const double stored0 = scene.ropeOnDrum(s);
    // (Wrapped drum: plus R_drum times its fall's lean, 4.8e-7 m here.)
    EXPECT_NEAR(stored0, p.ropeOnDrum, 1e-5);
    EXPECT_EQ(d.countLines(storedRopeColour), helixLines(stored0));  // 328 lines for 40 m
    // Haul in 5 m (the drum turns back): 5 m more rope drawn on the drum, still on the first layer
    // (28 turns of 20.8 mm on the 0.6 m drum hold 54.6 m).
    scene.drum().setOneQ(s, 0, scene.drum().getOneQ(s, 0) - 5.0 / p.drumRadius);
    scene.system().realize(s, Stage::Position);
    EXPECT_NEAR(scene.ropeOnDrum(s), stored0 + 5.0, 1e-12);
    d = draw(scene.reeving(), s);
    EXPECT_EQ(d.countLines(storedRopeColour), helixLines(stored0 + 5.0));
}

TEST(VisualizerDecorations, ForceScaleIsValidated) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    ReevingSubsystem rv(system, Vec3(0, -9.81, 0));
    EXPECT_THROW_MESSAGE(rv.setDecorationForceScale(-1.0), std::invalid_argument,
                         "ReevingSubsystem::setDecorationForceScale: reference force = -1 N must be finite and >= 0");
    EXPECT_THROW_MESSAGE(rv.setDecorationForceScale(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument,
                         "ReevingSubsystem::setDecorationForceScale: reference force = nan N must be finite and >= 0");
    EXPECT_THROW_MESSAGE(rv.setDecorationForceScale(std::numeric_limits<double>::infinity()), std::invalid_argument,
                         "ReevingSubsystem::setDecorationForceScale: reference force = inf N must be finite and >= 0");
    EXPECT_NO_THROW(rv.setDecorationForceScale(0.0));
    EXPECT_NO_THROW(rv.setDecorationForceScale(1e5));
}
