#include "Report.h"

#include "ChildProcess.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace study {
namespace {

using Json = nlohmann::ordered_json;

struct Counts {
    long ok = 0, failed = 0, timeout = 0;
};

Counts count(const std::vector<ResultRow>& rows) {
    Counts c;
    for (const ResultRow& r : rows) (r.status == "ok" ? c.ok : r.status == "timeout" ? c.timeout : c.failed)++;
    return c;
}

std::string fixed(double v, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    return buffer;
}

// A value of a results column as a number; NaN if it is not one.
double asNumber(const std::string& text) {
    double v;
    return toFiniteNumber(text, v) ? v : std::numeric_limits<double>::quiet_NaN();
}

// gnuplot single-quoted string.
std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream ss(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
        if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return "";
}

// The text of a metric (or wall_seconds) in a row.
std::string metricText(const Study& study, const ResultRow& row, const std::string& metric) {
    if (metric == "wall_seconds") return numberText(row.wallSeconds);
    for (std::size_t k = 0; k < study.metrics.size(); ++k)
        if (study.metrics[k].path == metric) return row.metrics[k];
    return "";
}

// The value of a figure's metric (or wall_seconds) in a row; NaN for a case that did not succeed.
double metricOf(const Study& study, const ResultRow& row, const std::string& metric) {
    if (row.status != "ok") return std::numeric_limits<double>::quiet_NaN();
    return asNumber(metricText(study, row, metric));
}

std::size_t columnOf(const std::vector<std::string>& columns, const std::string& name) {
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

std::string dataNumber(double v) { return std::isfinite(v) ? numberText(v) : "NaN"; }

// Lines: y over x, one line per combination of the other varied parameters (points only when a
// sample scatters the other parameters).
void linesFigure(std::ostream& gp, const fs::path& dir, const Study& study, const Figure& f,
                 const std::vector<ResultRow>& rows) {
    const std::vector<std::string> columns = parameterColumns(study);
    const std::size_t kx = columnOf(columns, f.x);
    std::map<std::string, std::vector<std::pair<double, double>>> series;
    std::vector<std::string> order;
    for (const ResultRow& r : rows) {
        std::string key;
        for (std::size_t k = 0; k < study.vary.size(); ++k)
            if (k != kx) key += (key.empty() ? "" : ", ") + columns[k] + "=" + r.parameters[k];
        if (!series.count(key)) order.push_back(key);
        series[key].emplace_back(asNumber(r.parameters[kx]), metricOf(study, r, f.y));
    }
    const fs::path data = dir / (f.name + ".dat");
    std::ofstream out(data);
    for (const std::string& key : order) {
        auto& points = series[key];
        std::stable_sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        out << "# " << (key.empty() ? f.y : key) << "\n";
        for (const auto& [x, y] : points) out << dataNumber(x) << ' ' << dataNumber(y) << '\n';
        out << "\n\n";
    }
    const bool scattered = study.sample.has_value();
    gp << "set terminal pngcairo size 1200,680 noenhanced font 'DejaVu Sans,10'\n"
       << "set output " << quoted((dir / (f.name + ".png")).string()) << "\n"
       << "set title " << quoted(study.scene->program + ": " + f.y + " over " + f.x) << "\n"
       << "set xlabel " << quoted(f.x) << "\nset ylabel " << quoted(f.y) << "\n"
       << "set grid\nset key outside right top\nunset logscale\nplot ";
    for (std::size_t i = 0; i < order.size(); ++i)
        // gnuplot's eight colours, then again dashed: every series its own look.
        gp << (i ? ", \\\n     " : "") << quoted(data.string()) << " index " << i << " using 1:2 with "
           << (scattered ? "points" : "linespoints lw 2") << " lt " << i % 8 + 1 << " dt " << i / 8 + 1 << " pt "
           << (i / 8 % 4) * 2 + 7 << " title " << quoted(order[i].empty() ? f.y : order[i]);
    gp << "\n";
}

// Heat map: z over the grid of x and y (cells in the order of the values, labelled with them), one
// panel per combination of the other varied parameters (and sample point); with a boundary, the
// cell edges between the cells on its two sides drawn black (a number: the colours centred on it,
// red below, blue above).
void heatmapFigure(std::ostream& gp, const fs::path& dir, const Study& study, const Figure& f,
                   const std::vector<ResultRow>& rows) {
    const std::vector<std::string> columns = parameterColumns(study);
    const std::size_t kx = columnOf(columns, f.x), ky = columnOf(columns, f.y);
    auto sortedValues = [&](std::size_t k) {
        std::vector<std::string> v = study.vary[k].values;
        std::stable_sort(v.begin(), v.end(), [](const std::string& a, const std::string& b) {
            return asNumber(a) < asNumber(b);
        });
        return v;
    };
    const std::vector<std::string> xs = sortedValues(kx), ys = sortedValues(ky);
    const long samples = sampleSize(study);
    std::map<std::string, std::vector<double>> panels;  // panel -> z[i * ny + j]
    std::map<std::string, std::vector<int>> sides;      // panel -> side of the boundary (-1: no case)
    std::vector<std::string> order;
    const bool hasBoundary = f.boundary || !f.boundaryMetric.empty();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const ResultRow& r : rows) {
        std::string key;
        for (std::size_t k = 0; k < study.vary.size(); ++k)
            if (k != kx && k != ky) key += (key.empty() ? "" : ", ") + columns[k] + "=" + r.parameters[k];
        if (study.sample) key += (key.empty() ? "" : ", ") + std::string("sample ") + std::to_string(r.id % samples);
        if (!panels.count(key)) {
            order.push_back(key);
            panels[key].assign(xs.size() * ys.size(), std::numeric_limits<double>::quiet_NaN());
            sides[key].assign(xs.size() * ys.size(), -1);
        }
        const auto i = static_cast<std::size_t>(std::find(xs.begin(), xs.end(), r.parameters[kx]) - xs.begin());
        const auto j = static_cast<std::size_t>(std::find(ys.begin(), ys.end(), r.parameters[ky]) - ys.begin());
        const double z = metricOf(study, r, f.z);
        panels[key][i * ys.size() + j] = z;
        if (r.status == "ok" && f.boundary && std::isfinite(z)) sides[key][i * ys.size() + j] = z >= *f.boundary;
        if (r.status == "ok" && !f.boundaryMetric.empty())
            sides[key][i * ys.size() + j] = metricText(study, r, f.boundaryMetric) == f.boundaryValue;
        if (std::isfinite(z)) {
            lo = std::min(lo, z);
            hi = std::max(hi, z);
        }
    }
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    if (f.boundary) {
        const double b = *f.boundary, d = std::max({std::abs(hi - b), std::abs(lo - b), 1e-12});
        lo = b - d;
        hi = b + d;
    } else if (hi == lo) {
        hi = lo + 1;
    }
    const fs::path data = dir / (f.name + ".dat"), edges = dir / (f.name + "_boundary.dat");
    std::ofstream out(data), edge(edges);
    for (const std::string& key : order) {
        const std::vector<double>& z = panels[key];
        out << "# " << key << "\n";
        for (std::size_t i = 0; i < xs.size(); ++i)
            for (std::size_t j = 0; j < ys.size(); ++j) out << i << ' ' << j << ' ' << dataNumber(z[i * ys.size() + j]) << '\n';
        out << "\n\n";
        edge << "# " << key << "\n0 0\n\n";  // a point that draws nothing, so that every panel has a block
        if (hasBoundary) {
            const std::vector<int>& side = sides[key];
            auto crosses = [](int a, int b) { return a >= 0 && b >= 0 && a != b; };
            for (std::size_t i = 0; i < xs.size(); ++i)
                for (std::size_t j = 0; j < ys.size(); ++j) {
                    const int here = side[i * ys.size() + j];
                    const double x = static_cast<double>(i), y = static_cast<double>(j);
                    if (i + 1 < xs.size() && crosses(here, side[(i + 1) * ys.size() + j]))
                        edge << x + 0.5 << ' ' << y - 0.5 << '\n' << x + 0.5 << ' ' << y + 0.5 << "\n\n";
                    if (j + 1 < ys.size() && crosses(here, side[i * ys.size() + j + 1]))
                        edge << x - 0.5 << ' ' << y + 0.5 << '\n' << x + 0.5 << ' ' << y + 0.5 << "\n\n";
                }
        }
        edge << "\n";
    }
    const std::size_t n = order.size();
    const auto cols = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
    const std::size_t rowsOfPanels = (n + cols - 1) / cols;
    auto tics = [](const std::vector<std::string>& values) {
        std::string t = "(";
        for (std::size_t i = 0; i < values.size(); ++i) t += (i ? ", " : "") + quoted(values[i]) + " " + std::to_string(i);
        return t + ")";
    };
    const bool labels = xs.size() * ys.size() <= 150;
    gp << "set terminal pngcairo size " << 300 + 430 * cols << "," << 80 + 380 * rowsOfPanels
       << " noenhanced font 'DejaVu Sans,9'\n"
       << "set output " << quoted((dir / (f.name + ".png")).string()) << "\n"
       << "unset grid\nunset key\nset palette defined (0 '#d6604d', 0.5 '#f7f7f7', 1 '#4393c3')\n"
       << "set cbrange [" << numberText(lo) << ":" << numberText(hi) << "]\nunset cblabel\n"
       << "set xrange [-0.5:" << xs.size() - 0.5 << "]\nset yrange [-0.5:" << ys.size() - 0.5 << "]\n"
       << "set xtics " << tics(xs) << " rotate by 45 right\nset ytics " << tics(ys) << "\n"
       << "set xlabel " << quoted(f.x) << "\nset ylabel " << quoted(f.y) << "\n"
       << "set multiplot layout " << rowsOfPanels << "," << cols << " title "
       << quoted(f.z + " over " + f.x + " and " + f.y +
                 (f.boundary      ? "; black line: " + f.z + " = " + numberText(*f.boundary)
                  : hasBoundary ? "; black line: between " + f.boundaryMetric + " = " + f.boundaryValue + " and not"
                                : std::string()))
       << "\n";
    for (std::size_t p = 0; p < n; ++p) {
        gp << "set title " << quoted(order[p]) << "\n"
           << "plot " << quoted(data.string()) << " index " << p << " using 1:2:3 with image";
        if (labels)
            gp << ", \\\n     " << quoted(data.string()) << " index " << p
               << " using 1:2:($3 == $3 ? sprintf('%.3g', $3) : 'failed') with labels font ',7'";
        if (hasBoundary) gp << ", \\\n     " << quoted(edges.string()) << " index " << p << " with lines lw 3 lc 'black'";
        gp << "\n";
    }
    gp << "unset multiplot\n";
}

}  // namespace

