#include "NodeLaw.h"

#include <stdexcept>
#include <string>

namespace SimbodyReeving::detail {

namespace {
template <class Law>
Law placed(Law law, int node, int numSpans) {
    const bool end = node == 0 || node == numSpans;
    if (end ? !Law::kAtEnd : !Law::kInterior)
        throw std::invalid_argument("RopeModel: " + std::string(end ? "end" : "interior") + " node " +
                                    std::to_string(node) + " cannot be " + Law::kName + " (" + Law::kWhereNot + ")");
    return law;
}
}  // namespace

NodeLaw makeNodeLaw(MaterialNode kind, int node, int numSpans, double unstretchedLength) {
    switch (kind) {
        case MaterialNode::Fixed: return {placed(FixedLaw{node == 0 ? 0.0 : unstretchedLength}, node, numSpans)};
        case MaterialNode::Sliding: return {placed(SlidingLaw{}, node, numSpans)};
        case MaterialNode::Driven: return {placed(DrivenLaw{}, node, numSpans)};
        case MaterialNode::Slipping: return {placed(SlippingLaw{}, node, numSpans)};
    }
    throw std::invalid_argument("RopeModel: node " + std::to_string(node) + "'s kind " +
                                std::to_string(static_cast<int>(kind)) + " is not a MaterialNode");
}

}  // namespace SimbodyReeving::detail
