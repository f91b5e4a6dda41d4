#pragma once
/// @file
/// Internal to the plugin: what the node kinds on a MobilizedBody::Pin share (WinchDrumNode,
/// TurningSheaveNode, TractionSheaveNode): the pin's checks, the Driven material relation
/// s = s_ref + g(theta) (DrivenLaw.h), and the grip on a wrapped groove with its angle measure
/// (DrivenAngle.h).

#include "NodeKinds.h"

namespace SimbodyReeving {
namespace detail {

/// Radius finite and > 0, the body a Pin, the node on its axis, sense +1 or -1.
/// @throws std::invalid_argument (ReevingSubsystem's message) otherwise.
void validatePinnedNode(const NodeSite& site);

/// Makes the node Driven and returns its DrivenNode record with its node filled (the kind sets
/// s_ref, its DrivenLaw and its DrivenRole, then pushes it; the angle is a PinAngle unless
/// grippingSheaveWrap makes it the sheave's own).
RopeRecord::DrivenNode drivenNodeOf(NodeSite& site);

/// A TurningSheave, TractionSheave or WinchDrum with SheaveModel::Wrapped grips the rope on its
/// groove (a traction sheave while it sticks): s = s_ref + g(theta) is the material
/// coordinate at the groove's top (WrapStationMap), so the wrap sense is sigma = -sign(g'(0))
/// (pin axis . n). On a planar rope its pin must turn about the plane normal; with turningParent
/// (TurningSheave, WinchDrum of a planar rope) the parent may turn too, about that normal, and
/// theta is the sheave's own angle (its pin's plus the parent's turn: the DrivenAngle
/// ParentTurnAngle, or TurningAxisAngle on a spatial rope whose pin axis turns with the parent);
/// otherwise (a TractionSheave, a spatial rope) the parent must keep Ground's orientation.
/// kindName names the node in the messages ("rope 'r': TurningSheave at node 1: ...").
/// @throws std::invalid_argument if the parent turns where it may not or the pin axis is off the
///         plane normal.
NodeWrap grippingSheaveWrap(const NodeSite& site, const char* kindName, const SimTK::Vec3& planeNormal,
                            bool turningParent);

}  // namespace detail
}  // namespace SimbodyReeving
