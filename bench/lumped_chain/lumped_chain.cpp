// bench-lumped-chain: the alternative a Simbody user has without this plugin, a lumped-mass chain.
//
// The single-span hanging rope (Ground origin -> payload, Table 1 properties, EI = 0) built two ways:
//   chain: what a Simbody user builds without the plugin: N segments, N-1 interior point masses on
//          MobilizedBody::Translation, joined by springs with the ALE element's constitutive law
//          (Green strain eps = (lambda^2-1)/2, axial force P = EA eps, tension T = P lambda), one
//          Force::Custom for the whole chain (potential energy EA l0 eps^2 / 2 per segment). The
//          bottom half-segment mass rhoA l0 / 2 is added to the payload body as a point mass at the
//          attachment station (one rigid body, MassProperties combined); the top half-segment mass
//          sits on Ground and is lost. Nothing from the plugin is used by this model.
//   ale:   SimbodyReeving::ReevingSubsystem, one planar rope, no sheaves, n_a axial and n_t
//          transverse modes.
// Both: payload a MobilizedBody::Free, static equilibrium, then payload vx = 1 m/s and the rope's
// velocity linear in the material coordinate (0 at the top, vx at the payload).
//
// Subcommands:
//   run     one simulation; writes the sampled observables (t, x, y, P) and a header line with
//           wall time, steps, energy drift to --out.
//   analyze reads run files, a reference, writes errors, Pareto fronts, speed ratios.
//   ratios  the fronts and speed ratios again from analyze's lumped_chain_runs.csv (no run files).
//   static  prints the static end force of both models against the continuum (no integration).

#include "SimbodyReeving/simbody/Integrators.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"

#include <Simbody.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// ---- Table 1 (single vertical span) ------------------------------------------------------------
struct Params {
    double L = 20.0, d = 0.3, g = 9.81, rhoA = 0.6205, EA = 16.5e6, M = 1000.0, J = 36.0;
    double vx = 1.0;
};

struct Sample {
    double t, x, y, P;
    double Pn;  // the payload-end axial force from the force the rope puts on the payload (see Model)
};

// Observables shared by both models.
class Model {
public:
    virtual ~Model() = default;
    virtual SimTK::MultibodySystem& system() = 0;
    virtual SimTK::State makeInitialState() = 0;
    virtual SimTK::Vec3 payloadPosition(const SimTK::State& s) const = 0;
    virtual double endAxialForce(const SimTK::State& s) const = 0;  // P = EA eps at the payload end
    /// The payload-end axial force from the force the rope exerts on the payload: P = T / lambda, T the
    /// magnitude of that force (Green law T = EA (lambda^3 - lambda) / 2). Chain: the last spring's
    /// force, i.e. endAxialForce. ALE: ReevingSubsystem::getNodeForce at the end node.
    virtual double endAxialForceFromNodeForce(const SimTK::State& s) const { return endAxialForce(s); }
    virtual SimTK::Stage observationStage() const { return SimTK::Stage::Velocity; }  // needed by the observables
    virtual double energy(const SimTK::State& s) const = 0;         // total mechanical energy [J]
};

// ---- the lumped chain ----------------------------------------------------------------------------

// Tension of a segment for the Green-strain law: T = EA (lambda^2 - 1)/2 lambda; inverse by Newton.
double stretchForTension(double T, double EA) {
    double lam = 1.0 + T / EA;
    for (int it = 0; it < 50; ++it) {
        const double f = 0.5 * EA * (lam * lam * lam - lam) - T;
        const double df = 0.5 * EA * (3 * lam * lam - 1);
        const double dl = f / df;
        lam -= dl;
        if (std::abs(dl) < 1e-16 * lam) break;
    }
    return lam;
}

class ChainForce : public SimTK::Force::Custom::Implementation {
public:
    // nodes[0] = Ground (station origin), nodes[1..N-1] translation bodies (origin), nodes[N] payload
    // at station `endStation`.
    ChainForce(std::vector<SimTK::MobilizedBody> nodes, SimTK::Vec3 endStation, double l0, double EA)
        : nodes_(std::move(nodes)), endStation_(endStation), l0_(l0), EA_(EA) {}

    SimTK::Vec3 nodePos(const SimTK::State& s, int i) const {
        const int N = static_cast<int>(nodes_.size()) - 1;
        if (i == 0) return SimTK::Vec3(0);
        if (i == N) return nodes_[i].findStationLocationInGround(s, endStation_);
        return nodes_[i].getBodyOriginLocation(s);
    }

    void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override {
        const int N = static_cast<int>(nodes_.size()) - 1;
        SimTK::Vec3 prev = nodePos(s, 0);
        for (int i = 1; i <= N; ++i) {
            const SimTK::Vec3 cur = nodePos(s, i);
            const SimTK::Vec3 dr = cur - prev;  // from node i-1 to node i
            const double l = dr.norm();
            const double lam = l / l0_;
            const double T = 0.5 * EA_ * (lam * lam - 1.0) * lam;
            const SimTK::Vec3 f = (T / l) * dr;  // pulls node i towards node i-1
            if (i == N)
                nodes_[i].applyForceToBodyPoint(s, endStation_, -f, bodyForces);
            else
                bodyForces[nodes_[i].getMobilizedBodyIndex()][1] -= f;
            if (i - 1 > 0) bodyForces[nodes_[i - 1].getMobilizedBodyIndex()][1] += f;
            prev = cur;
        }
    }

