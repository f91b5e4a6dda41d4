#pragma once
/// @file
/// Internal to the element layer (not installed): a rope node's law, one of the law types (how
/// the node's material coordinate s_k is determined, and what equations and forces that adds),
/// as a variant RopeModel holds per node and calls through std::visit. A new law is a new type
/// with the same static interface (FixedLaw's traits and members, or SlidingLaw's for a law whose
/// s_k is solved), registered here; RopeModel's evaluations do not name the kinds.

#include "DrivenLaw.h"
#include "FixedLaw.h"
#include "NodeColumns.h"
#include "SlidingLaw.h"
#include "SlippingLaw.h"

#include <type_traits>
#include <variant>

namespace SimbodyReeving::detail {

/// Node k's law. The traits every law type declares (its registration, as a joint's nq and nv):
/// kKind (the public tag), kName, kAtEnd and kInterior (where it may stand; kWhereNot: why not
/// elsewhere), kExternal (an external coordinate in drivenS), kDependent (s_k solved by the
/// rope), kDrum (a wrapped end node, rope stored beyond it) and kTurningGroove (on a groove whose
/// axis turns). Laws with a known s_k (kDependent false) give coordinate, rate and agrees; laws
/// with a solved one give tensionRow, multiplierRow, multiplierProducts and addFriction.
struct NodeLaw {
    std::variant<FixedLaw, SlidingLaw, DrivenLaw, SlippingLaw> law;
};

/// The registration: the law of tag kind at node k of a rope of numSpans spans and unstretched
/// length L [m] (a Fixed end's s_k: 0 at the start, L at the end), its columns not yet placed.
/// A Slipping node starts with kappa = 1.
/// @throws std::invalid_argument if the kind may not stand at that node (a Fixed interior node, a
///         Sliding or Slipping end) or is not a MaterialNode.
NodeLaw makeNodeLaw(MaterialNode kind, int node, int numSpans, double unstretchedLength);

/// A trait of node k's law (see NodeLaw): e.g. lawTrait(law, [](auto l) { return decltype(l)::kDrum; }).
template <class Trait>
auto lawTrait(const NodeLaw& law, const Trait& trait) {
    return std::visit([&](const auto& l) { return trait(std::decay_t<decltype(l)>{}); }, law.law);
}
inline MaterialNode kindOf(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kKind; });
}
inline const char* nameOf(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kName; });
}
inline bool hasExternalCoordinate(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kExternal; });
}
inline bool hasDependentCoordinate(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kDependent; });
}
inline bool isDrum(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kDrum; });
}
inline bool allowsTurningGroove(const NodeLaw& law) {
    return lawTrait(law, [](auto l) { return decltype(l)::kTurningGroove; });
}

/// Places node k's law at its candidate columns; returns its material coordinate's column in z.
inline int placeLaw(NodeLaw& law, const NodeColumns& columns) {
    return std::visit([&](auto& l) { return l.place(columns); }, law.law);
}
/// Calls f(law) if node k's s_k is known (Fixed, Driven).
template <class F>
void visitKnown(const NodeLaw& law, const F& f) {
    std::visit(
        [&](const auto& l) {
            if constexpr (!std::decay_t<decltype(l)>::kDependent) f(l);
        },
        law.law);
}
/// Calls f(law) if node k's s_k is solved (Sliding, Slipping).
template <class F>
void visitDependent(const NodeLaw& law, const F& f) {
    std::visit(
        [&](const auto& l) {
            if constexpr (std::decay_t<decltype(l)>::kDependent) f(l);
        },
        law.law);
}

}  // namespace SimbodyReeving::detail
