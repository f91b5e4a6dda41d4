#include "Machine.h"

#include "Casters.h"
#include "Errors.h"
#include "Simulation.h"

#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace py = pybind11;
using namespace SimbodyReeving;
using SimTK::Stage;
using SimTK::State;
using SimTK::Vec3;

namespace simbody_reeving_python {
namespace {

std::string text(double v) {
    std::ostringstream o;
    o.precision(17);
    o << v;
    return o.str();
}

bool finite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// ---- what a Python System owns ----------------------------------------------------------------

// The Simbody system and its subsystems, made in PendulumScene's order (matter, general forces,
// gravity, reeving), so a machine built like a bundled scene has the scene's state layout. Shared by
// the System, its bodies, node specs naming its bodies and rope handles: whichever Python object
// lives longest keeps it.
struct Machine {
    explicit Machine(const Vec3& g) : matter(system), forces(system), gravity(forces, matter, g), reeving(system, g) {}
    Machine(const Machine&) = delete;
    Machine& operator=(const Machine&) = delete;

    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter;
    SimTK::GeneralForceSubsystem forces;
    SimTK::Force::Gravity gravity;
    ReevingSubsystem reeving;
    std::vector<std::string> kinds{"Ground"};  // by MobilizedBodyIndex
    std::vector<int> mobilities{0};            // by MobilizedBodyIndex
    bool topology = false;
    State defaultState;  // after realizeTopology: the layout the queries' states must have

    void requireBuilding(const std::string& what) const {
        require(!topology, what + ": the System's topology is realized (realize_topology() or default_state() was "
                                  "called); add bodies, motions, forces and ropes before that");
    }
    void realizeTopology() {
        if (topology) return;
        system.realizeTopology();
        defaultState = system.getDefaultState();
        topology = true;
    }
    // A state of this system (its layout), realized to `stage`.
    const State& check(const State& s, Stage stage) const {
        require(topology, "the System's topology is not realized: make its states with default_state()");
        require(s.getNumSubsystems() == defaultState.getNumSubsystems() && s.getNQ() == defaultState.getNQ() &&
                    s.getNU() == defaultState.getNU() && s.getNZ() == defaultState.getNZ(),
                "the state is not one of this System's (nq " + std::to_string(s.getNQ()) + ", nu " +
                    std::to_string(s.getNU()) + ", nz " + std::to_string(s.getNZ()) + "; the System's: nq " +
                    std::to_string(defaultState.getNQ()) + ", nu " + std::to_string(defaultState.getNU()) +
                    ", nz " + std::to_string(defaultState.getNZ()) + ")");
        system.realize(s, stage);
        return s;
    }
};
using MachinePtr = std::shared_ptr<Machine>;

// A mobilized body of a Machine (Ground included).
struct Body {
    MachinePtr machine;
    SimTK::MobilizedBodyIndex index;
    const SimTK::MobilizedBody& get() const { return machine->matter.getMobilizedBody(index); }
};
using BodyPtr = std::shared_ptr<Body>;

// The System's Python face (the Machine behind a shared pointer).
struct System {
    MachinePtr machine;
};

// ---- conversions --------------------------------------------------------------------------------

py::array_t<double> mat33(const SimTK::Mat33& r) {
    py::array_t<double> a({py::ssize_t(3), py::ssize_t(3)});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a.mutable_data()[3 * i + j] = r(i, j);
    return a;
}

py::array_t<double> array(const SimTK::Vector& v) {
    py::array_t<double> a(v.size());
    for (int i = 0; i < v.size(); ++i) a.mutable_data()[i] = v[i];
    return a;
}

// A 3x3 array-like (rows). Plain arrays: SimTK's Mat33 arithmetic (transposes, columns) trips
// GCC 12's -Warray-bounds inside Simbody's headers.
using Rows = std::array<std::array<double, 3>, 3>;
Rows toRows(const py::object& o, const char* what) {
    py::array_t<double, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
    } catch (const py::error_already_set&) {
        a = {};
    }
    require(a && a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3,
            std::string(what) + " must be a 3x3 matrix (rows)");
    Rows m{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = a.data()[3 * i + j];
    return m;
}

// A rotation matrix given as rows: orthonormal with determinant +1 to 1e-9, used as given.
SimTK::Rotation toRotation(const py::object& o) {
    const Rows m = toRows(o, "rotation");
    double err = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double d = i == j ? -1.0 : 0.0;
            for (int k = 0; k < 3; ++k) d += m[k][i] * m[k][j];
            err = std::max(err, std::abs(d));
        }
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    require(std::isfinite(err) && err <= 1e-9 && det > 0,
            "rotation: the matrix must be orthonormal with determinant +1 (to 1e-9; |R^T R - I| = " + text(err) + ")");
    const SimTK::Mat33 r(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]);
    return SimTK::Rotation(r, true);
}

// A frame on a body: None (identity), a Transform, or a translation (three numbers).
SimTK::Transform toTransform(const py::object& o, const char* what) {
    if (o.is_none()) return SimTK::Transform();
    if (py::isinstance<SimTK::Transform>(o)) return o.cast<SimTK::Transform>();
    try {
        const Vec3 p = o.cast<Vec3>();
        require(finite(p), std::string(what) + ": the translation must be finite");
        return SimTK::Transform(p);
    } catch (const py::cast_error&) {
        throw py::type_error(std::string(what) + ": a Transform, a translation (three numbers) or None");
    }
}

// A number (any with __float__: a numpy scalar too) or a sequence of numbers.
std::vector<double> toValues(const py::object& o) {
    if (!PySequence_Check(o.ptr()) && py::hasattr(o, "__float__")) return {py::float_(o).cast<double>()};
    try {
        return o.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
        throw py::type_error("a number or a sequence of numbers, not " + std::string(py::str(o.get_type().attr("__name__"))));
    }
}

// ---- node specs: the C++ kind structs with the body as a Python Body ----------------------------

template <class Node>
struct PyNode {
    BodyPtr body;
    Node node;
    // The C++ struct with the body's handle (empty without a body: addRope's message names it).
    Node cpp() const {
        Node n = node;
        if (body) n.body = body->get();
        return n;
    }
};
using AnchorSpec = PyNode<RopeAnchor>;
using DeviationSpec = PyNode<DeviationSheave>;
using DrumSpec = PyNode<WinchDrum>;
using TurningSpec = PyNode<TurningSheave>;
using TractionSpec = PyNode<TractionSheave>;

template <class Node>
class NodeClass {
public:
    NodeClass(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc) {
        cls_.def_property(
            "body", [](const PyNode<Node>& s) { return s.body; },
            [](PyNode<Node>& s, BodyPtr b) { s.body = std::move(b); },
            "The Body the node is on (a System's body or ground; None: no body, which add_rope refuses).");
        names_.push_back("body");
    }
    template <class V>
    NodeClass& operator()(const char* name, V Node::*member, const char* doc) {
        cls_.def_property(
            name, [member](const PyNode<Node>& s) { return s.node.*member; },
            [member](PyNode<Node>& s, const V& v) { s.node.*member = v; }, doc);
        names_.push_back(name);
        return *this;
    }
    py::class_<PyNode<Node>>& cls() {
        const std::vector<std::string> names = names_;
        cls_.def("__repr__", [names](const py::object& self) {
            std::string s = std::string(py::str(self.get_type().attr("__name__"))) + "(";
            for (std::size_t i = 0; i < names.size(); ++i) {
                py::object v = self.attr(names[i].c_str());
                std::string r = py::isinstance<py::array>(v) ? std::string(py::repr(v.attr("tolist")()))
                                                             : std::string(py::repr(v));
                s += (i ? ", " : "") + names[i] + "=" + r;
            }
            return s + ")";
        });
        return cls_;
    }

private:
    py::class_<PyNode<Node>> cls_;
    std::vector<std::string> names_;
};

// ---- the rope spec: ends and sheaves as the Python node objects, checked on assignment ----------

struct PyRopeSpec {
    std::string name;
    py::object start, end;
    py::list sheaves;
    RopeProperties properties;
    double unstretchedLength, minimumSpanLength;
    SpanOptions spanDefaults;
    std::vector<std::pair<int, SpanOptions>> spanOverrides;
    Vec3 planeNormal;
    SheaveModel sheaveModel;

