// WrapStationMap: a rope's tangent points and arc lengths from the anchor points and groove
// centres that bodies carry. Its Jacobian and bias accelerations against finite differences
// (point-to-circle, open and crossed circle-to-circle spans; planar, and spatial with tilted
// grooves and fleet angles), the energy of a hook block hung in four falls swinging under a
// ceiling sheave, and falls that hang vertical from sheaves a diameter apart (with point sheaves
// they lean).
#include "SimbodyReeving/element/WrapStationMap.h"

#include "support/ExpectThrowMessage.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <variant>

using namespace SimbodyReeving;
using Eigen::Vector2d;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

SpanOptions spanOptions(int axialModes, int transverseModes) {
    SpanOptions o;
    o.axialModes = axialModes;
    o.transverseModes = transverseModes;
    return o;
}

RopeModel<2> makeRope(const RopeProperties& props, const SpanOptions& o, double L, const std::vector<NodeWrap>& wraps) {
    const Vector2d g(0.0, -kG);
    std::vector<SpanModel<2>> spans;
    for (std::size_t j = 0; j + 1 < wraps.size(); ++j) spans.emplace_back(props, o, g);
    return RopeModel<2>(std::move(spans), L, {}, wraps);
}

NodeWrap wrap(double R, int sense) {
    NodeWrap w;
    w.radius = R;
    w.wrapSense = sense;
    return w;
}

// x(t) at stations Y + Ydot t + Yddot t^2 / 2.
template <int Dim>
Eigen::VectorXd externalAt(const WrapStationMap<Dim>& map, const Eigen::VectorXd& Y, const Eigen::VectorXd& Yd,
                           const Eigen::VectorXd& Ydd, double t) {
    WrapStationMapData d;
    map.evaluate(Y + t * Yd + 0.5 * t * t * Ydd, Yd + t * Ydd, d);
    return d.x;
}

}  // namespace

// xdot = J Ydot and xddot = J Yddot + b against 4th-order central differences of x(t) along a
// quadratic path of the stations (h = 1e-3 s), for a point-to-circle rope and for open and crossed
// circle-to-circle spans. Measured agreement: 1.0e-12 (rates) and 2.2e-9 (accelerations, whose
// second differences lose digits) relative to the largest entry; bounds 1e-10 (100x) and 1e-7 (46x).
TEST(WrapStationMap, JacobianAndBiasMatchFiniteDifferences) {
    const RopeProperties props{1.0, 1e6, 0.0};
    struct Layout {
        std::vector<NodeWrap> wraps;
        std::vector<Vector2d> stations;
    };
    const std::vector<Layout> layouts = {
        {{NodeWrap{}, wrap(0.3, 1), NodeWrap{}}, {{-1.0, 0.0}, {0.2, -2.0}, {1.2, 0.1}}},
        {{NodeWrap{}, wrap(0.3, 1), wrap(0.25, 1), NodeWrap{}}, {{-1.0, 0.5}, {0.0, -2.0}, {2.0, -2.2}, {3.0, 0.4}}},
        {{NodeWrap{}, wrap(0.3, 1), wrap(0.25, -1), NodeWrap{}}, {{-1.0, 0.0}, {0.0, -2.5}, {1.5, 0.3}, {3.2, -2.0}}},
    };
    double worstRate = 0, worstAcceleration = 0;
    for (const Layout& layout : layouts) {
        const RopeModel<2> rope = makeRope(props, spanOptions(0, 0), 20.0, layout.wraps);
        const WrapStationMap map(rope);
        const int nY = map.numStationCoordinates();
        Eigen::VectorXd Y(nY), Yd(nY), Ydd(nY);
        for (std::size_t k = 0; k < layout.stations.size(); ++k) {
            Y.segment<2>(2 * k) = layout.stations[k];
            Yd.segment<2>(2 * k) = Vector2d(0.3 + 0.1 * k, -0.2 + 0.15 * k);
            Ydd.segment<2>(2 * k) = Vector2d(-0.4 + 0.2 * k, 0.5 - 0.1 * k);
        }
        WrapStationMapData d;
        map.evaluate(Y, Yd, d);
        const double h = 1e-3;
        const Eigen::VectorXd x2m = externalAt(map, Y, Yd, Ydd, -2 * h), x1m = externalAt(map, Y, Yd, Ydd, -h);
        const Eigen::VectorXd x1p = externalAt(map, Y, Yd, Ydd, h), x2p = externalAt(map, Y, Yd, Ydd, 2 * h);
        const Eigen::VectorXd rate = (x2m - 8 * x1m + 8 * x1p - x2p) / (12 * h);
        const Eigen::VectorXd acc = (-x2m + 16 * x1m - 30 * d.x + 16 * x1p - x2p) / (12 * h * h);
        worstRate = std::max(worstRate, (rate - d.xdot).cwiseAbs().maxCoeff() / rate.cwiseAbs().maxCoeff());
        const Eigen::VectorXd model = d.jacobian * Ydd + d.bias;
        worstAcceleration = std::max(worstAcceleration, (acc - model).cwiseAbs().maxCoeff() / acc.cwiseAbs().maxCoeff());
        for (int k = 0; k < rope.numNodes(); ++k) {
            if (rope.isWrapped(k)) {
                EXPECT_GT(d.wrapAngles[k], 0.5);
            }
        }
    }
    EXPECT_LT(worstRate, 1e-10);
    EXPECT_LT(worstAcceleration, 1e-7);
}

namespace {

NodeWrap wrap3(double R, int sense, const Eigen::Vector3d& axis) {
    NodeWrap w = wrap(R, sense);
    w.axis = axis.normalized();
    return w;
}

}  // namespace