    SimTK::Real calcPotentialEnergy(const SimTK::State& s) const override {
        const int N = static_cast<int>(nodes_.size()) - 1;
        double U = 0;
        for (int i = 1; i <= N; ++i) {
            const double lam = (nodePos(s, i) - nodePos(s, i - 1)).norm() / l0_;
            const double eps = 0.5 * (lam * lam - 1.0);
            U += 0.5 * EA_ * l0_ * eps * eps;
        }
        return U;
    }

    double lastSegmentAxialForce(const SimTK::State& s) const {
        const int N = static_cast<int>(nodes_.size()) - 1;
        const double lam = (nodePos(s, N) - nodePos(s, N - 1)).norm() / l0_;
        return 0.5 * EA_ * (lam * lam - 1.0);
    }

private:
    std::vector<SimTK::MobilizedBody> nodes_;
    SimTK::Vec3 endStation_;
    double l0_, EA_;
};

// A user's plain linear spring instead (T = EA (lambda - 1)), for the constitutive-law comparison.
class ChainModel : public Model {
public:
    ChainModel(const Params& p, int N, bool linearSprings)
        : p_(p), N_(N), linear_(linearSprings), matter_(system_), forces_(system_),
          gravity_(forces_, matter_, SimTK::Vec3(0, -p.g, 0)) {
        using namespace SimTK;
        l0_ = p.L / N;
        const double m = p.rhoA * l0_;
        const Body::Rigid pointMass(MassProperties(m, Vec3(0), Inertia(0)));
        std::vector<MobilizedBody> nodes;
        nodes.push_back(matter_.updGround());
        for (int i = 1; i < N; ++i) {
            MobilizedBody::Translation b(matter_.updGround(), Transform(), pointMass, Transform());
            nodes.push_back(b);
            interior_.push_back(b);
        }
        // Payload with the bottom half-segment mass as a point mass at the attachment station.
        const double mEnd = 0.5 * m;
        const Vec3 station(0, p.d, 0);
        const double mTot = p.M + mEnd;
        const Inertia I = Inertia(p.J) + Inertia::pointMassAt(station, mEnd);
        const Body::Rigid payloadBody(MassProperties(mTot, station * (mEnd / mTot), I));
        payload_ = MobilizedBody::Free(matter_.updGround(), Transform(), payloadBody, Transform());
        nodes.push_back(payload_);
        station_ = station;
        if (linear_) {
            for (int i = 1; i <= N; ++i)
                Force::TwoPointLinearSpring(forces_, nodes[i - 1], Vec3(0), nodes[i], i == N ? station : Vec3(0),
                                            p.EA / l0_, l0_);
        }
        impl_ = new ChainForce(nodes, station, l0_, p.EA);
        // With linear springs the custom force still serves the observable; its forces are not applied.
        if (!linear_) Force::Custom(forces_, impl_);
        else ownedImpl_.reset(impl_);
        system_.realizeTopology();
    }

    SimTK::MultibodySystem& system() override { return system_; }

    SimTK::State makeInitialState() override {
        using namespace SimTK;
        State s = system_.getDefaultState();
        // Segment i (from node i-1 to node i) carries the weight of everything below node i-1.
        std::vector<double> y(N_ + 1, 0.0);
        double W = (p_.M + 0.5 * p_.rhoA * l0_) * p_.g;  // payload + bottom half-segment
        std::vector<double> len(N_ + 1, 0.0);
        for (int i = N_; i >= 1; --i) {
            len[i] = linear_ ? l0_ * (1.0 + W / p_.EA) : l0_ * stretchForTension(W, p_.EA);
            W += p_.rhoA * l0_ * p_.g;  // node i-1's mass is carried by segment i-1
        }
        for (int i = 1; i <= N_; ++i) y[i] = y[i - 1] - len[i];
        for (int i = 1; i < N_; ++i) {
            interior_[i - 1].setQToFitTranslation(s, Vec3(0, y[i], 0));
            interior_[i - 1].setUToFitLinearVelocity(s, Vec3(p_.vx * i * l0_ / p_.L, 0, 0));
        }
        payload_.setQToFitTranslation(s, Vec3(0, y[N_] - p_.d, 0));
        payload_.setUToFitLinearVelocity(s, Vec3(p_.vx, 0, 0));
        system_.realize(s, Stage::Acceleration);
        return s;
    }
    SimTK::Vec3 payloadPosition(const SimTK::State& s) const override { return payload_.getBodyOriginLocation(s); }
    double endAxialForce(const SimTK::State& s) const override {
        if (linear_) {  // P = EA (lambda - 1) for the linear spring
            const double l = (impl_->nodePos(s, N_) - impl_->nodePos(s, N_ - 1)).norm();
            return p_.EA * (l / l0_ - 1.0);
        }
        return impl_->lastSegmentAxialForce(s);
    }
    double energy(const SimTK::State& s) const override { return system_.calcEnergy(s); }
    // Residual of the static equilibrium: largest |udot| [m/s^2 or rad/s^2] at zero velocity.
    double staticResidual() {
        SimTK::State s = makeInitialState();
        s.updU() = 0;
        system_.realize(s, SimTK::Stage::Acceleration);
        return s.getUDot().normInf();
    }

private:
    Params p_;
    int N_;
    bool linear_;
    double l0_ = 0;
    SimTK::MultibodySystem system_;
    SimTK::SimbodyMatterSubsystem matter_;
    SimTK::GeneralForceSubsystem forces_;
    SimTK::Force::Gravity gravity_;
    std::vector<SimTK::MobilizedBody::Translation> interior_;
    SimTK::MobilizedBody::Free payload_;
    SimTK::Vec3 station_;
    ChainForce* impl_ = nullptr;  // owned by the Force::Custom handle (or ownedImpl_)
    std::unique_ptr<ChainForce> ownedImpl_;
};

