// The reeving-crane executable end to end: outputs with their columns and
// keys, the number of falls, both sheave models, a rope limit ending the run (exit 3, outputs
// written), bad input and unusable output folders (exit 2, nothing written), SIGINT (exit 130,
// nothing written).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kExe = REEVING_CRANE_EXE;

int run(const std::string& args, const std::string& log) {
    const std::string cmd = "'" + kExe + "' " + args + " > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("reeving_crane_test_" + name);
    fs::remove_all(p);
    fs::remove(p.string() + ".log");
    return p;
}

// Every value of every data row is a finite number and every row has the header's column count;
// returns the header's columns and sets `rows`.
std::vector<std::string> checkCsv(const fs::path& p, size_t& rows) {
    std::ifstream in(p);
    std::string header, line;
    std::getline(in, header);
    std::vector<std::string> columns;
    {
        std::stringstream ss(header);
        std::string c;
        while (std::getline(ss, c, ',')) columns.push_back(c);
    }
    rows = 0;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell;
        size_t n = 0;
        while (std::getline(ss, cell, ',')) {
            char* end = nullptr;
            const double v = std::strtod(cell.c_str(), &end);
            EXPECT_TRUE(end != cell.c_str() && std::isfinite(v)) << p << ": '" << cell << "'";
            ++n;
        }
        EXPECT_EQ(n, columns.size()) << p << ": " << line;
        ++rows;
    }
    return columns;
}

std::vector<std::string> expectedColumns(int falls) {
    std::vector<std::string> c{"t", "trolley_x", "hook_x", "hook_height", "sway", "payload_angle"};
    for (int k = 1; k <= falls; ++k) c.push_back("fall_" + std::to_string(k));
    for (const char* s : {"drum_speed", "motor_torque", "motor_power", "rope_on_drum", "trolley_force", "trolley_power",
                          "motion_work", "energy_residual"})
        c.push_back(s);
    return c;
}

// No null anywhere (a NaN or infinity is written as null).
void expectNoNull(const nlohmann::json& j, const std::string& where) {
    EXPECT_FALSE(j.is_null()) << where;
    if (j.is_object())
        for (const auto& [k, v] : j.items()) expectNoNull(v, where + "." + k);
    if (j.is_array())
        for (size_t i = 0; i < j.size(); ++i) expectNoNull(j[i], where + "[" + std::to_string(i) + "]");
}

// summary.json parses and has every key with a value of the right kind; returns it.
nlohmann::json checkSummary(const fs::path& p) {
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(slurp(p));
    } catch (const nlohmann::json::exception& e) {
        ADD_FAILURE() << p << ": " << e.what();
        return json;
    }
    for (const char* key : {"program", "axial_dynamics", "axial_law", "integrator", "termination", "limit"})
        EXPECT_TRUE(json.contains(key) && json[key].is_string()) << key;
    for (const char* key : {"falls", "axial_modes", "transverse_modes", "steps", "rhs_evaluations"})
        EXPECT_TRUE(json.contains(key) && json[key].is_number_integer()) << key;
    for (const char* key : {"accuracy", "fixed_step", "report_interval", "lift_m", "traverse_m", "t_end",
                            "t_reached", "static_reference_axial_force_N", "max_abs_sway_rad",
                            "max_abs_payload_angle_rad", "initial_hook_height_m", "final_hook_height_m",
                            "final_rope_on_drum_m", "max_abs_motor_torque_Nm", "max_abs_motor_power_W",
                            "max_abs_trolley_force_N", "final_motion_work_J", "max_abs_motion_work_J",
                            "max_abs_energy_residual_J", "energy_residual_relative", "wall_seconds",
                            "real_time_factor"})
        EXPECT_TRUE(json.contains(key) && json[key].is_number()) << key;
    // The fall forces are axial forces P = EA eps (not tensions), one per fall.
    const size_t falls = json.value("falls", 0u);
    for (const char* key : {"static_fall_axial_force_N", "max_fall_axial_force_N"})
        EXPECT_TRUE(json.contains(key) && json[key].is_array() && json[key].size() == falls) << key;
    for (const char* old : {"static_fall_tension_N", "static_reference_tension_N", "max_fall_tension_N"})
        EXPECT_FALSE(json.contains(old)) << old;
    EXPECT_TRUE(json.contains("snapshot_times") && json["snapshot_times"].is_array());
    // The most bent rope section (RopeLifeMonitor; rope_bending.csv has every section).
    EXPECT_TRUE(json.contains("rope_life") && json["rope_life"].is_object());
    if (json.contains("rope_life")) {
        const auto& life = json["rope_life"];
        for (const char* key : {"rope_diameter_m", "section_length_m", "reverse_bend_factor"})
            EXPECT_TRUE(life.contains(key) && life[key].is_number()) << key;
        for (const char* key : {"sections", "bend_events"})
            EXPECT_TRUE(life.contains(key) && life[key].is_number_integer()) << key;
        // The most bent section: present once a section went onto or off a sheave or the drum.
        EXPECT_EQ(life.contains("worst_section"), life.value("bend_events", 0) > 0);
        if (life.contains("worst_section")) {
            EXPECT_TRUE(life["worst_section"].is_object());
            for (const char* key : {"index", "s_start_m", "s_end_m", "cycles", "simple_cycles", "reverse_cycles",
                                    "max_tension_N", "min_diameter_ratio"})
                EXPECT_TRUE(life["worst_section"].contains(key) && life["worst_section"][key].is_number()) << key;
        }
    }
    EXPECT_TRUE(json.contains("parameters") && json["parameters"].is_object() && json["parameters"].size() == 25u);
    expectNoNull(json, "summary");
    return json;
}

