// reeving-study end to end over the elevator and pendulum demos (the cheapest cases: short
// --t-end, one axial mode): a study's numbers are the demo runs' exactly; failing cases are
// recorded with their messages while the others complete; a study killed part way and resumed
// ends with the uninterrupted table; under mpirun -n 3 the table is the serial one bit for bit;
// bad input found by the demos' --check exits 2 naming the place and writes nothing.
#include "StudyTestSupport.h"

#include "ChildProcess.h"

#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdlib>

using namespace study_test;

namespace {

const std::string kStudy = REEVING_STUDY_EXE;
const std::string kElevator = REEVING_ELEVATOR_EXE;

// Six emergency stops: car load x car position (the elevator's cheapest dynamics with slip).
const char* kSixCases =
    "scene: elevator\n"
    "scenario: emergency-stop\n"
    "fixed: {t-end: 0.4, axial-modes: 1, transverse-modes: 1}\n"
    "vary:\n"
    "  car-load: [0, 1.25]\n"
    "  car-position: {linear: {from: 5, to: 35, count: 3}}\n"
    "metrics: [traction_table.0.traction_margin, traction_table.0.slip_distance_m, traction_table.0.car_rise_m,\n"
    "          traction_table.0.max_car_acceleration_mps2, traction_table.0.steps, traction_table.0.traction,\n"
    "          counterweight_kg, wall_seconds]\n"
    "figures:\n"
    "  - {type: lines, x: car-load, y: traction_table.0.traction_margin}\n"
    "  - {type: heatmap, x: car-position, y: car-load, z: traction_table.0.traction_margin, boundary: 1.001}\n";

nlohmann::json readJson(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

const nlohmann::json& at(const nlohmann::json& j, const std::string& path) {
    const nlohmann::json* p = &j;
    std::stringstream ss(path);
    std::string part;
    while (std::getline(ss, part, '.'))
        p = p->is_array() ? &(*p)[static_cast<std::size_t>(std::stoul(part))] : &p->at(part);
    return *p;
}

bool haveGnuplot() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

}  // namespace

// A study of six small cases gives, per case, exactly the numbers of the demo run
// with the same options (run here from the command line, the options space-separated).
TEST(StudyRuns, SixCasesGiveExactlyTheDemoRunsNumbers) {
    const fs::path dir = scratch("six");
    writeFile(dir / "six.yaml", kSixCases);
    const ProgramRun r = run(kStudy + " " + quote(dir / "six.yaml") + " --out " + quote(dir / "out") + " --quiet", dir);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("6 cases: 6 ok, 0 failed, 0 timeout"), std::string::npos) << r.out;
    const auto rows = csvRows(dir / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 7u);
    const std::vector<std::string>& header = rows[0];
    EXPECT_EQ(header.front(), "case");
    EXPECT_EQ(header[1], "car-load");
    EXPECT_EQ(header[2], "car-position");
    EXPECT_EQ(header[header.size() - 3], "wall_seconds");
    int compared = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const std::vector<std::string>& row = rows[i];
        ASSERT_EQ(row.size(), header.size());
        EXPECT_EQ(row[0], std::to_string(i - 1));  // sorted by case id
        EXPECT_EQ(row[row.size() - 2], "ok") << row.back();
        const fs::path demoOut = dir / ("demo-" + row[0]);
        const ProgramRun d = run(quote(kElevator) + " --scenario emergency-stop --t-end 0.4 --axial-modes 1 "
                                 "--transverse-modes 1 --car-load " + row[1] + " --car-position " + row[2] +
                                     " --no-plots --quiet --out " + quote(demoOut),
                                 dir);
        ASSERT_EQ(d.status, 0) << d.err;
        const nlohmann::json summary = readJson(demoOut / "summary.json");
        for (std::size_t k = 3; k + 3 < header.size(); ++k) {
            const nlohmann::json& v = at(summary, header[k]);
            if (v.is_number_float()) {
                EXPECT_EQ(std::strtod(row[k].c_str(), nullptr), v.get<double>()) << header[k] << " case " << row[0];
            } else if (v.is_number_integer()) {
                EXPECT_EQ(row[k], std::to_string(v.get<long>())) << header[k];
            } else {
                EXPECT_EQ(row[k], v.get<std::string>()) << header[k];
            }
            ++compared;
        }
    }
    EXPECT_EQ(compared, 6 * 7);
    const nlohmann::json s = readJson(dir / "out" / "summary.json");
    EXPECT_EQ(s.at("cases"), 6);
    EXPECT_EQ(s.at("ok"), 6);
    EXPECT_EQ(s.at("ranks"), 1);
    EXPECT_FALSE(fs::exists(dir / "out" / "results.csv.partial"));
    if (!haveGnuplot()) GTEST_SKIP() << "gnuplot not found: the figures were not checked";
    for (const char* png : {"traction_table_0_traction_margin_over_car-load.png",
                            "traction_table_0_traction_margin_over_car-position_and_car-load.png"})
        EXPECT_GT(fs::exists(dir / "out" / "figures" / png) ? fs::file_size(dir / "out" / "figures" / png) : 0u, 5000u)
            << png;
}

