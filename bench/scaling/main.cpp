// bench-scaling: cost of one right-hand side against the number of spans and the mode counts
// (the cost per span should stay constant as spans are added).
//
// Scene (planar, in the x-y plane, gravity -9.81 m/s^2 along y): one rope anchored on Ground at the
// origin, running over N frictionless deviation sheaves fixed on Ground in a zigzag (sheave k at
// x = k --pitch, y = --rise for odd k and 0 for even k: every zigzag span is inclined, none
// vertical), its end fastened --attach above the centre of a payload of --mass kg (a
// MobilizedBody::Planar: x, y and the rotation about z) hanging --drop m (unstretched span) below
// the last sheave. N + 1 spans. Table 1 rope (rhoA 0.6205 kg/m, EA 16.5 MN, EI 30.9 N m^2,
// tension-only); every span with n_a = --axial-modes and n_t = --transverse-modes, the other span
// options SpanOptions' defaults (AxialDynamics::QuasiStatic, VelocityModel::Complete). The run
// starts from static equilibrium (ReevingSubsystem::findStaticEquilibrium) with the payload pushed
// horizontally at --velocity m/s.
//
// Modes:
//   --evaluations K   exactly K right-hand-side evaluations (System::realize to Stage::Acceleration)
//                     at K distinct states: those an integrator (--integrator, --accuracy) realized
//                     to Stage::Acceleration along the trajectory, in its order. They are recorded
//                     first in a pre-run that always records the first --record states (K <= R), so
//                     the set-up (scene, static equilibrium, pre-run) is the same for every K and
//                     cancels in callgrind's counts of K and 2K evaluations: instructions per rhs =
//                     (I(2K) - I(K)) / K, the mean over evaluations K..2K-1 (bench/scaling/scaling.sh).
//                     The replay sets time and Y of one working State, as an integrator does, so the
//                     rope's warm starts see the integrator's sequence of states. Built with
//                     valgrind's callgrind.h, the replay is bracketed by
//                     CALLGRIND_START/STOP_INSTRUMENTATION (no-ops outside valgrind): run callgrind
//                     with --instr-atstart=no and the set-up runs uninstrumented (fast); the counts
//                     then hold the replay only (still take the K / 2K difference).
//   --t-end T         (default, T = 1 s) an ordinary run with the InterpolatingTimeStepper: prints
//                     steps, rhs evaluations and wall time.
//
// Reproduce: bench/scaling/scaling.sh [BUILD_DIR]   (docs/performance.md)
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SCALING_HAVE_CALLGRIND 1
#endif
#endif
#ifndef SCALING_HAVE_CALLGRIND
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace SimbodyReeving;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace {

struct Options {
    int sheaves = 8;              // N, >= 1
    int axialModes = 3;           // n_a, 0..16
    int transverseModes = 1;      // n_t, 0..16
    int evaluations = 0;          // K > 0: evaluation mode
    int record = 100;             // R: states recorded in the pre-run, >= K
    double tEnd = 1.0;            // [s], run mode
    double accuracy = 1e-6;       // integrator accuracy
    std::string integrator = "rk-merson";
    double pitch = 1.0;           // horizontal sheave pitch [m]
    double rise = 0.5;            // zigzag height [m]
    double drop = 3.0;            // unstretched length of the hanging span [m]
    double attach = 0.3;          // rope attachment above the payload's centre of mass [m]
    double mass = 1000.0;         // payload mass [kg]
    double inertia = 36.0;        // payload moment of inertia about z through its centre [kg m^2]
    double velocity = 0.1;        // initial horizontal payload velocity [m/s]
};

// Records (t, Y) of every state realized to Stage::Acceleration while `on`, skipping a state equal
// to the last one recorded. Applies no force.
class Recorder : public SimTK::Force::Custom::Implementation {
public:
    struct Entry {
        double t;
        SimTK::Vector y;
    };
    bool on = false;
    mutable std::vector<Entry> entries;

    void calcForce(const State&, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<Vec3>&,
                   SimTK::Vector&) const override {}
    SimTK::Real calcPotentialEnergy(const State&) const override { return 0; }
    void realizeAcceleration(const State& s) const override {
        if (!on) return;
        auto& e = entries;
        if (!e.empty() && e.back().t == s.getTime() && e.back().y.size() == s.getNY()) {
            bool same = true;
            for (int i = 0; same && i < s.getNY(); ++i) same = e.back().y[i] == s.getY()[i];
            if (same) return;
        }
        e.push_back({s.getTime(), s.getY()});
    }
};

struct Scene {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};
    SimTK::GeneralForceSubsystem forces{system};
    SimTK::Force::Gravity gravity{forces, matter, Vec3(0, -9.81, 0)};
    Recorder* recorder = nullptr;  // owned by its Force::Custom
    std::unique_ptr<ReevingSubsystem> reeving;
    std::unique_ptr<SimTK::MobilizedBody::Planar> payload;
    double hangStretch = 1;  // stretch of the hanging span in the straight guess

    explicit Scene(const Options& o) {
        recorder = new Recorder;
        const SimTK::Force::Custom recorderForce(forces, recorder);  // the subsystem takes ownership
        reeving = std::make_unique<ReevingSubsystem>(system, Vec3(0, -9.81, 0));
        const SimTK::Body::Rigid body(SimTK::MassProperties(o.mass, Vec3(0), SimTK::Inertia(o.inertia)));
        payload = std::make_unique<SimTK::MobilizedBody::Planar>(matter.updGround(), SimTK::Transform(), body,
                                                                 SimTK::Transform());
        RopeSpec rope;
        rope.name = "zigzag rope";
        rope.start = RopeAnchor{matter.Ground(), Vec3(0)};
        double chords = 0;
        Vec3 previous(0);
        for (int k = 1; k <= o.sheaves; ++k) {
            const Vec3 c(k * o.pitch, k % 2 == 1 ? o.rise : 0.0, 0);
            rope.sheaves.push_back(DeviationSheave{matter.Ground(), c, 0.1});
            chords += (c - previous).norm();
            previous = c;
        }
        rope.end = RopeAnchor{*payload, Vec3(0, o.attach, 0)};
        rope.properties = {0.6205, 16.5e6, 30.9};  // Table 1, tension-only
        // Straight guess: the whole rope at the axial force of the hanging weight, P = EA eps
        // (Green strain), stretch sqrt(1 + 2 eps).
        const double P = o.mass * 9.81;
        hangStretch = std::sqrt(1.0 + 2.0 * P / rope.properties.axialStiffness);
        rope.unstretchedLength = chords / hangStretch + o.drop;
        rope.spanDefaults.axialModes = o.axialModes;
        rope.spanDefaults.transverseModes = o.transverseModes;
        rope.planeNormal = Vec3(0, 0, 1);
        reeving->addRope(rope);
        system.realizeTopology();
    }

    State makeInitialState(const Options& o) const {
        State s = system.getDefaultState();
        const double xLast = o.sheaves * o.pitch, yLast = o.sheaves % 2 == 1 ? o.rise : 0.0;
        payload->setQToFitTranslation(s, Vec3(xLast, yLast - o.drop * hangStretch - o.attach, 0));
        const double residual = reeving->findStaticEquilibrium(s, 1e-9);
        payload->setUToFitLinearVelocity(s, Vec3(o.velocity, 0, 0));
        system.realize(s, Stage::Velocity);
        const Vec3 p = payload->getBodyOriginLocation(s);
        std::printf("scene: N = %d sheaves, %d spans, n_a = %d, n_t = %d, %d modal coordinates; static "
                    "equilibrium residual %.2e, payload at (%.6f, %.6f) m\n",
                    o.sheaves, reeving->getNumSpans(0), o.axialModes, o.transverseModes,
                    reeving->getNumModalCoordinates(0), residual, p[0], p[1]);
        return s;
    }
};

