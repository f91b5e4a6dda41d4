// The Driven nodes' run-time units (plugin/simbody/src/nodes/DrivenLaw.h, DrivenAngle.h) on their
// own: the linear law s = s_ref + dsdTheta theta with its derivatives and inverse, and the three
// angle measures (the pin's q; q plus the parent's turn about a fixed axis; q plus the parent's
// turn about a turning axis) against the bodies' angles, their rates against central differences
// of the angles along the motion, and their rows of the coupled solve against Simbody's
// accelerations.
#include "../../plugin/simbody/src/nodes/DrivenAngle.h"
#include "../../plugin/simbody/src/nodes/DrivenLaw.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>

using namespace SimTK;
using SimbodyReeving::detail::DrivenAngle;
using SimbodyReeving::detail::DrivenAngleRow;
using SimbodyReeving::detail::DrivenAngleSite;
using SimbodyReeving::detail::DrivenLaw;
using SimbodyReeving::detail::LinearDrivenLaw;
using SimbodyReeving::detail::ParentTurnAngle;
using SimbodyReeving::detail::PinAngle;
using SimbodyReeving::detail::TurningAxisAngle;

namespace {

// A sheave on a Pin on a parent Pin on Ground, each turning about its inboard frame's z: the
// parent's frame in Ground and the sheave's (at 1 m along the parent's x) in the parent, each
// turned about y by parentTilt, sheaveTilt [rad] (0: both pins about Ground's z). No forces: the
// accelerations are the bodies' own (centripetal and gyroscopic).
struct TwoPins {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    MobilizedBody::Pin parent, sheave;
    State state;
    TwoPins(double parentTilt, double sheaveTilt)
        : parent(matter.Ground(), Transform(Rotation(parentTilt, YAxis), Vec3(0)),
                 Body::Rigid(MassProperties(2, Vec3(0.3, 0, 0), Inertia(1))), Transform()),
          sheave(parent, Transform(Rotation(sheaveTilt, YAxis), Vec3(1, 0, 0)),
                 Body::Rigid(MassProperties(1, Vec3(0.01, 0.02, 0), Inertia(0.1))), Transform()) {
        system.realizeTopology();
        state = system.getDefaultState();
    }
    void set(double qParent, double qSheave, double uParent, double uSheave) {
        parent.setOneQ(state, 0, qParent);
        sheave.setOneQ(state, 0, qSheave);
        parent.setOneU(state, 0, uParent);
        sheave.setOneU(state, 0, uSheave);
        system.realize(state, Stage::Acceleration);
    }
    /// A_GB of every body, by MobilizedBodyIndex (Stage::Acceleration).
    Vector_<SpatialVec> bodyAccelerations() const {
        Vector_<SpatialVec> A(matter.getNumBodies());
        for (MobilizedBodyIndex b(0); b < matter.getNumBodies(); ++b)
            A[b] = matter.getMobilizedBody(b).getBodyAcceleration(state);
        return A;
    }
};

const Vec3 kUp(0, 1, 0);

// Central difference of theta along the motion q(t) = q + u t (step h [s]).
double angleRateByDifferences(TwoPins& m, const DrivenAngle& angle, double qp, double qs, double up, double us) {
    const double h = 1e-6;
    m.set(qp + up * h, qs + us * h, up, us);
    const double ahead = angle.angle({m.state, m.sheave, kUp});
    m.set(qp - up * h, qs - us * h, up, us);
    const double behind = angle.angle({m.state, m.sheave, kUp});
    m.set(qp, qs, up, us);
    return (ahead - behind) / (2 * h);
}

}  // namespace

TEST(DrivenLaw, LinearLawItsDerivativesAndItsInverse) {
    const DrivenLaw law{LinearDrivenLaw{-0.25}};  // a start drum of R = 0.25 m, sense +1
    EXPECT_EQ(law.materialCoordinate(3.0, 2.0), 3.0 - 0.25 * 2.0);  // s_ref + dsdTheta theta
    EXPECT_EQ(law.slope(7.0), -0.25);                                // constant
    EXPECT_EQ(law.materialRate(7.0, 4.0), -0.25 * 4.0);              // dsdTheta thetadot
    EXPECT_EQ(law.acceleration(7.0, 4.0, 8.0), -0.25 * 8.0);         // no thetadot^2 term (g'' = 0)
    // offsetOf inverts materialCoordinate (the stick offset taking over from a slip state):
    // round-off of two operations on values of order 1.
    EXPECT_NEAR(law.offsetOf(law.materialCoordinate(3.0, 2.0), 2.0), 3.0, 1e-15);
    // The rate is the derivative of s along theta(t) (exact for a linear law up to round-off).
    const double h = 1e-3, theta = 0.7, rate = 1.3;
    const double byDifferences =
        (law.materialCoordinate(1.0, theta + rate * h) - law.materialCoordinate(1.0, theta - rate * h)) / (2 * h);
    EXPECT_NEAR(byDifferences, law.materialRate(theta, rate), 1e-12);
}

