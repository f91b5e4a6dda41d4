#include "Results.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace study {
namespace {

std::string csvField(const std::string& text) {
    bool quote = !text.empty() && (text.front() == ' ' || text.back() == ' ');
    for (char c : text) quote = quote || c == ',' || c == '"' || c == '\n' || c == '\r';
    if (!quote) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string oneLine(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\r') continue;
        if (text[i] == '\n') {
            if (i + 1 < text.size()) out += " | ";
        } else {
            out += text[i];
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> resultColumns(const Study& study) {
    std::vector<std::string> columns{"case"};
    for (const std::string& p : parameterColumns(study)) columns.push_back(p);
    for (const Metric& m : study.metrics) columns.push_back(m.path);
    columns.insert(columns.end(), {"wall_seconds", "status", "message"});
    return columns;
}

std::string csvHeader(const Study& study) {
    std::string line;
    for (const std::string& c : resultColumns(study)) line += (line.empty() ? "" : ",") + csvField(c);
    return line;
}

std::string formatRow(const ResultRow& row) {
    std::string line = std::to_string(row.id);
    for (const std::string& p : row.parameters) line += "," + csvField(p);
    for (const std::string& m : row.metrics) line += "," + csvField(m);
    line += "," + numberText(row.wallSeconds) + "," + csvField(row.status) + "," + csvField(oneLine(row.message));
    return line;
}

bool splitCsv(const std::string& line, std::vector<std::string>& fields) {
    fields.clear();
    std::string field;
    bool quoted = false, wasQuoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"') {
                if (i + 1 < line.size() && line[i + 1] == '"') {
                    field += '"';
                    ++i;
                } else {
                    quoted = false;
                }
            } else {
                field += c;
            }
        } else if (c == ',') {
            fields.push_back(field);
            field.clear();
            wasQuoted = false;
        } else if (c == '"' && field.empty() && !wasQuoted) {
            quoted = wasQuoted = true;
        } else {
            field += c;
        }
    }
    if (quoted) return false;
    fields.push_back(field);
    return true;
}

bool parseRow(const std::string& line, std::size_t parameters, std::size_t metrics, ResultRow& row, std::string& why) {
    std::vector<std::string> f;
    if (!splitCsv(line, f)) {
        why = "unbalanced quotes";
        return false;
    }
    const std::size_t expected = 1 + parameters + metrics + 3;
    if (f.size() != expected) {
        why = std::to_string(f.size()) + " fields, not " + std::to_string(expected);
        return false;
    }
    char* end = nullptr;
    errno = 0;
    row.id = std::strtol(f[0].c_str(), &end, 10);
    if (f[0].empty() || *end != '\0' || errno == ERANGE || row.id < 0) {
        why = "case id '" + f[0] + "' is not a number";
        return false;
    }
    row.parameters.assign(f.begin() + 1, f.begin() + 1 + static_cast<long>(parameters));
    row.metrics.assign(f.begin() + 1 + static_cast<long>(parameters), f.end() - 3);
    if (!toFiniteNumber(f[f.size() - 3], row.wallSeconds)) {
        why = "wall_seconds '" + f[f.size() - 3] + "' is not a number";
        return false;
    }
    row.status = f[f.size() - 2];
    row.message = f.back();
    if (row.status != "ok" && row.status != "failed" && row.status != "timeout") {
        why = "status '" + row.status + "' is not ok, failed or timeout";
        return false;
    }
    return true;
}

bool metricValue(const nlohmann::json& summary, const std::string& path, std::string& text, std::string& why) {
    const nlohmann::json* at = &summary;
    std::stringstream ss(path);
    std::string part, walked;
    while (std::getline(ss, part, '.')) {
        walked += (walked.empty() ? "" : ".") + part;
        if (at->is_object()) {
            const auto it = at->find(part);
            if (it == at->end()) {
                why = "summary.json has no '" + walked + "'";
                return false;
            }
            at = &*it;
        } else if (at->is_array()) {
            char* end = nullptr;
            const long index = std::strtol(part.c_str(), &end, 10);
            if (part.empty() || *end != '\0' || index < 0 || static_cast<std::size_t>(index) >= at->size()) {
                why = "summary.json has no '" + walked + "' (" + std::to_string(at->size()) + " items)";
                return false;
            }
            at = &(*at)[static_cast<std::size_t>(index)];
        } else {
            why = "summary.json has no '" + walked + "'";
            return false;
        }
    }
    if (at->is_number_integer()) {
        text = at->dump();
    } else if (at->is_number_float()) {
        text = numberText(at->get<double>());
    } else if (at->is_string()) {
        text = at->get<std::string>();
    } else if (at->is_boolean()) {
        text = at->get<bool>() ? "true" : "false";
    } else if (at->is_null()) {
        text.clear();
    } else {
        why = "summary.json's '" + path + "' is not a single value";
        return false;
    }
    return true;
}

std::map<long, ResultRow> readResults(const std::filesystem::path& file, const Study& study,
                                      const std::vector<Case>& cases) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw StudyError(file.string() + ": cannot read it: " + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::map<long, ResultRow> rows;
    std::size_t at = 0;
    int lineNumber = 0;
    const std::size_t parameters = parameterColumns(study).size(), metrics = study.metrics.size();
    while (at < text.size()) {
        const std::size_t eol = text.find('\n', at);
        if (eol == std::string::npos) break;  // a write cut short: the case runs again
        const std::string line = text.substr(at, eol - at);
        at = eol + 1;
        ++lineNumber;
        const std::string place = file.string() + ":" + std::to_string(lineNumber) + ": ";
        if (lineNumber == 1) {
            if (line != csvHeader(study))
                throw StudyError(place + "its columns are not this study's (" + line.substr(0, 200) +
                                 "): another study's results? Give another --out, or remove the file");
            continue;
        }
        ResultRow row;
        std::string why;
        if (!parseRow(line, parameters, metrics, row, why))
            throw StudyError(place + "not a row of this study's results: " + why);
        if (row.id >= static_cast<long>(cases.size()))
            throw StudyError(place + "case " + std::to_string(row.id) + " is not a case of this study (it has " +
                             std::to_string(cases.size()) + ")");
        if (row.parameters != cases[static_cast<std::size_t>(row.id)].values)
            throw StudyError(place + "case " + std::to_string(row.id) +
                             " has other parameter values than this study's (was the study file changed?)");
        rows.emplace(row.id, std::move(row));
    }
    if (lineNumber == 0) throw StudyError(file.string() + ": empty: not a results table");
    return rows;
}

PartialResults::PartialResults(const std::filesystem::path& file, const Study& study,
                               const std::vector<ResultRow>& existing)
    : file_(file) {
    const std::filesystem::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << csvHeader(study) << '\n';
        for (const ResultRow& r : existing) out << formatRow(r) << '\n';
        out.flush();
        if (!out) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, file);
    out_.open(file, std::ios::binary | std::ios::app);
    if (!out_) throw std::runtime_error("cannot append to " + file.string());
}

void PartialResults::append(const ResultRow& row) {
    out_ << formatRow(row) << '\n';
    out_.flush();
    if (!out_) throw std::runtime_error("cannot write to " + file_.string());
}

void writeResults(const std::filesystem::path& file, const Study& study, std::vector<ResultRow> rows) {
    std::sort(rows.begin(), rows.end(), [](const ResultRow& a, const ResultRow& b) { return a.id < b.id; });
    const std::filesystem::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << csvHeader(study) << '\n';
        for (const ResultRow& r : rows) out << formatRow(r) << '\n';
        out.flush();
        if (!out) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, file);
}

}  // namespace study
