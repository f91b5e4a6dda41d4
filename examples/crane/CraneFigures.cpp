#include "CraneFigures.h"

#include "common/RopeLifeOutput.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <variant>

namespace fs = std::filesystem;
using SimbodyReeving::CraneScene;
using SimTK::Vec2;
using SimTK::Vec3;

namespace crane_demo {
namespace {

Vec2 xy(const Vec3& p) { return Vec2(p[0], p[1]); }

// A closed polygon of body-frame points, drawn in Ground.
Polyline bodyPolygon(Ink ink, const SimTK::MobilizedBody& body, const SimTK::State& s, const std::vector<Vec2>& pts) {
    Polyline line{ink, {}};
    for (size_t i = 0; i <= pts.size(); ++i) {
        const Vec2& p = pts[i % pts.size()];
        line.points.push_back(xy(body.findStationLocationInGround(s, Vec3(p[0], p[1], 0))));
    }
    return line;
}

std::vector<Vec2> rectangle(double x0, double x1, double y0, double y1) {
    return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

std::vector<Vec2> circle(double x, double y, double r) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 24; ++i) pts.emplace_back(x + r * std::cos(i * SimTK::Pi / 12), y + r * std::sin(i * SimTK::Pi / 12));
    return pts;
}

// Smallest and largest trolley position of the cycle (sampled).
std::pair<double, double> trolleyRange(const CraneScene& scene) {
    const auto& traverse = scene.cycle().traverse;
    const double x0 = scene.parameters().trolleyX0, tEnd = std::max(traverse.endTime(), 1.0);
    double lo = x0, hi = x0;
    for (int i = 0; i <= 400; ++i) {
        const double x = x0 + traverse.position(tEnd * i / 400.0);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    return {lo, hi};
}

}  // namespace

std::string phaseAt(const SimbodyReeving::CraneCycle& cycle, double t) {
    const double v = cycle.hoist.velocity(t), u = cycle.traverse.velocity(t);
    std::string phase;
    if (v > 1e-9) phase = "lifting";
    if (v < -1e-9) phase = "lowering";
    if (std::abs(u) > 1e-9) phase += phase.empty() ? "traversing" : " + traversing";
    return phase.empty() ? "at rest" : phase;
}

std::vector<Polyline> drawCrane(const CraneScene& scene, const SimTK::State& s) {
    const SimbodyReeving::CraneParameters& p = scene.parameters();
    const int n = scene.falls();
    std::vector<Polyline> lines;
    // Ground and rail over the trolley's travel.
    const auto [lo, hi] = trolleyRange(scene);
    double left = 0, right = 0;  // trolley frame extent of its nodes and drum
    for (int k = 0; k <= n; ++k) {
        if (scene.nodeOnHook(k)) continue;
        const double x = k == 0 ? scene.drum().getDefaultInboardFrame().p()[0] : scene.nodeStation(k)[0];
        left = std::min(left, x);
        right = std::max(right, x);
    }
    left -= 0.4 + p.drumRadius;
    right += 0.4;
    const double railY = p.railHeight + 0.3;
    lines.push_back({Ink::Structure, {Vec2(lo + left - 1.5, 0), Vec2(hi + right + 1.5, 0)}});
    if (std::isfinite(scene.floorHeight())) {  // lift-off: the floor the payload stands on
        const double x = p.trolleyX0 + scene.hookRestOffset(), w = 0.5 * p.payloadWidth + 1.5;
        lines.push_back({Ink::Structure, {Vec2(x - w, scene.floorHeight()), Vec2(x + w, scene.floorHeight())}});
    }
    lines.push_back({Ink::Structure, {Vec2(lo + left - 1.5, railY), Vec2(hi + right + 1.5, railY)}});
    // Trolley box, the drum's bracket.
    const SimTK::MobilizedBody& trolley = scene.trolley();
    lines.push_back(bodyPolygon(Ink::Trolley, trolley, s, rectangle(left, right, -0.25, 0.3)));
    const Vec3 drumAxis = scene.drum().getDefaultInboardFrame().p();
    lines.push_back({Ink::Trolley,
                     {xy(trolley.findStationLocationInGround(s, Vec3(drumAxis[0], 0.3, 0))),
                      xy(trolley.findStationLocationInGround(s, drumAxis))}});
    // Drum: its rim and a spoke that turns with it.
    const SimTK::MobilizedBody& drum = scene.drum();
    lines.push_back(bodyPolygon(Ink::Drum, drum, s, circle(0, 0, p.drumRadius)));
    lines.push_back({Ink::Drum, {xy(drum.findStationLocationInGround(s, Vec3(0))),
                                 xy(drum.findStationLocationInGround(s, Vec3(p.drumRadius, 0, 0)))}});
    // Sheaves (a small triangle marks the dead end).
    const std::vector<Vec3> nodes = scene.nodePositions(s);
    for (int k = 1; k < n; ++k) {
        std::vector<Vec2> c = circle(nodes[k][0], nodes[k][1], p.sheaveRadius);
        c.push_back(c.front());
        lines.push_back({Ink::Sheave, c});
    }
    const double m = 0.08;
    lines.push_back({Ink::Sheave,
                     {Vec2(nodes[n][0] - m, nodes[n][1] - m), Vec2(nodes[n][0] + m, nodes[n][1] - m),
                      Vec2(nodes[n][0], nodes[n][1] + m), Vec2(nodes[n][0] - m, nodes[n][1] - m)}});
    // The rope, one polyline in rope order: the falls and, on wrapped sheaves, the rope on their
    // grooves between them (ReevingSubsystem::sampleArc).
    const SimbodyReeving::ReevingSubsystem& reeving = scene.reeving();
    const SimbodyReeving::RopeSpec& spec = reeving.getRopeSpec(0);
    Polyline rope{Ink::Rope, {}};
    auto append = [&](const std::vector<Vec3>& points) {  // the first point repeats the last one drawn
        for (size_t i = rope.points.empty() ? 0 : 1; i < points.size(); ++i) rope.points.push_back(xy(points[i]));
    };
    for (int k = 0; k < n; ++k) {
        if (k > 0 && spec.sheaveModel == SimbodyReeving::SheaveModel::Wrapped &&
            std::holds_alternative<SimbodyReeving::DeviationSheave>(spec.sheaves[k - 1]))
            append(reeving.sampleArc(s, 0, k, 13));
        append(reeving.sampleSpan(s, 0, k, 24));
    }
    lines.push_back(rope);
    // Hook block, sling, payload.
    double hl = 0, hr = 0;
    for (int k = 1; k <= n; ++k)
        if (scene.nodeOnHook(k)) {
            hl = std::min(hl, scene.nodeStation(k)[0]);
            hr = std::max(hr, scene.nodeStation(k)[0]);
        }
    const SimTK::MobilizedBody& hook = scene.hookBlock();
    lines.push_back(bodyPolygon(Ink::Hook, hook, s, rectangle(hl - 0.25, hr + 0.25, -p.hookPinBelow, 0.2)));
    const SimTK::MobilizedBody& payload = scene.payload();
    const double w = 0.5 * p.payloadWidth, h = 0.5 * p.payloadHeight;
    const Vec2 pin = xy(hook.findStationLocationInGround(s, Vec3(0, -p.hookPinBelow, 0)));
    lines.push_back({Ink::Payload, {xy(payload.findStationLocationInGround(s, Vec3(-0.8 * w, h, 0))), pin,
                                    xy(payload.findStationLocationInGround(s, Vec3(0.8 * w, h, 0)))}});
    lines.push_back(bodyPolygon(Ink::Payload, payload, s, rectangle(-w, w, -h, h)));
    return lines;
}

void writeSnapshots(std::ostream& out, const std::vector<Snapshot>& snapshots) {
    out << std::setprecision(8);
    for (size_t i = 0; i < snapshots.size(); ++i) {
        if (i) out << "\n\n";
        out << "# snapshot " << i << ": t = " << snapshots[i].t << " s, " << snapshots[i].phase << "\n";
        for (size_t j = 0; j < snapshots[i].lines.size(); ++j) {
            if (j) out << "\n";
            const Polyline& l = snapshots[i].lines[j];
            for (const Vec2& q : l.points) out << q[0] << ' ' << q[1] << ' ' << static_cast<int>(l.ink) << '\n';
        }
    }
}

bool makePlots(const fs::path& dir, const CraneScene& scene, const std::vector<Snapshot>& snapshots,
               double staticReferenceAxialForce) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        std::cerr << "reeving-crane: gnuplot not found, figures skipped (apt-get install gnuplot-nox)\n";
        return false;
    }
    const int n = scene.falls();
    const auto& p = scene.parameters();
    // timeseries.csv columns (see main.cpp): t trolley_x hook_x hook_height sway payload_angle
    // fall_1..fall_n drum_speed motor_torque motor_power rope_on_drum trolley_force trolley_power
    // motion_work energy_residual.
    const int fall1 = 7, motorPower = 9 + n, trolleyPower = 12 + n, work = 13 + n, residual = 14 + n;
    std::ofstream gp(dir / "plots.gp");
    gp << std::setprecision(10);
    gp << "set terminal pngcairo size 1000,760 font 'DejaVu Sans,11'\nset datafile separator ','\nset grid\n"
       << "set key outside right\nset xlabel 't [s]'\n";
    // Hook height and sway.
    gp << "set output 'fig_hook_height_sway.png'\nset multiplot layout 2,1 title 'Hook block height and sway ("
       << n << " falls)'\n"
       << "set ylabel 'height [m]'\nplot 'timeseries.csv' every ::1 using 1:4 with lines lw 2 title 'hook block',"
       << " '' every ::1 using 1:2 with lines lw 1 dt 2 title 'trolley x [m]'\n"
       << "set ylabel 'angle [deg]'\nplot 'timeseries.csv' every ::1 using 1:($5*180/pi) with lines lw 2 title "
          "'falls (sway)', '' every ::1 using 1:($6*180/pi) with lines lw 2 title 'payload (sling)'\n"
       << "unset multiplot\n";
    // Fall axial forces.
    gp << "set output 'fig_fall_axial_forces.png'\nset title 'Axial force at the top of every fall'\n"
       << "set ylabel 'axial force [kN]'\nplot ";
    for (int k = 0; k < n; ++k)
        gp << (k ? ", " : "") << "'timeseries.csv' every ::1 using 1:($" << fall1 + k
           << "/1000) with lines lw 1.5 title 'fall " << k + 1 << "'";
    gp << ", " << staticReferenceAxialForce / 1000 << " with lines dt 2 lw 2 lc 'black' title '(M + m_{hook}) g / n'\n"
       << "unset title\n";
    // Energy balance.
    gp << "set output 'fig_energy.png'\nset multiplot layout 3,1 title 'Drives and energy balance'\n"
       << "set ylabel 'power [kW]'\nplot 'timeseries.csv' every ::1 using 1:($" << motorPower
       << "/1000) with lines lw 2 title 'hoist motor', '' every ::1 using 1:($" << trolleyPower
       << "/1000) with lines lw 2 title 'traverse drive'\n"
       << "set ylabel 'energy [kJ]'\nplot 'timeseries.csv' every ::1 using 1:($" << work
       << "/1000) with lines lw 2 title 'motion work W', '' every ::1 using 1:(($" << work << "+$" << residual
       << ")/1000) with lines lw 1 dt 2 title 'E - E_0'\n"
       << "set ylabel 'residual [J]'\nplot 'timeseries.csv' every ::1 using 1:" << residual
       << " with lines lw 2 title 'E - E_0 - W'\nunset multiplot\n";
    // Lift-off: the rope's force against its static value and the spring-mass peak, the floor and
    // the sling.
    if (p.scenario == SimbodyReeving::CraneScenario::LiftOff) {
        const int rope = 15 + n, floor = 16 + n, sling = 17 + n;
        const double fs = scene.staticRopeForce() / 1000, peak = fs + (scene.springMassDynamicFactor() - 1) * scene.liftedMass() * p.g / 1000;
        // From just before the sling is taut (hoistRamp + slackTime); the sling's jerk as it
        // stops the hook block may reach far above the rope's peak.
        const double taut = p.hoistRamp + p.slackTime;
        gp << "set output 'fig_lift_off.png'\nset title 'Lift-off at v_h = " << p.hoistSpeed
           << " m/s: forces'\nset ylabel 'force [kN]'\nset xrange [" << std::max(0.0, taut - 0.05)
           << ":*]\nset yrange [0:" << 1.3 * peak << "]\nplot 'timeseries.csv' every ::1 using 1:($" << rope
           << "/1000) with lines lw 2 title 'rope (all falls, at the top)', '' every ::1 using 1:($" << floor
           << "/1000) with lines lw 1.5 title 'floor on the payload', '' every ::1 using 1:($" << sling
           << "/1000) with lines lw 1 dt 3 title 'sling', " << fs
           << " with lines dt 2 lw 2 lc 'black' title 'static (M + m_{hook}) g + rope', " << peak
           << " with lines dt 4 lw 2 lc 'red' title 'spring-mass peak: + v_h sqrt(k M)'\nunset title\n"
           << "set xrange [*:*]\nset yrange [*:*]\n";
    }
    // Rope geometry snapshots.
    double xmin = 1e300, xmax = -1e300, ymin = -0.5, ymax = p.railHeight + 1;
    for (const Snapshot& sn : snapshots)
        for (const Polyline& l : sn.lines)
            for (const Vec2& q : l.points) {
                xmin = std::min(xmin, q[0]);
                xmax = std::max(xmax, q[0]);
                ymin = std::min(ymin, q[1] - 0.5);
                ymax = std::max(ymax, q[1] + 0.5);
            }
    const int cols = snapshots.size() <= 3 ? static_cast<int>(snapshots.size()) : snapshots.size() <= 8 ? 3 : 4;
    const int rows = (static_cast<int>(snapshots.size()) + cols - 1) / cols;
    gp << "set terminal pngcairo size " << 500 * cols << "," << 520 * rows + 40 << " font 'DejaVu Sans,10'\n"
       << "set output 'fig_snapshots.png'\nset datafile separator whitespace\nunset grid\nunset key\n"
       << "set size ratio -1\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
       << "set xrange [" << xmin - 0.5 << ":" << xmax + 0.5 << "]\nset yrange [" << ymin << ":" << ymax << "]\n"
       << "set linetype 1 lc rgb '#909090' lw 1.5\nset linetype 2 lc rgb '#1f5fa8' lw 2\n"
       << "set linetype 3 lc rgb '#d07000' lw 2\nset linetype 4 lc rgb '#7030a0' lw 1\n"
       << "set linetype 5 lc rgb '#101010' lw 1\nset linetype 6 lc rgb '#1f5fa8' lw 2\n"
       << "set linetype 7 lc rgb '#2a8a2a' lw 2\n"
       << "set multiplot layout " << rows << "," << cols << " title 'The crane at " << snapshots.size()
       << " instants (" << n << " falls; x-y plane, y up)'\n";
    for (size_t i = 0; i < snapshots.size(); ++i) {
        std::ostringstream title;
        title << std::fixed << std::setprecision(1) << "t = " << snapshots[i].t << " s: " << snapshots[i].phase;
        gp << "set title '" << title.str() << "'\nplot 'snapshots.dat' index " << i
           << " using 1:2:3 with lines lc variable\n";
    }
    gp << "unset multiplot\n";
    // Bending cycles along the rope, the reeving beside it (rope_bending.csv, rope_bending.dat).
    gp << demo_common::ropeBendingPlot("fig_rope_bending.png", "rope_bending.csv", "rope_bending.dat",
                                       "reeving-crane: bending cycles per rope section over the run");
    gp.close();
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp";
    if (std::system(cmd.c_str()) != 0) {
        std::cerr << "reeving-crane: gnuplot failed; see " << (dir / "plots.gp").string() << "\n";
        return false;
    }
    return true;
}

}  // namespace crane_demo
