#pragma once
// The results table: one CSV row per case (case id, parameters, metrics, wall_seconds, status,
// message), streamed to DIR/results.csv.partial as cases finish (flushed per row) and written
// sorted by case id to DIR/results.csv when the study ends (atomically: through a temporary file
// renamed into place).

#include "Cases.h"
#include "StudyFile.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace study {

struct ResultRow {
    long id = -1;
    std::vector<std::string> parameters;  ///< parameterColumns' values
    std::vector<std::string> metrics;     ///< Study::metrics' values ("" when missing)
    double wallSeconds = 0;               ///< the case's wall-clock time, demo start to end [s]
    std::string status;                   ///< ok, failed or timeout
    std::string message;                  ///< why it failed ("" when ok)
};

/// case, the parameter columns, the metrics, wall_seconds, status, message.
std::vector<std::string> resultColumns(const Study& study);
/// The CSV header line (no newline).
std::string csvHeader(const Study& study);
/// One CSV line (no newline): fields with a comma, quote or space at an end quoted ("" for a
/// quote); line breaks in the message become " | ".
std::string formatRow(const ResultRow& row);
/// The fields of one CSV line; false if its quotes are unbalanced.
bool splitCsv(const std::string& line, std::vector<std::string>& fields);
/// Reads a row written by formatRow for a study with these column counts; false (and why) if the
/// line is not one.
bool parseRow(const std::string& line, std::size_t parameters, std::size_t metrics, ResultRow& row, std::string& why);

/// The value at a dotted path of summary.json as text: numbers with round-trip precision (whole
/// numbers in plain digits), strings as they are, true/false, null as "" (a NaN of the demo).
/// false (and why) if the path does not lead to a scalar.
bool metricValue(const nlohmann::json& summary, const std::string& path, std::string& text, std::string& why);

/// The rows of a results file written for this study (results.csv or results.csv.partial), by case
/// id, the first of duplicates kept; a last line without its line break (a write cut short) is
/// left out. @throws StudyError if the file's columns or a row's parameter values are not this
/// study's, or a line is not a row.
std::map<long, ResultRow> readResults(const std::filesystem::path& file, const Study& study,
                                      const std::vector<Case>& cases);

/// Appends rows to DIR/results.csv.partial, flushed per row.
class PartialResults {
public:
    /// Writes the header and `existing` rows (in this order) to a new .partial file, replacing one
    /// there. @throws std::runtime_error if it cannot be written.
    PartialResults(const std::filesystem::path& file, const Study& study, const std::vector<ResultRow>& existing);
    /// @throws std::runtime_error if the row cannot be written.
    void append(const ResultRow& row);
    const std::filesystem::path& path() const { return file_; }

private:
    std::filesystem::path file_;
    std::ofstream out_;
};

/// Writes `rows` sorted by case id to `file` through file.tmp renamed into place.
/// @throws std::runtime_error if writing fails.
void writeResults(const std::filesystem::path& file, const Study& study, std::vector<ResultRow> rows);

}  // namespace study
