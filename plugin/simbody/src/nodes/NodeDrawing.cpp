// What the node kinds' drawings share.

#include "NodeDrawing.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

using SimTK::Vec3;

Vec3 perpendicularTo(const Vec3& u) {
    const Vec3 trial = std::abs(u[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return (trial - SimTK::dot(trial, u) * u).normalize();
}

std::pair<Vec3, Vec3> pinAxes(const SimTK::State& s, const SimTK::MobilizedBody& pin) {
    const SimTK::Rotation R_GM = pin.getBodyRotation(s) * pin.getOutboardFrame(s).R();
    return {Vec3(R_GM.z()), Vec3(R_GM.x())};
}

void drawSheaveDisc(const NodeDrawing& drawing, const Vec3& axis, const Vec3& radial, bool spokes) {
    const double R = drawing.spec().radius;
    const Vec3 centre = drawing.centre();
    const SimTK::Rotation R_GC(SimTK::UnitVec3(axis), SimTK::YAxis);  // cylinder axis (its y) along the sheave axis
    const double halfWidth = 0.3 * R;
    drawing.geometry.push_back(SimTK::DecorativeCylinder(R, halfWidth)
                                   .setTransform(SimTK::Transform(R_GC, centre))
                                   .setColor(Vec3(0.72, 0.72, 0.78))
                                   .setResolution(2));
    if (!spokes) return;
    for (double face : {-1.0, 1.0}) {  // a spoke turning with the pin, on both faces
        const Vec3 o = centre + face * 1.05 * halfWidth * axis;
        drawing.geometry.push_back(SimTK::DecorativeLine(o - 0.9 * R * radial, o + 0.9 * R * radial)
                                       .setColor(Vec3(0.15, 0.15, 0.15))
                                       .setLineThickness(3));
    }
}

// ---- each kind's drawing ------------------------------------------------------------------

void AnchorNode::draw(const NodeDrawing& drawing) {
    drawing.geometry.push_back(
        SimTK::DecorativeSphere(0.05).setTransform(SimTK::Transform(drawing.centre())).setColor(Vec3(0.2, 0.2, 0.2)));
}

void DeviationSheaveNode::draw(const NodeDrawing& drawing) {
    Vec3 axis;
    if (drawing.rope.planar) {
        axis = toSimTK(drawing.rope.normal);
    } else if (drawing.rope.wraps[drawing.node].radius > 0) {  // a wrapped groove: its own axis
        axis = toSimTK(drawing.rope.grooveAxis(drawing.node, drawing.cache.nodes3));
    } else {  // the plane of the two spans at the sheave (any plane through a straight pass)
        const Eigen::Matrix3Xd& p = drawing.cache.nodes3;
        const int k = drawing.node;
        const Vec3 in = toSimTK(Eigen::Vector3d(p.col(k) - p.col(k - 1)));
        const Vec3 out = toSimTK(Eigen::Vector3d(p.col(k + 1) - p.col(k)));
        const Vec3 normal = SimTK::cross(in, out);
        axis = normal.norm() > 1e-9 * in.norm() * out.norm() ? normal.normalize() : perpendicularTo(in.normalize());
    }
    drawSheaveDisc(drawing, axis, perpendicularTo(axis), false);
}

void TurningSheaveNode::draw(const NodeDrawing& drawing) {
    const auto [axis, radial] = pinAxes(drawing.state, drawing.spec().body);
    drawSheaveDisc(drawing, axis, radial, true);
}

void TractionSheaveNode::draw(const NodeDrawing& drawing) { TurningSheaveNode::draw(drawing); }

void WinchDrumNode::draw(const NodeDrawing& drawing) {
    // Core and flanges; the drawn length holds the rope stored at pin angle 0 on one layer.
    const NodeSpec& n = drawing.spec();
    const double d = drawing.ropeDiameter;
    const Vec3 centre = drawing.centre();
    const auto [axis, radial] = pinAxes(drawing.state, n.body);
    const SimTK::Rotation R_GC(SimTK::UnitVec3(axis), SimTK::YAxis);
    const double storedAtZero = std::max(n.ropeOnDrum, 0.0);
    const double length = std::max(2.0 * n.radius, d * std::ceil(storedAtZero / (2.0 * SimTK::Pi * n.radius)));
    drawing.geometry.push_back(SimTK::DecorativeCylinder(n.radius, 0.5 * length)
                                   .setTransform(SimTK::Transform(R_GC, centre))
                                   .setColor(Vec3(0.45, 0.45, 0.5))
                                   .setResolution(2));
    for (double side : {-1.0, 1.0})
        drawing.geometry.push_back(SimTK::DecorativeCylinder(n.radius + 3 * d, 0.5 * d)
                                       .setTransform(SimTK::Transform(R_GC, centre + side * (0.5 * length + 0.5 * d) * axis))
                                       .setColor(Vec3(0.3, 0.3, 0.35))
                                       .setResolution(2));
    // The stored rope, wound from its fastening (body-fixed, radial direction) in layers of
    // turnsPerLayer turns; body angle phi = sense u / rho along the wound length u, so the point
    // where the rope leaves the drum stays put in Ground while the drum turns.
    const double stored = drawing.reeving.getRope(drawing.rope.index).getWinchDrum(drawing.node).getRopeOnDrum(drawing.state);
    const Vec3 tangent = SimTK::cross(axis, radial);
    const int turnsPerLayer = std::max(1, static_cast<int>(std::floor(length / d)));
    const int segmentsPerTurn = 16;
    const double dPhi = 2.0 * SimTK::Pi / segmentsPerTurn;
    double u = 0;
    Vec3 previous;
    for (int step = 0; u < stored && step < 4000; ++step) {
        const int turn = step / segmentsPerTurn, layer = turn / turnsPerLayer;
        const double rho = n.radius + (layer + 0.5) * d;
        const double along = (turn % turnsPerLayer + double(step % segmentsPerTurn) / segmentsPerTurn) * d;
        const double z = -0.5 * length + 0.5 * d + (layer % 2 == 0 ? along : length - d - along);
        const double phi = n.sense * step * dPhi;
        const Vec3 point = centre + z * axis + rho * (std::cos(phi) * radial + std::sin(phi) * tangent);
        if (step > 0)
            drawing.geometry.push_back(SimTK::DecorativeLine(previous, point).setColor(Vec3(0.45, 0.28, 0.12)).setLineThickness(2));
        previous = point;
        u += rho * dPhi;
    }
}

}  // namespace detail
}  // namespace SimbodyReeving
