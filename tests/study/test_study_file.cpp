// The study file's parser (study/StudyFile.h): what a good file gives, and for each kind of bad
// input the exact words of the one error, with the place (FILE:LINE:COLUMN) it names.
#include "StudyFile.h"

#include "support/ExpectThrowMessage.h"

#include <gtest/gtest.h>

#include <string>

using study::parseStudy;
using study::Study;
using study::StudyError;

namespace {

Study parse(const std::string& text) { return parseStudy(text, "s.yaml"); }

}  // namespace

TEST(StudyFile, ReadsEveryPart) {
    const Study s = parse(
        "scene: elevator\n"
        "scenario: emergency-stop\n"
        "description: traction map\n"
        "fixed: {axial-modes: 1, set.M: 5000, compensation: true}\n"
        "vary:\n"
        "  car-load: {values: [0, 0.5, 1.25]}\n"
        "  friction: [0.1, 0.2]\n"
        "  car-position: {linear: {from: 2, to: 38, count: 4}}\n"
        "  retardation-time: {log: {from: 0.001, to: 0.1, count: 3}}\n"
        "sample: {method: latin-hypercube, count: 2, seed: 7, parameters: {rated-load: {from: 400, to: 800}, "
        "accuracy: {from: 1e-8, to: 1e-4, scale: log}}}\n"
        "metrics: [traction_table.0.traction_margin, wall_seconds, traction_table.0.traction]\n"
        "limits: {wall_seconds: 60, max_steps: 100000}\n"
        "figures:\n"
        "  - {type: lines, x: car-load, y: traction_table.0.traction_margin}\n"
        "  - {type: heatmap, x: car-position, y: car-load, z: traction_table.0.traction_margin, boundary: 1, name: map}\n");
    EXPECT_EQ(s.scene->name, "elevator");
    EXPECT_EQ(s.scene->program, "reeving-elevator");
    EXPECT_EQ(s.description, "traction map");
    ASSERT_EQ(s.fixed.size(), 4u);
    EXPECT_EQ(s.fixed[0].name, "scenario");
    EXPECT_EQ(s.fixed[0].value, "emergency-stop");
    EXPECT_EQ(s.fixed[2].name, "set.M");
    EXPECT_EQ(s.fixed[2].value, "5000");
    EXPECT_EQ(s.fixed[2].place.line, 4);
    ASSERT_EQ(s.vary.size(), 4u);
    EXPECT_EQ(s.vary[0].values, (std::vector<std::string>{"0", "0.5", "1.25"}));
    EXPECT_EQ(s.vary[0].valuePlaces[1].line, 6);
    EXPECT_EQ(s.vary[0].valuePlaces[1].column, 26);
    EXPECT_EQ(s.vary[1].values, (std::vector<std::string>{"0.1", "0.2"}));
    EXPECT_EQ(s.vary[2].values, (std::vector<std::string>{"2", "14", "26", "38"}));
    EXPECT_EQ(s.vary[3].values, (std::vector<std::string>{"0.001", "0.01", "0.1"}));
    ASSERT_TRUE(s.sample.has_value());
    EXPECT_EQ(s.sample->count, 2);
    EXPECT_EQ(s.sample->seed, 7u);
    ASSERT_EQ(s.sample->parameters.size(), 2u);
    EXPECT_TRUE(s.sample->parameters[1].logScale);
    ASSERT_EQ(s.metrics.size(), 2u);  // wall_seconds is the runner's
    EXPECT_TRUE(s.wallSecondsListed);
    EXPECT_EQ(s.limits.wallSeconds, 60.0);
    EXPECT_EQ(s.limits.maxSteps, 100000);
    ASSERT_EQ(s.figures.size(), 2u);
    EXPECT_EQ(s.figures[0].name, "traction_table_0_traction_margin_over_car-load");
    EXPECT_EQ(s.figures[1].name, "map");
    EXPECT_EQ(*s.figures[1].boundary, 1.0);
}

TEST(StudyFile, RangesEndExactlyAtTheirEnds) {
    const Study s = parse("scene: crane\nvary:\n  hoist-speed: {linear: {from: 0.1, to: 0.5, count: 5}}\n"
                          "  set.initialHookDepth: {log: {from: 5, to: 40, count: 4}}\n  x: {linear: {from: 3, to: 4, count: 1}}\n"
                          "metrics: [steps]\n");
    EXPECT_EQ(s.vary[0].values, (std::vector<std::string>{"0.1", "0.2", "0.3", "0.4", "0.5"}));
    EXPECT_EQ(s.vary[1].values, (std::vector<std::string>{"5", "10", "20", "40"}));
    EXPECT_EQ(s.vary[2].values, (std::vector<std::string>{"3"}));
}

