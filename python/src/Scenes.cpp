#include "Scenes.h"

#include "Errors.h"
#include "Simulation.h"

#include <SimbodyReeving/scenes/CraneScene.h>
#include <SimbodyReeving/scenes/ElevatorScene.h>
#include <SimbodyReeving/scenes/PendulumScene.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace SimbodyReeving;
using SimTK::Stage;
using SimTK::State;

namespace simbody_reeving_python {
namespace {

// ---- parameter structs: keyword constructors, a repr listing the fields, to_dict ----------------

template <class T>
std::vector<std::string>& fieldNames() {
    static std::vector<std::string> names;
    return names;
}

template <class T>
class Fields {
public:
    Fields(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc) {
        cls_.def(py::init([](const py::kwargs& kw) {
                     py::object o = py::cast(T{});
                     const std::vector<std::string>& names = fieldNames<T>();
                     for (auto item : kw) {
                         const std::string key = py::str(item.first);
                         if (std::find(names.begin(), names.end(), key) == names.end())
                             throw py::type_error(std::string(py::str(o.get_type().attr("__name__"))) +
                                                  ": unknown parameter '" + key + "'");
                         py::setattr(o, item.first, item.second);
                     }
                     return o.cast<T>();
                 }),
                 "Keyword arguments set fields; the others keep their defaults.");
        cls_.def("__repr__", [](const py::object& self) {
            std::string s = std::string(py::str(self.get_type().attr("__name__"))) + "(";
            bool first = true;
            for (const std::string& n : fieldNames<T>()) {
                s += (first ? "" : ", ") + n + "=" + std::string(py::repr(self.attr(n.c_str())));
                first = false;
            }
            return s + ")";
        });
        cls_.def("to_dict", [](const py::object& self) {
            py::dict d;
            for (const std::string& n : fieldNames<T>()) d[py::str(n)] = self.attr(n.c_str());
            return d;
        }, "The fields as a dict.");
        cls_.def(py::pickle([](const py::object& self) { return py::dict(self.attr("to_dict")()); },
                            [](const py::dict& d) {
                                py::object o = py::cast(T{});
                                for (auto item : d) py::setattr(o, item.first, item.second);
                                return o.cast<T>();
                            }));
    }
    template <class V>
    Fields& operator()(const char* name, V T::*member, const char* doc) {
        cls_.def_readwrite(name, member, doc);
        fieldNames<T>().push_back(name);
        return *this;
    }
    py::class_<T>& cls() { return cls_; }

private:
    py::class_<T> cls_;
};

py::array_t<double> vec3(const SimTK::Vec3& v) {
    py::array_t<double> a(3);
    for (int i = 0; i < 3; ++i) a.mutable_data()[i] = v[i];
    return a;
}

py::array_t<double> vector(const SimTK::Vector& v) {
    py::array_t<double> a(v.size());
    for (int i = 0; i < v.size(); ++i) a.mutable_data()[i] = v[i];
    return a;
}

// ---- index checks: the plugin indexes without checking in places; out of range is an IndexError ---

void checkRope(const ReevingSubsystem& r, int rope) {
    if (rope < 0 || rope >= r.getNumRopes())
        throw std::out_of_range("rope " + std::to_string(rope) + " out of range: there are " +
                                std::to_string(r.getNumRopes()) + " rope(s)");
}
void checkSpan(const ReevingSubsystem& r, int rope, int span) {
    checkRope(r, rope);
    if (span < 0 || span >= r.getNumSpans(rope))
        throw std::out_of_range("span " + std::to_string(span) + " out of range: rope " + std::to_string(rope) +
                                " has " + std::to_string(r.getNumSpans(rope)) + " span(s)");
}
void checkNode(const ReevingSubsystem& r, int rope, int node) {
    checkRope(r, rope);
    if (node < 0 || node > r.getNumSpans(rope))
        throw std::out_of_range("node " + std::to_string(node) + " out of range: rope " + std::to_string(rope) +
                                " has " + std::to_string(r.getNumSpans(rope) + 1) + " nodes");
}

// A state of r's system: its topology realized and the state's layout its default state's (a state
// of another system would crash Simbody's realizations).
void checkState(const ReevingSubsystem& r, const State& s) {
    const SimTK::System& system = r.getSystem();
    require(system.systemTopologyHasBeenRealized(),
            "the system's topology is not realized: make its states with default_state() (a System) or "
            "make_initial_state() (a scene)");
    const State& d = system.getDefaultState();
    require(s.getNumSubsystems() == d.getNumSubsystems() && s.getNQ() == d.getNQ() && s.getNU() == d.getNU() &&
                s.getNZ() == d.getNZ(),
            "the state is not one of this system's (nq " + std::to_string(s.getNQ()) + ", nu " +
                std::to_string(s.getNU()) + ", nz " + std::to_string(s.getNZ()) + "; the system's: nq " +
                std::to_string(d.getNQ()) + ", nu " + std::to_string(d.getNU()) + ", nz " + std::to_string(d.getNZ()) +
                ")");
}

// A scene's query: the state checked as one of the scene's, realized to `stage`.
template <class Scene>
void realizeScene(const Scene& scene, const State& s, Stage stage) {
    checkState(scene.reeving(), s);
    scene.system().realize(s, stage);
}

// Queries realize the state they are given as far as they need (a no-op on a realized state).
void realize(const ReevingSubsystem& r, const State& s, Stage stage) {
    checkState(r, s);
    r.getSystem().realize(s, stage);
}

void bindReeving(py::module_& m) {
    py::class_<ReevingSubsystem>(m, "ReevingSubsystem",
                                 "A scene's ropes (scene.reeving): the queries that apply to every rope, span and node. "
                                 "Indices: rope 0.., span 0..num_spans-1 (span k joins nodes k and k+1).")
        .def_property_readonly("num_ropes", &ReevingSubsystem::getNumRopes)
        .def("num_spans", [](const ReevingSubsystem& r, int rope) { checkRope(r, rope); return r.getNumSpans(rope); },
             py::arg("rope"))
        .def("is_planar", [](const ReevingSubsystem& r, int rope) { checkRope(r, rope); return r.isPlanar(rope); },
             py::arg("rope"))
        .def("rope_name", [](const ReevingSubsystem& r, int rope) { checkRope(r, rope); return r.getRopeSpec(rope).name; },
             py::arg("rope"))
        .def("unstretched_length",
             [](const ReevingSubsystem& r, int rope) { checkRope(r, rope); return r.getRopeSpec(rope).unstretchedLength; },
             py::arg("rope"), "[m]")
        .def("span_material_range",
             [](const ReevingSubsystem& r, const State& s, int rope, int span) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Position);
                 return r.getSpanMaterialRange(s, rope, span);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), "(s1, s2): the span's material coordinates [m]")
        .def("axial_force",
             [](const ReevingSubsystem& r, const State& s, int rope, int span, double at) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Dynamics);
                 return r.getAxialForce(s, rope, span, at);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), py::arg("s"),
             "Axial force P = EA eps [N] at material coordinate s (in span_material_range).")
        .def("axial_force",
             [](const ReevingSubsystem& r, const State& s, int rope, int span, py::array_t<double> at) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Dynamics);
                 py::array_t<double> out(at.size());
                 const double* src = at.data();
                 for (py::ssize_t i = 0; i < at.size(); ++i) out.mutable_data()[i] = r.getAxialForce(s, rope, span, src[i]);
                 return out;
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), py::arg("s"), "The same at every s of an array.")
        .def("axial_force_along",
             [](const ReevingSubsystem& r, const State& s, int rope, int span, int points) {
                 checkSpan(r, rope, span);
                 require(points >= 2, "points = " + std::to_string(points) + " must be >= 2");
                 realize(r, s, Stage::Dynamics);
                 const auto [s1, s2] = r.getSpanMaterialRange(s, rope, span);
                 py::array_t<double> sa(points), pa(points);
                 for (int k = 0; k < points; ++k) {
                     // as the pendulum demo's static_axial_force.csv
                     const double sk = s1 + (s2 - s1) * k / static_cast<double>(points - 1);
                     sa.mutable_data()[k] = sk;
                     pa.mutable_data()[k] = r.getAxialForce(s, rope, span, std::min(sk, s2));
                 }
                 return py::make_tuple(sa, pa);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), py::arg("points") = 60,
             "(s, P): the axial force at `points` equally spaced material coordinates along the span.")
        .def("tension",
             [](const ReevingSubsystem& r, const State& s, int rope, int span, double at) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Dynamics);
                 return r.getTension(s, rope, span, at);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), py::arg("s"), "Tension T = P |dr/ds| [N].")
        .def("span_max_strain",
             [](const ReevingSubsystem& r, const State& s, int rope, int span) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Dynamics);
                 return r.getSpanMaxStrain(s, rope, span);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"))
        .def("is_span_slack",
             [](const ReevingSubsystem& r, const State& s, int rope, int span) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Dynamics);
                 return r.isSpanSlack(s, rope, span);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"))
        .def("fleet_angles",
             [](const ReevingSubsystem& r, const State& s, int rope, int span) {
                 checkSpan(r, rope, span);
                 realize(r, s, Stage::Position);
                 return r.getFleetAngles(s, rope, span);
             },
             py::arg("state"), py::arg("rope"), py::arg("span"),
             "The span's angles to the grooves' planes at its two ends [rad] (0 for a planar rope).")
        .def("sample_span",
             [](const ReevingSubsystem& r, const State& s, int rope, int span, int points) {
                 checkSpan(r, rope, span);
                 require(points >= 2, "points = " + std::to_string(points) + " must be >= 2");
                 realize(r, s, Stage::Position);
                 const std::vector<SimTK::Vec3> p = r.sampleSpan(s, rope, span, points);
                 py::array_t<double> a({static_cast<py::ssize_t>(p.size()), py::ssize_t(3)});
                 for (std::size_t i = 0; i < p.size(); ++i)
                     for (int j = 0; j < 3; ++j) a.mutable_data()[3 * i + j] = p[i][j];
                 return a;
             },
             py::arg("state"), py::arg("rope"), py::arg("span"), py::arg("points") = 20,
             "Points x points on the span's centre line, an array (points, 3) [m].")
        .def("material_coordinate",
             [](const ReevingSubsystem& r, const State& s, int rope, int node) {
                 checkNode(r, rope, node);
                 realize(r, s, Stage::Position);
                 return r.getMaterialCoordinate(s, rope, node);
             },
             py::arg("state"), py::arg("rope"), py::arg("node"), "The rope's material coordinate s at the node [m].")
        .def("node_force",
             [](const ReevingSubsystem& r, const State& s, int rope, int node) {
                 checkNode(r, rope, node);
                 realize(r, s, Stage::Dynamics);
                 return vec3(r.getNodeForce(s, rope, node));
             },
             py::arg("state"), py::arg("rope"), py::arg("node"),
             "The force the rope exerts on the node's body, in Ground [N] (at a sheave: the bearing load).")
        .def("wrap_angle",
             [](const ReevingSubsystem& r, const State& s, int rope, int node) {
                 checkNode(r, rope, node);
                 realize(r, s, Stage::Position);
                 return r.getWrapAngle(s, rope, node);
             },
             py::arg("state"), py::arg("rope"), py::arg("node"),
             "alpha at a sheave [rad] (ValueError at an end node or a point sheave of a spatial rope).")
        .def("arc_length",
             [](const ReevingSubsystem& r, const State& s, int rope, int node) {
                 checkNode(r, rope, node);
                 realize(r, s, Stage::Position);
                 return r.getArcLength(s, rope, node);
             },
             py::arg("state"), py::arg("rope"), py::arg("node"), "The rope on the node's groove R alpha [m].")
        .def("constraint_error",
             [](const ReevingSubsystem& r, const State& s, int rope, int node) {
                 checkNode(r, rope, node);
                 require(node > 0 && node < r.getNumSpans(rope), "constraint_error: node " + std::to_string(node) +
                                                                    " is an end node (sheaves: 1.." +
                                                                    std::to_string(r.getNumSpans(rope) - 1) + ")");
                 realize(r, s, Stage::Dynamics);
                 return r.getConstraintError(s, rope, node);
             },
             py::arg("state"), py::arg("rope"), py::arg("node"),
             "F_a - F_b at a sheave [N]: the tension-equality residual at a DeviationSheave.")
        .def("find_static_equilibrium",
             [](const ReevingSubsystem& r, State& s, double tolerance, int iterations) {
                 checkState(r, s);
                 py::gil_scoped_release release;
                 return r.findStaticEquilibrium(s, tolerance, iterations);
             },
             py::arg("state"), py::arg("relative_tolerance") = 1e-10, py::arg("max_iterations") = 50,
             "Moves `state` (in place) to static equilibrium of bodies and ropes; returns the relative residual.")
        .def("max_constraint_error",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Dynamics);
                 return r.getMaxConstraintError(s);
             },
             py::arg("state"))
        .def("mechanical_energy",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Velocity);
                 return r.calcMechanicalEnergy(s);
             },
             py::arg("state"), "Bodies and ropes: kinetic + potential [J].")
        .def("rope_kinetic_energy",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Velocity);
                 return r.calcRopeKineticEnergy(s);
             },
             py::arg("state"), "[J]")
        .def("rope_potential_energy",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Velocity);
                 return r.calcRopePotentialEnergy(s);
             },
             py::arg("state"), "Strain and gravity of the ropes [J].")
        .def("damping_work",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Velocity);
                 return r.getDampingWork(s);
             },
             py::arg("state"), "Work dissipated by the ropes' damping since t = 0 [J].")
        .def("total_friction_work",
             [](const ReevingSubsystem& r, const State& s) {
                 realize(r, s, Stage::Velocity);
                 return r.getTotalFrictionWork(s);
             },
             py::arg("state"), "Work dissipated by slip on every traction sheave since t = 0 [J].")
        .def_property_readonly("limit_reached", &ReevingSubsystem::getLimitReached,
                               "'' or the rope limit that requested the run's end.")
        .def_property_readonly("num_evaluation_failures", &ReevingSubsystem::getNumEvaluationFailures)
        .def_property_readonly("last_evaluation_failure", &ReevingSubsystem::getLastEvaluationFailure);
}