// ---- the ALE rope --------------------------------------------------------------------------------
class AleModel : public Model {
public:
    AleModel(const Params& p, int na, int nt, bool completeVelocity = false)
        : p_(p), matter_(system_), forces_(system_), gravity_(forces_, matter_, SimTK::Vec3(0, -p.g, 0)),
          reeving_(system_, SimTK::Vec3(0, -p.g, 0)) {
        using namespace SimTK;
        const Body::Rigid body(MassProperties(p.M, Vec3(0), Inertia(p.J)));
        payload_ = MobilizedBody::Free(matter_.updGround(), Transform(), body, Transform());
        SimbodyReeving::RopeSpec rope;
        rope.name = "single span";
        rope.start = SimbodyReeving::RopeAnchor{matter_.Ground(), Vec3(0)};
        rope.end = SimbodyReeving::RopeAnchor{payload_, Vec3(0, p.d, 0)};
        rope.properties = {p.rhoA, p.EA, 0.0};
        rope.unstretchedLength = p.L;
        rope.spanDefaults.axialModes = na;
        rope.spanDefaults.transverseModes = nt;
        rope.spanDefaults.velocityModel = completeVelocity ? SimbodyReeving::VelocityModel::Complete
                                                           : SimbodyReeving::VelocityModel::Simplified;
        rope.spanDefaults.axialDynamics = SimbodyReeving::AxialDynamics::Dynamic;  // not the default: the setting of the recorded results
        rope.planeNormal = Vec3(0, 0, 1);
        reeving_.addRope(rope);
        system_.realizeTopology();
    }
    SimTK::MultibodySystem& system() override { return system_; }
    SimTK::State makeInitialState() override {
        using namespace SimTK;
        State s = system_.getDefaultState();
        const double P = (p_.M + p_.rhoA * p_.L) * p_.g;
        const double stretch = std::sqrt(1.0 + 2.0 * P / p_.EA);
        payload_.setQToFitTranslation(s, Vec3(0, -p_.L * stretch - p_.d, 0));
        try {
            reeving_.findStaticEquilibrium(s, 1e-11);
        } catch (const std::exception&) {
            reeving_.findStaticEquilibrium(s, 1e-9);
        }
        payload_.setUToFitLinearVelocity(s, Vec3(p_.vx, 0, 0));
        system_.realize(s, Stage::Acceleration);
        return s;
    }
    SimTK::Vec3 payloadPosition(const SimTK::State& s) const override { return payload_.getBodyOriginLocation(s); }
    double endAxialForce(const SimTK::State& s) const override {
        const auto range = reeving_.getSpanMaterialRange(s, 0, 0);
        return reeving_.getAxialForce(s, 0, 0, range.second);
    }
    double endAxialForceFromNodeForce(const SimTK::State& s) const override {
        const double T = reeving_.getNodeForce(s, 0, 1).norm();
        return T / stretchForTension(T, p_.EA);
    }
    SimTK::Stage observationStage() const override { return SimTK::Stage::Dynamics; }
    double energy(const SimTK::State& s) const override { return reeving_.calcMechanicalEnergy(s); }

private:
    Params p_;
    SimTK::MultibodySystem system_;
    SimTK::SimbodyMatterSubsystem matter_;
    SimTK::GeneralForceSubsystem forces_;
    SimTK::Force::Gravity gravity_;
    SimbodyReeving::ReevingSubsystem reeving_;
    SimTK::MobilizedBody::Free payload_;
};