// Number of gnuplot data sets (snapshots) in snapshots.dat.
int countSnapshots(const fs::path& p) {
    const std::string text = slurp(p);
    int n = 0;
    for (size_t at = text.find("# snapshot "); at != std::string::npos; at = text.find("# snapshot ", at + 1)) ++n;
    return n;
}

}  // namespace

TEST(CraneDemo, WritesAllOutputs) {
    const fs::path out = scratch("default");
    ASSERT_EQ(run("--t-end 1.5 --report-interval 0.1 --quiet --out '" + out.string() + "'", out.string() + ".log"), 0)
        << slurp(out.string() + ".log");
    size_t rows = 0;
    EXPECT_EQ(checkCsv(out / "timeseries.csv", rows), expectedColumns(4));
    EXPECT_EQ(rows, 16u);  // t = 0, 0.1, ..., 1.5
    const nlohmann::json json = checkSummary(out / "summary.json");
    EXPECT_EQ(json.value("termination", ""), "completed");
    EXPECT_EQ(json.value("falls", 0), 4);
    EXPECT_EQ(json.value("program", ""), "reeving-crane");
    EXPECT_EQ(countSnapshots(out / "snapshots.dat"), 6);
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_EQ(e.path().extension(), e.path().extension() == ".partial" ? ".none" : e.path().extension()) << e.path();
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "gnuplot not found: the five figures were not checked (the other checks above ran)";
    for (const char* fig : {"fig_hook_height_sway.png", "fig_fall_axial_forces.png", "fig_energy.png",
                            "fig_snapshots.png", "fig_rope_bending.png"})
        EXPECT_GT(fs::exists(out / fig) ? fs::file_size(out / fig) : 0u, 1000u) << fig;
}

TEST(CraneDemo, FallsAndModeOptions) {
    for (const auto& [falls, args] : std::vector<std::pair<int, std::string>>{
             {1, "--axial-modes 0"}, {3, "--axial-modes 2 --transverse-modes 2"}, {12, "--axial-modes 1"},
             {2, "--axial-modes 1 --axial-dynamics dynamic --integrator rk3"}}) {
        const fs::path out = scratch("falls_" + std::to_string(falls));
        EXPECT_EQ(run("--falls " + std::to_string(falls) + " " + args +
                          " --t-end 0.2 --report-interval 0.05 --snapshots 2 --no-plots --quiet --out '" +
                          out.string() + "'",
                      out.string() + ".log"),
                  0)
            << falls << ": " << slurp(out.string() + ".log");
        size_t rows = 0;
        EXPECT_EQ(checkCsv(out / "timeseries.csv", rows), expectedColumns(falls)) << falls;
        EXPECT_EQ(rows, 5u);
        EXPECT_EQ(checkSummary(out / "summary.json").value("falls", 0), falls);
        EXPECT_EQ(countSnapshots(out / "snapshots.dat"), 2);
        EXPECT_FALSE(fs::exists(out / "fig_snapshots.png"));
    }
}

