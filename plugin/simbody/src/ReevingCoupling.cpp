// ReevingSubsystem::Guts: realizeDynamics, the coupled rope/body solve (free accelerations of the
// coupled coordinates, their mobility Lambda, the Schur complement on the rope's support forces,
// modal accelerations).

#include "ReevingSubsystemGuts.h"

#include <algorithm>

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
// (RopeCoupling), so the rope's S and h enter as the matching entries; a driven s = s_ref + g(theta)
// moves with its angle: its row of the Jacobian is g'(theta) times the angle's row (DrivenAngleRow:
// the pin's mobility, or the sheave body's angular velocity about an axis), its acceleration
// law.acceleration(theta, thetadot, thetaddot), and a force f_s on it is the generalized force
// g'(theta) f_s on the angle.
int ReevingSubsystem::Guts::realizeSubsystemDynamicsImpl(const State& s) const {
    // Force::Gravity's magnitude and direction are State parameters (they invalidate
    // Stage::Dynamics); the ropes were built with gravity_.
    checkStateGravity(s);
    PositionCache& pc = updPositionCache(s);
    refreshFromZ(s, pc, true);
    CouplingWorkspace& ws = pc.coupling;
    Vector_<SpatialVec>& bodyForces = mbs().updRigidBodyForces(s, Stage::Dynamics);
    Vector& mobilityForces = mbs().updMobilityForces(s, Stage::Dynamics);

    const int m = static_cast<int>(mobileNodes_.size()), na = static_cast<int>(mobileAngles_.size());
    const int ns = numStationRows_, n = ns + na;
    // Traction sheaves slipping with TractionSlip::RopeMomentum: the friction's reaction on the pin
    // is an applied force; Y is condensed out of its rope: with F the Y indices and g_F the momentum
    // balance's right sides, S' = S - S_xF S_FF^-1 S_Fx and h' = h - S_xF S_FF^-1 g_F on the others.
    condenseMomentumSlips(s, pc, mobilityForces, bodyForces);
    ws.h.setZero(n);
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeCoupling& rc = ropeCoupling_[i];
        const RopeCache& c = pc.ropes[i];
        const Eigen::VectorXd& h = c.condensed ? c.condensedForce : ropes[i].planar ? c.planar.nodeForce : c.spatial.nodeForce;
        for (size_t b = 0; b < rc.rows.size(); ++b) ws.h[rc.rows[b]] = h[rc.external[b]];
    }
    // S on the coupled rows, for the routes that need it whole (constraints; fewer rows than
    // mobilities): each rope's nodeMass, formed now if computeDynamics skipped it.
    auto assembleS = [&]() {
        ws.S.setZero(n, n);
        for (size_t i = 0; i < ropes.size(); ++i) {
            const RopeCoupling& rc = ropeCoupling_[i];
            if (rc.rows.empty()) continue;
            RopeCache& c = pc.ropes[i];
            if (ropes[i].planar ? c.planar.nodeMass.size() == 0 : c.spatial.nodeMass.size() == 0) {
                const int nx = ropes[i].numExternal();
                if (ropes[i].planar)
                    c.planarModel->multiplyByNodeMass(c.planar, Eigen::MatrixXd::Identity(nx, nx), c.planar.nodeMass);
                else
                    spatialModel(s, ropes[i]).multiplyByNodeMass(c.spatial, Eigen::MatrixXd::Identity(nx, nx),
                                                                c.spatial.nodeMass);
            }
            const Eigen::MatrixXd& S = c.condensed ? c.condensedMass : ropes[i].planar ? c.planar.nodeMass : c.spatial.nodeMass;
            const int k = static_cast<int>(rc.rows.size());
            for (int b = 0; b < k; ++b)
                for (int a = 0; a < k; ++a) ws.S(rc.rows[a], rc.rows[b]) = S(rc.external[a], rc.external[b]);
        }
    };
    bool products = false;

    ws.f.setZero(n);
    ws.rdd.setZero(n);
    if (n > 0) {
        // Per evaluation, once: each mobile node's offset R_GB station from its body's origin (in
        // Ground, from the body transforms of this realization), each driven angle's row (its
        // DrivenAngle unit) and its law's slope g'(theta).
        ws.nodeOffsets.resize(m);
        for (int a = 0; a < m; ++a) ws.nodeOffsets[a] = pc.bodyX[mobileNodes_[a].slot].R() * mobileNodes_[a].station;
        ws.angleRows.resize(na);
        ws.angleSlopes.resize(na);
        for (int a = 0; a < na; ++a) {
            const MobileAngle& ma = mobileAngles_[a];
            const RopeRecord::DrivenNode& d = ropes[ma.rope].driven[ma.driven];
            d.angle.row(angleSite(s, ropes[ma.rope], d), ws.angleRows[a]);
            ws.angleSlopes[a] = d.law.slope(pc.ropes[ma.rope].drivenAngles[ma.driven]);
        }
        // Free accelerations a0 under every force applied so far (prescribed motion included).
        // Without an enabled constraint calcAcceleration is the tree operator itself.
        const bool constrained = anyConstraintEnabled(s);
        if (constrained)
            matter().calcAcceleration(s, mobilityForces, bodyForces, ws.udot, ws.A_GB);
        else
            matter().calcAccelerationIgnoringConstraints(s, mobilityForces, bodyForces, ws.udot, ws.A_GB);
        couplingAccelerations(pc, ws.A_GB, ws.udot, ws.a0);
        // Mobility Lambda: accelerations of y per unit force on y.
        ws.Lambda.resize(n, n);
        if (!constrained) {
            mobilityLambda(s, ws);
            products = static_cast<int>(ws.U.size()) <= n && ws.freeSlips.empty();
            if (!products) {
                // (The product route keeps Lambda in its factors; a condensed rope needs S whole.)
                if (static_cast<int>(ws.U.size()) <= n) ws.Lambda.noalias() = ws.JUMinv * ws.JU.transpose();
                assembleS();
            }
        } else {
            assembleS();
            // Constraints: calcAcceleration honours them; Lambda by differences, one call per column.
            for (int col = 0; col < n; ++col) {
                ws.bodyForcesUnit = bodyForces;
                ws.mobilityForcesUnit = mobilityForces;
                if (col < ns) {
                    const auto [a, d] = rowOwner_[col];
                    const Vec3 dir = toSimTK(mobileNodes_[a].directions.col(d));
                    ws.bodyForcesUnit[mobileNodes_[a].bodyIndex] += SpatialVec(ws.nodeOffsets[a] % dir, dir);
                } else {
                    ws.angleRows[col - ns].addGeneralizedForce(ws.angleSlopes[col - ns], ws.mobilityForcesUnit,
                                                               ws.bodyForcesUnit);
                }
                matter().calcAcceleration(s, ws.mobilityForcesUnit, ws.bodyForcesUnit, ws.udot, ws.A_GB);
                couplingAccelerations(pc, ws.A_GB, ws.udot, ws.aUnit);
                ws.Lambda.col(col) = ws.aUnit - ws.a0;
            }
        }
        // Support forces on the rope: (I + S Lambda) f = S a0 - h; the bodies receive -f. With
        // Lambda = J_U Minv_UU J_U^T (k <= n mobilities), S Lambda = (S J_U) (J_U Minv_UU)^T and S a0
        // come from k + 1 products per rope (one block solve of its chain), not from S itself.
        if (products) {
            const int k = static_cast<int>(ws.U.size());
            ws.SJ.setZero(n, k + 1);
            for (size_t i = 0; i < ropes.size(); ++i) {
                const RopeCoupling& rc = ropeCoupling_[i];
                if (rc.rows.empty()) continue;
                const RopeRecord& r = ropes[i];
                RopeCache& c = pc.ropes[i];
                ws.ropeX.setZero(r.numExternal(), k + 1);
                for (size_t a = 0; a < rc.rows.size(); ++a) {
                    ws.ropeX.row(rc.external[a]).head(k) = ws.JU.row(rc.rows[a]);
                    ws.ropeX(rc.external[a], k) = ws.a0[rc.rows[a]];
                }
                if (r.planar)
                    c.planarModel->multiplyByNodeMass(c.planar, ws.ropeX, ws.ropeSX);
                else
                    spatialModel(s, r).multiplyByNodeMass(c.spatial, ws.ropeX, ws.ropeSX);
                for (size_t a = 0; a < rc.rows.size(); ++a) ws.SJ.row(rc.rows[a]) = ws.ropeSX.row(rc.external[a]);
            }
            ws.rhs = ws.SJ.col(k) - ws.h;
            // I + S Lambda = I + A B^T with A = S J_U, B = J_U Minv_UU (n x k each), so by the
            // Woodbury identity f = r - A (I_k + B^T A)^-1 B^T r: a k x k factorization, not n x n.
            ws.f = ws.rhs;
            if (k > 0) {  // no mobilities (coupled coordinates on prescribed bodies only): f = r
                ws.lhs.noalias() = ws.JUMinv.transpose() * ws.SJ.leftCols(k);
                ws.lhs.diagonal().array() += 1.0;
                ws.lu.compute(ws.lhs);
                ws.reducedRhs.noalias() = ws.JUMinv.transpose() * ws.rhs;
                ws.reducedSolution = ws.lu.solve(ws.reducedRhs);
                ws.f.noalias() -= ws.SJ.leftCols(k) * ws.reducedSolution;
            }
        } else {
            ws.rhs.noalias() = ws.S * ws.a0;
            ws.rhs -= ws.h;
            ws.lhs.noalias() = ws.S * ws.Lambda;
            ws.lhs.diagonal().array() += 1.0;
            ws.lu.compute(ws.lhs);
            ws.f = ws.lu.solve(ws.rhs);
        }
        // Product route: rdd = a0 - Lambda f = a0 - J_U z with z = Minv_UU J_U^T f (Lambda itself
        // is not formed), i.e. [J_U | a0] [-z; 1], the columns each rope has just solved for
        // (multiplyByNodeMass): its modal accelerations are the same combination of those solutions
        // (no further solve of its chain).
        ws.rdd = ws.a0;
        if (products) {
            const int k = static_cast<int>(ws.U.size());
            ws.productWeights.resize(k + 1);
            ws.productWeights.head(k).noalias() = -(ws.JUMinv.transpose() * ws.f);
            ws.productWeights[k] = 1.0;
            ws.rdd.noalias() += ws.JU.lazyProduct(ws.productWeights.head(k));
        } else {
            ws.rdd.noalias() -= ws.Lambda * ws.f;
        }
        // MobilizedBody::applyForceToBodyPoint / applyOneMobilityForce, with this evaluation's
        // offsets and u indices.
        for (int a = 0; a < m; ++a) {
            const MobileNode& mn = mobileNodes_[a];
            const Vec3 force = -toSimTK(mn.directions.leftCols(mn.dims) * ws.f.segment(mn.row, mn.dims));
            bodyForces[mn.bodyIndex] += SpatialVec(ws.nodeOffsets[a] % force, force);
        }
        for (int a = 0; a < na; ++a)  // on the pin's mobility, or a torque about the groove's axis
            ws.angleRows[a].addGeneralizedForce(-ws.angleSlopes[a] * ws.f[ns + a], mobilityForces, bodyForces);
    }

    productCoupling_ = products;

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
        if (c.condensed) recoverMomentumSlips(pc, static_cast<int>(i));
        c.nodeAccelerations3.setZero(3, r.numNodes());
        for (int k = 0; k < r.numNodes(); ++k) {
            if (r.planar)
                c.nodeAccelerations3.col(k) = r.planeBasis * c.externalAccelerations.segment<2>(2 * k);
            else
                c.nodeAccelerations3.col(k) = c.externalAccelerations.segment<3>(3 * k);
        }
        if (products && !rc.rows.empty()) {
            if (r.planar)
                c.planarModel->modalAccelerationsFromLastProduct(c.planar, ws.productWeights, c.modalAccelerations);
            else
                spatialModel(s, r).modalAccelerationsFromLastProduct(c.spatial, ws.productWeights, c.modalAccelerations);
        } else if (r.planar) {
            c.planarModel->modalAccelerations(c.planar, c.externalAccelerations, c.modalAccelerations);
        } else {
            spatialModel(s, r).modalAccelerations(c.spatial, c.externalAccelerations, c.modalAccelerations);
        }
        if (r.planar) {
            c.planarModel->recoverInertialStrain(c.planar, c.externalAccelerations, c.modalAccelerations);
        } else {
            spatialModel(s, r).recoverInertialStrain(c.spatial, c.externalAccelerations, c.modalAccelerations);
        }
        for (int j = 0; j < r.numModal; ++j) {
            zdot[r.zOffset + j] = z[r.zOffset + r.numModal + j];
            zdot[r.zOffset + r.numModal + j] = c.modalAccelerations[j];
        }
        if (r.dampingZOffset >= 0) zdot[r.dampingZOffset] = r.planar ? c.planar.dampingPower : c.spatial.dampingPower;
        // The driven nodes' own Z entries (a TractionSheave's friction work and slip states).
        for (int d = 0; d < static_cast<int>(r.driven.size()); ++d)
            r.driven[d].role.zDerivatives(r.drivenRun(*this, d), s, c, ws, z, zdot);
    }
    return 0;
}

