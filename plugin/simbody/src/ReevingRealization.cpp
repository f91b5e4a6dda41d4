// ReevingSubsystem::Guts: realization (topology to velocity), the per-rope position and velocity
// caches, the potential energy and the decorations.

#include "ReevingSubsystemGuts.h"
#include "nodes/NodeDrawing.h"

#include "ForceFreeSubsystem.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

using SimTK::Array_;
using SimTK::DecorativeGeometry;
using SimTK::DecorativeLine;
using SimTK::ForceSubsystem;
using SimTK::MobilizedBody;
using SimTK::Real;
using SimTK::Stage;
using SimTK::State;
using SimTK::SubsystemIndex;
using SimTK::System;
using SimTK::Value;
using SimTK::Vec3;
using SimTK::Vector;

namespace SimbodyReeving {

using namespace detail;

// ---- realization -----------------------------------------------------------------------
int ReevingSubsystem::Guts::realizeSubsystemTopologyImpl(State& s) const {
    const System& sys = getSystem();
    const SubsystemIndex me = getMySubsystemIndex();
    for (SubsystemIndex i(me + 1); i < sys.getNumSubsystems(); ++i)
        if (dynamic_cast<const ForceSubsystem::Guts*>(&sys.getSubsystem(i).getSubsystemGuts()) &&
            !dynamic_cast<const ForceFreeSubsystemGuts*>(&sys.getSubsystem(i).getSubsystemGuts()))
            throw std::logic_error(
                "ReevingSubsystem: force subsystem '" + sys.getSubsystem(i).getName() +
                "' was added after the ReevingSubsystem; construct the ReevingSubsystem after every other "
                "force subsystem (GeneralForceSubsystem included) so it sees all forces in its coupled solve");
    system_ = nullptr;
    matter_ = nullptr;
    int z = 0;
    auto& self = const_cast<Guts&>(*this);
    // Gravity: the system's (one-argument constructor) or the given one, which must then agree with
    // the system's gravity forces if there are any.
    self.findGravityForces();
    Vec3 systemG;
    const int numGravityForces = systemGravity(nullptr, systemG);
    if (gravityFromSystem_) {
        self.gravity_ = systemG;
    } else if (numGravityForces > 0 && (gravity_ - systemG).norm() > 1e-12 * std::max(gravity_.norm(), systemG.norm())) {
        throw std::logic_error("ReevingSubsystem: the ropes' gravity " + str(gravity_) +
                               " m/s^2 (constructor argument) differs from the gravity the bodies feel, " +
                               str(systemG) + " m/s^2 (the sum of the system's " + std::to_string(numGravityForces) +
                               " Force::Gravity / Force::UniformGravity defaults); give the same vector, or "
                               "construct the ReevingSubsystem without one to take the system's");
    }
    const Eigen::Vector3d gravity = toEigen(gravity_);
    for (RopeRecord& r : self.ropes) {
        if (!r.planar) continue;
        if (std::abs(r.normal.dot(gravity)) > 1e-12 * gravity.norm())
            throw std::logic_error("ReevingSubsystem: rope '" + r.spec.name + "': gravity " + str(gravity_) +
                                   " is not in the rope plane (normal " + str(r.spec.planeNormal) + ")");
        std::vector<SpanModel<2>> spans;
        const Eigen::Vector2d g2(r.e1.dot(gravity), r.e2.dot(gravity));
        for (int j = 0; j < r.numSpans(); ++j) spans.emplace_back(r.spec.properties, r.spanOptions[j], g2);
        auto model = std::make_shared<RopeModel<2>>(std::move(spans), r.spec.unstretchedLength, r.materialKinds, r.wraps);
        r.addStoredRope(*model);
        model->setStationaryNodes(r.stationaryNodes());
        r.planarModel = std::move(model);
    }
    for (RopeRecord& r : self.ropes) {
        for (int k = 0; k < r.numNodes(); ++k) {
            const MobilizedBody& b = *r.node(k).first;
            if (&b.getMatterSubsystem() != &matter())
                throw std::logic_error("ReevingSubsystem: rope '" + r.spec.name + "' node " + std::to_string(k) +
                                       " is on a body of another system's matter subsystem");
        }
        r.zOffset = z;
        z += 2 * r.numModal;
        r.index = static_cast<int>(&r - self.ropes.data());
    }
    TractionStates traction;  // every traction sheave in stick at its spec's s_ref
    for (RopeRecord& r : self.ropes) {
        // The driven nodes' Z entries (DrivenRole::layoutZ): their work integrals, then their states.
        for (const DrivenZBlock block : {DrivenZBlock::Work, DrivenZBlock::States})
            for (RopeRecord::DrivenNode& d : r.driven) d.role.layoutZ(block, z);
        bool damped = r.spec.properties.axialRetardationTime > 0;
        for (const SpanOptions& o : r.spanOptions) damped = damped || o.transverseDampingRatio > 0;
        r.dampingZOffset = damped ? z++ : -1;  // damping work
        r.tractionModels.clear();
        r.spatialTractionModels.clear();
        traction.ropes.emplace_back();  // each phase node's entry: DrivenRole::initialPhase
        for (const RopeRecord::DrivenNode& d : r.driven) d.role.initialPhase(traction.ropes.back(), d.sRef);
    }
    // The coupled vector y: every rope's mobile nodes (2 or 3 rows each), then every driven material
    // coordinate (1 row each); each rope records which of its external coordinates each row is.
    self.mobileNodes_.clear();
    self.mobileAngles_.clear();
    self.bodySlots_.clear();
    self.ropeCoupling_.assign(ropes.size(), RopeCoupling{});
    // Body slots: each body carrying a rope node once, so that its kinematics are read from Simbody
    // once per stage rather than once per node.
    // (By index: a RopeNode holds its own MobilizedBody handle, so handles of one body differ.)
    auto slotOf = [&self](const MobilizedBody* body) {
        for (size_t b = 0; b < self.bodySlots_.size(); ++b)
            if (self.bodySlots_[b]->getMobilizedBodyIndex() == body->getMobilizedBodyIndex()) return static_cast<int>(b);
        self.bodySlots_.push_back(body);
        return static_cast<int>(self.bodySlots_.size()) - 1;
    };
    for (RopeRecord& r : self.ropes) {
        r.nodeSlot.assign(r.numStations(), 0);
        for (int k = 0; k < r.numStations(); ++k) r.nodeSlot[k] = slotOf(r.station(k).first);
    }
    for (size_t i = 0; i < ropes.size(); ++i)
        for (int k = 0; k < ropes[i].numStations(); ++k) {  // nodes and axis stations
            const auto [body, station] = ropes[i].station(k);
            if (body->isGround()) continue;
            MobileNode mn{static_cast<int>(i), k, body, station};
            mn.slot = ropes[i].nodeSlot[k];
            mn.bodyIndex = body->getMobilizedBodyIndex();
            mn.dims = ropes[i].dim();
            if (ropes[i].planar) {
                mn.directions.setZero();
                mn.directions.leftCols<2>() = ropes[i].planeBasis;
            }
            self.mobileNodes_.push_back(mn);
        }
    self.rowOwner_.clear();
    for (size_t a = 0; a < mobileNodes_.size(); ++a) {
        self.mobileNodes_[a].row = static_cast<int>(rowOwner_.size());
        for (int d = 0; d < mobileNodes_[a].dims; ++d) self.rowOwner_.push_back({static_cast<int>(a), d});
    }
    self.numStationRows_ = static_cast<int>(rowOwner_.size());
    for (size_t i = 0; i < ropes.size(); ++i)
        for (size_t d = 0; d < ropes[i].driven.size(); ++d) {
            const RopeRecord::DrivenNode& dn = ropes[i].driven[d];
            self.mobileAngles_.push_back({static_cast<int>(i), static_cast<int>(d), &ropes[i].nodeSpec(dn.node).body});
        }
    const int numMobile = static_cast<int>(mobileNodes_.size());
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeRecord& r = ropes[i];
        RopeCoupling& rc = self.ropeCoupling_[i];
        std::vector<std::pair<int, int>> entries;  // (first row in y, node)
        for (int a = 0; a < numMobile; ++a)
            if (mobileNodes_[a].rope == static_cast<int>(i)) entries.push_back({mobileNodes_[a].row, mobileNodes_[a].node});
        int angleRow = numStationRows_;
        std::vector<std::pair<int, int>> angles;
        for (const MobileAngle& ma : mobileAngles_) {
            if (ma.rope == static_cast<int>(i)) angles.push_back({angleRow, ma.driven});
            ++angleRow;
        }
        // A node's rows are its rope's own node coordinates (the plane basis for planar ropes).
        const int dim = r.dim();
        for (const auto& [yRow, node] : entries)
            for (int d = 0; d < dim; ++d) {
                rc.rows.push_back(yRow + d);
                rc.external.push_back(dim * node + d);
            }
        for (const auto& [yRow, d] : angles) {
            rc.rows.push_back(yRow);
            rc.external.push_back(r.drivenExternal(d));
        }
    }
    if (z > 0) allocateZ(s, Vector(z, 0.0));
    positionCache_ = allocateCacheEntry(s, Stage::Position, new Value<PositionCache>());
    SpatialFrames frames;  // none yet: built at the state's first realization to Stage::Position
    frames.models.assign(ropes.size(), nullptr);
    frames.changes.assign(ropes.size(), 0);
    framesVariable_ = allocateDiscreteVariable(s, Stage::Position, new Value<SpatialFrames>(frames));
    tractionVariable_ = allocateDiscreteVariable(s, Stage::Position, new Value<TractionStates>(traction));
    return 0;
}