// The spatial map (RopeModel<3>, each groove with its own axis): xdot = J Ydot and
// xddot = J Yddot + b against the same 4th-order differences, for a sheave tilted out of the
// rope's plane (fleet angles of several degrees at both of its tangent points), two sheaves with
// different axes, and a gripping (Driven) sheave whose material coordinate is measured about its
// tilted axis. Bounds as the planar test's (measured below).
TEST(WrapStationMap, SpatialJacobianAndBiasMatchFiniteDifferences) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const Eigen::Vector3d tilted = Eigen::Vector3d(0.12, 0.05, 1.0).normalized();
    struct Layout {
        std::vector<NodeWrap> wraps;
        std::vector<MaterialNode> kinds;
        std::vector<Eigen::Vector3d> stations;
    };
    const std::vector<Layout> layouts = {
        {{NodeWrap{}, wrap3(0.3, 1, tilted), NodeWrap{}}, {}, {{-1.0, 0.0, 0.3}, {0.2, -2.0, 0.0}, {1.2, 0.1, -0.2}}},
        {{NodeWrap{}, wrap3(0.3, 1, tilted), wrap3(0.25, 1, Eigen::Vector3d(-0.1, 0.0, 1.0)), NodeWrap{}},
         {},
         {{-1.0, 0.5, 0.2}, {0.0, -2.0, 0.0}, {2.0, -2.2, 0.1}, {3.0, 0.4, -0.3}}},
        {{NodeWrap{}, wrap3(0.3, 1, tilted), NodeWrap{}},
         {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed},
         {{-1.0, 0.0, 0.3}, {0.2, -2.0, 0.0}, {1.2, 0.1, -0.2}}},
    };
    double worstRate = 0, worstAcceleration = 0, largestFleet = 0;
    for (const Layout& layout : layouts) {
        const Eigen::Vector3d g(0.0, -kG, 0.0);
        std::vector<SpanModel<3>> spans;
        for (std::size_t j = 0; j + 1 < layout.wraps.size(); ++j) spans.emplace_back(props, spanOptions(0, 0), g);
        const RopeModel<3> rope(std::move(spans), 20.0, layout.kinds, layout.wraps);
        const WrapStationMap<3> map(rope);
        const int nY = map.numStationCoordinates();
        Eigen::VectorXd Y = Eigen::VectorXd::Zero(nY), Yd = Eigen::VectorXd::Zero(nY), Ydd = Eigen::VectorXd::Zero(nY);
        for (std::size_t k = 0; k < layout.stations.size(); ++k) {
            Y.segment<3>(3 * k) = layout.stations[k];
            Yd.segment<3>(3 * k) = Eigen::Vector3d(0.3 + 0.1 * k, -0.2 + 0.15 * k, 0.1 - 0.05 * k);
            Ydd.segment<3>(3 * k) = Eigen::Vector3d(-0.4 + 0.2 * k, 0.5 - 0.1 * k, 0.2 + 0.1 * k);
        }
        if (rope.numDrivenNodes() > 0) {  // the groove's surface coordinate
            Y[nY - 1] = 1.7;
            Yd[nY - 1] = 0.4;
            Ydd[nY - 1] = -0.3;
        }
        WrapStationMapData d;
        map.evaluate(Y, Yd, d);
        const double h = 1e-3;
        const Eigen::VectorXd x2m = externalAt(map, Y, Yd, Ydd, -2 * h), x1m = externalAt(map, Y, Yd, Ydd, -h);
        const Eigen::VectorXd x1p = externalAt(map, Y, Yd, Ydd, h), x2p = externalAt(map, Y, Yd, Ydd, 2 * h);
        const Eigen::VectorXd rate = (x2m - 8 * x1m + 8 * x1p - x2p) / (12 * h);
        const Eigen::VectorXd acc = (-x2m + 16 * x1m - 30 * d.x + 16 * x1p - x2p) / (12 * h * h);
        worstRate = std::max(worstRate, (rate - d.xdot).cwiseAbs().maxCoeff() / rate.cwiseAbs().maxCoeff());
        const Eigen::VectorXd model = d.jacobian * Ydd + d.bias;
        worstAcceleration = std::max(worstAcceleration, (acc - model).cwiseAbs().maxCoeff() / acc.cwiseAbs().maxCoeff());
        largestFleet = std::max({largestFleet, d.startFleetAngles.cwiseAbs().maxCoeff(), d.endFleetAngles.cwiseAbs().maxCoeff()});
        // The axis entries are the groove's own.
        for (int k = 0; k < rope.numNodes(); ++k)
            if (rope.isWrapped(k)) {
                EXPECT_EQ(Eigen::Vector3d(d.x.segment<3>(rope.nodeCoordinateOffset(k) + RopeModel<3>::wrappedAxisOffset())),
                          rope.grooveAxis(k));
            }
    }
    std::printf("spatial map: rates %.2e, accelerations %.2e (relative); largest fleet angle %.1f deg\n", worstRate,
                worstAcceleration, largestFleet * 180 / kPi);
    EXPECT_GT(largestFleet, 3 * kPi / 180);
    EXPECT_LT(worstRate, 1e-10);
    EXPECT_LT(worstAcceleration, 1e-7);
}

