// The reeving-elevator executable end to end (issue 21, acceptance 5): the traction table in
// summary.json, the stalled counterweight slips (the car rises far less than the machine's rope
// travel would lift it), the trip follows its profile within the rope's stretch, bad input exits 2
// and writes nothing.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kExe = REEVING_ELEVATOR_EXE;

int run(const std::string& args, const std::string& log) {
    const std::string cmd = "'" + kExe + "' " + args + " > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("reeving_elevator_test_" + name);
    fs::remove_all(p);
    return p;
}

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

// Columns of a CSV file by header name.
std::vector<std::vector<double>> readCsv(const fs::path& p, std::vector<std::string>& header) {
    std::ifstream in(p);
    std::string line;
    std::getline(in, line);
    std::stringstream hs(line);
    for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::stringstream ls(line);
        std::vector<double> row;
        for (std::string v; std::getline(ls, v, ',');) row.push_back(std::stod(v));
        rows.push_back(row);
    }
    return rows;
}

int column(const std::vector<std::string>& header, const std::string& name) {
    for (size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return static_cast<int>(i);
    ADD_FAILURE() << "no column " << name;
    return 0;
}

}  // namespace

TEST(ElevatorDemo, StallSlipsAndTheCarRisesFarLessThanTheRopeTravel) {
    const fs::path out = scratch("stall");
    ASSERT_EQ(run("--scenario stall --no-plots --quiet --out '" + out.string() + "'", out.string() + ".log"), 0);
    const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
    EXPECT_EQ(t.at("scenario"), "stall");
    EXPECT_EQ(t.at("traction"), "slipped");
    const double rise = t.at("car_rise_m"), travel = -t.at("rope_travel_m").get<double>();
    std::printf("stall: car rise %.4f m for %.4f m of rope travel; slip %.4f m\n", rise, travel,
                t.at("slip_distance_m").get<double>());
    EXPECT_GT(travel, 2.0);
    EXPECT_LT(rise, 0.1 * travel);  // measured 0.050 m of 2.5 m
    EXPECT_NEAR(t.at("traction_margin").get<double>(), 1.0, 1e-6);  // slipping: at the capstan limit
    // Energy closes with the friction work: measured 2.8e-6 of the machine's work at accuracy 1e-6.
    EXPECT_LE(t.at("energy_residual_relative").get<double>(), 1e-4);
}

TEST(ElevatorDemo, TripFollowsItsProfileWithinTheRopeStretchAndHolds) {
    const fs::path out = scratch("trip");
    ASSERT_EQ(run("--scenario trip --no-plots --quiet --out '" + out.string() + "'", out.string() + ".log"), 0);
    const nlohmann::json s = readJson(out / "summary.json");
    const nlohmann::json t = s.at("traction_table").at(0);
    EXPECT_EQ(t.at("traction"), "held");
    EXPECT_GT(t.at("traction_margin").get<double>(), 1.0);
    std::vector<std::string> h;
    const auto rows = readCsv(out / "timeseries_trip.csv", h);
    const int cy = column(h, "car_y_m"), tr = column(h, "rope_travel_m"), pa = column(h, "car_side_force_N");
    // The car's rise equals the rope hauled in (-travel) up to the change of the car fall's stretch,
    // P l / EA with l = 40 m - rise (the rope set's EA = 16 MN; P at the sheave, the fall's mean
    // force is lower by half its weight, 1.7 %): 4.1 cm at the start, 1.2 cm less at the end.
    double worstMiss = 0, largest = 0;
    const double l0 = 40.0, EA = 1.6e7;
    for (const auto& r : rows) {
        const double rise = r[cy] - rows[0][cy];
        const double predicted = (r[pa] * (l0 - rise) - rows[0][pa] * l0) / EA;  // stretch change [m]
        worstMiss = std::max(worstMiss, std::abs((rise - (-r[tr])) - (-predicted)));
        largest = std::max(largest, std::abs(predicted));
    }
    std::printf("trip: largest stretch change %.4f m, car path off it by at most %.5f m\n", largest, worstMiss);
    EXPECT_GT(largest, 0.005);
    EXPECT_LE(worstMiss, 0.1 * largest);
    EXPECT_EQ(h.size(), 18u);
}

TEST(ElevatorDemo, TractionTableHasEveryScenario) {
    const fs::path out = scratch("all");
    ASSERT_EQ(run("--t-end 0.5 --no-plots --quiet --out '" + out.string() + "'", out.string() + ".log"), 0);
    const nlohmann::json table = readJson(out / "summary.json").at("traction_table");
    ASSERT_EQ(table.size(), 4u);
    for (const auto& t : table) {
        EXPECT_TRUE(t.at("traction") == "held" || t.at("traction") == "slipped") << t.dump();
        for (const char* key : {"traction_limit", "largest_force_ratio", "traction_margin", "slip_distance_m",
                                "real_time_factor", "energy_residual_relative"})
            EXPECT_TRUE(t.contains(key)) << key;
    }
}

TEST(ElevatorDemo, BadInputExitsTwoAndWritesNothing) {
    for (const std::string& args : {std::string("--scenario nope"), std::string("--friction -1"),
                                    std::string("--retardation-time -0.1"), std::string("--t-end 0"),
                                    std::string("--rated-load abc")}) {
        const fs::path out = scratch("bad");
        EXPECT_EQ(run(args + " --out '" + out.string() + "'", out.string() + ".log"), 2) << args;
        EXPECT_FALSE(fs::exists(out / "summary.json")) << args;
    }
}
