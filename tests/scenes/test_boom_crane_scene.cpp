#include <SimbodyReeving/scenes/BoomCraneScene.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>

using namespace SimbodyReeving;
using SimTK::Stage;
using SimTK::State;

namespace {
SpanOptions spans() {
    SpanOptions o;
    o.axialModes = 1;
    o.transverseModes = 1;
    o.axialDynamics = AxialDynamics::QuasiStatic;
    return o;
}
}  // namespace

TEST(BoomCraneScene, Scratch) {
    for (SheaveModel m : {SheaveModel::Wrapped, SheaveModel::Point}) {
        BoomCraneParameters p;
        p.sheaveModel = m;
        BoomCraneScene scene(p, BoomCraneCycle::liftSlewLower(p), spans());
        State s;
        {
            State d = scene.system().getDefaultState();
            scene.boom().setOneQ(d, 0, p.boomAngle);
            d.setTime(0);
            scene.system().realize(d, Stage::Time);
            scene.system().prescribe(d);
            {
                const double b = p.boomAngle;
                const SimTK::Vec3 tip = p.boomFoot + SimTK::Vec3(std::cos(b), std::sin(b), 0) * p.boomLength;
                scene.hookBlock().setQToFitTransform(d, SimTK::Transform(tip + SimTK::Vec3(m == SheaveModel::Wrapped ? p.hoistSheaveRadius : 0, -p.initialHookDepth, 0)));
            }
            scene.system().realize(d, Stage::Position);
            std::printf("hook at %s\n", std::to_string(scene.hookPosition(d)[1]).c_str());
            try {
                scene.system().realize(d, Stage::Acceleration);
                std::cout << "udot " << d.getUDot() << "\n";
                for (int r = 0; r < 2; ++r) for (int k = 0; k < 4; ++k) std::printf("F %d %d %.1f\n", r, k, scene.spanForce(d, r, k));
            } catch (const std::exception& e) { std::printf("realize: %s\n", e.what()); }
        }
        try { s = scene.makeInitialState(); } catch (const std::exception& e) {
            std::printf("FAILED: %s\nlast: %s (%d failures)\n", e.what(), scene.reeving().getLastEvaluationFailure().c_str(), scene.reeving().getNumEvaluationFailures());
            throw;
        }
        scene.system().realize(s, Stage::Acceleration);
        std::printf("boom %.4f deg hook %s radius %.3f\n", scene.boomAngle(s) * 180 / SimTK::Pi,
                    std::to_string(scene.hookPosition(s)[1]).c_str(), scene.hookRadius(s));
        for (int r = 0; r < 2; ++r)
            for (int k = 0; k < 4; ++k) std::printf("rope %d span %d force %.1f\n", r, k, scene.spanForce(s, r, k));
        const double e0 = scene.reeving().calcMechanicalEnergy(s);
        SimTK::RungeKuttaMersonIntegrator integ(scene.system());
        integ.setAccuracy(1e-6);
        InterpolatingTimeStepper ts(scene.system(), integ);
        ts.initialize(s);
        for (double t = 1; t <= 40; t += 1) {
            ts.stepTo(t);
            const State& st = ts.getState();
            scene.system().realize(st, Stage::Acceleration);
            std::printf("t %.0f slew %.3f boom %.3f hook y %.3f r %.3f swing %.4f %.4f fleet %.4f %.4f res %.3e W %.3e steps %d\n", t,
                        scene.slewAngle(st), scene.boomAngle(st) * 180 / SimTK::Pi, scene.hookPosition(st)[1], scene.hookRadius(st),
                        scene.outOfPlaneSwing(st), scene.inPlaneSwing(st), scene.largestFleetAngle(st, 0),
                        scene.largestFleetAngle(st, 1), scene.energyResidual(st, e0), scene.workMeter().getWork(st),
                        integ.getNumStepsTaken());
            std::fflush(stdout);
            if (!scene.reeving().getLimitReached().empty()) { std::printf("%s\n", scene.reeving().getLimitReached().c_str()); break; }
        }
    }
}
