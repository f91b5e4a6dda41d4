#pragma once
/// @file
/// Internal to the element layer (not installed): the elements of a RopeModel, fixed at its
/// construction and shared (not copied) by its copies and by the models that differ from it in
/// node laws only (RopeModel::withNodeLaw).

#include "SimbodyReeving/element/AxialCondensation.h"
#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/SpanModel.h"

#include <vector>

namespace SimbodyReeving::detail {

/// The spans (path order), their condensation kernels (one per span when some span is condensed,
/// else none) and the groove arcs of the wrapped nodes (node order). Immutable once built: the
/// node laws and the coordinate layout that depends on them belong to the RopeModel.
template <int Dim>
struct RopeElements {
    std::vector<SpanModel<Dim>> spans;
    std::vector<AxialCondensation<Dim>> kernels;
    std::vector<GrooveArc<Dim>> arcs;
};

}  // namespace SimbodyReeving::detail