// A lift beyond the two-blocking height: the shortest fall reaches minimumSpanLength, the run ends
// there cleanly, the outputs up to that instant are written, exit status 3 with one stderr line.
// --sheaves point|wrapped over the first 1.5 s (at rest, then the lift starts at 1 s): summary.json
// names the model and reports the falls' lean at rest, the wrap angles' range per sheave and the
// rope's length error (tests/scenes/test_crane_wrapped_sheaves.cpp has the physics).
TEST(CraneDemo, SheaveModels) {
    for (const std::string sheaves : {"point", "wrapped"}) {
        const fs::path out = scratch("sheaves_" + sheaves);
        const std::string log = out.string() + ".log";
        ASSERT_EQ(run("--sheaves " + sheaves + " --t-end 1.5 --report-interval 0.1 --no-plots --quiet --out '" +
                          out.string() + "'",
                      log),
                  0)
            << slurp(log);
        const nlohmann::json json = checkSummary(out / "summary.json");
        EXPECT_EQ(json.value("sheaves", ""), sheaves);
        EXPECT_EQ(json.value("termination", ""), "completed");
        const double lean = json.value("initial_largest_fall_lean_deg", -1.0);
        if (sheaves == "point") {
            // The falls join nodes sheavePitch = 0.2 m apart 11 m below: measured 1.05946 deg; bound
            // 1e-3 deg (23x over its 4.4e-5 deg from 1.0595).
            EXPECT_NEAR(lean, 1.0595, 1e-3);
        } else {
            // Measured 9.86e-5 deg (the inextensible rope on the drum and the grooves:
            // FallsHangVerticalAtRest); bound 1e-3 deg, 10x, 100x inside the required 0.1 deg.
            EXPECT_GE(lean, 0.0);
            EXPECT_LT(lean, 1e-3);
        }
        EXPECT_GE(json.value("max_largest_fall_lean_deg", -1.0), lean);
        // One range per sheave 1..3: pi with wrapped sheaves (measured within -2.4e-9 .. +1.0e-6 rad
        // as the lift starts; bound 1e-5 rad, 10x), 0 with point sheaves (no rope on the groove).
        ASSERT_TRUE(json.contains("sheave_wrap_angles") && json["sheave_wrap_angles"].is_array());
        const auto& wraps = json["sheave_wrap_angles"];
        ASSERT_EQ(wraps.size(), 3u);
        for (size_t k = 0; k < wraps.size(); ++k) {
            EXPECT_EQ(wraps[k].value("sheave", 0), static_cast<int>(k) + 1);
            const double lo = wraps[k].value("min_rad", -1.0), hi = wraps[k].value("max_rad", -1.0);
            EXPECT_LE(lo, hi) << k;
            const double expected = sheaves == "point" ? 0.0 : std::acos(-1.0);
            EXPECT_NEAR(lo, expected, 1e-5) << sheaves << " " << k;
            EXPECT_NEAR(hi, expected, 1e-5) << sheaves << " " << k;
        }
        EXPECT_EQ(json.value("max_fleet_angle_rad", -1.0), 0.0);  // the rope is planar
        // Round-off of a sum of lengths up to 40 m: measured 1.4e-14 m in both; bound 1e-12 m (70x).
        EXPECT_GE(json.value("max_abs_rope_length_error_m", -1.0), 0.0);
        EXPECT_LT(json.value("max_abs_rope_length_error_m", 1.0), 1e-12);
    }
}