// Lambda = J M^-1 J^T without Simbody constraints, J the Jacobian of y (n rows). J is nonzero only
// at the mobilities U of the mobile bodies' paths to Ground (the pins' included), so
// Lambda = J_U (M^-1)_UU J_U^T exactly, (M^-1)_UU the U block of the whole tree's inverse (the
// other bodies' inertia enters through it). multiplyByMInv leaves prescribed mobilities' udot at 0
// and ignores their forces, as prescribed (and locked) motion does not respond to forces, so their
// rows and columns of (M^-1)_UU are 0. With k = |U|, each of the two ways costs O(size of the tree)
// Simbody operations (no station Jacobian filled element by element):
//  - k <= n (e.g. the 12-fall crane: 27 rows, k = 5): per mobility i of U, one multiplyBySystemJacobian
//    of the unit speed e_i gives every body's spatial velocity V_i, hence column i of J_U for all
//    rows at once (row (node, direction d) = d . (v + w x p), p = R_GB station: one body pass), and
//    one multiplyByMInv(e_i) gives column i of (M^-1)_UU; then J_U (M^-1)_UU. Lambda stays in these
//    factors: the coupled solve takes the k x k Woodbury form of (I + S Lambda) f = S a0 - h, and
//    Lambda f = J_U ((M^-1)_UU J_U^T f).
//  - n < k (e.g. the pendulum: 2 rows on a 6-mobility free body): per row r, one
//    multiplyBySystemJacobianTranspose of the row's unit spatial force (p x d, d) at its body gives
//    J_r^T, one multiplyByMInv of it gives M^-1 J_r^T, and Lambda's column r is J_U times that.
void ReevingSubsystem::Guts::mobilityLambda(const State& s, CouplingWorkspace& ws) const {
    const int ns = numStationRows_, na = static_cast<int>(mobileAngles_.size()), n = ns + na;
    const int nu = s.getNU();
    // U: the mobilities the coupled coordinates depend on (sorted, unique).
    ws.U.clear();
    ws.U.reserve(nu);  // capacity kept: no allocation per evaluation
    for (const MobilizedBody* body : bodySlots_)  // every node's body (the pins' included), once
        for (const MobilizedBody* b = body; b->getMobilizedBodyIndex() != SimTK::GroundIndex;
             b = &b->getParentMobilizedBody()) {  // (by index: isGround() is a dynamic_cast)
            const int first = static_cast<int>(b->getFirstUIndex(s)), count = b->getNumU(s);
            for (int j = 0; j < count; ++j) ws.U.push_back(first + j);
        }
    std::sort(ws.U.begin(), ws.U.end());
    ws.U.erase(std::unique(ws.U.begin(), ws.U.end()), ws.U.end());
    const int k = static_cast<int>(ws.U.size());
    ws.JU.setZero(n, k);
    ws.udotUnit.resize(nu);
    for (int a = 0; a < na; ++a)  // driven rows on a mobility: g'(theta) there (body rows below)
        if (const DrivenAngleRow& row = ws.angleRows[a]; row.onMobility())
            ws.JU(ns + a, std::lower_bound(ws.U.begin(), ws.U.end(), row.mobility) - ws.U.begin()) = ws.angleSlopes[a];
    if (k <= n) {
        ws.MinvUU.resize(k, k);
        ws.generalizedForce.resize(nu);
        ws.generalizedForce = 0;
        for (int c = 0; c < k; ++c) {
            ws.generalizedForce[ws.U[c]] = 1;
            matter().multiplyBySystemJacobian(s, ws.generalizedForce, ws.bodyVelocities);
            for (const MobileNode& mn : mobileNodes_) {
                const SpatialVec& V = ws.bodyVelocities[mn.bodyIndex];
                const Vec3 v = V[1] + V[0] % ws.nodeOffsets[&mn - mobileNodes_.data()];
                for (int d = 0; d < mn.dims; ++d)
                    ws.JU(mn.row + d, c) = mn.directions(0, d) * v[0] + mn.directions(1, d) * v[1] + mn.directions(2, d) * v[2];
            }
            for (int a = 0; a < na; ++a)  // driven body rows: g'(theta) (axis . omega) of the sheave
                if (const DrivenAngleRow& row = ws.angleRows[a]; !row.onMobility())
                    ws.JU(ns + a, c) = ws.angleSlopes[a] * row.bodyRate(ws.bodyVelocities);
            matter().multiplyByMInv(s, ws.generalizedForce, ws.udotUnit);
            for (int r = 0; r < k; ++r) ws.MinvUU(r, c) = ws.udotUnit[ws.U[r]];
            ws.generalizedForce[ws.U[c]] = 0;
        }
        // Lambda = JUMinv J_U^T is not formed: the product route (k <= n) uses its factors.
        ws.JUMinv.noalias() = ws.JU * ws.MinvUU;
        return;
    }
    // n < k: Lambda column by column.
    ws.bodyForces.resize(matter().getNumBodies());
    ws.bodyForces = SpatialVec(Vec3(0), Vec3(0));
    for (int r = 0; r < ns; ++r) {
        const auto [a, d] = rowOwner_[r];
        const MobileNode& mn = mobileNodes_[a];
        const Vec3 dir = toSimTK(mn.directions.col(d));
        ws.bodyForces[mn.bodyIndex] = SpatialVec(ws.nodeOffsets[a] % dir, dir);
        matter().multiplyBySystemJacobianTranspose(s, ws.bodyForces, ws.generalizedForce);
        for (int c = 0; c < k; ++c) ws.JU(r, c) = ws.generalizedForce[ws.U[c]];
        ws.bodyForces[mn.bodyIndex] = SpatialVec(Vec3(0), Vec3(0));
    }
    for (int a = 0; a < na; ++a) {  // driven body rows: the torque g'(theta) about the axis
        const DrivenAngleRow& row = ws.angleRows[a];
        if (row.onMobility()) continue;
        ws.bodyForces[row.body] = row.bodyTorque(ws.angleSlopes[a]);
        matter().multiplyBySystemJacobianTranspose(s, ws.bodyForces, ws.generalizedForce);
        for (int c = 0; c < k; ++c) ws.JU(ns + a, c) = ws.generalizedForce[ws.U[c]];
        ws.bodyForces[row.body] = SpatialVec(Vec3(0), Vec3(0));
    }
    ws.generalizedForce.resize(nu);
    ws.responseU.resize(k);
    for (int col = 0; col < n; ++col) {
        ws.generalizedForce = 0;
        for (int c = 0; c < k; ++c) ws.generalizedForce[ws.U[c]] = ws.JU(col, c);
        matter().multiplyByMInv(s, ws.generalizedForce, ws.udotUnit);
        for (int c = 0; c < k; ++c) ws.responseU[c] = ws.udotUnit[ws.U[c]];
        ws.Lambda.col(col).noalias() = ws.JU * ws.responseU;
    }
}

