#pragma once
/// @file
/// Internal to the element layer (not installed): where a node law finds its coordinates in a
/// RopeModel's coordinates z = [x | q_free | q_condensed, s_sliding, nu | s_fixed].

namespace SimbodyReeving::detail {

/// Node k's candidate columns in z, from the rope's layout (RopeModel's registration of the node
/// laws); each law takes those it has (-1: the node has none of that kind).
struct NodeColumns {
    int external = -1;   ///< its external material coordinate in x (drivenS: Driven and Slipping nodes)
    int dependent = -1;  ///< its solved material coordinate s_k (Sliding and Slipping nodes)
    int constant = -1;   ///< its constant material coordinate (Fixed nodes)
};

}  // namespace SimbodyReeving::detail
