#pragma once
// What a person reads after a study: DIR/summary.json and the printed summary (counts, failures
// with their messages, wall time, speedup over one process), and the figures the study file asks
// for (gnuplot, in DIR/figures/).

#include "Cases.h"
#include "Results.h"
#include "StudyFile.h"

#include <filesystem>
#include <string>
#include <vector>

namespace study {

struct RunInfo {
    std::string demo;             ///< the demo program's path
    double wallSeconds = 0;       ///< this run of the study, from start to the last case [s]
    long casesRun = 0;            ///< cases run by this run (the others came from --resume)
    double caseWallSeconds = 0;   ///< sum of the wall times of the cases this run ran [s]
    int ranks = 1;                ///< MPI ranks (1: serial)
    int workers = 1;              ///< processes that ran cases
};

/// Writes DIR/summary.json (through a .tmp file renamed into place).
void writeSummary(const std::filesystem::path& file, const Study& study, const std::vector<ResultRow>& rows,
                  const RunInfo& info, const std::vector<std::string>& figures, const std::string& figureNote);

/// The printed summary: counts, wall time and speedup, then one line per failure (the first 20).
std::string summaryText(const Study& study, const std::vector<ResultRow>& rows, const RunInfo& info);

/// Makes the study's figures in `dir` (created) with gnuplot, one run each (NAME.gp, NAME.dat,
/// NAME.png): the PNGs' paths relative to dir's parent. Without gnuplot the list is empty and `note`
/// says so; a figure gnuplot cannot draw is left out and named in `note` (its NAME.log kept). Cases
/// that failed leave their points out.
std::vector<std::string> makeFigures(const std::filesystem::path& dir, const Study& study,
                                     const std::vector<ResultRow>& rows, std::string& note);

}  // namespace study