// ---- observers: what each scene reports (the demos' rows) ---------------------------------------

// examples/pendulum/main.cpp observe(), in its order.
Observer pendulumObserver(const PendulumScene& scene) {
    Observer o;
    o.columns = {"t", "x", "y", "theta", "axial_force_payload", "axial_force_sheave", "s_sheave", "energy",
                 "constraint_error", "wrap_angle"};
    o.observe = [&scene](const State& s, std::vector<double>& row) {
        // Stage::Dynamics: the axial forces of QuasiStatic spans include the mode-acceleration correction.
        scene.system().realize(s, Stage::Dynamics);
        const SimTK::Vec3 p = scene.payloadPosition(s);
        const ReevingSubsystem& rv = scene.reeving();
        row = {s.getTime(),
               p[0],
               p[1],
               scene.payloadAngle(s),
               scene.axialForceAtPayload(s),
               scene.axialForceAtSheave(s),
               scene.sheaveMaterialCoordinate(s),
               rv.calcMechanicalEnergy(s),
               rv.getConstraintError(s, 0, 1),
               rv.getRopeSpec(0).sheaveModel == SheaveModel::Wrapped ? rv.getWrapAngle(s, 0, 1) : 0.0};
    };
    return o;
}

// examples/elevator/main.cpp observe(), the scene's observables (its traction-sheave node queries
// come with the typed node handles).
Observer elevatorObserver(const ElevatorScene& scene, double e0) {
    Observer o;
    o.columns = {"t",
                 "car_y",
                 "car_v",
                 "car_a",
                 "counterweight_y",
                 "rope_travel",
                 "car_side_force",
                 "counterweight_side_force",
                 "force_ratio",
                 "wrap_angle",
                 "friction_work",
                 "damping_work",
                 "machine_work",
                 "energy_residual",
                 "pit_sheave_y"};
    o.observe = [&scene, e0](const State& s, std::vector<double>& row) {
        scene.system().realize(s, Stage::Acceleration);
        const ReevingSubsystem& rv = scene.reeving();
        const double pCar = scene.carSideForce(s), pCwt = scene.counterweightSideForce(s);
        row = {s.getTime(),
               scene.carHeight(s),
               scene.carVelocity(s),
               scene.carAcceleration(s),
               scene.counterweightHeight(s),
               scene.ropeTravel(s),
               pCar,
               pCwt,
               pCar / pCwt,
               scene.tractionWrapAngle(s),
               rv.getTotalFrictionWork(s),
               rv.getDampingWork(s),
               scene.workMeter().getWork(s),
               scene.energyResidual(s, e0),
               scene.pitSheaveHeight(s)};
    };
    return o;
}