    PyRopeSpec() {
        const RopeSpec d;
        name = d.name;
        start = py::cast(AnchorSpec{});
        end = py::cast(AnchorSpec{});
        properties = d.properties;
        unstretchedLength = d.unstretchedLength;
        minimumSpanLength = d.minimumSpanLength;
        spanDefaults = d.spanDefaults;
        planeNormal = d.planeNormal;
        sheaveModel = d.sheaveModel;
    }
};

py::object checkEnd(const py::object& o, const char* which) {
    if (py::isinstance<AnchorSpec>(o) || py::isinstance<DrumSpec>(o)) return o;
    throw py::type_error(std::string("RopeSpec.") + which + ": a RopeAnchor or a WinchDrum (a rope end), not " +
                         std::string(py::str(o.get_type().attr("__name__"))));
}

py::list checkSheaves(const py::iterable& items) {
    py::list out;
    int k = 0;
    for (py::handle h : items) {
        if (!py::isinstance<DeviationSpec>(h) && !py::isinstance<TurningSpec>(h) && !py::isinstance<TractionSpec>(h))
            throw py::type_error("RopeSpec.sheaves[" + std::to_string(k) +
                                 "]: a DeviationSheave, TurningSheave or TractionSheave (a node inside the path), not " +
                                 std::string(py::str(h.get_type().attr("__name__"))));
        out.append(h);
        ++k;
    }
    return out;
}

RopeEnd toEnd(const py::object& o, const char* which) {
    checkEnd(o, which);
    if (py::isinstance<AnchorSpec>(o)) return o.cast<const AnchorSpec&>().cpp();
    return o.cast<const DrumSpec&>().cpp();
}

RopeSpec toCpp(const PyRopeSpec& p) {
    RopeSpec r;
    r.name = p.name;
    r.start = toEnd(p.start, "start");
    r.end = toEnd(p.end, "end");
    for (py::handle h : checkSheaves(p.sheaves)) {
        if (py::isinstance<DeviationSpec>(h))
            r.sheaves.emplace_back(h.cast<const DeviationSpec&>().cpp());
        else if (py::isinstance<TurningSpec>(h))
            r.sheaves.emplace_back(h.cast<const TurningSpec&>().cpp());
        else
            r.sheaves.emplace_back(h.cast<const TractionSpec&>().cpp());
    }
    r.properties = p.properties;
    r.unstretchedLength = p.unstretchedLength;
    r.minimumSpanLength = p.minimumSpanLength;
    r.spanDefaults = p.spanDefaults;
    r.spanOverrides = p.spanOverrides;
    r.planeNormal = p.planeNormal;
    r.sheaveModel = p.sheaveModel;
    return r;
}

// ---- rope and node handles: the C++ handles, with the Machine they refer to ---------------------

const char* kindName(const RopeNode& n) {
    switch (n.index()) {
        case 0: return "RopeAnchor";
        case 1: return "DeviationSheave";
        case 2: return "WinchDrum";
        case 3: return "TurningSheave";
        default: return "TractionSheave";
    }
}

struct NodeRef {
    NodeRef(MachinePtr m, int r, int n) : machine(std::move(m)), rope(r), node(n) {}
    virtual ~NodeRef() = default;
    MachinePtr machine;
    int rope, node;
    const ReevingSubsystem& reeving() const { return machine->reeving; }
    RopeNode spec() const { return reeving().getRopeSpec(rope).node(node); }
    bool isSheave() const { return node > 0 && node < reeving().getNumSpans(rope); }
};

struct PinnedRef : NodeRef {
    using NodeRef::NodeRef;
    virtual PinnedNodeHandle pinned() const = 0;
};

struct DrumRef : PinnedRef {
    DrumRef(MachinePtr m, WinchDrumHandle h) : PinnedRef(std::move(m), h.getRopeIndex(), h.getNodeIndex()), handle(h) {}
    WinchDrumHandle handle;
    PinnedNodeHandle pinned() const override { return handle; }
};

struct TurningRef : PinnedRef {
    TurningRef(MachinePtr m, TurningSheaveHandle h)
        : PinnedRef(std::move(m), h.getRopeIndex(), h.getNodeIndex()), handle(h) {}
    TurningSheaveHandle handle;
    PinnedNodeHandle pinned() const override { return handle; }
};

struct TractionRef : PinnedRef {
    TractionRef(MachinePtr m, TractionSheaveHandle h)
        : PinnedRef(std::move(m), h.getRopeIndex(), h.getNodeIndex()), handle(h) {}
    TractionSheaveHandle handle;
    PinnedNodeHandle pinned() const override { return handle; }
};

struct RopeRef {
    MachinePtr machine;
    RopeHandle handle;
    const ReevingSubsystem& reeving() const { return machine->reeving; }
    int index() const { return handle.getIndex(); }
    int numSpans() const { return reeving().getNumSpans(index()); }
    void checkSpan(int span) const {
        if (span < 0 || span >= numSpans())
            throw std::out_of_range("span " + std::to_string(span) + " out of range: the rope has " +
                                    std::to_string(numSpans()) + " span(s)");
    }
    void checkNode(int node) const {
        if (node < 0 || node > numSpans())
            throw std::out_of_range("node " + std::to_string(node) + " out of range: the rope has " +
                                    std::to_string(numSpans() + 1) + " nodes");
    }
    // Node k's handle, of its kind's class.
    std::shared_ptr<NodeRef> node(int k) const {
        checkNode(k);
        const RopeNode n = reeving().getRopeSpec(index()).node(k);
        if (std::holds_alternative<WinchDrum>(n)) return std::make_shared<DrumRef>(machine, handle.getWinchDrum(k));
        if (std::holds_alternative<TurningSheave>(n))
            return std::make_shared<TurningRef>(machine, handle.getTurningSheave(k));
        if (std::holds_alternative<TractionSheave>(n))
            return std::make_shared<TractionRef>(machine, handle.getTractionSheave(k));
        return std::make_shared<NodeRef>(machine, index(), k);
    }
};

// Whether getWrapAngle answers at node k: every sheave (the ends have none).
bool hasWrapAngle(const ReevingSubsystem& r, int rope, int k) { return k > 0 && k < r.getNumSpans(rope); }

// ---- the machine's reports: what Simulation.run returns for a System ----------------------------

Observer machineObserver(const Machine& m) {
    Observer o;
    o.columns = {"t"};
    const int nq = m.defaultState.getNQ(), nu = m.defaultState.getNU();
    for (int i = 0; i < nq; ++i) o.columns.push_back("q" + std::to_string(i));
    for (int i = 0; i < nu; ++i) o.columns.push_back("u" + std::to_string(i));
    o.columns.push_back("energy");
    const ReevingSubsystem& rv = m.reeving;
    for (int r = 0; r < rv.getNumRopes(); ++r) {
        const std::string rope = "rope" + std::to_string(r) + ".";
        for (int k = 0; k < rv.getNumSpans(r); ++k) {
            o.columns.push_back(rope + "span" + std::to_string(k) + ".axial_force_start");
            o.columns.push_back(rope + "span" + std::to_string(k) + ".axial_force_end");
        }
        for (int k = 0; k <= rv.getNumSpans(r); ++k) {
            const std::string node = rope + "node" + std::to_string(k) + ".";
            const RopeNode n = rv.getRopeSpec(r).node(k);
            o.columns.push_back(node + "material_coordinate");
            if (hasWrapAngle(rv, r, k)) o.columns.push_back(node + "wrap_angle");
            if (std::holds_alternative<WinchDrum>(n)) o.columns.push_back(node + "rope_on_drum");
            if (n.index() >= 2) o.columns.push_back(node + "torque");
            if (std::holds_alternative<TractionSheave>(n)) {
                o.columns.push_back(node + "slip_rate");
                o.columns.push_back(node + "traction_ratio");
                o.columns.push_back(node + "traction_limit");
            }
        }
    }
    const Machine* mp = &m;
    o.observe = [mp](const State& s, std::vector<double>& row) {
        const Machine& m = *mp;
        // Stage::Dynamics: node torques, and the quasi-static spans' mode-acceleration correction.
        m.system.realize(s, Stage::Dynamics);
        const ReevingSubsystem& rv = m.reeving;
        row.clear();
        row.push_back(s.getTime());
        for (int i = 0; i < s.getNQ(); ++i) row.push_back(s.getQ()[i]);
        for (int i = 0; i < s.getNU(); ++i) row.push_back(s.getU()[i]);
        row.push_back(rv.calcMechanicalEnergy(s));
        for (int r = 0; r < rv.getNumRopes(); ++r) {
            for (int k = 0; k < rv.getNumSpans(r); ++k) {
                const auto [s1, s2] = rv.getSpanMaterialRange(s, r, k);
                row.push_back(rv.getAxialForce(s, r, k, s1));
                row.push_back(rv.getAxialForce(s, r, k, s2));
            }
            const RopeHandle rope = rv.getRope(r);
            for (int k = 0; k <= rv.getNumSpans(r); ++k) {
                const RopeNode n = rv.getRopeSpec(r).node(k);
                row.push_back(rv.getMaterialCoordinate(s, r, k));
                if (hasWrapAngle(rv, r, k)) row.push_back(rv.getWrapAngle(s, r, k));
                if (std::holds_alternative<WinchDrum>(n)) {
                    const WinchDrumHandle h = rope.getWinchDrum(k);
                    row.push_back(h.getRopeOnDrum(s));
                    row.push_back(h.getTorque(s));
                } else if (std::holds_alternative<TurningSheave>(n)) {
                    row.push_back(rope.getTurningSheave(k).getTorque(s));
                } else if (std::holds_alternative<TractionSheave>(n)) {
                    const TractionSheaveHandle h = rope.getTractionSheave(k);
                    row.push_back(h.getTorque(s));
                    row.push_back(h.getSlipRate(s));
                    row.push_back(h.getTractionRatio(s));
                    row.push_back(h.getTractionLimit(s));
                }
            }
        }
    };
    return o;
}

