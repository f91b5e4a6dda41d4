#pragma once
/// @file
/// Internal to the plugin: what a node kind's bend queries receive (ReevingSubsystem::
/// getNodeMaterialInterval and getNodeBendAxis, at Stage::Position) and the pieces the kinds
/// share. Each kind answers in its unit (NodeKinds.h):
///   - bendRadius(spec): the radius R [m] the rope bends over (0 at an Anchor);
///   - heldInterval(bend): the material interval [s_a, s_b] [m] of rope on the node;
///   - bendAxis(bend): the axis in Ground the rope turns about over the node as it runs towards
///     its end (right hand; not normalized, zero where it does not bend).

#include "NodeKinds.h"

#include <utility>

namespace SimbodyReeving {
namespace detail {

/// One rope node asked how it bends the rope: the subsystem, the rope's record, the node's index
/// and the state (realized to Stage::Position).
struct NodeBend {
    const ReevingSubsystem::Guts& guts;
    const RopeRecord& rope;
    int node;
    const SimTK::State& state;
    const NodeSpec& spec() const { return rope.nodeSpec(node); }
    /// Material coordinate range [s1, s2] of span j [m] (ReevingSubsystem::getSpanMaterialRange).
    std::pair<double, double> spanRange(int span) const;
    /// Material coordinate s_k at the node [m] (ReevingSubsystem::getMaterialCoordinate).
    double materialCoordinate() const;
};

/// A sheave's interval (nodes 1..N-1): from the end of span k - 1 (where the rope arrives) to
/// the start of span k (where it leaves), one point on a point sheave, the arc on a wrapped one.
std::pair<double, double> sheaveInterval(const NodeBend& bend);

/// The unit normal of a planar rope's plane in Ground (RopeSpec::planeNormal normalized).
SimTK::Vec3 unitPlaneNormal(const RopeRecord& rope);

/// The turn between the chords of spans k - 1 and k at sheave k: their cross product [m^2] (a
/// point sheave's bend, zero if they are parallel).
SimTK::Vec3 chordTurn(const NodeBend& bend);

/// The pin axis of the node's MobilizedBody::Pin in Ground (the z axis of its outboard frame M).
SimTK::Vec3 pinAxisInGround(const NodeBend& bend);

/// The bend axis of a TurningSheave or TractionSheave: with SheaveModel::Wrapped its wrap sense
/// -sense times its pin axis (the rope gripped on its groove), else chordTurn.
SimTK::Vec3 pinnedSheaveBendAxis(const NodeBend& bend);

}  // namespace detail
}  // namespace SimbodyReeving