// Integrator error weights of the rope's Z entries (State::updZWeights; the integrators weigh a
// step's error estimate of z with the weights of the state the step starts from). Transverse
// amplitudes are lengths like body positions (weight 1/m). An axial amplitude error da changes the
// strain by i pi da / l, i.e. the axial force by EA i pi da / l: weight w = i pi / (l eps_ref)
// with eps_ref = 1e-3, so an accuracy of 1e-6 holds the axial force to about EA 1e-9 (0.02 N for
// the Table 1 rope). l is the span's own current material length s_{j+1} - s_j, set at every
// realization to Stage::Position (hoisting changes span lengths by orders of magnitude; at
// Stage::Instance, before positions are known, the mean span length L / (number of spans) stands
// in). Rates: w / omega_i with omega_i = i pi / l sqrt(EA / rhoA) the span's i-th axial
// frequency, i.e. 1 / (eps_ref sqrt(EA / rhoA)): the same for every span length.
void ReevingSubsystem::Guts::setZWeights(const State& s, const RopeRecord& r,
                                         const Eigen::VectorXd* materialCoordinates) const {
    Vector& w = const_cast<State&>(s).updZWeights(getMySubsystemIndex());  // invalidates Stage::Report only
    const double pi = std::acos(-1.0);
    const double meanLength = r.spec.unstretchedLength / r.numSpans();
    const double wave = std::sqrt(r.spec.properties.axialStiffness / r.spec.properties.massPerLength);
    int k = 0;
    for (int j = 0; j < r.numSpans(); ++j) {
        const SpanOptions& o = r.spanOptions[j];
        const double l = materialCoordinates ? (*materialCoordinates)[j + 1] - (*materialCoordinates)[j] : meanLength;
        const int dynamicAxialModes = o.axialDynamics == AxialDynamics::Dynamic ? o.axialModes : 0;
        for (int i = 1; i <= dynamicAxialModes; ++i, ++k) {
            const double weight = i * pi / (l * kAxialWeightStrain);
            w[r.zOffset + k] = weight;
            w[r.zOffset + r.numModal + k] = 1.0 / (kAxialWeightStrain * wave);
        }
        const int transverseStates =
            o.transverseDynamics == TransverseDynamics::Dynamic ? (r.planar ? 1 : 2) * o.transverseModes : 0;
        for (int i = 0; i < transverseStates; ++i, ++k) {
            w[r.zOffset + k] = 1.0;
            w[r.zOffset + r.numModal + k] = 1.0;
        }
    }
}