// ---- command line -------------------------------------------------------------------------------
std::map<std::string, std::string> parseArgs(int argc, char** argv, int first) {
    std::map<std::string, std::string> a;
    for (int i = first; i < argc; ++i) {
        std::string k = argv[i];
        if (k.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument " + k);
        k = k.substr(2);
        if (i + 1 >= argc) throw std::invalid_argument("missing value for --" + k);
        a[k] = argv[++i];
    }
    return a;
}
std::string get(const std::map<std::string, std::string>& a, const std::string& k, const std::string& def) {
    auto it = a.find(k);
    return it == a.end() ? def : it->second;
}

std::unique_ptr<Model> makeModel(const std::map<std::string, std::string>& a, const Params& p) {
    const std::string model = get(a, "model", "chain");
    if (model == "chain") return std::make_unique<ChainModel>(p, std::stoi(get(a, "N", "20")), false);
    if (model == "chain-linear") return std::make_unique<ChainModel>(p, std::stoi(get(a, "N", "20")), true);
    if (model == "ale")
        return std::make_unique<AleModel>(p, std::stoi(get(a, "na", "0")), std::stoi(get(a, "nt", "1")),
                                          get(a, "velocity", "simplified") == "complete");
    throw std::invalid_argument("unknown --model " + model + " (chain, chain-linear, ale)");
}

struct RunOutcome {
    std::string status = "ok";
    double wall = 0;
    long steps = 0, realizations = 0;
    double E0 = 0, maxDrift = 0;
    std::vector<Sample> samples;
};

RunOutcome simulate(Model& model, const std::string& integName, double accuracy, double tEnd, double dt,
                    double cap, bool record) {
    RunOutcome out;
    SimTK::State s0 = model.makeInitialState();
    auto integ = SimbodyReeving::makeIntegrator(integName, model.system());
    integ->setAccuracy(accuracy);
    integ->initialize(s0);
    auto observe = [&](const SimTK::State& st) {
        SimTK::State tmp;
        const SimTK::State* s = &st;
        if (st.getSystemStage() < model.observationStage()) {
            tmp = st;
            model.system().realize(tmp, model.observationStage());
            s = &tmp;
        }
        const SimTK::Vec3 x = model.payloadPosition(*s);
        const double E = model.energy(*s);
        if (s->getTime() == 0) out.E0 = E;
        out.maxDrift = std::max(out.maxDrift, std::abs(E - out.E0));
        if (record)
            out.samples.push_back(
                {s->getTime(), x[0], x[1], model.endAxialForce(*s), model.endAxialForceFromNodeForce(*s)});
    };
    observe(integ->getState());
    const int nSamples = static_cast<int>(std::lround(tEnd / dt));
    using Clock = std::chrono::steady_clock;
    double wall = 0;
    try {
        for (int k = 1; k <= nSamples; ++k) {
            const auto t0 = Clock::now();
            integ->stepTo(k * dt);
            wall += std::chrono::duration<double>(Clock::now() - t0).count();
            const SimTK::State& st = integ->getState();
            if (!std::isfinite(model.payloadPosition(st)[1])) {
                out.status = "failed: non-finite state";
                break;
            }
            observe(st);
            if (wall > cap) {
                out.status = "too slow";
                break;
            }
        }
    } catch (const std::exception& e) {
        std::string msg = e.what();
        msg = msg.substr(0, msg.find('\n'));
        out.status = "failed: " + msg.substr(0, 120);
    }
    out.wall = wall;
    out.steps = integ->getNumStepsTaken();
    out.realizations = integ->getNumRealizations();
    return out;
}

int cmdRun(const std::map<std::string, std::string>& a) {
    Params p;
    const std::string integName = get(a, "integrator", "rk-merson");
    const double acc = std::stod(get(a, "accuracy", "1e-6"));
    const double tEnd = std::stod(get(a, "tend", "20"));
    const double cap = std::stod(get(a, "cap", "120"));
    const int repeats = std::stoi(get(a, "repeats", "3"));
    const double repeatBelow = std::stod(get(a, "repeat-below", "20"));
    const std::string outPath = get(a, "out", "");
    std::vector<double> walls;
    RunOutcome first;
    {
        auto model = makeModel(a, p);
        first = simulate(*model, integName, acc, tEnd, 0.01, cap, true);
    }
    walls.push_back(first.wall);
    if (first.status == "ok" && first.wall < repeatBelow) {
        for (int r = 1; r < repeats; ++r) {
            auto model = makeModel(a, p);
            RunOutcome o = simulate(*model, integName, acc, tEnd, 0.01, cap, false);
            walls.push_back(o.wall);
        }
    }
    std::vector<double> sorted = walls;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    std::ostringstream head;
    head.precision(10);
    head << "# model=" << get(a, "model", "chain") << " N=" << get(a, "N", "-") << " na=" << get(a, "na", "-")
         << " nt=" << get(a, "nt", "-") << " velocity=" << get(a, "velocity", "simplified") << " integrator=" << integName << " accuracy=" << acc
         << " status=" << (first.status.find(' ') == std::string::npos ? first.status : "\"" + first.status + "\"")
         << " wall=" << median << " walls=";
    for (size_t i = 0; i < walls.size(); ++i) head << (i ? ";" : "") << walls[i];
    head << " steps=" << first.steps << " realizations=" << first.realizations << " tend_reached="
         << (first.samples.empty() ? 0.0 : first.samples.back().t) << " E0=" << first.E0
         << " energy_drift=" << first.maxDrift;
    std::cout << head.str() << "\n";
    if (!outPath.empty()) {
        std::ofstream f(outPath);
        f.precision(17);
        f << head.str() << "\n";
        for (const Sample& s : first.samples)
            f << s.t << "," << s.x << "," << s.y << "," << s.P << "," << s.Pn << "\n";
    }
    return 0;
}

// ---- analysis -----------------------------------------------------------------------------------
struct RunFile {
    std::string path;
    std::map<std::string, std::string> meta;
    std::vector<Sample> samples;
};

RunFile readRun(const std::string& path) {
    RunFile r;
    r.path = path;
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot read " + path);
    std::string line;
    std::getline(f, line);
    // parse "# k=v k=v k="quoted v""
    size_t i = 2;
    while (i < line.size()) {
        size_t eq = line.find('=', i);
        if (eq == std::string::npos) break;
        std::string k = line.substr(i, eq - i);
        std::string v;
        size_t j = eq + 1;
        if (j < line.size() && line[j] == '"') {
            size_t e = line.find('"', j + 1);
            v = line.substr(j + 1, e - j - 1);
            j = e + 1;
        } else {
            size_t e = line.find(' ', j);
            if (e == std::string::npos) e = line.size();
            v = line.substr(j, e - j);
            j = e;
        }
        r.meta[k] = v;
        i = j + 1;
    }
    while (std::getline(f, line)) {
        Sample s{};
        const int n = std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &s.t, &s.x, &s.y, &s.P, &s.Pn);
        if (n == 4) s.Pn = s.P;  // files written before the node-force column
        if (n >= 4) r.samples.push_back(s);
    }
    return r;
}