bool ReevingSubsystem::Guts::anyConstraintEnabled(const State& s) const {
    const SimbodyMatterSubsystem& mat = matter();
    for (SimTK::ConstraintIndex c(0); c < mat.getNumConstraints(); ++c)
        if (!mat.isConstraintDisabled(s, c)) return true;
    return false;
}

Eigen::VectorXd ReevingSubsystem::Guts::ropeReaction(const State& s, const RopeRecord& r, const RopeCache& c) const {
    const Eigen::MatrixXd& S = r.planar ? c.planar.nodeMass : c.spatial.nodeMass;
    Eigen::VectorXd f = r.planar ? c.planar.nodeForce : c.spatial.nodeForce;
    if (S.size() > 0) {
        f.noalias() -= S * c.externalAccelerations;
        return f;
    }
    Eigen::MatrixXd Sx;  // S not formed (product coupling): S xddot by one solve
    if (r.planar)
        c.planarModel->multiplyByNodeMass(c.planar, c.externalAccelerations, Sx);
    else
        spatialModel(s, r).multiplyByNodeMass(c.spatial, c.externalAccelerations, Sx);
    f -= Sx.col(0);
    return f;
}

void ReevingSubsystem::Guts::couplingAccelerations(const PositionCache& pc, const Vector_<SpatialVec>& A_GB,
                                                   const Vector& udot, Eigen::VectorXd& a) const {
    const Eigen::Index ns = numStationRows_;
    const CouplingWorkspace& ws = pc.coupling;
    a.resize(ns + static_cast<Eigen::Index>(mobileAngles_.size()));
    for (size_t i = 0; i < mobileNodes_.size(); ++i) {
        const MobileNode& mn = mobileNodes_[i];
        const SpatialVec& A = A_GB[mn.bodyIndex];
        const Vec3& p = ws.nodeOffsets[i];
        const Vec3& w = pc.bodyV[mn.slot][0];
        const Eigen::Vector3d a3 = toEigen(A[1] + A[0] % p + w % (w % p));
        a.segment(mn.row, mn.dims).noalias() = mn.directions.leftCols(mn.dims).transpose() * a3;
    }
    for (size_t d = 0; d < mobileAngles_.size(); ++d) {  // sddot = law.acceleration(theta, thetadot, thetaddot)
        const MobileAngle& ma = mobileAngles_[d];
        const RopeCache& c = pc.ropes[ma.rope];
        a[ns + static_cast<Eigen::Index>(d)] = ropes[ma.rope].driven[ma.driven].law.acceleration(
            c.drivenAngles[ma.driven], c.drivenAngleRates[ma.driven], ws.angleRows[d].acceleration(A_GB, udot));
    }
}


