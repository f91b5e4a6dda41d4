// The reeving-elevator executable end to end: the traction table in summary.json, the stalled
// counterweight slips (the car rises far less than the machine's rope travel would lift it; also at
// mu = 10), the trip follows its profile within the rope's stretch, 1:1 and 2:1, the 2:1 emergency
// stop decelerates the car at half the brake's rate, the figures include the machine's snapshots,
// bad input exits 2 and writes nothing.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// The trip of `roping` (1 or 2): the car's rise is the rope hauled in divided by the roping, up to
// the change of the car falls' stretch.
// The trip's bending cycles per section of the hoist ropes (rope_bending_trip.csv), counted by hand.
// Wrapped sheaves (the default), half a turn on each; the car rises by tripDistance = 12 m.
// 1:1: the traction sheave (R = 0.32 m) is the only sheave; 12 m of rope pass its arrival tangent
// point, and the sections that also leave its departure point, 12 - pi R = 10.995 m of rope, go
// over it once: 1 simple cycle each, 109.9 sections of 0.1 m (the run's rope travel is 12 m to
// within the change of stretch, millimetres); none more.
// 2:1: hitch -> car sheave (r = 0.2 m) -> traction sheave -> counterweight sheave (r) -> hitch. The
// rope moves 24 m over the traction sheave and 12 m over each of the others (relative to them). The
// rope runs over the traction sheave's top and under the counterweight's sheave: a reverse bend.
// The sections that pass the traction sheave and then the counterweight's sheave are those within
// 12 m of the latter's arrival point less what lies between the two (the traction sheave's arc and
// the counterweight's fall, l_cw = the counterweight sheave's depth below the traction sheave's axis)
// and the counterweight sheave's own arc: 12 - pi R - l_cw - pi r = 8.366 m at l_cw = 2.0008 m,
// 83.7 sections with 1 simple + 1 reverse cycle (3 weighted with w_r = 2), the most of any
// section; the car sheave's sections are not reached by the traction sheave (40 m of fall between).
void checkTripBending(int roping, const fs::path& out, double counterweightY, const nlohmann::json& life) {
    const double pi = std::acos(-1.0), R = 0.32, r = 0.2, lCw = -counterweightY;
    std::vector<std::string> h;
    const auto sections = readCsv(out / "rope_bending_trip.csv", h);
    const int cycles = column(h, "cycles"), simple = column(h, "simple_cycles"), reverse = column(h, "reverse_cycles");
    int once = 0, onceAndReverse = 0;
    double most = 0;
    for (const auto& v : sections) {
        most = std::max(most, v[cycles]);
        if (v[simple] == 1.0 && v[reverse] == 0.0) ++once;
        if (v[simple] == 1.0 && v[reverse] == 1.0) ++onceAndReverse;
    }
    const auto& worst = life.at("worst_section");
    if (roping == 1) {
        // (12 - pi R) / 0.1 = 109.9: the sections that straddle a band edge count half; bound +-1.
        EXPECT_NEAR(once, (12.0 - pi * R) / 0.1, 1.0) << "measured " << once;
        EXPECT_EQ(onceAndReverse, 0);
        EXPECT_EQ(most, 1.0);
        EXPECT_EQ(worst.at("min_diameter_ratio").get<double>(), 2 * R / 0.01);
    } else {
        const double expected = (12.0 - pi * R - lCw - pi * r) / 0.1;  // 83.7 at l_cw = 2.0008 m
        EXPECT_NEAR(onceAndReverse, expected, 1.5) << "measured " << onceAndReverse;
        EXPECT_EQ(most, 1.0 + 2.0);
        EXPECT_EQ(worst.at("simple_cycles").get<double>(), 1.0);
        EXPECT_EQ(worst.at("reverse_cycles").get<double>(), 1.0);
        EXPECT_EQ(worst.at("min_diameter_ratio").get<double>(), 2 * r / 0.01);
    }
}