TEST(StudyFile, MissingOrMalformedFile) {
    EXPECT_THROW_MESSAGE(study::loadStudy("/no/such/study.yaml"), StudyError,
                         "/no/such/study.yaml: cannot read the study file: No such file or directory");
    EXPECT_THROW_MESSAGE(parse(""), StudyError, "s.yaml: the study file is empty (it needs scene: and metrics:)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nvary: {friction: [0.1, 0.2}\n"), StudyError,
                         "s.yaml:2:27: malformed YAML: illegal flow end");
    EXPECT_THROW_MESSAGE(parse("- scene\n- elevator\n"), StudyError,
                         "s.yaml:1:1: a study file is a map of keys (scene, fixed, vary, metrics, ...)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [steps]\nmetrix: [x]\n"), StudyError,
                         "s.yaml:3:1: unknown key 'metrix' (a study file has: scene, scenario, description, fixed, "
                         "vary, sample, metrics, limits, figures)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nscene: crane\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:1: 'scene' is given twice (also at 1:1)");
    EXPECT_THROW_MESSAGE(parse("metrics: [steps]\n"), StudyError, "s.yaml:1:1: no scene: (one of pendulum, crane, elevator)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\n"), StudyError,
                         "s.yaml:1:1: no metrics: (a list of summary.json paths to collect, e.g. [steps])");
}

TEST(StudyFile, UnknownSceneOrScenario) {
    EXPECT_THROW_MESSAGE(parse("scene: cran\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:1:8: unknown scene 'cran' (one of pendulum, crane, elevator)");
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nscenario: lift-off\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:1: scene pendulum has no scenarios (its demo has no --scenario)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nscenario: [trip, stall]\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:11: scenario must be one value, not a list or a map");
    // A scenario name the demo does not know is its --check's to reject (test_study_runs).
}

TEST(StudyFile, BadParameters) {
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {Friction: 0.2}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:9: 'Friction' is not a demo option's name (a long option without its dashes, such "
                         "as t-end, or set.KEY for --set KEY=...)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {out: x}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:9: 'out' is not a study parameter: the runner gives each case its own output folder");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {max-steps: 9}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:9: 'max-steps' is not a study parameter: set it for every case with limits: "
                         "{max_steps: N}");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {friction: 0.2}\nvary: {friction: [0.1, 0.3]}\nmetrics: [steps]\n"),
                         StudyError, "s.yaml:3:8: parameter 'friction' is given twice (also at 2:9)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {friction: [0.1, 0.2]}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:19: fixed 'friction' must be one value (vary: takes a list or a range)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nfixed: {friction: }\nmetrics: [steps]\n"), StudyError,
                         "fixed 'friction' has no value");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nvary: {friction: 0.2}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:18: vary 'friction' needs several values: a list [a, b], {values: [...]}, {linear: "
                         "{from, to, count}} or {log: {from, to, count}} (one value goes under fixed:)");
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nfixed: {t-end: 1}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:1:8: scene pendulum needs axial-modes (fixed: or vary:): each case runs one value "
                         "(reeving-pendulum's default runs several, one summary each)");
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nfixed: {axial-modes: '0,1'}\nmetrics: [steps]\n"), StudyError,
                         "s.yaml:2:22: axial-modes '0,1': one value per case (vary: lists several)");
    // A parameter the demo does not have is its --check's to reject (test_study_runs).
}