void writeSummary(const fs::path& file, const Study& study, const std::vector<ResultRow>& rows, const RunInfo& info,
                  const std::vector<std::string>& figures, const std::string& figureNote) {
    const Counts c = count(rows);
    const std::vector<std::string> columns = parameterColumns(study);
    Json j;
    j["program"] = "reeving-study";
    j["study"] = study.file;
    if (!study.description.empty()) j["description"] = study.description;
    j["scene"] = study.scene->name;
    j["demo"] = info.demo;
    Json fixedOptions = Json::object();
    for (const FixedParameter& f : study.fixed) fixedOptions[f.name] = f.value;
    j["fixed"] = fixedOptions;
    j["parameters"] = columns;
    Json metrics = Json::array();
    for (const Metric& m : study.metrics) metrics.push_back(m.path);
    j["metrics"] = metrics;
    j["cases"] = rows.size();
    j["ok"] = c.ok;
    j["failed"] = c.failed;
    j["timeout"] = c.timeout;
    Json failures = Json::array();
    for (const ResultRow& r : rows) {
        if (r.status == "ok") continue;
        Json p = Json::object();
        for (std::size_t k = 0; k < columns.size(); ++k) p[columns[k]] = r.parameters[k];
        failures.push_back({{"case", r.id}, {"parameters", p}, {"status", r.status}, {"message", r.message}});
    }
    j["failures"] = failures;
    j["wall_seconds"] = info.wallSeconds;
    j["cases_run"] = info.casesRun;
    j["cases_resumed"] = static_cast<long>(rows.size()) - info.casesRun;
    j["case_wall_seconds"] = info.caseWallSeconds;
    j["ranks"] = info.ranks;
    j["workers"] = info.workers;
    j["speedup_estimate"] = info.wallSeconds > 0 ? info.caseWallSeconds / info.wallSeconds : 0.0;
    j["results"] = "results.csv";
    j["figures"] = figures;
    if (!figureNote.empty()) j["figures_note"] = figureNote;
    const fs::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp);
        out << j.dump(2) << '\n';
        if (!out) throw std::runtime_error("cannot write " + tmp.string());
    }
    fs::rename(tmp, file);
}

