// A study's cases (study/Cases.h): the grid in file order, linear and log ranges, the Latin
// hypercube (every stratum of every parameter hit once, the same points for a seed), grid x
// sample, the demo's command line; the results table's rows (study/Results.h): CSV round trip,
// metrics read from summary.json, a results file read back for --resume.
#include "Cases.h"
#include "Results.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace study;

namespace {

Study parse(const std::string& text) { return parseStudy(text, "s.yaml"); }

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("test_study_cases_" + std::to_string(getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace

TEST(StudyCases, GridInFileOrderFirstSlowest) {
    const Study s = parse("scene: elevator\nvary:\n  car-load: [0, 1]\n  friction: {linear: {from: 0.1, to: 0.3, count: 3}}\n"
                          "metrics: [friction]\n");
    EXPECT_EQ(parameterColumns(s), (std::vector<std::string>{"car-load", "friction"}));
    const std::vector<Case> cases = makeCases(s);
    ASSERT_EQ(cases.size(), 6u);
    const std::vector<std::vector<std::string>> expected = {{"0", "0.1"}, {"0", "0.2"}, {"0", "0.3"},
                                                            {"1", "0.1"}, {"1", "0.2"}, {"1", "0.3"}};
    for (std::size_t i = 0; i < cases.size(); ++i) {
        EXPECT_EQ(cases[i].id, static_cast<long>(i));
        EXPECT_EQ(cases[i].values, expected[i]) << i;
    }
}

TEST(StudyCases, LogRangeIsGeometric) {
    const Study s = parse("scene: elevator\nvary: {accuracy: {log: {from: 1e-8, to: 1e-4, count: 5}}}\nmetrics: [friction]\n");
    const std::vector<std::string>& v = s.vary[0].values;
    ASSERT_EQ(v.size(), 5u);
    EXPECT_EQ(v.front(), "1e-08");
    EXPECT_EQ(v.back(), "1e-04");
    for (std::size_t i = 1; i < v.size(); ++i)
        EXPECT_NEAR(std::stod(v[i]) / std::stod(v[i - 1]), 10.0, 1e-12) << v[i];
}

TEST(StudyCases, NumbersReadBackExactly) {
    for (double x : {0.1, 0.30000000000000004, 1e-300, 123456.789, -2.5e-7, 3.0, 100000.0, 1e22})
        EXPECT_EQ(std::stod(numberText(x)), x) << numberText(x);
    EXPECT_EQ(numberText(100000.0), "100000");  // integer options read plain digits
    EXPECT_EQ(numberText(0.1), "0.1");
}

TEST(StudyCases, LatinHypercubeHitsEveryStratumOnce) {
    for (long n : {1L, 2L, 7L, 50L, 1000L}) {
        const auto points = latinHypercube(n, 3, 42);
        ASSERT_EQ(points.size(), static_cast<std::size_t>(n));
        for (std::size_t j = 0; j < 3; ++j) {
            std::set<long> strata;
            for (const auto& p : points) {
                ASSERT_GE(p[j], 0.0);
                ASSERT_LT(p[j], 1.0);
                strata.insert(static_cast<long>(std::floor(p[j] * static_cast<double>(n))));
            }
            EXPECT_EQ(strata.size(), static_cast<std::size_t>(n)) << "n = " << n << ", parameter " << j;
        }
    }
    // The same seed the same points; another seed other points; the parameters not in lock step.
    EXPECT_EQ(latinHypercube(20, 2, 1), latinHypercube(20, 2, 1));
    EXPECT_NE(latinHypercube(20, 2, 1), latinHypercube(20, 2, 2));
    const auto p = latinHypercube(20, 2, 1);
    int same = 0;
    for (const auto& x : p) same += std::floor(x[0] * 20) == std::floor(x[1] * 20);
    EXPECT_LT(same, 20);
}

TEST(StudyCases, SampleValuesFollowTheirScale) {
    const Study s = parse("scene: elevator\nsample:\n  method: latin-hypercube\n  count: 40\n  seed: 3\n  parameters:\n"
                          "    friction: {from: 0.1, to: 0.5}\n    accuracy: {from: 1e-8, to: 1e-4, scale: log}\n"
                          "metrics: [friction]\n");
    const std::vector<Case> cases = makeCases(s);
    ASSERT_EQ(cases.size(), 40u);
    std::set<long> linearStrata, logStrata;
    for (const Case& c : cases) {
        const double mu = std::stod(c.values[0]), tol = std::stod(c.values[1]);
        ASSERT_GE(mu, 0.1);
        ASSERT_LT(mu, 0.5);
        ASSERT_GE(tol, 1e-8 * (1 - 1e-12));
        ASSERT_LT(tol, 1e-4);
        linearStrata.insert(static_cast<long>(std::floor((mu - 0.1) / 0.4 * 40)));
        logStrata.insert(static_cast<long>(std::floor(std::log10(tol / 1e-8) / 4 * 40 + 1e-9)));
    }
    EXPECT_EQ(linearStrata.size(), 40u);
    EXPECT_EQ(logStrata.size(), 40u);  // strata equal in log
    EXPECT_EQ(makeCases(s)[17].values, cases[17].values);  // seeded: the same every time
}

TEST(StudyCases, GridTimesSample) {
    const Study s = parse("scene: elevator\nvary: {car-load: [0, 0.5, 1]}\n"
                          "sample: {method: latin-hypercube, count: 4, parameters: {friction: {from: 0.1, to: 0.3}}}\n"
                          "metrics: [friction]\n");
    EXPECT_EQ(gridSize(s), 3);
    EXPECT_EQ(sampleSize(s), 4);
    const std::vector<Case> cases = makeCases(s);
    ASSERT_EQ(cases.size(), 12u);
    EXPECT_EQ(parameterColumns(s), (std::vector<std::string>{"car-load", "friction"}));
    for (const Case& c : cases) {
        EXPECT_EQ(c.values[0], s.vary[0].values[static_cast<std::size_t>(c.id / 4)]);  // id = grid * 4 + sample
        EXPECT_EQ(c.values[1], cases[static_cast<std::size_t>(c.id % 4)].values[1]);   // the same samples at every grid point
    }
}

TEST(StudyCases, DemoCommandLine) {
    const Study s = parse("scene: elevator\nscenario: stall\nfixed: {compensation: true, visualize-not: false, "
                          "t-end: 2}\nvary: {car-load: [0.5]}\nmetrics: [friction]\nlimits: {max_steps: 500}\n");
    const std::vector<Case> cases = makeCases(s);
    EXPECT_EQ(demoArguments(s, cases[0], "/tmp/x"),
              (std::vector<std::string>{"--scenario=stall", "--compensation", "--t-end=2", "--car-load=0.5",
                                        "--out=/tmp/x", "--no-plots", "--quiet", "--max-steps=500"}));
    const Study p = parse("scene: pendulum\nfixed: {axial-modes: 0, set.M: 2000}\nvary: {vx0: [-1]}\nmetrics: [steps]\n");
    EXPECT_EQ(demoArguments(p, makeCases(p)[0], "o"),
              (std::vector<std::string>{"--axial-modes=0", "--set=M=2000", "--vx0=-1", "--out=o", "--no-plots", "--quiet"}));
    EXPECT_EQ(describeCase(p, makeCases(p)[0]), "vx0=-1");
}

TEST(StudyResults, RowsSurviveTheCsvRoundTrip) {
    ResultRow row;
    row.id = 12;
    row.parameters = {"0.1", "a,b"};
    row.metrics = {"1.0000000000000002", "held", "", "say \"hi\""};
    row.wallSeconds = 0.125;
    row.status = "failed";
    row.message = "exit status 1: first line\nsecond, with a comma";
    const std::string line = formatRow(row);
    EXPECT_EQ(line, "12,0.1,\"a,b\",1.0000000000000002,held,,\"say \"\"hi\"\"\",0.125,failed,\"exit status 1: first "
                    "line | second, with a comma\"");
    ResultRow back;
    std::string why;
    ASSERT_TRUE(parseRow(line, 2, 4, back, why)) << why;
    EXPECT_EQ(back.id, 12);
    EXPECT_EQ(back.parameters, row.parameters);
    EXPECT_EQ(back.metrics, row.metrics);
    EXPECT_EQ(back.wallSeconds, 0.125);
    EXPECT_EQ(back.message, "exit status 1: first line | second, with a comma");
    EXPECT_EQ(formatRow(back), line);
    EXPECT_FALSE(parseRow(line, 2, 3, back, why));
    EXPECT_EQ(why, "10 fields, not 9");
    EXPECT_FALSE(parseRow("3,\"open", 0, 0, back, why));
    EXPECT_EQ(why, "unbalanced quotes");
}

TEST(StudyResults, MetricValuesFromSummary) {
    const nlohmann::json j = nlohmann::json::parse(
        R"({"steps": 947, "margin": 0.999999999486, "whole": 630.0, "traction": "held", "nan": null, "ok": true,
            "table": [{"m": 1.5}, {"m": 2.5}], "obj": {"a": 1}})");
    std::string text, why;
    ASSERT_TRUE(metricValue(j, "steps", text, why));
    EXPECT_EQ(text, "947");
    ASSERT_TRUE(metricValue(j, "margin", text, why));
    EXPECT_EQ(text, "0.999999999486");
    EXPECT_EQ(std::stod(text), j["margin"].get<double>());  // the same double
    ASSERT_TRUE(metricValue(j, "whole", text, why));
    EXPECT_EQ(text, "630");
    ASSERT_TRUE(metricValue(j, "traction", text, why));
    EXPECT_EQ(text, "held");
    ASSERT_TRUE(metricValue(j, "nan", text, why));
    EXPECT_EQ(text, "");
    ASSERT_TRUE(metricValue(j, "ok", text, why));
    EXPECT_EQ(text, "true");
    ASSERT_TRUE(metricValue(j, "table.1.m", text, why));
    EXPECT_EQ(text, "2.5");
    EXPECT_FALSE(metricValue(j, "table.2.m", text, why));
    EXPECT_EQ(why, "summary.json has no 'table.2' (2 items)");
    EXPECT_FALSE(metricValue(j, "stepz", text, why));
    EXPECT_EQ(why, "summary.json has no 'stepz'");
    EXPECT_FALSE(metricValue(j, "obj", text, why));
    EXPECT_EQ(why, "summary.json's 'obj' is not a single value");
}

TEST(StudyResults, ResultsFileReadBackForResume) {
    const Study s = parse("scene: elevator\nvary: {friction: [0.1, 0.2, 0.3]}\nmetrics: [traction_table.0.steps]\n");
    const std::vector<Case> cases = makeCases(s);
    const fs::path dir = scratch("resume");
    auto row = [&](long id) {
        ResultRow r;
        r.id = id;
        r.parameters = cases[static_cast<std::size_t>(id)].values;
        r.metrics = {std::to_string(100 + id)};
        r.wallSeconds = 0.5;
        r.status = "ok";
        return r;
    };
    {
        PartialResults partial(dir / "results.csv.partial", s, {row(2)});
        partial.append(row(0));
    }
    {  // a last row cut short by a kill: not a row, the case runs again
        std::ofstream out(dir / "results.csv.partial", std::ios::app);
        out << "1,0.2,10";
    }
    const auto rows = readResults(dir / "results.csv.partial", s, cases);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows.at(0).metrics[0], "100");
    EXPECT_EQ(rows.at(2).metrics[0], "102");
    // Another study's table, or the same ids with other values: refused.
    const Study other = parse("scene: elevator\nvary: {friction: [0.1, 0.2, 0.3]}\nmetrics: [traction_table.0.traction]\n");
    EXPECT_THROW_MESSAGE(readResults(dir / "results.csv.partial", other, cases), StudyError,
                         "results.csv.partial:1: its columns are not this study's");
    const Study changed = parse("scene: elevator\nvary: {friction: [0.1, 0.25, 0.35]}\nmetrics: [traction_table.0.steps]\n");
    EXPECT_THROW_MESSAGE(readResults(dir / "results.csv.partial", changed, makeCases(changed)), StudyError,
                         "results.csv.partial:2: case 2 has other parameter values than this study's (was the study "
                         "file changed?)");
    // The final table: sorted by case id.
    writeResults(dir / "results.csv", s, {row(2), row(0), row(1)});
    std::ifstream in(dir / "results.csv");
    std::string header, a, b, c;
    std::getline(in, header);
    std::getline(in, a);
    std::getline(in, b);
    std::getline(in, c);
    EXPECT_EQ(header, "case,friction,traction_table.0.steps,wall_seconds,status,message");
    EXPECT_EQ(a, "0,0.1,100,0.5,ok,");
    EXPECT_EQ(c, "2,0.3,102,0.5,ok,");
    EXPECT_FALSE(fs::exists(dir / "results.csv.tmp"));
    fs::remove_all(dir.parent_path());
}