void checkTrip(int roping) {
    const fs::path out = scratch("trip" + std::to_string(roping));
    ASSERT_EQ(run("--scenario trip --roping " + std::to_string(roping) +
                      ":1 --reverse-bend-factor 2 --no-plots --quiet --out '" + out.string() + "'",
                  out.string() + ".log"),
              0);
    const nlohmann::json s = readJson(out / "summary.json");
    EXPECT_EQ(s.at("roping"), std::to_string(roping) + ":1");
    const nlohmann::json t = s.at("traction_table").at(0);
    EXPECT_EQ(t.at("traction"), "held");
    EXPECT_GT(t.at("traction_margin").get<double>(), 1.0);
    std::vector<std::string> h;
    const auto rows = readCsv(out / "timeseries_trip.csv", h);
    const int cy = column(h, "car_y_m"), tr = column(h, "rope_travel_m"), pa = column(h, "car_side_force_N");
    // The car's rise equals the rope hauled in (-travel) / roping up to the change of a car fall's
    // stretch, P l / EA with l = 40 m - rise (the rope set's EA = 16 MN; P at the sheave, the fall's
    // mean force is lower by half its weight, 1.7 % in 1:1; in 2:1 the two car falls each stretch by
    // P l / EA and the car takes half of their sum): 1:1 4.1 cm at the start, 1.2 cm less at the end.
    double worstMiss = 0, largest = 0;
    const double l0 = 40.0, EA = 1.6e7;
    for (const auto& r : rows) {
        const double rise = r[cy] - rows[0][cy];
        const double predicted = (r[pa] * (l0 - rise) - rows[0][pa] * l0) / EA;  // stretch change [m]
        worstMiss = std::max(worstMiss, std::abs((rise - (-r[tr]) / roping) - (-predicted)));
        largest = std::max(largest, std::abs(predicted));
    }
    // At rest the car fall at the sheave carries 1 / roping of the car and its own weight (40 m of
    // 1.4 kg/m; in 2:1 the fall from the car sheave).
    const double carWeight = (1000.0 + 630.0) * 9.81, fallWeight = 1.4 * 9.81 * 40.0;
    const double atRest = carWeight / roping + fallWeight;
    std::printf("trip %d:1: largest stretch change %.4f m, car path off it by at most %.5f m; car fall at rest "
                "%.1f N vs %.1f N\n",
                roping, largest, worstMiss, rows[0][pa], atRest);
    EXPECT_GT(largest, 0.005 / roping);
    // Measured: 1:1 0.25 mm of 16 mm (1.6 %); 2:1 0.54 mm of 8.4 mm (6.4 %: the one-fall stretch
    // model above leaves out how the car's frictionless sheave shares the stretch between the two
    // falls while they accelerate). Bounds 10 % and 70 %: a wrong roping ratio misses by metres.
    EXPECT_LE(worstMiss, (roping == 1 ? 0.1 : 0.7) * largest);
    // Measured 0.42 % (1:1) and 0.65 % (2:1) low: one sine mode (n_a = 1) represents the fall's
    // linear strain gradient under its weight with an error at its ends.
    EXPECT_NEAR(rows[0][pa] / atRest, 1.0, 0.02);
    EXPECT_EQ(h.size(), 20u);
    checkTripBending(roping, out, rows[0][column(h, "counterweight_y_m")], t.at("rope_life"));
}

TEST(ElevatorDemo, TripFollowsItsProfileWithinTheRopeStretchAndHolds) { checkTrip(1); }

TEST(ElevatorDemo, TwoToOneTripMovesTheCarHalfTheRopeTravelAndHolds) { checkTrip(2); }