TEST(StudyFile, EmptyOrInvertedRanges) {
    auto vary = [](const std::string& spec) { return parse("scene: elevator\nvary:\n  friction: " + spec + "\nmetrics: [steps]\n"); };
    EXPECT_THROW_MESSAGE(vary("[]"), StudyError, "s.yaml:3:13: vary 'friction': the list of values is empty");
    EXPECT_THROW_MESSAGE(vary("{values: []}"), StudyError, "s.yaml:3:22: vary 'friction': the list of values is empty");
    EXPECT_THROW_MESSAGE(vary("[0.1, 0.2, 0.1]"), StudyError,
                         "s.yaml:3:24: vary 'friction': value '0.1' is listed twice (also at 3:14)");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.3, to: 0.1, count: 3}}"), StudyError,
                         "s.yaml:3:22: vary 'friction' linear: inverted range: from (0.3) must be below to (0.1)");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.2, to: 0.2, count: 3}}"), StudyError,
                         "s.yaml:3:22: vary 'friction' linear: empty range: from and to are both 0.2");
    EXPECT_THROW_MESSAGE(vary("{log: {from: 0, to: 1, count: 3}}"), StudyError,
                         "s.yaml:3:19: vary 'friction' log: a log range needs from > 0 (got 0)");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.1, to: 0.2, count: 0}}"), StudyError,
                         "s.yaml:3:50: vary 'friction' linear count must be in 1..1000000, not 0");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.1, to: 0.2, count: 2.5}}"), StudyError,
                         "s.yaml:3:50: vary 'friction' linear count: '2.5' is not an integer");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: abc, to: 0.2, count: 2}}"), StudyError,
                         "s.yaml:3:29: vary 'friction' linear from: 'abc' is not a finite number");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.1, count: 2}}"), StudyError,
                         "s.yaml:3:22: vary 'friction' linear needs 'to'");
    EXPECT_THROW_MESSAGE(vary("{linear: {from: 0.1, to: 0.2, count: 2}, values: [1]}"), StudyError,
                         "s.yaml:3:13: vary 'friction' takes one of values: [...], linear: {from, to, count}, log: "
                         "{from, to, count}");
    EXPECT_THROW_MESSAGE(vary("{range: [1, 2]}"), StudyError,
                         "s.yaml:3:14: vary 'friction': unknown key 'range' (known: values, linear, log)");
}

TEST(StudyFile, BadSample) {
    auto sample = [](const std::string& spec) { return parse("scene: elevator\nsample: " + spec + "\nmetrics: [steps]\n"); };
    EXPECT_THROW_MESSAGE(sample("{method: sobol, count: 4, parameters: {friction: {from: 0.1, to: 0.2}}}"), StudyError,
                         "s.yaml:2:18: unknown sample method 'sobol' (latin-hypercube)");
    EXPECT_THROW_MESSAGE(sample("{method: latin-hypercube, count: 0, parameters: {friction: {from: 0.1, to: 0.2}}}"),
                         StudyError, "s.yaml:2:42: sample count must be in 1..1000000, not 0");
    EXPECT_THROW_MESSAGE(sample("{method: latin-hypercube, count: 4, parameters: {friction: {from: 0.3, to: 0.2}}}"),
                         StudyError,
                         "s.yaml:2:68: sample 'friction': inverted range: from (0.3) must be below to (0.2)");
    EXPECT_THROW_MESSAGE(
        sample("{method: latin-hypercube, count: 4, parameters: {friction: {from: 0.1, to: 0.2, scale: cubic}}}"),
        StudyError, "s.yaml:2:96: sample 'friction': scale must be linear or log, not 'cubic'");
    EXPECT_THROW_MESSAGE(sample("{method: latin-hypercube, count: 4, parameters: {}}"), StudyError,
                         "s.yaml:2:57: sample parameters: the map is empty");
    EXPECT_THROW_MESSAGE(sample("{method: latin-hypercube, count: 4}"), StudyError, "s.yaml:2:9: sample needs 'parameters'");
}

