#include "SimbodyReeving/ReevingSubsystem.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <memory>
#include <iomanip>
#include <sstream>
#include <stdexcept>

using SimTK::Array_;
using SimTK::CacheEntryIndex;
using SimTK::DecorativeGeometry;
using SimTK::DecorativeLine;
using SimTK::ForceSubsystem;
using SimTK::MobilizedBody;
using SimTK::MultibodySystem;
using SimTK::Real;
using SimTK::SimbodyMatterSubsystem;
using SimTK::SpatialVec;
using SimTK::Stage;
using SimTK::State;
using SimTK::SubsystemIndex;
using SimTK::System;
using SimTK::Value;
using SimTK::Vec3;
using SimTK::Vector;
using SimTK::Vector_;

namespace SimbodyReeving {
namespace {

Eigen::Vector3d toEigen(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 toSimTK(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

bool finite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

[[noreturn]] void invalid(const std::string& what) { throw std::invalid_argument("ReevingSubsystem: " + what); }

std::string str(const Vec3& v) {
    std::ostringstream o;
    o << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return o.str();
}

/// One rope: its spec, its model (planar or spatial) and where its state lives.
struct RopeRecord {
    RopeSpec spec;
    bool planar = false;
    Eigen::Vector3d e1, e2, normal;  // plane basis (planar ropes)
    Eigen::Matrix<double, 3, 2> planeBasis = Eigen::Matrix<double, 3, 2>::Zero();  // [e1 e2]
    std::vector<SpanOptions> spanOptions;
    std::shared_ptr<const RopeModel<2>> planarModel;
    // Spatial spans take their reference frames from the first configuration the rope is
    // evaluated in (after realizeTopology); built lazily, then fixed.
    mutable std::shared_ptr<const RopeModel<3>> spatialModel;
    int numModal = 0;
    int zOffset = 0;  // first Z entry (modal coordinates), rates follow

    int numSpans() const { return static_cast<int>(spec.sheaves.size()) + 1; }
    int numNodes() const { return numSpans() + 1; }
    // Node k: (body, station)
    std::pair<const MobilizedBody*, Vec3> node(int k) const {
        if (k == 0) return {&spec.start.body, spec.start.station};
        if (k == numNodes() - 1) return {&spec.end.body, spec.end.station};
        return {&spec.sheaves[k - 1].body, spec.sheaves[k - 1].centre};
    }
};

/// Per-rope evaluation cache, allocated at Stage::Position. realizeVelocity refreshes its
/// velocity-level part (material rates, span evaluations, the rope reduced to its nodes) every time
/// velocities are realized; velocity-level queries check the stage.
struct RopeCache {
    Eigen::Matrix3Xd nodes3, nodeVelocities3;
    Eigen::Matrix2Xd nodes2, nodeVelocities2;  // planar ropes: in the plane basis
    Eigen::VectorXd modalCoordinates, modalRates;
    RopeData<2> planar;
    RopeData<3> spatial;
    // dynamics
    Eigen::Matrix3Xd nodeAccelerations3;
    Eigen::Matrix2Xd nodeAccelerations2;
    Eigen::VectorXd modalAccelerations;
};

/// Workspace of the coupled rope/body solve (sized once, reused every evaluation).
struct CouplingWorkspace {
    Eigen::MatrixXd S, Lambda, lhs;
    Eigen::VectorXd h, f, rdd, a0, aUnit, rhs;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    Vector udot, generalizedForce, udotUnit;
    SimTK::Matrix stationJacobian;
    Vector_<SpatialVec> A_GB, bodyForcesUnit;
};

struct PositionCache {
    std::vector<RopeCache> ropes;
    CouplingWorkspace coupling;
};

/// A rope node on a body other than Ground: it takes part in the coupled solve.
struct MobileNode {
    int rope = 0, node = 0;
    const MobilizedBody* body = nullptr;
    Vec3 station{0};
};

}  // namespace

class ReevingSubsystem::Guts : public ForceSubsystem::Guts {
public:
    explicit Guts(const Vec3& gravity) : ForceSubsystem::Guts("ReevingSubsystem", "0.1"), gravity_(gravity) {}
    Guts* cloneImpl() const override {
        Guts* copy = new Guts(*this);
        copy->system_ = nullptr;  // a clone belongs to another System
        copy->matter_ = nullptr;
        return copy;
    }

    std::vector<RopeRecord> ropes;
    int decorationPoints = 20;

    // Cached at realizeTopology (MultibodySystem::downcast is a dynamic_cast: not per evaluation).
    const MultibodySystem& mbs() const {
        if (!system_) system_ = &MultibodySystem::downcast(getSystem());
        return *system_;
    }
    const SimbodyMatterSubsystem& matter() const {
        if (!matter_) matter_ = &mbs().getMatterSubsystem();
        return *matter_;
    }
    const Vec3& gravity() const { return gravity_; }

    // ---- realization -----------------------------------------------------------------------
    int realizeSubsystemTopologyImpl(State& s) const override {
        const System& sys = getSystem();
        const SubsystemIndex me = getMySubsystemIndex();
        for (SubsystemIndex i(me + 1); i < sys.getNumSubsystems(); ++i)
            if (dynamic_cast<const ForceSubsystem::Guts*>(&sys.getSubsystem(i).getSubsystemGuts()))
                throw std::logic_error(
                    "ReevingSubsystem: force subsystem '" + sys.getSubsystem(i).getName() +
                    "' was added after the ReevingSubsystem; construct the ReevingSubsystem after every other "
                    "force subsystem (GeneralForceSubsystem included) so it sees all forces in its coupled solve");
        system_ = nullptr;
        matter_ = nullptr;
        int z = 0;
        auto& self = const_cast<Guts&>(*this);
        for (RopeRecord& r : self.ropes) {
            for (int k = 0; k < r.numNodes(); ++k) {
                const MobilizedBody& b = *r.node(k).first;
                if (&b.getMatterSubsystem() != &matter())
                    throw std::logic_error("ReevingSubsystem: rope '" + r.spec.name + "' node " + std::to_string(k) +
                                           " is on a body of another system's matter subsystem");
            }
            r.zOffset = z;
            z += 2 * r.numModal;
            r.spatialModel.reset();
        }
        self.mobileNodes_.clear();
        self.mobileBodies_.clear();
        self.mobileStations_.clear();
        for (size_t i = 0; i < ropes.size(); ++i)
            for (int k = 0; k < ropes[i].numNodes(); ++k) {
                const auto [body, station] = ropes[i].node(k);
                if (body->isGround()) continue;
                self.mobileNodes_.push_back({static_cast<int>(i), k, body, station});
                self.mobileBodies_.push_back(body->getMobilizedBodyIndex());
                self.mobileStations_.push_back(station);
            }
        if (z > 0) allocateZ(s, Vector(z, 0.0));
        positionCache_ = allocateCacheEntry(s, Stage::Position, new Value<PositionCache>());
        return 0;
    }

    // Integrator error weights of the rope's Z entries. Transverse amplitudes are lengths like body
    // positions (weight 1/m). An axial amplitude error da changes the strain by i pi da / l, i.e. the
    // axial force by EA i pi da / l: weight w = i pi / (l eps_ref) with eps_ref = 1e-3, so an
    // accuracy of 1e-6 holds the axial force to about EA 1e-9 (0.02 N for the Table 1 rope);
    // l = L / (number of spans), the mean span length. Rates: w / omega_i with omega_i the span's
    // i-th axial frequency i pi / l sqrt(EA / rhoA).
    int realizeSubsystemInstanceImpl(const State& s) const override {
        if (getZ(s).size() == 0) return 0;
        Vector& w = const_cast<State&>(s).updZWeights(getMySubsystemIndex());
        const double pi = std::acos(-1.0);
        for (const RopeRecord& r : ropes) {
            const double l = r.spec.unstretchedLength / r.numSpans();
            const double wave = std::sqrt(r.spec.properties.axialStiffness / r.spec.properties.massPerLength);
            int k = 0;
            for (int j = 0; j < r.numSpans(); ++j) {
                const SpanOptions& o = r.spanOptions[j];
                const int dynamicAxialModes = o.axialDynamics == AxialDynamics::Dynamic ? o.axialModes : 0;
                for (int i = 1; i <= dynamicAxialModes; ++i, ++k) {
                    const double weight = i * pi / (l * 1e-3);
                    w[r.zOffset + k] = weight;
                    w[r.zOffset + r.numModal + k] = weight / (i * pi / l * wave);
                }
                for (int i = 0; i < (r.planar ? 1 : 2) * o.transverseModes; ++i, ++k) {
                    w[r.zOffset + k] = 1.0;
                    w[r.zOffset + r.numModal + k] = 1.0;
                }
            }
        }
        return 0;
    }

    // The modal coordinates q_m and rates live in Z, and Simbody invalidates only Stage::Dynamics when Z
    // alone changes (Verlet refines z at fixed q, for one). So every stage checks that the rope's cached
    // position- and velocity-level quantities were computed from the current Z and refreshes them if not.
    int realizeSubsystemPositionImpl(const State& s) const override {
        PositionCache& pc = Value<PositionCache>::updDowncast(updCacheEntry(s, positionCache_));
        pc.ropes.resize(ropes.size());
        for (size_t i = 0; i < ropes.size(); ++i) updatePositionPart(s, ropes[i], pc.ropes[i]);
        markCacheValueRealized(s, positionCache_);
        return 0;
    }

    int realizeSubsystemVelocityImpl(const State& s) const override {
        PositionCache& pc = Value<PositionCache>::updDowncast(updCacheEntry(s, positionCache_));
        for (size_t i = 0; i < ropes.size(); ++i) {
            if (!matchesZ(s, ropes[i], pc.ropes[i].modalCoordinates, false))
                updatePositionPart(s, ropes[i], pc.ropes[i]);
            updateVelocityPart(s, ropes[i], pc.ropes[i]);
        }
        return 0;
    }

    /// Refreshes rope i's cache if Z changed after it was computed (see realizeSubsystemPositionImpl).
    void refreshFromZ(const State& s, PositionCache& pc, bool velocityLevel) const {
        for (size_t i = 0; i < ropes.size(); ++i) {
            RopeCache& c = pc.ropes[i];
            const bool positionsCurrent = matchesZ(s, ropes[i], c.modalCoordinates, false);
            if (!positionsCurrent) updatePositionPart(s, ropes[i], c);
            if (velocityLevel && (!positionsCurrent || !matchesZ(s, ropes[i], c.modalRates, true)))
                updateVelocityPart(s, ropes[i], c);
        }
    }

    bool matchesZ(const State& s, const RopeRecord& r, const Eigen::VectorXd& cached, bool rates) const {
        if (cached.size() != r.numModal) return false;
        const Vector& z = getZ(s);
        const int offset = r.zOffset + (rates ? r.numModal : 0);
        for (int j = 0; j < r.numModal; ++j)
            if (cached[j] != z[offset + j]) return false;
        return true;
    }

    void updatePositionPart(const State& s, const RopeRecord& r, RopeCache& c) const {
        c.nodes3.resize(3, r.numNodes());
        for (int k = 0; k < r.numNodes(); ++k) {
            const auto [body, station] = r.node(k);
            c.nodes3.col(k) = toEigen(body->findStationLocationInGround(s, station));
        }
        modal(getZ(s), r, false, c.modalCoordinates);
        // A failure here is usually a trial state of an integrator step (an extrapolation too far).
        // What Simbody 3.7 does with the exception (its sources, confirmed in
        // tests/test_step_failures.cpp): the Runge-Kutta family (AbstractIntegratorRep::
        // attemptDAEStep) catches it, rejects the step and retries at 0.1 h, with no retry limit
        // (counted as a convergence-test failure); CPodes receives a recoverable right-hand-side
        // error and retries at 0.25 h, at most 10 times per step; a fixed-step integrator, the
        // realization of an accepted or interpolated state, and (RK) the realization inside a
        // constraint projection cannot retry and end the run. Every final message drops the cause,
        // so it is recorded here (getLastEvaluationFailure) with the rope, the time and the equation.
        try {
            if (r.planar) {
                c.nodes2.noalias() = r.planeBasis.transpose() * c.nodes3;
                r.planarModel->solveDependentCoordinates(c.nodes2, c.modalCoordinates, c.planar);
            } else {
                spatialModel(r, c.nodes3).solveDependentCoordinates(c.nodes3, c.modalCoordinates, c.spatial);
            }
        } catch (const std::exception& e) {
            failEvaluation(s, r, e);
        }
    }

    /// Records an evaluation failure of rope r and rethrows it as std::runtime_error naming the
    /// rope and the time.
    [[noreturn]] void failEvaluation(const State& s, const RopeRecord& r, const std::exception& e) const {
        std::ostringstream msg;
        msg << "ReevingSubsystem: rope '" << r.spec.name << "' at t = " << std::setprecision(17) << s.getTime()
            << " s: " << e.what();
        recordEvaluationFailure(msg.str());
        throw std::runtime_error(msg.str());
    }

    void updateVelocityPart(const State& s, const RopeRecord& r, RopeCache& c) const {
        c.nodeVelocities3.resize(3, r.numNodes());
        for (int k = 0; k < r.numNodes(); ++k) {
            const auto [body, station] = r.node(k);
            c.nodeVelocities3.col(k) = toEigen(body->findStationVelocityInGround(s, station));
        }
        modal(getZ(s), r, true, c.modalRates);
        try {
            if (r.planar) {
                c.nodeVelocities2.noalias() = r.planeBasis.transpose() * c.nodeVelocities3;
                r.planarModel->computeDynamics(c.nodes2, c.nodeVelocities2, c.modalCoordinates, c.modalRates,
                                               c.planar);
            } else {
                spatialModel(r, c.nodes3).computeDynamics(c.nodes3, c.nodeVelocities3, c.modalCoordinates,
                                                          c.modalRates, c.spatial);
            }
        } catch (const std::exception& e) {
            failEvaluation(s, r, e);
        }
    }

    int realizeSubsystemDynamicsImpl(const State& s) const override {
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

    bool anyConstraintEnabled(const State& s) const {
        const SimbodyMatterSubsystem& mat = matter();
        for (SimTK::ConstraintIndex c(0); c < mat.getNumConstraints(); ++c)
            if (!mat.isConstraintDisabled(s, c)) return true;
        return false;
    }

    Real calcPotentialEnergy(const State& s) const override {
        const PositionCache& pc = positionCache(s);
        Real u = 0;
        // From Stage::Velocity on, the velocity-level rope data (refreshed by positionCache) hold the
        // energies of these positions: no second span evaluation.
        const bool velocityCurrent = s.getSystemStage() >= Stage::Velocity;
        for (size_t i = 0; i < ropes.size(); ++i) {
            const RopeRecord& r = ropes[i];
            const RopeCache& c = pc.ropes[i];
            if (velocityCurrent) {
                u += r.planar ? c.planar.strainEnergy + c.planar.gravityEnergy
                              : c.spatial.strainEnergy + c.spatial.gravityEnergy;
            } else if (r.planar) {
                u += potential(*r.planarModel, c.planar, planarNodes(r, c.nodes3), modal(getZ(s), r, false));
            } else {
                u += potential(*r.spatialModel, c.spatial, c.nodes3, modal(getZ(s), r, false));
            }
        }
        return u;
    }

    int calcDecorativeGeometryAndAppendImpl(const State& s, Stage stage,
                                            Array_<DecorativeGeometry>& geometry) const override {
        if (stage != Stage::Position) return 0;
        for (size_t i = 0; i < ropes.size(); ++i)
            for (int j = 0; j < ropes[i].numSpans(); ++j) {
                const std::vector<Vec3> p = sample(s, static_cast<int>(i), j, decorationPoints);
                for (size_t k = 0; k + 1 < p.size(); ++k)
                    geometry.push_back(DecorativeLine(p[k], p[k + 1]).setColor(Vec3(0.55, 0.35, 0.1)).setLineThickness(3));
            }
        return 0;
    }

    // ---- helpers -------------------------------------------------------------------------
    /// The rope cache, valid for the current Z (see realizeSubsystemPositionImpl); velocity-level parts
    /// are refreshed too when the state is realized to Stage::Velocity.
    const PositionCache& positionCache(const State& s) const {
        getCacheEntry(s, positionCache_);  // throws unless realized to Stage::Position
        PositionCache& pc = Value<PositionCache>::updDowncast(updCacheEntry(s, positionCache_));
        refreshFromZ(s, pc, s.getSystemStage() >= Stage::Velocity);
        return pc;
    }

    void modal(const Vector& z, const RopeRecord& r, bool rates, Eigen::VectorXd& q) const {
        q.resize(r.numModal);
        for (int j = 0; j < r.numModal; ++j) q[j] = z[r.zOffset + (rates ? r.numModal : 0) + j];
    }
    Eigen::VectorXd modal(const Vector& z, const RopeRecord& r, bool rates) const {
        Eigen::VectorXd q;
        modal(z, r, rates, q);
        return q;
    }

    Eigen::Matrix2Xd planarNodes(const RopeRecord& r, const Eigen::Matrix3Xd& p) const {
        Eigen::Matrix2Xd out(2, p.cols());
        out.row(0) = r.e1.transpose() * p;
        out.row(1) = r.e2.transpose() * p;
        return out;
    }

    const RopeModel<3>& spatialModel(const RopeRecord& r, const Eigen::Matrix3Xd& nodes) const {
        if (!r.spatialModel) {
            std::vector<SpanModel<3>> spans;
            for (int j = 0; j < r.numSpans(); ++j)
                spans.emplace_back(r.spec.properties, r.spanOptions[j], toEigen(gravity_),
                                   makeReferenceFrame(nodes.col(j + 1) - nodes.col(j)));
            r.spatialModel = std::make_shared<const RopeModel<3>>(std::move(spans), r.spec.unstretchedLength);
        }
        return *r.spatialModel;
    }

    Eigen::Matrix3d nodeMass3(const RopeRecord& r, const RopeCache& c, int a, int b) const {
        if (!r.planar) return c.spatial.nodeMass.block<3, 3>(3 * a, 3 * b);
        Eigen::Matrix<double, 3, 2> E;
        E << r.e1, r.e2;
        return E * c.planar.nodeMass.block<2, 2>(2 * a, 2 * b) * E.transpose();
    }
    Eigen::Vector3d nodeForce3(const RopeRecord& r, const RopeCache& c, int a) const {
        if (!r.planar) return c.spatial.nodeForce.segment<3>(3 * a);
        return r.e1 * c.planar.nodeForce[2 * a] + r.e2 * c.planar.nodeForce[2 * a + 1];
    }

    /// Accelerations in Ground of the mobile nodes from the bodies' spatial accelerations.
    void nodeAccelerations(const State& s, const Vector_<SpatialVec>& A_GB, Eigen::VectorXd& a) const {
        a.resize(3 * static_cast<Eigen::Index>(mobileNodes_.size()));
        for (size_t k = 0; k < mobileNodes_.size(); ++k) {
            const MobilizedBody& b = *mobileNodes_[k].body;
            const SpatialVec& A = A_GB[b.getMobilizedBodyIndex()];
            const Vec3 p = b.getBodyRotation(s) * mobileNodes_[k].station;
            const Vec3& w = b.getBodyAngularVelocity(s);
            a.segment<3>(3 * static_cast<Eigen::Index>(k)) = toEigen(A[1] + A[0] % p + w % (w % p));
        }
    }

    template <int Dim>
    double potential(const RopeModel<Dim>& model, const RopeData<Dim>& data,
                     const Eigen::Matrix<double, Dim, Eigen::Dynamic>& nodes, const Eigen::VectorXd& qm) const {
        double u = 0;
        Eigen::VectorXd q;
        for (int j = 0; j < model.numSpans(); ++j) {
            model.spanCoordinates(j, nodes, qm, data, q);
            SpanData<Dim> d;
            model.span(j).evaluate(q, Eigen::VectorXd::Zero(q.size()), d);
            u += d.potentialEnergy();
        }
        return u;
    }

    std::vector<Vec3> sample(const State& s, int rope, int span, int numPoints) const {
        const RopeRecord& r = ropes.at(rope);
        const RopeCache& c = positionCache(s).ropes.at(rope);
        std::vector<Vec3> out;
        Eigen::VectorXd q;
        const Eigen::VectorXd qm = modal(getZ(s), r, false);
        if (r.planar) {
            const Eigen::Matrix2Xd n2 = planarNodes(r, c.nodes3);
            r.planarModel->spanCoordinates(span, n2, qm, c.planar, q);
            const auto& sp = r.planarModel->span(span);
            const double offset = r.normal.dot(c.nodes3.col(0));
            for (int k = 0; k < numPoints; ++k) {
                const double sk = q[sp.s1Index()] + (q[sp.s2Index()] - q[sp.s1Index()]) * k / (numPoints - 1);
                const Eigen::Vector2d p = sp.position(q, std::min(sk, q[sp.s2Index()]));
                out.push_back(toSimTK(r.e1 * p[0] + r.e2 * p[1] + r.normal * offset));
            }
        } else {
            r.spatialModel->spanCoordinates(span, c.nodes3, qm, c.spatial, q);
            const auto& sp = r.spatialModel->span(span);
            for (int k = 0; k < numPoints; ++k) {
                const double sk = q[sp.s1Index()] + (q[sp.s2Index()] - q[sp.s1Index()]) * k / (numPoints - 1);
                out.push_back(toSimTK(Eigen::Vector3d(sp.position(q, std::min(sk, q[sp.s2Index()])))));
            }
        }
        return out;
    }

    /// Evaluation failures (a rope's dependent coordinates not found at a trial state): how many,
    /// and the message of the last one. Integrators usually recover from them (smaller step).
    void recordEvaluationFailure(const std::string& message) const {
        lastEvaluationFailure_ = message;
        ++numEvaluationFailures_;
    }
    int numEvaluationFailures() const { return numEvaluationFailures_; }
    const std::string& lastEvaluationFailure() const { return lastEvaluationFailure_; }

private:
    Vec3 gravity_;
    // Fixed at realizeTopology: the mobile nodes of all ropes, in rope and node order.
    std::vector<MobileNode> mobileNodes_;
    Array_<SimTK::MobilizedBodyIndex> mobileBodies_;
    Array_<Vec3> mobileStations_;
    mutable std::string lastEvaluationFailure_;
    mutable int numEvaluationFailures_ = 0;

    mutable CacheEntryIndex positionCache_;
    mutable const MultibodySystem* system_ = nullptr;
    mutable const SimbodyMatterSubsystem* matter_ = nullptr;
};

// ---- ReevingSubsystem ------------------------------------------------------------------------

bool ReevingSubsystem::isInstanceOf(const ForceSubsystem& s) {
    return dynamic_cast<const Guts*>(&s.getSubsystemGuts()) != nullptr;
}
const ReevingSubsystem& ReevingSubsystem::downcast(const ForceSubsystem& s) {
    return static_cast<const ReevingSubsystem&>(s);
}
ReevingSubsystem& ReevingSubsystem::updDowncast(ForceSubsystem& s) { return static_cast<ReevingSubsystem&>(s); }
ReevingSubsystem::Guts& ReevingSubsystem::updGuts() { return dynamic_cast<Guts&>(updSubsystemGuts()); }
const ReevingSubsystem::Guts& ReevingSubsystem::getGuts() const { return dynamic_cast<const Guts&>(getSubsystemGuts()); }

ReevingSubsystem::ReevingSubsystem(MultibodySystem& system, const Vec3& gravity) {
    if (!finite(gravity)) invalid("gravity [m/s^2] = " + str(gravity) + " must be finite");
    adoptSubsystemGuts(new Guts(gravity));
    system.addForceSubsystem(*this);
}

int ReevingSubsystem::addRope(const RopeSpec& specIn) {
    Guts& g = updGuts();
    RopeRecord r;
    r.spec = specIn;
    const RopeSpec& spec = r.spec;
    const std::string who = "rope '" + spec.name + "': ";
    auto checkAnchor = [&](const RopeAnchor& a, const char* which) {
        if (a.body.isEmptyHandle()) invalid(who + which + " anchor has no body");
        if (!finite(a.station)) invalid(who + which + " anchor station [m] = " + str(a.station) + " must be finite");
    };
    checkAnchor(spec.start, "start");
    checkAnchor(spec.end, "end");
    for (size_t k = 0; k < spec.sheaves.size(); ++k) {
        const DeviationSheave& sh = spec.sheaves[k];
        const std::string name = who + "sheave " + std::to_string(k);
        if (sh.body.isEmptyHandle()) invalid(name + " has no body");
        if (!finite(sh.centre)) invalid(name + " centre [m] = " + str(sh.centre) + " must be finite");
        if (!std::isfinite(sh.radius) || !(sh.radius > 0)) {
            std::ostringstream o;
            o << name << " radius [m] = " << sh.radius << " must be finite and > 0";
            invalid(o.str());
        }
    }
    // Consecutive path points on the same body must not coincide.
    for (int k = 0; k + 1 < r.numNodes(); ++k) {
        const auto a = r.node(k), b = r.node(k + 1);
        if (a.first->getMobilizedBodyIndex() == b.first->getMobilizedBodyIndex() && (a.second - b.second).norm() == 0)
            invalid(who + "path points " + std::to_string(k) + " and " + std::to_string(k + 1) +
                    " coincide (same body, station " + str(a.second) + ")");
    }
    if (!std::isfinite(spec.unstretchedLength) || !(spec.unstretchedLength > 0)) {
        std::ostringstream o;
        o << who << "unstretchedLength [m] = " << spec.unstretchedLength << " must be finite and > 0";
        invalid(o.str());
    }
    try {
        validate(spec.properties);
    } catch (const std::invalid_argument& e) {
        invalid(who + e.what());
    }
    r.spanOptions.assign(r.numSpans(), spec.spanDefaults);
    for (const auto& [index, options] : spec.spanOverrides) {
        if (index < 0 || index >= r.numSpans())
            invalid(who + "span override index = " + std::to_string(index) + " is outside 0.." +
                    std::to_string(r.numSpans() - 1));
        r.spanOptions[index] = options;
    }
    if (!finite(spec.planeNormal)) invalid(who + "planeNormal = " + str(spec.planeNormal) + " must be finite");
    r.planar = spec.planeNormal.norm() > 0;
    const Eigen::Vector3d gravity = toEigen(g.gravity());
    try {
        if (r.planar) {
            const Eigen::Matrix3d frame = makeReferenceFrame(toEigen(spec.planeNormal));
            r.normal = frame.col(0);
            r.e1 = frame.col(1);
            r.e2 = frame.col(2);
            r.planeBasis << r.e1, r.e2;
            if (std::abs(r.normal.dot(gravity)) > 1e-12 * gravity.norm())
                invalid(who + "gravity " + str(g.gravity()) + " is not in the rope plane (normal " +
                        str(spec.planeNormal) + ")");
            std::vector<SpanModel<2>> spans;
            const Eigen::Vector2d g2(r.e1.dot(gravity), r.e2.dot(gravity));
            for (int j = 0; j < r.numSpans(); ++j) spans.emplace_back(spec.properties, r.spanOptions[j], g2);
            r.planarModel = std::make_shared<const RopeModel<2>>(std::move(spans), spec.unstretchedLength);
            r.numModal = r.planarModel->numModalCoordinates();
        } else {
            for (int j = 0; j < r.numSpans(); ++j) {
                const SpanModel<3> probe(spec.properties, r.spanOptions[j], gravity);  // validates options
                r.numModal += probe.numModalCoordinates();
                if (r.spanOptions[j].axialDynamics == AxialDynamics::QuasiStatic)
                    r.numModal -= probe.axialModes();  // condensed: not states
            }
        }
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        if (msg.rfind("ReevingSubsystem", 0) == 0) throw;
        invalid(who + msg);
    }
    g.ropes.push_back(std::move(r));
    invalidateSubsystemTopologyCache();
    return static_cast<int>(g.ropes.size()) - 1;
}

int ReevingSubsystem::getNumRopes() const { return static_cast<int>(getGuts().ropes.size()); }

namespace {
const RopeRecord& ropeAt(const ReevingSubsystem::Guts& g, int rope) {
    if (rope < 0 || rope >= static_cast<int>(g.ropes.size()))
        invalid("rope index = " + std::to_string(rope) + " is outside 0.." + std::to_string(g.ropes.size() - 1));
    return g.ropes[rope];
}
}  // namespace

const RopeSpec& ReevingSubsystem::getRopeSpec(int rope) const { return ropeAt(getGuts(), rope).spec; }
int ReevingSubsystem::getNumSpans(int rope) const { return ropeAt(getGuts(), rope).numSpans(); }
bool ReevingSubsystem::isPlanar(int rope) const { return ropeAt(getGuts(), rope).planar; }
int ReevingSubsystem::getNumModalCoordinates(int rope) const { return ropeAt(getGuts(), rope).numModal; }

Vector ReevingSubsystem::getModalCoordinates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset, r.numModal);
}
Vector ReevingSubsystem::getModalRates(const State& s, int rope) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    return getGuts().getZ(s)(r.zOffset + r.numModal, r.numModal);
}
void ReevingSubsystem::setModalCoordinates(State& s, int rope, const Vector& q) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (q.size() != r.numModal)
        invalid("setModalCoordinates: size " + std::to_string(q.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset, r.numModal) = q;
}
void ReevingSubsystem::setModalRates(State& s, int rope, const Vector& qdot) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (qdot.size() != r.numModal)
        invalid("setModalRates: size " + std::to_string(qdot.size()) + " differs from " + std::to_string(r.numModal));
    getGuts().updZ(s)(r.zOffset + r.numModal, r.numModal) = qdot;
}

