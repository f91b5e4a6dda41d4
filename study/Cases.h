#pragma once
// The cases of a study: the full grid of the varied parameters (the first one in the file varies
// slowest) times the sample's points, numbered 0, 1, ... (case id = grid index * sample count +
// sample index), and each case's command line for the scene's demo.

#include "StudyFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace study {

/// One case: the value of every study parameter column (parameterColumns), as the demo gets it.
struct Case {
    long id = 0;
    std::vector<std::string> values;
};

/// The columns of the results table that name a case's parameters: the varied ones in file order,
/// then the sampled ones.
std::vector<std::string> parameterColumns(const Study& study);

/// The number of grid points (1 without vary:), of sample points (1 without sample:), of cases.
long gridSize(const Study& study);
long sampleSize(const Study& study);
long caseCount(const Study& study);

/// The Latin hypercube of a sample: points[i][j] in [0, 1) is point i's coordinate along
/// parameter j; for every j, floor(points[i][j] * count) runs over 0..count-1 once (each stratum
/// hit once). Deterministic for a seed on every platform (its own 64-bit generator, splitmix64).
std::vector<std::vector<double>> latinHypercube(long count, std::size_t dimensions, std::uint64_t seed);

/// Every case's values, by id. The sample's values are numbers in shortest round-trip form.
std::vector<Case> makeCases(const Study& study);

/// The demo's arguments for a case (after the program name): the scenario, the fixed parameters,
/// the case's values as --name=value (`set.KEY` as --set=KEY=value; the value true as a bare flag,
/// false left out), then the runner's --out=DIR --no-plots --quiet and --max-steps=N (limits).
std::vector<std::string> demoArguments(const Study& study, const Case& c, const std::string& outDir);

/// "car-load=0.5, friction=0.2" (the case's parameter columns).
std::string describeCase(const Study& study, const Case& c);

}  // namespace study
