// AxialDynamics::QuasiStatic in the Simbody layer (issue 12, acceptance 1 and 2): the static
// equilibrium equals the Dynamic model's, and the conservative pendulum keeps its energy.
#include "SimbodyReeving/Integrators.h"
#include "SimbodyReeving/PendulumScene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using SimTK::Stage;
using SimTK::State;
using namespace SimbodyReeving;

namespace {

SpanOptions spans(int na, AxialDynamics dynamics) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = 1;
    o.axialDynamics = dynamics;
    return o;
}

/// Axial force at 41 points along each span of the pendulum's rope.
std::vector<double> axialForceProfile(const PendulumScene& scene, const State& s) {
    std::vector<double> out;
    const ReevingSubsystem& rv = scene.reeving();
    for (int span = 0; span < 2; ++span) {
        const auto [s1, s2] = rv.getSpanMaterialRange(s, 0, span);
        for (int k = 0; k <= 40; ++k) out.push_back(rv.getAxialForce(s, 0, span, std::min(s2, s1 + (s2 - s1) * k / 40)));
    }
    return out;
}

}  // namespace

TEST(QuasiStaticAxial, StaticEquilibriumEqualsDynamic) {
    for (int na : {1, 3, 8}) {
        const PendulumScene dynamic(PendulumParameters{}, spans(na, AxialDynamics::Dynamic));
        const PendulumScene quasi(PendulumParameters{}, spans(na, AxialDynamics::QuasiStatic));
        EXPECT_EQ(quasi.reeving().getNumModalCoordinates(0), 2);  // only the transverse modes are states
        const State sd = dynamic.makeInitialState(0, 0);
        const State sq = quasi.makeInitialState(0, 0);
        const std::vector<double> pd = axialForceProfile(dynamic, sd), pq = axialForceProfile(quasi, sq);
        double worst = 0, scale = 0;
        for (size_t k = 0; k < pd.size(); ++k) {
            worst = std::max(worst, std::abs(pd[k] - pq[k]));
            scale = std::max(scale, std::abs(pd[k]));
        }
        std::printf("n_a = %d: max |P_quasi-static - P_dynamic| = %.3e N of %.1f N (%.2e relative)\n", na, worst,
                    scale, worst / scale);
        EXPECT_LT(worst / scale, 1e-9) << "n_a = " << na;
        const double dy = (quasi.payloadPosition(sq) - dynamic.payloadPosition(sd)).norm();
        EXPECT_LT(dy, 1e-9) << "n_a = " << na;
    }
}