std::pair<double, double> ReevingSubsystem::getSpanMaterialRange(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (span < 0 || span >= r.numSpans())
        invalid("span index = " + std::to_string(span) + " is outside 0.." + std::to_string(r.numSpans() - 1));
    const RopeCache& c = g.positionCache(s).ropes[rope];
    const Eigen::VectorXd& sv = r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates;
    return {sv[span], sv[span + 1]};
}

double ReevingSubsystem::getAxialForce(const State& s, int rope, int span, double sMaterial) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    const double eps = strainAt(s, rope, span, sMaterial);
    return axialForce(r.spec.properties, eps);
}

double ReevingSubsystem::getTension(const State& s, int rope, int span, double sMaterial) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    const double eps = strainAt(s, rope, span, sMaterial);
    return axialForce(r.spec.properties, eps) * std::sqrt(std::max(1.0 + 2.0 * eps, 0.0));
}

int ReevingSubsystem::getNumEvaluationFailures() const { return getGuts().numEvaluationFailures(); }
const std::string& ReevingSubsystem::getLastEvaluationFailure() const { return getGuts().lastEvaluationFailure(); }

double ReevingSubsystem::getSpanMaxStrain(const State& s, int rope, int span) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    getSpanMaterialRange(s, rope, span);  // validates span
    const RopeCache& c = g.positionCache(s).ropes[rope];
    return r.planar ? r.planarModel->span(span).maxStrain(c.planar.spanQ[span])
                    : r.spatialModel->span(span).maxStrain(c.spatial.spanQ[span]);
}