// The default cycle's bending cycles per rope section (rope_bending.csv, summary.json rope_life),
// counted by hand from the lift, the falls and the sheave positions.
// The rope: the drum (radius R_d = 0.3 m, centre drumHeight = 0.8 m above the rail at railHeight =
// 15 m) -> hook sheave 1 (counter-clockwise about +z) -> trolley sheave 2 (clockwise) -> hook sheave
// 3 -> the dead end on the trolley; sheave radius R = 0.09 m, the hook sheaves' centres
// initialHookDepth = 11 m below the rail. With wrapped sheaves the falls hang vertical between
// tangent points, each carrying P = (M + m_hook) g / 4 = 12 753 N, so a fall h m long holds
// h / lambda of material, lambda = sqrt(1 + 2 P / EA) (Green strain, EA = 25 MN). Material
// coordinates from the drum's top (s = 0 at pin angle 0): the rope leaves the drum a quarter turn
// on, at s = R_d pi / 2, so at rest
//   arrival at sheave 1:   s_a1 = R_d pi / 2 + (15.8 - 4) / lambda            = 12.265 m,
//   departure at sheave 2: s_b2 = s_a1 + pi R + (15 - 4) / lambda + pi R      = 23.825 m.
// The lift hauls 4 x 5 = 20 m onto the drum; the material at sheave 1's arrival moves by 3 x 5 =
// 15 m, at sheave 2's by 10 m, at sheave 3's by 5 m, and the lowering runs them back. Sheave 3's
// 5 m and sheave 2's 10 m reach no other sheave; the sections in [s_b2, s_a1 + 15] = [23.825,
// 27.265] m pass sheave 2 (their first bend, simple) and then sheave 1 (the other side of the rope:
// reverse) on the lift, and back over sheave 1 (the same side as their last bend: simple) and
// sheave 2 (reverse) on the lowering: 2 simple + 2 reverse cycles, the most of any section (the
// drum and sheave 1 give 1 + 2 = 3 simple at most), 6 weighted with w_r = 2.
TEST(CraneDemo, RopeBendingCountsEachSection) {
    const fs::path out = scratch("rope_bending");
    const std::string log = out.string() + ".log";
    ASSERT_EQ(run("--reverse-bend-factor 2 --no-plots --quiet --out '" + out.string() + "'", log), 0) << slurp(log);
    size_t rows = 0;
    const std::vector<std::string> columns = checkCsv(out / "rope_bending.csv", rows);
    EXPECT_EQ(columns, (std::vector<std::string>{"section", "s_start_m", "s_end_m", "cycles", "simple_cycles",
                                                 "reverse_cycles", "max_tension_N"}));
    const nlohmann::json json = checkSummary(out / "summary.json");
    const auto& life = json["rope_life"];
    EXPECT_EQ(rows, life.value("sections", 0u));
    EXPECT_EQ(life.value("reverse_bend_factor", 0.0), 2.0);
    const auto& worst = life["worst_section"];
    EXPECT_EQ(worst.value("simple_cycles", -1.0), 2.0);
    EXPECT_EQ(worst.value("reverse_cycles", -1.0), 2.0);
    EXPECT_EQ(worst.value("cycles", -1.0), 2.0 + 2.0 * 2.0);
    EXPECT_EQ(worst.value("min_diameter_ratio", 0.0), 2 * 0.09 / 0.02);  // D/d of the sheaves
    // Its largest tension: a fall's share of the hook load, (5000 + 200) 9.81 / 4 = 12.8 kN, and the
    // lift's dynamics (measured 13.8 kN); bound: within 30 % of the static share.
    EXPECT_GT(worst.value("max_tension_N", 0.0), 0.9 * 12753.0);
    EXPECT_LT(worst.value("max_tension_N", 0.0), 1.3 * 12753.0);

    // The band of the hand count above, from the parameters.
    const double pi = std::acos(-1.0), P = 5200 * 9.81 / 4, lambda = std::sqrt(1 + 2 * P / 25e6);
    const double hookY = 15.0 - 11.0, sheaveR = 0.09, drumR = 0.3;
    const double sA1 = drumR * pi / 2 + (15.8 - hookY) / lambda;
    const double sB2 = sA1 + 2 * pi * sheaveR + (15.0 - hookY) / lambda;
    const double bandLow = sB2, bandHigh = sA1 + 3 * 5.0;
    // Every section wholly inside the band by more than a section length counts 2 + 2; every section
    // that counts 2 + 2 lies in the band widened by one section length at each end (a section on a
    // band edge straddles a tangent point at the lift's start or end; the falls' dynamic stretch
    // moves the edges by millimetres). Measured: the 34 sections with 2 + 2 span [23.871, 27.271] m.
    std::ifstream in(out / "rope_bending.csv");
    std::string line;
    std::getline(in, line);
    int inside = 0, twoAndTwo = 0;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::vector<double> v;
        for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
        ASSERT_EQ(v.size(), 7u) << line;
        const double start = v[1], end = v[2];
        const bool counted = v[4] == 2.0 && v[5] == 2.0;
        if (start >= bandLow + 0.1 && end <= bandHigh - 0.1) {
            ++inside;
            EXPECT_TRUE(counted) << line;
        }
        if (counted) {
            ++twoAndTwo;
            EXPECT_GE(start, bandLow - 0.1) << line;
            EXPECT_LE(end, bandHigh + 0.1) << line;
        }
        EXPECT_LE(v[3], 6.0) << line;  // no section more than the band's
    }
    EXPECT_GE(inside, 30);  // (27.265 - 23.825 - 0.2) / 0.1 = 32 sections
    // The band's 3.44 m hold 34 whole sections; bound +-3 (the edge sections).
    EXPECT_GE(twoAndTwo, 31);
    EXPECT_LE(twoAndTwo, 37);
}