// Grooves whose axes turn with their bodies (NodeWrap::turningAxis, a sheave on a slewing or
// luffing boom; a frictionless one and one that grips the rope): each turning node's axis station a = c + n moves with its centre c while n turns
// about a fixed direction e by theta(t) = w t + w' t^2 / 2, so ndot = thetadot e x n and
// nddot = thetaddot e x n + thetadot^2 e x (e x n) exactly (a rigid body's motion: |n| stays 1).
// xdot = J Ydot and xddot = J Yddot + b against 4th-order differences of x(t) (h = 1e-3 s) for a
// turning sheave between two points and for a turning sheave next to a fixed-axis one (their
// circle-to-circle tangent), fleet angles of several degrees; and drums whose groove walks along
// their axis as rope is stored (NodeWrap::groove a WalkingGroove: the centre c + (x0 + x' Y) n
// moves with the drum's coordinate Y, and with n where the axis turns). Bounds as the fixed-axis
// test's.
TEST(WrapStationMap, TurningGrooveAxesJacobianAndBiasMatchFiniteDifferences) {
    const RopeProperties props{1.0, 1e6, 0.0};
    struct Turning {
        int node;
        Eigen::Vector3d about;  // e
        double rate, acceleration;
    };
    struct Layout {
        std::vector<NodeWrap> wraps;
        std::vector<Eigen::Vector3d> stations;
        std::vector<Turning> turning;
        std::vector<MaterialNode> kinds;
    };
    auto turningWrap = [](double R, int sense, const Eigen::Vector3d& axis) {
        NodeWrap w = wrap3(R, sense, axis);
        w.turningAxis = true;
        return w;
    };
    auto layWrap = [](NodeWrap w) {
        w.groove.unit = WalkingGroove{0.1, 0.2};
        return w;
    };
    const Eigen::Vector3d tilted = Eigen::Vector3d(0.12, 0.05, 1.0).normalized();
    const std::vector<Layout> layouts = {
        {{NodeWrap{}, turningWrap(0.3, 1, tilted), NodeWrap{}},
         {{-1.0, 0.0, 0.3}, {0.2, -2.0, 0.0}, {1.2, 0.1, -0.2}},
         {{1, Eigen::Vector3d(0.0, 1.0, 0.0), 0.7, -0.4}},
         {}},
        {{NodeWrap{}, turningWrap(0.3, 1, tilted), wrap3(0.25, 1, Eigen::Vector3d(-0.1, 0.0, 1.0)), NodeWrap{}},
         {{-1.0, 0.5, 0.2}, {0.0, -2.0, 0.0}, {2.0, -2.2, 0.1}, {3.0, 0.4, -0.3}},
         {{1, Eigen::Vector3d(0.3, 0.8, -0.2).normalized(), -0.5, 0.9}},
         {}},
        // A gripping (Driven) groove whose axis turns: its material coordinate is measured from
        // "up" projected onto the turning groove plane.
        {{NodeWrap{}, turningWrap(0.3, 1, tilted), NodeWrap{}},
         {{-1.0, 0.0, 0.3}, {0.2, -2.0, 0.0}, {1.2, 0.1, -0.2}},
         {{1, Eigen::Vector3d(0.6, 0.3, 0.2).normalized(), 0.8, -0.6}},
         {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed}},
        // Drums that spool across their width (WalkingGroove): the groove x = 0.1 + 0.2 Y
        // along the axis from the drum's centre, the axis fixed (to a hanging end) and turning (to
        // a tilted sheave).
        {{layWrap(wrap3(0.4, 1, tilted)), NodeWrap{}},
         {{0.0, 0.0, 0.0}, {0.5, -3.0, 0.4}},
         {},
         {MaterialNode::Driven, MaterialNode::Fixed}},
        {{layWrap(turningWrap(0.4, -1, tilted)), wrap3(0.25, 1, Eigen::Vector3d(-0.1, 0.0, 1.0)), NodeWrap{}},
         {{0.0, 0.0, 0.0}, {2.0, -2.2, 0.3}, {3.0, 0.4, -0.3}},
         {{0, Eigen::Vector3d(0.0, 1.0, 0.2).normalized(), 0.6, -0.5}},
         {MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Fixed}},
    };
    double worstRate = 0, worstAcceleration = 0, largestFleet = 0;
    for (const Layout& layout : layouts) {
        const Eigen::Vector3d g(0.0, -kG, 0.0);
        std::vector<SpanModel<3>> spans;
        for (std::size_t j = 0; j + 1 < layout.wraps.size(); ++j) spans.emplace_back(props, spanOptions(0, 0), g);
        const RopeModel<3> rope(std::move(spans), 20.0, layout.kinds, layout.wraps);
        ASSERT_EQ(rope.numStations(), rope.numNodes() + static_cast<int>(layout.turning.size()));
        const WrapStationMap<3> map(rope);
        const int nY = map.numStationCoordinates();
        // Stations, rates and accelerations at time t: centres on quadratic paths, axis stations
        // a = c + n(t).
        auto at = [&](double t, Eigen::VectorXd& Y, Eigen::VectorXd& Yd, Eigen::VectorXd& Ydd) {
            Y.setZero(nY);
            Yd.setZero(nY);
            Ydd.setZero(nY);
            for (std::size_t k = 0; k < layout.stations.size(); ++k) {
                const Eigen::Vector3d v(0.3 + 0.1 * k, -0.2 + 0.15 * k, 0.1 - 0.05 * k);
                const Eigen::Vector3d a(-0.4 + 0.2 * k, 0.5 - 0.1 * k, 0.2 + 0.1 * k);
                Y.segment<3>(3 * k) = layout.stations[k] + t * v + 0.5 * t * t * a;
                Yd.segment<3>(3 * k) = v + t * a;
                Ydd.segment<3>(3 * k) = a;
            }
            for (const Turning& tu : layout.turning) {
                const double theta = tu.rate * t + 0.5 * tu.acceleration * t * t, thetadot = tu.rate + tu.acceleration * t;
                const Eigen::Vector3d n = Eigen::AngleAxisd(theta, tu.about) * rope.grooveAxis(tu.node);
                const Eigen::Vector3d nd = thetadot * tu.about.cross(n);
                const Eigen::Vector3d ndd = tu.acceleration * tu.about.cross(n) + thetadot * thetadot * tu.about.cross(tu.about.cross(n));
                const int a = rope.axisStation(tu.node), c = tu.node;
                Y.segment<3>(3 * a) = Y.segment<3>(3 * c) + n;
                Yd.segment<3>(3 * a) = Yd.segment<3>(3 * c) + nd;
                Ydd.segment<3>(3 * a) = Ydd.segment<3>(3 * c) + ndd;
            }
            if (rope.numDrivenNodes() > 0) {  // the groove's surface coordinate
                Y[nY - 1] = 1.7 + 0.4 * t - 0.15 * t * t;
                Yd[nY - 1] = 0.4 - 0.3 * t;
                Ydd[nY - 1] = -0.3;
            }
        };
        auto xAt = [&](double t) {
            Eigen::VectorXd Y, Yd, Ydd;
            at(t, Y, Yd, Ydd);
            WrapStationMapData d;
            map.evaluate(Y, Yd, d);
            return d.x;
        };
        Eigen::VectorXd Y, Yd, Ydd;
        at(0.0, Y, Yd, Ydd);
        WrapStationMapData d;
        map.evaluate(Y, Yd, d);
        const double h = 1e-3;
        const Eigen::VectorXd x2m = xAt(-2 * h), x1m = xAt(-h), x1p = xAt(h), x2p = xAt(2 * h);
        const Eigen::VectorXd rate = (x2m - 8 * x1m + 8 * x1p - x2p) / (12 * h);
        const Eigen::VectorXd acc = (-x2m + 16 * x1m - 30 * d.x + 16 * x1p - x2p) / (12 * h * h);
        worstRate = std::max(worstRate, (rate - d.xdot).cwiseAbs().maxCoeff() / rate.cwiseAbs().maxCoeff());
        const Eigen::VectorXd model = d.jacobian * Ydd + d.bias;
        worstAcceleration = std::max(worstAcceleration, (acc - model).cwiseAbs().maxCoeff() / acc.cwiseAbs().maxCoeff());
        largestFleet = std::max({largestFleet, d.startFleetAngles.cwiseAbs().maxCoeff(), d.endFleetAngles.cwiseAbs().maxCoeff()});
        // A walking groove's tangent point lies x = 0.1 + 0.2 Y along the axis from the centre.
        for (int k = 0; k < rope.numNodes(); ++k) {
            if (!std::holds_alternative<WalkingGroove>(rope.groovePlacement(k).unit)) continue;
            const Eigen::Vector3d c = Y.segment<3>(3 * k), T = d.x.segment<3>(rope.nodeCoordinateOffset(k) +
                                                                                   RopeModel<3>::wrappedDepartureOffset());
            const int a = rope.axisStation(k);
            const Eigen::Vector3d n = a >= 0 ? Eigen::Vector3d(Y.segment<3>(3 * a) - c) : rope.grooveAxis(k);
            EXPECT_NEAR((T - c).dot(n), 0.1 + 0.2 * Y[nY - 1], 1e-14);
            EXPECT_NEAR(((T - c) - (T - c).dot(n) * n).norm(), rope.arc(k).radius(), 1e-14);
        }
        // The axis entries are the stations' difference, and they move.
        for (const Turning& tu : layout.turning) {
            const int o = rope.nodeCoordinateOffset(tu.node) + RopeModel<3>::wrappedAxisOffset();
            EXPECT_EQ(Eigen::Vector3d(d.x.segment<3>(o)),
                      Eigen::Vector3d(Y.segment<3>(3 * rope.axisStation(tu.node)) - Y.segment<3>(3 * tu.node)));
            EXPECT_GT(d.xdot.segment<3>(o).norm(), 0.1);
        }
    }
    std::printf("turning axes: rates %.2e, accelerations %.2e (relative); largest fleet angle %.1f deg\n", worstRate,
                worstAcceleration, largestFleet * 180 / kPi);
    EXPECT_GT(largestFleet, 3 * kPi / 180);
    EXPECT_LT(worstRate, 1e-10);
    EXPECT_LT(worstAcceleration, 1e-7);
}

// A walking groove (a drum spooling across its width): only at a wrapped Driven end node of a
// spatial rope, finite.
TEST(WrapStationMap, GrooveLaysAreForWrappedDrumsOfSpatialRopes) {
    const RopeProperties props{1.0, 1e6, 0.0};
    auto spans3 = [&]() {
        std::vector<SpanModel<3>> spans;
        for (int j = 0; j < 2; ++j) spans.emplace_back(props, spanOptions(0, 0), Eigen::Vector3d(0.0, -kG, 0.0));
        return spans;
    };
    NodeWrap drum = wrap3(0.3, 1, Eigen::Vector3d::UnitZ());
    drum.groove.unit = WalkingGroove{0.0, 0.01};
    const std::vector<MaterialNode> kinds{MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Fixed};
    const RopeModel<3> rope(spans3(), 20.0, kinds, {drum, NodeWrap{}, NodeWrap{}});
    EXPECT_EQ(std::get<WalkingGroove>(rope.groovePlacement(0).unit).dxdY, 0.01);
    EXPECT_TRUE(std::holds_alternative<CentredGroove>(rope.groovePlacement(1).unit));
    const char* where = "needs a wrapped Driven end node of a spatial rope";
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 20.0, {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed},
                                      {NodeWrap{}, drum, NodeWrap{}}),
                         std::invalid_argument, where);
    NodeWrap point;
    point.groove.unit = WalkingGroove{0.2, 0.0};
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 20.0, kinds, {point, NodeWrap{}, NodeWrap{}}), std::invalid_argument, where);
    std::vector<SpanModel<2>> planar;
    for (int j = 0; j < 2; ++j) planar.emplace_back(props, spanOptions(0, 0), Vector2d(0.0, -kG));
    NodeWrap planarDrum = wrap(0.3, 1);
    planarDrum.groove.unit = WalkingGroove{0.0, 0.01};
    EXPECT_THROW_MESSAGE(RopeModel<2>(std::move(planar), 20.0, kinds, {planarDrum, NodeWrap{}, NodeWrap{}}),
                         std::invalid_argument, where);
    drum.groove.unit = WalkingGroove{0.0, std::nan("")};
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 20.0, kinds, {drum, NodeWrap{}, NodeWrap{}}), std::invalid_argument,
                         "must be finite");
}

