// Spans that turn without limit, element level (no Simbody): re-expressing a spatial span's transverse modes in
// a new reference frame (reReferenceTransverseModes) leaves the span's configuration, velocity
// field and energies unchanged.
#include "SimbodyReeving/element/ChordFrame.h"
#include "SimbodyReeving/element/SpanModel.h"
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

using namespace SimbodyReeving;

namespace {

const RopeProperties kRope{0.6, 1e6, 50.0};

Eigen::Matrix3d rotated(const Eigen::Matrix3d& A, double angle, const Eigen::Vector3d& axis) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix() * A;
}

}  // namespace

TEST(FrameReference, AlignmentIsOnePlusTheCosineToTheReference) {
    const Eigen::Matrix3d A0 = makeReferenceFrame(Eigen::Vector3d(1, 0, 0));
    EXPECT_DOUBLE_EQ(referenceAlignment(Eigen::Vector3d(3, 0, 0), A0), 2.0);
    EXPECT_NEAR(referenceAlignment(Eigen::Vector3d(0, 2, 0), A0), 1.0, 1e-16);
    EXPECT_NEAR(referenceAlignment(Eigen::Vector3d(-1, 1, 0), A0), 1.0 - std::sqrt(0.5), 1e-15);
    EXPECT_THROW_MESSAGE(referenceAlignment(Eigen::Vector3d::Zero(), A0), std::domain_error,
                         "referenceAlignment: chord e = (0 0 0) is zero or not finite");
}

// The transverse displacement of each mode and its velocity are the same in both frames.
TEST(FrameReference, ModesAndRatesMapExactlyForBothVelocityModels) {
    const Eigen::Vector3d e(3.0, -1.0, 2.0), edot(0.4, 0.7, -0.3);
    // The old reference 150 degrees away from the chord (a chord that has turned far), the new one
    // the current element frame twisted about the chord (any frame with i0 near the chord works).
    const Eigen::Matrix3d A0 = rotated(makeReferenceFrame(e), 2.6, Eigen::Vector3d(0.2, 1.0, 0.5).cross(e));
    ChordFrame<3> f0;
    computeChordFrame<3>(e, edot, A0, f0);
    const Eigen::Matrix3d A1 = rotated(f0.A, 0.9, e);
    ChordFrame<3> f1;
    computeChordFrame<3>(e, edot, A1, f1);
    for (bool complete : {false, true}) {
        Eigen::VectorXd b(3), c(3), bd(3), cd(3);
        b << 0.1, -0.02, 0.005;
        c << -0.05, 0.03, 0.001;
        bd << 0.3, 0.1, -0.2;
        cd << -0.1, 0.25, 0.05;
        const Eigen::VectorXd b0 = b, c0 = c, bd0 = bd, cd0 = cd;
        reReferenceTransverseModes(e, edot, A0, A1, complete, b, c, bd, cd);
        double worstW = 0, worstV = 0;
        for (int i = 0; i < 3; ++i) {
            const Eigen::Vector3d w0 = f0.A.col(1) * b0[i] + f0.A.col(2) * c0[i];
            const Eigen::Vector3d w1 = f1.A.col(1) * b[i] + f1.A.col(2) * c[i];
            Eigen::Vector3d v0 = f0.A.col(1) * bd0[i] + f0.A.col(2) * cd0[i];
            Eigen::Vector3d v1 = f1.A.col(1) * bd[i] + f1.A.col(2) * cd[i];
            if (complete) {
                v0 += f0.Adot.col(1) * b0[i] + f0.Adot.col(2) * c0[i];
                v1 += f1.Adot.col(1) * b[i] + f1.Adot.col(2) * c[i];
            }
            worstW = std::max(worstW, (w1 - w0).norm());
            worstV = std::max(worstV, (v1 - v0).norm());
        }
        std::printf("[ frame ] %s: displacement %.3e m, velocity %.3e m/s\n", complete ? "Complete" : "Simplified",
                    worstW, worstV);
        EXPECT_LE(worstW, 1e-15) << "complete " << complete;  // measured 1.7e-17 m (both models)
        EXPECT_LE(worstV, 1e-14) << "complete " << complete;  // measured 1.5e-16 / 8.1e-17 m/s
        // The frames twist at different rates, so Complete changes the rates by more than the rotation.
        if (complete) {
            EXPECT_GT(std::abs(std::hypot(bd[0], cd[0]) - std::hypot(bd0[0], cd0[0])), 1e-3);
        }
    }
}