// ---- bindings -----------------------------------------------------------------------------------

SimTK::Inertia toInertia(const py::object& o) {
    // A number: J about every axis; three numbers: the principal moments; six: xx, yy, zz, xy, xz, yz;
    // a 3x3 matrix. About the body's origin, in its frame [kg m^2].
    Rows m{};
    if (py::isinstance<py::float_>(o) || py::isinstance<py::int_>(o)) {
        for (int i = 0; i < 3; ++i) m[i][i] = o.cast<double>();
    } else {
        py::array_t<double, py::array::c_style | py::array::forcecast> a;
        try {
            a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
        } catch (const py::error_already_set&) {
            a = {};
        }
        require(bool(a), "inertia: a number, three moments, six components (xx, yy, zz, xy, xz, yz) or a 3x3 matrix");
        if (a.ndim() == 1 && a.shape(0) == 3) {
            for (int i = 0; i < 3; ++i) m[i][i] = a.data()[i];
        } else if (a.ndim() == 1 && a.shape(0) == 6) {
            const double* d = a.data();
            m = Rows{{{d[0], d[3], d[4]}, {d[3], d[1], d[5]}, {d[4], d[5], d[2]}}};
        } else {
            m = toRows(o, "inertia");
        }
    }
    double asym = 0;
    bool ok = true;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ok = ok && std::isfinite(m[i][j]);
            asym = std::max(asym, std::abs(m[i][j] - m[j][i]));
        }
    require(ok, "inertia [kg m^2] must be finite");
    const double xx = m[0][0], yy = m[1][1], zz = m[2][2];
    require(asym <= 1e-12 * std::max(1.0, std::abs(xx) + std::abs(yy) + std::abs(zz)), "inertia [kg m^2] must be symmetric");
    require(xx >= 0 && yy >= 0 && zz >= 0,
            "inertia: the moments [kg m^2] = " + text(xx) + ", " + text(yy) + ", " + text(zz) + " must be >= 0");
    const double slop = 1e-12 * std::max(1.0, xx + yy + zz);
    require(xx + yy + slop >= zz && xx + zz + slop >= yy && yy + zz + slop >= xx,
            "inertia: the moments [kg m^2] = " + text(xx) + ", " + text(yy) + ", " + text(zz) +
                " must satisfy the triangle inequality");
    return SimTK::Inertia(SimTK::SymMat33(xx, m[1][0], yy, m[2][0], m[2][1], zz));
}

BodyPtr makeBody(const MachinePtr& m, SimTK::MobilizedBodyIndex index) {
    return std::make_shared<Body>(Body{m, index});
}

const Body& checkParent(const System& sys, const BodyPtr& parent) {
    require(bool(parent), "parent: a Body (the System's ground or one of its bodies), not None");
    require(parent->machine == sys.machine, "parent: a body of another System");
    return *parent;
}

template <class Mobilizer, int Mobilities>
BodyPtr addBody(System& sys, const char* kind, const BodyPtr& parent, const SimTK::MassProperties& mass,
                const py::object& inParent, const py::object& inBody) {
    Machine& m = *sys.machine;
    m.requireBuilding(std::string("add_") + kind);
    const Body& p = checkParent(sys, parent);
    const SimTK::Transform X_PF = toTransform(inParent, "in_parent"), X_BM = toTransform(inBody, "in_body");
    Mobilizer mobod(m.matter.updMobilizedBody(p.index), X_PF, SimTK::Body::Rigid(mass), X_BM);
    const SimTK::MobilizedBodyIndex index = mobod.getMobilizedBodyIndex();
    if (static_cast<int>(m.kinds.size()) <= index) {
        m.kinds.resize(index + 1);
        m.mobilities.resize(index + 1);
    }
    m.kinds[index] = kind;
    m.mobilities[index] = Mobilities;
    return makeBody(sys.machine, index);
}

const char* const mobilizerDoc =
    "(parent, body, in_parent=None, in_body=None): a rigid body (body: MassProperties) on this mobilizer "
    "to `parent` (a Body of this System, ground included). in_parent: the mobilizer's fixed frame F on the "
    "parent, in_body: its moving frame M on the new body (each a Transform, a translation [m] or None: "
    "identity). Returns the new Body.";

void bindGeometry(py::module_& m) {
    py::class_<SimTK::Transform>(m, "Transform",
                                 "A frame (SimTK::Transform): rotation (3x3, rows) and origin p [m] in the "
                                 "frame it is measured from.")
        .def(py::init([](const py::object& rotation, const Vec3& p) {
                 require(finite(p), "Transform: p [m] must be finite");
                 if (rotation.is_none()) return SimTK::Transform(p);
                 return SimTK::Transform(toRotation(rotation), p);
             }),
             py::arg("rotation") = py::none(), py::arg("p") = Vec3(0),
             "rotation: a 3x3 rotation matrix (rows, orthonormal to 1e-9) or None (identity); p: the origin [m].")
        .def_static(
            "about_axis",
            [](double angle, const py::object& axis, const Vec3& p) {
                require(std::isfinite(angle), "Transform.about_axis: angle [rad] must be finite");
                require(finite(p), "Transform.about_axis: p [m] must be finite");
                Vec3 a(0);
                if (py::isinstance<py::str>(axis)) {
                    const std::string s = axis.cast<std::string>();
                    require(s == "x" || s == "y" || s == "z", "Transform.about_axis: axis '" + s + "' must be 'x', 'y' or 'z'");
                    a[s[0] - 'x'] = 1;
                } else {
                    a = axis.cast<Vec3>();
                    require(finite(a) && a.norm() > 0, "Transform.about_axis: the axis must be a finite non-zero vector");
                }
                return SimTK::Transform(SimTK::Rotation(angle, SimTK::UnitVec3(a)), p);
            },
            py::arg("angle"), py::arg("axis"), py::arg("p") = Vec3(0),
            "A rotation by `angle` [rad] about `axis` ('x', 'y', 'z' or a vector), origin p [m]. A Pin turns "
            "about z of its frames and a Slider slides along x (Simbody's): as in_parent, "
            "Transform.about_axis(pi/2, 'y') turns a Pin's axis to the parent's x, "
            "Transform.about_axis(-pi/2, 'z') a Slider's travel to the parent's -y.")
        .def_property_readonly("rotation", [](const SimTK::Transform& x) { return mat33(x.R()); }, "3x3 (rows)")
        .def_property_readonly("p", [](const SimTK::Transform& x) { return x.p(); }, "[m]")
        .def("__repr__", [](const SimTK::Transform& x) {
            std::ostringstream o;
            o.precision(17);
            o << "Transform(rotation=[";
            for (int i = 0; i < 3; ++i)
                o << (i ? ", [" : "[") << x.R().asMat33()(i, 0) << ", " << x.R().asMat33()(i, 1) << ", " << x.R().asMat33()(i, 2) << "]";
            o << "], p=[" << x.p()[0] << ", " << x.p()[1] << ", " << x.p()[2] << "])";
            return o.str();
        });

    py::class_<SimTK::MassProperties>(m, "MassProperties",
                                      "A rigid body's mass properties (SimTK::MassProperties; Body::Rigid is made "
                                      "from them): mass [kg], centre of mass in the body frame [m], inertia about "
                                      "the body's origin [kg m^2].")
        .def(py::init([](double mass, const Vec3& com, const py::object& inertia) {
                 require(std::isfinite(mass) && mass >= 0, "MassProperties: mass [kg] = " + text(mass) +
                                                                " must be finite and >= 0");
                 require(finite(com), "MassProperties: com [m] must be finite");
                 return SimTK::MassProperties(mass, com, toInertia(inertia));
             }),
             py::arg("mass"), py::arg("com") = Vec3(0), py::arg("inertia") = 0.0,
             "inertia about the body's origin (not the centre of mass), in the body frame: a number J (J about "
             "every axis, as Inertia(J)), three principal moments, six components (xx, yy, zz, xy, xz, yz) or a "
             "3x3 matrix.")
        .def_property_readonly("mass", &SimTK::MassProperties::getMass, "[kg]")
        .def_property_readonly("com", [](const SimTK::MassProperties& p) { return p.getMassCenter(); }, "[m]")
        .def_property_readonly("inertia", [](const SimTK::MassProperties& p) { return mat33(p.getInertia().toMat33()); },
                               "about the body's origin [kg m^2]");
}