TEST(CraneDemo, TwoBlockingEndsTheRunWithExitThree) {
    const fs::path out = scratch("two_blocking");
    const std::string log = out.string() + ".log";
    ASSERT_EQ(run("--lift 12 --axial-modes 0 --t-end 15 --report-interval 0.1 --no-plots --quiet --out '" +
                      out.string() + "'",
                  log),
              3)
        << slurp(log);
    const nlohmann::json json = checkSummary(out / "summary.json");
    EXPECT_EQ(json.value("termination", ""), "limit_reached") << json.dump(2);
    EXPECT_NE(json.value("limit", ""), "") << json.dump(2);
    size_t rows = 0;
    checkCsv(out / "timeseries.csv", rows);
    EXPECT_GT(rows, 20u);
    EXPECT_LT(rows, 111u);  // ended before the lift's end at 10 s
    const std::string msg = slurp(log);
    EXPECT_NE(msg.find("reeving-crane: rope limit reached at t = "), std::string::npos) << msg;
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 2) << msg;  // the summary line and the note
}

TEST(CraneDemo, BadInputExitsTwoAndWritesNothing) {
    // The message names the option and quotes the value (CLI11's "option: message" form).
    const std::vector<std::pair<std::string, std::string>> cases{
        {"--bogus", "not expected: --bogus"},
        {"--falls 0", "--falls: '0' must be in 1..12"},
        {"--falls 13", "--falls: '13' must be in 1..12"},
        {"--falls two", "--falls: 'two' is not an integer"},
        {"--axial-modes 17", "--axial-modes: '17' must be in 0..16"},
        {"--transverse-modes -1", "--transverse-modes: '-1' must be in 0..16"},
        {"--axial-dynamics fast", "--axial-dynamics: 'fast' must be one of: quasi-static, dynamic"},
        {"--axial-law rigid", "--axial-law: 'rigid' must be one of: tension-only, linear"},
        {"--sheaves bogus", "--sheaves: 'bogus' must be one of: point, wrapped"},
        {"--lift 0", "--lift: '0' must be > 0"},
        {"--traverse inf", "--traverse: 'inf' is not a finite number"},
        {"--t-end -1", "--t-end: '-1' must be > 0"},
        {"--integrator rk45", "--integrator: 'rk45' must be one of: rk-merson,"},
        {"--accuracy 2", "--accuracy: '2' must be in (0, 1)"},
        {"--set EA=-5", "--set: 'EA=-5': CraneParameters: EA = -5"},
        {"--set Q=1", "--set: 'Q=1': unknown key"},
        {"--set payloadMass", "--set: 'payloadMass' must be KEY=VALUE"},
        {"--snapshots 0", "--snapshots: '0' must be in 1..12"},
        {"--report-interval nan", "--report-interval: 'nan' is not a finite number"},
        {"--report-interval 1 --t-end 0.5", "--report-interval: 1 s must not exceed --t-end (0.5 s)"},
        {"--out", "--out: 1 required DIR missing"},
        {"--section-length 0", "--section-length: '0' must be > 0"},
        {"--rope-diameter 0.7", "RopeLifeMonitor: rope 'hoist rope', node 0: D/d = 2 R / d = 2 * 0.3 / 0.7"},
        {"--rope-diameter 0.2", "node 1: D/d = 2 R / d = 2 * 0.09 / 0.2 = 0.9 is below 1"},
        {"--reverse-bend-factor 0.5", "RopeLifeMonitor: reverseBendFactor [-] = 0.5 must be finite and >= 1"},
    };
    for (const auto& [args, needle] : cases) {
        const fs::path out = scratch("bad");
        const std::string log = out.string() + ".log";
        EXPECT_EQ(run(args + (args == "--out" ? "" : " --out '" + out.string() + "'"), log), 2) << args;
        const std::string msg = slurp(log);
        EXPECT_NE(msg.find(needle), std::string::npos) << args << " -> " << msg;
        EXPECT_NE(msg.find("Try 'reeving-crane --help'."), std::string::npos) << msg;
        EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 2) << msg;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    const fs::path out = scratch("help");
    EXPECT_EQ(run("--help", out.string() + ".log"), 0);
    EXPECT_NE(slurp(out.string() + ".log").find("Exit status"), std::string::npos);
}

