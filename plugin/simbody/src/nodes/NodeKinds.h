#pragma once
/// @file
/// Internal to the plugin: each NodeKind as its own unit. A unit is a struct of static members
/// (a closed set, dispatched once by visitNodeKind: no virtual call, and a new kind is one new unit
/// plus one case there):
///   - kName: its name in messages;
///   - validate(site): its own fields (the common ones, body, matter subsystem and point, are
///     checked by addRope first), throwing std::invalid_argument with the site's name;
///   - addMaterialRelation(site): how the rope's material coordinate at the node is determined
///     (RopeRecord::materialKinds: Fixed, Sliding or Driven; a Driven node's DrivenNode record:
///     s = s_ref + g(theta) with its DrivenLaw g and DrivenAngle theta, a drum's stored rope, a
///     traction sheave's friction);
///   - wrap(site, planeNormal): its groove with SheaveModel::Wrapped (NodeWrap; radius 0: a
///     point); planeNormal is the planar rope's, zero for a spatial rope;
///   - kTensionEquality: the node's constraint row is the frictionless tension equality (its
///     residual counts in getMaxConstraintError);
///   - draw(drawing): its Visualizer decoration (NodeDrawing.h);
///   - bendRadius(spec), heldInterval(bend), bendAxis(bend): how it bends the rope, the radius it
///     bends over, the material interval of rope on it and the axis the rope turns about there
///     (NodeBend.h; ReevingSubsystem::getNodeRadius, getNodeMaterialInterval, getNodeBendAxis).
/// What every node shares at run time (a station on a body: positions, velocities, the coupled
/// solve's rows) is generic in ReevingRealization.cpp and ReevingCoupling.cpp; a Driven node's
/// run time is its units' (DrivenAngle.h: how theta and its rate are measured and its row of the
/// coupled solve; DrivenLaw.h: s(theta) with its derivatives; DrivenRole.h: what its kind adds,
/// a drum's stored rope, a traction sheave's phases, Z entries, events, condensation and
/// queries), which the generic code calls without asking for the kind.

#include "../ReevingSubsystemGuts.h"

#include <string>
#include <utility>

