#include "StudyFile.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace study {

std::string placed(const std::string& file, const Place& place, const std::string& message) {
    if (place.line <= 0) return file + ": " + message;
    return file + ":" + std::to_string(place.line) + ":" + std::to_string(place.column) + ": " + message;
}

std::string numberText(double v) {
    // Whole numbers in plain digits ("100000", not "1e+05": integer options read them).
    if (v == std::trunc(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}

bool toFiniteNumber(const std::string& text, double& value) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return false;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(v) || errno == ERANGE) return false;
    value = v;
    return true;
}

namespace {

Place placeOf(const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return {};
    return {m.line + 1, m.column + 1};
}

std::string where(const Place& p) { return std::to_string(p.line) + ":" + std::to_string(p.column); }

// Options the runner gives every case itself.
const std::map<std::string, std::string>& reservedOptions() {
    static const std::map<std::string, std::string> reserved = {
        {"out", "the runner gives each case its own output folder"},
        {"quiet", "the runner runs every case with --quiet"},
        {"no-plots", "the runner runs every case with --no-plots"},
        {"check", "the runner checks every case with --check before running any"},
        {"max-steps", "set it for every case with limits: {max_steps: N}"},
        {"visualize", "cases run without a display"},
        {"help", "not an option of a case"},
    };
    return reserved;
}

bool isOptionName(const std::string& name) {
    if (name.rfind("set.", 0) == 0) {
        const std::string key = name.substr(4);
        if (key.empty()) return false;
        for (char c : key)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
        return true;
    }
    if (name.empty() || !(std::islower(static_cast<unsigned char>(name[0])) || std::isdigit(static_cast<unsigned char>(name[0]))))
        return false;
    for (char c : name)
        if (!std::islower(static_cast<unsigned char>(c)) && !std::isdigit(static_cast<unsigned char>(c)) && c != '-')
            return false;
    return true;
}

bool isMetricPath(const std::string& path) {
    if (path.empty() || path.front() == '.' || path.back() == '.' || path.find("..") != std::string::npos) return false;
    for (char c : path)
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == '"') return false;
    return true;
}

std::string safeName(const std::string& s) {
    std::string out;
    for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out;
}

// A range's value without the round-off of its arithmetic: 15 significant digits when they read
// back within 1e-14 relative (0.30000000000000004 -> 0.3, 19.999999999999996 -> 20).
double roundOff(double x) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.15g", x);
    const double y = std::strtod(buffer, nullptr);
    return std::abs(y - x) <= 1e-14 * std::abs(x) ? y : x;
}

class Parser {
public:
    explicit Parser(std::string file) : file_(std::move(file)) {}

