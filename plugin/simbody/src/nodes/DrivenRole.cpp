// The driven relation every DrivenRole starts from (nodes/DrivenRole.h): s = s_ref + g(theta).

#include "../ReevingSubsystemGuts.h"

namespace SimbodyReeving {
namespace detail {

void DrivenRoleDefaults::materialCoordinate(const DrivenRun& run, const SimTK::State&, double theta, double thetaDot,
                                            bool rates, double& s, double& sdot) const {
    s = run.node.law.materialCoordinate(run.node.sRef, theta);
    if (rates) sdot = run.node.law.materialRate(theta, thetaDot);
}

}  // namespace detail
}  // namespace SimbodyReeving
