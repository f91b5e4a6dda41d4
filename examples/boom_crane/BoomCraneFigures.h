#pragma once
// Figures of the reeving-boom-crane demo: the machine drawn in 3D at a state (snapshots, shown as
// a side view in the boom's plane and a plan view from above) and the gnuplot script of all figures.

#include <SimbodyReeving/scenes/BoomCraneScene.h>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace boom_crane_demo {

/// Drawing colours (gnuplot line types 1..7 of the script).
enum class Ink { Structure = 1, Boom = 2, Drum = 3, Sheave = 4, Rope = 5, Hook = 6, Payload = 7 };

/// One polyline of a drawing, Ground points [m].
struct Polyline {
    Ink ink;
    std::vector<SimTK::Vec3> points;
};

/// The machine at one instant.
struct Snapshot {
    double t = 0;
    std::string phase;     ///< "at rest", "lifting", "slewing + luffing", "lowering", "limit reached"...
    SimTK::Vec3 boomPlane; ///< unit horizontal direction of the boom's plane (superstructure's x in Ground)
    std::vector<Polyline> lines;
};

/// Draws the slewing ring and the superstructure's deck, the A-frame, the boom, both drums (with a
/// spoke showing their angle), every sheave in its groove's plane, both ropes (their spans sampled
/// with ReevingSubsystem::sampleSpan and, on wrapped sheaves, the rope on the grooves with
/// sampleArc), the hook block, the sling and the payload at `s` (Stage::Position).
std::vector<Polyline> drawBoomCrane(const SimbodyReeving::BoomCraneScene& scene, const SimTK::State& s);

/// The unit horizontal direction of the boom's vertical plane at `s` (Stage::Position).
SimTK::Vec3 boomPlaneDirection(const SimbodyReeving::BoomCraneScene& scene, const SimTK::State& s);

/// What the cycle is doing at time t ("at rest", or "lifting", "lowering", "slewing", "luffing"
/// joined by " + ").
std::string phaseAt(const SimbodyReeving::BoomCraneCycle& cycle, double t);

/// Writes the snapshots in gnuplot's format: one data set per snapshot (two blank lines between),
/// one block per polyline (one blank line between), columns x y z r ink, where r is the distance
/// from the slewing axis along the snapshot's boom plane (the side view's abscissa).
void writeSnapshots(std::ostream& out, const std::vector<Snapshot>& snapshots);

/// Writes DIR/plots.gp (reads timeseries.csv and snapshots.dat in DIR) and runs gnuplot in DIR.
/// staticReferenceAxialForce [N]: the dashed line of fig_span_axial_forces.png, (M + m_hook) g / 2;
/// wrappedSheaves: false draws the fleet and wrap angles (all 0) on a fixed range.
/// Returns false (with a line on stderr) if gnuplot is missing or fails.
bool makePlots(const std::filesystem::path& dir, const std::vector<Snapshot>& snapshots, double staticReferenceAxialForce,
               bool wrappedSheaves);

}  // namespace boom_crane_demo
