#pragma once
// Output conventions shared by the bundled demos (reeving-pendulum, reeving-crane): the output
// folder is checked before anything is simulated, and every file is written through a .partial
// file renamed into place only when complete.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

namespace demo_common {

/// Creates `dir` if needed and checks that it is a writable folder. On failure prints one line,
/// "<program>: --out '<dir>': cannot create the output folder: <why>" (or "...: the output folder
/// is not writable"), to stderr and returns false; the caller then exits 2.
bool prepareOutputFolder(const std::string& program, const std::string& dir);

/// Writes `path` through `path.partial`, renamed into place only by commit(): an interrupted or
/// failed write leaves no half-written file under the real name (the destructor removes the
/// .partial file of an uncommitted write).
class OutputFile {
public:
    /// @throws std::runtime_error if the .partial file cannot be opened.
    explicit OutputFile(std::filesystem::path path);
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;
    ~OutputFile();
    std::ofstream& stream() { return out_; }
    /// Closes the stream and renames the .partial file to the real name.
    /// @throws std::runtime_error if writing failed (disk full...).
    void commit();

private:
    std::filesystem::path path_, partial_;
    std::ofstream out_;
    bool committed_ = false;
};

/// summary.json's objects keep their keys in the order written.
using Json = nlohmann::ordered_json;

/// A real number for summary.json, rounded to 12 significant digits (what `%.12g` prints: the
/// digits beyond are integration noise and make files differ from run to run for nothing); NaN
/// and infinities become null.
Json jsonNumber(double v);

/// Writes `json` indented by two spaces, with a final newline.
void writeJson(std::ostream& out, const Json& json);

}  // namespace demo_common
