#include "Cases.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace study {
namespace {

// splitmix64 (Steele, Lea & Flood 2014): a small generator with a fixed definition, so a seed
// gives the same sample with any standard library.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1): the top 53 bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    /// Uniform in 0..n-1 (rejection: no modulo bias).
    std::uint64_t below(std::uint64_t n) {
        const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
        std::uint64_t x;
        do x = next();
        while (x >= limit);
        return x % n;
    }

private:
    std::uint64_t state_;
};

void appendOption(std::vector<std::string>& args, const std::string& name, const std::string& value) {
    if (value == "false") return;
    const bool set = name.rfind("set.", 0) == 0;
    const std::string option = set ? "--set" : "--" + name;
    if (value == "true" && !set)
        args.push_back(option);
    else
        args.push_back(option + "=" + (set ? name.substr(4) + "=" : std::string()) + value);
}

}  // namespace

std::vector<std::string> parameterColumns(const Study& study) {
    std::vector<std::string> columns;
    for (const VariedParameter& v : study.vary) columns.push_back(v.name);
    if (study.sample)
        for (const SampledParameter& p : study.sample->parameters) columns.push_back(p.name);
    return columns;
}

long gridSize(const Study& study) {
    long n = 1;
    for (const VariedParameter& v : study.vary) n *= static_cast<long>(v.values.size());
    return n;
}

long sampleSize(const Study& study) { return study.sample ? study.sample->count : 1; }

long caseCount(const Study& study) { return gridSize(study) * sampleSize(study); }

std::vector<std::vector<double>> latinHypercube(long count, std::size_t dimensions, std::uint64_t seed) {
    SplitMix64 rng(seed);
    const auto n = static_cast<std::size_t>(count);
    std::vector<std::vector<double>> points(n, std::vector<double>(dimensions));
    std::vector<std::size_t> strata(n);
    for (std::size_t j = 0; j < dimensions; ++j) {
        for (std::size_t i = 0; i < n; ++i) strata[i] = i;
        for (std::size_t i = n; i > 1; --i) std::swap(strata[i - 1], strata[rng.below(i)]);  // Fisher-Yates
        for (std::size_t i = 0; i < n; ++i) {
            double u = (static_cast<double>(strata[i]) + rng.uniform()) / static_cast<double>(n);
            // Round-off must not carry a point into the next stratum.
            const double top = std::nextafter(static_cast<double>(strata[i] + 1) / static_cast<double>(n), 0.0);
            points[i][j] = std::min(u, top);
        }
    }
    return points;
}

std::vector<Case> makeCases(const Study& study) {
    const long grid = gridSize(study), samples = sampleSize(study);
    std::vector<std::vector<std::string>> sampleValues(static_cast<std::size_t>(samples));
    if (study.sample) {
        const auto& ps = study.sample->parameters;
        const auto points = latinHypercube(samples, ps.size(), study.sample->seed);
        for (std::size_t i = 0; i < points.size(); ++i)
            for (std::size_t j = 0; j < ps.size(); ++j) {
                const SampledParameter& p = ps[j];
                const double u = points[i][j];
                const double x = p.logScale ? p.from * std::pow(p.to / p.from, u) : p.from + (p.to - p.from) * u;
                sampleValues[i].push_back(numberText(x));
            }
    }
    std::vector<Case> cases;
    cases.reserve(static_cast<std::size_t>(grid * samples));
    for (long g = 0; g < grid; ++g) {
        // Grid index to one value per varied parameter, the last varying fastest.
        std::vector<std::string> gridValues(study.vary.size());
        long rest = g;
        for (std::size_t k = study.vary.size(); k-- > 0;) {
            const auto n = static_cast<long>(study.vary[k].values.size());
            gridValues[k] = study.vary[k].values[static_cast<std::size_t>(rest % n)];
            rest /= n;
        }
        for (long s = 0; s < samples; ++s) {
            Case c;
            c.id = g * samples + s;
            c.values = gridValues;
            if (study.sample)
                c.values.insert(c.values.end(), sampleValues[static_cast<std::size_t>(s)].begin(),
                                sampleValues[static_cast<std::size_t>(s)].end());
            cases.push_back(std::move(c));
        }
    }
    return cases;
}

std::vector<std::string> demoArguments(const Study& study, const Case& c, const std::string& outDir) {
    std::vector<std::string> args;
    for (const FixedParameter& f : study.fixed) appendOption(args, f.name, f.value);
    const std::vector<std::string> columns = parameterColumns(study);
    for (std::size_t k = 0; k < columns.size(); ++k) appendOption(args, columns[k], c.values[k]);
    args.push_back("--out=" + outDir);
    args.push_back("--no-plots");
    args.push_back("--quiet");
    if (study.limits.maxSteps > 0) args.push_back("--max-steps=" + std::to_string(study.limits.maxSteps));
    return args;
}

std::string describeCase(const Study& study, const Case& c) {
    const std::vector<std::string> columns = parameterColumns(study);
    std::string s;
    for (std::size_t k = 0; k < columns.size(); ++k) s += (k ? ", " : "") + columns[k] + "=" + c.values[k];
    return s.empty() ? "the only case" : s;
}

}  // namespace study