void bindBodies(py::module_& m) {
    py::class_<Body, BodyPtr>(m, "Body",
                              "A body of a System on its mobilizer (a SimTK::MobilizedBody; system.ground is "
                              "Ground). Keeps its System alive. Queries realize the state as far as they need.")
        .def_property_readonly("index", [](const Body& b) { return static_cast<int>(b.index); },
                               "The MobilizedBodyIndex (0: ground).")
        .def_property_readonly("kind", [](const Body& b) { return b.machine->kinds[b.index]; },
                               "The mobilizer: 'Ground', 'Pin', 'Slider', 'Free', 'Ball', 'Weld' or 'Planar'.")
        .def("__eq__", [](const Body& a, const Body& b) { return a.machine == b.machine && a.index == b.index; })
        .def("__hash__", [](const Body& b) { return std::hash<const void*>()(b.machine.get()) ^ std::size_t(b.index); })
        .def("__repr__", [](const Body& b) {
            return "Body(" + b.machine->kinds[b.index] + ", index=" + std::to_string(static_cast<int>(b.index)) + ")";
        })
        .def("q_index", [](const Body& b, const State& s) { b.machine->check(s, Stage::Model); return static_cast<int>(b.get().getFirstQIndex(s)); },
             py::arg("state"), "Where its q start in the state's q (the reports' q<i> columns).")
        .def("u_index", [](const Body& b, const State& s) { b.machine->check(s, Stage::Model); return static_cast<int>(b.get().getFirstUIndex(s)); },
             py::arg("state"), "Where its u start in the state's u (the reports' u<i> columns).")
        .def("q", [](const Body& b, const State& s) { b.machine->check(s, Stage::Model); return array(b.get().getQAsVector(s)); },
             py::arg("state"), "Its mobilizer's generalized coordinates (a Pin: the angle [rad]; a Slider: [m]; "
                               "Free: quaternion then translation).")
        .def("u", [](const Body& b, const State& s) { b.machine->check(s, Stage::Model); return array(b.get().getUAsVector(s)); },
             py::arg("state"), "Its mobilizer's generalized speeds (a Pin: [rad/s]).")
        .def("set_q",
             [](const Body& b, State& s, const py::object& values) {
                 b.machine->check(s, Stage::Model);
                 const std::vector<double> v = toValues(values);
                 const int n = b.get().getNumQ(s);
                 require(static_cast<int>(v.size()) == n, "set_q: " + std::to_string(v.size()) +
                                                              " value(s) for the mobilizer's " + std::to_string(n) + " q");
                 for (int i = 0; i < n; ++i) b.get().setOneQ(s, i, v[i]);
             },
             py::arg("state"), py::arg("values"), "Sets the mobilizer's q (a number for one).")
        .def("set_u",
             [](const Body& b, State& s, const py::object& values) {
                 b.machine->check(s, Stage::Model);
                 const std::vector<double> v = toValues(values);
                 const int n = b.get().getNumU(s);
                 require(static_cast<int>(v.size()) == n, "set_u: " + std::to_string(v.size()) +
                                                              " value(s) for the mobilizer's " + std::to_string(n) + " u");
                 for (int i = 0; i < n; ++i) b.get().setOneU(s, i, v[i]);
             },
             py::arg("state"), py::arg("values"), "Sets the mobilizer's u (a number for one).")
        .def("set_q_to_fit_translation",
             [](const Body& b, State& s, const Vec3& p) { b.machine->check(s, Stage::Model); b.get().setQToFitTranslation(s, p); },
             py::arg("state"), py::arg("p"), "q that best put M's origin at p in F [m] (MobilizedBody::setQToFitTranslation).")
        .def("set_q_to_fit_rotation",
             [](const Body& b, State& s, const py::object& r) { b.machine->check(s, Stage::Model); b.get().setQToFitRotation(s, toRotation(r)); },
             py::arg("state"), py::arg("rotation"), "q that best give M the rotation (3x3) in F.")
        .def("set_u_to_fit_linear_velocity",
             [](const Body& b, State& s, const Vec3& v) { b.machine->check(s, Stage::Model); b.get().setUToFitLinearVelocity(s, v); },
             py::arg("state"), py::arg("v"), "u that best give M's origin the velocity v in F [m/s].")
        .def("set_u_to_fit_angular_velocity",
             [](const Body& b, State& s, const Vec3& w) { b.machine->check(s, Stage::Model); b.get().setUToFitAngularVelocity(s, w); },
             py::arg("state"), py::arg("w"), "u that best give M the angular velocity w in F [rad/s].")
        .def("position", [](const Body& b, const State& s) { b.machine->check(s, Stage::Position); return b.get().getBodyOriginLocation(s); },
             py::arg("state"), "The body origin in Ground [m].")
        .def("rotation", [](const Body& b, const State& s) { b.machine->check(s, Stage::Position); return mat33(b.get().getBodyRotation(s)); },
             py::arg("state"), "The body's rotation in Ground (3x3, rows).")
        .def("station_position",
             [](const Body& b, const State& s, const Vec3& station) {
                 b.machine->check(s, Stage::Position);
                 return b.get().findStationLocationInGround(s, station);
             },
             py::arg("state"), py::arg("station"), "A point fixed on the body (body frame [m]) in Ground [m].")
        .def("velocity", [](const Body& b, const State& s) { b.machine->check(s, Stage::Velocity); return b.get().getBodyOriginVelocity(s); },
             py::arg("state"), "The body origin's velocity in Ground [m/s].")
        .def("angular_velocity", [](const Body& b, const State& s) { b.machine->check(s, Stage::Velocity); return b.get().getBodyAngularVelocity(s); },
             py::arg("state"), "In Ground [rad/s].")
        .def("prescribe_steady_speed",
             [](const Body& b, double u) {
                 b.machine->requireBuilding("prescribe_steady_speed");
                 require(b.machine->mobilities[b.index] > 0,
                         "prescribe_steady_speed: the " + b.machine->kinds[b.index] + " has no mobilities");
                 require(std::isfinite(u), "prescribe_steady_speed: u = " + text(u) + " must be finite");
                 SimTK::Motion::Steady(b.machine->matter.updMobilizedBody(b.index), u);
             },
             py::arg("u"),
             "Prescribes every generalized speed of the mobilizer to u (SimTK::Motion::Steady; u = 0 holds a drum "
             "at its q; find_static_equilibrium keeps prescribed mobilities). Before realize_topology().");
}

