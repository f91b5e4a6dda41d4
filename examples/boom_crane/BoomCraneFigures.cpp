#include "BoomCraneFigures.h"

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
using SimbodyReeving::BoomCraneScene;
using SimTK::Vec3;

namespace boom_crane_demo {
namespace {

// Body-frame points drawn in Ground.
Polyline bodyLine(Ink ink, const SimTK::MobilizedBody& body, const SimTK::State& s, const std::vector<Vec3>& pts) {
    Polyline line{ink, {}};
    for (const Vec3& p : pts) line.points.push_back(body.findStationLocationInGround(s, p));
    return line;
}

// A closed circle of radius r about `centre` in the plane normal to `axis` (body frame).
std::vector<Vec3> circle(const Vec3& centre, const Vec3& axis, double r) {
    const Vec3 n = axis / axis.norm();
    const Vec3 helper = std::abs(n[1]) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    const Vec3 u = SimTK::cross(helper, n).normalize(), v = SimTK::cross(n, u);
    std::vector<Vec3> pts;
    for (int i = 0; i <= 24; ++i) pts.push_back(centre + r * (std::cos(i * SimTK::Pi / 12) * u + std::sin(i * SimTK::Pi / 12) * v));
    return pts;
}

// The twelve edges of a box of half sizes h about `centre` (body frame), as two closed rectangles
// (bottom and top) and the four uprights.
std::vector<std::vector<Vec3>> boxEdges(const Vec3& centre, const Vec3& h) {
    auto corner = [&](double sx, double sy, double sz) { return centre + Vec3(sx * h[0], sy * h[1], sz * h[2]); };
    std::vector<std::vector<Vec3>> edges;
    for (double sy : {-1.0, 1.0})
        edges.push_back({corner(-1, sy, -1), corner(1, sy, -1), corner(1, sy, 1), corner(-1, sy, 1), corner(-1, sy, -1)});
    for (double sx : {-1.0, 1.0})
        for (double sz : {-1.0, 1.0}) edges.push_back({corner(sx, -1, sz), corner(sx, 1, sz)});
    return edges;
}

void addBox(std::vector<Polyline>& lines, Ink ink, const SimTK::MobilizedBody& body, const SimTK::State& s,
            const Vec3& centre, const Vec3& halfSizes) {
    for (const auto& edge : boxEdges(centre, halfSizes)) lines.push_back(bodyLine(ink, body, s, edge));
}

}  // namespace

SimTK::Vec3 boomPlaneDirection(const BoomCraneScene& scene, const SimTK::State& s) {
    const Vec3 x = scene.superstructure().getBodyRotation(s).x();
    return Vec3(x[0], 0, x[2]).normalize();
}

std::string phaseAt(const SimbodyReeving::BoomCraneCycle& cycle, double t) {
    std::string phase;
    auto add = [&phase](const char* what) { phase += phase.empty() ? what : std::string(" + ") + what; };
    const double v = cycle.hoist.velocity(t);
    if (v > 1e-9) add("lifting");
    if (v < -1e-9) add("lowering");
    if (std::abs(cycle.slew.velocity(t)) > 1e-9) add("slewing");
    if (std::abs(cycle.luff.velocity(t)) > 1e-9) add("luffing");
    return phase.empty() ? "at rest" : phase;
}

std::vector<Polyline> drawBoomCrane(const BoomCraneScene& scene, const SimTK::State& s) {
    const SimbodyReeving::BoomCraneParameters& p = scene.parameters();
    const SimTK::MobilizedBody &ground = scene.system().getMatterSubsystem().getGround(), &super = scene.superstructure(),
                               &boom = scene.boom();
    std::vector<Polyline> lines;
    // The slewing ring on the ground; the superstructure's deck and counterweight.
    lines.push_back(bodyLine(Ink::Structure, ground, s, circle(Vec3(0), Vec3(0, 1, 0), 2.0)));
    addBox(lines, Ink::Structure, super, s, Vec3(-1.0, 0.5, 0), Vec3(3.5, 0.5, 1.4));
    addBox(lines, Ink::Structure, super, s, Vec3(-4.0, 1.6, 0), Vec3(0.6, 0.6, 1.3));
    // The A-frame's legs (as BoomCraneScene decorates it).
    const Vec3& a = p.aFrameTop;
    for (double sz : {-0.8, 0.8}) {
        const Vec3 top(a[0], a[1], 0.4 * sz);
        lines.push_back(bodyLine(Ink::Structure, super, s, {Vec3(a[0] - 1.5, 1.0, sz), top, Vec3(p.boomFoot[0], 1.0, sz)}));
    }
    // The boom: four lattice chords from the foot to the tip, and the tip's cross member.
    for (double sy : {-0.35, 0.35})
        for (double sz : {-0.4, 0.4})
            lines.push_back(bodyLine(Ink::Boom, boom, s, {Vec3(0.3, sy, sz), Vec3(p.boomLength - 0.3, 0.5 * sy, 0.5 * sz)}));
    lines.push_back(bodyLine(Ink::Boom, boom, s, {Vec3(p.boomLength, 0, -0.4), Vec3(p.boomLength, 0, 0.4)}));
    // Drums (rims and a spoke that turns with them) and sheaves (in their grooves' planes); a small
    // cross marks each dead end.
    const SimbodyReeving::ReevingSubsystem& reeving = scene.reeving();
    for (int rope : {BoomCraneScene::kLuffingRope, BoomCraneScene::kHoistRope}) {
        const SimbodyReeving::RopeSpec& spec = reeving.getRopeSpec(rope);
        const SimTK::MobilizedBody& drum = std::get<SimbodyReeving::WinchDrum>(spec.start).body;
        lines.push_back(bodyLine(Ink::Drum, drum, s, circle(Vec3(0), Vec3(0, 0, 1), p.drumRadius)));
        lines.push_back(bodyLine(Ink::Drum, drum, s, {Vec3(0), Vec3(p.drumRadius, 0, 0)}));
        for (const SimbodyReeving::RopeSheave& node : spec.sheaves)
            if (const auto* sheave = std::get_if<SimbodyReeving::DeviationSheave>(&node))
                lines.push_back(bodyLine(Ink::Sheave, sheave->body, s, circle(sheave->centre, sheave->axis, sheave->radius)));
        const auto& deadEnd = std::get<SimbodyReeving::RopeAnchor>(spec.end);
        const Vec3 end = deadEnd.body.findStationLocationInGround(s, deadEnd.station);
        const double m = 0.1;
        lines.push_back({Ink::Sheave, {end - Vec3(m, 0, 0), end + Vec3(m, 0, 0)}});
        lines.push_back({Ink::Sheave, {end - Vec3(0, m, 0), end + Vec3(0, m, 0)}});
        lines.push_back({Ink::Sheave, {end - Vec3(0, 0, m), end + Vec3(0, 0, m)}});
    }
    // The ropes, one polyline each in rope order: the spans and, on wrapped sheaves, the rope on
    // their grooves between them (ReevingSubsystem::sampleArc).
    for (int rope : {BoomCraneScene::kLuffingRope, BoomCraneScene::kHoistRope}) {
        const SimbodyReeving::RopeSpec& spec = reeving.getRopeSpec(rope);
        Polyline line{Ink::Rope, {}};
        auto append = [&line](const std::vector<Vec3>& points) {  // the first point repeats the last one drawn
            for (size_t i = line.points.empty() ? 0 : 1; i < points.size(); ++i) line.points.push_back(points[i]);
        };
        for (int k = 0; k < BoomCraneScene::kSpans; ++k) {
            if (k > 0 && spec.sheaveModel == SimbodyReeving::SheaveModel::Wrapped &&
                std::holds_alternative<SimbodyReeving::DeviationSheave>(spec.sheaves[k - 1]))
                append(reeving.sampleArc(s, rope, k, 13));
            append(reeving.sampleSpan(s, rope, k, 24));
        }
        lines.push_back(line);
    }
    // Hook block (a plate about its sheave), sling, payload.
    const SimTK::MobilizedBody &hook = scene.hookBlock(), &payload = scene.payload();
    addBox(lines, Ink::Hook, hook, s, Vec3(0, -0.1, 0), Vec3(0.05, p.hoistSheaveRadius + 0.15, p.hoistSheaveRadius + 0.1));
    lines.push_back({Ink::Payload, {hook.findStationLocationInGround(s, Vec3(0, -p.hookPinBelow, 0)),
                                    payload.findStationLocationInGround(s, Vec3(0, 0.6, 0))}});
    addBox(lines, Ink::Payload, payload, s, Vec3(0), Vec3(0.8, 0.6, 0.8));
    return lines;
}

void writeSnapshots(std::ostream& out, const std::vector<Snapshot>& snapshots) {
    out << std::setprecision(8);
    for (size_t i = 0; i < snapshots.size(); ++i) {
        const Snapshot& sn = snapshots[i];
        if (i) out << "\n\n";
        out << "# snapshot " << i << ": t = " << sn.t << " s, " << sn.phase << "; columns x y z r ink (r along the boom's plane "
            << sn.boomPlane[0] << " 0 " << sn.boomPlane[2] << ")\n";
        for (size_t j = 0; j < sn.lines.size(); ++j) {
            if (j) out << "\n";
            const Polyline& l = sn.lines[j];
            for (const Vec3& q : l.points)
                out << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << SimTK::dot(q, sn.boomPlane) << ' ' << static_cast<int>(l.ink)
                    << '\n';
        }
    }
}

namespace {

// The snapshots' grid figure: one panel per snapshot, `using` the columns of snapshots.dat.
void snapshotFigure(std::ostream& gp, const std::vector<Snapshot>& snapshots, const std::string& file,
                    const std::string& title, const std::string& xlabel, const std::string& ylabel,
                    const std::string& columns, double xmin, double xmax, double ymin, double ymax) {
    const int cols = snapshots.size() <= 3 ? static_cast<int>(snapshots.size()) : snapshots.size() <= 8 ? 3 : 4;
    const int rows = (static_cast<int>(snapshots.size()) + cols - 1) / cols;
    gp << "set terminal pngcairo size " << 500 * cols << "," << 520 * rows + 40 << " font 'DejaVu Sans,10'\n"
       << "set output '" << file << "'\nset datafile separator whitespace\nunset grid\nunset key\n"
       << "set size ratio -1\nset xlabel '" << xlabel << "'\nset ylabel '" << ylabel << "'\n"
       << "set xrange [" << xmin << ":" << xmax << "]\nset yrange [" << ymin << ":" << ymax << "]\n"
       << "set multiplot layout " << rows << "," << cols << " title '" << title << "'\n";
    for (size_t i = 0; i < snapshots.size(); ++i) {
        std::ostringstream t;
        t << std::fixed << std::setprecision(1) << "t = " << snapshots[i].t << " s: " << snapshots[i].phase;
        gp << "set title '" << t.str() << "'\nplot 'snapshots.dat' index " << i << " using " << columns
           << ":5 with lines lc variable\n";
    }
    gp << "unset multiplot\nset size noratio\n";
}

}  // namespace

bool makePlots(const fs::path& dir, const std::vector<Snapshot>& snapshots, double staticReferenceAxialForce,
               bool wrappedSheaves) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        std::cerr << "reeving-boom-crane: gnuplot not found, figures skipped (apt-get install gnuplot-nox)\n";
        return false;
    }
    std::ofstream gp(dir / "plots.gp");
    gp << std::setprecision(10);
    // timeseries.csv's columns by name (main.cpp writes the header).
    gp << "set terminal pngcairo size 1000,760 font 'DejaVu Sans,11'\nset datafile separator ','\nset grid\n"
       << "set key outside right\nset xlabel 't [s]'\ndeg(x) = x * 180 / pi\n";
    // Slew, luff, hook radius.
    gp << "set output 'fig_slew_luff.png'\nset multiplot layout 2,1 title 'Slewing and luffing'\n"
       << "set ylabel 'angle [deg]'\nplot 'timeseries.csv' using "
          "'t':(deg(column('slew_angle_rad'))) with lines lw 2 title 'slew', '' using 't':(deg(column('boom_angle_rad'))) "
          "with lines lw 2 title 'boom angle'\n"
       << "set ylabel 'length [m]'\nplot 'timeseries.csv' using 't':'hook_radius_m' with lines lw 2 title 'hook radius', '' "
          "using 't':'hook_y_m' with lines lw 2 title 'hook height'\nunset multiplot\n";
    // Swing of the payload.
    gp << "set output 'fig_swing.png'\nset title 'Payload swing about the boom tip'\nset ylabel 'angle [deg]'\n"
       << "plot 'timeseries.csv' using 't':(deg(column('swing_out_of_plane_rad'))) with lines lw 2 title 'out of the "
          "boom plane', '' using 't':(deg(column('swing_in_plane_rad'))) with lines lw 2 title 'in the boom plane'\n"
       << "unset title\n";
    // Span axial forces.
    gp << "set output 'fig_span_axial_forces.png'\nset multiplot layout 2,1 title 'Axial force at the top of every span'\n"
       << "set ylabel 'luffing rope [kN]'\nplot ";
    for (int k = 1; k <= BoomCraneScene::kSpans; ++k)
        gp << (k > 1 ? ", " : "") << "'timeseries.csv' using 't':(column('luffing_span_" << k
           << "_N')/1000) with lines lw 1.5 title 'span " << k << "'";
    gp << "\nset ylabel 'hoist rope [kN]'\nplot ";
    for (int k = 1; k <= BoomCraneScene::kSpans; ++k)
        gp << (k > 1 ? ", " : "") << "'timeseries.csv' using 't':(column('hoist_span_" << k
           << "_N')/1000) with lines lw 1.5 title 'span " << k << "'";
    gp << ", " << staticReferenceAxialForce / 1000 << " with lines dt 2 lw 2 lc 'black' title '(M + m_{hook}) g / 2'\n"
       << "unset multiplot\n";
    // Fleet and wrap angles (0 throughout with point sheaves: a fixed range, gnuplot refuses an empty one).
    gp << "set output 'fig_fleet_wrap_angles.png'\nset multiplot layout 2,1 title 'Fleet and wrap angles"
       << (wrappedSheaves ? "" : " (point sheaves: none)") << "'\n" << (wrappedSheaves ? "" : "set yrange [-1:1]\n")
       << "set ylabel 'largest fleet angle [deg]'\nplot 'timeseries.csv' using 't':(deg(column('luffing_fleet_max_rad'))) "
          "with lines lw 2 title 'luffing rope', '' using 't':(deg(column('hoist_fleet_max_rad'))) with lines lw 2 title "
          "'hoist rope'\n"
       << "set ylabel 'wrap angle [deg]'\nplot ";
    const char* sheaves[] = {"a_frame_1", "luffing_tip", "a_frame_2", "foot", "hoist_tip", "hook"};
    for (int i = 0; i < 6; ++i)
        gp << (i ? ", " : "") << "'timeseries.csv' using 't':(deg(column('wrap_" << sheaves[i]
           << "_rad'))) with lines lw 1.5 title '" << sheaves[i] << "'";
    gp << "\nunset multiplot\nset yrange [*:*]\n";
    // Drives and the energy balance.
    gp << "set output 'fig_energy.png'\nset multiplot layout 3,1 title 'Drives and energy balance'\n"
       << "set ylabel 'power [kW]'\nplot 'timeseries.csv' using 't':(column('slew_power_W')/1000) with lines lw 2 title "
          "'slew', '' using 't':(column('luff_power_W')/1000) with lines lw 2 title 'luffing drum', '' using "
          "'t':(column('hoist_power_W')/1000) with lines lw 2 title 'hoist drum'\n"
       << "set ylabel 'energy [kJ]'\nplot 'timeseries.csv' using 't':(column('motion_work_J')/1000) with lines lw 2 title "
          "'motion work W', '' using 't':((column('motion_work_J')+column('energy_residual_J'))/1000) with lines lw 1 dt 2 "
          "title 'E - E_0'\n"
       << "set ylabel 'residual [J]'\nplot 'timeseries.csv' using 't':'energy_residual_J' with lines lw 2 title "
          "'E - E_0 - W'\nunset multiplot\n";
    // The machine at the snapshots: side view in each snapshot's boom plane, plan view from above.
    double rmin = 1e300, rmax = -1e300, ymin = -0.5, ymax = 1, xmin = 1e300, xmax = -1e300, zmin = 1e300, zmax = -1e300;
    for (const Snapshot& sn : snapshots)
        for (const Polyline& l : sn.lines)
            for (const Vec3& q : l.points) {
                const double r = SimTK::dot(q, sn.boomPlane);
                rmin = std::min(rmin, r);
                rmax = std::max(rmax, r);
                ymin = std::min(ymin, q[1]);
                ymax = std::max(ymax, q[1]);
                xmin = std::min(xmin, q[0]);
                xmax = std::max(xmax, q[0]);
                zmin = std::min(zmin, -q[2]);
                zmax = std::max(zmax, -q[2]);
            }
    gp << "set linetype 1 lc rgb '#909090' lw 1.5\nset linetype 2 lc rgb '#c89000' lw 2\n"
       << "set linetype 3 lc rgb '#d07000' lw 2\nset linetype 4 lc rgb '#7030a0' lw 1\n"
       << "set linetype 5 lc rgb '#101010' lw 1\nset linetype 6 lc rgb '#1f5fa8' lw 2\n"
       << "set linetype 7 lc rgb '#2a8a2a' lw 2\n";
    snapshotFigure(gp, snapshots, "fig_snapshots_side.png", "The boom crane in the boom plane (side view, y up)",
                   "distance from the slewing axis along the boom plane [m]", "y [m]", "4:2", rmin - 1, rmax + 1, ymin - 1,
                   ymax + 1);
    snapshotFigure(gp, snapshots, "fig_snapshots_plan.png", "The boom crane from above (plan view)", "x [m]", "-z [m]",
                   "1:(-$3)", xmin - 1, xmax + 1, zmin - 1, zmax + 1);
    // Bending cycles along each rope, the reeving beside it (side view at t = 0).
    for (const char* rope : {"luffing", "hoist"})
        gp << demo_common::ropeBendingPlot(std::string("fig_rope_bending_") + rope + ".png",
                                           std::string("rope_bending_") + rope + ".csv",
                                           std::string("rope_bending_") + rope + ".dat",
                                           std::string("reeving-boom-crane: bending cycles per section of the ") + rope +
                                               " rope over the run");
    gp.close();
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp";
    if (std::system(cmd.c_str()) != 0) {
        std::cerr << "reeving-boom-crane: gnuplot failed; see " << (dir / "plots.gp").string() << "\n";
        return false;
    }
    return true;
}

}  // namespace boom_crane_demo
