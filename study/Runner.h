#pragma once
// Running a study's cases: each one is the scene's demo program in a child process, with its own
// output folder in a scratch folder, --no-plots --quiet and the study's limits; its numbers come
// from the summary.json it writes. A case that fails, crashes or passes its wall-clock limit is a
// row with status failed or timeout and the end of the demo's stderr as its message.

#include "Cases.h"
#include "Results.h"
#include "StudyFile.h"

#include <filesystem>
#include <string>
#include <vector>

namespace study {

/// A scratch folder of the runner's (TMPDIR or /tmp), removed with everything in it on destruction.
class ScratchFolder {
public:
    /// @throws std::runtime_error if it cannot be created.
    ScratchFolder();
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    ~ScratchFolder();
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

struct RunSettings {
    std::string program;          ///< the demo's path
    std::filesystem::path scratch;
    double terminateGrace = 2.0;  ///< [s] between SIGTERM and SIGKILL of a case past its wall limit
};

/// The demo program of the study's scene: `demoDir`/reeving-<scene> (demoDir "" : the folder of the
/// running executable). @throws StudyError naming the scene's place if it is not there.
std::string locateDemo(const Study& study, const std::string& demoDir);

/// Runs one case. Sets `interrupted` (and returns an empty row) if SIGINT or SIGTERM came first:
/// the case's demo was stopped and the case is not done.
ResultRow runCase(const Study& study, const Case& c, const RunSettings& settings, bool& interrupted);

/// Checks the cases' values with the demo's --check, `parallel` at a time, in id order.
/// @throws StudyError for the lowest case id rejected, naming the place in the study file of the
/// parameter the demo's message names ("unknown parameter 'x'" for an option the demo does not
/// have).
void checkCases(const Study& study, const std::vector<Case>& cases, const RunSettings& settings, int parallel);

}  // namespace study
