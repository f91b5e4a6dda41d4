// bench-floor-crane: Simbody's own floor for the overhead crane. The
// reeving-crane demo's scene (SimbodyReeving::CraneScene, default parameters, 12 falls by default)
// with the rope replaced by massless SimTK::Force::TwoPointLinearSpring's, integrated and reported
// as the demo does; it prints the steps, right-hand sides and wall time that Simbody alone spends.
// bench/cost.sh sets it side by side with the demo.
//
// The same as CraneScene (its geometry is recomputed here with CraneScene's formulas): the
// trolley, a MobilizedBody::Slider along x at railHeight, prescribed by the default cycle's
// traverse (CraneCycle::liftTraverseLower, SimbodyReeving::prescribeProfile); the drum, a
// MobilizedBody::Pin on the trolley, prescribed by the cycle's hoist profile (angle
// -falls / drumRadius x lift); the hook block, a MobilizedBody::Planar from Ground; the payload, a
// MobilizedBody::Pin under the hook's sling pin; gravity g along -y; the MotionWorkMeter that
// integrates the drives' work (so the energy residual E - E0 - W checks the run). The same as the
// demo: RK-Merson at accuracy 1e-6, reports every 0.02 s through InterpolatingTimeStepper, the
// reporter realizing Stage::Acceleration (the drives' forces) and reading the trolley and hook
// positions, sway and payload angles, every fall's force, the drum speed, the motor torque and
// the traverse force, the motion work and the energy residual; 36 s simulated.
//
// The rope: rope node k (k = 0..n) is the drum axis (k = 0, on the drum), a hook sheave centre
// (odd k), a trolley sheave centre (even k) or the dead end, exactly CraneScene's stations. Fall
// k + 1 (span k) is one spring between nodes k and k + 1, of stiffness k_f = EA / l_f and natural
// length l_f = (its length at t = 0) / sqrt(1 + 2 T / EA), T = (payloadMass + hookMass) g / n:
// the fall's unstretched length in CraneScene's construction of the rope's length, so that each
// spring carries about T at the start. The first fall's spring ends at the drum's axis (the drum's
// frame origin): the drum stays a body with its prescribed motion, whose cost Simbody pays and
// whose motor torque (its inertia only) is reported, but a spring of fixed natural length cannot
// haul rope in, so the hoist does not lift the hook here (a rim point instead would pull the fall
// 0.3 m in and out every drum turn). The traverse is the demo's: the trolley moves 10 m and the
// hook and payload sway under it.
// Not the same physics, so compare costs per right-hand side, not steps: the reeved rope slides
// over the hook's sheaves, so its falls carry one tension and the hook block turns against gravity
// alone, while n separate springs on the sheave centres hold its rotation with sum k_f x^2 (x the
// sheave's offset; 1.3e7 N m/rad for 12 falls, against ~25 kg m^2: a mode of order 100 Hz) that
// RK-Merson resolves: measured, 13 469 steps over the 36 s (the demo: 2 667), 360 of them in the
// first second, at rest; with 1 fall, 45 steps in the first 2 s. (All hook ends at the block's
// frame origin instead: 3 567 steps, but the fanned springs then hold the hook horizontally and
// their forces swing by +-20 kN in the traverse.)
//
// Initial state (the demo's: hook hanging at rest): prescribed motions at t = 0 (at rest), the
// hook block from its rest offset below the trolley and the payload hanging, then Newton on the
// hook's and the payload's four coordinates with a finite-difference Jacobian of their
// accelerations at zero speeds, to |udot| <= 1e-10 g.
//
// usage: bench-floor-crane [--falls N] [--t-end T] [--accuracy TOL] [--integrator NAME]
//                          [--report-interval DT] [--out DIR] [--quiet]
#include "FloorRun.h"

#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/scenes/MotionProfile.h>
#include <SimbodyReeving/simbody/MotionWorkMeter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

namespace {

using namespace SimTK;
using SimbodyReeving::CraneParameters;

/// The crane without its rope, springs in its place (see the header).
struct FloorCrane {
    FloorCrane(const CraneParameters& p, const SimbodyReeving::CraneCycle& cycle);
    State makeInitialState() const;
    std::vector<double> observe(const State& s, double energy0) const;
    std::vector<std::string> columns() const;