// The stall at mu = 10 (e^(mu alpha) = 4.4e13): the counterweight's fall is slack, so the groove
// still cannot haul the car up, and the slack side must not break the traction sheave (it did
// before the tension-ratio row was scaled: RopeModel's weightBefore_ / weightAfter_). With the
// figures: the machine's snapshots are drawn.
// Energy: closes to 1.2e-6 of the largest term (7 transitions; at af00e15, Newton at 1e-15, the run
// chattered for 15 ms at t = 4.25 s, 3 421 transitions, and closed to 1.3e-6: see TractionSheave);
// with n_a = 0 (one transition) to 2.2e-7.
// Point sheaves for n_a = 1: with wrapped ones the counterweight's fall hangs vertical from its
// tangent point, and once it is slack its quasi-static axial amplitude has no stiffness left
// against the fall's weight along its chord: the dependent coordinates' Newton stalls at
// t = 1.49 s (residual 1.1e-6 in strain; docs/elevator.md). The wrapped model runs below with
// n_a = 0.
TEST(ElevatorDemo, StallSlipsAtLargeFrictionToo) {
    const fs::path out = scratch("stall_mu10");
    ASSERT_EQ(run("--scenario stall --friction 10 --sheaves point --quiet --out '" + out.string() + "'",
                  out.string() + ".log"),
              0);
    const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
    EXPECT_EQ(t.at("traction"), "slipped");
    std::vector<std::string> h;
    const auto rows = readCsv(out / "timeseries_stall.csv", h);
    const double rise = rows.back()[column(h, "car_y_m")] - rows[0][column(h, "car_y_m")];
    const double travel = -rows.back()[column(h, "rope_travel_m")];
    std::printf("stall at mu = 10: car rose %.4f m for %.3f m of rope driven\n", rise, travel);
    EXPECT_GT(travel, 2.0);
    EXPECT_LT(rise, 0.1 * travel);  // measured 0.076 m of 2.5 m (0.042 m at af00e15: sensitive to round-off)
    EXPECT_LE(t.at("energy_residual_relative").get<double>(), 1e-5);  // measured 1.2e-6
    const bool gnuplot = std::system("command -v gnuplot > /dev/null 2>&1") == 0;
    if (gnuplot) {
        ASSERT_TRUE(fs::exists(out / "elevator_stall_machine.png"));
        EXPECT_GT(fs::file_size(out / "elevator_stall_machine.png"), 10000u);
        EXPECT_GT(fs::file_size(out / "elevator_stall.png"), 10000u);
    }
    const fs::path out0 = scratch("stall_mu10_na0");
    ASSERT_EQ(run("--scenario stall --friction 10 --axial-modes 0 --no-plots --quiet --out '" + out0.string() + "'",
                  out0.string() + ".log"),
              0);
    const nlohmann::json t0 = readJson(out0 / "summary.json").at("traction_table").at(0);
    EXPECT_EQ(t0.at("traction"), "slipped");
    EXPECT_LE(t0.at("energy_residual_relative").get<double>(), 1e-5);  // measured 9.2e-7 (wrapped)
    if (!gnuplot) GTEST_SKIP() << "gnuplot not found: elevator_stall*.png were not checked (the other checks ran)";
}

// The compensating rope (--compensation) carries the hoist ropes' weight across. The trip moves the
// car up 12 m: without compensation the weight of 12 m of hoist rope goes from the car side to the
// counterweight side and the force ratio at rest changes by ln(r1 / r0) = -2.27 % (the static
// ratio (M_car g + w l_car) / (M_cwt g + w l_cwt), w = rhoA g, l the falls' lengths); with it the
// ratio keeps its value. Both runs also see the point sheave's chord to the sheave's centre, which
// leans the short counterweight fall (2 m long, 0.32 m off: 9 degrees) and raises its force by
// 1 / cos: that change is common to both, so the test compares the difference of the two runs'
// ln(r1 / r0) with the rope weight's. Rope damping (c = 0.05 s) lets the car settle after the stop.
TEST(ElevatorDemo, CompensationCarriesTheHoistRopesWeightAcross) {
    double change[2] = {0, 0}, predicted = 0;
    for (int compensated = 0; compensated < 2; ++compensated) {
        const fs::path out = scratch("comp" + std::to_string(compensated));
        ASSERT_EQ(run(std::string("--scenario trip --retardation-time 0.05 --no-plots --quiet ") +
                          (compensated ? "--compensation " : "") + "--out '" + out.string() + "'",
                      out.string() + ".log"),
                  0);
        const nlohmann::json s = readJson(out / "summary.json");
        EXPECT_EQ(s.at("compensation"), compensated == 1);
        EXPECT_EQ(s.at("traction_table").at(0).at("traction"), "held");
        std::vector<std::string> h;
        const auto rows = readCsv(out / "timeseries_trip.csv", h);
        const int ratio = column(h, "force_ratio"), pit = column(h, "pit_sheave_y_m");
        const int cy = column(h, "car_y_m"), wy = column(h, "counterweight_y_m");
        change[compensated] = std::log(rows.back()[ratio] / rows.front()[ratio]);  // both at rest
        EXPECT_EQ(std::isfinite(rows.back()[pit]), compensated == 1);
        if (!compensated) {
            const double g = 9.81, w = 1.4 * g, car = 1630 * g, cwt = 1315 * g;
            auto ratioAt = [&](const std::vector<double>& r) { return (car - w * r[cy]) / (cwt - w * r[wy]); };
            predicted = std::log(ratioAt(rows.back()) / ratioAt(rows.front()));
        }
    }
    const double weightEffect = change[0] - change[1];
    std::printf("ln(r1 / r0) over the trip: %.5e without compensation, %.5e with; difference %.5e, rope weight "
                "%.5e\n",
                change[0], change[1], weightEffect, predicted);
    EXPECT_LT(predicted, -0.02);
    EXPECT_NEAR(weightEffect / predicted, 1.0, 0.05);  // measured 0.7 % off (n_a = 1, leaning falls)
}

