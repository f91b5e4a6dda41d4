// What reeving-study needs from the demos: --check (validate and build the scenes, write nothing)
// and --max-steps (stop with exit status 1) in reeving-pendulum and reeving-elevator; the
// elevator's --car-load and --car-position; and the scene catalogue (study/SceneCatalog.cpp) in
// step with the summary.json each demo writes; the bundled rope-bending study over the crane's
// reeving.
#include "StudyTestSupport.h"

#include "SceneCatalog.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

using namespace study_test;

namespace {

const std::string kPendulum = REEVING_PENDULUM_EXE;
const std::string kElevator = REEVING_ELEVATOR_EXE;
const std::string kCrane = REEVING_CRANE_EXE;
const std::string kStudy = REEVING_STUDY_EXE;

nlohmann::json readJson(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

void leafPaths(const nlohmann::json& j, const std::string& prefix, std::vector<std::string>& out) {
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) leafPaths(it.value(), prefix + it.key() + ".", out);
    } else if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i) leafPaths(j[i], prefix + std::to_string(i) + ".", out);
    } else {
        out.push_back(prefix.substr(0, prefix.size() - 1));
    }
}

// Every scalar of the demo's summary.json files (one per scenario) is a catalogued metric, and
// every catalogued pattern matches one of them.
void expectCatalogued(const std::string& scene, const std::vector<fs::path>& summaries) {
    const study::SceneInfo* info = study::findScene(scene);
    ASSERT_NE(info, nullptr);
    std::vector<std::string> paths;
    for (const fs::path& summary : summaries) leafPaths(readJson(summary), "", paths);
    ASSERT_FALSE(paths.empty());
    std::set<std::string> matched;
    for (const std::string& path : paths) {
        EXPECT_TRUE(study::isKnownMetric(*info, path))
            << info->program << "'s summary.json has '" << path << "', not in study/SceneCatalog.cpp";
        for (const std::string& pattern : info->metricPatterns) {
            study::SceneInfo one = *info;
            one.metricPatterns = {pattern};
            if (study::isKnownMetric(one, path)) matched.insert(pattern);
        }
    }
    for (const std::string& pattern : info->metricPatterns)
        EXPECT_TRUE(matched.count(pattern)) << "study/SceneCatalog.cpp lists '" << pattern << "' for " << scene
                                            << ", which " << info->program << "'s summary.json does not have";
}

}  // namespace

