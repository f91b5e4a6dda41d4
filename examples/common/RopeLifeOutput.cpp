#include "RopeLifeOutput.h"

#include "Cli.h"

#include <algorithm>
#include <iomanip>
#include <cmath>
#include <limits>
#include <sstream>

using SimbodyReeving::ReevingSubsystem;
using SimbodyReeving::RopeLifeMonitor;
using SimbodyReeving::RopeSectionCount;

namespace demo_common {

SimbodyReeving::RopeLifeOptions RopeLifeCli::options() const {
    SimbodyReeving::RopeLifeOptions o;
    o.ropeDiameter = ropeDiameter;
    o.sectionLength = sectionLength;
    o.reverseBendFactor = reverseBendFactor;
    return o;
}

void addRopeLifeOptions(CLI::App& app, RopeLifeCli& cli) {
    app.add_option("--rope-diameter", cli.ropeDiameter,
                   "rope diameter d for the bending count [m] (default " + numberText(cli.ropeDiameter) +
                       "; D/d >= 1\nat every sheave and drum)")
        ->type_name("D")
        ->check(positiveNumber());
    app.add_option("--section-length", cli.sectionLength,
                   "unstretched length of the rope sections whose bending cycles are\ncounted [m] (default " +
                       numberText(cli.sectionLength) + ")")
        ->type_name("M")
        ->check(positiveNumber());
    app.add_option("--reverse-bend-factor", cli.reverseBendFactor,
                   "weight of a reverse bending cycle against a simple one, >= 1\n(default 1: counted as simple; "
                   "the reverse cycles are reported\nseparately; docs/rope-life.md)")
        ->type_name("W")
        ->check(finiteNumber());
}

void writeRopeBendingCsv(std::ostream& out, const RopeLifeMonitor& life) {
    out << "section,s_start_m,s_end_m,cycles,simple_cycles,reverse_cycles,max_tension_N\n" << std::setprecision(12);
    for (int i = 0; i < life.numSections(); ++i) {
        const RopeSectionCount& c = life.sections()[i];
        out << i << ',' << c.start << ',' << c.start + life.sectionLength(i) << ',' << c.cycles << ',' << c.simpleCycles
            << ',' << c.reverseCycles << ',' << c.maxTension << '\n';
    }
}

Json ropeLifeSummary(const RopeLifeMonitor& life, const RopeLifeCli& cli) {
    Json rl;
    rl["rope_diameter_m"] = jsonNumber(cli.ropeDiameter);
    rl["section_length_m"] = jsonNumber(cli.sectionLength);
    rl["reverse_bend_factor"] = jsonNumber(cli.reverseBendFactor);
    rl["sections"] = life.numSections();
    rl["bend_events"] = static_cast<long>(life.events().size());
    // The most bent section; none (no key) when no section went onto or off a sheave or drum.
    const int worst = life.mostBentSection();
    if (worst < 0 || !(life.sections()[worst].cycles > 0)) return rl;
    const RopeSectionCount& c = life.sections()[worst];
    // The smallest D/d among the nodes it went onto or off.
    double smallestRatio = std::numeric_limits<double>::infinity();
    for (const auto& e : life.events())
        if (e.section == worst) smallestRatio = std::min(smallestRatio, e.diameterRatio);
    rl["worst_section"] = {{"index", worst},
                           {"s_start_m", jsonNumber(c.start)},
                           {"s_end_m", jsonNumber(c.start + life.sectionLength(worst))},
                           {"cycles", jsonNumber(c.cycles)},
                           {"simple_cycles", jsonNumber(c.simpleCycles)},
                           {"reverse_cycles", jsonNumber(c.reverseCycles)},
                           {"max_tension_N", jsonNumber(c.maxTension)},
                           {"min_diameter_ratio", jsonNumber(smallestRatio)}};
    return rl;
}

std::vector<RopePathPoint> sampleRopePath(const ReevingSubsystem& reeving, const SimTK::State& state, int rope,
                                          int pointsPerSpan) {
    std::vector<RopePathPoint> path;
    const int spans = reeving.getNumSpans(rope);
    auto addSegment = [&](const std::vector<SimTK::Vec3>& points, double s1, double s2) {
        const int n = static_cast<int>(points.size());
        for (int i = 0; i < n; ++i) path.push_back({points[i], s1 + (s2 - s1) * i / (n - 1)});
        path.push_back({SimTK::Vec3(std::numeric_limits<double>::quiet_NaN()), 0.0});  // a break
    };
    for (int j = 0; j < spans; ++j) {
        const auto [s1, s2] = reeving.getSpanMaterialRange(state, rope, j);
        addSegment(reeving.sampleSpan(state, rope, j, pointsPerSpan), s1, s2);
        // The rope on the groove of node j + 1 (a wrapped sheave): the material between this span's
        // end and the next span's start; a point node has none.
        if (j + 1 < spans) {
            const double next = reeving.getSpanMaterialRange(state, rope, j + 1).first;
            if (next > s2) addSegment(reeving.sampleArc(state, rope, j + 1, pointsPerSpan), s2, next);
        }
    }
    return path;
}

std::vector<double> nodeMaterialCoordinates(const ReevingSubsystem& reeving, const SimTK::State& state, int rope) {
    std::vector<double> s;
    for (int k = 0; k <= reeving.getNumSpans(rope); ++k) s.push_back(reeving.getMaterialCoordinate(state, rope, k));
    return s;
}

void writeRopeBendingFigureData(std::ostream& out, const std::vector<RopePathPoint>& path,
                                const std::vector<double>& nodes, const RopeLifeMonitor& life) {
    const auto& sections = life.sections();
    out << std::setprecision(10);
    out << "# x,y,z,s,cycles\n";
    bool broken = true;  // a blank line ends a segment; two would end the data block
    for (const RopePathPoint& p : path) {
        if (std::isnan(p.position[0])) {
            if (!broken) out << '\n';
            broken = true;
            continue;
        }
        // The section holding s: the last one starting at or before it.
        const auto it = std::upper_bound(sections.begin(), sections.end(), p.materialCoordinate,
                                         [](double s, const RopeSectionCount& c) { return s < c.start; });
        if (it == sections.begin()) continue;
        const int i = static_cast<int>(it - sections.begin()) - 1;
        if (p.materialCoordinate > sections[i].start + life.sectionLength(i)) continue;
        out << p.position[0] << ',' << p.position[1] << ',' << p.position[2] << ',' << p.materialCoordinate << ','
            << sections[i].cycles << '\n';
        broken = false;
    }
    out << (broken ? "\n" : "\n\n") << "# k,s_k\n";
    for (size_t k = 0; k < nodes.size(); ++k) out << k << ',' << nodes[k] << '\n';
}

std::string ropeBendingPlot(const std::string& output, const std::string& csv, const std::string& data,
                            const std::string& title) {
    std::ostringstream g;
    g << "set terminal pngcairo size 1400,640 font 'DejaVu Sans,11' noenhanced\n"
      << "set output '" << output << "'\n"
      << "set datafile separator ','\nstats '" << csv << "' using 4 nooutput name 'C'\n"
      << "top = C_max > 0 ? 1.15 * C_max : 1\n"
      << "set multiplot title '" << title << "'\n"
      // Left: the rope drawn at the start, coloured by the cycles of the material there.
      << "set palette defined (0 '#d0d0d0', 1 '#3060ff', 2 '#ff9000', 3 '#d00000')\n"
      << "set cbrange [0:top]\nset cblabel 'bending cycles of the section'\nunset key\nset grid\n"
      << "set origin 0,0\nset size noratio 0.36,0.95\nset autoscale xy\nset offsets graph 0.1, graph 0.1, graph 0.05, graph 0.05\n"
      << "set xlabel 'x [m]'\nset ylabel 'y [m]'\nset title 'the reeving at the start, coloured by cycles'\n"
      << "plot '" << data << "' index 0 using 1:2:5 with lines lw 3 palette\n"
      // Right: cycles per section along the rope, the nodes' material coordinates at the start.
      << "set origin 0.36,0\nset size noratio 0.64,0.95\nunset colorbox\nset autoscale x\nset offsets 0, 0, 0, 0\n"
      << "set yrange [0:top]\nset key inside left top opaque\n"
      << "set xlabel 'material coordinate s [m], from the start of the rope'\nset ylabel 'bending cycles'\n"
      << "set title 'cycles per section; dashed: the nodes at the start'\n"
      << "plot '" << data << "' index 1 using 2:(top) with impulses dt 2 lc rgb '#808080' notitle, "
      << "'' index 1 using 2:(0.96 * top):(sprintf(' node %d', $1)) with labels left font ',9' notitle, "
      << "'" << csv << "' using 2:4 with steps lw 2 lc rgb '#d00000' title 'cycles (reverse weighted)', "
      << "'' using 2:6 with steps lw 1 lc rgb '#3060ff' title 'reverse cycles (unweighted)'\n"
      << "unset multiplot\nset autoscale\nset offsets 0, 0, 0, 0\nset origin 0,0\nset size 1,1\nset colorbox\n"
      << "set datafile separator ','\n";
    return g.str();
}

}  // namespace demo_common