int ReevingSubsystem::Guts::realizeSubsystemInstanceImpl(const State& s) const {
    // A new run (an integrator's initialize realizes Stage::Instance afresh) has reached no limit
    // yet; a limit ends a run, so this never clears the message of the current one.
    recordLimit("");
    if (getZ(s).size() == 0) return 0;
    for (const RopeRecord& r : ropes) setZWeights(s, r, nullptr);
    return 0;
}

// The modal coordinates q_m and rates live in Z, and Simbody invalidates only Stage::Dynamics when Z
// alone changes (Verlet refines z at fixed q, for one). So every stage checks that the rope's cached
// position- and velocity-level quantities were computed from the current Z and refreshes them if not.
int ReevingSubsystem::Guts::realizeSubsystemPositionImpl(const State& s) const {
    PositionCache& pc = updPositionCache(s);
    pc.ropes.resize(ropes.size());
    updateBodyKinematics(s, pc, false);
    for (size_t i = 0; i < ropes.size(); ++i) {
        updatePositionPart(s, ropes[i], pc, pc.ropes[i]);
        if (ropes[i].numModal > 0)
            setZWeights(s, ropes[i],
                        ropes[i].planar ? &pc.ropes[i].planar.materialCoordinates : &pc.ropes[i].spatial.materialCoordinates);
    }
    markCacheValueRealized(s, positionCache_);
    return 0;
}

int ReevingSubsystem::Guts::realizeSubsystemVelocityImpl(const State& s) const {
    PositionCache& pc = updPositionCache(s);
    updateBodyKinematics(s, pc, true);
    for (size_t i = 0; i < ropes.size(); ++i) {
        if (!matchesZ(s, ropes[i], pc.ropes[i], false))
            updatePositionPart(s, ropes[i], pc, pc.ropes[i]);
        updateVelocityPart(s, ropes[i], pc, pc.ropes[i]);
    }
    return 0;
}

