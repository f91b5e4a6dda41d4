#pragma once
/// @file
/// Where a node's groove circle lies along its axis: one of the placement units, as a variant a
/// NodeWrap carries and the element layer calls through std::visit (pure C++17, no Eigen or
/// Simbody include). A new placement is one new unit (CentredGroove's traits and members) plus
/// its entry in the variant; the station map and the rope do not name the units.

#include "SimbodyReeving/element/CentredGroove.h"
#include "SimbodyReeving/element/WalkingGroove.h"

#include <type_traits>
#include <variant>

namespace SimbodyReeving {

/// A node's groove placement: the axial offset x(Y) [m] of the groove circle from the node's
/// position along its axis n, with dx/dY [-] and d2x/dY2 [1/m], Y the node's driven coordinate
/// (the groove's centre is c + x n). Every unit declares kName, kFollowsDriven (x depends on Y:
/// the node must then be Driven, and the station map adds Y's columns) and kAtCentre (x = 0
/// identically), and gives validate() (@throws std::invalid_argument for bad parameters), x(Y),
/// dx(Y) and ddx(Y). A placement other than kAtCentre needs a wrapped Driven end node of a spatial
/// rope (RopeModel<3>: a drum, whose one tangent point follows the groove; the node block's centre
/// c and the stored rope's ring stay at the node's position). Default: CentredGroove.
struct GroovePlacement {
    std::variant<CentredGroove, WalkingGroove> unit;  ///< the unit (its registration: this list)
};

/// A placement's x, dx/dY and d2x/dY2 at one Y.
struct GrooveLay {
    double x = 0;    ///< [m]
    double dx = 0;   ///< [-]
    double ddx = 0;  ///< [1/m]
};

/// A trait of the placement's unit, trait(unit type{}): e.g. the name, a lambda returning the
/// unit type's kName.
template <class Trait>
auto placementTrait(const GroovePlacement& p, const Trait& trait) {
    return std::visit([&](const auto& u) { return trait(std::decay_t<decltype(u)>{}); }, p.unit);
}
/// The unit's kName.
inline const char* placementName(const GroovePlacement& p) {
    return placementTrait(p, [](auto u) { return decltype(u)::kName; });
}
/// The unit's kFollowsDriven: x depends on the driven coordinate Y.
inline bool followsDriven(const GroovePlacement& p) {
    return placementTrait(p, [](auto u) { return decltype(u)::kFollowsDriven; });
}
/// The unit's kAtCentre: x = 0 identically.
inline bool isAtCentre(const GroovePlacement& p) {
    return placementTrait(p, [](auto u) { return decltype(u)::kAtCentre; });
}
/// The unit's own check of its parameters.
/// @throws std::invalid_argument as the unit's validate().
inline void validatePlacement(const GroovePlacement& p) {
    std::visit([](const auto& u) { u.validate(); }, p.unit);
}
/// x, dx/dY, d2x/dY2 at the driven coordinate Y [m] (any Y for a unit that does not follow it).
inline GrooveLay layAt(const GroovePlacement& p, double Y) {
    return std::visit([&](const auto& u) { return GrooveLay{u.x(Y), u.dx(Y), u.ddx(Y)}; }, p.unit);
}

}  // namespace SimbodyReeving
