// ReevingSubsystem::Guts: realizeDynamics, the coupled rope/body solve (free node accelerations,
// node mobility Lambda, the Schur complement on the node forces, modal accelerations).

#include "ReevingSubsystemGuts.h"

using SimTK::MobilizedBody;
using SimTK::SimbodyMatterSubsystem;
using SimTK::SpatialVec;
using SimTK::Stage;
using SimTK::State;
using SimTK::Value;
using SimTK::Vec3;
using SimTK::Vector;
using SimTK::Vector_;

namespace SimbodyReeving {

using namespace detail;

int ReevingSubsystem::Guts::realizeSubsystemDynamicsImpl(const State& s) const {
    PositionCache& pc = Value<PositionCache>::updDowncast(updCacheEntry(s, positionCache_));
    refreshFromZ(s, pc, true);
    CouplingWorkspace& ws = pc.coupling;
    Vector_<SpatialVec>& bodyForces = mbs().updRigidBodyForces(s, Stage::Dynamics);
    const Vector& mobilityForces = mbs().updMobilityForces(s, Stage::Dynamics);

    // Rope-side S and h of the mobile nodes (on bodies other than Ground), in 3D.
    const int m = static_cast<int>(mobileNodes_.size());
    ws.S.setZero(3 * m, 3 * m);
    ws.h.setZero(3 * m);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
            if (mobileNodes_[a].rope != mobileNodes_[b].rope) continue;
            const RopeRecord& r = ropes[mobileNodes_[a].rope];
            const RopeCache& c = pc.ropes[mobileNodes_[a].rope];
            ws.S.block<3, 3>(3 * a, 3 * b) = nodeMass3(r, c, mobileNodes_[a].node, mobileNodes_[b].node);
            if (a == b) ws.h.segment<3>(3 * a) = nodeForce3(r, c, mobileNodes_[a].node);
        }

    ws.f.setZero(3 * m);
    ws.rdd.setZero(3 * m);
    if (m > 0) {
        // Free node accelerations a0 under every force applied so far.
        matter().calcAcceleration(s, mobilityForces, bodyForces, ws.udot, ws.A_GB);
        nodeAccelerations(s, ws.A_GB, ws.a0);
        // Node mobility Lambda: node accelerations per unit node force.
        ws.Lambda.resize(3 * m, 3 * m);
        if (!anyConstraintEnabled(s)) {
            // No constraint: Lambda = J M^-1 J^T with J the nodes' station Jacobian (3m x nu), one
            // O(n) multiplyByMInv per column. multiplyByMInv leaves prescribed mobilities' udot at 0,
            // as prescribed (and locked) motion does not respond to forces.
            matter().calcStationJacobian(s, mobileBodies_, mobileStations_, ws.stationJacobian);
            const int nu = ws.stationJacobian.ncol();
            ws.generalizedForce.resize(nu);
            for (int col = 0; col < 3 * m; ++col) {
                for (int i = 0; i < nu; ++i) ws.generalizedForce[i] = ws.stationJacobian(col, i);
                matter().multiplyByMInv(s, ws.generalizedForce, ws.udotUnit);
                for (int row = 0; row <= col; ++row) {
                    double acc = 0;
                    for (int i = 0; i < nu; ++i) acc += ws.stationJacobian(row, i) * ws.udotUnit[i];
                    ws.Lambda(row, col) = ws.Lambda(col, row) = acc;  // symmetric
                }
            }
        } else {
            // Constraints: calcAcceleration honours them; Lambda by differences, one call per column.
            for (int col = 0; col < 3 * m; ++col) {
                ws.bodyForcesUnit = bodyForces;
                Vec3 unit(0);
                unit[col % 3] = 1.0;
                mobileNodes_[col / 3].body->applyForceToBodyPoint(s, mobileNodes_[col / 3].station, unit,
                                                                  ws.bodyForcesUnit);
                matter().calcAcceleration(s, mobilityForces, ws.bodyForcesUnit, ws.udot, ws.A_GB);
                nodeAccelerations(s, ws.A_GB, ws.aUnit);
                ws.Lambda.col(col) = ws.aUnit - ws.a0;
            }
        }
        // Node forces on the rope: (I + S Lambda) f = S a0 - h; the bodies receive -f.
        ws.lhs.noalias() = ws.S * ws.Lambda;
        ws.lhs.diagonal().array() += 1.0;
        ws.rhs.noalias() = ws.S * ws.a0;
        ws.rhs -= ws.h;
        ws.lu.compute(ws.lhs);
        ws.f = ws.lu.solve(ws.rhs);
        ws.rdd = ws.a0;
        ws.rdd.noalias() -= ws.Lambda * ws.f;
        for (int a = 0; a < m; ++a)
            mobileNodes_[a].body->applyForceToBodyPoint(s, mobileNodes_[a].station,
                                                        -toSimTK(ws.f.segment<3>(3 * a)), bodyForces);
    }