void ReevingSubsystem::Guts::seedDependentCoordinates(const State& from, const State& to) const {
    if (from.getSubsystemStage(getMySubsystemIndex()) < Stage::Position) return;
    const PositionCache& source =
        static_cast<const SimTK::Value<PositionCache>&>(getCacheEntry(from, positionCache_)).get();
    PositionCache& target = updPositionCache(to);
    if (target.ropes.size() != source.ropes.size()) return;  // `to` not realized yet: its own start
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeCache& a = source.ropes[i];
        RopeCache& b = target.ropes[i];
        auto seed = [](const auto& x, auto& y) {  // assignments of equal sizes: no allocation
            y.materialCoordinates = x.materialCoordinates;
            y.condensedAmplitudes = x.condensedAmplitudes;
            y.multipliers = x.multipliers;
        };
        if (ropes[i].planar) {
            if (a.planarModel == b.planarModel) seed(a.planar, b.planar);
        } else if (ropes[i].numPhaseNodes == 0 || a.spatialModel == b.spatialModel) {
            seed(a.spatial, b.spatial);
        }
    }
}

void ReevingSubsystem::Guts::updateBodyKinematics(const State& s, PositionCache& pc, bool velocities) const {
    const size_t n = bodySlots_.size();
    if (velocities) {
        pc.bodyV.resize(n);
        for (size_t b = 0; b < n; ++b) pc.bodyV[b] = bodySlots_[b]->getBodyVelocity(s);
    } else {
        pc.bodyX.resize(n);
        for (size_t b = 0; b < n; ++b) pc.bodyX[b] = bodySlots_[b]->getBodyTransform(s);
    }
}

namespace {
// The rope's driven nodes' Z states (their rates if `rates`) into `out`, one entry per driven node
// (DrivenRole::readZState; 0 where a node has none).
void readDrivenZStates(const Vector& z, const RopeRecord& r, bool rates, Eigen::VectorXd& out) {
    const auto n = static_cast<Eigen::Index>(r.driven.size());
    if (out.size() != n) out.setZero(n);
    for (Eigen::Index d = 0; d < n; ++d) r.driven[static_cast<std::size_t>(d)].role.readZState(z, rates, out[d]);
}
}  // namespace

void ReevingSubsystem::Guts::refreshFromZ(const State& s, PositionCache& pc, bool velocityLevel) const {
    for (size_t i = 0; i < ropes.size(); ++i) {
        RopeCache& c = pc.ropes[i];
        const bool positionsCurrent = matchesZ(s, ropes[i], c, false);
        if (!positionsCurrent) updatePositionPart(s, ropes[i], pc, c);
        if (velocityLevel && (!positionsCurrent || !matchesZ(s, ropes[i], c, true)))
            updateVelocityPart(s, ropes[i], pc, c);
    }
}

bool ReevingSubsystem::Guts::matchesZ(const State& s, const RopeRecord& r, const RopeCache& c,
                                      bool rates) const {
    const Eigen::VectorXd& cached = rates ? c.modalRates : c.modalCoordinates;
    if (cached.size() != r.numModal) return false;
    const Vector& z = getZ(s);
    const int offset = r.zOffset + (rates ? r.numModal : 0);
    for (int j = 0; j < r.numModal; ++j)
        if (cached[j] != z[offset + j]) return false;
    // The driven nodes' Z states (rates) are Z too (DrivenRole::zStateMatches).
    const Eigen::VectorXd& states = rates ? c.drivenZRates : c.drivenZStates;
    if (states.size() != static_cast<Eigen::Index>(r.driven.size())) return false;
    for (std::size_t d = 0; d < r.driven.size(); ++d)
        if (!r.driven[d].role.zStateMatches(z, rates, states[static_cast<Eigen::Index>(d)])) return false;
    return true;
}

