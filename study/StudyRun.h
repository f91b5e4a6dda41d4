#pragma once
// One run of a study on the process that writes (the only one without MPI, rank 0 with it): the
// command line, the checks before any case runs, the results streamed as cases finish, the
// progress line and the outputs at the end.

#include "Cases.h"
#include "Report.h"
#include "Results.h"
#include "Runner.h"
#include "StudyFile.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace study {

class StudyRun;

/// Exit statuses of reeving-study.
constexpr int kExitOk = 0;            ///< every case ok (or --dry-run, --help)
constexpr int kExitCaseFailed = 1;    ///< the study ran to its end; some cases failed or timed out
constexpr int kExitBadInput = 2;      ///< bad study file or command line: nothing run, nothing written
constexpr int kExitInterrupted = 130; ///< SIGINT/SIGTERM: results.csv.partial kept for --resume

struct CommandLine {
    std::string studyFile;  ///< the study file (a folder given on the command line: its study.yaml)
    std::string outDir;     ///< DIR (default out/<the study's name>)
    std::string demoDir;    ///< where the demos are ("": next to reeving-study)
    bool dryRun = false, resume = false, quiet = false;
};

/// Parses reeving-study's command line. Returns -1 to go on, else the exit status: 0 after --help
/// (printed), 2 for a bad command line (the message printed). `speak` false: nothing printed (the
/// MPI ranks other than 0).
int parseCommandLine(int argc, char** argv, CommandLine& commandLine, bool speak = true);

/// Runs the pending cases of a prepared run one after the other; returns finish()'s status.
int runSerial(StudyRun& run);

class StudyRun {
public:
    /// ranks: MPI ranks (1: serial); workers: processes that run cases.
    StudyRun(CommandLine commandLine, int ranks, int workers);
    ~StudyRun();

    /// Parses the study's text, checks every case to run with the demo's --check, then lists the
    /// cases (--dry-run) or prepares the output folder and its results.csv.partial. Returns -1 to
    /// run pending(), else the exit status (0 after --dry-run; 2 bad input, the message printed).
    int prepare(const std::string& studyText);

    const Study& study() const { return study_; }
    const std::vector<Case>& cases() const { return cases_; }
    /// The case ids to run, ascending.
    const std::vector<long>& pending() const { return pending_; }
    const RunSettings& settings() const { return settings_; }

    /// A finished case: appended to results.csv.partial (flushed), progress line updated.
    /// @throws std::runtime_error if it cannot be written.
    void record(const ResultRow& row);

    /// Ends the study: unless interrupted, writes results.csv (sorted by case id; the .partial
    /// removed), summary.json and the figures and prints the summary. Returns the exit status.
    int finish(bool interrupted);

private:
    void progress(bool last);

    CommandLine commandLine_;
    int ranks_, workers_;
    Study study_;
    std::vector<Case> cases_;
    std::vector<long> pending_;
    std::vector<ResultRow> rows_;  // resumed, then as they finish
    std::unique_ptr<ScratchFolder> scratch_;
    RunSettings settings_;
    std::unique_ptr<PartialResults> partial_;
    std::filesystem::path out_;
    std::chrono::steady_clock::time_point start_, lastProgress_;
    long resumed_ = 0, runNow_ = 0, failedNow_ = 0;
    double caseWall_ = 0;
    bool progressShown_ = false;
};

}  // namespace study