// examples/crane/main.cpp's observables.
Observer craneObserver(const CraneScene& scene, double e0) {
    Observer o;
    o.columns = {"t", "trolley_x", "hook_x", "hook_y", "sway", "payload_angle"};
    for (int k = 0; k < scene.falls(); ++k) o.columns.push_back("fall_top_force_" + std::to_string(k));
    for (const char* c : {"drum_speed", "motor_torque", "rope_on_drum", "trolley_force", "machine_work",
                          "energy_residual", "largest_fall_lean", "rope_length_error"})
        o.columns.push_back(c);
    for (int k = 1; k < scene.falls(); ++k) o.columns.push_back("wrap_angle_" + std::to_string(k));
    o.observe = [&scene, e0](const State& s, std::vector<double>& row) {
        scene.system().realize(s, Stage::Acceleration);
        const SimTK::Vec3 hook = scene.hookPosition(s);
        row = {s.getTime(), scene.trolleyX(s), hook[0], hook[1], scene.swayAngle(s), scene.payloadAngle(s)};
        for (int k = 0; k < scene.falls(); ++k) row.push_back(scene.fallTopForce(s, k));
        row.push_back(scene.drumSpeed(s));
        row.push_back(scene.motorTorque(s));
        row.push_back(scene.ropeOnDrum(s));
        row.push_back(scene.trolleyForce(s));
        row.push_back(scene.workMeter().getWork(s));
        row.push_back(scene.energyResidual(s, e0));
        row.push_back(scene.largestFallLean(s));
        row.push_back(scene.ropeLengthError(s));
        for (int k = 1; k < scene.falls(); ++k) row.push_back(scene.sheaveWrapAngle(s, k));
    };
    return o;
}

// ---- the pendulum demo's case (examples/pendulum/main.cpp runCase), numbers to the last bit ------

struct PendulumRunOptions {
    PendulumParameters parameters;
    int axialModes = 0, transverseModes = 1;
    std::string axialDynamics = "quasi-static", quasiStaticTransverse = "none";
    double tEnd = 20, vx0 = 1, vy0 = 0;
    std::string integrator = "rk-merson";
    double accuracy = 1e-6, step = 0, reportInterval = 0.01;
    long maxSteps = 0;
};