// A case forced to fail (a value that passes --check but fails the run: a rope too
// soft for the static equilibrium) is recorded with its message, the other case completes, and the
// study ends with exit status 1. No wall limit here: how long the failing case takes depends on the
// machine (and on sanitizers), its status must not.
TEST(StudyRuns, FailingCasesAreRecordedAndTheOthersComplete) {
    const fs::path dir = scratch("failing");
    writeFile(dir / "fail.yaml",
              "scene: pendulum\n"
              "fixed: {axial-modes: 0, t-end: 1}\n"
              "vary:\n"
              "  set.EA: [16.5e6, 10]\n"
              "  vx0: [1, 2]\n"
              "metrics: [steps, max_energy_drift_J]\n");
    const ProgramRun r = run(kStudy + " " + quote(dir / "fail.yaml") + " --out " + quote(dir / "out") + " --quiet", dir);
    EXPECT_EQ(r.status, 1) << r.out << r.err;
    const auto rows = csvRows(dir / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 5u);
    auto field = [&](std::size_t row, const std::string& column) {
        const auto& h = rows[0];
        return rows[row][static_cast<std::size_t>(std::find(h.begin(), h.end(), column) - h.begin())];
    };
    for (std::size_t row : {1u, 2u}) {  // EA 16.5 MN
        EXPECT_EQ(field(row, "status"), "ok");
        EXPECT_GT(std::stol(field(row, "steps")), 0);
    }
    for (std::size_t row : {3u, 4u}) {  // EA 10 N
        EXPECT_EQ(field(row, "status"), "failed");
        EXPECT_NE(field(row, "message").find("exit status 1: reeving-pendulum: simulation failed: "
                                             "ReevingSubsystem::findStaticEquilibrium: no convergence"),
                  std::string::npos)
            << field(row, "message");
        EXPECT_EQ(field(row, "steps"), "");
    }
    EXPECT_NE(r.out.find("4 cases: 2 ok, 2 failed"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("case 2 (set.EA=10, vx0=1) failed: exit status 1"), std::string::npos) << r.out;
    const nlohmann::json s = readJson(dir / "out" / "summary.json");
    EXPECT_EQ(s.at("failed"), 2);
    EXPECT_EQ(s.at("timeout"), 0);
    ASSERT_EQ(s.at("failures").size(), 2u);
    EXPECT_EQ(s.at("failures")[0].at("case"), 2);
    EXPECT_EQ(s.at("failures")[0].at("parameters").at("set.EA"), "10");
}

// A case past the wall limit is stopped and recorded as a timeout, the other case
// completes. Measured on an idle 2-core machine with t-end 5 s: the quick case (vx0 1 m/s) takes
// 0.19 s of wall, the slow one (vx0 1000 m/s, ~100 000 steps per simulated second) 27.7 s. The
// limit, 4 s, is 20x the quick case's wall (which sanitizers slow about 3-5x) and a seventh of the
// slow case's.
TEST(StudyRuns, CasesPastTheWallLimitAreStoppedAndRecorded) {
    const fs::path dir = scratch("timeout");
    writeFile(dir / "timeout.yaml",
              "scene: pendulum\n"
              "fixed: {axial-modes: 0, t-end: 5}\n"
              "vary:\n"
              "  vx0: [1, 1000]\n"
              "metrics: [steps, max_energy_drift_J]\n"
              "limits: {wall_seconds: 4}\n");
    const ProgramRun r = run(kStudy + " " + quote(dir / "timeout.yaml") + " --out " + quote(dir / "out") + " --quiet",
                             dir);
    EXPECT_EQ(r.status, 1) << r.out << r.err;
    const auto rows = csvRows(dir / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 3u);
    auto field = [&](std::size_t row, const std::string& column) {
        const auto& h = rows[0];
        return rows[row][static_cast<std::size_t>(std::find(h.begin(), h.end(), column) - h.begin())];
    };
    EXPECT_EQ(field(1, "status"), "ok");  // vx0 1 m/s
    EXPECT_GT(std::stol(field(1, "steps")), 0);
    EXPECT_EQ(field(2, "status"), "timeout");
    EXPECT_EQ(field(2, "message"), "passed the wall-clock limit of 4 s: stopped");
    EXPECT_GE(std::stod(field(2, "wall_seconds")), 4.0);
    EXPECT_LT(std::stod(field(2, "wall_seconds")), 8.0);
    EXPECT_NE(r.out.find("2 cases: 1 ok, 0 failed, 1 timeout"), std::string::npos) << r.out;
    const nlohmann::json s = readJson(dir / "out" / "summary.json");
    EXPECT_EQ(s.at("failed"), 0);
    EXPECT_EQ(s.at("timeout"), 1);
    ASSERT_EQ(s.at("failures").size(), 1u);
    EXPECT_EQ(s.at("failures")[0].at("case"), 1);
    EXPECT_EQ(s.at("failures")[0].at("parameters").at("vx0"), "1000");
}

// The step limit: the demo's --max-steps stops every case, recorded with the demo's message.
TEST(StudyRuns, StepLimitFailsCasesWithTheDemosMessage) {
    const fs::path dir = scratch("steps");
    writeFile(dir / "steps.yaml",
              "scene: elevator\nscenario: stall\nfixed: {t-end: 1}\nvary: {friction: [0.1, 0.2]}\n"
              "metrics: [traction_table.0.steps]\nlimits: {max_steps: 5}\n");
    const ProgramRun r = run(kStudy + " " + quote(dir / "steps.yaml") + " --out " + quote(dir / "out") + " --quiet", dir);
    EXPECT_EQ(r.status, 1) << r.out << r.err;
    const auto rows = csvRows(dir / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 3u);
    for (std::size_t i = 1; i < 3; ++i) {
        EXPECT_EQ(rows[i][rows[i].size() - 2], "failed");
        EXPECT_NE(rows[i].back().find("exit status 1: reeving-elevator: stopped: stall: the integrator took --max-steps 5 "
                                      "steps at t = "),
                  std::string::npos)
            << rows[i].back();
    }
}

// A study killed (SIGKILL) part way and resumed runs only the missing cases and ends
// with the same table as an uninterrupted run (wall times aside).
TEST(StudyRuns, KilledStudyResumesToTheUninterruptedTable) {
    const fs::path dir = scratch("resume");
    writeFile(dir / "slow.yaml",
              "scene: elevator\nscenario: loading\nfixed: {t-end: 4}\n"
              "vary: {car-load: [0, 0.25, 0.5, 0.75, 1, 1.25]}\n"
              "metrics: [traction_table.0.traction_margin, traction_table.0.steps, traction_table.0.traction]\n");
    const ProgramRun whole = run(kStudy + " " + quote(dir / "slow.yaml") + " --out " + quote(dir / "whole") + " --quiet", dir);
    ASSERT_EQ(whole.status, 0) << whole.err;
    const fs::path partial = dir / "killed" / "results.csv.partial";
    std::size_t done = 0;
    {
        // The killed runner cannot remove its scratch folder: put it in this test's.
        fs::create_directories(dir / "tmp");
        const char* tmp = std::getenv("TMPDIR");
        const std::string savedTmp = tmp ? tmp : "";
        setenv("TMPDIR", (dir / "tmp").c_str(), 1);
        study::ChildProcess runner(kStudy, {(dir / "slow.yaml").string(), "--out", (dir / "killed").string(), "--quiet"},
                                   dir / "killed.out", dir / "killed.err");
        if (tmp)
            setenv("TMPDIR", savedTmp.c_str(), 1);
        else
            unsetenv("TMPDIR");
        for (int i = 0; i < 20000 && !runner.poll(); ++i) {
            if (fs::exists(partial) && lines(partial).size() >= 3) break;  // the header and two cases
            study::sleepFor(0.001);
        }
        ASSERT_FALSE(runner.ended()) << readFile(dir / "killed.err");
        kill(runner.pid(), SIGKILL);
        while (!runner.poll()) study::sleepFor(0.001);
        EXPECT_EQ(runner.termSignal(), SIGKILL);
        done = lines(partial).size() - 1;
    }
    ASSERT_GE(done, 2u);
    ASSERT_LT(done, 6u) << "the runner finished before the kill";
    EXPECT_FALSE(fs::exists(dir / "killed" / "results.csv"));
    // Without --resume the stopped study is not overwritten.
    const ProgramRun again = run(kStudy + " " + quote(dir / "slow.yaml") + " --out " + quote(dir / "killed"), dir);
    EXPECT_EQ(again.status, 2);
    EXPECT_NE(again.err.find("results.csv.partial exists: a study stopped there. --resume continues it"),
              std::string::npos)
        << again.err;
    const ProgramRun resumed =
        run(kStudy + " " + quote(dir / "slow.yaml") + " --out " + quote(dir / "killed") + " --resume --quiet", dir);
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_EQ(withoutColumn(dir / "killed" / "results.csv", "wall_seconds"),
              withoutColumn(dir / "whole" / "results.csv", "wall_seconds"));
    EXPECT_FALSE(fs::exists(partial));
    const nlohmann::json s = readJson(dir / "killed" / "summary.json");
    EXPECT_EQ(s.at("cases_run"), static_cast<long>(6 - done));  // only the missing ones ran
    EXPECT_EQ(s.at("cases_resumed"), static_cast<long>(done));
    // A finished study resumed: nothing to run, the same table.
    const ProgramRun noop =
        run(kStudy + " " + quote(dir / "slow.yaml") + " --out " + quote(dir / "killed") + " --resume --quiet", dir);
    ASSERT_EQ(noop.status, 0) << noop.err;
    EXPECT_EQ(readJson(dir / "killed" / "summary.json").at("cases_run"), 0);
    EXPECT_EQ(withoutColumn(dir / "killed" / "results.csv", "wall_seconds"),
              withoutColumn(dir / "whole" / "results.csv", "wall_seconds"));
}

// With MPI, the same study under mpirun -n 3 (oversubscribed on small machines) gives
// the serial table bit for bit (wall times aside).
TEST(StudyRuns, MpiRunEqualsTheSerialRun) {
    if (!REEVING_STUDY_WITH_MPI) GTEST_SKIP() << "reeving-study was built without MPI (SIMBODYREEVING_STUDY_MPI OFF)";
    const fs::path dir = scratch("mpi");
    writeFile(dir / "six.yaml", kSixCases);
    const ProgramRun serial = run(kStudy + " " + quote(dir / "six.yaml") + " --out " + quote(dir / "serial") + " --quiet", dir);
    ASSERT_EQ(serial.status, 0) << serial.err;
    // mpirun refuses root without these (containers, CI).
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    // In the sanitizer build: what OpenMPI itself leaves allocated at MPI_Finalize is not ours.
    const char* asan = std::getenv("ASAN_OPTIONS");
    setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":detect_leaks=0").c_str(), 1);
    const ProgramRun mpi = run(quote(MPIEXEC_EXECUTABLE) + " -n 3 --oversubscribe " + kStudy + " " +
                                   quote(dir / "six.yaml") + " --out " + quote(dir / "mpi") + " --quiet",
                               dir);
    ASSERT_EQ(mpi.status, 0) << mpi.out << mpi.err;
    EXPECT_NE(mpi.out.find("(3 ranks, 2 running cases: speedup "), std::string::npos) << mpi.out;
    const std::string table = withoutColumn(dir / "serial" / "results.csv", "wall_seconds");
    EXPECT_EQ(withoutColumn(dir / "mpi" / "results.csv", "wall_seconds"), table);
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 7);
    const nlohmann::json s = readJson(dir / "mpi" / "summary.json");
    EXPECT_EQ(s.at("ranks"), 3);
    EXPECT_EQ(s.at("workers"), 2);
    EXPECT_GT(s.at("speedup_estimate").get<double>(), 0.0);
}