// A turning groove axis: for wrapped interior Sliding and Driven nodes of spatial ropes; the node
// arguments then carry the axis stations (N + 1 + i).
TEST(WrapStationMap, TurningGrooveAxesAreForWrappedInteriorNodesOfSpatialRopes) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const Eigen::Vector3d g(0.0, -kG, 0.0);
    auto spans3 = [&]() {
        std::vector<SpanModel<3>> spans;
        for (int j = 0; j < 2; ++j) spans.emplace_back(props, spanOptions(0, 0), g);
        return spans;
    };
    NodeWrap turning = wrap3(0.3, 1, Eigen::Vector3d::UnitZ());
    turning.turningAxis = true;
    NodeWrap point;
    point.turningAxis = true;
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 20.0, {}, {NodeWrap{}, point, NodeWrap{}}), std::invalid_argument,
                         "needs a wrapped node");
    EXPECT_THROW_MESSAGE(RopeModel<3>(spans3(), 20.0, {MaterialNode::Fixed, MaterialNode::Slipping, MaterialNode::Fixed},
                                      {NodeWrap{}, turning, NodeWrap{}}),
                         std::invalid_argument, "not for a slipping traction sheave");
    // A drum (a wrapped Driven end) may turn: its axis station follows the interior ones.
    const RopeModel<3> drum(spans3(), 20.0, {MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Fixed},
                            {turning, NodeWrap{}, NodeWrap{}});
    EXPECT_EQ(drum.numStations(), 4);
    EXPECT_EQ(drum.axisStation(0), 3);
    std::vector<SpanModel<2>> planar;
    for (int j = 0; j < 2; ++j) planar.emplace_back(props, spanOptions(0, 0), Vector2d(0.0, -kG));
    EXPECT_THROW_MESSAGE(RopeModel<2>(std::move(planar), 20.0, {}, {NodeWrap{}, turning, NodeWrap{}}),
                         std::invalid_argument, "needs a spatial rope");
    const RopeModel<3> rope(spans3(), 20.0, {}, {NodeWrap{}, turning, NodeWrap{}});
    EXPECT_EQ(rope.numStations(), 4);
    EXPECT_EQ(rope.axisStation(1), 3);
    EXPECT_EQ(rope.axisStation(0), -1);
    RopeData<3> data;
    Eigen::Matrix3Xd nodes(3, 3);
    nodes << -1.0, 0.0, 1.0, 0.0, -2.0, 0.0, 0.0, 0.0, 0.0;
    EXPECT_THROW_MESSAGE(rope.solveDependentCoordinates(nodes, Eigen::VectorXd(), data), std::invalid_argument,
                         "3 node positions given for 3 nodes and 1 axis stations");
}

// With every station in the plane z = 0 and every axis +z, the spatial map is the planar one: x,
// J and b equal the planar map's (z rows and columns aside) to round-off (measured 0), and the
// fleet angles are 0.
TEST(WrapStationMap, SpatialMapInThePlaneIsThePlanarMap) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const std::vector<NodeWrap> wraps{NodeWrap{}, wrap(0.3, 1), wrap(0.25, -1), NodeWrap{}};
    const std::vector<MaterialNode> kinds{MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Sliding,
                                          MaterialNode::Fixed};
    const std::vector<Vector2d> stations{{-1.0, 0.0}, {0.0, -2.5}, {1.5, 0.3}, {3.2, -2.0}};
    std::vector<SpanModel<2>> spans2;
    std::vector<SpanModel<3>> spans3;
    for (int j = 0; j < 3; ++j) {
        spans2.emplace_back(props, spanOptions(0, 0), Vector2d(0.0, -kG));
        spans3.emplace_back(props, spanOptions(0, 0), Eigen::Vector3d(0.0, -kG, 0.0));
    }
    const RopeModel<2> rope2(std::move(spans2), 20.0, kinds, wraps);
    const RopeModel<3> rope3(std::move(spans3), 20.0, kinds, wraps);
    Eigen::VectorXd Y2(9), Yd2(9), Y3 = Eigen::VectorXd::Zero(13), Yd3 = Eigen::VectorXd::Zero(13);
    for (int k = 0; k < 4; ++k) {
        Y2.segment<2>(2 * k) = stations[k];
        Yd2.segment<2>(2 * k) = Vector2d(0.3 + 0.1 * k, -0.2 + 0.15 * k);
        Y3.segment<2>(3 * k) = Y2.segment<2>(2 * k);
        Yd3.segment<2>(3 * k) = Yd2.segment<2>(2 * k);
    }
    Y2[8] = Y3[12] = 0.9;
    Yd2[8] = Yd3[12] = -0.2;
    WrapStationMapData d2, d3;
    WrapStationMap<2>(rope2).evaluate(Y2, Yd2, d2);
    WrapStationMap<3>(rope3).evaluate(Y3, Yd3, d3);
    // Row r of the planar x is row rowOf(r) of the spatial one; station column c is column colOf(c).
    auto rowOf = [&](int r) {
        for (int k = 0; k < 4; ++k) {
            const int o2 = rope2.nodeCoordinateOffset(k), o3 = rope3.nodeCoordinateOffset(k);
            const int size = rope2.isWrapped(k) ? RopeModel<2>::wrappedBlockSize() : 2;
            if (r < o2 || r >= o2 + size) continue;
            const int i = r - o2;
            if (!rope2.isWrapped(k)) return o3 + i;
            if (i == RopeModel<2>::wrappedArcLengthOffset()) return o3 + RopeModel<3>::wrappedArcLengthOffset();
            return o3 + 3 * (i / 2) + i % 2;  // c, T_in, T_out: x and y of each
        }
        return rope3.numNodeCoordinates() + (r - rope2.numNodeCoordinates());
    };
    auto colOf = [](int c) { return c < 8 ? 3 * (c / 2) + c % 2 : 12; };
    double worst = 0;
    for (int r = 0; r < rope2.numExternalCoordinates(); ++r) {
        worst = std::max({worst, std::abs(d2.x[r] - d3.x[rowOf(r)]), std::abs(d2.bias[r] - d3.bias[rowOf(r)])});
        for (int c = 0; c < 9; ++c) worst = std::max(worst, std::abs(d2.jacobian(r, c) - d3.jacobian(rowOf(r), colOf(c))));
    }
    std::printf("spatial map in the plane vs planar map: %.2e\n", worst);
    EXPECT_LT(worst, 1e-14);
    EXPECT_EQ(d3.startFleetAngles.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(d3.endFleetAngles.cwiseAbs().maxCoeff(), 0.0);
}