struct Errors {
    double pos = NAN, force = NAN, forceNode = NAN;  // forceNode: Pn against the reference's P
    bool complete = false;
};
Errors errorsAgainst(const RunFile& r, const RunFile& ref) {
    Errors e;
    const size_t n = std::min(r.samples.size(), ref.samples.size());
    e.complete = r.samples.size() >= ref.samples.size();
    double ep = 0, ef = 0, en = 0;
    for (size_t k = 0; k < n; ++k) {
        const Sample& a = r.samples[k];
        const Sample& b = ref.samples[k];
        if (std::abs(a.t - b.t) > 1e-9) {  // CPodes' stepTo once returned early (t = 0.019 for 0.02)
            std::cerr << "note: sample " << k << " of " << r.path << " at t = " << a.t << " (expected " << b.t
                      << "), skipped\n";
            continue;
        }
        ep = std::max(ep, std::hypot(a.x - b.x, a.y - b.y));
        ef = std::max(ef, std::abs(a.P - b.P));
        en = std::max(en, std::abs(a.Pn - b.P));
    }
    e.pos = ep;
    e.force = ef;
    e.forceNode = en;
    return e;
}

// One timed run of the sweep with its errors against the reference (a row of lumped_chain_runs.csv).
struct Row {
    std::string model, label, integ, status;
    double acc = 0, wall = 0, drift = 0;
    long steps = 0;
    Errors e;
};

// The chain's segment count N of a label "N=50" (0 for an ALE label).
int chainSegments(const std::string& label) { return label.rfind("N=", 0) == 0 ? std::stoi(label.substr(2)) : 0; }