void ReevingSubsystem::Guts::updatePositionPart(const State& s, const RopeRecord& r, const PositionCache& pc,
                                                RopeCache& c) const {
    c.nodes3.resize(3, r.numStations());
    for (int k = 0; k < r.numStations(); ++k)  // MobilizedBody::findStationLocationInGround, per body
        c.nodes3.col(k) = toEigen(pc.bodyX[r.nodeSlot[k]] * r.station(k).second);
    modal(getZ(s), r, false, c.modalCoordinates);
    readDrivenZStates(getZ(s), r, false, c.drivenZStates);
    drivenCoordinates(s, r, c, false);
    // A failure here is usually a trial state of an integrator step (an extrapolation too far).
    // What Simbody 3.7 does with the exception (its sources, confirmed in
    // tests/simbody/test_step_failures.cpp): the Runge-Kutta family (AbstractIntegratorRep::
    // attemptDAEStep) catches it, rejects the step and retries at 0.1 h, with no retry limit
    // (counted as a convergence-test failure); CPodes receives a recoverable right-hand-side
    // error and retries at 0.25 h, at most 10 times per step; a fixed-step integrator, the
    // realization of an accepted or interpolated state, and (RK) the realization inside a
    // constraint projection cannot retry and end the run. Every final message drops the cause,
    // so it is recorded here (getLastEvaluationFailure) with the rope, the time and the equation.
    try {
        if (r.planar) {
            c.nodes2.noalias() = r.planeBasis.transpose() * c.nodes3;
            const RopeModel<2>& model = planarModel(s, r);
            if (c.planarModel != &model) {
                // Another traction phase: fresh data for its model (other dependents), warm-started
                // from the material coordinates and amplitudes of the last phase.
                RopeData<2> fresh;
                fresh.materialCoordinates = c.planar.materialCoordinates;
                fresh.condensedAmplitudes = c.planar.condensedAmplitudes;
                c.planar = std::move(fresh);
                c.planarModel = &model;
            }
            // A gripping drum's creep (its Z state; RopeModel::setGrip) lays its stored ring and
            // walks its groove: set after a fresh RopeData (a state's first realization, a new phase).
            c.planar.gripCreep = c.drivenZStates;
            model.solveDependentCoordinates(c.nodes2, c.drivenS, c.modalCoordinates, c.planar);
        } else {
            const RopeModel<3>& model = spatialModel(s, r, c.nodes3);
            if (r.numPhaseNodes > 0 && c.spatialModel != &model) {
                // Another traction phase or other span frames: fresh data for its model, warm-started
                // from the material coordinates and amplitudes of the last one (as planar ropes).
                RopeData<3> fresh;
                fresh.materialCoordinates = c.spatial.materialCoordinates;
                fresh.condensedAmplitudes = c.spatial.condensedAmplitudes;
                c.spatial = std::move(fresh);
            }
            c.spatialModel = &model;
            c.spatial.gripCreep = c.drivenZStates;  // (as planar ropes: after a fresh RopeData)
            model.solveDependentCoordinates(c.nodes3, c.drivenS, c.modalCoordinates, c.spatial);
        }
    } catch (const std::exception& e) {
        failEvaluation(s, r, e);
    }
}

void ReevingSubsystem::Guts::failEvaluation(const State& s, const RopeRecord& r,
                                            const std::exception& e) const {
    std::ostringstream msg;
    msg << "ReevingSubsystem: rope '" << r.spec.name << "' at t = " << std::setprecision(17) << s.getTime()
        << " s: " << e.what();
    recordEvaluationFailure(msg.str());
    throw std::runtime_error(msg.str());
}

void ReevingSubsystem::Guts::updateVelocityPart(const State& s, const RopeRecord& r, const PositionCache& pc,
                                                RopeCache& c) const {
    c.nodeVelocities3.resize(3, r.numStations());
    for (int k = 0; k < r.numStations(); ++k) {  // MobilizedBody::findStationVelocityInGround, per body
        const SimTK::SpatialVec& V = pc.bodyV[r.nodeSlot[k]];
        const Vec3 p = pc.bodyX[r.nodeSlot[k]].R() * r.station(k).second;
        c.nodeVelocities3.col(k) = toEigen(V[1] + V[0] % p);
    }
    modal(getZ(s), r, true, c.modalRates);
    readDrivenZStates(getZ(s), r, true, c.drivenZRates);
    drivenCoordinates(s, r, c, true);
    // The coupled solve of the last realizeDynamics needed S only as products (productCoupling_):
    // then the rope does not form it.
    c.planar.formNodeMass = c.spatial.formNodeMass = !productCoupling_;
    try {
        if (r.planar) {
            c.nodeVelocities2.noalias() = r.planeBasis.transpose() * c.nodeVelocities3;
            planarModel(s, r).computeDynamics(c.nodes2, c.nodeVelocities2, c.drivenS, c.drivenSdot, c.modalCoordinates,
                                           c.modalRates, c.planar);
        } else {
            const RopeModel<3>& model = spatialModel(s, r, c.nodes3);
            c.spatialModel = &model;
            model.computeDynamics(c.nodes3, c.nodeVelocities3, c.drivenS, c.drivenSdot, c.modalCoordinates,
                                  c.modalRates, c.spatial);
        }
    } catch (const std::exception& e) {
        failEvaluation(s, r, e);
    }
}

template <int Dim>
double ReevingSubsystem::Guts::potential(const RopeModel<Dim>& model, const RopeData<Dim>& data,
                                         const Eigen::Matrix<double, Dim, Eigen::Dynamic>& nodes,
                                         const Eigen::VectorXd& qm) const {
    double u = 0;
    Eigen::VectorXd q;
    for (int j = 0; j < model.numSpans(); ++j) {
        model.spanCoordinates(j, nodes, qm, data, q);
        SpanData<Dim> d;
        model.span(j).evaluate(q, Eigen::VectorXd::Zero(q.size()), d);
        u += d.potentialEnergy();
    }
    return u + model.storedRopeGravityEnergy(nodes, data) + model.arcGravityEnergy(nodes, data);
}