// A whole span evaluated in both references: material points, kinetic, strain and gravity energy.
TEST(FrameReference, SpanConfigurationAndEnergiesAreUnchanged) {
    SpanOptions o;
    o.axialModes = 2;
    o.transverseModes = 3;
    o.velocityModel = VelocityModel::Complete;
    const Eigen::Vector3d g(0, 0, -9.81);
    const Eigen::Vector3d r1(0.5, 0.2, 1.0), r2(-8.0, 3.0, 0.5);
    const Eigen::Vector3d e = r2 - r1, edot(0.8, 2.0, -0.1);
    const Eigen::Matrix3d A0 = rotated(makeReferenceFrame(-e), 0.5, Eigen::Vector3d(0, 0, 1));  // ~150 deg off
    ChordFrame<3> f0;
    computeChordFrame<3>(e, edot, A0, f0);
    const Eigen::Matrix3d A1 = makeReferenceFrame(e, f0.A.col(2));
    const SpatialSpanModel before(kRope, o, g, A0), after(kRope, o, g, A1);
    const int n = before.numCoordinates();
    Eigen::VectorXd q(n), qd(n);
    q << r1, r2, 0.01, -0.003, 0.2, -0.05, 0.02, 0.1, 0.04, -0.01, 1.0, 9.0;
    qd << 0.1, 0.0, 0.05, 0.9, 2.0, -0.05, 0.02, 0.01, 0.5, -0.2, 0.1, -0.3, 0.2, 0.05, 0.1, 0.15;
    Eigen::VectorXd q1 = q, qd1 = qd;
    const int jFirst = before.transverseModeIndex(0, 0), kFirst = before.transverseModeIndex(1, 0);
    reReferenceTransverseModes(e, edot, A0, A1, true, q1.segment(jFirst, 3), q1.segment(kFirst, 3),
                               qd1.segment(jFirst, 3), qd1.segment(kFirst, 3));
    double worst = 0;
    for (int k = 0; k <= 10; ++k) {
        const double s = 1.0 + 8.0 * k / 10.0;
        worst = std::max(worst, (after.position(q1, s) - before.position(q, s)).norm());
    }
    SpanData<3> d0, d1;
    before.evaluate(q, qd, d0);
    after.evaluate(q1, qd1, d1);
    std::printf("[ frame ] span: positions %.3e m, kinetic %.3e, strain %.3e, gravity %.3e relative, end force %.3e N\n",
                worst, std::abs(d1.kineticEnergy / d0.kineticEnergy - 1), std::abs(d1.strainEnergy() / d0.strainEnergy() - 1),
                std::abs(d1.gravityEnergy / d0.gravityEnergy - 1), std::abs(after.axialForce(q1, 1.0) - before.axialForce(q, 1.0)));
    EXPECT_LE(worst, 1e-14);  // measured 4.4e-16 m over an 8 m span
    // Measured relative differences: kinetic 0, strain 6.7e-16, gravity 0.
    EXPECT_NEAR(d1.kineticEnergy, d0.kineticEnergy, 1e-14 * d0.kineticEnergy);
    EXPECT_NEAR(d1.strainEnergy(), d0.strainEnergy(), 1e-14 * d0.strainEnergy());
    EXPECT_NEAR(d1.gravityEnergy, d0.gravityEnergy, 1e-14 * std::abs(d0.gravityEnergy));
    // The axial force at the ends (what the sheaves and bodies see) is a property of the configuration.
    // Measured: equal (0 N difference).
    EXPECT_NEAR(after.axialForce(q1, 1.0), before.axialForce(q, 1.0), 1e-12 * std::abs(before.axialForce(q, 1.0)));
}