void bindNodeSpecs(py::module_& m) {
    NodeClass<RopeAnchor>(m, "RopeAnchor", "A rope end fastened to a station of a body (SimbodyReeving::RopeAnchor).")
        ("station", &RopeAnchor::station, "the point in the body's frame [m]")
        .cls()
        .def(py::init([](BodyPtr body, const Vec3& station) { return AnchorSpec{std::move(body), RopeAnchor{{}, station}}; }),
             py::arg("body") = nullptr, py::arg("station") = Vec3(0));

    const DeviationSheave ds;
    NodeClass<DeviationSheave>(m, "DeviationSheave", "A frictionless sheave in the path (SimbodyReeving::DeviationSheave).")
        ("centre", &DeviationSheave::centre, "in the body's frame [m]")
        ("radius", &DeviationSheave::radius, "[m], > 0")
        ("wrap_sense", &DeviationSheave::wrapSense, "SheaveModel.Wrapped: +1 counter-clockwise about the plane normal (spatial: about axis), -1 clockwise")
        ("axis", &DeviationSheave::axis, "SheaveModel.Wrapped on a spatial rope: the groove's unit axis in the body frame")
        .cls()
        .def(py::init([](BodyPtr body, const Vec3& centre, double radius, int wrapSense, const Vec3& axis) {
                 DeviationSheave n;
                 n.centre = centre;
                 n.radius = radius;
                 n.wrapSense = wrapSense;
                 n.axis = axis;
                 return DeviationSpec{std::move(body), n};
             }),
             py::arg("body") = nullptr, py::arg("centre") = ds.centre, py::arg("radius") = ds.radius,
             py::arg("wrap_sense") = ds.wrapSense, py::arg("axis") = ds.axis);

    const WinchDrum wd;
    NodeClass<WinchDrum>(m, "WinchDrum", "A rope end wound on a drum on a Pin body (SimbodyReeving::WinchDrum).")
        ("radius", &WinchDrum::radius, "R [m], > 0")
        ("rope_on_drum", &WinchDrum::ropeOnDrum, "rope stored at pin angle 0 [m], >= 0 (stored: rope_on_drum - payout_sense R theta)")
        ("payout_sense", &WinchDrum::payoutSense, "+1: a positive pin angle pays rope out; -1: hauls in")
        ("centre", &WinchDrum::centre, "the node's point on the pin axis, body frame [m]")
        ("pitch", &WinchDrum::pitch, "axial advance per turn on a spatial wrapped rope [m] (0: none)")
        .cls()
        .def(py::init([](BodyPtr body, double radius, double ropeOnDrum, int payoutSense, const Vec3& centre, double pitch) {
                 WinchDrum n;
                 n.radius = radius;
                 n.ropeOnDrum = ropeOnDrum;
                 n.payoutSense = payoutSense;
                 n.centre = centre;
                 n.pitch = pitch;
                 return DrumSpec{std::move(body), n};
             }),
             py::arg("body") = nullptr, py::arg("radius") = wd.radius, py::arg("rope_on_drum") = wd.ropeOnDrum,
             py::arg("payout_sense") = wd.payoutSense, py::arg("centre") = wd.centre, py::arg("pitch") = wd.pitch);

    const TurningSheave ts;
    NodeClass<TurningSheave>(m, "TurningSheave", "A sheave on a Pin body the rope turns without slip (SimbodyReeving::TurningSheave).")
        ("radius", &TurningSheave::radius, "R [m], > 0")
        ("material_coordinate_at_zero_angle", &TurningSheave::materialCoordinateAtZeroAngle, "s_ref [m]: s = s_ref + sense R theta")
        ("sense", &TurningSheave::sense, "+1 or -1")
        ("centre", &TurningSheave::centre, "the node's point on the pin axis, body frame [m]")
        .cls()
        .def(py::init([](BodyPtr body, double radius, double sRef, int sense, const Vec3& centre) {
                 TurningSheave n;
                 n.radius = radius;
                 n.materialCoordinateAtZeroAngle = sRef;
                 n.sense = sense;
                 n.centre = centre;
                 return TurningSpec{std::move(body), n};
             }),
             py::arg("body") = nullptr, py::arg("radius") = ts.radius,
             py::arg("material_coordinate_at_zero_angle") = ts.materialCoordinateAtZeroAngle,
             py::arg("sense") = ts.sense, py::arg("centre") = ts.centre);

    const TractionSheave tr;
    NodeClass<TractionSheave>(m, "TractionSheave",
                              "A sheave on a Pin body whose groove drives the rope by friction (SimbodyReeving::TractionSheave).")
        ("radius", &TractionSheave::radius, "R [m], > 0")
        ("friction_coefficient", &TractionSheave::frictionCoefficient, "mu [-], >= 0")
        ("wrap_angle", &TractionSheave::wrapAngle, "alpha [rad]; 0: the geometry's")
        ("material_coordinate_at_zero_angle", &TractionSheave::materialCoordinateAtZeroAngle, "s_ref [m] with no slip yet")
        ("sense", &TractionSheave::sense, "+1 or -1, as a TurningSheave's")
        ("centre", &TractionSheave::centre, "the node's point on the pin axis, body frame [m]")
        ("slip_model", &TractionSheave::slipModel, "TractionSlip")
        .cls()
        .def(py::init([](BodyPtr body, double radius, double mu, double alpha, double sRef, int sense, const Vec3& centre,
                         TractionSlip slip) {
                 TractionSheave n;
                 n.radius = radius;
                 n.frictionCoefficient = mu;
                 n.wrapAngle = alpha;
                 n.materialCoordinateAtZeroAngle = sRef;
                 n.sense = sense;
                 n.centre = centre;
                 n.slipModel = slip;
                 return TractionSpec{std::move(body), n};
             }),
             py::arg("body") = nullptr, py::arg("radius") = tr.radius, py::arg("friction_coefficient") = tr.frictionCoefficient,
             py::arg("wrap_angle") = tr.wrapAngle,
             py::arg("material_coordinate_at_zero_angle") = tr.materialCoordinateAtZeroAngle, py::arg("sense") = tr.sense,
             py::arg("centre") = tr.centre, py::arg("slip_model") = tr.slipModel);

    const RopeProperties rp;
    py::class_<RopeProperties>(m, "RopeProperties", "The rope's section (SimbodyReeving::RopeProperties), SI units.")
        .def(py::init([](double rhoA, double EA, double EI, bool tensionOnly, double c) {
                 RopeProperties p;
                 p.massPerLength = rhoA;
                 p.axialStiffness = EA;
                 p.bendingStiffness = EI;
                 p.tensionOnly = tensionOnly;
                 p.axialRetardationTime = c;
                 return p;
             }),
             py::arg("mass_per_length") = rp.massPerLength, py::arg("axial_stiffness") = rp.axialStiffness,
             py::arg("bending_stiffness") = rp.bendingStiffness, py::arg("tension_only") = rp.tensionOnly,
             py::arg("axial_retardation_time") = rp.axialRetardationTime)
        .def_readwrite("mass_per_length", &RopeProperties::massPerLength, "rhoA [kg/m], > 0")
        .def_readwrite("axial_stiffness", &RopeProperties::axialStiffness, "EA [N], > 0")
        .def_readwrite("bending_stiffness", &RopeProperties::bendingStiffness, "EI [N m^2], >= 0")
        .def_readwrite("tension_only", &RopeProperties::tensionOnly, "True: P = EA max(eps, 0); False: the paper's P = EA eps")
        .def_readwrite("axial_retardation_time", &RopeProperties::axialRetardationTime, "Kelvin-Voigt c [s], >= 0")
        .def("__repr__", [](const RopeProperties& p) {
            return "RopeProperties(mass_per_length=" + text(p.massPerLength) + ", axial_stiffness=" + text(p.axialStiffness) +
                   ", bending_stiffness=" + text(p.bendingStiffness) + ", tension_only=" + (p.tensionOnly ? "True" : "False") +
                   ", axial_retardation_time=" + text(p.axialRetardationTime) + ")";
        });

    const RopeSpec d;
    py::class_<PyRopeSpec>(m, "RopeSpec",
                           "Everything that describes one rope (SimbodyReeving::RopeSpec), SI units: start and end a "
                           "RopeAnchor or a WinchDrum, sheaves a list of DeviationSheave, TurningSheave or "
                           "TractionSheave in path order (other kinds raise TypeError on assignment).")
        .def(py::init([](const std::string& name, const py::object& start, const py::iterable& sheaves,
                         const py::object& end, const RopeProperties& properties, double unstretchedLength,
                         double minimumSpanLength, const SpanOptions& spanDefaults,
                         const std::vector<std::pair<int, SpanOptions>>& spanOverrides, const Vec3& planeNormal,
                         SheaveModel sheaveModel) {
                 PyRopeSpec s;
                 s.name = name;
                 if (!start.is_none()) s.start = checkEnd(start, "start");
                 s.sheaves = checkSheaves(sheaves);
                 if (!end.is_none()) s.end = checkEnd(end, "end");
                 s.properties = properties;
                 s.unstretchedLength = unstretchedLength;
                 s.minimumSpanLength = minimumSpanLength;
                 s.spanDefaults = spanDefaults;
                 s.spanOverrides = spanOverrides;
                 s.planeNormal = planeNormal;
                 s.sheaveModel = sheaveModel;
                 return s;
             }),
             py::arg("name") = d.name, py::arg("start") = py::none(), py::arg("sheaves") = py::list(),
             py::arg("end") = py::none(), py::arg("properties") = d.properties,
             py::arg("unstretched_length") = d.unstretchedLength, py::arg("minimum_span_length") = d.minimumSpanLength,
             py::arg("span_defaults") = d.spanDefaults, py::arg("span_overrides") = d.spanOverrides,
             py::arg("plane_normal") = d.planeNormal, py::arg("sheave_model") = d.sheaveModel,
             "start / end None: a RopeAnchor without a body (add_rope names it).")
        .def_readwrite("name", &PyRopeSpec::name, "names the rope in messages")
        .def_property("start", [](const PyRopeSpec& s) { return s.start; },
                      [](PyRopeSpec& s, const py::object& o) { s.start = checkEnd(o, "start"); }, "RopeAnchor or WinchDrum")
        .def_property("end", [](const PyRopeSpec& s) { return s.end; },
                      [](PyRopeSpec& s, const py::object& o) { s.end = checkEnd(o, "end"); }, "RopeAnchor or WinchDrum")
        .def_property("sheaves", [](const PyRopeSpec& s) { return s.sheaves; },
                      [](PyRopeSpec& s, const py::iterable& o) { s.sheaves = checkSheaves(o); },
                      "DeviationSheave, TurningSheave or TractionSheave, in path order (a list)")
        .def_readwrite("properties", &PyRopeSpec::properties, "RopeProperties")
        .def_readwrite("unstretched_length", &PyRopeSpec::unstretchedLength, "L [m] between the end nodes at pin angles 0, > 0")
        .def_readwrite("minimum_span_length", &PyRopeSpec::minimumSpanLength, "[m], > 0: a shorter span ends the run")
        .def_readwrite("span_defaults", &PyRopeSpec::spanDefaults, "SpanOptions of every span...")
        .def_readwrite("span_overrides", &PyRopeSpec::spanOverrides, "...but these: a list of (span index, SpanOptions) (assign a new list)")
        .def_readwrite("plane_normal", &PyRopeSpec::planeNormal, "non-zero: a planar rope in the plane through the start with this normal")
        .def_readwrite("sheave_model", &PyRopeSpec::sheaveModel, "SheaveModel")
        .def("num_nodes", [](const PyRopeSpec& s) { return static_cast<int>(py::len(s.sheaves)) + 2; });
}