Real ReevingSubsystem::Guts::calcPotentialEnergy(const State& s) const {
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
            u += potential(planarModel(s, r), c.planar, planarNodes(r, c.nodes3), modal(getZ(s), r, false));
        } else {
            u += potential(spatialModel(s, r), c.spatial, c.nodes3, modal(getZ(s), r, false));
        }
        for (const RopeRecord::DrivenNode& d : r.driven) d.role.addHeldEnergy(getZ(s), u);
    }
    return u;
}

// ---- decorations (see ReevingSubsystem::setDecorationForceScale for what is drawn) -----------

namespace {

/// The span colour map: blue (0.1, 0.3, 1) at x <= 0 (slack, P = 0), red (1, 0.1, 0.05) at x >= 1.
Vec3 forceColour(double x) {
    x = std::min(std::max(x, 0.0), 1.0);
    return Vec3(0.1, 0.3, 1.0) * (1.0 - x) + Vec3(1.0, 0.1, 0.05) * x;
}

/// Diameter drawn for a rope of mass per length rhoA [kg/m]: a steel wire rope (7850 kg/m^3) whose
/// metal fills 0.6 of its circle [m] (20.8 mm for 1.6 kg/m). Drawing only.
double drawnRopeDiameter(double rhoA) { return std::sqrt(4.0 * rhoA / (SimTK::Pi * 0.6 * 7850.0)); }

/// Axial forces at the midpoints of the numPoints - 1 drawn segments of a span [N].
void segmentForces(const ReevingSubsystem& rv, const State& s, int rope, int span, int numPoints,
                   std::vector<double>& forces) {
    const auto range = rv.getSpanMaterialRange(s, rope, span);
    forces.resize(numPoints - 1);
    for (int k = 0; k + 1 < numPoints; ++k)
        forces[k] = rv.getAxialForce(s, rope, span, range.first + (range.second - range.first) * (k + 0.5) / (numPoints - 1));
}

}  // namespace

void ReevingSubsystem::setDecorationForceScale(double referenceForce) {
    if (!std::isfinite(referenceForce) || referenceForce < 0) {
        std::ostringstream o;
        o << "ReevingSubsystem::setDecorationForceScale: reference force = " << referenceForce
          << " N must be finite and >= 0";
        throw std::invalid_argument(o.str());
    }
    updGuts().decorationForceScale = referenceForce;
}

double ReevingSubsystem::getDecorationForceScale(const State& s) const {
    const Guts& g = getGuts();
    if (g.decorationForceScale > 0) return g.decorationForceScale;
    double largest = 0;
    std::vector<double> forces;
    for (int i = 0; i < getNumRopes(); ++i)
        for (int j = 0; j < getNumSpans(i); ++j) {
            segmentForces(*this, s, i, j, g.decorationPoints, forces);
            for (double f : forces) largest = std::max(largest, f);
        }
    return largest;
}

int ReevingSubsystem::Guts::calcDecorativeGeometryAndAppendImpl(const State& s, Stage stage,
                                                                Array_<DecorativeGeometry>& geometry) const {
    if (stage != Stage::Position) return 0;
    const ReevingSubsystem& rv = static_cast<const ReevingSubsystem&>(getOwnerSubsystemHandle());  // this Guts' handle
    const double reference = rv.getDecorationForceScale(s);
    std::vector<double> forces;
    for (size_t i = 0; i < ropes.size(); ++i) {
        const RopeRecord& r = ropes[i];
        const RopeCache& c = positionCache(s).ropes[i];
        const int rope = static_cast<int>(i);
        // Spans: polylines coloured by the axial force at each segment's midpoint.
        for (int j = 0; j < r.numSpans(); ++j) {
            const std::vector<Vec3> p = sample(s, rope, j, decorationPoints);
            segmentForces(rv, s, rope, j, decorationPoints, forces);
            for (size_t k = 0; k + 1 < p.size(); ++k)
                geometry.push_back(DecorativeLine(p[k], p[k + 1])
                                       .setColor(forceColour(reference > 0 ? forces[k] / reference : 0.0))
                                       .setLineThickness(4));
        }
        // The rope on the grooves of wrapped sheaves, in the colour of the axial force where it
        // arrives (the end of the span before; the tension equality makes it the departing span's).
        for (int k = 1; k + 1 < r.numNodes(); ++k) {
            if (!(r.wraps[k].radius > 0)) continue;
            const std::vector<Vec3> p = rv.sampleArc(s, rope, k, decorationPoints);
            const double arrival = rv.getAxialForce(s, rope, k - 1, rv.getSpanMaterialRange(s, rope, k - 1).second);
            const Vec3 colour = forceColour(reference > 0 ? arrival / reference : 0.0);
            for (size_t m = 0; m + 1 < p.size(); ++m)
                geometry.push_back(DecorativeLine(p[m], p[m + 1]).setColor(colour).setLineThickness(4));
        }
        // Nodes: each kind draws itself (nodes/NodeDrawing.cpp): sheaves and drums at their
        // radius, anchors as small spheres.
        const double d = drawnRopeDiameter(r.spec.properties.massPerLength);
        for (int k = 0; k < r.numNodes(); ++k) {
            const NodeDrawing drawing{s, rv, r, c, k, d, geometry};
            visitNodeKind(r.nodeSpec(k).kind, [&](auto unit) { decltype(unit)::draw(drawing); });
        }
    }
    return 0;
}

