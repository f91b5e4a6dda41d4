#include "Cli.h"

#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <utility>

namespace demo_common {
namespace {

std::string inQuotes(const std::string& text) { return "'" + text + "'"; }

}  // namespace

std::string numberText(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

void applyConventions(CLI::App& app) {
    app.set_help_flag("-h,--help", "this text");
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.get_formatter()->column_width(27);
}

bool parse(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        return true;
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    return false;
}

std::string usageErrorText(const std::string& program, const std::string& message) {
    return program + ": " + message + "\nTry '" + program + " --help'.\n";
}

int parseOrExitStatus(CLI::App& app, int argc, char** argv) {
    try {
        if (parse(app, argc, argv)) {
            std::cout << app.help();
            return 0;
        }
    } catch (const UsageError& e) {
        std::cerr << usageErrorText(app.get_name(), e.what());
        return kUsageExitStatus;
    }
    return -1;
}

bool toFiniteNumber(const std::string& text, double& value) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(v) || errno == ERANGE) return false;
    value = v;
    return true;
}

bool toInteger(const std::string& text, long& value) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || errno == ERANGE || v < -1000000000L || v > 1000000000L) return false;
    value = v;
    return true;
}

CLI::Validator finiteNumber() {
    return CLI::Validator(
        [](std::string& text) {
            double v;
            return toFiniteNumber(text, v) ? std::string() : inQuotes(text) + " is not a finite number";
        },
        "", "finite number");
}

CLI::Validator positiveNumber() {
    return CLI::Validator(
        [](std::string& text) {
            double v;
            if (!toFiniteNumber(text, v)) return inQuotes(text) + " is not a finite number";
            return v > 0 ? std::string() : inQuotes(text) + " must be > 0";
        },
        "", "positive number");
}

CLI::Validator numberInOpenInterval(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            double v;
            if (!toFiniteNumber(text, v)) return inQuotes(text) + " is not a finite number";
            return v > lo && v < hi ? std::string()
                                    : inQuotes(text) + " must be in (" + numberText(lo) + ", " + numberText(hi) + ")";
        },
        "", "number in an open interval");
}

CLI::Validator integerIn(long lo, long hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            long v;
            if (!toInteger(text, v)) return inQuotes(text) + " is not an integer";
            if (v < lo || v > hi)
                return inQuotes(text) + " must be in " + std::to_string(lo) + ".." + std::to_string(hi);
            text = std::to_string(v);  // CLI11 converts with base 0 ("010" would be 8): hand it plain decimal
            return std::string();
        },
        "", "integer in a range");
}

CLI::Validator integerListIn(long lo, long hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            const std::string why = inQuotes(text) + " must be a comma list of integers in " + std::to_string(lo) +
                                    ".." + std::to_string(hi) + ", such as 0,1,3";
            if (text.empty() || text.back() == ',') return why;
            std::stringstream ss(text);
            std::string item;
            while (std::getline(ss, item, ',')) {
                long v;
                if (!toInteger(item, v) || v < lo || v > hi) return why;
            }
            return std::string();
        },
        "", "integer list");
}

CLI::Validator oneOf(std::vector<std::string> choices) {
    return CLI::Validator(
        [choices = std::move(choices)](std::string& text) {
            for (const std::string& c : choices)
                if (text == c) return std::string();
            std::string list;
            for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
            return inQuotes(text) + " must be one of: " + list;
        },
        "", "one of");
}

CLI::Option* addSheaveModelOption(CLI::App& app, SimbodyReeving::SheaveModel& model, const std::string& help) {
    using SimbodyReeving::SheaveModel;
    return app
        .add_option_function<std::string>(
            "--sheaves", [&model](const std::string& v) { model = v == "wrapped" ? SheaveModel::Wrapped : SheaveModel::Point; },
            help)
        ->type_name("MODEL")
        ->check(oneOf({"point", "wrapped"}));
}

CLI::Validator nonEmpty() {
    return CLI::Validator(
        [](std::string& text) { return text.empty() ? inQuotes(text) + " must not be empty" : std::string(); }, "",
        "non-empty");
}

std::vector<int> parseIntegerList(const std::string& text) {
    std::vector<int> values;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        long v = 0;
        if (!toInteger(item, v)) throw UsageError(inQuotes(text) + " is not a comma list of integers");
        bool seen = false;
        for (int x : values) seen = seen || x == v;
        if (!seen) values.push_back(static_cast<int>(v));
    }
    return values;
}

}  // namespace demo_common