bool ReevingSubsystem::isSpanSlack(const State& s, int rope, int span) const {
    return getRopeSpec(rope).properties.tensionOnly && getSpanMaxStrain(s, rope, span) <= 0.0;
}

double ReevingSubsystem::strainAt(const State& s, int rope, int span, double sMaterial) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    getSpanMaterialRange(s, rope, span);  // validates span
    const RopeCache& c = g.positionCache(s).ropes[rope];
    Eigen::VectorXd q;
    const Eigen::VectorXd qm = g.modal(g.getZ(s), r, false);
    // QuasiStatic spans: once the accelerations are known (Stage::Dynamics), the strain includes the
    // mode-acceleration correction (RopeModel::recoverInertialStrain), which also moves the material
    // coordinates at the sheaves slightly; the point is taken at the same relative position
    // xi = (s - s1) / (s2 - s1) of the corrected span, so span ends stay span ends.
    const bool recovered = s.getSystemStage() >= Stage::Dynamics;
    auto strainOf = [&](const auto& model, const auto& nodes, const auto& data) {
        model.spanCoordinates(span, nodes, qm, data, q);
        if (!recovered) return model.span(span).strain(q, sMaterial);
        const auto& sp = model.span(span);
        const double s1 = q[sp.s1Index()], s2 = q[sp.s2Index()];
        const double xi = std::clamp((sMaterial - s1) / (s2 - s1), 0.0, 1.0);
        model.span(span).strain(q, sMaterial);  // validates sMaterial against the span's range
        model.recoveredSpanCoordinates(span, nodes, qm, data, q);
        const double r1 = q[sp.s1Index()], r2 = q[sp.s2Index()];
        return sp.strain(q, xi >= 1.0 ? r2 : r1 + xi * (r2 - r1));
    };
    if (r.planar) return strainOf(*r.planarModel, g.planarNodes(r, c.nodes3), c.planar);
    return strainOf(*r.spatialModel, c.nodes3, c.spatial);
}