// Pareto fronts, the speed ratios at equal error, printed and written to outDir: lumped_chain_pareto.csv,
// front_<model>_<observable>.dat (the plot's), lumped_chain_ratios.csv.
void writeFrontsAndRatios(const std::vector<Row>& rows, const std::string& outDir) {
    // Pareto fronts (complete runs only): for each model and observable, the points not dominated in
    // (wall, error).
    struct Point {
        double wall, err;
        std::string label;
    };
    std::ofstream pf(outDir + "/lumped_chain_pareto.csv");
    pf << "model,observable,discretization,integrator,accuracy,wall_s,error\n";
    std::map<std::string, std::vector<Point>> fronts;  // key model|obs
    // Observables: 0 position, 1 end force P = EA eps (the models' strain at the end), 2 end force from
    // the force on the payload (ALE: getNodeForce; for the chain the same as 1).
    const char* obsKey[] = {"pos", "force", "nodeforce"};
    const char* obsName[] = {"position", "force", "node-force"};
    for (const std::string model : {"chain", "ale"}) {
        for (int obs = 0; obs < 3; ++obs) {
            if (model == "chain" && obs == 2) continue;
            std::vector<const Row*> cand;
            for (const auto& r : rows)
                if (r.model == model && r.status == "ok") cand.push_back(&r);
            std::sort(cand.begin(), cand.end(), [](const Row* x, const Row* y) { return x->wall < y->wall; });
            double best = INFINITY;
            std::vector<Point> front;
            for (const Row* r : cand) {
                const double err = obs == 0 ? r->e.pos : obs == 1 ? r->e.force : r->e.forceNode;
                if (err < 0.999 * best) {  // a real improvement, not round-off
                    best = err;
                    front.push_back({r->wall, err, r->label});
                    pf << model << "," << obsName[obs] << "," << r->label << "," << r->integ << "," << r->acc << ","
                       << r->wall << "," << err << "\n";
                }
            }
            fronts[model + "|" + obsKey[obs]] = front;
            std::ofstream dat(outDir + "/front_" + model + "_" + obsKey[obs] + ".dat");
            for (auto& pt : front) dat << pt.wall << "," << pt.err << "\n";
        }
    }
    // Wall time to reach an error level along a front: log-log interpolation between the two front
    // points bracketing it; the first point if already below (then an upper bound of the wall needed);
    // NaN if never reached.
    auto wallAt = [](const std::vector<Point>& f, double level) -> double {
        if (f.empty()) return std::nan("");
        if (f.front().err <= level) return f.front().wall;
        for (size_t i = 1; i < f.size(); ++i) {
            if (f[i].err <= level) {
                const double lw0 = std::log(f[i - 1].wall), lw1 = std::log(f[i].wall);
                const double le0 = std::log(f[i - 1].err), le1 = std::log(f[i].err);
                const double t = (std::log(level) - le0) / (le1 - le0);
                return std::exp(lw0 + t * (lw1 - lw0));
            }
        }
        return std::nan("");
    };
    // A level the chain's front does not reach: the segments it needs, from the order of convergence of
    // the front's last two points (error ~ N^-p), and
    // - a lower bound of its wall: the front's most accurate run (a finer chain costs more), or a run that
    //   hit the time cap with no more segments than needed (its cap), whichever is larger;
    // - an estimate: the most accurate run's wall times (N_needed / N)^2 (the chain's explicit steps are
    //   stability-limited, so steps and the work per step both grow like N).
    struct ChainBound {
        double needed = std::nan(""), lower = std::nan(""), estimate = std::nan("");
        std::string why;
    };
    auto chainBound = [&](const std::vector<Point>& f, double level) {
        ChainBound b;
        if (f.size() < 2) return b;
        const Point& p1 = f[f.size() - 2];
        const Point& p2 = f.back();
        const int n1 = chainSegments(p1.label), n2 = chainSegments(p2.label);
        if (n1 <= 0 || n2 <= n1) return b;
        const double order = std::log(p1.err / p2.err) / std::log(double(n2) / n1);
        b.needed = n2 * std::pow(p2.err / level, 1.0 / order);
        b.lower = p2.wall;
        b.why = "the most accurate chain run, " + p2.label;
        for (const auto& r : rows)
            if (r.model == "chain" && r.status != "ok" && chainSegments(r.label) <= b.needed && r.wall > b.lower) {
                b.lower = r.wall;
                b.why = "the chain " + r.label + " hit the " + std::to_string(int(std::lround(r.wall))) + " s cap";
            }
        b.estimate = p2.wall * std::pow(b.needed / n2, 2.0);
        return b;
    };
    std::ofstream ratios(outDir + "/lumped_chain_ratios.csv");
    ratios << "observable,level,chain_wall_s,chain_wall_kind,chain_segments_needed,chain_wall_estimate_s,ale_wall_s,"
              "ratio_chain_over_ale,ale_nodeforce_wall_s,ratio_chain_over_ale_nodeforce,ratio_estimate\n";
    // The four required error levels first, then intermediate ones both models reach.
    const std::vector<std::pair<std::string, double>> levels{{"pos", 1e-4}, {"pos", 1e-6},  {"force", 1.0},
                                                             {"force", 0.01}, {"pos", 1e-5}, {"force", 10.0},
                                                             {"force", 5.0}, {"force", 3.0}, {"force", 0.1}};
    for (const auto& kv : fronts)
        if (!kv.second.empty())
            std::cout << kv.first << ": best error " << kv.second.back().err << " at " << kv.second.back().wall
                      << " s\n";
    auto fmt = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.4g", v);
        return std::string(buf);
    };
    for (const auto& lv : levels) {
        const auto& chainFront = fronts["chain|" + lv.first];
        double wc = wallAt(chainFront, lv.second);
        const bool reached = !std::isnan(wc);
        const ChainBound b = reached ? ChainBound{} : chainBound(chainFront, lv.second);
        if (!reached) wc = b.lower;
        const double wa = wallAt(fronts["ale|" + lv.first], lv.second);
        const double wn = lv.first == "force" ? wallAt(fronts["ale|nodeforce"], lv.second) : std::nan("");
        const double bestAle = std::isnan(wn) ? wa : std::isnan(wa) ? wn : std::min(wa, wn);
        ratios << lv.first << "," << lv.second << "," << wc << "," << (reached ? "interpolated" : "lower_bound") << ","
               << b.needed << "," << b.estimate << "," << wa << "," << wc / wa << "," << wn << "," << wc / wn << ","
               << b.estimate / bestAle << "\n";
        // A lower bound where the chain did not reach the level, or where the ALE's cheapest run is
        // already below it (its wall then bounds the ALE's cost from above).
        auto atFloor = [&](const std::string& key) {
            const auto& f = fronts[key];
            return !f.empty() && f.front().err <= lv.second;
        };
        const std::string rel = !reached ? "> " : atFloor("ale|" + lv.first) ? ">= " : "";
        const std::string relNode = !reached ? "> " : atFloor("ale|nodeforce") ? ">= " : "";
        std::cout << lv.first << " error " << lv.second << ": chain ";
        if (reached)
            std::cout << fmt(wc) << " s";
        else if (!std::isnan(wc))
            std::cout << "not reached in the sweep, > " << fmt(wc) << " s (" << b.why << "; about N = "
                      << fmt(b.needed) << " needed, ~" << fmt(b.estimate) << " s estimated)";
        else
            std::cout << "not reached";
        if (!std::isnan(wa) || lv.first == "pos")
            std::cout << ", ale " << (std::isnan(wa) ? "not reached" : fmt(wa) + " s") << ", ratio "
                      << (std::isnan(wc / wa) ? "-" : rel + fmt(wc / wa));
        else
            std::cout << ", ale from the strain not reached";
        if (lv.first == "force")
            std::cout << "; ale from the node force " << fmt(wn) << " s, ratio " << relNode << fmt(wc / wn);
        if (!reached && !std::isnan(b.estimate)) std::cout << " (estimate ~" << fmt(b.estimate / bestAle) << ")";
        std::cout << "\n";
    }
}

