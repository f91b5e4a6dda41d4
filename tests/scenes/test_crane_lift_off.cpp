// The crane's lift-off scenario (CraneScenario::LiftOff): a payload resting on a compliant floor is
// picked up through a slack sling by the hoist at a steady speed v_h. With a light rope its peak
// rope force is that of a mass M picked up by a spring k at v_h, M g + v_h sqrt(k M): at lift-off
// the load is at rest and the rope at its static stretch, stretching at v_h, so the load bounces
// with amplitude v_h / omega, omega = sqrt(k / M), and the dynamic factor is
//     phi = 1 + v_h sqrt(k / M) / g,   k = n^2 EA / (the falls' length)  (n EA / h for equal falls).
// As the rope's mass grows the factor falls below that. The energy balance against the hoist's
// work and the contacts' dissipation closes throughout.
#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace SimbodyReeving;
using SimTK::Stage;
using SimTK::State;

namespace {

// The crane demo's defaults (examples/crane/CraneCli.h): n_a = 1 quasi-static, n_t = 1 per fall.
SpanOptions demoSpans() {
    SpanOptions o;
    o.axialModes = 1;
    o.transverseModes = 1;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    return o;
}

// The figures below were measured with the paper's point sheaves (the wrapped sheaves' stiff-contact
// case is its own check in LightRopeDynamicFactorIsThatOfAMassPickedUpByASpring).
CraneParameters liftOffParameters(double hoistSpeed, double rhoA, SheaveModel sheaves = SheaveModel::Point) {
    CraneParameters p;
    p.sheaveModel = sheaves;
    p.scenario = CraneScenario::LiftOff;
    p.hoistSpeed = hoistSpeed;
    p.rhoA = rhoA;
    return p;
}

struct LiftOffRun {
    double closedForm = 0;      // 1 + v_h sqrt(k / M) / g
    double staticForce = 0;     // CraneScene::staticRopeForce [N]
    double peak = 0;            // largest CraneScene::ropeForce [N]
    double phi = 0;             // peak / staticForce
    double peakTime = 0, liftOffTime = -1, estimatedLiftOff = 0;  // [s]
    double maxResidual = 0;     // max |E - E0 + W_contact - W_motion| [J]
    double maxWithoutContacts = 0;  // the same balance without W_contact [J]
    double maxWork = 0;         // max |W_motion| [J]
    double contactWork = 0;     // W_contact at the end [J]
    long steps = 0;
};

// Runs the lift-off cycle (RK-Merson at the demo's accuracy 1e-6) and samples every 5 ms until
// 10 ms before the sling is taut, then every 0.25 ms (the peak to (omega dt)^2 / 8 = 1.4e-5 of the
// bounce's amplitude at omega = 42 rad/s).
LiftOffRun runLiftOff(const CraneParameters& p) {
    const CraneCycle cycle = CraneCycle::liftOff(p);
    CraneScene scene(p, cycle, demoSpans());
    State s = scene.makeInitialState();
    scene.system().realize(s, Stage::Acceleration);
    const double e0 = scene.reeving().calcMechanicalEnergy(s);
    SimTK::RungeKuttaMersonIntegrator integ(scene.system());
    integ.setAccuracy(1e-6);
    InterpolatingTimeStepper ts(scene.system(), integ);
    ts.initialize(s);
    LiftOffRun r;
    r.closedForm = scene.springMassDynamicFactor();
    r.staticForce = scene.staticRopeForce();
    const double taut = p.hoistRamp + p.slackTime;
    r.estimatedLiftOff = taut + p.payloadMass * p.g / (scene.hookStiffness() * p.hoistSpeed);
    double t = 0, previousFloor = scene.floorForce(s);
    std::vector<double> liftOffs;  // times the floor's force fell to zero
    while (t < cycle.duration - 1e-12) {
        t = std::min(cycle.duration, t + (t < taut - 0.01 ? 5e-3 : 2.5e-4));
        ts.stepTo(t);
        const State& st = ts.getState();
        scene.system().realize(st, Stage::Acceleration);
        const double f = scene.ropeForce(st), floor = scene.floorForce(st);
        if (f > r.peak) {
            r.peak = f;
            r.peakTime = t;
        }
        if (previousFloor > 0 && floor <= 0) liftOffs.push_back(t);
        previousFloor = floor;
        const double residual = scene.energyResidual(st, e0), w = scene.workMeter().getWork(st);
        r.maxResidual = std::max(r.maxResidual, std::abs(residual));
        r.maxWithoutContacts = std::max(r.maxWithoutContacts, std::abs(residual - scene.contactDissipation(st)));
        r.maxWork = std::max(r.maxWork, std::abs(w));
        r.contactWork = scene.contactDissipation(st);
    }
    // The last time the floor let go before the peak (the payload may bounce on the floor as the
    // sling jerks taut).
    for (double x : liftOffs)
        if (x <= r.peakTime) r.liftOffTime = x;
    r.phi = r.peak / r.staticForce;
    r.steps = integ.getNumStepsTaken();
    return r;
}

// The energy balance E(t) - E(0) + W_contact(t) = W_motion(t) (CraneScene::energyResidual) at
// RK-Merson 1e-6, sampled as above. Measured over the eight runs of this file (v_h 0.1 .. 0.3,
// rhoA 0.016 .. 2.4 kg/m, the contacts 10x stiffer in one): at most 2.7e-7 of max |W_motion|
// (4.8e-4 J of 1.77 kJ, v_h = 0.2 m/s, the light rope); bound 2e-6, margin 7x. The effect it
// verifies: the contacts' dashpots dissipate about 1/2 m_hook v_h^2 as the sling stops the hook
// block (1.1 J at 0.1 m/s, 4.1 J at 0.2 m/s: 2.3e-3 of W_motion there), 650x the bound or more.
constexpr double kEnergyBound = 2e-6;

void expectEnergyBalance(const LiftOffRun& r, const char* what) {
    EXPECT_LE(r.maxResidual, kEnergyBound * r.maxWork) << what;
    EXPECT_GT(r.maxWithoutContacts, 5 * kEnergyBound * r.maxWork) << what;  // the bound separates the models
    EXPECT_GT(r.contactWork, 0.0) << what;
}

}  // namespace