    CraneParameters p;
    int n;
    std::vector<Vec3> stations;  // node k in its body's frame (CraneScene's)
    double hookRestOffset = 0;
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    std::unique_ptr<SimbodyReeving::MotionWorkMeter> workMeter;
    std::unique_ptr<MobilizedBody::Slider> trolley;
    std::unique_ptr<MobilizedBody::Pin> drum;
    std::unique_ptr<MobilizedBody::Planar> hook;
    std::unique_ptr<MobilizedBody::Pin> payload;
    struct Fall {
        const MobilizedBody* a;
        const MobilizedBody* b;
        Vec3 stationA, stationB;
        double stiffness, naturalLength;
    };
    std::vector<Fall> falls;

    bool onHook(int k) const { return k % 2 == 1; }
    const MobilizedBody& nodeBody(int k) const {
        if (k == 0) return *drum;
        return onHook(k) ? static_cast<const MobilizedBody&>(*hook) : static_cast<const MobilizedBody&>(*trolley);
    }
};

FloorCrane::FloorCrane(const CraneParameters& params, const SimbodyReeving::CraneCycle& cycle) : p(params), n(params.falls) {
    p.validate();
    cycle.validate();
    // CraneScene's node offsets and hook rest offset (CraneScene.cpp, constructor).
    std::vector<double> x(n + 1);
    for (int k = 0; k <= n; ++k) x[k] = (k - 0.5 * n) * p.sheavePitch;
    double sumW = 0, sumWx = 0;
    for (int k = 1; k <= n; k += 2) {
        const double w = k < n ? 2.0 : 1.0;
        sumW += w;
        sumWx += w * x[k];
    }
    const double hookCentroid = sumWx / sumW;
    stations.resize(n + 1);
    stations[0] = Vec3(0);
    for (int k = 1; k <= n; ++k) stations[k] = Vec3(onHook(k) ? x[k] - hookCentroid : x[k], 0, 0);
    const double h = p.initialHookDepth;
    double num = 0, den = 0;
    for (int k = 0; k < n; ++k) {
        const int top = onHook(k) ? k + 1 : k, bottom = onHook(k) ? k : k + 1;
        const double topX = top == 0 ? x[0] : stations[top][0];
        const double length = h + (top == 0 ? p.drumHeight : 0.0);
        num += (topX - stations[bottom][0]) / length;
        den += 1.0 / length;
    }
    hookRestOffset = num / den;

    Force::Gravity gravity(forces, matter, Vec3(0, -p.g, 0));  // the subsystem keeps it
    workMeter = std::make_unique<SimbodyReeving::MotionWorkMeter>(system);
    const Body::Rigid trolleyBody(MassProperties(p.trolleyMass, Vec3(0), Inertia(p.trolleyMass)));
    trolley = std::make_unique<MobilizedBody::Slider>(matter.updGround(), Transform(Vec3(p.trolleyX0, p.railHeight, 0)),
                                                      trolleyBody, Transform());
    SimbodyReeving::prescribeProfile(*trolley, cycle.traverse, 1.0);
    const Body::Rigid drumBody(MassProperties(p.drumMass, Vec3(0), Inertia(p.drumInertia)));
    drum = std::make_unique<MobilizedBody::Pin>(*trolley, Transform(Vec3(x[0], p.drumHeight, 0)), drumBody, Transform());
    SimbodyReeving::prescribeProfile(*drum, cycle.hoist, -n / p.drumRadius);
    const Body::Rigid hookBody(MassProperties(p.hookMass, Vec3(0, -p.hookComBelow, 0),
                                              Inertia(p.hookInertia).shiftFromMassCenter(Vec3(0, -p.hookComBelow, 0), p.hookMass)));
    hook = std::make_unique<MobilizedBody::Planar>(matter.updGround(), Transform(), hookBody, Transform());
    const Body::Rigid payloadBody(MassProperties(p.payloadMass, Vec3(0), Inertia(p.payloadInertia)));
    payload = std::make_unique<MobilizedBody::Pin>(*hook, Transform(Vec3(0, -p.hookPinBelow, 0)), payloadBody,
                                                   Transform(Vec3(0, p.slingLength, 0)));

    // One spring per fall, between its nodes' stations.
    auto restPosition = [&](int k) {  // trolley frame, hook at rest
        if (k == 0) return Vec3(x[0], p.drumHeight, 0);
        return onHook(k) ? stations[k] + Vec3(hookRestOffset, -h, 0) : stations[k];
    };
    const double tension = (p.payloadMass + p.hookMass) * p.g / n;
    for (int k = 0; k < n; ++k) {
        const double l0 = (restPosition(k + 1) - restPosition(k)).norm() / std::sqrt(1.0 + 2.0 * tension / p.EA);
        falls.push_back({&nodeBody(k), &nodeBody(k + 1), stations[k], stations[k + 1], p.EA / l0, l0});
        Force::TwoPointLinearSpring spring(forces, *falls.back().a, stations[k], *falls.back().b, stations[k + 1], p.EA / l0,
                                           l0);
    }
    system.realizeTopology();
}

State FloorCrane::makeInitialState() const {
    State s = system.getDefaultState();
    s.setTime(0);
    hook->setQToFitTransform(s, Transform(Vec3(p.trolleyX0 + hookRestOffset, p.railHeight - p.initialHookDepth, 0)));
    payload->setQ(s, 0);
    system.realize(s, Stage::Time);
    system.prescribe(s);
    // Newton on (hook q, payload q) for zero accelerations at zero speeds.
    const MobilizedBody* bodies[2] = {hook.get(), payload.get()};
    std::vector<std::pair<const MobilizedBody*, int>> coords;
    for (const MobilizedBody* b : bodies)
        for (int i = 0; i < b->getNumQ(s); ++i) coords.push_back({b, i});
    const int m = static_cast<int>(coords.size());
    auto residual = [&](State& st) {
        system.realize(st, Stage::Acceleration);
        Vector r(m);
        for (int i = 0; i < m; ++i) r[i] = coords[i].first->getOneUDot(st, MobilizerUIndex(coords[i].second));
        return r;
    };
    const double tolerance = 1e-10 * p.g, dq = 1e-7;
    for (int iteration = 0;; ++iteration) {
        const Vector r = residual(s);
        if (r.normInf() <= tolerance) break;
        if (iteration == 30)
            throw std::runtime_error("bench-floor-crane: no static equilibrium after 30 Newton iterations, |udot| = " +
                                     std::to_string(r.normInf()));
        Matrix J(m, m);
        for (int j = 0; j < m; ++j) {
            State t = s;
            const auto [b, i] = coords[j];
            b->setOneQ(t, MobilizerQIndex(i), b->getOneQ(s, MobilizerQIndex(i)) + dq);
            const Vector rj = residual(t);
            for (int row = 0; row < m; ++row) J(row, j) = (rj[row] - r[row]) / dq;
        }
        FactorLU lu(J);
        Vector step;
        lu.solve(r, step);
        for (int j = 0; j < m; ++j) {
            const auto [b, i] = coords[j];
            b->setOneQ(s, MobilizerQIndex(i), b->getOneQ(s, MobilizerQIndex(i)) - step[j]);
        }
    }
    workMeter->setWork(s, 0);
    system.realize(s, Stage::Velocity);
    return s;
}

std::vector<std::string> FloorCrane::columns() const {
    std::vector<std::string> c = {"t", "trolley_x", "hook_x", "hook_height", "sway", "payload_angle"};
    for (int k = 1; k <= n; ++k) c.push_back("fall_" + std::to_string(k));
    for (const char* name : {"drum_speed", "motor_torque", "trolley_force", "motion_work", "energy_residual"}) c.push_back(name);
    return c;
}

std::vector<double> FloorCrane::observe(const State& s, double energy0) const {
    system.realize(s, Stage::Acceleration);
    const Vec3 t = trolley->getBodyOriginLocation(s), hk = hook->getBodyOriginLocation(s);
    const Vec3 pin = hook->findStationLocationInGround(s, Vec3(0, -p.hookPinBelow, 0));
    const Vec3 c = payload->getBodyOriginLocation(s);
    std::vector<double> row = {s.getTime(), t[0], hk[0], hk[1], std::atan2(hk[0] - t[0] - hookRestOffset, t[1] - hk[1]),
                               std::atan2(c[0] - pin[0], pin[1] - c[1])};
    for (const Fall& f : falls) {
        const double length =
            (f.b->findStationLocationInGround(s, f.stationB) - f.a->findStationLocationInGround(s, f.stationA)).norm();
        row.push_back(f.stiffness * (length - f.naturalLength));
    }
    const double work = workMeter->getWork(s);
    row.push_back(drum->getOneU(s, 0));
    row.push_back(-drum->getOneTau(s, MobilizerUIndex(0)));
    row.push_back(-trolley->getOneTau(s, MobilizerUIndex(0)));
    row.push_back(work);
    row.push_back(system.calcEnergy(s) - energy0 - work);
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string program = "bench-floor-crane";
    bench_floor::Options o;
    o.tEnd = 36.0;
    o.reportInterval = 0.02;
    int fallCount = 12;
    CLI::App app("Simbody's own floor for the overhead crane: the reeving-crane scene with the rope replaced\n"
                 "by one massless Force::TwoPointLinearSpring per fall (see the source's header).",
                 program);
    bench_floor::defineOptions(app, o);
    app.add_option("--falls", fallCount, "rope parts between trolley and hook block, 1..12 (default 12)")
        ->type_name("N")
        ->transform(demo_common::integerIn(1, 12));
    if (const int status = demo_common::parseOrExitStatus(app, argc, argv); status >= 0) return status;
    if (!o.outDir.empty() && !demo_common::prepareOutputFolder(program, o.outDir)) return demo_common::kUsageExitStatus;

    CraneParameters p;  // the demo's defaults
    p.falls = fallCount;
    bench_floor::Result result;
    double maxResidual = 0, maxWork = 0;
    std::unique_ptr<FloorCrane> crane;
    try {
        crane = std::make_unique<FloorCrane>(p, SimbodyReeving::CraneCycle::liftTraverseLower());
        const State s0 = crane->makeInitialState();
        crane->system.realize(s0, Stage::Dynamics);
        const double energy0 = crane->system.calcEnergy(s0);
        result = bench_floor::run(crane->system, s0, o, [&](const State& s) { return crane->observe(s, energy0); });
        for (const auto& row : result.rows) {
            maxResidual = std::max(maxResidual, std::abs(row.back()));
            maxWork = std::max(maxWork, std::abs(row[row.size() - 2]));
        }
    } catch (const std::exception& e) {
        std::cerr << program << ": simulation failed: " << e.what() << "\n";
        return 1;
    }
    if (!o.outDir.empty()) {
        using demo_common::jsonNumber;
        demo_common::Json extra;
        extra["falls"] = fallCount;
        demo_common::Json k = demo_common::Json::array(), l0 = demo_common::Json::array();
        for (const auto& f : crane->falls) {
            k.push_back(jsonNumber(f.stiffness));
            l0.push_back(jsonNumber(f.naturalLength));
        }
        extra["spring_stiffness_N_per_m"] = k;
        extra["spring_natural_length_m"] = l0;
        extra["max_abs_energy_residual_J"] = jsonNumber(maxResidual);
        extra["max_abs_motion_work_J"] = jsonNumber(maxWork);
        try {
            bench_floor::writeOutputs(program, o, result, crane->columns(), extra);
        } catch (const std::exception& e) {
            std::cerr << program << ": writing the outputs failed: " << e.what() << "\n";
            return 1;
        }
    }
    bench_floor::printSummary(program, o, result);
    if (!o.quiet) std::printf("%s: %d falls, max |energy residual| %.3e J (motion work up to %.3e J)\n", program.c_str(),
                              fallCount, maxResidual, maxWork);
    return 0;
}