// Coordinates of a rope alone (no body; a TractionSlip::RopeMomentum sheave's slip state Y in
// slip) that move by their own balance: with F their indices in a rope and g_F their balances'
// right sides, S' = S - S_xF S_FF^-1 S_Fx and h' = h - S_xF S_FF^-1 g_F on the other coordinates
// (rows and columns F zero), so the coupled solve sees the rope with them moving as their
// balances say. The driven nodes register them (DrivenRole::condense).
void ReevingSubsystem::Guts::condenseMomentumSlips(const State& s, PositionCache& pc, Vector& mobilityForces,
                                                   Vector_<SpatialVec>& bodyForces) const {
    CouplingWorkspace& ws = pc.coupling;
    ws.freeSlips.clear();
    for (const RopeRecord& r : ropes) {
        pc.ropes[r.index].condensed = false;
        for (int d = 0; d < static_cast<int>(r.driven.size()); ++d)
            r.driven[d].role.condense(r.drivenRun(*this, d), s, ws, mobilityForces, bodyForces);
    }
    for (const RopeRecord& r : ropes) {
        ws.freeIndex.clear();
        for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
            if (f.rope == r.index) ws.freeIndex.push_back(f.external);
        if (ws.freeIndex.empty()) continue;
        RopeCache& c = pc.ropes[r.index];
        const int nx = r.numExternal(), nf = static_cast<int>(ws.freeIndex.size());
        const Eigen::MatrixXd& S = withRope(r, c, [&](const auto& model, auto& data) -> const Eigen::MatrixXd& {
            if (data.nodeMass.size() == 0)
                model.multiplyByNodeMass(data, Eigen::MatrixXd::Identity(nx, nx), data.nodeMass);
            return data.nodeMass;
        });
        ws.freeSxF.resize(nx, nf);
        ws.freeSFF.resize(nf, nf);
        ws.freeDrive.resize(nf);
        int a = 0;
        for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
            if (f.rope == r.index) ws.freeDrive[a++] = f.drive;
        for (a = 0; a < nf; ++a) {
            ws.freeSxF.col(a) = S.col(ws.freeIndex[a]);
            for (int b = 0; b < nf; ++b) ws.freeSFF(a, b) = S(ws.freeIndex[a], ws.freeIndex[b]);
        }
        for (a = 0; a < nf; ++a) ws.freeSxF.row(ws.freeIndex[a]).setZero();  // the others' rows only
        ws.freeLdlt.compute(ws.freeSFF);
        ws.freeSolve = ws.freeLdlt.solve(ws.freeSxF.transpose());
        c.condensedMass = S;
        c.condensedMass.noalias() -= ws.freeSxF * ws.freeSolve;
        ws.freeAcceleration = ws.freeLdlt.solve(ws.freeDrive);
        c.condensedForce = withRope(r, c, [](const auto&, const auto& data) -> const Eigen::VectorXd& { return data.nodeForce; });
        c.condensedForce.noalias() -= ws.freeSxF * ws.freeAcceleration;
        for (a = 0; a < nf; ++a) {
            c.condensedMass.row(ws.freeIndex[a]).setZero();
            c.condensedMass.col(ws.freeIndex[a]).setZero();
            c.condensedForce[ws.freeIndex[a]] = 0;
        }
        c.condensed = true;
    }
}