// The traction sheave's energy balance on the elevator itself, with its default quasi-static axial modes: the
// emergency stop sticks, slips and sticks again (2 transitions), and E(t) - E(0) + W_friction +
// W_damping - W_machine stays within 1e-6 of the largest term (measured 4.1e-7; 1.9e-5
// if the slipping node's condensed amplitudes carry the ratio's multiplier).
TEST(ElevatorDemo, EmergencyStopEnergyClosesThroughStickSlipStick) {
    const fs::path out = scratch("stop_energy");
    ASSERT_EQ(run("--scenario emergency-stop --no-plots --quiet --out '" + out.string() + "'", out.string() + ".log"), 0);
    const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
    std::printf("emergency stop: %d transitions, energy residual %.3e of the largest term\n",
                t.at("stick_slip_transitions").get<int>(), t.at("energy_residual_relative").get<double>());
    EXPECT_EQ(t.at("stick_slip_transitions"), 2);
    EXPECT_GT(t.at("friction_work_J").get<double>(), 0);
    EXPECT_LE(t.at("energy_residual_relative").get<double>(), 1e-6);
}

// The emergency stop with Kelvin-Voigt rope damping (c = 0.01 s): it starts from the same steady
// descent as without damping (findStaticEquilibrium balances the system at rest, not against the
// damping of rope dragged over the braking sheave: before that the damped run started 16 mm lower,
// already slipping, and slid the wrong way, friction work -45.7 kJ), slips towards the car side
// and sticks again: measured slip 0.1177 m against 0.1164 m undamped (1.1 %), friction work
// 1072 J against 1061 J, damping work 12.7 J, energy residual 5.4e-8.
TEST(ElevatorDemo, EmergencyStopWithRopeDampingSlipsAsWithout) {
    auto stop = [](const std::string& name, const std::string& extra, std::vector<double>& first) {
        const fs::path out = scratch(name);
        EXPECT_EQ(run("--scenario emergency-stop --no-plots --quiet " + extra + " --out '" + out.string() + "'",
                      out.string() + ".log"),
                  0);
        std::vector<std::string> header;
        const auto rows = readCsv(out / "timeseries_emergency-stop.csv", header);
        first = {rows.at(0).at(column(header, "car_y_m")), rows.at(0).at(column(header, "car_a_mps2"))};
        return readJson(out / "summary.json").at("traction_table").at(0);
    };
    std::vector<double> plain0, damped0;
    const nlohmann::json plain = stop("stop_plain", "", plain0);
    const nlohmann::json damped = stop("stop_damped", "--retardation-time 0.01", damped0);
    std::printf("damped stop: start %.9f m (undamped %.9f m), a0 %.4f m/s^2; slip %.4f m (undamped %.4f m), "
                "friction %.1f J, damping %.2f J, residual %.2e\n",
                damped0[0], plain0[0], damped0[1], damped.at("slip_distance_m").get<double>(),
                plain.at("slip_distance_m").get<double>(), damped.at("friction_work_J").get<double>(),
                damped.at("damping_work_J").get<double>(), damped.at("energy_residual_relative").get<double>());
    EXPECT_NEAR(damped0[0], plain0[0], 1e-9);  // the same equilibrium (measured equal to 1e-10)
    EXPECT_LT(std::abs(damped0[1]), 0.1);      // steady descent (measured -0.009: the rope flowing through its weight gradient)
    EXPECT_EQ(damped.at("stick_slip_transitions"), 2);
    EXPECT_GT(damped.at("friction_work_J").get<double>(), 0);
    EXPECT_GT(damped.at("damping_work_J").get<double>(), 0);
    EXPECT_NEAR(damped.at("slip_distance_m").get<double>() / plain.at("slip_distance_m").get<double>(), 1.0,
                0.05);  // measured 1.011
    EXPECT_LE(damped.at("energy_residual_relative").get<double>(), 1e-6);
}

