// Randomized robustness (issue 14), fixed seeds: thousands of random, often hostile, inputs (NaN,
// inf, huge, tiny, negative, degenerate geometry, coincident nodes, sheaves on moving bodies).
// Each must end in a documented exception at set-up, or evaluate/simulate to finite numbers, or
// stop with a clear exception naming what failed -- never a crash, a hang, or NaN in an output.
#include "SimbodyReeving/simbody/InterpolatingTimeStepper.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "SimbodyReeving/element/SpanModel.h"

#include <gtest/gtest.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>

using namespace SimbodyReeving;
using SimTK::MobilizedBody;
using SimTK::Vec3;

namespace {

/// Mostly ordinary values in [lo, hi], sometimes hostile ones.
class Hostile {
public:
    explicit Hostile(unsigned seed) : rng_(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    bool chance(double p) { return uniform(0, 1) < p; }
    double value(double lo, double hi, double hostileProbability = 0.1) {
        if (!chance(hostileProbability)) return uniform(lo, hi);
        static const double specials[] = {std::numeric_limits<double>::quiet_NaN(),
                                          std::numeric_limits<double>::infinity(),
                                          -std::numeric_limits<double>::infinity(),
                                          0.0, -1.0, 1e300, -1e300, 1e-300, 1e-12, 1e12};
        return specials[integer(0, 9)];
    }
    Vec3 point(double scale, double hostileProbability = 0.05) {
        return Vec3(value(-scale, scale, hostileProbability), value(-scale, scale, hostileProbability),
                    value(-scale, scale, hostileProbability));
    }

private:
    std::mt19937_64 rng_;
};

bool allFinite(const SpanData<2>& d) {
    return d.massMatrix.allFinite() && d.velocityForces.allFinite() && d.elasticForces.allFinite() &&
           d.gravityForces.allFinite() && std::isfinite(d.kineticEnergy + d.axialEnergy + d.bendingEnergy +
                                                        d.stringEnergy + d.gravityEnergy);
}

}  // namespace

// 4 000 random spans and states: construction throws std::invalid_argument, or evaluation throws
// std::invalid_argument / std::domain_error, or every output is finite.
TEST(Robustness, RandomSpansAndStates) {
    Hostile h(20261129);
    std::map<std::string, int> outcomes;
    for (int trial = 0; trial < 4000; ++trial) {
        RopeProperties p{h.value(0.01, 10), h.value(1e3, 1e9), h.value(0, 1e3)};
        p.tensionOnly = h.chance(0.5);
        SpanOptions o;
        o.axialModes = h.chance(0.05) ? h.integer(-2, 20) : h.integer(0, 4);
        o.transverseModes = h.chance(0.05) ? h.integer(-2, 20) : h.integer(0, 3);
        o.velocityModel = h.chance(0.5) ? VelocityModel::Simplified : VelocityModel::Complete;
        o.axialDynamics = h.chance(0.3) ? AxialDynamics::QuasiStatic : AxialDynamics::Dynamic;
        o.elasticModel = h.chance(0.1) ? ElasticEnergyModel::PaperLiteral : ElasticEnergyModel::Consistent;
        o.quadraturePoints = h.chance(0.05) ? h.integer(-5, 300) : 0;
        const Eigen::Vector2d g(h.value(-1, 1, 0.02), h.value(-10, 0, 0.02));
        std::unique_ptr<PlanarSpanModel> span;
        try {
            span = std::make_unique<PlanarSpanModel>(p, o, g);
        } catch (const std::invalid_argument&) {
            ++outcomes["construction: invalid_argument"];
            continue;
        }
        const int n = span->numCoordinates();
        Eigen::VectorXd q(n), qd(n);
        const double l = h.value(0.01, 100, 0.05);
        q.setZero();
        q.segment<2>(0) = Eigen::Vector2d(h.value(-50, 50, 0.02), h.value(-50, 50, 0.02));
        const double chordScale = h.chance(0.05) ? 0.0 : h.uniform(0.2, 1.5);  // 0: coincident nodes
        q.segment<2>(2) = q.segment<2>(0) + chordScale * std::abs(l) * Eigen::Vector2d(h.uniform(-1, 1), h.uniform(-1, 1)).normalized();
        for (int i = 4; i < n - 2; ++i) q[i] = h.value(-0.05, 0.05, 0.02) * std::abs(l);
        q[n - 2] = h.value(0, 10, 0.02);
        q[n - 1] = q[n - 2] + l;
        for (int i = 0; i < n; ++i) qd[i] = h.value(-5, 5, 0.02);
        PlanarSpanModel::Data d;
        try {
            span->evaluate(q, qd, d);
        } catch (const std::invalid_argument&) {
            ++outcomes["evaluate: invalid_argument"];
            continue;
        } catch (const std::domain_error&) {
            ++outcomes["evaluate: domain_error"];
            continue;
        }
        ASSERT_TRUE(allFinite(d)) << "trial " << trial << ": non-finite output for q = " << q.transpose();
        ++outcomes["evaluate: finite"];
    }
    std::printf("random spans:");
    for (const auto& [k, v] : outcomes) std::printf("  %s %d;", k.c_str(), v);
    std::printf("\n");
    EXPECT_GT(outcomes["evaluate: finite"], 1500);  // the generator mostly makes usable spans
}

namespace {

struct SceneOutcome {
    std::string kind;  // what ended the case
    std::string message;
};

/// One random scene: a rope from a ground anchor over 0-3 sheaves (on Ground or on a free body) to a
/// free hook, random everything; 0.05 s of RK-Merson.
SceneOutcome randomScene(Hostile& h) {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter(system);
    SimTK::GeneralForceSubsystem forces(system);
    const Vec3 gravity(0, -9.81, 0);
    SimTK::Force::Gravity grav(forces, matter, gravity);
    std::unique_ptr<ReevingSubsystem> reeving;
    try {
        reeving = std::make_unique<ReevingSubsystem>(system, h.chance(0.03) ? h.point(10, 1.0) : gravity);
    } catch (const std::invalid_argument& e) {
        return {"setup: invalid_argument", e.what()};
    }
    const auto body = SimTK::Body::Rigid(SimTK::MassProperties(h.uniform(1, 1e4), Vec3(0), SimTK::Inertia(h.uniform(0.1, 100))));
    MobilizedBody::Free hook(matter.Ground(), SimTK::Transform(h.point(30, 0.0)), body, SimTK::Transform());
    MobilizedBody::Free block(matter.Ground(), SimTK::Transform(h.point(30, 0.0)), body, SimTK::Transform());
    RopeSpec spec;
    spec.name = "random rope";
    spec.start = RopeAnchor{matter.Ground(), h.point(30)};
    const int sheaves = h.integer(0, 3);
    double path = 0;
    Vec3 previous = spec.start.point;
    for (int k = 0; k < sheaves; ++k) {
        const bool onBlock = h.chance(0.3);
        const Vec3 at = onBlock ? h.point(0.5) : h.point(30);
        DeviationSheave sheave;
        sheave.body = onBlock ? static_cast<const MobilizedBody&>(block) : static_cast<const MobilizedBody&>(matter.Ground());
        sheave.centre = at;
        sheave.radius = h.value(0.01, 0.5);
        spec.sheaves.push_back(sheave);
        path += (at - previous).norm();
        previous = at;
    }
    spec.end = RopeAnchor{hook, h.chance(0.1) ? h.point(1) : Vec3(0)};
    path += 30;
    spec.properties = {h.value(0.01, 5), h.value(1e4, 1e9), h.value(0, 100), h.chance(0.3)};
    spec.unstretchedLength = h.chance(0.05) ? h.value(-1, 1, 1.0) : path * h.uniform(0.3, 2.0);
    spec.spanDefaults.axialModes = h.chance(0.05) ? h.integer(-1, 20) : h.integer(0, 2);
    spec.spanDefaults.transverseModes = h.chance(0.05) ? h.integer(-1, 20) : h.integer(0, 2);
    spec.spanDefaults.axialDynamics = h.chance(0.5) ? AxialDynamics::QuasiStatic : AxialDynamics::Dynamic;
    spec.spanDefaults.velocityModel = VelocityModel::Simplified;  // pre-issue-19 default, explicit
    spec.planeNormal = h.chance(0.5) ? Vec3(0) : (h.chance(0.8) ? Vec3(0, 0, 1) : h.point(1, 0.3));
    try {
        reeving->addRope(spec);
        system.realizeTopology();
    } catch (const std::invalid_argument& e) {
        return {"setup: invalid_argument", e.what()};
    } catch (const std::logic_error& e) {  // the rope's gravity disagrees with the Force::Gravity
        return {"setup: logic_error", e.what()};
    }
    SimTK::State s = system.getDefaultState();
    hook.setQToFitTranslation(s, h.point(40, 0.0));
    hook.setUToFitLinearVelocity(s, h.point(5, 0.0));
    SimTK::RungeKuttaMersonIntegrator integ(system);
    integ.setAccuracy(1e-4);
    InterpolatingTimeStepper ts(system, integ);
    ts.setStepLimit(20000);
    try {
        ts.initialize(s);
        for (int k = 1; k <= 5; ++k) {
            if (ts.stepTo(0.01 * k) == SimTK::Integrator::ReachedStepLimit)
                return {"simulation: stopped at the step limit (stiff, not hung)", ""};
            const SimTK::State& st = ts.getState();
            system.realize(st, SimTK::Stage::Velocity);
            const double e = reeving->calcMechanicalEnergy(st);
            const Vec3 x = hook.getBodyOriginLocation(st);
            double force = 0;
            for (int span = 0; span < reeving->getNumSpans(0); ++span)
                force += reeving->getAxialForce(st, 0, span, reeving->getSpanMaterialRange(st, 0, span).second);
            if (!std::isfinite(e) || !x.isFinite() || !std::isfinite(force))
                return {"NON-FINITE OUTPUT", "t = " + std::to_string(st.getTime())};
        }
    } catch (const std::invalid_argument& e) {
        return {"simulation: invalid_argument", e.what()};
    } catch (const std::domain_error& e) {
        return {"simulation: domain_error", e.what()};
    } catch (const std::runtime_error& e) {
        return {"simulation: runtime_error", e.what()};
    } catch (const SimTK::Exception::Base& e) {
        // The integrator gave up (trial evaluations kept failing): Simbody's message drops the cause,
        // the subsystem keeps it.
        if (reeving->getNumEvaluationFailures() > 0)
            return {"simulation: integrator gave up, rope's cause kept", reeving->getLastEvaluationFailure()};
        return {"simulation: SimTK exception", e.what()};
    }
    return {"simulation: finite to the end", ""};
}

}  // namespace

// 90 random scenes, 0.05 s each. The first 90 of the seed's stream cover every outcome that its 150
// did (measured 2026-12-01: 44 finite to the end, 3 integrator gave up with the rope's cause kept, 2
// stopped at the step limit, the rest invalid_argument at set-up); scenes 90-149 added no kind but
// 44 % of the run time (56 of 126 s wall on a loaded machine: five of them take 4-20 s each).
TEST(Robustness, RandomScenesSimulateOrFailCleanly) {
    Hostile h(777);
    std::map<std::string, int> outcomes;
    std::map<std::string, std::string> example;
    for (int trial = 0; trial < 90; ++trial) {
        const SceneOutcome r = randomScene(h);
        ++outcomes[r.kind];
        if (!example.count(r.kind)) example[r.kind] = r.message.substr(0, 300);
        ASSERT_NE(r.kind, "NON-FINITE OUTPUT") << "trial " << trial << ": " << r.message;
    }
    std::printf("random scenes:\n");
    for (const auto& [k, v] : outcomes) std::printf("  %4d  %s   e.g. %s\n", v, k.c_str(), example[k].c_str());
    EXPECT_GT(outcomes["simulation: finite to the end"], 40);  // measured 44 of 90 (2026-12-01)
}