Vec3 ReevingSubsystem::getNodeForce(const State& s, int rope, int node) const {
    const Guts& g = getGuts();
    const RopeRecord& r = ropeAt(g, rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    if (s.getSystemStage() < Stage::Dynamics)
        throw std::logic_error("ReevingSubsystem::getNodeForce: realize the state to Stage::Dynamics first");
    const RopeCache& c = g.positionCache(s).ropes[rope];
    // The rope's node equation is S rdd - h = f (f: force on the rope); the body receives -f.
    Eigen::Vector3d force = g.nodeForce3(r, c, node);
    for (int b = 0; b < r.numNodes(); ++b) force.noalias() -= g.nodeMass3(r, c, node, b) * c.nodeAccelerations3.col(b);
    return toSimTK(force);
}

double ReevingSubsystem::getMaterialCoordinate(const State& s, int rope, int node) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (node < 0 || node >= r.numNodes())
        invalid("node index = " + std::to_string(node) + " is outside 0.." + std::to_string(r.numNodes() - 1));
    const RopeCache& c = getGuts().positionCache(s).ropes[rope];
    return (r.planar ? c.planar.materialCoordinates : c.spatial.materialCoordinates)[node];
}

double ReevingSubsystem::getConstraintError(const State& s, int rope, int sheave) const {
    const RopeRecord& r = ropeAt(getGuts(), rope);
    if (sheave < 1 || sheave >= r.numNodes() - 1)
        invalid("sheave node index = " + std::to_string(sheave) + " is outside 1.." + std::to_string(r.numNodes() - 2));
    const RopeCache& c = getGuts().positionCache(s).ropes[rope];
    return r.planar ? r.planarModel->constraintError(c.planar, sheave)
                    : r.spatialModel->constraintError(c.spatial, sheave);
}