// Bad input that only the demo's own --check finds: exit 2 before any case runs, one message
// naming the place in the study file, nothing written.
TEST(StudyRuns, BadValuesFoundByTheDemosCheckExitTwoWritingNothing) {
    const fs::path dir = scratch("bad");
    struct Bad {
        std::string text, words;
    };
    const std::vector<Bad> bad = {
        {"scene: elevator\nscenario: lift-off\nmetrics: [friction]\n",
         "bad.yaml:2:11: unknown scenario 'lift-off' for scene elevator (reeving-elevator: --scenario: 'lift-off' must "
         "be one of: all, trip, loading, emergency-stop, stall)"},
        {"scene: elevator\nvary: {scenario: [trip, lift]}\nmetrics: [friction]\n",
         "bad.yaml:2:25: unknown scenario 'lift' for scene elevator (reeving-elevator: --scenario: 'lift' must be one of: "
         "all, trip, loading, emergency-stop, stall)"},
        {"scene: elevator\nfixed: {bogus: 3}\nmetrics: [friction]\n",
         "bad.yaml:2:9: unknown parameter 'bogus' for scene elevator (reeving-elevator: The following argument was not "
         "expected: --bogus=3; see reeving-elevator --help)"},
        {"scene: elevator\nvary:\n  set.M: [1, 2]\nmetrics: [friction]\n",
         "bad.yaml:3:3: unknown parameter 'set.M' for scene elevator (reeving-elevator: The following argument was not "
         "expected: --set=M=1"},
        {"scene: elevator\nvary:\n  car-load: {values: [0.5, 1, 2]}\nmetrics: [friction]\n",
         "bad.yaml:3:31: case 2 (car-load=2) is rejected by reeving-elevator: ElevatorParameters: carLoad [-] = 2 must "
         "be in [0, 1.25] (of the rated load) (scenario trip)"},
        {"scene: elevator\nscenario: emergency-stop\nvary:\n  car-position: {linear: {from: 0, to: 30, count: 4}}\n"
         "metrics: [friction]\n",
         "bad.yaml:4:26: case 0 (car-position=0) is rejected by reeving-elevator: ElevatorParameters: carPosition [m] = "
         "0 must be in [2, hoistway - 2] in the emergency-stop scenario"},
        {"scene: elevator\nvary: {friction: [0.1, -0.2]}\nmetrics: [friction]\n",
         "bad.yaml:2:24: case 1 (friction=-0.2) is rejected by reeving-elevator: --friction: '-0.2' must be > 0"},
        {"scene: pendulum\nfixed: {axial-modes: 0}\nvary: {set.M: [1000, -5]}\nmetrics: [steps]\n",
         "bad.yaml:3:22: case 1 (set.M=-5) is rejected by reeving-pendulum: --set: 'M=-5': PendulumParameters: M = -5 "
         "must be finite and > 0"},
        {"scene: pendulum\nfixed: {axial-modes: 0, integrator: euler}\nmetrics: [steps]\n",
         "bad.yaml:2:37: case 0 (the only case) is rejected by reeving-pendulum: --integrator: 'euler' must be one of"},
    };
    for (const Bad& b : bad) {
        writeFile(dir / "bad.yaml", b.text);
        const ProgramRun r = run("cd " + quote(dir) + " && " + kStudy + " bad.yaml --out out", dir);
        EXPECT_EQ(r.status, 2) << b.text;
        EXPECT_NE(r.err.find("reeving-study: " + b.words), std::string::npos) << "stderr: " << r.err << "\nexpected: "
                                                                              << b.words;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out")) << b.text;
        EXPECT_EQ(r.out, "");
    }
}

// --dry-run: every case checked and listed with its command line; nothing run or written.
TEST(StudyRuns, DryRunListsTheCasesAndWritesNothing) {
    const fs::path dir = scratch("dry");
    writeFile(dir / "six.yaml", kSixCases);
    const ProgramRun r = run("cd " + quote(dir) + " && " + kStudy + " six.yaml --dry-run", dir);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("6 cases (6 grid points x 1 sample point); every case passed reeving-elevator --check"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("case 5: car-load=1.25, car-position=35\n    reeving-elevator --scenario=emergency-stop "
                         "--t-end=0.4 --axial-modes=1 --transverse-modes=1 --car-load=1.25 --car-position=35 "
                         "--out=CASE_DIR --no-plots --quiet\n"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "out"));
}