TEST(CraneLiftOff, ScenarioNamesAndBadParameters) {
    EXPECT_STREQ(toString(CraneScenario::Cycle), "cycle");
    EXPECT_STREQ(toString(CraneScenario::LiftOff), "lift-off");
    EXPECT_EQ(craneScenarioFromString("lift-off"), CraneScenario::LiftOff);
    EXPECT_THROW_MESSAGE(craneScenarioFromString("liftoff"), std::invalid_argument,
                         "crane scenario 'liftoff' is not one of cycle, lift-off");
    CraneParameters p = liftOffParameters(0.3, 1.6);
    p.hoistSpeed = 0;
    EXPECT_THROW_MESSAGE(CraneCycle::liftOff(p), std::invalid_argument,
                         "CraneParameters: hoistSpeed = 0 must be finite and > 0");
    p = liftOffParameters(0.3, 1.6);
    p.floorDampingRatio = -1;
    EXPECT_THROW_MESSAGE(CraneScene(p, CraneCycle::liftTraverseLower(), demoSpans()), std::invalid_argument,
                         "CraneParameters: floorDampingRatio = -1 must be finite and >= 0");
    p = liftOffParameters(0.3, 1.6);
    p.slingStiffness = std::nan("");
    EXPECT_THROW_MESSAGE(CraneCycle::liftOff(p), std::invalid_argument,
                         "CraneParameters: slingStiffness = nan must be finite and > 0");
    // The slack must fit in the sling: 0.3 (0.25 + 4) = 1.275 m > 2 - 0.75 m.
    p = liftOffParameters(0.3, 1.6);
    p.slackTime = 4;
    EXPECT_THROW_MESSAGE(CraneScene(p, CraneCycle::liftOff(p), demoSpans()), std::invalid_argument,
                         "CraneParameters: lift-off: the slack hoistSpeed (hoistRamp / 2 + slackTime) = 1.275 m "
                         "must be less than the sling's length, slingLength - payloadHeight / 2");
}