TEST(DrivenAngle, PinAngleIsThePinsCoordinateAndItsRowItsMobility) {
    TwoPins m{0.0, 0.0};
    m.set(0.4, -1.2, 0.5, 2.0);
    const DrivenAngle angle{PinAngle{}};
    const DrivenAngleSite site{m.state, m.sheave, kUp};
    EXPECT_EQ(angle.angle(site), -1.2);
    EXPECT_EQ(angle.rate(site), 2.0);
    EXPECT_FALSE(angle.includesParentTurn(m.sheave));
    EXPECT_EQ(angle.parentTurn(site), 0.0);
    DrivenAngleRow row;
    angle.row(site, row);
    ASSERT_TRUE(row.onMobility());
    EXPECT_EQ(row.mobility, static_cast<int>(m.sheave.getFirstUIndex(m.state)));
    EXPECT_EQ(row.acceleration(m.bodyAccelerations(), m.state.getUDot()), m.sheave.getOneUDot(m.state, 0));
}

TEST(DrivenAngle, ParentTurnAngleIsTheSheavesOwnAngle) {
    TwoPins m{0.0, 0.0};  // the parent turns about the sheave's axis (Ground z)
    const DrivenAngle angle{ParentTurnAngle{Vec3(0, 0, 1)}};
    const double qp = 0.9, qs = -0.4, up = 0.7, us = -1.1;
    m.set(qp, qs, up, us);
    const DrivenAngleSite site{m.state, m.sheave, kUp};
    // The sheave body's rotation about z is qp + qs (both pins about z): to round-off.
    EXPECT_NEAR(angle.angle(site), qp + qs, 1e-15);
    EXPECT_NEAR(angle.parentTurn(site), qp, 1e-15);
    EXPECT_TRUE(angle.includesParentTurn(m.sheave));
    EXPECT_FALSE(angle.includesParentTurn(m.parent));  // its parent is Ground
    EXPECT_NEAR(angle.rate(site), up + us, 1e-15);
    // The rate is theta's derivative along the motion: central differences, error O(h^2) and
    // round-off 1e-16 / 1e-6.
    EXPECT_NEAR(angleRateByDifferences(m, angle, qp, qs, up, us), angle.rate(site), 1e-9);
    // Its row: the sheave body's angular acceleration about z (no bias): udot_p + udot_s.
    DrivenAngleRow row;
    angle.row(site, row);
    ASSERT_FALSE(row.onMobility());
    EXPECT_EQ(row.body, m.sheave.getMobilizedBodyIndex());
    EXPECT_NEAR(row.acceleration(m.bodyAccelerations(), m.state.getUDot()),
                m.parent.getOneUDot(m.state, 0) + m.sheave.getOneUDot(m.state, 0), 1e-12);
}

TEST(DrivenAngle, TurningAxisAngleRateAndRowFollowTheAngle) {
    // The parent luffs about Ground's x; the sheave's axis (the parent's x, Ground's -z at rest)
    // turns with it. The unit's directions as grippingSheaveWrap sets them: the sheave's pin axis
    // in its body and in the parent, and its inboard frame's x in the parent.
    TwoPins m{Pi / 2, Pi / 2};
    TurningAxisAngle unit;
    // (The sheave's outboard frame is the identity: its z; its inboard frame turns z onto the
    // parent's x and x onto the parent's -z.)
    unit.bodyAxis = Vec3(0, 0, 1);
    unit.parentAxis = Vec3(1, 0, 0);
    unit.parentPerp = Vec3(0, 0, -1);
    const DrivenAngle angle{unit};
    const double qp = 0.3, qs = 0.8, up = 0.6, us = 1.7;
    m.set(qp, qs, up, us);
    const DrivenAngleSite site{m.state, m.sheave, kUp};
    EXPECT_TRUE(angle.includesParentTurn(m.sheave));
    EXPECT_NEAR(angle.angle(site), qs + angle.parentTurn(site), 1e-15);
    // thetadot = m . omega_B against central differences of theta (error O(h^2), round-off
    // 1e-16 / 1e-6).
    EXPECT_NEAR(angleRateByDifferences(m, angle, qp, qs, up, us), angle.rate(site), 1e-8);
    // Its row: thetaddot = m . omegadot_B + mdot . omega_B, against central differences of the
    // rate along the accelerated motion (q + u t + udot t^2 / 2, u + udot t).
    DrivenAngleRow row;
    angle.row(site, row);
    ASSERT_FALSE(row.onMobility());
    const double thetaDDot = row.acceleration(m.bodyAccelerations(), m.state.getUDot());
    const double ap = m.parent.getOneUDot(m.state, 0), as = m.sheave.getOneUDot(m.state, 0), h = 1e-6;
    m.set(qp + up * h + ap * h * h / 2, qs + us * h + as * h * h / 2, up + ap * h, us + as * h);
    const double ahead = angle.rate({m.state, m.sheave, kUp});
    m.set(qp - up * h + ap * h * h / 2, qs - us * h + as * h * h / 2, up - ap * h, us - as * h);
    const double behind = angle.rate({m.state, m.sheave, kUp});
    EXPECT_NEAR((ahead - behind) / (2 * h), thetaDDot, 1e-8);
}