// analyze --ref FILE --out-dir DIR file...   (files given after "--files")
int cmdAnalyze(int argc, char** argv) {
    std::string refPath, outDir = ".";
    std::vector<std::string> files;
    bool inFiles = false;
    for (int i = 2; i < argc; ++i) {
        std::string k = argv[i];
        if (inFiles) {
            files.push_back(k);
        } else if (k == "--ref") {
            refPath = argv[++i];
        } else if (k == "--out-dir") {
            outDir = argv[++i];
        } else if (k == "--files") {
            inFiles = true;
        } else {
            throw std::invalid_argument("analyze: unexpected " + k);
        }
    }
    const RunFile ref = readRun(refPath);
    std::vector<Row> rows;
    for (const auto& path : files) {
        RunFile r = readRun(path);
        Row row;
        row.model = r.meta["model"];
        row.label = row.model == "ale" ? "na=" + r.meta["na"] + " nt=" + r.meta["nt"] +
                                             (r.meta["velocity"] == "complete" ? " complete" : "")
                                       : "N=" + r.meta["N"];
        row.integ = r.meta["integrator"];
        row.status = r.meta["status"];
        row.acc = std::stod(r.meta["accuracy"]);
        row.wall = std::stod(r.meta["wall"]);
        row.drift = std::stod(r.meta["energy_drift"]);
        row.steps = std::stol(r.meta["steps"]);
        row.e = errorsAgainst(r, ref);
        rows.push_back(row);
    }
    std::ofstream all(outDir + "/lumped_chain_runs.csv");
    all << "model,discretization,integrator,accuracy,status,wall_s,steps,pos_err_m,force_err_N,energy_drift_J,"
           "node_force_err_N\n";
    for (const auto& r : rows)
        all << r.model << "," << r.label << "," << r.integ << "," << r.acc << "," << r.status << "," << r.wall
            << "," << r.steps << "," << r.e.pos << "," << r.e.force << "," << r.drift << "," << r.e.forceNode << "\n";
    writeFrontsAndRatios(rows, outDir);
    return 0;
}

// ratios RUNS_CSV [--out-dir DIR]: the fronts and speed ratios again from a lumped_chain_runs.csv that
// `analyze` wrote (no run files needed; default DIR: the CSV's folder).
int cmdRatios(int argc, char** argv) {
    if (argc < 3) throw std::invalid_argument("ratios RUNS_CSV [--out-dir DIR]");
    const std::string path = argv[2];
    std::string outDir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/'));
    for (int i = 3; i < argc; ++i) {
        const std::string k = argv[i];
        if (k == "--out-dir" && i + 1 < argc)
            outDir = argv[++i];
        else
            throw std::invalid_argument("ratios: unexpected " + k);
    }
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot read " + path);
    std::string line;
    std::getline(f, line);  // header
    std::vector<Row> rows;
    while (std::getline(f, line)) {
        if (line.empty()) continue;
        std::vector<std::string> c;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
        if (c.size() < 11) throw std::runtime_error(path + ": a row with fewer than 11 columns: " + line);
        Row r;
        r.model = c[0];
        r.label = c[1];
        r.integ = c[2];
        r.acc = std::stod(c[3]);
        r.status = c[4];
        r.wall = std::stod(c[5]);
        r.steps = std::stol(c[6]);
        r.e.pos = std::stod(c[7]);
        r.e.force = std::stod(c[8]);
        r.drift = std::stod(c[9]);
        r.e.forceNode = std::stod(c[10]);
        rows.push_back(r);
    }
    writeFrontsAndRatios(rows, outDir);
    return 0;
}

// Compares two run files directly (reference agreement).
int cmdCompare(int argc, char** argv) {
    if (argc < 4) throw std::invalid_argument("compare A B");
    const RunFile a = readRun(argv[2]);
    const RunFile b = readRun(argv[3]);
    const Errors e = errorsAgainst(a, b);
    const double Pmax = [&] {
        double m = 0;
        for (auto& s : b.samples) m = std::max(m, std::abs(s.P));
        return m;
    }();
    std::printf("max|dpos| = %.3e m   max|dP| = %.3e N   max|dPnode - P_B| = %.3e N   (max|P| = %.1f N)  complete=%d\n",
                e.pos, e.force, e.forceNode, Pmax, e.complete ? 1 : 0);
    return 0;
}

