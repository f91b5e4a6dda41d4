#pragma once
// Command-line conventions shared by the examples, on CLI11 (Debian libcli11-dev): the same help
// flag, parse rules and exit statuses in every program, and validators whose messages quote the
// offending value.
//
// Exit statuses of every example: 0 done (or --help printed); 2 bad command line (or unusable --out
// folder), with one line on stderr naming the option and a pointer to --help; 1 the simulation
// failed. The bundled demos add 3 (crane: a rope limit ended the run) and 130 (interrupted).

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace SimbodyReeving {
enum class SheaveModel;  // SimbodyReeving/simbody/ReevingSubsystem.h
}

namespace demo_common {

/// Exit status of a bad command line or an unusable --out folder.
constexpr int kUsageExitStatus = 2;

/// A bad command line: what() is one line naming the option and quoting the value, e.g.
/// "--t-end: '-1' must be > 0" or "The following argument was not expected: --bogus".
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Applies the examples' conventions to `app`: "-h,--help" prints the help text; an option given
/// twice keeps its last value (as the hand-written parsers did); option names in a 27-character
/// column.
void applyConventions(CLI::App& app);

/// Parses argv into the variables bound to `app`.
/// @returns true if -h or --help was given: unknown arguments are not reported then, but a value
///          that a validator rejects still is (CLI11 checks values before it looks at --help).
/// @throws UsageError for an unknown option, a missing value or a value a validator rejects.
bool parse(CLI::App& app, int argc, char** argv);

/// parse(), then: --help prints app.help() to stdout and returns 0; a bad command line prints
/// "<program>: <message>" and "Try '<program> --help'." to stderr and returns kUsageExitStatus;
/// otherwise returns -1 (go on).
int parseOrExitStatus(CLI::App& app, int argc, char** argv);

/// The two stderr lines of a bad command line (see parseOrExitStatus).
std::string usageErrorText(const std::string& program, const std::string& message);

/// `v` as an ostream prints it by default (6 significant digits: "0.01", "1e-06"), for messages.
std::string numberText(double v);

/// `text` as a finite real number (strtod syntax, the whole text); false if it is not one.
bool toFiniteNumber(const std::string& text, double& value);
/// `text` as a decimal integer in [-1e9, 1e9] (the whole text); false if it is not one.
bool toInteger(const std::string& text, long& value);

// Validators: they check the text before CLI11 converts it, so that "nan", "1e400" and "1,,2" are
// refused with a message naming the value (CLI11's own conversions accept the first two). Their
// help descriptions are empty: the option's text says the range.

/// A finite real number: "'abc' is not a finite number".
CLI::Validator finiteNumber();
/// A finite number > 0: "'-1' must be > 0" ("'abc' is not a finite number").
CLI::Validator positiveNumber();
/// A finite number in the open interval (lo, hi): "'2' must be in (0, 1)".
CLI::Validator numberInOpenInterval(double lo, double hi);
/// An integer in [lo, hi]: "'17' must be in 0..16" ("'two' is not an integer"). Use it with Option::transform: it
/// rewrites the text in plain decimal ("010" -> "10"; CLI11's own conversion reads "010" as octal).
CLI::Validator integerIn(long lo, long hi);
/// A comma list of integers, each in [lo, hi], no empty item: "'1,,2' must be a comma list ...".
CLI::Validator integerListIn(long lo, long hi);
/// One of `choices`: "'fast' must be one of: dynamic, quasi-static".
CLI::Validator oneOf(std::vector<std::string> choices);
/// A non-empty text: "'' must not be empty".
CLI::Validator nonEmpty();

/// The integers of a comma list that integerListIn accepted, in order, duplicates dropped.
std::vector<int> parseIntegerList(const std::string& text);

/// Adds `--sheaves MODEL`, "point" or "wrapped", setting `model` (SheaveModel::Point or Wrapped);
/// `help` says what the demo's default is and which sheaves it sets.
CLI::Option* addSheaveModelOption(CLI::App& app, SimbodyReeving::SheaveModel& model, const std::string& help);

}  // namespace demo_common