namespace {

// A hook block hung in four falls: anchor (-R, 0) -> block sheave 1 (centre q) -> ceiling sheave
// (2R, 0) -> block sheave 2 (centre q + (4R, 0)) -> anchor (5R, 0); the block translates (no
// rotation), mass M.
struct FourFallBlock {
    RopeModel<2> rope;
    WrapStationMap<2> map;
    double R, M;
    RopeData<2> data;
    WrapStationMapData mapData;

    FourFallBlock(const RopeProperties& props, const SpanOptions& o, double L, double R, double M, bool wrapped)
        : rope(makeRope(props, o, L,
                        wrapped ? std::vector<NodeWrap>{NodeWrap{}, wrap(R, 1), wrap(R, -1), wrap(R, 1), NodeWrap{}}
                                : std::vector<NodeWrap>(5))),
          map(rope), R(R), M(M) {}
    FourFallBlock(const FourFallBlock&) = delete;

    Eigen::VectorXd stations(const Vector2d& q) const {
        Eigen::VectorXd Y(10);
        Y << -R, 0.0, q[0], q[1], 2 * R, 0.0, q[0] + 4 * R, q[1], 5 * R, 0.0;
        return Y;
    }
    Eigen::Matrix<double, 10, 2> stationJacobian() const {
        Eigen::Matrix<double, 10, 2> J = Eigen::Matrix<double, 10, 2>::Zero();
        J.block<2, 2>(2, 0).setIdentity();
        J.block<2, 2>(6, 0).setIdentity();
        return J;
    }
    // The block's acceleration and the rope's modal accelerations; the total energy.
    void evaluate(const Vector2d& q, const Vector2d& qd, const Eigen::VectorXd& qm, const Eigen::VectorXd& qmd,
                  Vector2d& qdd, Eigen::VectorXd& qmdd, double& energy) {
        const auto Jq = stationJacobian();
        map.evaluate(stations(q), Jq * qd, mapData);
        rope.computeDynamicsFromExternal(mapData.x, mapData.xdot, qm, qmd, data);
        Eigen::MatrixXd SY;
        Eigen::VectorXd hY;
        map.stationNodeMass(mapData, data, SY);
        map.stationNodeForce(mapData, data, hY);
        const Vector2d g(0.0, -kG);
        const Eigen::Matrix2d A = M * Eigen::Matrix2d::Identity() + Jq.transpose() * SY * Jq;
        qdd = A.ldlt().solve(M * g + Jq.transpose() * hY);
        const Eigen::VectorXd xdd = mapData.jacobian * (Jq * qdd) + mapData.bias;
        rope.modalAccelerations(data, xdd, qmdd);
        energy = data.kineticEnergy + data.strainEnergy + data.gravityEnergy + 0.5 * M * qd.squaredNorm() - M * g.dot(q);
    }
    // The block's static position (no modal coordinates): the vertical and horizontal balance
    // M g + J^T h_Y = 0 by Newton's method on q with a central-difference Jacobian.
    Vector2d staticPosition(Vector2d q) {
        auto residual = [&](const Vector2d& p) {
            Vector2d a;
            Eigen::VectorXd none, qmdd;
            double e = 0;
            evaluate(p, Vector2d::Zero(), none, none, a, qmdd, e);
            Eigen::VectorXd hY;
            map.stationNodeForce(mapData, data, hY);
            return Vector2d(Vector2d(0.0, -M * kG) + stationJacobian().transpose() * hY);
        };
        for (int it = 0; it < 30; ++it) {
            const Vector2d r = residual(q);
            if (r.norm() < 1e-11 * M * kG) break;
            Eigen::Matrix2d K;
            for (int i = 0; i < 2; ++i) {
                const double e = 1e-7;
                K.col(i) = (residual(q + e * Vector2d::Unit(i)) - residual(q - e * Vector2d::Unit(i))) / (2 * e);
            }
            q -= K.lu().solve(r);
        }
        residual(q);  // leave the data at q
        return q;
    }
};

}  // namespace

// Falls from sheaves a diameter apart hang vertical: the block's static position puts every fall
// (all four spans) at |u_x| < 1e-9 (measured 1.8e-17 rad with wrapped sheaves), and every fall's
// force is the block's share (M g + the rope weight it carries) / 4: the two arcs on its sheaves
// and, with linear spans (no axial modes: uniform strain), half of each fall,
// F = EA eps lambda = (M g + rhoA g (2 pi R + 4 l / 2)) / 4 (measured 2.3e-13 relative, the
// Newton's and the strain's round-off; bound 1e-11, 44x).
// With point sheaves at the same centres the falls lean: the outer ones by atan(R / h), the inner
// ones (block sheave to ceiling sheave, 2R apart) by atan(2R / h), 0.197 rad here.
TEST(WrapStationMap, FallsFromSheavesADiameterApartHangVertical) {
    const RopeProperties props{2.0, 5e6, 0.0, false};
    const double R = 0.3, M = 500.0;
    FourFallBlock wrapped(props, spanOptions(0, 0), 4 * 3.0 + 3 * kPi * R, R, M, true);
    const Vector2d q = wrapped.staticPosition(Vector2d(0.02, -3.0));
    double lean = 0;
    for (const SpanTangency& t : wrapped.mapData.tangencies) lean = std::max(lean, std::abs(t.direction[0]));
    EXPECT_LT(lean, 1e-9);
    EXPECT_NEAR(q[0], 0.0, 1e-9);
    const double h = -q[1];
    for (int j = 0; j < 4; ++j) {
        EndStrain<2> e;
        const Eigen::VectorXd& qj = wrapped.data.spanCoordinates(j);
        wrapped.rope.span(j).endStrain(qj, Eigen::VectorXd::Zero(qj.size()), SpanEnd::First, e);
        // The force the fall carries: EA eps (the Green strain's conjugate, per unstretched length)
        // times the stretch lambda = sqrt(1 + 2 eps).
        const double P = props.axialStiffness * e.strain * std::sqrt(1 + 2 * e.strain);
        const double material = qj[wrapped.rope.span(j).s2Index()] - qj[wrapped.rope.span(j).s1Index()];
        const double expected = (M * kG + props.massPerLength * kG * (2 * kPi * R + 2 * material)) / 4;
        EXPECT_NEAR(P, expected, 1e-11 * expected) << "fall " << j;
        EXPECT_NEAR(wrapped.mapData.tangencies[j].length, h, 1e-3 * h) << "fall " << j;
    }

    FourFallBlock point(props, spanOptions(0, 0), 4 * 3.0, R, M, false);
    point.staticPosition(Vector2d(0.02, -3.0));
    double pointLean = 0;
    for (const SpanTangency& t : point.mapData.tangencies)
        pointLean = std::max(pointLean, std::asin(std::abs(t.direction[0])));
    EXPECT_NEAR(pointLean, std::atan(2 * R / h), 0.01);
}