    Study parse(const std::string& text) {
        YAML::Node root;
        try {
            root = YAML::Load(text);
        } catch (const YAML::ParserException& e) {
            const Place p = e.mark.is_null() ? Place{} : Place{e.mark.line + 1, e.mark.column + 1};
            fail(p, "malformed YAML: " + e.msg);
        }
        study_.file = file_;
        if (!root.IsDefined() || root.IsNull()) fail(Place{}, "the study file is empty (it needs scene: and metrics:)");
        if (!root.IsMap()) fail(placeOf(root), "a study file is a map of keys (scene, fixed, vary, metrics, ...)");
        static const std::vector<std::string> known = {"scene",  "scenario", "description", "fixed",  "vary",
                                                       "sample", "metrics",  "limits",      "figures"};
        std::map<std::string, std::pair<YAML::Node, YAML::Node>> entries;  // key -> (key node, value)
        for (auto it = root.begin(); it != root.end(); ++it) {
            const std::string key = scalarKey(it->first);
            if (std::find(known.begin(), known.end(), key) == known.end())
                fail(it->first, "unknown key '" + key + "' (a study file has: " + join(known) + ")");
            if (entries.count(key))
                fail(it->first, "'" + key + "' is given twice (also at " + where(placeOf(entries[key].first)) + ")");
            entries[key] = {it->first, it->second};
        }
        auto has = [&](const char* key) { return entries.count(key) > 0; };
        if (!has("scene")) fail(Place{1, 1}, "no scene: (one of " + sceneNames() + ")");
        parseScene(entries["scene"].second);
        if (has("description")) study_.description = scalar(entries["description"].second, "description");
        if (has("scenario")) {
            const YAML::Node& n = entries["scenario"].second;
            addFixed("scenario", entries["scenario"].first, scalar(n, "scenario"), placeOf(n));
        }
        if (has("fixed")) {
            study_.fixedPlace = placeOf(entries["fixed"].first);
            parseFixed(entries["fixed"].second);
        }
        if (has("vary")) {
            study_.varyPlace = placeOf(entries["vary"].first);
            parseVary(entries["vary"].second);
        }
        if (has("sample")) parseSample(entries["sample"].first, entries["sample"].second);
        if (!has("metrics"))
            fail(Place{1, 1}, "no metrics: (a list of summary.json paths to collect, e.g. [steps])");
        parseMetrics(entries["metrics"].first, entries["metrics"].second);
        if (has("limits")) parseLimits(entries["limits"].second);
        if (has("figures")) parseFigures(entries["figures"].second);
        checkSingleValueOptions();
        checkCaseCount();
        return study_;
    }

private:
    [[noreturn]] void fail(const Place& p, const std::string& message) const {
        throw StudyError(placed(file_, p, message));
    }
    [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const { fail(placeOf(n), message); }

    static std::string join(const std::vector<std::string>& items) {
        std::string s;
        for (const std::string& i : items) s += (s.empty() ? "" : ", ") + i;
        return s;
    }

    std::string scalarKey(const YAML::Node& key) const {
        if (!key.IsScalar()) fail(key, "a key must be a plain name");
        return key.Scalar();
    }

    std::string scalar(const YAML::Node& n, const std::string& what) const {
        if (!n.IsDefined() || n.IsNull()) fail(n, what + " has no value");
        if (!n.IsScalar()) fail(n, what + " must be one value, not a list or a map");
        return n.Scalar();
    }

    double number(const YAML::Node& n, const std::string& what) const {
        const std::string text = scalar(n, what);
        double v = 0;
        if (!toFiniteNumber(text, v)) fail(n, what + ": '" + text + "' is not a finite number");
        return v;
    }

    long integer(const YAML::Node& n, const std::string& what, long lo, long hi) const {
        const std::string text = scalar(n, what);
        char* end = nullptr;
        errno = 0;
        const long v = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
            fail(n, what + ": '" + text + "' is not an integer");
        if (v < lo || v > hi) fail(n, what + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", not " + text);
        return v;
    }

    // The entries of a map node, each key once, checked against `known` if given.
    std::vector<std::pair<YAML::Node, YAML::Node>> mapEntries(const YAML::Node& n, const std::string& what,
                                                              const std::vector<std::string>& known = {}) const {
        if (!n.IsMap()) fail(n, what + " must be a map (key: value, ...)");
        std::vector<std::pair<YAML::Node, YAML::Node>> out;
        std::map<std::string, Place> seen;
        for (auto it = n.begin(); it != n.end(); ++it) {
            const std::string key = scalarKey(it->first);
            if (!known.empty() && std::find(known.begin(), known.end(), key) == known.end())
                fail(it->first, what + ": unknown key '" + key + "' (known: " + join(known) + ")");
            if (seen.count(key)) fail(it->first, what + ": '" + key + "' is given twice (also at " + where(seen[key]) + ")");
            seen[key] = placeOf(it->first);
            out.emplace_back(it->first, it->second);
        }
        return out;
    }

    YAML::Node required(const std::vector<std::pair<YAML::Node, YAML::Node>>& entries, const YAML::Node& parent,
                        const std::string& key, const std::string& what) const {
        for (const auto& [k, v] : entries)
            if (k.Scalar() == key) return v;
        fail(parent, what + " needs '" + key + "'");
    }
    static const YAML::Node* optional(const std::vector<std::pair<YAML::Node, YAML::Node>>& entries,
                                      const std::string& key) {
        for (const auto& e : entries)
            if (e.first.Scalar() == key) return &e.second;
        return nullptr;
    }

    void parseScene(const YAML::Node& n) {
        const std::string name = scalar(n, "scene");
        study_.scene = findScene(name);
        study_.scenePlace = placeOf(n);
        if (!study_.scene) fail(n, "unknown scene '" + name + "' (one of " + sceneNames() + ")");
    }

    // A parameter's name: a demo option, not the runner's, not given before.
    void checkParameterName(const YAML::Node& key, const std::string& name) {
        if (!isOptionName(name))
            fail(key, "'" + name +
                          "' is not a demo option's name (a long option without its dashes, such as t-end, or "
                          "set.KEY for --set KEY=...)");
        const auto reserved = reservedOptions().find(name);
        if (reserved != reservedOptions().end()) fail(key, "'" + name + "' is not a study parameter: " + reserved->second);
        if (name == "scenario" && !study_.scene->hasScenarios)
            fail(key, "scene " + study_.scene->name + " has no scenarios (its demo has no --scenario)");
        const auto before = names_.find(name);
        if (before != names_.end())
            fail(key, "parameter '" + name + "' is given twice (also at " + where(before->second) + ")");
        names_[name] = placeOf(key);
    }

    void addFixed(const std::string& name, const YAML::Node& key, const std::string& value, Place valuePlace) {
        checkParameterName(key, name);
        study_.fixed.push_back({name, value, valuePlace, placeOf(key)});
    }

    void parseFixed(const YAML::Node& n) {
        if (n.IsNull()) return;
        for (const auto& [key, value] : mapEntries(n, "fixed")) {
            const std::string name = key.Scalar();
            if (value.IsSequence() || value.IsMap())
                fail(value, "fixed '" + name + "' must be one value (vary: takes a list or a range)");
            addFixed(name, key, scalar(value, "fixed '" + name + "'"), placeOf(value));
        }
    }

    void parseVary(const YAML::Node& n) {
        if (n.IsNull()) return;
        for (const auto& [key, spec] : mapEntries(n, "vary")) {
            const std::string name = key.Scalar();
            checkParameterName(key, name);
            VariedParameter v;
            v.name = name;
            v.place = placeOf(key);
            const std::string what = "vary '" + name + "'";
            if (spec.IsSequence()) {
                listValues(spec, what, v);
            } else if (spec.IsMap()) {
                const auto entries = mapEntries(spec, what, {"values", "linear", "log"});
                if (entries.size() != 1)
                    fail(spec, what + " takes one of values: [...], linear: {from, to, count}, log: {from, to, count}");
                const std::string kind = entries[0].first.Scalar();
                const YAML::Node& body = entries[0].second;
                if (kind == "values") {
                    if (!body.IsSequence()) fail(body, what + ": values must be a list, such as [0.1, 0.2]");
                    listValues(body, what, v);
                } else {
                    rangeValues(body, what + " " + kind, kind == "log", v);
                }
            } else {
                fail(spec, what +
                               " needs several values: a list [a, b], {values: [...]}, {linear: {from, to, count}} or "
                               "{log: {from, to, count}} (one value goes under fixed:)");
            }
            study_.vary.push_back(std::move(v));
        }
    }

    void listValues(const YAML::Node& list, const std::string& what, VariedParameter& v) const {
        if (list.size() == 0) fail(list, what + ": the list of values is empty");
        std::map<std::string, Place> seen;
        for (const YAML::Node& item : list) {
            const std::string value = scalar(item, what + " value");
            if (seen.count(value))
                fail(item, what + ": value '" + value + "' is listed twice (also at " + where(seen[value]) + ")");
            seen[value] = placeOf(item);
            v.values.push_back(value);
            v.valuePlaces.push_back(placeOf(item));
        }
    }

    void rangeValues(const YAML::Node& body, const std::string& what, bool logScale, VariedParameter& v) const {
        const auto entries = mapEntries(body, what, {"from", "to", "count"});
        const double from = number(required(entries, body, "from", what), what + " from");
        const double to = number(required(entries, body, "to", what), what + " to");
        const YAML::Node countNode = required(entries, body, "count", what);
        const long count = integer(countNode, what + " count", 1, 1000000);
        checkRange(body, what, from, to, logScale);
        for (long i = 0; i < count; ++i) {
            double x = from;
            if (count > 1) {
                const double t = static_cast<double>(i) / static_cast<double>(count - 1);
                x = i == count - 1 ? to : logScale ? from * std::pow(to / from, t) : from + (to - from) * t;
            }
            v.values.push_back(numberText(roundOff(x)));
            v.valuePlaces.push_back(placeOf(body));
        }
    }

    void checkRange(const YAML::Node& at, const std::string& what, double from, double to, bool logScale) const {
        if (from > to)
            fail(at, what + ": inverted range: from (" + numberText(from) + ") must be below to (" + numberText(to) + ")");
        if (from == to) fail(at, what + ": empty range: from and to are both " + numberText(from));
        if (logScale && from <= 0)
            fail(at, what + ": a log range needs from > 0 (got " + numberText(from) + ")");
    }

    void parseSample(const YAML::Node& key, const YAML::Node& n) {
        const std::string what = "sample";
        const auto entries = mapEntries(n, what, {"method", "count", "seed", "parameters"});
        Sample s;
        s.place = placeOf(key);
        const YAML::Node method = required(entries, n, "method", what);
        if (scalar(method, "sample method") != "latin-hypercube")
            fail(method, "unknown sample method '" + method.Scalar() + "' (latin-hypercube)");
        s.count = integer(required(entries, n, "count", what), "sample count", 1, 1000000);
        if (const YAML::Node* seed = optional(entries, "seed"))
            s.seed = static_cast<std::uint64_t>(integer(*seed, "sample seed", 0, 2147483647L));
        const YAML::Node parameters = required(entries, n, "parameters", what);
        if (parameters.IsMap() && parameters.size() == 0) fail(parameters, "sample parameters: the map is empty");
        for (const auto& [pkey, spec] : mapEntries(parameters, "sample parameters")) {
            const std::string name = pkey.Scalar();
            checkParameterName(pkey, name);
            const std::string pwhat = "sample '" + name + "'";
            const auto p = mapEntries(spec, pwhat, {"from", "to", "scale"});
            SampledParameter sp;
            sp.name = name;
            sp.place = placeOf(pkey);
            sp.from = number(required(p, spec, "from", pwhat), pwhat + " from");
            sp.to = number(required(p, spec, "to", pwhat), pwhat + " to");
            if (const YAML::Node* scale = optional(p, "scale")) {
                const std::string text = scalar(*scale, pwhat + " scale");
                if (text != "linear" && text != "log") fail(*scale, pwhat + ": scale must be linear or log, not '" + text + "'");
                sp.logScale = text == "log";
            }
            checkRange(spec, pwhat, sp.from, sp.to, sp.logScale);
            s.parameters.push_back(sp);
        }
        study_.sample = s;
    }

    void parseMetrics(const YAML::Node& key, const YAML::Node& n) {
        if (!n.IsSequence()) fail(n.IsNull() ? key : n, "metrics must be a list of summary.json paths, such as [steps]");
        if (n.size() == 0) fail(n, "metrics: the list is empty");
        std::map<std::string, Place> seen;
        for (const YAML::Node& item : n) {
            const std::string path = scalar(item, "a metric");
            if (seen.count(path)) fail(item, "metric '" + path + "' is listed twice (also at " + where(seen[path]) + ")");
            seen[path] = placeOf(item);
            if (path == "wall_seconds") {
                study_.wallSecondsListed = true;
                continue;
            }
            if (!isMetricPath(path) || !isKnownMetric(*study_.scene, path)) fail(item, unknownMetric(path));
            study_.metrics.push_back({path, placeOf(item)});
        }
    }

    std::string unknownMetric(const std::string& path) const {
        const SceneInfo& scene = *study_.scene;
        std::string message = "unknown metric '" + path + "' for scene " + scene.name;
        const std::string last = path.substr(path.rfind('.') == std::string::npos ? 0 : path.rfind('.') + 1);
        std::string hint;
        for (const std::string& pattern : scene.metricPatterns) {
            const auto dot = pattern.rfind('.');
            if (pattern.substr(dot == std::string::npos ? 0 : dot + 1) == last && pattern != path) {
                std::string example = pattern;
                for (size_t at; (at = example.find('#')) != std::string::npos;) example.replace(at, 1, "0");
                hint = example;
                break;
            }
        }
        if (!hint.empty()) return message + " (did you mean " + hint + "?)";
        std::string known;
        bool index = false, key = false;  // whether the list has # (an array index) and * (any key)
        for (const std::string& pattern : scene.metricPatterns) {
            known += (known.empty() ? "" : ", ") + pattern;
            std::stringstream parts(pattern);
            for (std::string part; std::getline(parts, part, '.');) {
                index |= part == "#";
                key |= part == "*";
            }
        }
        const std::string legend = index && key ? ", where # is an index and * a key"
                                   : index      ? ", where # is an index"
                                   : key        ? ", where * is a key"
                                                : "";
        return message + " (" + scene.program + "'s summary.json has " + known + legend +
               "; the runner adds wall_seconds)";
    }

    void parseLimits(const YAML::Node& n) {
        for (const auto& [key, value] : mapEntries(n, "limits", {"wall_seconds", "max_steps"})) {
            if (key.Scalar() == "wall_seconds") {
                const double w = number(value, "limits wall_seconds");
                if (w <= 0) fail(value, "limits wall_seconds must be > 0 [s], not " + value.Scalar());
                study_.limits.wallSeconds = w;
            } else {
                study_.limits.maxSteps = integer(value, "limits max_steps", 1, 1000000000L);
            }
        }
    }

    const VariedParameter* varied(const std::string& name) const {
        for (const VariedParameter& v : study_.vary)
            if (v.name == name) return &v;
        return nullptr;
    }
    bool sampled(const std::string& name) const {
        if (!study_.sample) return false;
        for (const SampledParameter& p : study_.sample->parameters)
            if (p.name == name) return true;
        return false;
    }
    bool collected(const std::string& metric) const {
        if (metric == "wall_seconds") return true;
        for (const Metric& m : study_.metrics)
            if (m.path == metric) return true;
        return false;
    }

    void figureAxis(const YAML::Node& node, const std::string& role, bool gridOnly) const {
        const std::string name = node.Scalar();
        const VariedParameter* v = varied(name);
        if (!v && !(sampled(name) && !gridOnly))
            fail(node, "figure " + role + " '" + name + "' is not a " + (gridOnly ? "varied" : "varied or sampled") +
                           " parameter of the study");
        if (v) {
            for (size_t i = 0; i < v->values.size(); ++i) {
                double x;
                if (!toFiniteNumber(v->values[i], x))
                    fail(node, "figure " + role + " '" + name + "': its value '" + v->values[i] + "' is not a number");
            }
        }
    }

    void parseFigures(const YAML::Node& n) {
        if (!n.IsSequence()) fail(n, "figures must be a list of {type: lines, x: PARAMETER, y: METRIC} or "
                                     "{type: heatmap, x: PARAMETER, y: PARAMETER, z: METRIC, boundary: NUMBER or {metric: METRIC, "
                                     "equals: VALUE}}");
        std::map<std::string, Place> names;
        for (const YAML::Node& item : n) {
            const auto entries = mapEntries(item, "a figure", {"type", "x", "y", "z", "boundary", "name"});
            Figure f;
            f.place = placeOf(item);
            const YAML::Node type = required(entries, item, "type", "a figure");
            const std::string t = scalar(type, "figure type");
            if (t != "lines" && t != "heatmap") fail(type, "figure type must be lines or heatmap, not '" + t + "'");
            f.type = t == "lines" ? Figure::Type::Lines : Figure::Type::Heatmap;
            const YAML::Node x = required(entries, item, "x", "a " + t + " figure");
            const YAML::Node y = required(entries, item, "y", "a " + t + " figure");
            f.x = scalar(x, "figure x");
            f.y = scalar(y, "figure y");
            if (f.type == Figure::Type::Lines) {
                if (optional(entries, "z")) fail(*optional(entries, "z"), "a lines figure has no z (y is its metric)");
                if (optional(entries, "boundary"))
                    fail(*optional(entries, "boundary"), "a lines figure has no boundary (heat maps have)");
                figureAxis(x, "x", false);
                if (!collected(f.y)) fail(y, "figure y '" + f.y + "' is not one of the study's metrics");
                f.name = safeName(f.y + "_over_" + f.x);
            } else {
                const YAML::Node z = required(entries, item, "z", "a heatmap figure");
                f.z = scalar(z, "figure z");
                figureAxis(x, "x", true);
                figureAxis(y, "y", true);
                if (f.x == f.y) fail(y, "figure x and y are both '" + f.x + "'");
                if (!collected(f.z)) fail(z, "figure z '" + f.z + "' is not one of the study's metrics");
                if (const YAML::Node* b = optional(entries, "boundary")) {
                    if (b->IsMap()) {
                        const auto be = mapEntries(*b, "figure boundary", {"metric", "equals"});
                        const YAML::Node metric = required(be, *b, "metric", "figure boundary");
                        f.boundaryMetric = scalar(metric, "figure boundary metric");
                        f.boundaryValue = scalar(required(be, *b, "equals", "figure boundary"), "figure boundary equals");
                        if (!collected(f.boundaryMetric))
                            fail(metric, "figure boundary metric '" + f.boundaryMetric + "' is not one of the study's metrics");
                    } else {
                        f.boundary = number(*b, "figure boundary");
                    }
                }
                long panels = study_.sample ? study_.sample->count : 1;
                for (const VariedParameter& v : study_.vary)
                    if (v.name != f.x && v.name != f.y) panels *= static_cast<long>(v.values.size());
                if (panels > 24)
                    fail(item, "the heat map would have " + std::to_string(panels) +
                                   " panels (one per combination of the other varied parameters and samples); at most 24");
                f.name = safeName(f.z + "_over_" + f.x + "_and_" + f.y);
            }
            if (const YAML::Node* name = optional(entries, "name")) {
                f.name = scalar(*name, "figure name");
                if (f.name.empty() || safeName(f.name) != f.name)
                    fail(*name, "figure name '" + f.name + "' may only have letters, digits, - and _");
            }
            if (names.count(f.name))
                fail(item, "two figures are named '" + f.name + "' (the other at " + where(names[f.name]) +
                               "): give one a name:");
            names[f.name] = f.place;
            study_.figures.push_back(f);
        }
    }

    void checkSingleValueOptions() const {
        for (const std::string& option : study_.scene->singleValueOptions) {
            bool given = false;
            for (const FixedParameter& f : study_.fixed)
                if (f.name == option) {
                    given = true;
                    if (f.value.find(',') != std::string::npos)
                        fail(f.place, option + " '" + f.value + "': one value per case (vary: lists several)");
                }
            if (const VariedParameter* v = varied(option)) {
                given = true;
                for (size_t i = 0; i < v->values.size(); ++i)
                    if (v->values[i].find(',') != std::string::npos)
                        fail(v->valuePlaces[i], option + " '" + v->values[i] + "': one value per case");
            }
            given = given || sampled(option);
            if (!given)
                fail(study_.scenePlace, "scene " + study_.scene->name + " needs " + option +
                                            " (fixed: or vary:): each case runs one value (" +
                                            study_.scene->program + "'s default runs several, one summary each)");
        }
    }

    void checkCaseCount() const {
        double count = study_.sample ? static_cast<double>(study_.sample->count) : 1.0;
        for (const VariedParameter& v : study_.vary) count *= static_cast<double>(v.values.size());
        if (count > 1e6)
            fail(study_.varyPlace.line ? study_.varyPlace : study_.sample->place,
                 "the study has " + std::to_string(static_cast<long long>(count)) + " cases; at most 1 000 000");
    }

    std::string file_;
    Study study_;
    std::map<std::string, Place> names_;  // parameters given so far, with the places of their names
};

}  // namespace

Study parseStudy(const std::string& text, const std::string& fileName) { return Parser(fileName).parse(text); }

std::string readStudyText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw StudyError(path + ": cannot read the study file: " + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw StudyError(path + ": cannot read the study file");
    return ss.str();
}

Study loadStudy(const std::string& path) { return parseStudy(readStudyText(path), path); }

}  // namespace study