double ReevingSubsystem::getMaxConstraintError(const State& s) const {
    double worst = 0;
    for (int i = 0; i < getNumRopes(); ++i)
        for (int k = 1; k + 1 < getGuts().ropes[i].numNodes(); ++k)
            worst = std::max(worst, std::abs(getConstraintError(s, i, k)));
    return worst;
}

std::vector<Vec3> ReevingSubsystem::sampleSpan(const State& s, int rope, int span, int numPoints) const {
    getSpanMaterialRange(s, rope, span);  // validates
    if (numPoints < 2) invalid("sampleSpan: numPoints = " + std::to_string(numPoints) + " must be >= 2");
    return getGuts().sample(s, rope, span, numPoints);
}

double ReevingSubsystem::calcRopeKineticEnergy(const State& s) const {
    const Guts& g = getGuts();
    // The velocity-level rope data live beside the position-level data and are refreshed by every
    // realize(Velocity): reading them below that stage would return stale numbers.
    if (s.getSystemStage() < Stage::Velocity)
        throw std::logic_error("ReevingSubsystem::calcRopeKineticEnergy: realize the state to Stage::Velocity first");
    double t = 0;
    for (size_t i = 0; i < g.ropes.size(); ++i) {
        const RopeCache& c = g.positionCache(s).ropes[i];
        t += g.ropes[i].planar ? c.planar.kineticEnergy : c.spatial.kineticEnergy;
    }
    return t;
}