TEST(StudyDemos, CheckValidatesAndWritesNothing) {
    const fs::path dir = scratch("check");
    const std::string out = " --out " + quote(dir / "out");
    ProgramRun r = run(quote(kPendulum) + " --check --axial-modes 0,3" + out, dir);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out + r.err, "");
    r = run(quote(kPendulum) + " --check --set EA=-1" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "reeving-pendulum: --set: 'EA=-1': PendulumParameters: EA = -1 must be finite and > 0\n"
                     "Try 'reeving-pendulum --help'.\n");
    r = run(quote(kPendulum) + " --check --axial-modes 0 --bogus" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("The following argument was not expected: --bogus"), std::string::npos) << r.err;
    r = run(quote(kElevator) + " --check" + out, dir);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out + r.err, "");
    // The car's position is checked per scenario: mid-shaft ranges differ in the emergency stop.
    r = run(quote(kElevator) + " --check --car-position 0" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "reeving-elevator: ElevatorParameters: carPosition [m] = 0 must be in [2, hoistway - 2] in the "
                     "emergency-stop scenario (car and counterweight 2 m or more below the sheave) (scenario "
                     "emergency-stop)\nTry 'reeving-elevator --help'.\n");
    r = run(quote(kElevator) + " --check --scenario loading --car-position 0" + out, dir);
    EXPECT_EQ(r.status, 0) << r.err;
    r = run(quote(kElevator) + " --check --scenario trip --car-position 20" + out, dir);
    EXPECT_EQ(r.status, 0) << r.err;
    r = run(quote(kElevator) + " --check --scenario trip --car-position 25" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("carPosition + tripDistance [m] = 37 must be < hoistway - 4 in the trip scenario"),
              std::string::npos)
        << r.err;
    r = run(quote(kElevator) + " --check --car-load 1.3 --scenario stall" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("ElevatorParameters: carLoad [-] = 1.3 must be in [0, 1.25] (of the rated load)"),
              std::string::npos)
        << r.err;
    r = run(quote(kElevator) + " --check --integrator euler" + out, dir);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("--integrator: 'euler' must be one of: rk-merson"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

// --max-steps N: the run stops with exit status 1 and a message once the integrator has taken N
// steps, writing nothing; a limit the run stays under changes none of its numbers.
TEST(StudyDemos, MaxStepsStopsTheRun) {
    const fs::path dir = scratch("steps");
    ProgramRun r = run(quote(kPendulum) + " --axial-modes 0 --t-end 1 --max-steps 20 --no-plots --quiet --out " +
                           quote(dir / "p"),
                       dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("reeving-pendulum: stopped: n_a = 0: the integrator took --max-steps 20 steps at t = "),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "p" / "summary.json"));
    r = run(quote(kElevator) + " --scenario stall --t-end 1 --max-steps 7 --no-plots --quiet --out " + quote(dir / "e"), dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("reeving-elevator: stopped: stall: the integrator took --max-steps 7 steps at t = "),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "e" / "summary.json"));
    // Under the limit: the same steps and numbers as without it.
    for (const std::string& limit : {std::string(), std::string(" --max-steps 100000")}) {
        r = run(quote(kElevator) + " --scenario stall --t-end 1 --no-plots --quiet --out " +
                    quote(dir / ("free" + std::to_string(limit.size()))) + limit,
                dir);
        ASSERT_EQ(r.status, 0) << r.err;
    }
    nlohmann::json a = readJson(dir / "free0" / "summary.json"), b = readJson(dir / "free19" / "summary.json");
    for (nlohmann::json* j : {&a, &b})
        for (const char* wall : {"wall_s", "real_time_factor"}) (*j)["traction_table"][0].erase(wall);
    EXPECT_EQ(a, b);
    EXPECT_GT(a["traction_table"][0]["steps"].get<long>(), 7);
}