// At t = 0 the payload stands on the floor, the hook block hangs from the rope above it with the
// sling slack by v_h (hoistRamp / 2 + slackTime), and the hoist's program reaches v_h before the
// sling is taut and holds it to the cycle's end.
TEST(CraneLiftOff, StartsOnTheFloorWithTheSlingSlack) {
    const CraneParameters p = liftOffParameters(0.2, 1.6);
    const CraneCycle cycle = CraneCycle::liftOff(p);
    CraneScene scene(p, cycle, demoSpans());
    const State s = scene.makeInitialState();
    scene.system().realize(s, Stage::Acceleration);
    const double slack = 0.2 * (0.5 * p.hoistRamp + p.slackTime);
    EXPECT_NEAR(scene.ropeSlack(), slack, 1e-15);
    // The floor carries the payload, nothing else: a static equilibrium to 1e-9 of the largest
    // force, so the floor's force is the payload's weight to about that.
    EXPECT_NEAR(scene.floorForce(s), p.payloadMass * p.g, 1e-6 * p.payloadMass * p.g);
    EXPECT_EQ(scene.slingForce(s), 0.0);
    EXPECT_LT(scene.payloadClearance(s), 0.0);  // pressed into the compliant floor by 2.5e-5 m
    EXPECT_GT(scene.payloadClearance(s), -2 * p.payloadMass * p.g / p.floorStiffness);
    // The rope holds the hook block and its own weight: (m_hook g + rhoA g l) within the n_a = 1
    // series' end bias at the falls' tops (measured 49 N of 2.67 kN; bound 5 %, 133 N: margin 2.7x;
    // the payload's weight, 49 kN, would be 370x the bound).
    const double hanging = p.hookMass * p.g + p.rhoA * p.g * (scene.fallsLength() + 4 * slack);
    EXPECT_NEAR(scene.ropeForce(s), hanging, 0.05 * hanging);
    // The hook at its depth (the rope's unstretched length set for the hook block's weight).
    EXPECT_NEAR(p.railHeight - scene.hookPosition(s)[1], p.initialHookDepth, 1e-3);
    // The hoist: steady at v_h from hoistRamp to the end, the slack taken up at hoistRamp + slackTime.
    const double taut = p.hoistRamp + p.slackTime;
    for (double t : {p.hoistRamp, taut, 0.5 * (taut + cycle.duration), cycle.duration})
        EXPECT_NEAR(cycle.hoist.velocity(t), 0.2, 1e-15) << t;
    EXPECT_NEAR(cycle.hoist.position(taut), slack, 1e-15);
    EXPECT_EQ(cycle.traverse.moves.size(), 0u);
    EXPECT_GT(cycle.duration, taut);
}