TEST(CraneDemo, UnusableOutputFolderExitsTwoWithOneClearLine) {
    const fs::path file = scratch("out_is_a_file");
    { std::ofstream(file) << "keep me\n"; }
    for (const std::string& out : {file.string(), (file / "sub").string()}) {
        const std::string log = scratch("out_log").string();
        EXPECT_EQ(run("--t-end 0.1 --no-plots --out '" + out + "'", log), 2) << out;
        const std::string msg = slurp(log);
        EXPECT_NE(msg.find("reeving-crane: --out '" + out + "': cannot create the output folder"), std::string::npos)
            << msg;
        EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
    }
    EXPECT_EQ(slurp(file), "keep me\n");
    fs::remove(file);
}

TEST(CraneDemo, InterruptedRunWritesNothingAndExitsNonZero) {
    const fs::path out = scratch("interrupted");
    const std::string log = out.string() + ".log";
    const std::string cmd = "timeout --preserve-status -s INT 3 '" + kExe +
                            "' --falls 12 --axial-modes 3 --axial-dynamics dynamic --t-end 1000 --no-plots --quiet "
                            "--out '" +
                            out.string() + "' > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130) << slurp(log);
    const std::string msg = slurp(log);
    EXPECT_NE(msg.find("reeving-crane: interrupted at t = "), std::string::npos) << msg;
    EXPECT_NE(msg.find("no outputs written"), std::string::npos) << msg;
    ASSERT_TRUE(fs::is_directory(out));
    EXPECT_TRUE(fs::is_empty(out)) << "files left in " << out;
}

// --scenario lift-off: the payload picked up off the floor at --hoist-speed; summary.json has the
// dynamic factor and its references, timeseries.csv the contacts' columns.
TEST(CraneDemo, LiftOffWritesTheDynamicFactor) {
    const fs::path out = scratch("lift_off");
    const std::string log = out.string() + ".log";
    ASSERT_EQ(run("--scenario lift-off --hoist-speed 0.1 --snapshots 3 --no-plots --quiet --out '" + out.string() + "'",
                  log),
              0)
        << slurp(log);
    size_t rows = 0;
    std::vector<std::string> columns = expectedColumns(4);
    for (const char* c : {"rope_force", "floor_force", "sling_force", "contact_dissipation"}) columns.push_back(c);
    EXPECT_EQ(checkCsv(out / "timeseries.csv", rows), columns);
    const nlohmann::json json = nlohmann::json::parse(slurp(out / "summary.json"));
    expectNoNull(json, "summary");
    EXPECT_EQ(json.value("scenario", ""), "lift-off");
    EXPECT_EQ(json.value("termination", ""), "completed");
    for (const char* key : {"static_rope_force", "peak_rope_force", "dynamic_factor", "lift_off_time", "hoist_speed",
                            "spring_mass_dynamic_factor", "hook_stiffness_N_per_m", "rope_slack_m", "t_end"})
        EXPECT_TRUE(json.contains(key) && json[key].is_number()) << key;
    EXPECT_EQ(json["parameters"].size(), 33u);
    // The default 1 ms reports to the lift-off cycle's end (about 1.1 s).
    EXPECT_NEAR(json.value("report_interval", 0.0), 0.001, 1e-15);
    EXPECT_EQ(rows, static_cast<size_t>(std::floor(json.value("t_end", 0.0) / 0.001 + 1e-9)) + 1);
    // The crane's own rope: within 1 % of the spring-mass factor (measured -0.30 %: the rope's
    // weight and the contacts' compliance; tests/scenes/test_crane_lift_off.cpp has the physics).
    const double phi = json.value("dynamic_factor", 0.0), reference = json.value("spring_mass_dynamic_factor", 0.0);
    EXPECT_NEAR(phi / reference, 1.0, 0.01) << phi << " " << reference;
    EXPECT_NEAR(phi, json.value("peak_rope_force", 0.0) / json.value("static_rope_force", 1.0), 1e-9);
    // Lift-off after the sling is taut (1 s) and before the end; the peak after it.
    const double liftOff = json.value("lift_off_time", 0.0);
    EXPECT_GT(liftOff, 1.0);
    EXPECT_LT(liftOff, json.value("peak_rope_force_time", 0.0));
    EXPECT_LT(json.value("energy_residual_relative", 1.0), 1e-6);
    EXPECT_EQ(countSnapshots(out / "snapshots.dat"), 3);
}