std::string summaryText(const Study& study, const std::vector<ResultRow>& rows, const RunInfo& info) {
    const Counts c = count(rows);
    std::ostringstream o;
    o << "reeving-study: " << study.file << ": " << rows.size() << " cases";
    if (info.casesRun != static_cast<long>(rows.size())) o << " (" << info.casesRun << " run now)";
    o << ": " << c.ok << " ok, " << c.failed << " failed, " << c.timeout << " timeout; wall "
      << fixed(info.wallSeconds, 1) << " s, the cases' walls " << fixed(info.caseWallSeconds, 1) << " s";
    if (info.ranks > 1)
        o << " (" << info.ranks << " ranks, " << info.workers << " running cases: speedup "
          << fixed(info.wallSeconds > 0 ? info.caseWallSeconds / info.wallSeconds : 0.0, 2) << " over one)";
    o << "\n";
    const std::vector<std::string> columns = parameterColumns(study);
    int listed = 0;
    for (const ResultRow& r : rows) {
        if (r.status == "ok") continue;
        if (++listed > 20) {
            o << "  ... and " << (c.failed + c.timeout - 20) << " more (summary.json lists them all)\n";
            break;
        }
        o << "  case " << r.id;
        std::string p;
        for (std::size_t k = 0; k < columns.size(); ++k) p += (k ? ", " : "") + columns[k] + "=" + r.parameters[k];
        if (!p.empty()) o << " (" << p << ")";
        o << " " << r.status << ": " << r.message << "\n";
    }
    return o.str();
}

