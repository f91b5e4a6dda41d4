// ReevingSubsystem::findStaticEquilibrium.

#include "ReevingSubsystemGuts.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

using SimTK::MultibodySystem;
using SimTK::SimbodyMatterSubsystem;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vector;

namespace SimbodyReeving {

using namespace detail;

double ReevingSubsystem::findStaticEquilibrium(State& state, double relativeTolerance, int maxIterations) const {
    const Guts& g = getGuts();
    const MultibodySystem& mbs = g.mbs();
    const SimbodyMatterSubsystem& matter = g.matter();
    state.updU() = 0;
    for (int i = 0; i < getNumRopes(); ++i) setModalRates(state, i, Vector(getNumModalCoordinates(i), 0.0));
    const int nu = state.getNU();
    int nm = 0;
    for (int i = 0; i < getNumRopes(); ++i) nm += getNumModalCoordinates(i);
    // Mobilities with prescribed motion (a drum on a speed profile, a trolley on its traverse
    // profile) keep their motion: neither unknowns nor residual rows.
    mbs.realize(state, Stage::Instance);
    std::vector<int> freeU;
    for (SimTK::MobilizedBodyIndex b(0); b < matter.getNumBodies(); ++b) {
        const SimTK::MobilizedBody& mb = matter.getMobilizedBody(b);
        if (mb.isGround() || mb.getUDotMotionMethod(state) != SimTK::Motion::Free) continue;
        for (int k = 0; k < mb.getNumU(state); ++k) freeU.push_back(mb.getFirstUIndex(state) + k);
    }
    const int nf = static_cast<int>(freeU.size());
    const int n = nf + nm;

    // Generalized force residual at zero velocity: bodies M udot, ropes Mbar_mm qddot_m; and the
    // scale: the largest applied generalized force on bodies and rope modes.
    // Evaluated at rest: every speed zero, the prescribed mobilities' too (System::project, below,
    // gives them their prescribed speeds back). Otherwise a drum or brake prescribed to turn at t = 0
    // would feed velocity-dependent forces into the balance (the rope's Kelvin-Voigt damping as the
    // rope is dragged over a turning sheave under bodies at rest), which is no static equilibrium.
    auto residual = [&](State& st, double* scale) {
        st.updU() = 0;
        mbs.realize(st, Stage::Acceleration);
        Eigen::VectorXd r(n);
        Vector Mudot;
        matter.multiplyByM(st, st.getUDot(), Mudot);
        for (int k = 0; k < nf; ++k) r[k] = Mudot[freeU[k]];
        const Vector& zdot = g.getZDot(st);
        const PositionCache& pc = g.positionCache(st);
        int off = nf;
        double fmax = 0;
        for (int i = 0; i < getNumRopes(); ++i) {
            const RopeRecord& rr = g.ropes[i];
            Eigen::VectorXd qdd(rr.numModal);
            for (int j = 0; j < rr.numModal; ++j) qdd[j] = zdot[rr.zOffset + rr.numModal + j];
            const int nn = rr.numExternal();
            const Eigen::MatrixXd& Mbar = rr.planar ? pc.ropes[i].planar.reducedMass() : pc.ropes[i].spatial.reducedMass();
            const Eigen::VectorXd& Qbar = rr.planar ? pc.ropes[i].planar.reducedForce() : pc.ropes[i].spatial.reducedForce();
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
            for (int k = 0; k < nf; ++k) fmax = std::max(fmax, std::abs(applied[freeU[k]]));
            *scale = fmax;
        }
        return r;
    };
    auto displace = [&](State& st, const Eigen::VectorXd& dy) {
        Vector du(nu, 0.0), dq;
        for (int k = 0; k < nf; ++k) du[freeU[k]] = dy[k];
        mbs.realize(st, Stage::Position);
        matter.multiplyByN(st, false, du, dq);
        st.updQ() += dq;
        int off = nf;
        for (int i = 0; i < getNumRopes(); ++i) {
            Vector q = getModalCoordinates(st, i);
            for (int j = 0; j < q.size(); ++j) q[j] += dy[off + j];
            setModalCoordinates(st, i, q);
            off += q.size();
        }
        mbs.realize(st, Stage::Position);
        mbs.project(st, 1e-12);
    };

    // On return: free speeds zero, prescribed ones at their motion's values.
    auto restorePrescribedSpeeds = [&](double rel) {
        mbs.realize(state, Stage::Time);
        mbs.prescribe(state);
        return rel;
    };
    // Nothing free (every mobility prescribed or locked, no rope mode): the state is what it is
    // (the residual below would be empty).
    if (n == 0) return restorePrescribedSpeeds(0.0);
    double scale = 0;
    Eigen::VectorXd r = residual(state, &scale);
    for (int iter = 0; iter < maxIterations; ++iter) {
        const double rel = r.cwiseAbs().maxCoeff() / scale;
        if (rel <= relativeTolerance) return restorePrescribedSpeeds(rel);
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
        Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(-r);
        // Step limit: a tension-only rope that is slack has no stiffness, so the Newton step of a
        // body hanging from it is (nearly) unbounded; each iteration moves a mobility by at most
        // kMaxStep (m or rad) and a modal coordinate by as much, and the body falls until the
        // rope takes it over a few iterations.
        constexpr double kMaxStep = 0.5;
        const double largest = step.cwiseAbs().maxCoeff();
        if (largest > kMaxStep) step *= kMaxStep / largest;
        // Backtracking; a trial state the rope cannot evaluate (its Newton fails, a span would lose
        // its material) counts as worse. Merit: the residual norm (Newton steps), or the potential
        // energy (steps along the net force). The last halving is accepted as it is when
        // `acceptLast`.
        auto potential = [&](State& st) {
            mbs.realize(st, Stage::Dynamics);
            return mbs.calcPotentialEnergy(st);
        };
        auto lineSearch = [&](const Eigen::VectorXd& direction, bool energyMerit, bool acceptLast) {
            double alpha = 1.0;
            const double m0 = energyMerit ? potential(state) : r.norm();
            for (int ls = 0; ls < 20; ++ls, alpha *= 0.5) {
                State trial = state;
                try {
                    displace(trial, alpha * direction);
                    const double m = energyMerit ? potential(trial) : residual(trial, nullptr).norm();
                    // Sufficient decrease (Armijo, 1e-3): a Newton step that barely changes
                    // |r| (a body in free fall under slack ropes) is not progress.
                    const double required = energyMerit ? m0 : (1.0 - 1e-3 * alpha) * m0;
                    if (!(m < required) && !(acceptLast && ls == 19)) continue;
                } catch (const std::exception&) {
                    continue;
                }
                state = trial;
                r = residual(state, &scale);
                return true;
            }
            return false;
        };
        const double before = r.norm();
        bool moved = lineSearch(step, false, false);
        // Where the Jacobian is (nearly) singular, as for a body hanging from slack ropes, the
        // Newton step may not move it: step along the net generalized force instead (downhill in
        // potential energy), kMaxStep at most.
        if (!moved || !(r.norm() < before)) {
            const double rmax = r.cwiseAbs().maxCoeff();
            if (rmax > 0) moved = lineSearch(Eigen::VectorXd(r * (kMaxStep / rmax)), true, false) || moved;
        }
        if (!moved) moved = lineSearch(step, false, true);
        if (!moved) break;  // no acceptable step: report the residual reached
    }
    const double rel = r.cwiseAbs().maxCoeff() / scale;
    if (rel <= relativeTolerance) return restorePrescribedSpeeds(rel);
    restorePrescribedSpeeds(rel);
    std::ostringstream msg;
    msg << "ReevingSubsystem::findStaticEquilibrium: no convergence in " << maxIterations
        << " iterations (relative residual " << rel << ")";
    throw std::runtime_error(msg.str());
}

}  // namespace SimbodyReeving
