#pragma once
/// @file
/// Test support: a rope over a traction sheave, for the node laws' tests. A winch drum at node 0
/// (wrapped, R = 0.3 m, Driven, with stored rope), the traction sheave at node 1 (wrapped,
/// R = 0.4 m: Driven in stick, Slipping in slip), a point deviation sheave at node 2 (Sliding) and
/// the fall's anchor at node 3 (Fixed); the drum and the anchor on Ground (stationary). The drum's
/// and the sheave's surface coordinates put 0.999 of each stretch's chord in its spans (strain
/// about 1e-3: every span taut), measured on the station map's geometry. Planar or spatial (the
/// anchor and the drum out of the sheave's plane: fleet angles).

#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapStationMap.h"

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace SimbodyReevingTest {

template <int Dim>
struct TractionRopeScene {
    using Model = SimbodyReeving::RopeModel<Dim>;
    using NodeMatrix = typename Model::NodeMatrix;
    static constexpr int kTraction = 1;  ///< the traction sheave's node

    std::vector<SimbodyReeving::SpanModel<Dim>> spans;
    std::vector<SimbodyReeving::NodeWrap> wraps;
    double length = 0;  ///< L [m]
    NodeMatrix stations, stationRates;
    Eigen::VectorXd drivenS, drivenSdot;  ///< the drum's and the sheave's surface coordinates [m], rates [m/s]

    /// The kinds with the traction sheave as tractionKind.
    static std::vector<SimbodyReeving::MaterialNode> kinds(SimbodyReeving::MaterialNode tractionKind) {
        using SimbodyReeving::MaterialNode;
        return {MaterialNode::Driven, tractionKind, MaterialNode::Sliding, MaterialNode::Fixed};
    }

    explicit TractionRopeScene(SimbodyReeving::AxialDynamics axial) {
        using namespace SimbodyReeving;
        SpanOptions o;
        o.axialModes = 3;
        o.transverseModes = 2;
        o.axialDynamics = axial;
        Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Zero();
        g[1] = -9.81;
        spans.assign(3, SpanModel<Dim>(RopeProperties{0.6205, 16.5e6, 30.9}, o, g));
        wraps = {NodeWrap{0.3, 1}, NodeWrap{0.4, -1}, NodeWrap{}, NodeWrap{}};
        stations = NodeMatrix::Zero(Dim, 4);
        stationRates = NodeMatrix::Zero(Dim, 4);
        stations.col(0).template head<2>() << -2.0, -1.0;
        stations.col(1).template head<2>() << 0.0, 0.0;
        stations.col(2).template head<2>() << 3.0, 0.3;
        stations.col(3).template head<2>() << 3.4, -9.0;
        stationRates.col(1).template head<2>() << 0.1, -0.05;
        stationRates.col(2).template head<2>() << 0.02, 0.01;
        if constexpr (Dim == 3) {
            stations(2, 0) = -0.1;
            stations(2, 3) = 0.2;
            stationRates(2, 1) = 0.03;
        }
        drivenSdot = Eigen::Vector2d(0.3, 0.5);
        // The geometry at zero surface coordinates, from a model of any length.
        const Model probe(spans, 100.0, kinds(MaterialNode::Driven), wraps);
        Eigen::VectorXd Y(Dim * 4 + 2);
        for (int k = 0; k < 4; ++k) Y.template segment<Dim>(Dim * k) = stations.col(k);
        Y.tail(2).setZero();
        WrapStationMapData m;
        WrapStationMap<Dim>(probe).evaluatePositions(Y, m);
        const Eigen::VectorXd& x = m.x;
        auto at = [&](int node, int offset) { return Eigen::Matrix<double, Dim, 1>(x.template segment<Dim>(probe.nodeCoordinateOffset(node) + offset)); };
        const double c0 = (at(1, Model::wrappedArrivalOffset()) - at(0, Model::wrappedDepartureOffset())).norm();
        const double c1 = (at(2, 0) - at(1, Model::wrappedDepartureOffset())).norm();
        const double c2 = (at(3, 0) - at(2, 0)).norm();
        const double arc = x[probe.nodeCoordinateOffset(1) + Model::wrappedArcLengthOffset()];
        const int nn = probe.numNodeCoordinates();
        drivenS = Eigen::Vector2d(1.0 - x[nn], 1.0 + 0.999 * c0 - x[nn + 1]);  // s_0 = 1 m
        length = 1.0 + 0.999 * c0 + arc + 0.999 * (c1 + c2);
    }

    /// The model with the traction sheave as tractionKind (a Slipping one with kappa0, c), the
    /// drum's stored rope and the stationary nodes.
    Model build(SimbodyReeving::MaterialNode tractionKind, double kappa0 = 1.0, double angleExponent = 0.0) const {
        Model rope(spans, length, kinds(tractionKind), wraps);
        if (tractionKind == SimbodyReeving::MaterialNode::Slipping) rope.setSlipLaw(kTraction, kappa0, angleExponent);
        configure(rope);
        return rope;
    }
    /// The drum's stored rope (12 m at s_0 = 0) and the nodes on Ground.
    static void configure(Model& rope) {
        rope.setStoredRope(0, 12.0);
        rope.setStationaryNodes({true, false, false, true});
    }
    static Eigen::VectorXd modal(const Model& rope, double amplitude, double phase) {
        Eigen::VectorXd q(rope.numModalCoordinates());
        for (int i = 0; i < q.size(); ++i) q[i] = amplitude * std::sin(phase + 0.7 * i);
        return q;
    }
};

}  // namespace SimbodyReevingTest