// ---- spatial span frames -----------------------------------------------------------------
const SpatialFrames& ReevingSubsystem::Guts::spatialFrames(const State& s) const {
    return Value<SpatialFrames>::downcast(getDiscreteVariable(s, framesVariable_)).get();
}

std::shared_ptr<const RopeModel<3>> ReevingSubsystem::Guts::makeSpatialModel(
    const RopeRecord& r, const std::vector<Eigen::Matrix3d>& references) const {
    std::vector<SpanModel<3>> spans;
    for (int j = 0; j < r.numSpans(); ++j)
        spans.emplace_back(r.spec.properties, r.spanOptions[j], toEigen(gravity_), references[j]);
    auto model = std::make_shared<RopeModel<3>>(std::move(spans), r.spec.unstretchedLength, r.materialKinds, r.wraps);
    r.addStoredRope(*model);
    model->setStationaryNodes(r.stationaryNodes());
    return model;
}

const RopeModel<3>& ReevingSubsystem::Guts::spatialModel(const State& s, const RopeRecord& r,
                                                         const Eigen::Matrix3Xd& nodes) const {
    const SpatialFrames& frames = spatialFrames(s);
    if (!frames.models[r.index]) {
        // The state's first realization to Stage::Position defines its frames, from its own
        // chords. This fills in a value the state did not have yet (nothing computed from it can
        // be stale), so it is written in place rather than through updDiscreteVariable, which
        // would invalidate the stage being realized.
        std::vector<Eigen::Matrix3d> references;
        for (int j = 0; j < r.numSpans(); ++j) {
            const Eigen::Vector3d chord = nodes.col(j + 1) - nodes.col(j);
            if (!(chord.norm() > 0))
                throw std::runtime_error("ReevingSubsystem: rope '" + r.spec.name + "' span " + std::to_string(j) +
                                         ": its end nodes coincide in the configuration that defines its frame");
            references.push_back(makeReferenceFrame(chord));
        }
        const_cast<SpatialFrames&>(frames).models[r.index] = makeSpatialModel(r, references);
    }
    if (r.numPhaseNodes == 0) return *frames.models[r.index];
    return tractionPhaseModel<3>(s, r, frames.models[r.index], r.spatialTractionModels);
}

const RopeModel<3>& ReevingSubsystem::Guts::spatialModel(const State& s, const RopeRecord& r) const {
    const SpatialFrames& frames = spatialFrames(s);
    if (!frames.models[r.index])
        throw std::logic_error("ReevingSubsystem: rope '" + r.spec.name +
                               "': the state has no span frames yet (realize it to Stage::Position first)");
    if (r.numPhaseNodes == 0) return *frames.models[r.index];
    return tractionPhaseModel<3>(s, r, frames.models[r.index], r.spatialTractionModels);
}

double ReevingSubsystem::Guts::frameChangeMargin(const State& s, int rope) const {
    const RopeRecord& r = ropes[rope];
    const RopeCache& c = positionCache(s).ropes[rope];
    const RopeModel<3>& model = spatialModel(s, r);
    double alignment = 2.0;
    for (int j = 0; j < r.numSpans(); ++j)
        alignment = std::min(alignment, referenceAlignment(c.nodes3.col(j + 1) - c.nodes3.col(j),
                                                           model.span(j).referenceFrame()));
    return alignment - frameChangeAlignment;
}