std::vector<std::string> makeFigures(const fs::path& dir, const Study& study, const std::vector<ResultRow>& rows,
                                     std::string& note) {
    note.clear();
    if (study.figures.empty()) return {};
    const std::string gnuplot = findOnPath("gnuplot");
    if (gnuplot.empty()) {
        note = "gnuplot not found: figures skipped (apt-get install gnuplot-nox)";
        return {};
    }
    fs::create_directories(dir);
    // One gnuplot run per figure: a figure gnuplot cannot draw (no data, say) costs only itself.
    std::vector<std::string> names, failed;
    for (const Figure& f : study.figures) {
        const fs::path script = dir / (f.name + ".gp"), log = dir / (f.name + ".log");
        {
            std::ofstream gp(script);
            if (f.type == Figure::Type::Lines)
                linesFigure(gp, dir, study, f, rows);
            else
                heatmapFigure(gp, dir, study, f, rows);
        }
        ChildProcess child(gnuplot, {script.string()}, dir / "gnuplot.out", log);
        while (!child.poll()) sleepFor(0.01);
        std::error_code ec;
        fs::remove(dir / "gnuplot.out", ec);
        if (child.exitStatus() != 0) {
            failed.push_back(f.name + " (" + fileTail(log, 1) + ")");
            fs::remove(dir / (f.name + ".png"), ec);
            continue;
        }
        if (fs::file_size(log, ec) == 0) fs::remove(log, ec);
        names.push_back((fs::path("figures") / (f.name + ".png")).string());
    }
    if (!failed.empty()) {
        note = "gnuplot could not draw";
        for (const std::string& f : failed) note += " " + f;
        note += " (see its .gp and .log in " + dir.string() + ")";
    }
    return names;
}

}  // namespace study