int evaluate(const Options& o) {
    Scene scene(o);
    const State initial = scene.makeInitialState(o);
    // Pre-run: record the first R states the integrator realizes to Stage::Acceleration.
    auto integ = makeIntegrator(o.integrator, scene.system);
    integ->setAccuracy(o.accuracy);
    InterpolatingTimeStepper ts(scene.system, *integ);
    scene.recorder->entries.reserve(o.record + 16);
    scene.recorder->on = true;
    ts.initialize(initial);
    ts.setStepLimit(1);
    while (static_cast<int>(scene.recorder->entries.size()) < o.record) ts.stepTo(1e6);
    scene.recorder->on = false;
    const auto& e = scene.recorder->entries;
    std::printf("pre-run: %d states recorded over t = [%.3e, %.3e] s, %d steps\n", static_cast<int>(e.size()),
                e.front().t, e[o.record - 1].t, integ->getNumStepsTaken());

    // The K evaluations, in one working state, as an integrator sets its advanced state.
    State w = initial;
    CALLGRIND_START_INSTRUMENTATION;
    for (int i = 0; i < o.evaluations; ++i) {
        w.setTime(e[i].t);
        w.updY() = e[i].y;
        scene.system.realize(w, Stage::Acceleration);
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    // Something of the last evaluation, so that two builds' runs can be compared.
    const SimTK::Vector& udot = w.getUDot();
    std::printf("evaluations: %d at t = [%.3e, %.3e] s; last payload acceleration (%.9e, %.9e) m/s^2, "
                "angular %.9e rad/s^2\n",
                o.evaluations, e.front().t, e[o.evaluations - 1].t, udot[1], udot[2], udot[0]);
    return 0;
}

int run(const Options& o) {
    Scene scene(o);
    const State initial = scene.makeInitialState(o);
    auto integ = makeIntegrator(o.integrator, scene.system);
    integ->setAccuracy(o.accuracy);
    InterpolatingTimeStepper ts(scene.system, *integ);
    ts.initialize(initial);
    const auto start = std::chrono::steady_clock::now();
    ts.stepTo(o.tEnd);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Vec3 p = scene.payload->getBodyOriginLocation(ts.getState());
    std::printf("run: t_end = %g s, %s %g: %d steps, %d rhs evaluations, wall %.3f s (%.1f us/rhs); payload at "
                "(%.6f, %.6f) m\n",
                o.tEnd, o.integrator.c_str(), o.accuracy, integ->getNumStepsTaken(), ts.getNumRealizations(),
                wall, 1e6 * wall / ts.getNumRealizations(), p[0], p[1]);
    return 0;
}

[[noreturn]] void usage(int code) {
    (code == 0 ? std::cout : std::cerr)
        << "usage: bench-scaling [--sheaves N=8] [--axial-modes NA=3] [--transverse-modes NT=1]\n"
           "                     [--evaluations K [--record R=100] | --t-end T=1]\n"
           "                     [--integrator rk-merson] [--accuracy 1e-6] [--velocity 0.1] [--mass 1000]\n"
           "                     [--inertia 36] [--pitch 1] [--rise 0.5] [--drop 3] [--attach 0.3]\n";
    std::exit(code);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help") usage(0);
        if (i + 1 >= argc) usage(2);
        const std::string v = argv[++i];
        if (a == "--sheaves") o.sheaves = std::stoi(v);
        else if (a == "--axial-modes") o.axialModes = std::stoi(v);
        else if (a == "--transverse-modes") o.transverseModes = std::stoi(v);
        else if (a == "--evaluations") o.evaluations = std::stoi(v);
        else if (a == "--record") o.record = std::stoi(v);
        else if (a == "--t-end") o.tEnd = std::stod(v);
        else if (a == "--integrator") o.integrator = v;
        else if (a == "--accuracy") o.accuracy = std::stod(v);
        else if (a == "--velocity") o.velocity = std::stod(v);
        else if (a == "--mass") o.mass = std::stod(v);
        else if (a == "--inertia") o.inertia = std::stod(v);
        else if (a == "--pitch") o.pitch = std::stod(v);
        else if (a == "--rise") o.rise = std::stod(v);
        else if (a == "--drop") o.drop = std::stod(v);
        else if (a == "--attach") o.attach = std::stod(v);
        else usage(2);
    }
    if (o.sheaves < 1 || o.evaluations < 0 || o.record < 1 || (o.evaluations > o.record) || !(o.tEnd > 0) ||
        !(o.pitch > 0) || !(o.rise >= 0) || !(o.drop > 0) || !(o.attach > 0) || !(o.mass > 0) || !(o.inertia > 0)) {
        std::cerr << "bench-scaling: need N >= 1, 0 <= K <= R, R >= 1, T > 0, pitch, drop, attach, mass, inertia > 0, "
                     "rise >= 0\n";
        return 2;
    }
    try {
        return o.evaluations > 0 ? evaluate(o) : run(o);
    } catch (const std::exception& ex) {
        std::cerr << "bench-scaling: " << ex.what() << '\n';
        return 1;
    }
}
