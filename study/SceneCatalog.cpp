#include "SceneCatalog.h"

#include <cctype>
#include <sstream>

namespace study {
namespace {

std::vector<std::string> split(const std::string& path) {
    std::vector<std::string> parts;
    std::stringstream ss(path);
    std::string part;
    while (std::getline(ss, part, '.')) parts.push_back(part);
    if (!path.empty() && path.back() == '.') parts.emplace_back();
    return parts;
}

bool isIndex(const std::string& s) {
    if (s.empty() || s.size() > 9) return false;
    for (char c : s)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

bool matches(const std::string& pattern, const std::string& path) {
    const std::vector<std::string> p = split(pattern), q = split(path);
    if (p.size() != q.size()) return false;
    for (size_t i = 0; i < p.size(); ++i) {
        if (q[i].empty()) return false;
        if (p[i] == "#" ? !isIndex(q[i]) : p[i] == "*" ? isIndex(q[i]) : p[i] != q[i]) return false;
    }
    return true;
}

}  // namespace

// Kept in step with the demos' summary.json by tests/study/test_study_demos.cpp
// (StudyDemos.SceneCatalogueMatchesTheDemosSummaries), which runs each demo (each crane scenario)
// and compares: a demo that writes a new key to its summary.json adds it here. Every key is listed
// (no `*` for the scene parameters), so that a misspelt metric is found before any case runs.
const std::vector<SceneInfo>& scenes() {
    static const std::vector<SceneInfo> list = {
        {"pendulum",
         "reeving-pendulum",
         false,
         {"axial-modes"},
         {"integrator", "accuracy", "fixed_step", "axial_modes", "transverse_modes", "axial_dynamics",
          "quasi_static_transverse", "axial_law", "sheaves", "t_end", "t_reached", "termination", "limit", "vx0", "vy0", "steps", "rhs_evaluations",
          "wall_seconds", "initial_kinetic_energy_J", "max_energy_drift_J", "max_constraint_error_N",
          "sheave_wrap_angles.#.sheave", "sheave_wrap_angles.#.min_rad", "sheave_wrap_angles.#.max_rad",
          "max_fleet_angle_rad", "parameters.a", "parameters.L",
          "parameters.d", "parameters.r", "parameters.g", "parameters.rhoA", "parameters.EA", "parameters.EI",
          "parameters.M", "parameters.J"}},
        {"crane",
         "reeving-crane",
         true,
         {},
         {"program", "scenario", "falls", "sheaves", "axial_modes", "transverse_modes", "axial_dynamics", "axial_law", "integrator",
          "accuracy", "fixed_step", "report_interval", "lift_m", "traverse_m", "t_end", "t_reached", "termination",
          "limit", "static_fall_axial_force_N.#", "static_reference_axial_force_N", "max_fall_axial_force_N.#",
          "static_rope_force", "peak_rope_force", "peak_rope_force_time", "dynamic_factor",
          // lift-off only
          "hoist_speed", "lift_off_time", "hook_stiffness_N_per_m", "spring_mass_dynamic_factor", "rope_slack_m",
          "floor_height_m", "final_contact_dissipation_J",
          // both scenarios
          "max_abs_sway_rad", "initial_largest_fall_lean_deg", "max_largest_fall_lean_deg",
          "sheave_wrap_angles.#.sheave", "sheave_wrap_angles.#.min_rad", "sheave_wrap_angles.#.max_rad",
          "max_fleet_angle_rad", "max_abs_rope_length_error_m", "max_abs_payload_angle_rad", "initial_hook_height_m", "final_hook_height_m",
          "final_rope_on_drum_m", "max_abs_motor_torque_Nm", "max_abs_motor_power_W", "max_abs_trolley_force_N",
          "final_motion_work_J", "max_abs_motion_work_J", "max_abs_energy_residual_J", "energy_residual_relative",
          // bending cycles per rope section (RopeLifeMonitor): the most bent one
          "rope_life.rope_diameter_m", "rope_life.section_length_m", "rope_life.reverse_bend_factor",
          "rope_life.sections", "rope_life.bend_events", "rope_life.worst_section.index",
          "rope_life.worst_section.s_start_m", "rope_life.worst_section.s_end_m", "rope_life.worst_section.cycles",
          "rope_life.worst_section.simple_cycles", "rope_life.worst_section.reverse_cycles",
          "rope_life.worst_section.max_tension_N", "rope_life.worst_section.min_diameter_ratio",
          "steps", "rhs_evaluations", "wall_seconds", "real_time_factor", "snapshot_times.#", "parameters.g",
          "parameters.railHeight", "parameters.trolleyX0", "parameters.trolleyMass", "parameters.sheavePitch",
          "parameters.sheaveRadius", "parameters.drumRadius", "parameters.drumHeight", "parameters.drumMass",
          "parameters.drumInertia", "parameters.ropeOnDrum", "parameters.hookMass", "parameters.hookInertia",
          "parameters.hookComBelow", "parameters.hookPinBelow", "parameters.initialHookDepth", "parameters.payloadMass",
          "parameters.payloadInertia", "parameters.slingLength", "parameters.payloadWidth", "parameters.payloadHeight",
          "parameters.rhoA", "parameters.EA", "parameters.EI", "parameters.minimumSpanLength",
          // lift-off only
          "parameters.hoistSpeed", "parameters.hoistRamp", "parameters.slackTime", "parameters.afterLiftOff",
          "parameters.floorStiffness", "parameters.floorDampingRatio", "parameters.slingStiffness",
          "parameters.slingDampingRatio"}},
        {"elevator",
         "reeving-elevator",
         true,
         {},
         {"program",
          "roping",
          "compensation",
          "sheaves",
          "traction_slip",
          "friction",
          "wrap_angle_rad",
          "deflector",
          "rated_load_kg",
          "car_mass_kg",
          "counterweight_kg",
          "retardation_time_s",
          "traction_table.#.scenario",
          "traction_table.#.traction",
          "traction_table.#.traction_limit",
          "traction_table.#.wrap_angle_min_rad",
          "traction_table.#.wrap_angle_max_rad",
          "traction_table.#.sheave_wrap_angles.#.node",
          "traction_table.#.sheave_wrap_angles.#.min_rad",
          "traction_table.#.sheave_wrap_angles.#.max_rad",
          "traction_table.#.max_fleet_angle_rad",
          "traction_table.#.largest_force_ratio",
          "traction_table.#.traction_margin",
          "traction_table.#.car_load",
          "traction_table.#.car_position_m",
          "traction_table.#.slip_distance_m",
          "traction_table.#.stick_slip_transitions",
          "traction_table.#.car_rise_m",
          "traction_table.#.rope_travel_m",
          "traction_table.#.max_car_acceleration_mps2",
          "traction_table.#.friction_work_J",
          "traction_table.#.damping_work_J",
          "traction_table.#.machine_work_J",
          "traction_table.#.max_energy_residual_J",
          "traction_table.#.energy_residual_relative",
          // the hoist ropes' bending cycles per section (RopeLifeMonitor): the most bent one
          "traction_table.#.rope_life.rope_diameter_m",
          "traction_table.#.rope_life.section_length_m",
          "traction_table.#.rope_life.reverse_bend_factor",
          "traction_table.#.rope_life.sections",
          "traction_table.#.rope_life.bend_events",
          "traction_table.#.rope_life.worst_section.index",
          "traction_table.#.rope_life.worst_section.s_start_m",
          "traction_table.#.rope_life.worst_section.s_end_m",
          "traction_table.#.rope_life.worst_section.cycles",
          "traction_table.#.rope_life.worst_section.simple_cycles",
          "traction_table.#.rope_life.worst_section.reverse_cycles",
          "traction_table.#.rope_life.worst_section.max_tension_N",
          "traction_table.#.rope_life.worst_section.min_diameter_ratio",
          "traction_table.#.simulated_s",
          "traction_table.#.steps",
          "traction_table.#.rhs_evaluations",
          "traction_table.#.wall_s",
          "traction_table.#.real_time_factor"}},
    };
    return list;
}

const SceneInfo* findScene(const std::string& name) {
    for (const SceneInfo& s : scenes())
        if (s.name == name) return &s;
    return nullptr;
}

std::string sceneNames() {
    std::string names;
    for (const SceneInfo& s : scenes()) names += (names.empty() ? "" : ", ") + s.name;
    return names;
}

bool isKnownMetric(const SceneInfo& scene, const std::string& path) {
    for (const std::string& pattern : scene.metricPatterns)
        if (matches(pattern, path)) return true;
    return false;
}

std::string metricPattern(const std::string& path) {
    std::string out;
    for (const std::string& part : split(path)) out += (out.empty() ? "" : ".") + (isIndex(part) ? "#" : part);
    return out;
}

}  // namespace study