// The block swinging and bouncing in its four falls (transverse modes on, the rope's arcs, tangent
// points and wrap angles moving with it, circle-to-circle spans): T + U of block and rope is
// conserved up to RK4's error, which falls by about 2^5 when the step halves. Measured drift over
// 1 s relative to the initial kinetic energy: 2.1e-7 at h = 1e-3 s, 6.6e-9 at h = 5e-4 s (ratio
// 31.9); bound 2e-7 at the fine step (30x) and a ratio above 8.
TEST(WrapStationMap, HookBlockInFourFallsConservesEnergy) {
    const RopeProperties props{2.0, 5e6, 0.0, false};
    const double R = 0.3, M = 500.0;
    auto drift = [&](double h) {
        FourFallBlock sys(props, spanOptions(0, 1), 4 * 3.0 * (1 - 2e-4) + 3 * kPi * R, R, M, true);
        const int nm = sys.rope.numModalCoordinates();
        Vector2d q(0.05, -3.0), qd(0.6, 0.05);
        Eigen::VectorXd qm = Eigen::VectorXd::Zero(nm), qmd = Eigen::VectorXd::Zero(nm);
        struct D {
            Vector2d q, qd;
            Eigen::VectorXd qm, qmd;
        };
        auto deriv = [&](const D& s, D& d) {
            double e = 0;
            d.q = s.qd;
            d.qm = s.qmd;
            sys.evaluate(s.q, s.qd, s.qm, s.qmd, d.qd, d.qmd, e);
        };
        auto energy = [&](const D& s) {
            Vector2d a;
            Eigen::VectorXd b;
            double e = 0;
            sys.evaluate(s.q, s.qd, s.qm, s.qmd, a, b, e);
            return e;
        };
        D y{q, qd, qm, qmd};
        const double e0 = energy(y), kinetic0 = 0.5 * M * qd.squaredNorm();
        double worst = 0;
        auto add = [](const D& s, const D& d, double f) { return D{s.q + f * d.q, s.qd + f * d.qd, s.qm + f * d.qm, s.qmd + f * d.qmd}; };
        for (int i = 0; i < static_cast<int>(std::lround(1.0 / h)); ++i) {
            D k1, k2, k3, k4;
            deriv(y, k1);
            deriv(add(y, k1, 0.5 * h), k2);
            deriv(add(y, k2, 0.5 * h), k3);
            deriv(add(y, k3, h), k4);
            y.q += h / 6 * (k1.q + 2 * k2.q + 2 * k3.q + k4.q);
            y.qd += h / 6 * (k1.qd + 2 * k2.qd + 2 * k3.qd + k4.qd);
            y.qm += h / 6 * (k1.qm + 2 * k2.qm + 2 * k3.qm + k4.qm);
            y.qmd += h / 6 * (k1.qmd + 2 * k2.qmd + 2 * k3.qmd + k4.qmd);
            worst = std::max(worst, std::abs(energy(y) - e0));
        }
        return worst / kinetic0;
    };
    const double coarse = drift(1e-3), fine = drift(5e-4);
    EXPECT_LT(fine, 2e-7);
    EXPECT_GT(coarse / fine, 8.0);
}

TEST(WrapStationMap, RejectsBadStationsAndImpossibleTangents) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const RopeModel<2> rope = makeRope(props, spanOptions(0, 0), 10.0, {NodeWrap{}, wrap(0.5, 1), NodeWrap{}});
    const WrapStationMap map(rope);
    WrapStationMapData d;
    EXPECT_THROW_MESSAGE(map.evaluate(Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(6), d), std::invalid_argument,
                         "4 stations and 6 rates given for 6 station coordinates");
    Eigen::VectorXd Y(6);
    Y << 0.2, 0.1, 0.0, 0.0, 3.0, 0.0;  // the start anchor inside the groove circle
    EXPECT_THROW_MESSAGE(map.evaluate(Y, Eigen::VectorXd::Zero(6), d), std::domain_error, "span 0 (nodes 0 and 1)");
    Y << -1.0, 0.0, 0.0, -2.0, 1.0, 0.0;  // down, under and up: counter-clockwise, against the sense -1
    const RopeModel<2> clockwise = makeRope(props, spanOptions(0, 0), 10.0, {NodeWrap{}, wrap(0.5, -1), NodeWrap{}});
    EXPECT_THROW_MESSAGE(WrapStationMap<2>(clockwise).evaluate(Y, Eigen::VectorXd::Zero(6), d), std::domain_error,
                         "node 1: the rope's path turns counter-clockwise about the groove's axis there (from node 0 "
                         "past the groove's centre to node 2) but its wrap sense is -1");
    Y[0] = NAN;
    EXPECT_THROW_MESSAGE(map.evaluate(Y, Eigen::VectorXd::Zero(6), d), std::invalid_argument, "must be finite");
}

// A planar rope with wrapped nodes evaluated from its stations through RopeModel's node forms
// (nodes = anchor points and groove centres) gives the map's S_Y, h_Y and modal accelerations,
// with S formed or not (multiplyByNodeMass, modalAccelerationsFromLastProduct), the dense reduced
// equations' Schur complement, and the potential energy of spans and arcs. Round-off only: bounds
// 1e-10 relative to each quantity's size.
TEST(WrapStationMap, RopeEvaluatedFromItsStationsMatchesTheMap) {
    const RopeProperties props{2.0, 5e6, 0.0, false};
    const double R = 0.3, M = 500.0;
    FourFallBlock sys(props, spanOptions(0, 1), 4 * 3.0 * (1 - 2e-4) + 3 * kPi * R, R, M, true);
    const RopeModel<2>& rope = sys.rope;
    const int nm = rope.numModalCoordinates();
    const Vector2d q(0.05, -3.0), qd(0.6, 0.05);
    Eigen::VectorXd qm(nm), qmd(nm);
    for (int i = 0; i < nm; ++i) {
        qm[i] = 1e-3 * std::sin(1.0 + i);
        qmd[i] = 0.02 * std::cos(2.0 + i);
    }
    const Eigen::VectorXd Y = sys.stations(q), Yd = sys.stationJacobian() * qd;
    Eigen::VectorXd Ydd(10);
    for (int i = 0; i < 10; ++i) Ydd[i] = 0.3 * std::sin(0.7 * i);
    // The explicit route.
    WrapStationMapData m;
    sys.map.evaluate(Y, Yd, m);
    RopeData<2> a;
    rope.computeDynamicsFromExternal(m.x, m.xdot, qm, qmd, a);
    Eigen::MatrixXd SY;
    Eigen::VectorXd hY, qmddA;
    sys.map.stationNodeMass(m, a, SY);
    sys.map.stationNodeForce(m, a, hY);
    rope.modalAccelerations(a, Eigen::VectorXd(m.jacobian * Ydd + m.bias), qmddA);
    // The node forms, with S formed and not.
    Eigen::Matrix<double, 2, Eigen::Dynamic> nodes(2, 5), vel(2, 5);
    for (int k = 0; k < 5; ++k) {
        nodes.col(k) = Y.segment<2>(2 * k);
        vel.col(k) = Yd.segment<2>(2 * k);
    }
    auto near = [](const auto& x, const auto& y) { return (x - y).norm() <= 1e-10 * std::max(1.0, y.norm()); };
    for (bool formed : {true, false}) {
        RopeData<2> b;
        b.formNodeMass = formed;
        rope.solveDependentCoordinates(nodes, qm, b);
        rope.computeDynamics(nodes, vel, qm, qmd, b);
        rope.computeDynamics(nodes, vel, qm, qmd, b);  // a repeated evaluation returns the same
        EXPECT_TRUE(near(b.nodeForce, hY)) << "formed " << formed;
        Eigen::MatrixXd SX;
        rope.multiplyByNodeMass(b, Eigen::MatrixXd::Identity(10, 10), SX);
        EXPECT_TRUE(near(SX, SY)) << "formed " << formed;
        if (formed) {
            EXPECT_TRUE(near(b.nodeMass, SY));
        }
        Eigen::VectorXd qmdd;
        rope.modalAccelerations(b, Ydd, qmdd);
        EXPECT_TRUE(near(qmdd, qmddA)) << "formed " << formed;
        rope.multiplyByNodeMass(b, Ydd, SX);
        rope.modalAccelerationsFromLastProduct(b, Eigen::VectorXd::Ones(1), qmdd);
        EXPECT_TRUE(near(qmdd, qmddA)) << "formed " << formed;
        // Dense reduced equations at the stations: S_Y is their Schur complement on the modes.
        const Eigen::MatrixXd& Mbar = b.reducedMass();
        const Eigen::MatrixXd schur = Mbar.topLeftCorner(10, 10) - Mbar.topRightCorner(10, nm) *
                                      Mbar.bottomRightCorner(nm, nm).ldlt().solve(Mbar.bottomLeftCorner(nm, 10));
        EXPECT_TRUE(near(schur, SY)) << "formed " << formed;
        // Potential energy from the stations: spans (spanCoordinates) and arcs.
        double u = rope.arcGravityEnergy(nodes, b);
        for (int j = 0; j < rope.numSpans(); ++j) {
            Eigen::VectorXd qj;
            rope.spanCoordinates(j, nodes, qm, b, qj);
            SpanData<2> d;
            rope.span(j).evaluate(qj, Eigen::VectorXd::Zero(qj.size()), d);
            u += d.potentialEnergy();
        }
        EXPECT_NEAR(u, a.strainEnergy + a.gravityEnergy, 1e-10 * std::abs(a.gravityEnergy));
    }
}