namespace SimbodyReeving {
namespace detail {

/// A node of a rope being added (addRope): the record it fills, its index and spec, its name for
/// messages ("rope 'r': sheave 0 (TurningSheave, node 1)").
struct NodeDrawing;  // NodeDrawing.h
struct NodeBend;     // NodeBend.h

struct NodeSite {
    RopeRecord& rope;
    int node;
    const NodeSpec& spec;
    const std::string& name;
};

/// "what = value must be must" for messages.
std::string mustBe(const std::string& what, double value, const char* must);

/// True if body b keeps Ground's orientation: Ground, or a Slider, Translation or Weld whose
/// inboard and outboard frames are aligned, on such a body.
bool keepsGroundOrientation(const SimTK::MobilizedBody& b);

/// Body b's orientation in Ground with every mobilizer of its chain at its reference (q = 0 of the
/// Pins, Sliders, Translations and Planars that keepsDirection accepts): the product of each
/// mobilizer's R_PF R_MB^T down the chain.
SimTK::Rotation referenceOrientation(const SimTK::MobilizedBody& b);

/// True if every motion of body b's chain keeps the Ground direction `direction` fixed: each
/// mobilizer is a Slider, Translation or Weld, or a Pin or Planar turning about that direction.
bool keepsDirection(const SimTK::MobilizedBody& b, const SimTK::Vec3& direction);

/// An end fastened to a body: s fixed (0 at the start, L at the end). Ends only.
struct AnchorNode {
    static constexpr const char* kName = "Anchor";
    static constexpr bool kTensionEquality = false;
    static void validate(const NodeSite&) {}
    static void addMaterialRelation(NodeSite& site);
    static NodeWrap wrap(const NodeSite&, const SimTK::Vec3&) { return {}; }
    static void draw(const NodeDrawing& drawing);
    /// The rope ends here unbent: radius 0, its end's one point [s_k, s_k], no bend axis (zero).
    static double bendRadius(const NodeSpec&) { return 0.0; }
    static std::pair<double, double> heldInterval(const NodeBend& bend);
    static SimTK::Vec3 bendAxis(const NodeBend&) { return SimTK::Vec3(0); }
};

/// A frictionless idler (paper eq 30/32): s solved from the tension equality. Inside a path.
struct DeviationSheaveNode {
    static constexpr const char* kName = "DeviationSheave";
    static constexpr bool kTensionEquality = true;
    static void validate(const NodeSite& site);
    static void addMaterialRelation(NodeSite& site);
    static NodeWrap wrap(const NodeSite& site, const SimTK::Vec3& planeNormal);
    static void draw(const NodeDrawing& drawing);
    /// Its radius; sheaveInterval (NodeBend.h); wrapped: wrapSense times its groove's axis (the
    /// plane normal of a planar rope, its body's axis in Ground otherwise), a point: chordTurn.
    static double bendRadius(const NodeSpec& spec) { return spec.radius; }
    static std::pair<double, double> heldInterval(const NodeBend& bend);
    static SimTK::Vec3 bendAxis(const NodeBend& bend);
};

/// A drum at a rope end on a Pin: s = s_end - or + sense R theta, its stored rope. Ends only.
struct WinchDrumNode {
    static constexpr const char* kName = "WinchDrum";
    static constexpr bool kTensionEquality = false;
    static void validate(const NodeSite& site);
    static void addMaterialRelation(NodeSite& site);
    static NodeWrap wrap(const NodeSite& site, const SimTK::Vec3& planeNormal);
    static void draw(const NodeDrawing& drawing);
    /// Its radius; the rope on it, unbounded on its stored side: (-inf, s_0] at a start drum,
    /// [s_N, +inf) at an end drum; payoutSense times its pin axis at a start drum (the rope
    /// leaving it), minus that at an end drum (the rope arriving), wrapped or not.
    static double bendRadius(const NodeSpec& spec) { return spec.radius; }
    static std::pair<double, double> heldInterval(const NodeBend& bend);
    static SimTK::Vec3 bendAxis(const NodeBend& bend);
};

/// A sheave on a Pin that grips the rope: s = s_ref + sense R theta. Inside a path.
struct TurningSheaveNode {
    static constexpr const char* kName = "TurningSheave";
    static constexpr bool kTensionEquality = false;
    static void validate(const NodeSite& site);
    static void addMaterialRelation(NodeSite& site);
    static NodeWrap wrap(const NodeSite& site, const SimTK::Vec3& planeNormal);
    static void draw(const NodeDrawing& drawing);
    /// Its radius; sheaveInterval; pinnedSheaveBendAxis (NodeBend.h).
    static double bendRadius(const NodeSpec& spec) { return spec.radius; }
    static std::pair<double, double> heldInterval(const NodeBend& bend);
    static SimTK::Vec3 bendAxis(const NodeBend& bend);
};

/// A sheave on a Pin that grips the rope by friction (stick: a TurningSheave with a state offset;
/// slip: the capstan law or the rope's momentum, TractionRole in DrivenRole.h and TractionSheaveRun.cpp).
/// Inside a path of a planar or spatial rope.
struct TractionSheaveNode {
    static constexpr const char* kName = "TractionSheave";
    static constexpr bool kTensionEquality = false;
    static void validate(const NodeSite& site);
    static void addMaterialRelation(NodeSite& site);
    static NodeWrap wrap(const NodeSite& site, const SimTK::Vec3& planeNormal);
    static void draw(const NodeDrawing& drawing);
    /// Its radius; sheaveInterval; pinnedSheaveBendAxis (NodeBend.h), in stick and in slip.
    static double bendRadius(const NodeSpec& spec) { return spec.radius; }
    static std::pair<double, double> heldInterval(const NodeBend& bend);
    static SimTK::Vec3 bendAxis(const NodeBend& bend);
};

/// Calls f with the unit of kind (a value of its empty struct) and returns what it returns: the
/// one switch over NodeKind.
template <class F>
decltype(auto) visitNodeKind(NodeKind kind, F&& f) {
    switch (kind) {
        case NodeKind::Anchor: return f(AnchorNode{});
        case NodeKind::DeviationSheave: return f(DeviationSheaveNode{});
        case NodeKind::WinchDrum: return f(WinchDrumNode{});
        case NodeKind::TurningSheave: return f(TurningSheaveNode{});
        case NodeKind::TractionSheave: return f(TractionSheaveNode{});
    }
    invalid("unknown NodeKind " + std::to_string(static_cast<int>(kind)));
}

/// The kind's name in messages ("Anchor", "DeviationSheave", ...).
inline const char* nodeKindName(NodeKind kind) {
    return visitNodeKind(kind, [](auto unit) { return decltype(unit)::kName; });
}

}  // namespace detail
}  // namespace SimbodyReeving