// Richardson: writes R = A + (A - B) / (r^p - 1) sample by sample (A finer, B coarser, r refinement).
int cmdRichardson(int argc, char** argv) {
    if (argc < 7) throw std::invalid_argument("richardson FINE COARSE ratio order OUT");
    const RunFile a = readRun(argv[2]);
    const RunFile b = readRun(argv[3]);
    const double r = std::stod(argv[4]), p = std::stod(argv[5]);
    const double c = 1.0 / (std::pow(r, p) - 1.0);
    std::ofstream f(argv[6]);
    f.precision(17);
    f << "# model=richardson fine=" << argv[2] << " coarse=" << argv[3] << " order=" << p << "\n";
    const size_t n = std::min(a.samples.size(), b.samples.size());
    for (size_t k = 0; k < n; ++k) {
        const Sample& x = a.samples[k];
        const Sample& y = b.samples[k];
        f << x.t << "," << x.x + c * (x.x - y.x) << "," << x.y + c * (x.y - y.y) << "," << x.P + c * (x.P - y.P)
          << "," << x.Pn + c * (x.Pn - y.Pn) << "\n";
    }
    return 0;
}

// Reference file: position from A, axial force from B.
int cmdComposeRef(int argc, char** argv) {
    if (argc < 5) throw std::invalid_argument("compose-ref POSITION_FILE FORCE_FILE OUT");
    const RunFile a = readRun(argv[2]);
    const RunFile b = readRun(argv[3]);
    std::ofstream f(argv[4]);
    f.precision(17);
    f << "# model=reference position=" << argv[2] << " force=" << argv[3] << "\n";
    const size_t n = std::min(a.samples.size(), b.samples.size());
    for (size_t k = 0; k < n; ++k)
        f << a.samples[k].t << "," << a.samples[k].x << "," << a.samples[k].y << "," << b.samples[k].P << ","
          << b.samples[k].P << "\n";
    return 0;
}

// Static end force of both models and of the continuum (no integration).
int cmdStatic(const std::map<std::string, std::string>& a) {
    Params p;
    // Continuum: T(s=L) = M g exactly (the payload hangs below the attachment, the rope's weight is
    // carried above it); P from T = P lambda.
    const double Tend = p.M * p.g;
    const double lamEnd = stretchForTension(Tend, p.EA);
    const double Pend = 0.5 * p.EA * (lamEnd * lamEnd - 1.0);
    std::printf("continuum: P(L) = %.9f N\n", Pend);
    for (int N : {5, 10, 20, 50, 100, 200, 400, 800}) {
        ChainModel c(p, N, false);
        SimTK::State s = c.makeInitialState();
        std::printf("chain N=%4d: P_last = %.6f N (err %+.4f)  payload y = %.12f  static |udot| = %.2e\n", N,
                    c.endAxialForce(s), c.endAxialForce(s) - Pend, c.payloadPosition(s)[1], c.staticResidual());
    }
    for (int na : {0, 1, 2, 3, 5, 8, 12, 16}) {
        AleModel m(p, na, std::stoi(get(a, "nt", "1")));
        SimTK::State s = m.makeInitialState();
        m.system().realize(s, SimTK::Stage::Dynamics);
        std::printf("ale na=%2d: P(L) = %.6f N (err %+.4f)  from the node force %.6f N (err %+.2e)  payload y = %.12f\n",
                    na, m.endAxialForce(s), m.endAxialForce(s) - Pend, m.endAxialForceFromNodeForce(s),
                    m.endAxialForceFromNodeForce(s) - Pend, m.payloadPosition(s)[1]);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc < 2) {
            std::cerr << "usage: bench-lumped-chain run|analyze|compare|richardson|static [options]\n"
                         "  run --model chain|chain-linear|ale [--N n] [--na n --nt n] --integrator name\n"
                         "      --accuracy a [--tend 20] [--cap 120] [--repeats 3] [--repeat-below 20] --out file\n"
                         "  analyze --ref file --out-dir dir --files f...\n"
                         "  ratios lumped_chain_runs.csv [--out-dir dir]   (fronts and speed ratios from analyze's table)\n"
                         "  compare A B | richardson FINE COARSE ratio order OUT | static\n";
            return 2;
        }
        const std::string cmd = argv[1];
        if (cmd == "run") return cmdRun(parseArgs(argc, argv, 2));
        if (cmd == "analyze") return cmdAnalyze(argc, argv);
        if (cmd == "ratios") return cmdRatios(argc, argv);
        if (cmd == "compare") return cmdCompare(argc, argv);
        if (cmd == "richardson") return cmdRichardson(argc, argv);
        if (cmd == "compose-ref") return cmdComposeRef(argc, argv);
        if (cmd == "static") return cmdStatic(parseArgs(argc, argv, 2));
        std::cerr << "unknown command " << cmd << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "bench-lumped-chain: " << e.what() << "\n";
        return 1;
    }
}
