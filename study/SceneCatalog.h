#pragma once
// The scenes a study can run: each one's demo program and what its summary.json holds, so that a
// study file's metrics are checked before any case runs.

#include <string>
#include <vector>

namespace study {

struct SceneInfo {
    std::string name;     ///< as in the study file's `scene:` ("elevator")
    std::string program;  ///< the demo program run for each case ("reeving-elevator")
    bool hasScenarios;    ///< the demo takes --scenario
    /// Options that must have one value per case (the pendulum's --axial-modes: several values
    /// write one summary per mode).
    std::vector<std::string> singleValueOptions;
    /// The scalar values of the demo's summary.json, as dotted paths: `#` stands for an array index
    /// ("traction_table.#.traction_margin"), `*` for any key of an object ("parameters.*").
    std::vector<std::string> metricPatterns;
};

/// The bundled scenes: pendulum, crane, elevator.
const std::vector<SceneInfo>& scenes();
/// The scene called `name`, or nullptr.
const SceneInfo* findScene(const std::string& name);
/// "pendulum, crane, elevator".
std::string sceneNames();

/// true if `path` (dotted, array indices as numbers: "traction_table.0.traction_margin") is one of
/// the scene's metric patterns.
bool isKnownMetric(const SceneInfo& scene, const std::string& path);

/// `path` with every array index replaced by `#` ("traction_table.0.x" -> "traction_table.#.x").
std::string metricPattern(const std::string& path);

}  // namespace study