// --check: parses, builds the scene with all its validation, runs and writes nothing; exit 0 when
// valid, 2 with the usual message when not.
TEST(CraneDemo, CheckValidatesWithoutRunning) {
    for (const std::string& args : {std::string("--check"), std::string("--scenario lift-off --hoist-speed 0.6 --check")}) {
        const fs::path out = scratch("check");
        EXPECT_EQ(run(args + " --out '" + out.string() + "'", out.string() + ".log"), 0) << args;
        EXPECT_EQ(slurp(out.string() + ".log"), "") << args;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    // A value only the scene can judge: the slack 0.3 (0.25 + 5) m does not fit in the sling.
    const fs::path out = scratch("check_bad");
    const std::string log = out.string() + ".log";
    EXPECT_EQ(run("--scenario lift-off --set slackTime=5 --check --out '" + out.string() + "'", log), 2);
    const std::string msg = slurp(log);
    EXPECT_NE(msg.find("reeving-crane: CraneParameters: lift-off: the slack"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Try 'reeving-crane --help'."), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(out));
    // The same without --check: the same message and exit status, before anything is written.
    EXPECT_EQ(run("--scenario lift-off --set slackTime=5 --out '" + out.string() + "'", log), 2);
    EXPECT_EQ(slurp(log), msg);
    EXPECT_FALSE(fs::exists(out));
}

// --max-steps N: the run stops once the integrator has taken N steps, exit 1, nothing written.
TEST(CraneDemo, MaxStepsStopsTheRun) {
    const fs::path out = scratch("max_steps");
    const std::string log = out.string() + ".log";
    EXPECT_EQ(run("--max-steps 50 --no-plots --quiet --out '" + out.string() + "'", log), 1);
    const std::string msg = slurp(log);
    EXPECT_NE(msg.find("reeving-crane: stopped: the integrator took --max-steps 50 steps at t = "), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("; nothing written"), std::string::npos) << msg;
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
    EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out));
    // Enough steps: the run completes (the 1.5 s run takes about 80).
    EXPECT_EQ(run("--max-steps 100000 --t-end 1.5 --no-plots --quiet --out '" + out.string() + "'", log), 0)
        << slurp(log);
}

TEST(CraneDemo, ScenarioOptionsExitTwoOnBadInput) {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"--scenario hanging", "--scenario: 'hanging' must be one of: cycle, lift-off"},
        {"--hoist-speed 0.2", "--hoist-speed: only with --scenario lift-off"},
        {"--scenario lift-off --hoist-speed 0", "--hoist-speed: '0' must be > 0"},
        {"--scenario lift-off --lift 3", "--lift: only with --scenario cycle"},
        {"--scenario lift-off --set floorStiffness=-1", "--set: 'floorStiffness=-1': CraneParameters: floorStiffness"},
        {"--max-steps 0", "--max-steps: '0' must be in 1..1000000000"},
        {"--max-steps many", "--max-steps: 'many' is not an integer"},
    };
    for (const auto& [args, needle] : cases) {
        const fs::path out = scratch("bad_scenario");
        const std::string log = out.string() + ".log";
        EXPECT_EQ(run(args + " --out '" + out.string() + "'", log), 2) << args;
        const std::string msg = slurp(log);
        EXPECT_NE(msg.find(needle), std::string::npos) << args << " -> " << msg;
        EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 2) << msg;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
}