void ReevingSubsystem::Guts::recoverMomentumSlips(PositionCache& pc, int rope) const {
    CouplingWorkspace& ws = pc.coupling;
    RopeCache& c = pc.ropes[rope];
    ws.freeIndex.clear();
    for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
        if (f.rope == rope) ws.freeIndex.push_back(f.external);
    const int nf = static_cast<int>(ws.freeIndex.size());
    const Eigen::MatrixXd& S =
        withRope(ropes[rope], c, [](const auto&, const auto& data) -> const Eigen::MatrixXd& { return data.nodeMass; });
    ws.freeDrive.resize(nf);
    ws.freeSFF.resize(nf, nf);
    int a = 0;
    for (const CouplingWorkspace::FreeSlip& f : ws.freeSlips)
        if (f.rope == rope) ws.freeDrive[a++] = f.drive;
    for (a = 0; a < nf; ++a) c.externalAccelerations[ws.freeIndex[a]] = 0;
    for (a = 0; a < nf; ++a) {
        ws.freeDrive[a] -= S.row(ws.freeIndex[a]).dot(c.externalAccelerations);
        for (int b = 0; b < nf; ++b) ws.freeSFF(a, b) = S(ws.freeIndex[a], ws.freeIndex[b]);
    }
    ws.freeLdlt.compute(ws.freeSFF);
    ws.freeAcceleration = ws.freeLdlt.solve(ws.freeDrive);
    for (a = 0; a < nf; ++a) c.externalAccelerations[ws.freeIndex[a]] = ws.freeAcceleration[a];
}

}  // namespace SimbodyReeving