// The demo's makeScene, with its option checks (PendulumCli.cpp).
std::unique_ptr<PendulumScene> makePendulumScene(const PendulumRunOptions& o) {
    require(o.axialDynamics == "quasi-static" || o.axialDynamics == "dynamic",
            "axial_dynamics = '" + o.axialDynamics + "' must be 'quasi-static' or 'dynamic'");
    require(o.quasiStaticTransverse == "none" || o.quasiStaticTransverse == "horizontal" ||
                o.quasiStaticTransverse == "all",
            "quasi_static_transverse = '" + o.quasiStaticTransverse + "' must be 'none', 'horizontal' or 'all'");
    const AxialDynamics dynamics = o.axialDynamics == "dynamic" ? AxialDynamics::Dynamic : AxialDynamics::QuasiStatic;
    require(o.quasiStaticTransverse == "none" || dynamics == AxialDynamics::QuasiStatic || o.axialModes == 0,
            "quasi_static_transverse = '" + o.quasiStaticTransverse +
                "' requires axial_dynamics = 'quasi-static' when axial_modes > 0 (got " + std::to_string(o.axialModes) +
                ")");
    SpanOptions spans;
    spans.axialModes = o.axialModes;
    spans.transverseModes = o.transverseModes;
    spans.axialDynamics = dynamics;
    SpanOptions condensed = spans;
    condensed.transverseDynamics = TransverseDynamics::QuasiStatic;
    if (o.quasiStaticTransverse == "all") spans = condensed;
    return std::make_unique<PendulumScene>(
        o.parameters, spans, true,
        o.quasiStaticTransverse == "horizontal" ? std::optional<SpanOptions>(condensed) : std::nullopt);
}

py::dict runPendulum(const PendulumRunOptions& o) {
    struct StaticRow {
        int span;
        double s, axialForce;
    };
    std::vector<StaticRow> staticRows;
    Reports reports;
    long steps = 0, rhs = 0;
    double wall = 0, initialKineticEnergy = 0, maxEnergyDrift = 0, maxConstraintError = 0;
    std::string limit;
    bool interrupted = false;
    {
        py::gil_scoped_release release;
        const std::unique_ptr<PendulumScene> scenePointer = makePendulumScene(o);
        const PendulumScene& scene = *scenePointer;
        State s = scene.makeInitialState(o.vx0, o.vy0);
        const ReevingSubsystem& rv = scene.reeving();
        for (int span = 0; span < 2; ++span) {
            const auto [s1, s2] = rv.getSpanMaterialRange(s, 0, span);
            for (int k = 0; k < 60; ++k) {
                const double sk = s1 + (s2 - s1) * k / 59.0;
                staticRows.push_back({span, sk, rv.getAxialForce(s, 0, span, std::min(sk, s2))});
            }
        }
        initialKineticEnergy = scene.system().calcKineticEnergy(s) + rv.calcRopeKineticEnergy(s);
        const double e0 = rv.calcMechanicalEnergy(s);
        Simulation sim(scene.system(), rv, s, o.integrator, o.accuracy, o.step, pendulumObserver(scene));
        InterruptPoll poll;
        const auto start = std::chrono::steady_clock::now();
        reports = sim.run(o.tEnd, o.reportInterval, o.maxSteps, poll, interrupted);
        wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        steps = sim.steps();
        rhs = sim.rhsEvaluations();
        limit = sim.limitReached();
        for (const std::vector<double>& row : reports.rows) {
            maxEnergyDrift = std::max(maxEnergyDrift, std::abs(row[7] - e0));
            maxConstraintError = std::max(maxConstraintError, std::abs(row[8]));
        }
    }
    if (interrupted) throw py::error_already_set();

    py::dict timeseries = reportsToDict(reports);
    py::dict staticForce;
    {
        const auto n = static_cast<py::ssize_t>(staticRows.size());
        py::array_t<int> span(n);
        py::array_t<double> sa(n), pa(n);
        for (py::ssize_t i = 0; i < n; ++i) {
            span.mutable_data()[i] = staticRows[static_cast<std::size_t>(i)].span;
            sa.mutable_data()[i] = staticRows[static_cast<std::size_t>(i)].s;
            pa.mutable_data()[i] = staticRows[static_cast<std::size_t>(i)].axialForce;
        }
        staticForce["span"] = span;
        staticForce["s"] = sa;
        staticForce["axial_force"] = pa;
    }
    // summary.json's keys (examples/pendulum/main.cpp writeCase), the numbers unrounded.
    const PendulumParameters& p = o.parameters;
    py::dict js;
    js["integrator"] = o.integrator;
    js["accuracy"] = o.accuracy;
    js["fixed_step"] = o.step;
    js["axial_modes"] = o.axialModes;
    js["transverse_modes"] = o.transverseModes;
    js["axial_dynamics"] = o.axialDynamics;
    js["quasi_static_transverse"] = o.quasiStaticTransverse;
    js["axial_law"] = p.tensionOnly ? "tension-only" : "linear";
    js["sheaves"] = p.sheaveModel == SheaveModel::Wrapped ? "wrapped" : "point";
    js["t_end"] = o.tEnd;
    js["t_reached"] = reports.rows.back()[0];
    js["termination"] = limit.empty() ? "completed" : "limit_reached";
    js["limit"] = limit;
    js["vx0"] = o.vx0;
    js["vy0"] = o.vy0;
    js["steps"] = steps;
    js["rhs_evaluations"] = rhs;
    js["wall_seconds"] = wall;
    js["initial_kinetic_energy_J"] = initialKineticEnergy;
    js["max_energy_drift_J"] = maxEnergyDrift;
    js["max_constraint_error_N"] = maxConstraintError;
    {
        double lo = reports.rows.front()[9], hi = lo;
        for (const auto& row : reports.rows) {
            lo = std::min(lo, row[9]);
            hi = std::max(hi, row[9]);
        }
        py::dict w;
        w["sheave"] = 1;
        w["min_rad"] = lo;
        w["max_rad"] = hi;
        py::list l;
        l.append(w);
        js["sheave_wrap_angles"] = l;
    }
    js["max_fleet_angle_rad"] = 0.0;
    py::dict params;
    for (auto [k, v] : std::vector<std::pair<const char*, double>>{{"a", p.a},   {"L", p.L},       {"d", p.d},
                                                                    {"r", p.r},   {"g", p.g},       {"rhoA", p.rhoA},
                                                                    {"EA", p.EA}, {"EI", p.EI},     {"M", p.M},
                                                                    {"J", p.J}})
        params[k] = v;
    js["parameters"] = params;
    py::dict out;
    out["timeseries"] = timeseries;
    out["static_axial_force"] = staticForce;
    out["summary"] = js;
    return out;
}

