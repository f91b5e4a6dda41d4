#pragma once
// A study file (YAML, docs/studies.md): the scene, its fixed and varied demo options, the metrics
// to collect from each case's summary.json, per-case limits and figures. parseStudy checks all of
// it that can be checked without the demo; each case's values are then checked by the demo's own
// --check (Runner.h).

#include "SceneCatalog.h"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace study {

/// Bad input (study file or command line): what() is one line, "FILE:LINE:COLUMN: message" when
/// it has a place in the study file. The program prints it and exits 2, having written nothing.
struct StudyError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A place in the study file: 1-based line and column (0: unknown).
struct Place {
    int line = 0, column = 0;
};

/// "FILE:LINE:COLUMN: message" (or "FILE: message" without a place).
std::string placed(const std::string& file, const Place& place, const std::string& message);

/// A demo option with one value for every case (`fixed:`; the top-level `scenario:` too).
struct FixedParameter {
    std::string name;   ///< as in the study file: "friction", "set.M", "scenario"
    std::string value;  ///< the text passed to the demo ("true": a bare flag; "false": left out)
    Place place;        ///< of the value
    Place namePlace;    ///< of the name
};

/// A demo option varied over a list (`vary:`): values, linear or log range.
struct VariedParameter {
    std::string name;
    /// In order. A range's numbers: from + (to - from) i / (count - 1) or from (to / from)^(i / (count
    /// - 1)), the ends exact, rounded to 15 significant digits (0.3, not 0.30000000000000004), in the
    /// shortest text that reads back to them.
    std::vector<std::string> values;
    std::vector<Place> valuePlaces;   ///< of each value (a range's values: the range's place)
    Place place;                      ///< of the name
};

/// A demo option drawn by the sample (`sample.parameters:`).
struct SampledParameter {
    std::string name;
    double from = 0, to = 1;
    bool logScale = false;
    Place place;
};

/// `sample:`: Latin hypercube sampling (the only method): `count` points, each parameter's range
/// cut into `count` equal strata (equal in log for scale: log), every stratum of every parameter
/// hit once, the points random within their strata (seeded: the same points every run).
struct Sample {
    long count = 0;
    std::uint64_t seed = 1;
    std::vector<SampledParameter> parameters;
    Place place;
};

/// A metric: a dotted path into the case's summary.json, or one the runner adds (wall_seconds).
struct Metric {
    std::string path;
    Place place;
};

struct Figure {
    enum class Type { Lines, Heatmap } type = Type::Lines;
    std::string x, y, z;  ///< lines: parameter x, metric y; heat map: parameters x and y, metric z
    /// Heat map: a boundary drawn along the cell edges between the cells on either side of it:
    /// z >= boundary and z < boundary (`boundary: NUMBER`), or boundaryMetric equal to
    /// boundaryValue and not (`boundary: {metric: METRIC, equals: VALUE}`, e.g. held and slipped).
    std::optional<double> boundary;
    std::string boundaryMetric, boundaryValue;
    std::string name;                ///< the PNG's name without .png
    Place place;
};

struct Limits {
    double wallSeconds = 0;  ///< per case, wall clock [s]; 0: none
    long maxSteps = 0;       ///< per case, integrator steps (the demo's --max-steps); 0: none
};

struct Study {
    std::string file;  ///< the study file's name, for messages
    std::string description;
    const SceneInfo* scene = nullptr;
    Place scenePlace;
    std::vector<FixedParameter> fixed;     ///< the top-level scenario first, then `fixed:` in file order
    std::vector<VariedParameter> vary;     ///< in file order: the first varies slowest
    std::optional<Sample> sample;
    std::vector<Metric> metrics;           ///< in file order, without the runner's wall_seconds
    bool wallSecondsListed = false;        ///< `wall_seconds` was listed in metrics
    Limits limits;
    std::vector<Figure> figures;
    Place varyPlace, fixedPlace;           ///< of the `vary:` and `fixed:` keys (0 if absent)
};

/// Parses a study file's text. @throws StudyError naming the place of the first problem: bad YAML,
/// a missing or unknown key, an unknown scene or metric, a scenario for a scene without scenarios,
/// a parameter given twice or set by the runner itself (out, quiet, no-plots, check, max-steps,
/// visualize, help), an empty list, an empty or inverted range, a count below 1, a bad number, a
/// figure over parameters that are not varied or a metric not collected.
Study parseStudy(const std::string& text, const std::string& fileName);

/// Reads and parses a study file. @throws StudyError if it cannot be read.
Study loadStudy(const std::string& path);

/// Reads a whole file. @throws StudyError "FILE: cannot read the study file: <why>".
std::string readStudyText(const std::string& path);

/// The number as text, the shortest that reads back to the same double ("0.1", "1e-06"); whole
/// numbers below 1e15 in plain digits ("3", "100000"; -0 as "0").
std::string numberText(double v);

/// `text` as a finite number (strtod syntax, all of it); false if it is not one.
bool toFiniteNumber(const std::string& text, double& value);

}  // namespace study
