// A rope over a traction sheave and a turning sheave, wound on a drum. With RIGHT_KIND (the
// control) every node is asked what its own kind answers: it builds and runs. Each WRONG_<case>
// adds one line that asks a node for another kind's query, or puts a kind where it may not stand:
// that line must not compile (tests/api/RunApiChecks.cmake).
#include <SimbodyReeving/simbody/ReevingSubsystem.h>

#include <Simbody.h>

#include <cmath>
#include <cstdio>

int main() {
    using namespace SimTK;
    namespace sr = SimbodyReeving;
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    Force::Gravity gravity(forces, matter, Vec3(0, -9.81, 0));
    sr::ReevingSubsystem reeving(system);
    const Body::Rigid wheel(MassProperties(10, Vec3(0), Inertia(1)));
    MobilizedBody::Pin drum(matter.Ground(), Transform(Vec3(-2, 0, 0)), wheel, Transform());
    MobilizedBody::Pin traction(matter.Ground(), Transform(Vec3(0, 0, 0)), wheel, Transform());
    MobilizedBody::Pin turning(matter.Ground(), Transform(Vec3(2, 0, 0)), wheel, Transform());
    MobilizedBody::Slider load(matter.Ground(), Transform(Rotation(Pi / 2, ZAxis), Vec3(3, -3, 0)),
                               Body::Rigid(MassProperties(100, Vec3(0), Inertia(1))), Transform(Rotation(Pi / 2, ZAxis)));

    sr::RopeSpec spec;
    spec.start = sr::WinchDrum{drum, 0.3, 10.0};
    sr::TractionSheave grip;
    grip.body = traction;
    grip.radius = 0.3;
    grip.frictionCoefficient = 0.2;
    grip.materialCoordinateAtZeroAngle = 2.3;
    spec.sheaves = {grip, sr::TurningSheave{turning, 0.3, 4.6}};
    spec.end = sr::RopeAnchor{load, Vec3(0)};
    spec.properties = {0.6, 1e6, 0};
    spec.unstretchedLength = 8;
    spec.planeNormal = Vec3(0, 0, 1);
    const sr::RopeHandle rope = reeving.addRope(spec);
    const int index = rope;  // the generic queries keep taking the rope's index
    system.realizeTopology();
    State state = system.getDefaultState();
    system.realize(state, Stage::Dynamics);

    const sr::WinchDrumHandle winch = rope.getWinchDrum(0);
    const sr::TractionSheaveHandle sheave = rope.getTractionSheave(1);
    const sr::TurningSheaveHandle idler = rope.getTurningSheave(2);
#if defined(RIGHT_KIND)
    const double stored = winch.getRopeOnDrum(state);
    const double slip = sheave.getSlipRate(state);
    const sr::TractionMode mode = sheave.getTractionMode(state);
    const double torque = idler.getTorque(state) + winch.getTorque(state);
    const double force = reeving.getAxialForce(state, index, 0, 1.0);
    std::printf("stored %g m, slip rate %g m/s, mode %d, torques %g N m, force %g N\n", stored, slip,
                static_cast<int>(mode), torque, force);
    return stored == 10.0 && slip == 0.0 && mode == sr::TractionMode::Stick && std::isfinite(torque) ? 0 : 1;
#elif defined(WRONG_DRUM_SLIP_RATE)
    return winch.getSlipRate(state) > 0;  // a drum has no slip rate
#elif defined(WRONG_DRUM_AS_TRACTION_SHEAVE)
    const sr::TractionSheaveHandle notATractionSheave = rope.getWinchDrum(0);  // handles do not convert
    return notATractionSheave.getNumTractionTransitions(state);
#elif defined(WRONG_TURNING_SHEAVE_ROPE_ON_DRUM)
    return idler.getRopeOnDrum(state) > 0;  // a sheave stores no rope
#elif defined(WRONG_SLIP_RATE_BY_INDICES)
    return reeving.getSlipRate(state, index, 1) > 0;  // kind-specific queries take a handle
#elif defined(WRONG_SHEAVE_AT_ROPE_END)
    spec.end = sr::DeviationSheave{matter.Ground(), Vec3(0), 0.1};  // a rope end is an anchor or a drum
    return 0;
#elif defined(WRONG_DRUM_IN_PATH)
    spec.sheaves.push_back(sr::WinchDrum{drum, 0.3, 10.0});  // a drum is a rope end
    return 0;
#else
#error "define RIGHT_KIND or one WRONG_<case>"
#endif
}
