#pragma once
// The bending count's outputs shared by the bundled demos (RopeLifeMonitor, docs/rope-life.md):
// its three command-line options, rope_bending.csv (one row per rope section), the summary's
// "rope_life" object, and the figure of the cycles along the rope with the reeving drawn beside it.
#include "DemoOutput.h"

#include <SimbodyReeving/simbody/RopeLifeMonitor.h>

#include <CLI/CLI.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace demo_common {

/// The bending count's command-line options (--rope-diameter, --section-length,
/// --reverse-bend-factor) and their values.
struct RopeLifeCli {
    double ropeDiameter = 0.02;      ///< d [m], > 0; the demo sets its rope's default
    double sectionLength = 0.1;      ///< [m], > 0
    double reverseBendFactor = 1.0;  ///< w_r [-], >= 1: 1 counts reverse bends as simple ones

    /// The monitor's options from these values (RopeLifeMonitor checks them).
    SimbodyReeving::RopeLifeOptions options() const;
};

/// Adds the three options to `app`, bound to `cli`, whose ropeDiameter is the demo's default.
void addRopeLifeOptions(CLI::App& app, RopeLifeCli& cli);

/// rope_bending.csv: `section,s_start_m,s_end_m,cycles,simple_cycles,reverse_cycles,max_tension_N`,
/// one row per section (material coordinates s from the start of the rope, the start drum's stored
/// rope first; cycles weighted by the reverse-bend factor, the simple and reverse ones unweighted).
void writeRopeBendingCsv(std::ostream& out, const SimbodyReeving::RopeLifeMonitor& life);

/// summary.json's "rope_life": the options, the number of sections and of bend events, and, when a
/// section collected cycles, "worst_section": the most bent one (index, material range, cycles,
/// simple and reverse cycles, largest tension, and the smallest D/d of the nodes it went onto or
/// off). Without any bend (a run too short to move rope over a sheave) there is no worst_section.
Json ropeLifeSummary(const SimbodyReeving::RopeLifeMonitor& life, const RopeLifeCli& cli);

/// A point of the rope drawn at one instant: its position in Ground [m] and material coordinate [m].
struct RopePathPoint {
    SimTK::Vec3 position{0};
    double materialCoordinate = 0;
};

/// The rope's spans (and, with wrapped sheaves, its arcs), `pointsPerSpan` >= 2 material points
/// each, in path order, at `state` (Stage::Position); the node points with their material
/// coordinates are the nodes' (ReevingSubsystem::getMaterialCoordinate).
std::vector<RopePathPoint> sampleRopePath(const SimbodyReeving::ReevingSubsystem& reeving, const SimTK::State& state,
                                          int rope, int pointsPerSpan);

/// The material coordinate of each node of `rope` at `state` [m] (nodes 0..N).
std::vector<double> nodeMaterialCoordinates(const SimbodyReeving::ReevingSubsystem& reeving, const SimTK::State& state,
                                            int rope);

/// The figure's data, comma separated: `path` rows "x,y,z,s,cycles" (a blank line between spans
/// and arcs; points whose material lies in no section are left out), then two blank lines and the
/// `nodes` rows "k,s_k". The cycles of a point are its section's (RopeSectionCount::cycles).
void writeRopeBendingFigureData(std::ostream& out, const std::vector<RopePathPoint>& path,
                                const std::vector<double>& nodes, const SimbodyReeving::RopeLifeMonitor& life);

/// Gnuplot commands for one PNG `output`: left, the rope drawn at the instant sampled (x, y
/// projection) coloured by each point's cycles; right, the cycles per section along the rope (from
/// `csv`, rope_bending.csv) with each node's material coordinate at that instant marked. `data`
/// is writeRopeBendingFigureData's file; `title` heads the figure.
std::string ropeBendingPlot(const std::string& output, const std::string& csv, const std::string& data,
                            const std::string& title);

}  // namespace demo_common