// A scene's simulation(): the Simulation keeps the scene alive.
template <class Scene>
std::unique_ptr<Simulation> makeSimulation(const Scene& scene, Observer observer, const State& state,
                                           const std::string& integrator, double accuracy, double fixedStep) {
    checkState(scene.reeving(), state);
    py::gil_scoped_release release;
    return std::make_unique<Simulation>(scene.system(), scene.reeving(), state, integrator, accuracy, fixedStep,
                                        std::move(observer));
}

template <class Scene>
double initialEnergy(const Scene& scene, const State& s) {
    realizeScene(scene, s, Stage::Velocity);
    return scene.reeving().calcMechanicalEnergy(s);
}

}  // namespace

void bindScenes(py::module_& m) {
    py::class_<State>(m, "State", "A Simbody state (SimTK::State): time, generalized coordinates and speeds.")
        .def_property_readonly("time", &State::getTime, "[s]")
        .def_property_readonly("q", [](const State& s) { return vector(s.getQ()); }, "A copy of q.")
        .def_property_readonly("u", [](const State& s) { return vector(s.getU()); }, "A copy of u.")
        .def_property_readonly("nq", [](const State& s) { return s.getNQ(); })
        .def_property_readonly("nu", [](const State& s) { return s.getNU(); })
        .def_property_readonly("nz", [](const State& s) { return s.getNZ(); }, "Auxiliary states (the ropes' modal coordinates and rates...).")
        .def("set_time", [](State& s, double t) {
                require(std::isfinite(t), "set_time: t must be finite");
                s.setTime(t);
            }, py::arg("t"), "[s]")
        .def("set_q", [](State& s, const std::vector<double>& q) {
                require(static_cast<int>(q.size()) == s.getNQ(), "set_q: " + std::to_string(q.size()) +
                                                                     " values for nq = " + std::to_string(s.getNQ()));
                for (int i = 0; i < s.getNQ(); ++i) s.updQ()[i] = q[static_cast<std::size_t>(i)];
            }, py::arg("q"), "Sets every q (nq values).")
        .def("set_u", [](State& s, const std::vector<double>& u) {
                require(static_cast<int>(u.size()) == s.getNU(), "set_u: " + std::to_string(u.size()) +
                                                                     " values for nu = " + std::to_string(s.getNU()));
                for (int i = 0; i < s.getNU(); ++i) s.updU()[i] = u[static_cast<std::size_t>(i)];
            }, py::arg("u"), "Sets every u (nu values).")
        .def("copy", [](const State& s) { return State(s); })
        .def("__copy__", [](const State& s) { return State(s); })
        .def("__repr__", [](const State& s) {
            return "State(t=" + std::string(py::repr(py::float_(s.getTime()))) + ", nq=" + std::to_string(s.getNQ()) +
                   ", nu=" + std::to_string(s.getNU()) + ")";
        });

    py::enum_<SheaveModel>(m, "SheaveModel")
        .value("Point", SheaveModel::Point)
        .value("Wrapped", SheaveModel::Wrapped);
    py::enum_<AxialDynamics>(m, "AxialDynamics")
        .value("QuasiStatic", AxialDynamics::QuasiStatic)
        .value("Dynamic", AxialDynamics::Dynamic);
    py::enum_<TransverseDynamics>(m, "TransverseDynamics")
        .value("Dynamic", TransverseDynamics::Dynamic)
        .value("QuasiStatic", TransverseDynamics::QuasiStatic);
    py::enum_<VelocityModel>(m, "VelocityModel")
        .value("Complete", VelocityModel::Complete)
        .value("Simplified", VelocityModel::Simplified);
    py::enum_<TractionSlip>(m, "TractionSlip")
        .value("CapstanConstraint", TractionSlip::CapstanConstraint)
        .value("RopeMomentum", TractionSlip::RopeMomentum);
    py::enum_<ElevatorScenario>(m, "ElevatorScenario")
        .value("Trip", ElevatorScenario::Trip)
        .value("Loading", ElevatorScenario::Loading)
        .value("EmergencyStop", ElevatorScenario::EmergencyStop)
        .value("Stall", ElevatorScenario::Stall);
    py::enum_<CraneScenario>(m, "CraneScenario")
        .value("Cycle", CraneScenario::Cycle)
        .value("LiftOff", CraneScenario::LiftOff);

    Fields<SpanOptions>(m, "SpanOptions", "A span's options (SimbodyReeving::SpanOptions).")
        ("axial_modes", &SpanOptions::axialModes, "n_a, 0..16")
        ("transverse_modes", &SpanOptions::transverseModes, "n_t, 0..16")
        ("velocity_model", &SpanOptions::velocityModel, "VelocityModel")
        ("axial_dynamics", &SpanOptions::axialDynamics, "AxialDynamics (QuasiStatic: condensed)")
        ("transverse_dynamics", &SpanOptions::transverseDynamics, "TransverseDynamics")
        ("quasi_static_slack_stiffness", &SpanOptions::quasiStaticSlackStiffness, "delta [-]")
        ("quasi_static_slack_transition_strain", &SpanOptions::quasiStaticSlackTransitionStrain, "eps_s [-]")
        ("quadrature_points", &SpanOptions::quadraturePoints, "0: automatic")
        ("transverse_damping_ratio", &SpanOptions::transverseDampingRatio, "[-]");

    Fields<PendulumParameters>(m, "PendulumParameters", "The paper's Table 1 (SimbodyReeving::PendulumParameters), SI units.")
        ("a", &PendulumParameters::a, "horizontal span [m], > 0")
        ("L", &PendulumParameters::L, "unstretched vertical span [m], > 0")
        ("d", &PendulumParameters::d, "attachment above the payload's centre [m], >= 0")
        ("r", &PendulumParameters::r, "sheave radius [m], > 0")
        ("g", &PendulumParameters::g, "[m/s^2], >= 0")
        ("rhoA", &PendulumParameters::rhoA, "[kg/m], > 0")
        ("EA", &PendulumParameters::EA, "[N], > 0")
        ("EI", &PendulumParameters::EI, "[N m^2], >= 0")
        ("M", &PendulumParameters::M, "payload mass [kg], > 0")
        ("J", &PendulumParameters::J, "payload inertia [kg m^2], > 0")
        ("tension_only", &PendulumParameters::tensionOnly, "False: the paper's linear law")
        ("sheave_model", &PendulumParameters::sheaveModel, "SheaveModel")
        .cls().def("validate", &PendulumParameters::validate, "Raises ValueError naming the first bad parameter.");

    Fields<ElevatorParameters>(m, "ElevatorParameters", "The traction elevator (SimbodyReeving::ElevatorParameters), SI units.")
        ("scenario", &ElevatorParameters::scenario, "ElevatorScenario")
        ("g", &ElevatorParameters::g, "[m/s^2]")
        ("car_mass", &ElevatorParameters::carMass, "[kg]")
        ("rated_load", &ElevatorParameters::ratedLoad, "[kg]")
        ("counterweight_mass", &ElevatorParameters::counterweightMass, "[kg]; 0: car + half the rated load")
        ("hoistway", &ElevatorParameters::hoistway, "[m]")
        ("sheave_radius", &ElevatorParameters::sheaveRadius, "[m]")
        ("sheave_inertia", &ElevatorParameters::sheaveInertia, "[kg m^2]")
        ("friction", &ElevatorParameters::friction, "groove friction mu [-]")
        ("wrap_angle", &ElevatorParameters::wrapAngle, "[rad] or None (the geometry's, pi with point sheaves)")
        ("rhoA", &ElevatorParameters::rhoA, "[kg/m]")
        ("EA", &ElevatorParameters::EA, "[N]")
        ("retardation_time", &ElevatorParameters::retardationTime, "Kelvin-Voigt c [s]")
        ("rated_speed", &ElevatorParameters::ratedSpeed, "[m/s]")
        ("trip_distance", &ElevatorParameters::tripDistance, "[m]")
        ("trip_ramp", &ElevatorParameters::tripRamp, "[s]")
        ("brake_deceleration", &ElevatorParameters::brakeDeceleration, "[m/s^2]")
        ("stall_speed", &ElevatorParameters::stallSpeed, "[m/s]")
        ("buffer_stiffness", &ElevatorParameters::bufferStiffness, "[N/m]")
        ("roping", &ElevatorParameters::roping, "1 (1:1) or 2 (2:1)")
        ("car_sheave_radius", &ElevatorParameters::carSheaveRadius, "[m]")
        ("sheave_model", &ElevatorParameters::sheaveModel, "SheaveModel")
        ("traction_slip", &ElevatorParameters::tractionSlip, "TractionSlip")
        ("deflector", &ElevatorParameters::deflector, "a deflector sheave (1:1, wrapped)")
        ("deflector_radius", &ElevatorParameters::deflectorRadius, "[m]")
        ("deflector_drop", &ElevatorParameters::deflectorDrop, "[m]")
        ("counterweight_rail", &ElevatorParameters::counterweightRail, "[m]")
        ("car_hitch_offset", &ElevatorParameters::carHitchOffset, "[m]")
        ("compensation", &ElevatorParameters::compensation, "a compensating rope")
        ("compensation_rhoA", &ElevatorParameters::compensationRhoA, "[kg/m]")
        ("pit_sheave_mass", &ElevatorParameters::pitSheaveMass, "[kg]")
        ("car_load", &ElevatorParameters::carLoad, "fraction of the rated load, 0..1.25, or None (the scenario's)")
        ("car_position", &ElevatorParameters::carPosition, "[m] above the bottom landing, or None (the scenario's)")
        .cls()
        .def("validate", &ElevatorParameters::validate, "Raises ValueError naming the first bad parameter.")
        .def("counterweight", &ElevatorParameters::counterweight, "The counterweight's mass [kg].");

    Fields<CraneParameters>(m, "CraneParameters", "The gantry crane (SimbodyReeving::CraneParameters), SI units.")
        ("falls", &CraneParameters::falls, "1..12")
        ("g", &CraneParameters::g, "[m/s^2]")
        ("rail_height", &CraneParameters::railHeight, "[m]")
        ("trolley_x0", &CraneParameters::trolleyX0, "[m]")
        ("trolley_mass", &CraneParameters::trolleyMass, "[kg]")
        ("sheave_pitch", &CraneParameters::sheavePitch, "[m]")
        ("sheave_radius", &CraneParameters::sheaveRadius, "[m]")
        ("sheave_model", &CraneParameters::sheaveModel, "SheaveModel")
        ("drum_radius", &CraneParameters::drumRadius, "[m]")
        ("drum_height", &CraneParameters::drumHeight, "[m]")
        ("drum_mass", &CraneParameters::drumMass, "[kg]")
        ("drum_inertia", &CraneParameters::drumInertia, "[kg m^2]")
        ("rope_on_drum", &CraneParameters::ropeOnDrum, "[m]")
        ("hook_mass", &CraneParameters::hookMass, "[kg]")
        ("hook_inertia", &CraneParameters::hookInertia, "[kg m^2]")
        ("hook_com_below", &CraneParameters::hookComBelow, "[m]")
        ("hook_pin_below", &CraneParameters::hookPinBelow, "[m]")
        ("initial_hook_depth", &CraneParameters::initialHookDepth, "[m]")
        ("payload_mass", &CraneParameters::payloadMass, "[kg]")
        ("payload_inertia", &CraneParameters::payloadInertia, "[kg m^2]")
        ("sling_length", &CraneParameters::slingLength, "[m]")
        ("payload_width", &CraneParameters::payloadWidth, "[m]")
        ("payload_height", &CraneParameters::payloadHeight, "[m]")
        ("rhoA", &CraneParameters::rhoA, "[kg/m]")
        ("EA", &CraneParameters::EA, "[N]")
        ("EI", &CraneParameters::EI, "[N m^2]")
        ("tension_only", &CraneParameters::tensionOnly, "")
        ("minimum_span_length", &CraneParameters::minimumSpanLength, "[m]")
        ("scenario", &CraneParameters::scenario, "CraneScenario")
        ("hoist_speed", &CraneParameters::hoistSpeed, "[m/s]")
        ("hoist_ramp", &CraneParameters::hoistRamp, "[s]")
        ("slack_time", &CraneParameters::slackTime, "[s]")
        ("after_lift_off", &CraneParameters::afterLiftOff, "[bounce periods]")
        ("floor_stiffness", &CraneParameters::floorStiffness, "[N/m]")
        ("floor_damping_ratio", &CraneParameters::floorDampingRatio, "[-]")
        ("sling_stiffness", &CraneParameters::slingStiffness, "[N/m]")
        ("sling_damping_ratio", &CraneParameters::slingDampingRatio, "[-]")
        .cls().def("validate", &CraneParameters::validate, "Raises ValueError naming the first bad parameter.");

    py::class_<CraneCycle>(m, "CraneCycle", "The crane's program (hoist and traverse profiles, duration).")
        .def_static("lift_traverse_lower", &CraneCycle::liftTraverseLower, py::arg("lift") = 5.0,
                    py::arg("traverse") = 10.0, "The demo's default cycle: lift, traverse, lower [m].")
        .def_static("lift_off", &CraneCycle::liftOff, py::arg("parameters"), "The lift-off scenario's program.")
        .def_readwrite("duration", &CraneCycle::duration, "[s]")
        .def("validate", &CraneCycle::validate);

    bindReeving(m);

    // ---- PendulumScene
    py::class_<PendulumScene>(m, "PendulumScene",
                              "The paper's two-branch pendulum (SimbodyReeving::PendulumScene): rope 0, span 0 "
                              "horizontal, span 1 vertical down to the payload.")
        .def(py::init([](const PendulumParameters& p, const SpanOptions& spans, bool planar,
                         const std::optional<SpanOptions>& horizontal) {
                 py::gil_scoped_release release;
                 return std::make_unique<PendulumScene>(p, spans, planar, horizontal);
             }),
             py::arg("parameters") = PendulumParameters(), py::arg("spans") = SpanOptions(),
             py::arg("planar_rope") = true, py::arg("horizontal_span") = std::nullopt)
        .def_property_readonly("parameters", [](const PendulumScene& sc) { return sc.parameters(); }, "A copy of the parameters.")
        .def_property_readonly("reeving", &PendulumScene::reeving, py::return_value_policy::reference_internal)
        .def(
            "make_initial_state",
            [](const PendulumScene& s, double vx, double vy) {
                py::gil_scoped_release release;
                return s.makeInitialState(vx, vy);
            },
            py::arg("vx") = 1.0, py::arg("vy") = 0.0,
            "Static equilibrium, then the payload's velocity (vx, vy) [m/s]; realized to Stage::Velocity.")
        .def("payload_position", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return vec3(sc.payloadPosition(s)); }, py::arg("state"), "[m]")
        .def("payload_angle", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.payloadAngle(s); }, py::arg("state"), "[rad]")
        .def("axial_force_at_payload", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Dynamics); return sc.axialForceAtPayload(s); }, py::arg("state"), "P = EA eps at the payload end of the vertical span [N]")
        .def("axial_force_at_sheave", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Dynamics); return sc.axialForceAtSheave(s); }, py::arg("state"), "[N]")
        .def("sheave_material_coordinate", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.sheaveMaterialCoordinate(s); }, py::arg("state"), "[m]")
        .def("wrap_angle", [](const PendulumScene& sc, const State& s) {
                realizeScene(sc, s, Stage::Position);
                return sc.parameters().sheaveModel == SheaveModel::Wrapped ? sc.reeving().getWrapAngle(s, 0, 1) : 0.0;
            }, py::arg("state"), "The deviation sheave's wrap angle [rad] (0 with the point sheave).")
        .def("kinetic_energy", [](const PendulumScene& sc, const State& s) { realizeScene(sc, s, Stage::Velocity); return sc.system().calcKineticEnergy(s); }, py::arg("state"), "The bodies' [J].")
        .def(
            "simulation",
            [](const PendulumScene& sc, const State& s, const std::string& integrator, double accuracy, double step) {
                return makeSimulation(sc, pendulumObserver(sc), s, integrator, accuracy, step);
            },
            py::arg("state"), py::arg("integrator") = "rk-merson", py::arg("accuracy") = 1e-6,
            py::arg("fixed_step") = 0.0, py::keep_alive<0, 1>(),
            "A Simulation from `state`; its reports are the demo's timeseries.csv columns.");

    m.def(
        "run_pendulum",
        [](int axialModes, const std::optional<PendulumParameters>& parameters, int transverseModes,
           const std::string& axialDynamics, const std::string& quasiStaticTransverse, double tEnd, double vx0,
           double vy0, const std::string& integrator, double accuracy, double step, double reportInterval,
           long maxSteps) {
            PendulumRunOptions o;
            if (parameters) o.parameters = *parameters;
            o.axialModes = axialModes;
            o.transverseModes = transverseModes;
            o.axialDynamics = axialDynamics;
            o.quasiStaticTransverse = quasiStaticTransverse;
            o.tEnd = tEnd;
            o.vx0 = vx0;
            o.vy0 = vy0;
            o.integrator = integrator;
            o.accuracy = accuracy;
            o.step = step;
            o.reportInterval = reportInterval;
            o.maxSteps = maxSteps;
            return runPendulum(o);
        },
        py::arg("axial_modes") = 0, py::arg("parameters") = std::nullopt, py::arg("transverse_modes") = 1,
        py::arg("axial_dynamics") = "quasi-static", py::arg("quasi_static_transverse") = "none",
        py::arg("t_end") = 20.0, py::arg("vx0") = 1.0, py::arg("vy0") = 0.0, py::arg("integrator") = "rk-merson",
        py::arg("accuracy") = 1e-6, py::arg("step") = 0.0, py::arg("report_interval") = 0.01, py::arg("max_steps") = 0,
        "One case of reeving-pendulum (the same options, defaults and numbers): returns a dict with "
        "'timeseries' (numpy arrays: t, x, y, theta, axial_force_payload, axial_force_sheave, s_sheave, "
        "energy, constraint_error, wrap_angle), 'static_axial_force' (span, s, axial_force) and "
        "'summary' (summary.json's keys, unrounded). Without the GIL; Ctrl-C raises KeyboardInterrupt.");

    // ---- ElevatorScene
    py::class_<ElevatorScene>(m, "ElevatorScene",
                              "The traction elevator (SimbodyReeving::ElevatorScene) in one of EN 81-50's scenarios.")
        .def(py::init([](const ElevatorParameters& p, const SpanOptions& spans) {
                 py::gil_scoped_release release;
                 return std::make_unique<ElevatorScene>(p, spans);
             }),
             py::arg("parameters") = ElevatorParameters(), py::arg("spans") = SpanOptions())
        .def_property_readonly("parameters", [](const ElevatorScene& sc) { return sc.parameters(); }, "A copy of the parameters.")
        .def_property_readonly("reeving", &ElevatorScene::reeving, py::return_value_policy::reference_internal)
        .def_property_readonly("duration", &ElevatorScene::duration, "The scenario's run [s].")
        .def_property_readonly("car_total_mass", &ElevatorScene::carTotalMass, "[kg]")
        .def("make_initial_state", [](const ElevatorScene& s) { py::gil_scoped_release r; return s.makeInitialState(); })
        .def("car_height", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.carHeight(s); }, py::arg("state"), "[m]")
        .def("counterweight_height", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.counterweightHeight(s); }, py::arg("state"), "[m]")
        .def("car_velocity", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Velocity); return sc.carVelocity(s); }, py::arg("state"), "[m/s]")
        .def("car_acceleration", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Acceleration); return sc.carAcceleration(s); }, py::arg("state"), "[m/s^2]")
        .def("rope_travel", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.ropeTravel(s); }, py::arg("state"), "[m]")
        .def("car_side_force", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Dynamics); return sc.carSideForce(s); }, py::arg("state"), "[N]")
        .def("counterweight_side_force", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Dynamics); return sc.counterweightSideForce(s); }, py::arg("state"), "[N]")
        .def("traction_wrap_angle", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.tractionWrapAngle(s); }, py::arg("state"), "[rad]")
        .def("machine_work", [](const ElevatorScene& sc, const State& s) { realizeScene(sc, s, Stage::Velocity); return sc.workMeter().getWork(s); }, py::arg("state"), "[J]")
        .def("energy_residual", [](const ElevatorScene& sc, const State& s, double e0) { realizeScene(sc, s, Stage::Velocity); return sc.energyResidual(s, e0); }, py::arg("state"), py::arg("e0"), "[J]")
        .def(
            "simulation",
            [](const ElevatorScene& sc, const State& s, const std::string& integrator, double accuracy, double step) {
                return makeSimulation(sc, elevatorObserver(sc, initialEnergy(sc, s)), s, integrator, accuracy, step);
            },
            py::arg("state"), py::arg("integrator") = "rk-merson", py::arg("accuracy") = 1e-6,
            py::arg("fixed_step") = 0.0, py::keep_alive<0, 1>(),
            "A Simulation from `state` (its energy the residual's E(0)).");

    // ---- CraneScene
    py::class_<CraneScene>(m, "CraneScene", "The gantry crane (SimbodyReeving::CraneScene).")
        .def(py::init([](const CraneParameters& p, const std::optional<CraneCycle>& cycle, const SpanOptions& spans) {
                 py::gil_scoped_release release;
                 const CraneCycle c = cycle ? *cycle
                                            : p.scenario == CraneScenario::LiftOff ? CraneCycle::liftOff(p)
                                                                                   : CraneCycle::liftTraverseLower();
                 return std::make_unique<CraneScene>(p, c, spans);
             }),
             py::arg("parameters") = CraneParameters(), py::arg("cycle") = std::nullopt,
             py::arg("spans") = SpanOptions(),
             "cycle None: the demo's (lift_traverse_lower(), or lift_off(parameters) in CraneScenario.LiftOff).")
        .def_property_readonly("parameters", [](const CraneScene& sc) { return sc.parameters(); }, "A copy of the parameters.")
        .def_property_readonly("reeving", &CraneScene::reeving, py::return_value_policy::reference_internal)
        .def_property_readonly("duration", [](const CraneScene& sc) { return sc.cycle().duration; }, "[s]")
        .def_property_readonly("falls", &CraneScene::falls)
        .def("make_initial_state", [](const CraneScene& s) { py::gil_scoped_release r; return s.makeInitialState(); })
        .def("hook_position", [](const CraneScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return vec3(sc.hookPosition(s)); }, py::arg("state"), "[m]")
        .def("sway_angle", [](const CraneScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.swayAngle(s); }, py::arg("state"), "[rad]")
        .def("fall_top_force", [](const CraneScene& sc, const State& s, int fall) {
                if (fall < 0 || fall >= sc.falls()) throw std::out_of_range("fall " + std::to_string(fall) + " out of range: 0.." + std::to_string(sc.falls() - 1));
                realizeScene(sc, s, Stage::Dynamics);
                return sc.fallTopForce(s, fall);
            }, py::arg("state"), py::arg("fall"), "[N]")
        .def("sheave_wrap_angle", [](const CraneScene& sc, const State& s, int k) {
                if (k < 1 || k >= sc.falls()) throw std::out_of_range("sheave " + std::to_string(k) + " out of range: 1.." + std::to_string(sc.falls() - 1));
                realizeScene(sc, s, Stage::Position);
                return sc.sheaveWrapAngle(s, k);
            }, py::arg("state"), py::arg("k"), "[rad]")
        .def("rope_on_drum", [](const CraneScene& sc, const State& s) { realizeScene(sc, s, Stage::Position); return sc.ropeOnDrum(s); }, py::arg("state"), "[m]")
        .def("motor_torque", [](const CraneScene& sc, const State& s) { realizeScene(sc, s, Stage::Acceleration); return sc.motorTorque(s); }, py::arg("state"), "[N m]")
        .def("energy_residual", [](const CraneScene& sc, const State& s, double e0) { realizeScene(sc, s, Stage::Velocity); return sc.energyResidual(s, e0); }, py::arg("state"), py::arg("e0"), "[J]")
        .def(
            "simulation",
            [](const CraneScene& sc, const State& s, const std::string& integrator, double accuracy, double step) {
                return makeSimulation(sc, craneObserver(sc, initialEnergy(sc, s)), s, integrator, accuracy, step);
            },
            py::arg("state"), py::arg("integrator") = "rk-merson", py::arg("accuracy") = 1e-6,
            py::arg("fixed_step") = 0.0, py::keep_alive<0, 1>(),
            "A Simulation from `state` (its energy the residual's E(0)).");
}

}  // namespace simbody_reeving_python