// The light rope (rhoA = 0.016 kg/m: 0.7 kg in the falls, 1.4e-4 of the lifted
// 5.2 t) at three hoisting speeds. The dynamic factor phi = peak / static rope force against
// 1 + v_h sqrt(k / M) / g, k = n^2 EA / l_falls = 8.99e6 N/m, M = 5 200 kg: measured -0.20 %,
// -0.28 %, -0.33 % at v_h = 0.1, 0.2, 0.3 m/s (phi 1.421, 1.845, 2.273); bound 1 %, margin 3x.
// What the model adds to the closed form is the floor's and the sling's compliance (2e9 N/m
// each, 220x k): the payload rises a little while the floor unloads and the sling stretches in
// series with the rope. With both 10x stiffer the factor comes within 3.9e-6 of the closed form
// (v_h = 0.2; bound 1e-4, margin 25x): the departure is theirs.
TEST(CraneLiftOff, LightRopeDynamicFactorIsThatOfAMassPickedUpByASpring) {
    for (double v : {0.1, 0.2, 0.3}) {
        const CraneParameters p = liftOffParameters(v, 0.016);
        const LiftOffRun r = runLiftOff(p);
        std::printf("[ lift-off ] v_h = %.2f m/s, light rope: phi %.5f (peak %.1f N over static %.1f N), "
                    "1 + v_h sqrt(k/M)/g = %.5f, departure %+.3e; lift-off at %.4f s (estimate %.4f s), peak at "
                    "%.4f s, %ld steps, energy residual %.2e of %.1f J (contacts dissipated %.3f J)\n",
                    v, r.phi, r.peak, r.staticForce, r.closedForm, r.phi / r.closedForm - 1, r.liftOffTime,
                    r.estimatedLiftOff, r.peakTime, r.steps, r.maxResidual, r.maxWork, r.contactWork);
        EXPECT_NEAR(r.phi / r.closedForm, 1.0, 0.01) << v;
        // The load lifts off where the rope's force has grown by its weight at k v_h from the sling's
        // tightening: measured 0.1 .. 0.2 ms after that estimate (the floor's and the sling's
        // stretch; the samples are 0.25 ms apart), bound 2 ms; the peak a quarter bounce period
        // (37 ms) later.
        EXPECT_NEAR(r.liftOffTime, r.estimatedLiftOff, 0.002) << v;
        EXPECT_GT(r.peakTime, r.liftOffTime) << v;
        expectEnergyBalance(r, "light rope");
    }
    CraneParameters stiff = liftOffParameters(0.2, 0.016);
    stiff.floorStiffness *= 10;
    stiff.slingStiffness *= 10;
    const LiftOffRun r = runLiftOff(stiff);
    std::printf("[ lift-off ] v_h = 0.20 m/s, light rope, floor and sling 10x stiffer: phi %.5f against %.5f "
                "(departure %+.3e)\n",
                r.phi, r.closedForm, r.phi / r.closedForm - 1);
    EXPECT_NEAR(r.phi / r.closedForm, 1.0, 1e-4);
    expectEnergyBalance(r, "stiff contacts");
    // The same with wrapped sheaves (the falls vertical, the rope on the grooves inextensible, so
    // k = n^2 EA / l_falls again): departure measured -1.68e-4 (-8.9e-4 with the contacts 3x
    // stiffer instead of 10x: the contacts' compliance, falling as they stiffen; the point model's
    // -3.9e-6 above is -7.4e-4 at 3x, so part of its small value is a cancellation). Bound 2e-3:
    // margin 12x.
    CraneParameters stiffWrapped = liftOffParameters(0.2, 0.016, SheaveModel::Wrapped);
    stiffWrapped.floorStiffness *= 10;
    stiffWrapped.slingStiffness *= 10;
    const LiftOffRun w = runLiftOff(stiffWrapped);
    std::printf("[ lift-off ] wrapped sheaves, v_h = 0.20 m/s, light rope, floor and sling 10x stiffer: phi %.5f "
                "against %.5f (departure %+.3e)\n",
                w.phi, w.closedForm, w.phi / w.closedForm - 1);
    EXPECT_NEAR(w.phi / w.closedForm, 1.0, 2e-3);
    expectEnergyBalance(w, "stiff contacts, wrapped sheaves");
}

// How the factor departs from the spring-mass one as the rope gets heavier (v_h = 0.2 m/s; rhoA
// 0.016, 0.8, 1.6 (the crane's 20 mm rope), 2.4 kg/m: 0.7, 35, 70, 106 kg in the falls, up to 2.0 %
// of the lifted mass). The static force gains the falls' weight faster than the peak gains from
// the rope's inertia, and the factor falls: measured 1.8452, 1.8388, 1.8302, 1.8105, departures
// -0.28 %, -0.63 %, -1.09 %, -2.16 % from 1 + v_h sqrt(k / M) / g = 1.8504. Asserted: strictly
// falling, the heaviest more than 1 % below the closed form; the values are printed. (Heavier
// still the fall does not go on steadily: 1.797, 1.808, 1.811 at 3.2, 4.8, 6.4 kg/m, as the rope's
// inertia loads the falls' tops at the peak's acceleration.)
TEST(CraneLiftOff, HeavierRopeLowersTheDynamicFactor) {
    std::vector<double> phi;
    double closedForm = 0;
    for (double rhoA : {0.016, 0.8, 1.6, 2.4}) {
        const CraneParameters p = liftOffParameters(0.2, rhoA);
        const LiftOffRun r = runLiftOff(p);
        const double ropeMass = rhoA * 4 * p.initialHookDepth;
        std::printf("[ lift-off ] rhoA %5.3f kg/m (%6.1f kg in the falls, %.2e of M): phi %.5f, 1 + v_h sqrt(k/M)/g "
                    "%.5f, departure %+.3e, static force %.1f N, peak %.1f N; energy residual %.2e of %.1f J\n",
                    rhoA, ropeMass, ropeMass / (p.payloadMass + p.hookMass), r.phi, r.closedForm,
                    r.phi / r.closedForm - 1, r.staticForce, r.peak, r.maxResidual, r.maxWork);
        if (!phi.empty()) {
            EXPECT_LT(r.phi, phi.back()) << rhoA;
        }
        phi.push_back(r.phi);
        closedForm = r.closedForm;
        expectEnergyBalance(r, "rope mass");
    }
    EXPECT_LT(phi.back() / closedForm - 1, -0.01);
}