int ReevingSubsystem::Guts::changeSpanFrames(State& s, int rope, bool onlyDue) const {
    const RopeRecord& r = ropes[rope];
    if (r.planar) return 0;
    getSystem().realize(s, Stage::Velocity);
    const RopeCache& c = positionCache(s).ropes[rope];
    const RopeModel<3>& model = spatialModel(s, r);
    const std::shared_ptr<const RopeModel<3>> keep = spatialFrames(s).models[rope];  // outlives the update
    Eigen::VectorXd q = modal(getZ(s), r, false), qdot = modal(getZ(s), r, true);
    std::vector<Eigen::Matrix3d> references;
    int changed = 0;
    for (int j = 0; j < r.numSpans(); ++j) {
        const SpanModel<3>& span = model.span(j);
        const Eigen::Vector3d e = c.nodes3.col(j + 1) - c.nodes3.col(j);
        const Eigen::Vector3d edot = c.nodeVelocities3.col(j + 1) - c.nodeVelocities3.col(j);
        references.push_back(span.referenceFrame());
        if (onlyDue && referenceAlignment(e, span.referenceFrame()) > frameChangeAlignment) continue;
        // The new reference is the current element frame (orthonormalised afresh: i0 along the
        // chord, k0 its k_e), so the chord is aligned with it: 1 + i0 . i_e = 2.
        ChordFrame<3> frame;
        computeChordFrame<3>(e, Eigen::Vector3d::Zero(), span.referenceFrame(), frame);
        const Eigen::Matrix3d next = makeReferenceFrame(e, frame.A.col(2));
        const int nt = span.transverseModes();
        const int first = model.modalOffset(j) + (model.isCondensed(j) ? 0 : span.axialModes());
        // Condensed transverse amplitudes are not states: the next solve finds them in the new frame.
        if (!span.condensesTransverseModes())
            reReferenceTransverseModes(e, edot, span.referenceFrame(), next,
                                   span.options().velocityModel == VelocityModel::Complete, q.segment(first, nt),
                                   q.segment(first + nt, nt), qdot.segment(first, nt), qdot.segment(first + nt, nt));
        references.back() = next;
        ++changed;
    }
    if (changed == 0) return 0;
    std::shared_ptr<const RopeModel<3>> next = makeSpatialModel(r, references);
    Vector& z = updZ(s);
    for (int j = 0; j < r.numModal; ++j) {
        z[r.zOffset + j] = q[j];
        z[r.zOffset + r.numModal + j] = qdot[j];
    }
    SpatialFrames& frames = Value<SpatialFrames>::updDowncast(updDiscreteVariable(s, framesVariable_)).upd();
    frames.models[rope] = std::move(next);
    ++frames.changes[rope];
    return changed;
}

namespace {

/// Witness: the smallest 1 + i0 . i_e over a spatial rope's spans, less frameChangeAlignment;
/// when it falls through zero, the spans due get new reference frames (their current element
/// frames), so no chord ever reaches reversal against its reference.
class SpanFrameEvent : public SimTK::TriggeredEventHandler {
public:
    SpanFrameEvent(const System& system, SubsystemIndex reeving, int rope)
        : SimTK::TriggeredEventHandler(Stage::Position), system_(system), reeving_(reeving), rope_(rope) {
        getTriggerInfo().setTriggerOnRisingSignTransition(false);
        getTriggerInfo().setTriggerOnFallingSignTransition(true);
        getTriggerInfo().setRequiredLocalizationTimeWindow(1e-3);
    }
    Real getValue(const State& s) const override { return guts().frameChangeMargin(s, rope_); }
    void handleEvent(State& s, Real, bool& shouldTerminate) const override {
        shouldTerminate = false;
        guts().changeSpanFrames(s, rope_, true);
    }

private:
    const ReevingSubsystem::Guts& guts() const {
        return dynamic_cast<const ReevingSubsystem::Guts&>(system_.getSubsystem(reeving_).getSubsystemGuts());
    }
    const System& system_;
    SubsystemIndex reeving_;
    int rope_;
};

}  // namespace

void detail::installFrameChangeHandler(System& system, SubsystemIndex reeving, int rope) {
    system.addEventHandler(new SpanFrameEvent(system, reeving, rope));  // the system owns it
}

void ReevingSubsystem::Guts::drivenCoordinates(const State& s, const RopeRecord& r, RopeCache& c, bool rates) const {
    const int n = static_cast<int>(r.driven.size());
    c.drivenS.resize(n);
    c.drivenAngles.resize(n);
    if (rates) {
        c.drivenSdot.resize(n);
        c.drivenAngleRates.resize(n);
    }
    for (int d = 0; d < n; ++d) {
        const RopeRecord::DrivenNode& dn = r.driven[d];
        const DrivenAngleSite site = angleSite(s, r, dn);
        c.drivenAngles[d] = dn.angle.angle(site);
        if (rates) c.drivenAngleRates[d] = dn.angle.rate(site);
        // s = sRef + g(theta), or what the node's role makes of it (a TractionSheave's stick
        // offset is state; in slip with TractionSlip::RopeMomentum s is the state Y).
        double unusedRate = 0;
        dn.role.materialCoordinate(r.drivenRun(*this, d), s, c.drivenAngles[d], rates ? c.drivenAngleRates[d] : 0.0,
                                   rates, c.drivenS[d], rates ? c.drivenSdot[d] : unusedRate);
    }
}

}  // namespace SimbodyReeving