void bindHandles(py::module_& m) {
    auto realize = [](const NodeRef& n, const State& s, Stage stage) -> const State& { return n.machine->check(s, stage); };

    py::class_<NodeRef, std::shared_ptr<NodeRef>>(
        m, "RopeNodeHandle",
        "A node of a rope (its rope and node indices): the queries every node answers. Nodes of the kinds with "
        "queries of their own come as WinchDrumHandle, TurningSheaveHandle or TractionSheaveHandle. Keeps its System alive.")
        .def_property_readonly("rope_index", [](const NodeRef& n) { return n.rope; })
        .def_property_readonly("node_index", [](const NodeRef& n) { return n.node; }, "0: start, 1..N-1 the sheaves, N: end")
        .def_property_readonly("kind", [](const NodeRef& n) { return std::string(kindName(n.spec())); })
        .def("__repr__", [](const NodeRef& n) {
            return std::string(kindName(n.spec())) + " node " + std::to_string(n.node) + " of rope " + std::to_string(n.rope);
        })
        .def("material_coordinate",
             [realize](const NodeRef& n, const State& s) { return n.reeving().getMaterialCoordinate(realize(n, s, Stage::Position), n.rope, n.node); },
             py::arg("state"), "The rope's material coordinate s at the node [m] (a wrapped sheave: where the rope arrives).")
        .def("node_force",
             [realize](const NodeRef& n, const State& s) { return n.reeving().getNodeForce(realize(n, s, Stage::Dynamics), n.rope, n.node); },
             py::arg("state"), "The force the rope exerts on the node's body, in Ground [N] (at a sheave: the bearing load).")
        .def("wrap_angle",
             [realize](const NodeRef& n, const State& s) { return n.reeving().getWrapAngle(realize(n, s, Stage::Position), n.rope, n.node); },
             py::arg("state"), "alpha [rad] at a sheave (ValueError at an end, or a point sheave of a spatial rope).")
        .def("arc_length",
             [realize](const NodeRef& n, const State& s) { return n.reeving().getArcLength(realize(n, s, Stage::Position), n.rope, n.node); },
             py::arg("state"), "The rope on the groove R alpha [m] (0 at point nodes and drums).");

    py::class_<PinnedRef, NodeRef, std::shared_ptr<PinnedRef>>(
        m, "PinnedNodeHandle", "A node on a Pin body whose material coordinate turns with it (drum, turning or traction sheave).")
        .def("torque", [realize](const PinnedRef& n, const State& s) { return n.pinned().getTorque(realize(n, s, Stage::Dynamics)); },
             py::arg("state"), "The rope's torque on the pin about its axis [N m].")
        .def("power", [realize](const PinnedRef& n, const State& s) { return n.pinned().getPower(realize(n, s, Stage::Dynamics)); },
             py::arg("state"), "The rope's power into the pin's body [W].");

    py::class_<DrumRef, PinnedRef, std::shared_ptr<DrumRef>>(m, "WinchDrumHandle", "A WinchDrum at a rope end.")
        .def("rope_on_drum", [realize](const DrumRef& n, const State& s) { return n.handle.getRopeOnDrum(realize(n, s, Stage::Position)); },
             py::arg("state"), "Rope stored on the drum [m]: rope_on_drum - payout_sense R theta.");

    py::class_<TurningRef, PinnedRef, std::shared_ptr<TurningRef>>(m, "TurningSheaveHandle", "A TurningSheave in a rope's path.");

    py::enum_<TractionMode>(m, "TractionMode")
        .value("Stick", TractionMode::Stick)
        .value("SlipTowardStart", TractionMode::SlipTowardStart)
        .value("SlipTowardEnd", TractionMode::SlipTowardEnd);

    py::class_<TractionRef, PinnedRef, std::shared_ptr<TractionRef>>(m, "TractionSheaveHandle",
                                                                     "A TractionSheave in a rope's path: its phase, slip and friction.")
        .def("traction_mode", [realize](const TractionRef& n, const State& s) { return n.handle.getTractionMode(realize(n, s, Stage::Model)); },
             py::arg("state"), "TractionMode: Stick, SlipTowardStart, SlipTowardEnd.")
        .def("slip_rate", [realize](const TractionRef& n, const State& s) { return n.handle.getSlipRate(realize(n, s, Stage::Velocity)); },
             py::arg("state"), "The rope's speed over the groove, positive towards the rope's start [m/s] (0 in stick).")
        .def("slip_distance", [realize](const TractionRef& n, const State& s) { return n.handle.getSlipDistance(realize(n, s, Stage::Position)); },
             py::arg("state"), "How far the rope has slid over the groove since the start [m].")
        .def("traction_ratio", [realize](const TractionRef& n, const State& s) { return n.handle.getTractionRatio(realize(n, s, Stage::Position)); },
             py::arg("state"), "P_a / P_b of the spans before and after the sheave [-] (NaN if P_b <= 0).")
        .def("traction_limit", [realize](const TractionRef& n, const State& s) { return n.handle.getTractionLimit(realize(n, s, Stage::Position)); },
             py::arg("state"), "e^(mu alpha) [-], the ratio at which the rope slips.")
        .def("friction_power", [realize](const TractionRef& n, const State& s) { return n.handle.getFrictionPower(realize(n, s, Stage::Velocity)); },
             py::arg("state"), "[W], >= 0 (0 in stick).")
        .def("friction_work", [realize](const TractionRef& n, const State& s) { return n.handle.getFrictionWork(realize(n, s, Stage::Velocity)); },
             py::arg("state"), "[J] since the start.")
        .def("num_traction_transitions",
             [realize](const TractionRef& n, const State& s) { return n.handle.getNumTractionTransitions(realize(n, s, Stage::Model)); },
             py::arg("state"));

    auto check = [](const RopeRef& r, const State& s, Stage stage) -> const State& { return r.machine->check(s, stage); };
    py::class_<RopeRef>(m, "RopeHandle",
                        "One rope of a System (System.add_rope): its nodes' typed handles and its queries as numpy "
                        "arrays. Keeps its System alive; int(rope) is its index for ReevingSubsystem's queries.")
        .def_property_readonly("index", &RopeRef::index)
        .def("__int__", &RopeRef::index)
        .def("__index__", &RopeRef::index)
        .def_property_readonly("name", [](const RopeRef& r) { return r.reeving().getRopeSpec(r.index()).name; })
        .def_property_readonly("num_nodes", [](const RopeRef& r) { return r.handle.getNumNodes(); })
        .def_property_readonly("num_spans", &RopeRef::numSpans)
        .def_property_readonly("is_planar", [](const RopeRef& r) { return r.reeving().isPlanar(r.index()); })
        .def_property_readonly("unstretched_length", [](const RopeRef& r) { return r.reeving().getRopeSpec(r.index()).unstretchedLength; }, "[m]")
        .def("node", &RopeRef::node, py::arg("k"),
             "Node k's handle, of its kind's class (WinchDrumHandle, TurningSheaveHandle, TractionSheaveHandle; "
             "RopeNodeHandle for an anchor or a deviation sheave).")
        .def_property_readonly("nodes", [](const RopeRef& r) {
            std::vector<std::shared_ptr<NodeRef>> v;
            for (int k = 0; k < r.handle.getNumNodes(); ++k) v.push_back(r.node(k));
            return v;
        })
        .def("winch_drum", [](const RopeRef& r, int k) { return std::make_shared<DrumRef>(r.machine, r.handle.getWinchDrum(k)); },
             py::arg("k"), "Node k as a WinchDrumHandle (ValueError if it is not a WinchDrum).")
        .def("turning_sheave", [](const RopeRef& r, int k) { return std::make_shared<TurningRef>(r.machine, r.handle.getTurningSheave(k)); },
             py::arg("k"), "Node k as a TurningSheaveHandle (ValueError if it is not one).")
        .def("traction_sheave", [](const RopeRef& r, int k) { return std::make_shared<TractionRef>(r.machine, r.handle.getTractionSheave(k)); },
             py::arg("k"), "Node k as a TractionSheaveHandle (ValueError if it is not one).")
        .def("axial_force_along",
             [check](const RopeRef& r, const State& s, int span, int points) {
                 r.checkSpan(span);
                 require(points >= 2, "points = " + std::to_string(points) + " must be >= 2");
                 const ReevingSubsystem& rv = r.reeving();
                 check(r, s, Stage::Dynamics);
                 const auto [s1, s2] = rv.getSpanMaterialRange(s, r.index(), span);
                 py::array_t<double> sa(points), pa(points);
                 for (int k = 0; k < points; ++k) {
                     const double sk = s1 + (s2 - s1) * k / static_cast<double>(points - 1);
                     sa.mutable_data()[k] = sk;
                     pa.mutable_data()[k] = rv.getAxialForce(s, r.index(), span, std::min(sk, s2));
                 }
                 return py::make_tuple(sa, pa);
             },
             py::arg("state"), py::arg("span"), py::arg("points") = 60,
             "(s, P): the axial force P = EA eps [N] at `points` equally spaced material coordinates s [m] of the span.")
        .def("span_end_forces",
             [check](const RopeRef& r, const State& s) {
                 const ReevingSubsystem& rv = r.reeving();
                 check(r, s, Stage::Dynamics);
                 py::array_t<double> a({py::ssize_t(r.numSpans()), py::ssize_t(2)});
                 for (int k = 0; k < r.numSpans(); ++k) {
                     const auto [s1, s2] = rv.getSpanMaterialRange(s, r.index(), k);
                     a.mutable_data()[2 * k] = rv.getAxialForce(s, r.index(), k, s1);
                     a.mutable_data()[2 * k + 1] = rv.getAxialForce(s, r.index(), k, s2);
                 }
                 return a;
             },
             py::arg("state"), "(num_spans, 2): each span's axial force at its start and its end [N].")
        .def("node_forces",
             [check](const RopeRef& r, const State& s) {
                 check(r, s, Stage::Dynamics);
                 py::array_t<double> a({py::ssize_t(r.numSpans() + 1), py::ssize_t(3)});
                 for (int k = 0; k <= r.numSpans(); ++k) {
                     const Vec3 f = r.reeving().getNodeForce(s, r.index(), k);
                     for (int j = 0; j < 3; ++j) a.mutable_data()[3 * k + j] = f[j];
                 }
                 return a;
             },
             py::arg("state"), "(num_nodes, 3): the force the rope exerts on each node's body, in Ground [N].")
        .def("material_coordinates",
             [check](const RopeRef& r, const State& s) {
                 check(r, s, Stage::Position);
                 py::array_t<double> a(r.numSpans() + 1);
                 for (int k = 0; k <= r.numSpans(); ++k) a.mutable_data()[k] = r.reeving().getMaterialCoordinate(s, r.index(), k);
                 return a;
             },
             py::arg("state"), "s at every node [m].")
        .def("wrap_angles",
             [check](const RopeRef& r, const State& s) {
                 check(r, s, Stage::Position);
                 py::array_t<double> a(r.numSpans() - 1);
                 for (int k = 1; k < r.numSpans(); ++k) a.mutable_data()[k - 1] = r.reeving().getWrapAngle(s, r.index(), k);
                 return a;
             },
             py::arg("state"),
             "alpha at sheaves 1..N-1 [rad] (at a point sheave the turning angle between its chords).")
        .def("fleet_angles",
             [check](const RopeRef& r, const State& s) {
                 check(r, s, Stage::Position);
                 py::array_t<double> a({py::ssize_t(r.numSpans()), py::ssize_t(2)});
                 for (int k = 0; k < r.numSpans(); ++k) {
                     const auto [g0, g1] = r.reeving().getFleetAngles(s, r.index(), k);
                     a.mutable_data()[2 * k] = g0;
                     a.mutable_data()[2 * k + 1] = g1;
                 }
                 return a;
             },
             py::arg("state"), "(num_spans, 2): each span's fleet angles at its start and end [rad] (0 on planar ropes).")
        .def("sample_span",
             [check](const RopeRef& r, const State& s, int span, int points) {
                 r.checkSpan(span);
                 require(points >= 2, "points = " + std::to_string(points) + " must be >= 2");
                 check(r, s, Stage::Position);
                 const std::vector<Vec3> p = r.reeving().sampleSpan(s, r.index(), span, points);
                 py::array_t<double> a({static_cast<py::ssize_t>(p.size()), py::ssize_t(3)});
                 for (std::size_t i = 0; i < p.size(); ++i)
                     for (int j = 0; j < 3; ++j) a.mutable_data()[3 * i + j] = p[i][j];
                 return a;
             },
             py::arg("state"), py::arg("span"), py::arg("points") = 20, "(points, 3): the span's centre line in Ground [m].");
}