    // Modal accelerations of every rope.
    Vector& zdot = updZDot(s);
    const Vector& z = getZ(s);
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeRecord& r = ropes[i];
        RopeCache& c = pc.ropes[i];
        c.nodeAccelerations3.setZero(3, r.numNodes());
        for (int a = 0; a < m; ++a)
            if (mobileNodes_[a].rope == static_cast<int>(i))
                c.nodeAccelerations3.col(mobileNodes_[a].node) = ws.rdd.segment<3>(3 * a);
        if (r.planar) {
            c.nodeAccelerations2.noalias() = r.planeBasis.transpose() * c.nodeAccelerations3;
            const Eigen::Map<const Eigen::VectorXd> a(c.nodeAccelerations2.data(), c.nodeAccelerations2.size());
            r.planarModel->modalAccelerations(c.planar, a, c.modalAccelerations);
            r.planarModel->recoverInertialStrain(c.planar, a, c.modalAccelerations);
        } else {
            const Eigen::Map<const Eigen::VectorXd> a(c.nodeAccelerations3.data(), c.nodeAccelerations3.size());
            r.spatialModel->modalAccelerations(c.spatial, a, c.modalAccelerations);
            r.spatialModel->recoverInertialStrain(c.spatial, a, c.modalAccelerations);
        }
        for (int j = 0; j < r.numModal; ++j) {
            zdot[r.zOffset + j] = z[r.zOffset + r.numModal + j];
            zdot[r.zOffset + r.numModal + j] = c.modalAccelerations[j];
        }
    }
    return 0;
}

bool ReevingSubsystem::Guts::anyConstraintEnabled(const State& s) const {
    const SimbodyMatterSubsystem& mat = matter();
    for (SimTK::ConstraintIndex c(0); c < mat.getNumConstraints(); ++c)
        if (!mat.isConstraintDisabled(s, c)) return true;
    return false;
}

Eigen::Matrix3d ReevingSubsystem::Guts::nodeMass3(const RopeRecord& r, const RopeCache& c, int a, int b) const {
    if (!r.planar) return c.spatial.nodeMass.block<3, 3>(3 * a, 3 * b);
    Eigen::Matrix<double, 3, 2> E;
    E << r.e1, r.e2;
    return E * c.planar.nodeMass.block<2, 2>(2 * a, 2 * b) * E.transpose();
}
Eigen::Vector3d ReevingSubsystem::Guts::nodeForce3(const RopeRecord& r, const RopeCache& c, int a) const {
    if (!r.planar) return c.spatial.nodeForce.segment<3>(3 * a);
    return r.e1 * c.planar.nodeForce[2 * a] + r.e2 * c.planar.nodeForce[2 * a + 1];
}

void ReevingSubsystem::Guts::nodeAccelerations(const State& s, const Vector_<SpatialVec>& A_GB,
                                               Eigen::VectorXd& a) const {
    a.resize(3 * static_cast<Eigen::Index>(mobileNodes_.size()));
    for (size_t k = 0; k < mobileNodes_.size(); ++k) {
        const MobilizedBody& b = *mobileNodes_[k].body;
        const SpatialVec& A = A_GB[b.getMobilizedBodyIndex()];
        const Vec3 p = b.getBodyRotation(s) * mobileNodes_[k].station;
        const Vec3& w = b.getBodyAngularVelocity(s);
        a.segment<3>(3 * static_cast<Eigen::Index>(k)) = toEigen(A[1] + A[0] % p + w % (w % p));
    }
}

}  // namespace SimbodyReeving
