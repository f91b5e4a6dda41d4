#pragma once
/// @file
/// Internal to the plugin: what a node kind's draw(drawing) receives (the Visualizer decorations of
/// ReevingSubsystem, drawn at Stage::Position) and the pieces the kinds share.

#include "NodeKinds.h"

namespace SimbodyReeving {
namespace detail {

/// One rope node to draw: its rope's record, spec and cache (node positions), its index, the
/// subsystem's public queries (stored rope), the drawn rope diameter [m] and where to append.
struct NodeDrawing {
    const SimTK::State& state;
    const ReevingSubsystem& reeving;
    const RopeRecord& rope;
    const RopeCache& cache;
    int node;
    double ropeDiameter;
    SimTK::Array_<SimTK::DecorativeGeometry>& geometry;
    const NodeSpec& spec() const { return rope.nodeSpec(node); }
    SimTK::Vec3 centre() const { return toSimTK(Eigen::Vector3d(cache.nodes3.col(node))); }
};

/// A unit vector perpendicular to the unit vector u.
SimTK::Vec3 perpendicularTo(const SimTK::Vec3& u);
/// The pin axis of a node's Pin body in Ground, and a body-fixed radial direction.
std::pair<SimTK::Vec3, SimTK::Vec3> pinAxes(const SimTK::State& s, const SimTK::MobilizedBody& pin);
/// A sheave's disc (radius R, width 0.6 R) about axis at the node's centre; with spokes, a bar
/// along radial on both faces that turns with the pin.
void drawSheaveDisc(const NodeDrawing& drawing, const SimTK::Vec3& axis, const SimTK::Vec3& radial, bool spokes);

}  // namespace detail
}  // namespace SimbodyReeving