// Roped 2:1 the emergency stop holds: the car decelerates at half the surface's 3 m/s^2. The brake
// stops the sheave along the scene's quintic (ElevatorScene: surface speed roping v (1 - r(t / T)),
// r(u) = 6 u^5 - 15 u^4 + 10 u^3, T = 15 roping v / (8 a_brake) = 2 s, the demo's v = 1.6 m/s and
// a_brake = 3 m/s^2), so a car gripped by the rope decelerates at
//     a(t) = (v / T) 30 (u^4 - 2 u^3 + u^2),  peak a_brake / roping = 1.5 m/s^2 at u = 1/2,
// and stops from v in T: mean deceleration v / T = 0.8 m/s^2. (The traction would allow more: with
// the falls' weight and the moving rope's inertia the force ratio reaches e^(mu alpha) = 1.874 at
// a car deceleration of about 1.96 m/s^2.) The car rides this on its ropes, a 5 Hz oscillator
// (k = 2 EA / l = 1.6 MN/m for 1630 kg on two 20 m falls), started by the brake's onset and by the
// steady descent leaving the static equilibrium of t = 0.
TEST(ElevatorDemo, TwoToOneEmergencyStopHolds) {
    const fs::path out = scratch("stop21");
    ASSERT_EQ(run("--scenario emergency-stop --roping 2:1 --no-plots --quiet --out '" + out.string() + "'",
                  out.string() + ".log"),
              0);
    const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
    std::printf("2:1 emergency stop: %s, margin %.4f\n", t.at("traction").get<std::string>().c_str(),
                t.at("traction_margin").get<double>());
    EXPECT_EQ(t.at("traction"), "held");
    EXPECT_GT(t.at("traction_margin").get<double>(), 1.0);  // measured 1.095
    EXPECT_EQ(t.at("stick_slip_transitions"), 0);
    std::vector<std::string> h;
    const auto rows = readCsv(out / "timeseries_emergency-stop.csv", h);
    const int ct = column(h, "t_s"), ca = column(h, "car_a_mps2"), cv = column(h, "car_v_mps");
    const double v = 1.6, aBrake = 3.0, roping = 2, T = 15 * roping * v / (8 * aBrake);
    double worstMiss = 0, peak = 0, vEnd = NAN;
    for (const auto& r : rows) {
        const double u = std::min(std::max(r[ct] / T, 0.0), 1.0);
        const double profile = v / T * 30 * (u * u * u * u - 2 * u * u * u + u * u);
        worstMiss = std::max(worstMiss, std::abs(r[ca] - profile));
        peak = std::max(peak, r[ca]);  // up: the descending car decelerating
        if (std::abs(r[ct] - T) < 1e-9) vEnd = r[cv];
    }
    const double meanDeceleration = (vEnd - rows.at(0)[cv]) / T;
    std::printf("2:1 emergency stop: peak car deceleration %.4f m/s^2 (brake %.2f / %.0f), worst miss of the profile "
                "%.4f m/s^2, mean deceleration over the brake %.5f m/s^2 (v / T %.3f)\n",
                peak, aBrake, roping, worstMiss, meanDeceleration, v / T);
    // Measured: the car's acceleration off the profile by at most 0.047 m/s^2 (at t = 0.06 s, the
    // oscillation on the ropes), peak 1.542 m/s^2. Bound 0.5 m/s^2 (10x): a car braked at the
    // surface's rate (3 m/s^2, the 1:1 kinematics) or not held by the traction (slipping at the
    // traction limit, or not braked) misses by 1.5 m/s^2 at the peak.
    EXPECT_LE(worstMiss, 0.5);
    EXPECT_NEAR(peak, aBrake / roping, 0.5);
    // Measured 0.80 m/s^2 to 4.2e-4 (the car's speed at T: 8.4e-4 m/s, the oscillation); bound 0.01
    // m/s^2 (24x); the surface's rate would give 1.6 m/s^2.
    EXPECT_NEAR(meanDeceleration, v / T, 0.01);
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

// --sheaves point|wrapped: both models run the 2:1 compensated loading check (the car's, the
// counterweight's and the pit sheave are the ones the option sets) and report their model.
TEST(ElevatorDemo, SheaveModels) {
    double ratio[2] = {0, 0};
    int i = 0;
    for (const std::string model : {"point", "wrapped"}) {
        const fs::path out = scratch("sheaves-" + model);
        ASSERT_EQ(run("--scenario loading --roping 2:1 --compensation --t-end 0.5 --sheaves " + model +
                          " --no-plots --quiet --out '" + out.string() + "'",
                      out.string() + ".log"),
                  0)
            << model;
        const nlohmann::json summary = readJson(out / "summary.json");
        EXPECT_EQ(summary.at("sheaves"), model);
        const nlohmann::json t = summary.at("traction_table").at(0);
        EXPECT_EQ(t.at("traction"), "held") << model;
        ratio[i++] = t.at("largest_force_ratio").get<double>();
    }
    // The models differ by the falls' lean and the rope on the grooves: measured 1.2904 (point) and
    // 1.3160 (wrapped); that they differ by more than 1e-3 (26x under the measured 0.026) shows the
    // option reached the scene.
    std::printf("2:1 compensated loading: largest force ratio %.4f (point), %.4f (wrapped)\n", ratio[0], ratio[1]);
    EXPECT_GT(std::abs(ratio[0] - ratio[1]), 1e-3);
}

// --deflector with the car's hitch off the tangent (--car-hitch-offset 0.15): the trip reports the
// traction sheave's wrap angle at every row, equal to the closed form pi - theta - psi at the
// car's height there (measured at most 5.0e-10 rad, the CSV's 10 digits; bound 1e-8 rad), its
// range in the traction table (2.7052 .. 2.7068 rad), and the capstan limit of that geometry.
TEST(ElevatorDemo, DeflectorSetsTheWrapAngleOverTheTrip) {
    const fs::path out = scratch("deflector");
    ASSERT_EQ(run("--scenario trip --deflector --car-hitch-offset 0.15 --no-plots --quiet --out '" + out.string() + "'",
                  out.string() + ".log"),
              0);
    const nlohmann::json summary = readJson(out / "summary.json");
    EXPECT_EQ(summary.at("deflector"), true);
    const nlohmann::json t = summary.at("traction_table").at(0);
    EXPECT_EQ(t.at("traction"), "held");
    const double lo = t.at("wrap_angle_min_rad").get<double>(), hi = t.at("wrap_angle_max_rad").get<double>();
    EXPECT_GT(lo, 2.70);
    EXPECT_LT(hi, 2.71);
    EXPECT_GT(hi - lo, 1e-3);  // the car moved its fall's lean
    const double limit = t.at("traction_limit").get<double>();
    EXPECT_GE(limit, std::exp(0.2 * lo) * (1 - 1e-12));
    EXPECT_LE(limit, std::exp(0.2 * hi) * (1 + 1e-12));
    std::vector<std::string> h;
    const auto rows = readCsv(out / "timeseries_trip.csv", h);
    const int wrap = column(h, "wrap_angle_rad"), carY = column(h, "car_y_m");
    const double R = 0.32, e = 0.15, rd = 0.2, dx = 0.7 - rd, drop = 0.8;  // the demo's geometry
    const double theta = std::atan2(dx, drop) + std::asin((rd - R) / std::hypot(dx, drop));
    double worst = 0;
    for (const auto& row : rows) {
        const double y = row[carY], rho = std::hypot(R + e, y);
        const double psi = std::acos(R / rho) - std::atan2(-y, R + e);
        worst = std::max(worst, std::abs(row[wrap] - (std::acos(-1.0) - theta - psi)));
    }
    std::printf("deflector trip: wrap angle %.5f .. %.5f rad, worst off the closed form %.1e rad over %zu rows\n", lo,
                hi, worst, rows.size());
    EXPECT_LE(worst, 1e-8);
    // Per sheave: the traction sheave (node 1) as above, the deflector (node 2) wrapped by theta,
    // fixed by the two fixed grooves (measured 4.5e-13 rad, the JSON's 12 digits; bound 1e-9 rad).
    const nlohmann::json sheaves = t.at("sheave_wrap_angles");
    ASSERT_EQ(sheaves.size(), 2u);
    EXPECT_EQ(sheaves.at(0).at("node"), 1);
    EXPECT_EQ(sheaves.at(0).at("min_rad").get<double>(), lo);
    EXPECT_EQ(sheaves.at(1).at("node"), 2);
    EXPECT_NEAR(sheaves.at(1).at("min_rad").get<double>(), theta, 1e-9);
    EXPECT_NEAR(sheaves.at(1).at("max_rad").get<double>(), theta, 1e-9);
    EXPECT_EQ(t.at("max_fleet_angle_rad"), 0.0);
}

// --traction-slip momentum (TractionSlip::RopeMomentum) on the stall: the rope slips the same 2.4887
// m (measured 1.0e-5 m from the massless contact point's; bound 1e-3 m), the energy still closes
// (measured 1.0e-7 of the machine's work; bound 1e-5), and the rope's inertia at the groove makes
// the force ratio overshoot the capstan limit at the slip's onset and ring (largest ratio 2.08
// against the limit 1.87: more than 1 % over it shows the option reached the scene).
TEST(ElevatorDemo, RopeMomentumSlipOnTheStall) {
    nlohmann::json t[2];
    const char* models[] = {"constraint", "momentum"};
    for (int m = 0; m < 2; ++m) {
        const fs::path out = scratch(std::string("slip_") + models[m]);
        ASSERT_EQ(run(std::string("--scenario stall --traction-slip ") + models[m] + " --no-plots --quiet --out '" +
                          out.string() + "'",
                      out.string() + ".log"),
                  0);
        const nlohmann::json summary = readJson(out / "summary.json");
        EXPECT_EQ(summary.at("traction_slip"), models[m]);
        t[m] = summary.at("traction_table").at(0);
        EXPECT_EQ(t[m].at("traction"), "slipped");
        EXPECT_LE(t[m].at("energy_residual_relative").get<double>(), 1e-5);
    }
    const double d0 = t[0].at("slip_distance_m").get<double>(), d1 = t[1].at("slip_distance_m").get<double>();
    const double limit = t[1].at("traction_limit").get<double>(), ratio = t[1].at("largest_force_ratio").get<double>();
    std::printf("stall: slip %.6f m (constraint), %.6f m (momentum); momentum's largest ratio %.4f, limit %.4f\n", d0,
                d1, ratio, limit);
    EXPECT_NEAR(d1, d0, 1e-3);
    EXPECT_GT(ratio, 1.01 * limit);
    EXPECT_NEAR(t[0].at("largest_force_ratio").get<double>(), limit, 1e-6 * limit);
}

// The wrapped stall at mu = 10 (e^(mu alpha) = 4.4e13) fails with the capstan row (its slack fall's
// quasi-static amplitude loses its equilibrium, docs/elevator.md) and completes with the rope's
// momentum at the groove: it slips, and the energy closes (measured 7.8e-7 of the largest term;
// bound 1e-5).
TEST(ElevatorDemo, RopeMomentumSlipCompletesTheWrappedStallAtMu10) {
    const fs::path out = scratch("stall_mu10_momentum");
    ASSERT_EQ(run("--scenario stall --friction 10 --traction-slip momentum --no-plots --quiet --out '" + out.string() +
                      "'",
                  out.string() + ".log"),
              0);
    const nlohmann::json t = readJson(out / "summary.json").at("traction_table").at(0);
    EXPECT_EQ(t.at("traction"), "slipped");
    EXPECT_EQ(t.at("simulated_s").get<double>(), 6.0);
    EXPECT_LE(t.at("energy_residual_relative").get<double>(), 1e-5);
}

TEST(ElevatorDemo, BadInputExitsTwoAndWritesNothing) {
    for (const std::string& args : {std::string("--scenario nope"), std::string("--friction -1"),
                                    std::string("--retardation-time -0.1"), std::string("--t-end 0"),
                                    std::string("--rated-load abc"), std::string("--roping 3:1"),
                                    std::string("--sheaves bogus"), std::string("--deflector --roping 2:1"),
                                    std::string("--deflector --sheaves point"), std::string("--car-hitch-offset 0.7"),
                                    std::string("--traction-slip sliding"), std::string("--rope-diameter 0.8"),
                                    std::string("--reverse-bend-factor 0.5"), std::string("--section-length 0")}) {
        const fs::path out = scratch("bad");
        EXPECT_EQ(run(args + " --out '" + out.string() + "'", out.string() + ".log"), 2) << args;
        EXPECT_FALSE(fs::exists(out / "summary.json")) << args;
    }
}