void bindSystem(py::module_& m) {
    py::class_<System>(m, "System",
                       "One's own machine: a SimTK::MultibodySystem with its SimbodyMatterSubsystem, a "
                       "GeneralForceSubsystem holding one Force::Gravity, and a ReevingSubsystem (the ropes feel the "
                       "same gravity). Add bodies and ropes, then default_state(); the bodies, ropes and node handles "
                       "keep it alive.")
        .def(py::init([](const Vec3& gravity) {
                 require(finite(gravity), "System: gravity [m/s^2] must be finite");
                 return System{std::make_shared<Machine>(gravity)};
             }),
             py::arg("gravity") = Vec3(0, -9.81, 0), "gravity [m/s^2] on bodies and ropes")
        .def_property_readonly("gravity", [](const System& s) { return s.machine->gravity.getDefaultGravityVector(); }, "[m/s^2]")
        .def_property_readonly("ground", [](const System& s) { return makeBody(s.machine, SimTK::GroundIndex); })
        .def_property_readonly("num_bodies", [](const System& s) { return s.machine->matter.getNumBodies(); }, "ground included")
        .def("body", [](const System& s, int index) {
                if (index < 0 || index >= s.machine->matter.getNumBodies())
                    throw std::out_of_range("body " + std::to_string(index) + " out of range: the System has " +
                                            std::to_string(s.machine->matter.getNumBodies()) + " (ground included)");
                return makeBody(s.machine, SimTK::MobilizedBodyIndex(index));
            }, py::arg("index"))
        .def("add_pin", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Pin, 1>(s, "Pin", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Pin, one rotation about z of F and M ") + mobilizerDoc).c_str())
        .def("add_slider", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Slider, 1>(s, "Slider", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Slider, one translation along x of F and M ") + mobilizerDoc).c_str())
        .def("add_free", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Free, 6>(s, "Free", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Free, six mobilities (q: quaternion then translation) ") + mobilizerDoc).c_str())
        .def("add_ball", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Ball, 3>(s, "Ball", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Ball, three rotations (a quaternion) ") + mobilizerDoc).c_str())
        .def("add_planar", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Planar, 3>(s, "Planar", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Planar, rotation about z then translation in x-y ") + mobilizerDoc).c_str())
        .def("add_weld", [](System& s, const BodyPtr& parent, const SimTK::MassProperties& body, const py::object& inParent, const py::object& inBody) {
                 return addBody<SimTK::MobilizedBody::Weld, 0>(s, "Weld", parent, body, inParent, inBody);
             }, py::arg("parent"), py::arg("body"), py::arg("in_parent") = py::none(),
             py::arg("in_body") = py::none(), (std::string("MobilizedBody::Weld, no mobility ") + mobilizerDoc).c_str())
        .def("add_mobility_force",
             [](System& sys, const BodyPtr& body, double force, int u) {
                 Machine& m = *sys.machine;
                 m.requireBuilding("add_mobility_force");
                 const Body& b = checkParent(sys, body);
                 require(std::isfinite(force), "add_mobility_force: force = " + text(force) + " must be finite");
                 const int n = m.mobilities[b.index];
                 require(u >= 0 && u < n, "add_mobility_force: u_index = " + std::to_string(u) + " is outside 0.." +
                                              std::to_string(n - 1) + " (the " + m.kinds[b.index] + "'s mobilities)");
                 SimTK::Force::MobilityConstantForce(m.forces, b.get(), SimTK::MobilizerUIndex(u), force);
             },
             py::arg("body"), py::arg("force"), py::arg("u_index") = 0,
             "A constant generalized force on one of the body's mobilities (Force::MobilityConstantForce: a torque "
             "[N m] on a Pin, a force [N] on a Slider). Before realize_topology().")
        .def(
            "add_rope",
            [](System& sys, const PyRopeSpec& spec) {
                Machine& m = *sys.machine;
                m.requireBuilding("add_rope");
                const RopeSpec cpp = toCpp(spec);
                return RopeRef{sys.machine, m.reeving.addRope(cpp)};
            },
            py::arg("spec"),
            "Adds a rope (ValueError with the C++ message for a bad spec); returns its RopeHandle.")
        .def_property_readonly("num_ropes", [](const System& s) { return s.machine->reeving.getNumRopes(); })
        .def("rope", [](const System& s, int rope) {
                const ReevingSubsystem& rv = s.machine->reeving;
                if (rope < 0 || rope >= rv.getNumRopes())
                    throw std::out_of_range("rope " + std::to_string(rope) + " out of range: there are " +
                                            std::to_string(rv.getNumRopes()) + " rope(s)");
                return RopeRef{s.machine, rv.getRope(rope)};
            }, py::arg("index"))
        .def_property_readonly("reeving", [](const System& s) -> const ReevingSubsystem& { return s.machine->reeving; },
                               py::return_value_policy::reference_internal,
                               "The ReevingSubsystem: the queries of every rope by index (as a scene's reeving), "
                               "find_static_equilibrium, energies.")
        .def("realize_topology", [](System& s) { py::gil_scoped_release r; s.machine->realizeTopology(); },
             "Ends the building: the ropes' models are made (gravity out of a rope's plane and the like raise here).")
        .def_property_readonly("topology_realized", [](const System& s) { return s.machine->topology; })
        .def("default_state",
             [](System& s) {
                 py::gil_scoped_release r;
                 s.machine->realizeTopology();
                 return State(s.machine->system.getDefaultState());
             },
             "A new default state (q, u at their defaults: pin angles 0, bodies at their mobilizers' zero; ropes "
             "straight), realize_topology() first if needed.")
        .def("realize",
             [](const System& s, const State& st, const std::string& stage) {
                 const Stage g = stage == "position"       ? Stage::Position
                                 : stage == "velocity"     ? Stage::Velocity
                                 : stage == "dynamics"     ? Stage::Dynamics
                                 : stage == "acceleration" ? Stage::Acceleration
                                 : stage == "report"       ? Stage::Report
                                                           : Stage::Empty;
                 require(g != Stage::Empty, "realize: stage '" + stage +
                                                "' must be 'position', 'velocity', 'dynamics', 'acceleration' or 'report'");
                 py::gil_scoped_release r;
                 s.machine->check(st, g);
             },
             py::arg("state"), py::arg("stage") = "acceleration", "Realizes the state (the queries do it themselves).")
        .def("kinetic_energy", [](const System& s, const State& st) { return s.machine->system.calcKineticEnergy(s.machine->check(st, Stage::Velocity)); },
             py::arg("state"), "The bodies' [J].")
        .def("potential_energy", [](const System& s, const State& st) { return s.machine->system.calcPotentialEnergy(s.machine->check(st, Stage::Dynamics)); },
             py::arg("state"), "Every force subsystem's (the ropes' strain and gravity included) [J].")
        .def("find_static_equilibrium",
             [](const System& s, State& st, double tol, int iterations) {
                 s.machine->check(st, Stage::Model);
                 py::gil_scoped_release r;
                 return s.machine->reeving.findStaticEquilibrium(st, tol, iterations);
             },
             py::arg("state"), py::arg("relative_tolerance") = 1e-10, py::arg("max_iterations") = 50,
             "Moves `state` (in place) to static equilibrium of bodies and ropes (ReevingSubsystem::findStaticEquilibrium; "
             "prescribed mobilities keep their motion); returns the relative residual.")
        .def("update_traction_modes",
             [](const System& s, State& st) {
                 s.machine->check(st, Stage::Model);
                 return s.machine->reeving.updateTractionModes(st);
             },
             py::arg("state"), "Puts sticking traction sheaves beyond their limit into slip; returns how many.")
        .def(
            "simulation",
            [](const System& s, const State& st, const std::string& integrator, double accuracy, double step) {
                const Machine& m = *s.machine;
                m.check(st, Stage::Model);
                py::gil_scoped_release release;
                return std::make_unique<Simulation>(m.system, m.reeving, st, integrator, accuracy, step, machineObserver(m));
            },
            py::arg("state"), py::arg("integrator") = "rk-merson", py::arg("accuracy") = 1e-6, py::arg("fixed_step") = 0.0,
            py::keep_alive<0, 1>(),
            "A Simulation from `state` (the scenes' runner: integrator by name, accuracy, fixed_step > 0 a fixed "
            "step [s]). Its reports (run(): a dict of numpy arrays): t, q0.., u0.., energy (bodies and ropes [J]), "
            "and per rope r: 'rope<r>.span<k>.axial_force_start' / '..._end' [N], 'rope<r>.node<k>.material_coordinate' "
            "[m], '.wrap_angle' [rad] at sheaves that have one, '.rope_on_drum' [m] at drums, '.torque' [N m] at "
            "pinned nodes, '.slip_rate' [m/s], '.traction_ratio', '.traction_limit' at traction sheaves.");
}

}  // namespace

void bindMachine(py::module_& m) {
    bindGeometry(m);
    bindBodies(m);
    bindNodeSpecs(m);
    bindHandles(m);
    bindSystem(m);
}

}  // namespace simbody_reeving_python