TEST(StudyFile, UnknownMetric) {
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [traction_margin]\n"), StudyError,
                         "s.yaml:2:11: unknown metric 'traction_margin' for scene elevator (did you mean "
                         "traction_table.0.traction_margin?)");
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nfixed: {axial-modes: 0}\nmetrics: [steps, peak_force]\n"), StudyError,
                         "s.yaml:3:18: unknown metric 'peak_force' for scene pendulum (reeving-pendulum's summary.json "
                         "has integrator, accuracy,");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [traction_table.x.steps]\n"), StudyError,
                         "s.yaml:2:11: unknown metric 'traction_table.x.steps' for scene elevator (did you mean "
                         "traction_table.0.steps?)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [friction, friction]\n"), StudyError,
                         "s.yaml:2:21: metric 'friction' is listed twice (also at 2:11)");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: []\n"), StudyError, "s.yaml:2:10: metrics: the list is empty");
    EXPECT_NO_THROW(parse("scene: crane\nmetrics: [parameters.payloadMass, max_fall_axial_force_N.3]\n"));
    // The scene parameters are listed key by key: a misspelt one is found before any case runs.
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nfixed: {axial-modes: 0}\nmetrics: [parameters.Ea]\n"), StudyError,
                         "s.yaml:3:11: unknown metric 'parameters.Ea' for scene pendulum (reeving-pendulum's "
                         "summary.json has integrator, accuracy, fixed_step, axial_modes, transverse_modes, "
                         "axial_dynamics, quasi_static_transverse, axial_law, sheaves, t_end, t_reached, termination, limit, vx0, vy0, steps, "
                         "rhs_evaluations, "
                         "wall_seconds, initial_kinetic_energy_J, max_energy_drift_J, max_constraint_error_N, "
                         "sheave_wrap_angles.#.sheave, sheave_wrap_angles.#.min_rad, sheave_wrap_angles.#.max_rad, "
                         "max_fleet_angle_rad, parameters.a, parameters.L, parameters.d, parameters.r, parameters.g, parameters.rhoA, "
                         "parameters.EA, parameters.EI, parameters.M, parameters.J, where # is an index; the runner adds wall_seconds)");
    EXPECT_THROW_MESSAGE(parse("scene: pendulum\nfixed: {axial-modes: 0}\nmetrics: [EA]\n"), StudyError,
                         "s.yaml:3:11: unknown metric 'EA' for scene pendulum (did you mean parameters.EA?)");
    EXPECT_THROW_MESSAGE(parse("scene: crane\nmetrics: [parameters.payloadmass]\n"), StudyError,
                         "s.yaml:2:11: unknown metric 'parameters.payloadmass' for scene crane (reeving-crane's "
                         "summary.json has program, scenario,");
    EXPECT_THROW_MESSAGE(parse("scene: crane\nmetrics: [hoistSpeed]\n"), StudyError,
                         "s.yaml:2:11: unknown metric 'hoistSpeed' for scene crane (did you mean parameters.hoistSpeed?)");
    EXPECT_THROW_MESSAGE(parse("scene: crane\nmetrics: [parameters.snapshot_times.0]\n"), StudyError,
                         "snapshot_times.#, parameters.g, parameters.railHeight,");
    EXPECT_THROW_MESSAGE(parse("scene: crane\nmetrics: [parameters.payloadmass]\n"), StudyError,
                         "parameters.slingDampingRatio, where # is an index; the runner adds wall_seconds)");
    // The lift-off scenario's parameters and results.
    EXPECT_NO_THROW(parse("scene: crane\nscenario: lift-off\nmetrics: [parameters.hoistSpeed, parameters.slackTime, "
                          "parameters.slingDampingRatio, lift_off_time, spring_mass_dynamic_factor, "
                          "final_contact_dissipation_J]\n"));
}

TEST(StudyFile, BadLimits) {
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [friction]\nlimits: {wall_seconds: 0}\n"), StudyError,
                         "s.yaml:3:24: limits wall_seconds must be > 0 [s], not 0");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [friction]\nlimits: {max_steps: -1}\n"), StudyError,
                         "s.yaml:3:21: limits max_steps must be in 1..1000000000, not -1");
    EXPECT_THROW_MESSAGE(parse("scene: elevator\nmetrics: [friction]\nlimits: {seconds: 5}\n"), StudyError,
                         "s.yaml:3:10: limits: unknown key 'seconds' (known: wall_seconds, max_steps)");
}

TEST(StudyFile, BadFigures) {
    const std::string head = "scene: elevator\nvary: {friction: [0.1, 0.2], car-load: [0, 1], scenario: [trip, stall]}\n"
                             "metrics: [traction_table.0.traction_margin]\nfigures:\n";
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: bars, x: friction, y: wall_seconds}\n"), StudyError,
                         "s.yaml:5:12: figure type must be lines or heatmap, not 'bars'");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: lines, x: rated-load, y: wall_seconds}\n"), StudyError,
                         "s.yaml:5:22: figure x 'rated-load' is not a varied or sampled parameter of the study");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: lines, x: friction, y: traction_table.0.steps}\n"), StudyError,
                         "s.yaml:5:35: figure y 'traction_table.0.steps' is not one of the study's metrics");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: lines, x: scenario, y: wall_seconds}\n"), StudyError,
                         "s.yaml:5:22: figure x 'scenario': its value 'trip' is not a number");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: heatmap, x: friction, y: friction, z: wall_seconds}\n"), StudyError,
                         "s.yaml:5:37: figure x and y are both 'friction'");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: heatmap, x: friction, y: car-load}\n"), StudyError,
                         "s.yaml:5:5: a heatmap figure needs 'z'");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: lines, x: friction, y: wall_seconds, boundary: 1}\n"), StudyError,
                         "s.yaml:5:59: a lines figure has no boundary (heat maps have)");
    EXPECT_THROW_MESSAGE(parse(head + "  - {type: lines, x: friction, y: wall_seconds}\n  - {type: lines, x: friction, "
                                      "y: wall_seconds}\n"),
                         StudyError,
                         "s.yaml:6:5: two figures are named 'wall_seconds_over_friction' (the other at 5:5): give one "
                         "a name:");
    EXPECT_NO_THROW(parse(head + "  - {type: heatmap, x: friction, y: car-load, z: wall_seconds, boundary: 1}\n"));
}
