// NodeKind::Anchor: a rope end fastened to a body.

#include "NodeBend.h"

namespace SimbodyReeving {
namespace detail {

void AnchorNode::addMaterialRelation(NodeSite& site) { site.rope.materialKinds[site.node] = MaterialNode::Fixed; }

std::pair<double, double> AnchorNode::heldInterval(const NodeBend& bend) {
    const double s = bend.materialCoordinate();
    return {s, s};
}

}  // namespace detail
}  // namespace SimbodyReeving
