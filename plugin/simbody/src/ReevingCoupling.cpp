// ReevingSubsystem::Guts: realizeDynamics, the coupled rope/body solve (free accelerations of the
// coupled coordinates, their mobility Lambda, the Schur complement on the rope's support forces,
// modal accelerations).

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

// The coupled vector y = [positions in Ground of the mobile nodes (3 each) | driven material
// coordinates (1 each)]. Each rope's external coordinates x map into it by a selection
// (RopeCoupling), so the rope's S and h enter as the matching entries; a driven s = s_ref + dsdTheta
// theta moves with its pin: its row of the Jacobian is dsdTheta at the pin's mobility, and a
// force f_s on it is the generalized force dsdTheta f_s on the pin.
int ReevingSubsystem::Guts::realizeSubsystemDynamicsImpl(const State& s) const {
    // Force::Gravity's magnitude and direction are State parameters (they invalidate
    // Stage::Dynamics); the ropes were built with gravity_.
    checkStateGravity(s);
    PositionCache& pc = Value<PositionCache>::updDowncast(updCacheEntry(s, positionCache_));
    refreshFromZ(s, pc, true);
    CouplingWorkspace& ws = pc.coupling;
    Vector_<SpatialVec>& bodyForces = mbs().updRigidBodyForces(s, Stage::Dynamics);
    Vector& mobilityForces = mbs().updMobilityForces(s, Stage::Dynamics);

    const int m = static_cast<int>(mobileNodes_.size()), na = static_cast<int>(mobileAngles_.size());
    const int ns = numStationRows_, n = ns + na;
    ws.S.setZero(n, n);
    ws.h.setZero(n);
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeCoupling& rc = ropeCoupling_[i];
        if (rc.rows.empty()) continue;
        const RopeCache& c = pc.ropes[i];
        const RopeData<2>* d2 = ropes[i].planar ? &c.planar : nullptr;
        const Eigen::MatrixXd& S = d2 ? d2->nodeMass : c.spatial.nodeMass;
        const Eigen::VectorXd& h = d2 ? d2->nodeForce : c.spatial.nodeForce;
        const int k = static_cast<int>(rc.rows.size());
        for (int b = 0; b < k; ++b) {
            ws.h[rc.rows[b]] = h[rc.external[b]];
            for (int a = 0; a < k; ++a) ws.S(rc.rows[a], rc.rows[b]) = S(rc.external[a], rc.external[b]);
        }
    }

    ws.f.setZero(n);
    ws.rdd.setZero(n);
    if (n > 0) {
        // Free accelerations a0 under every force applied so far (prescribed motion included).
        matter().calcAcceleration(s, mobilityForces, bodyForces, ws.udot, ws.A_GB);
        couplingAccelerations(s, ws.A_GB, ws.udot, ws.a0);
        // Mobility Lambda: accelerations of y per unit force on y.
        ws.Lambda.resize(n, n);
        if (!anyConstraintEnabled(s)) {
            // No constraint: Lambda = J M^-1 J^T with J the Jacobian of y (station rows from
            // calcStationJacobian, driven rows dsdTheta at the pin's mobility), one O(n)
            // multiplyByMInv per column. multiplyByMInv leaves prescribed mobilities' udot at 0,
            // as prescribed (and locked) motion does not respond to forces.
            const int nu = s.getNU();
            ws.J.setZero(n, nu);
            if (m > 0) {
                matter().calcStationJacobian(s, mobileBodies_, mobileStations_, ws.stationJacobian);
                for (int row = 0; row < ns; ++row) {
                    const auto [a, d] = rowOwner_[row];
                    const Eigen::Vector3d dir = mobileNodes_[a].directions.col(d);
                    for (int i = 0; i < nu; ++i)
                        ws.J(row, i) = dir[0] * ws.stationJacobian(3 * a, i) + dir[1] * ws.stationJacobian(3 * a + 1, i) +
                                       dir[2] * ws.stationJacobian(3 * a + 2, i);
                }
            }
            for (int a = 0; a < na; ++a)
                ws.J(ns + a, static_cast<int>(mobileAngles_[a].body->getFirstUIndex(s))) = mobileAngles_[a].dsdTheta;
            ws.generalizedForce.resize(nu);
            for (int col = 0; col < n; ++col) {
                for (int i = 0; i < nu; ++i) ws.generalizedForce[i] = ws.J(col, i);
                matter().multiplyByMInv(s, ws.generalizedForce, ws.udotUnit);
                for (int row = 0; row <= col; ++row) {
                    double acc = 0;
                    for (int i = 0; i < nu; ++i) acc += ws.J(row, i) * ws.udotUnit[i];
                    ws.Lambda(row, col) = ws.Lambda(col, row) = acc;  // symmetric
                }
            }
        } else {
            // Constraints: calcAcceleration honours them; Lambda by differences, one call per column.
            for (int col = 0; col < n; ++col) {
                ws.bodyForcesUnit = bodyForces;
                ws.mobilityForcesUnit = mobilityForces;
                if (col < ns) {
                    const MobileNode& mn = mobileNodes_[rowOwner_[col].first];
                    mn.body->applyForceToBodyPoint(s, mn.station, toSimTK(mn.directions.col(rowOwner_[col].second)),
                                                   ws.bodyForcesUnit);
                } else {
                    const MobileAngle& ma = mobileAngles_[col - ns];
                    ma.body->applyOneMobilityForce(s, 0, ma.dsdTheta, ws.mobilityForcesUnit);
                }
                matter().calcAcceleration(s, ws.mobilityForcesUnit, ws.bodyForcesUnit, ws.udot, ws.A_GB);
                couplingAccelerations(s, ws.A_GB, ws.udot, ws.aUnit);
                ws.Lambda.col(col) = ws.aUnit - ws.a0;
            }
        }
        // Support forces on the rope: (I + S Lambda) f = S a0 - h; the bodies receive -f.
        ws.lhs.noalias() = ws.S * ws.Lambda;
        ws.lhs.diagonal().array() += 1.0;
        ws.rhs.noalias() = ws.S * ws.a0;
        ws.rhs -= ws.h;
        ws.lu.compute(ws.lhs);
        ws.f = ws.lu.solve(ws.rhs);
        ws.rdd = ws.a0;
        ws.rdd.noalias() -= ws.Lambda * ws.f;
        for (int a = 0; a < m; ++a) {
            const MobileNode& mn = mobileNodes_[a];
            const Eigen::Vector3d force = mn.directions.leftCols(mn.dims) * ws.f.segment(mn.row, mn.dims);
            mn.body->applyForceToBodyPoint(s, mn.station, -toSimTK(force), bodyForces);
        }
        for (int a = 0; a < na; ++a) {
            const MobileAngle& ma = mobileAngles_[a];
            ma.body->applyOneMobilityForce(s, 0, -ma.dsdTheta * ws.f[ns + a], mobilityForces);
        }
    }

    // Modal accelerations of every rope from its external accelerations x_dd = T^T y_dd (zero at
    // Ground nodes).
    Vector& zdot = updZDot(s);
    const Vector& z = getZ(s);
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeRecord& r = ropes[i];
        RopeCache& c = pc.ropes[i];
        const RopeCoupling& rc = ropeCoupling_[i];
        c.externalAccelerations.setZero(r.numExternal());
        for (size_t a = 0; a < rc.rows.size(); ++a) c.externalAccelerations[rc.external[a]] = ws.rdd[rc.rows[a]];
        c.nodeAccelerations3.setZero(3, r.numNodes());
        for (int k = 0; k < r.numNodes(); ++k) {
            if (r.planar)
                c.nodeAccelerations3.col(k) = r.planeBasis * c.externalAccelerations.segment<2>(2 * k);
            else
                c.nodeAccelerations3.col(k) = c.externalAccelerations.segment<3>(3 * k);
        }
        if (r.planar) {
            r.planarModel->modalAccelerations(c.planar, c.externalAccelerations, c.modalAccelerations);
            r.planarModel->recoverInertialStrain(c.planar, c.externalAccelerations, c.modalAccelerations);
        } else {
            const RopeModel<3>& model = spatialModel(s, r);
            model.modalAccelerations(c.spatial, c.externalAccelerations, c.modalAccelerations);
            model.recoverInertialStrain(c.spatial, c.externalAccelerations, c.modalAccelerations);
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

Eigen::VectorXd ReevingSubsystem::Guts::ropeReaction(const RopeRecord& r, const RopeCache& c) const {
    const Eigen::MatrixXd& S = r.planar ? c.planar.nodeMass : c.spatial.nodeMass;
    Eigen::VectorXd f = r.planar ? c.planar.nodeForce : c.spatial.nodeForce;
    f.noalias() -= S * c.externalAccelerations;
    return f;
}

void ReevingSubsystem::Guts::couplingAccelerations(const State& s, const Vector_<SpatialVec>& A_GB,
                                                   const Vector& udot, Eigen::VectorXd& a) const {
    const Eigen::Index ns = numStationRows_;
    a.resize(ns + static_cast<Eigen::Index>(mobileAngles_.size()));
    for (const MobileNode& mn : mobileNodes_) {
        const MobilizedBody& b = *mn.body;
        const SpatialVec& A = A_GB[b.getMobilizedBodyIndex()];
        const Vec3 p = b.getBodyRotation(s) * mn.station;
        const Vec3& w = b.getBodyAngularVelocity(s);
        const Eigen::Vector3d a3 = toEigen(A[1] + A[0] % p + w % (w % p));
        a.segment(mn.row, mn.dims).noalias() = mn.directions.leftCols(mn.dims).transpose() * a3;
    }
    for (size_t d = 0; d < mobileAngles_.size(); ++d)
        a[ns + static_cast<Eigen::Index>(d)] =
            mobileAngles_[d].dsdTheta * udot[static_cast<int>(mobileAngles_[d].body->getFirstUIndex(s))];
}

}  // namespace SimbodyReeving
