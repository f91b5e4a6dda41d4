#pragma once
// Figures of the reeving-crane demo: the machine drawn in the x-y plane at a state (rope-geometry
// snapshots) and the gnuplot script of all figures.

#include <SimbodyReeving/scenes/CraneScene.h>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace crane_demo {

/// Drawing colours (gnuplot line types 1..7 of the script).
enum class Ink { Structure = 1, Trolley = 2, Drum = 3, Sheave = 4, Rope = 5, Hook = 6, Payload = 7 };

/// One polyline of a drawing [m].
struct Polyline {
    Ink ink;
    std::vector<SimTK::Vec2> points;
};

/// The machine at one instant.
struct Snapshot {
    double t = 0;
    std::string phase;  ///< "at rest", "lifting", "traversing", "lowering", "limit reached"...
    std::vector<Polyline> lines;
};

/// Draws trolley, drum (with a spoke showing its angle), sheaves, the rope as one polyline (the
/// falls sampled with ReevingSubsystem::sampleSpan and, on wrapped sheaves, the rope on the
/// grooves with sampleArc), hook block, sling and payload at `s` (Stage::Position).
std::vector<Polyline> drawCrane(const SimbodyReeving::CraneScene& scene, const SimTK::State& s);

/// What the cycle is doing at time t ("at rest", "lifting", "lowering", "traversing", or two of
/// them joined by " + ").
std::string phaseAt(const SimbodyReeving::CraneCycle& cycle, double t);

/// Writes the snapshots in gnuplot's format: one data set per snapshot (two blank lines between),
/// one block per polyline (one blank line between), columns x y ink.
void writeSnapshots(std::ostream& out, const std::vector<Snapshot>& snapshots);

/// Writes DIR/plots.gp (reads timeseries.csv and snapshots.dat in DIR) and runs gnuplot in DIR.
/// staticReferenceAxialForce [N]: the dashed reference line of fig_fall_axial_forces.png, (M + m_hook) g / n.
/// Returns false (with a line on stderr) if gnuplot is missing or fails.
bool makePlots(const std::filesystem::path& dir, const SimbodyReeving::CraneScene& scene,
               const std::vector<Snapshot>& snapshots, double staticReferenceAxialForce);

}  // namespace crane_demo