double ReevingSubsystem::calcRopePotentialEnergy(const State& s) const { return getGuts().calcPotentialEnergy(s); }

double ReevingSubsystem::calcMechanicalEnergy(const State& s) const {
    const MultibodySystem& mbs = getGuts().mbs();
    return mbs.calcKineticEnergy(s) + mbs.calcPotentialEnergy(s) + calcRopeKineticEnergy(s);
}

void ReevingSubsystem::setDecorationResolution(int pointsPerSpan) {
    if (pointsPerSpan < 2) invalid("decoration resolution = " + std::to_string(pointsPerSpan) + " must be >= 2");
    updGuts().decorationPoints = pointsPerSpan;
}

double ReevingSubsystem::findStaticEquilibrium(State& state, double relativeTolerance, int maxIterations) const {
    const Guts& g = getGuts();
    const MultibodySystem& mbs = g.mbs();
    const SimbodyMatterSubsystem& matter = g.matter();
    state.updU() = 0;
    for (int i = 0; i < getNumRopes(); ++i) setModalRates(state, i, Vector(getNumModalCoordinates(i), 0.0));
    const int nu = state.getNU();
    int nm = 0;
    for (int i = 0; i < getNumRopes(); ++i) nm += getNumModalCoordinates(i);
    const int n = nu + nm;

    // Generalized force residual at zero velocity: bodies M udot, ropes Mbar_mm qddot_m; and the
    // scale: the largest applied generalized force on bodies and rope modes.
    auto residual = [&](State& st, double* scale) {
        mbs.realize(st, Stage::Acceleration);
        Eigen::VectorXd r(n);
        Vector Mudot;
        matter.multiplyByM(st, st.getUDot(), Mudot);
        for (int k = 0; k < nu; ++k) r[k] = Mudot[k];
        const Vector& zdot = g.getZDot(st);
        const PositionCache& pc = g.positionCache(st);
        int off = nu;
        double fmax = 0;
        for (int i = 0; i < getNumRopes(); ++i) {
            const RopeRecord& rr = g.ropes[i];
            Eigen::VectorXd qdd(rr.numModal);
            for (int j = 0; j < rr.numModal; ++j) qdd[j] = zdot[rr.zOffset + rr.numModal + j];
            const int nn = (rr.planar ? 2 : 3) * rr.numNodes();
            const Eigen::MatrixXd& Mbar = rr.planar ? pc.ropes[i].planar.Mbar : pc.ropes[i].spatial.Mbar;
            const Eigen::VectorXd& Qbar = rr.planar ? pc.ropes[i].planar.Qbar : pc.ropes[i].spatial.Qbar;
            r.segment(off, rr.numModal) = Mbar.bottomRightCorner(rr.numModal, rr.numModal) * qdd;
            if (rr.numModal > 0) fmax = std::max(fmax, Qbar.tail(rr.numModal).cwiseAbs().maxCoeff());
            fmax = std::max(fmax, Qbar.head(nn).cwiseAbs().maxCoeff());
            off += rr.numModal;
        }
        if (scale) {
            Vector applied;
            matter.calcResidualForceIgnoringConstraints(st, mbs.getMobilityForces(st, Stage::Dynamics),
                                                        mbs.getRigidBodyForces(st, Stage::Dynamics),
                                                        Vector(nu, 0.0), applied);
            for (int k = 0; k < nu; ++k) fmax = std::max(fmax, std::abs(applied[k]));
            *scale = fmax;
        }
        return r;
    };
    auto displace = [&](State& st, const Eigen::VectorXd& dy) {
        Vector du(nu), dq;
        for (int k = 0; k < nu; ++k) du[k] = dy[k];
        mbs.realize(st, Stage::Position);
        matter.multiplyByN(st, false, du, dq);
        st.updQ() += dq;
        int off = nu;
        for (int i = 0; i < getNumRopes(); ++i) {
            Vector q = getModalCoordinates(st, i);
            for (int j = 0; j < q.size(); ++j) q[j] += dy[off + j];
            setModalCoordinates(st, i, q);
            off += q.size();
        }
        mbs.realize(st, Stage::Position);
        mbs.project(st, 1e-12);
    };

    double scale = 0;
    Eigen::VectorXd r = residual(state, &scale);
    for (int iter = 0; iter < maxIterations; ++iter) {
        const double rel = r.cwiseAbs().maxCoeff() / scale;
        if (rel <= relativeTolerance) return rel;
        // Jacobian of the accelerations by central differences in (u-space, modal) coordinates.
        Eigen::MatrixXd J(n, n);
        for (int k = 0; k < n; ++k) {
            const double h = 1e-7;
            State sp = state, sm = state;
            Eigen::VectorXd dy = Eigen::VectorXd::Zero(n);
            dy[k] = h;
            displace(sp, dy);
            displace(sm, -dy);
            J.col(k) = (residual(sp, nullptr) - residual(sm, nullptr)) / (2 * h);
        }
        const Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(-r);
        // Backtracking on the residual norm.
        double alpha = 1.0;
        State trial = state;
        for (int ls = 0; ls < 20; ++ls, alpha *= 0.5) {
            trial = state;
            displace(trial, alpha * step);
            const Eigen::VectorXd rt = residual(trial, nullptr);
            if (rt.norm() < r.norm() || ls == 19) {
                state = trial;
                r = residual(state, &scale);
                break;
            }
        }
    }
    const double rel = r.cwiseAbs().maxCoeff() / scale;
    if (rel <= relativeTolerance) return rel;
    std::ostringstream msg;
    msg << "ReevingSubsystem::findStaticEquilibrium: no convergence in " << maxIterations
        << " iterations (relative residual " << rel << ")";
    throw std::runtime_error(msg.str());
}

}  // namespace SimbodyReeving
