// NodeKind::Anchor: a rope end fastened to a body.

#include "NodeKinds.h"

namespace SimbodyReeving {
namespace detail {

void AnchorNode::addMaterialRelation(NodeSite& site) { site.rope.materialKinds[site.node] = MaterialNode::Fixed; }

}  // namespace detail
}  // namespace SimbodyReeving