namespace {

// A sheave that grips the rope (a Driven node, wrap sense -1: the rope runs up its left side, over
// the top and down its right side), centre c, radius R, between two anchors below it.
RopeModel<2> makeGrippingSheaveRope(double R, const Vector2d& g = Vector2d(0.0, -kG)) {
    const RopeProperties props{1.0, 1e6, 0.0};
    std::vector<SpanModel<2>> spans;
    for (int j = 0; j < 2; ++j) spans.emplace_back(props, spanOptions(0, 0), g);
    return RopeModel<2>(std::move(spans), 20.0, {MaterialNode::Fixed, MaterialNode::Driven, MaterialNode::Fixed},
                        {NodeWrap{}, wrap(R, -1), NodeWrap{}});
}

}  // namespace

// At a wrapped Driven node the rope arrives on the groove at s_in = Y_s + sigma R phi_in (phi_in
// from "up", against gravity) and leaves at s_in + l = Y_s + sigma R phi_out: with both anchors
// straight below the tangent points (phi_in = pi/2, phi_out = -pi/2, sigma = -1) s_in = Y_s - R pi/2
// and s_out = Y_s + R pi/2, i.e. Y_s is the material coordinate at the groove's top (measured
// exact, 0 m; bound 1e-13 m). J and b, with the stations and Y_s moving, against 4th-order
// central differences as above (measured 5.3e-13 and 4.5e-10 relative; bounds 1e-10 (190x) and
// 1e-7 (220x)).
TEST(WrapStationMap, GrippingSheaveCarriesTheMaterialCoordinateAroundItsGroove) {
    const double R = 0.4, Ys = 7.0;
    const RopeModel<2> rope = makeGrippingSheaveRope(R);
    const WrapStationMap map(rope);
    ASSERT_EQ(map.numStationCoordinates(), 7);
    Eigen::VectorXd Y(7), Yd = Eigen::VectorXd::Zero(7);
    Y << -R, -3.0, 0.0, 0.0, R, -2.0, Ys;
    WrapStationMapData d;
    map.evaluate(Y, Yd, d);
    const int row = rope.numNodeCoordinates() + rope.drivenIndex(1);
    const double arc = d.x[rope.nodeCoordinateOffset(1) + RopeModel<2>::wrappedArcLengthOffset()];
    EXPECT_NEAR(d.arrivalAngles[1], kPi / 2, 1e-13);
    EXPECT_NEAR(d.x[row], Ys - R * kPi / 2, 1e-13);
    EXPECT_NEAR(d.x[row] + arc, Ys + R * kPi / 2, 1e-13);

    // Moving stations and a turning sheave (Y_s changing).
    Y << -1.0, -2.5, 0.1, -0.05, 1.3, -1.8, Ys;
    Eigen::VectorXd Ydd(7);
    Yd << 0.3, -0.2, 0.05, 0.1, -0.4, 0.25, 0.8;
    Ydd << -0.4, 0.5, 0.2, -0.3, 0.1, 0.2, -0.6;
    map.evaluate(Y, Yd, d);
    const double h = 1e-3;
    const Eigen::VectorXd x2m = externalAt(map, Y, Yd, Ydd, -2 * h), x1m = externalAt(map, Y, Yd, Ydd, -h);
    const Eigen::VectorXd x1p = externalAt(map, Y, Yd, Ydd, h), x2p = externalAt(map, Y, Yd, Ydd, 2 * h);
    const Eigen::VectorXd rate = (x2m - 8 * x1m + 8 * x1p - x2p) / (12 * h);
    const Eigen::VectorXd acc = (-x2m + 16 * x1m - 30 * d.x + 16 * x1p - x2p) / (12 * h * h);
    EXPECT_LT((rate - d.xdot).cwiseAbs().maxCoeff() / rate.cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((acc - (d.jacobian * Ydd + d.bias)).cwiseAbs().maxCoeff() / acc.cwiseAbs().maxCoeff(), 1e-7);
}

// Without gravity "up" is +y: the same sheave with both anchors straight below its tangent points
// (phi_in = pi/2, phi_out = -pi/2 from +y, sigma = -1) carries s_in = Y_s - R pi/2 and
// s_out = Y_s + R pi/2 as under gravity -y; under gravity -x, the picture turned a quarter turn
// clockwise with it, "up" is +x and the same s_in follows. Measured exact (0 m); bound 1e-13 m. An
// "up" of +x without gravity would move s_in by R pi/2 = 0.63 m.
TEST(WrapStationMap, GrippingSheaveWithoutGravityMeasuresItsAngleFromPlusY) {
    const double R = 0.4, Ys = 7.0;
    WrapStationMapData d;
    Eigen::VectorXd Y(7), Yd = Eigen::VectorXd::Zero(7);
    {
        const RopeModel<2> rope = makeGrippingSheaveRope(R, Vector2d::Zero());
        const WrapStationMap map(rope);
        Y << -R, -3.0, 0.0, 0.0, R, -2.0, Ys;
        map.evaluate(Y, Yd, d);
        const int row = rope.numNodeCoordinates() + rope.drivenIndex(1);
        const double arc = d.x[rope.nodeCoordinateOffset(1) + RopeModel<2>::wrappedArcLengthOffset()];
        EXPECT_NEAR(d.arrivalAngles[1], kPi / 2, 1e-13);
        EXPECT_NEAR(d.x[row], Ys - R * kPi / 2, 1e-13);
        EXPECT_NEAR(d.x[row] + arc, Ys + R * kPi / 2, 1e-13);
    }
    {
        // Gravity along -x, "up" +x: the anchors at (-3, R) and (-2, -R), the rope arriving at the
        // tangent point (0, R), a quarter turn counter-clockwise from +x.
        const RopeModel<2> rope = makeGrippingSheaveRope(R, Vector2d(-kG, 0.0));
        const WrapStationMap map(rope);
        Y << -3.0, R, 0.0, 0.0, -2.0, -R, Ys;
        WrapStationMapData e;
        map.evaluate(Y, Yd, e);
        const int row = rope.numNodeCoordinates() + rope.drivenIndex(1);
        EXPECT_NEAR(e.arrivalAngles[1], kPi / 2, 1e-13);
        EXPECT_NEAR(e.x[row], Ys - R * kPi / 2, 1e-13);
    }
}

// phi_in stays continuous where the arriving tangent point passes the groove's bottom (phi_in = pi,
// where atan2 jumps by 2 pi): the first anchor rises past the sheave's right in 200 steps, T_in
// moving from 2.75 to 3.45 rad; s_in changes by at most R times the step's turn (measured largest
// step 1.4e-3 m, against the 2 pi R = 2.5 m of a branch jump; bound 0.05 m).
TEST(WrapStationMap, GrippingSheaveArrivalAngleIsContinuousPastTheGroovesBottom) {
    const double R = 0.4;
    const RopeModel<2> rope = makeGrippingSheaveRope(R);
    const WrapStationMap map(rope);
    WrapStationMapData d;
    Eigen::VectorXd Y(7);
    const int row = rope.numNodeCoordinates() + rope.drivenIndex(1);
    double previous = 0, largestStep = 0, firstAngle = 0;
    for (int i = 0; i <= 200; ++i) {
        // The anchor on a circle of radius 3 about the centre, from -30 to +10 degrees (below
        // right to right): the rope runs left into the groove's bottom and wraps it clockwise up
        // its left side to the other anchor, up left.
        const double a = (-30.0 + 40.0 * i / 200.0) * kPi / 180.0;
        Y << 3.0 * std::cos(a), 3.0 * std::sin(a), 0.0, 0.0, -2.0, 3.0, 7.0;
        map.evaluatePositions(Y, d);
        if (i == 0) firstAngle = d.arrivalAngles[1];
        if (i > 0) largestStep = std::max(largestStep, std::abs(d.x[row] - previous));
        previous = d.x[row];
    }
    EXPECT_LT(largestStep, 0.05);
    EXPECT_GT(std::abs(d.arrivalAngles[1] - firstAngle), 0.5);  // it did move past the bottom
    EXPECT_GT(std::abs(d.arrivalAngles[1]), kPi);                // continued past pi, not wrapped
}

namespace {

// Drum (wrapped, Driven) at the start -> wrapped deviation sheave -> drum (wrapped, Driven) at the
// end: both ends of the rope leave their drums at tangent points.
RopeModel<2> makeTwoDrumRope(double R) {
    const RopeProperties props{1.0, 1e6, 0.0};
    const Vector2d g(0.0, -kG);
    std::vector<SpanModel<2>> spans;
    for (int j = 0; j < 2; ++j) spans.emplace_back(props, spanOptions(1, 1), g);
    return RopeModel<2>(std::move(spans), 20.0, {MaterialNode::Driven, MaterialNode::Sliding, MaterialNode::Driven},
                        {wrap(R, 1), wrap(0.3, -1), wrap(0.5 * R, 1)});
}

}  // namespace

// A winch drum wrapped (a Driven end node with a NodeWrap): the rope leaves it at the tangent point
// of the span to its neighbour, T_in = T_out there, no arc (the rope beyond the tangent point is the
// drum's stored rope), and the material coordinate at the tangent point is Y_s + sigma R phi. With
// the rope hanging straight down from the drum's left side (sigma = +1: it unwinds
// counter-clockwise), phi = pi / 2 from "up" and s_0 = Y_s + R pi / 2. J and b against 4th-order
// central differences along a quadratic path of all stations (drums moving and turning): measured
// 2.6e-13 and 2.1e-9 relative, bounds 1e-10 and 1e-7 as the sheaves'.
TEST(WrapStationMap, WrappedDrumsLeaveTheRopeAtTheirTangentPoints) {
    const double R = 0.4;
    const RopeModel<2> rope = makeTwoDrumRope(R);
    const WrapStationMap map(rope);
    ASSERT_EQ(map.numStationCoordinates(), 8);
    // Drum 0 at (0, 0), the sheave (r 0.3) at (-R - 0.3, -4): the rope from the drum's left side
    // straight down to the sheave's right side, under it and straight up to drum 2's right side.
    Eigen::VectorXd Y(8), Yd = Eigen::VectorXd::Zero(8);
    Y << 0.0, 0.0, -R - 0.3, -4.0, -R - 0.6 - 0.5 * R, 0.0, 7.0, 2.0;
    WrapStationMapData d;
    map.evaluate(Y, Yd, d);
    const int o0 = rope.nodeCoordinateOffset(0), o2 = rope.nodeCoordinateOffset(2);
    using RM = RopeModel<2>;
    // Drum 0: tangent point (-R, 0), the same as T_in and T_out; no arc.
    EXPECT_NEAR(d.x[o0 + RM::wrappedDepartureOffset()], -R, 1e-13);
    EXPECT_NEAR(d.x[o0 + RM::wrappedDepartureOffset() + 1], 0.0, 1e-13);
    EXPECT_EQ(d.x.segment<2>(o0 + RM::wrappedArrivalOffset()), d.x.segment<2>(o0 + RM::wrappedDepartureOffset()));
    EXPECT_EQ(d.x[o0 + RM::wrappedArcLengthOffset()], 0.0);
    EXPECT_EQ(d.x.segment<2>(o2 + RM::wrappedArrivalOffset()), d.x.segment<2>(o2 + RM::wrappedDepartureOffset()));
    EXPECT_EQ(d.x[o2 + RM::wrappedArcLengthOffset()], 0.0);
    const int s0 = rope.numNodeCoordinates() + rope.drivenIndex(0);
    EXPECT_NEAR(d.x[s0], 7.0 + R * kPi / 2, 1e-13);  // phi = +pi/2 (left of "up"), sigma = +1

    Eigen::VectorXd Ydd(8);
    Yd << 0.3, -0.2, 0.05, 0.1, -0.4, 0.25, 0.8, -0.5;
    Ydd << -0.4, 0.5, 0.2, -0.3, 0.1, 0.2, -0.6, 0.3;
    map.evaluate(Y, Yd, d);
    const double h = 1e-3;
    const Eigen::VectorXd x2m = externalAt(map, Y, Yd, Ydd, -2 * h), x1m = externalAt(map, Y, Yd, Ydd, -h);
    const Eigen::VectorXd x1p = externalAt(map, Y, Yd, Ydd, h), x2p = externalAt(map, Y, Yd, Ydd, 2 * h);
    const Eigen::VectorXd rate = (x2m - 8 * x1m + 8 * x1p - x2p) / (12 * h);
    const Eigen::VectorXd acc = (-x2m + 16 * x1m - 30 * d.x + 16 * x1p - x2p) / (12 * h * h);
    const double rateError = (rate - d.xdot).cwiseAbs().maxCoeff() / rate.cwiseAbs().maxCoeff();
    const double accError = (acc - (d.jacobian * Ydd + d.bias)).cwiseAbs().maxCoeff() / acc.cwiseAbs().maxCoeff();
    std::printf("wrapped drums: rates %.1e, accelerations %.1e relative\n", rateError, accError);
    EXPECT_LT(rateError, 1e-10);
    EXPECT_LT(accError, 1e-7);
}