// --car-load and --car-position: the car's mass and its start in the shaft, the counterweight as
// high above its own start as the car is (one rope). At the start, at rest, the car-side fall
// carries the car and the rope below the sheave: P = (m_car + f m_rated) g + rhoA g (H - z), within
// 1 % (one axial mode's end force: measured 0.13 % to 0.56 % low).
TEST(StudyDemos, ElevatorCarLoadAndPosition) {
    const fs::path dir = scratch("car");
    const double g = 9.81, carMass = 1000, rated = 630, rhoA = 1.4, hoistway = 40;
    for (const auto& [f, z] : {std::pair<double, double>{0.0, 10.0}, {0.5, 30.0}, {1.25, 0.0}}) {
        const fs::path out = dir / ("f" + std::to_string(f) + "z" + std::to_string(z));
        const ProgramRun r = run(quote(kElevator) + " --scenario loading --t-end 0.05 --car-load " + std::to_string(f) +
                                     " --car-position " + std::to_string(z) + " --no-plots --quiet --out " + quote(out),
                                 dir);
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
        EXPECT_EQ(t.at("car_load").get<double>(), f);
        EXPECT_EQ(t.at("car_position_m").get<double>(), z);
        const auto rows = csvRows(out / "timeseries_loading.csv");
        ASSERT_GT(rows.size(), 2u);
        const auto& h = rows[0];
        auto value = [&](const std::string& column) {
            return std::stod(rows[1][static_cast<std::size_t>(std::find(h.begin(), h.end(), column) - h.begin())]);
        };
        EXPECT_NEAR(value("car_y_m"), -hoistway + z, 0.05);
        EXPECT_NEAR(value("counterweight_y_m"), -2.0 - z, 0.05);
        const double expected = (carMass + f * rated) * g + rhoA * g * (hoistway - z);
        EXPECT_NEAR(value("car_side_force_N") / expected, 1.0, 1e-2) << "f = " << f << ", z = " << z;
    }
    // Without them, each scenario's own load and position.
    const ProgramRun r = run(quote(kElevator) + " --t-end 0.02 --no-plots --quiet --out " + quote(dir / "own"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json table = readJson(dir / "own" / "summary.json").at("traction_table");
    const std::vector<double> load = {1, 1.25, 1, 0}, position = {0, 0, 20, 0};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(table[i].at("car_load").get<double>(), load[i]) << table[i].at("scenario");
        EXPECT_EQ(table[i].at("car_position_m").get<double>(), position[i]) << table[i].at("scenario");
    }
}

// The scene catalogue lists exactly the scalars of each demo's summary.json.
TEST(StudyDemos, SceneCatalogueMatchesTheDemosSummaries) {
    const fs::path dir = scratch("catalogue");
    ProgramRun r = run(quote(kPendulum) + " --axial-modes 1 --t-end 0.05 --no-plots --quiet --out " + quote(dir / "p"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    expectCatalogued("pendulum", {dir / "p" / "summary.json"});
    // The trip for 3 s: the rope has moved over the traction sheave (rope_life's worst section).
    r = run(quote(kElevator) + " --scenario trip --t-end 3 --no-plots --quiet --out " + quote(dir / "e"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    expectCatalogued("elevator", {dir / "e" / "summary.json"});
    r = run(quote(kCrane) + " --t-end 0.1 --no-plots --quiet --out " + quote(dir / "c"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    r = run(quote(kCrane) + " --scenario lift-off --no-plots --quiet --out " + quote(dir / "l"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    expectCatalogued("crane", {dir / "c" / "summary.json", dir / "l" / "summary.json"});
}

// studies/crane-rope-bending: the crane's default cycle over its reeving, falls x sheave radius,
// mapping the most bent section's cycles. Hand counts (docs/rope-life.md's counting rules):
// - 2 falls (drum -> hook sheave -> dead end on the trolley): the lift hauls 2 x 5 m, the hook
//   sheave's arrival point moves 5 m, and the rope from there to the drum, a fall of about 11 m, is
//   longer, so no section reaches the drum after the sheave: the sections the sheave passes run over
//   it on the lift and back on the lowering, 2 simple cycles, the most of any;
// - 4 falls: 2 simple + 2 reverse (tests/demos/test_crane_demo.cpp's RopeBendingCountsEachSection
//   derives it), 4 with the reverse bends weighted 1;
// and at every sheave radius R the section runs over the sheaves, D/d = 2 R / 0.02 m.
TEST(StudyDemos, CraneRopeBendingStudyMapsTheWorstSection) {
    const fs::path dir = scratch("rope_bending_study");
    const ProgramRun r = run(kStudy + " " + quote(fs::path(STUDIES_DIR) / "crane-rope-bending") + " --out " +
                                 quote(dir / "out") + " --quiet",
                             dir);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto rows = csvRows(dir / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 1u + 15u);
    const auto& h = rows[0];
    auto col = [&](const std::string& name) {
        const auto it = std::find(h.begin(), h.end(), name);
        EXPECT_NE(it, h.end()) << name;
        return static_cast<std::size_t>(it - h.begin());
    };
    const std::size_t falls = col("falls"), radius = col("set.sheaveRadius"), cycles = col("rope_life.worst_section.cycles"),
                      simple = col("rope_life.worst_section.simple_cycles"),
                      reverse = col("rope_life.worst_section.reverse_cycles"),
                      ratio = col("rope_life.worst_section.min_diameter_ratio");
    int checked = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto& v = rows[i];
        const int n = std::stoi(v[falls]);
        const double R = std::stod(v[radius]);
        EXPECT_NEAR(std::stod(v[ratio]), 2 * R / 0.02, 1e-9) << "falls " << n << ", R " << R;
        if (n == 2 || n == 4) {
            ++checked;
            EXPECT_EQ(std::stod(v[simple]), 2.0) << "falls " << n << ", R " << R;
            EXPECT_EQ(std::stod(v[reverse]), n == 2 ? 0.0 : 2.0) << "falls " << n << ", R " << R;
            EXPECT_EQ(std::stod(v[cycles]), n == 2 ? 2.0 : 4.0) << "falls " << n << ", R " << R;
        }
    }
    EXPECT_EQ(checked, 6);
}
