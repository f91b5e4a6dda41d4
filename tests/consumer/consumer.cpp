// Links against an installed SimbodyReeving: evaluates one span (pure element) and runs the
// Table 1 pendulum (Simbody layer) for 0.1 s.
#include <SimbodyReeving/scenes/PendulumScene.h>
#include <SimbodyReeving/element/SpanModel.h>

#include <cstdio>

int main() {
    using namespace SimbodyReeving;
    SpanOptions options;
    options.axialModes = 1;
    const PlanarSpanModel span({0.6205, 16.5e6, 30.9}, options, Eigen::Vector2d(0, -9.81));
    Eigen::VectorXd q = Eigen::VectorXd::Zero(span.numCoordinates());
    q.segment<2>(2) = Eigen::Vector2d(0, -20.01);
    q[span.s2Index()] = 20.0;
    SpanData<2> data;
    span.evaluate(q, Eigen::VectorXd::Zero(q.size()), data);

    PendulumScene scene(PendulumParameters{}, options);
    SimTK::State s = scene.makeInitialState(1.0, 0.0);
    SimTK::RungeKuttaMersonIntegrator integ(scene.system());
    SimTK::TimeStepper ts(scene.system(), integ);
    ts.initialize(s);
    ts.stepTo(0.1);
    const double x = scene.payloadPosition(integ.getState())[0];
    std::printf("span strain energy %.6f J; payload x after 0.1 s: %.6f m\n", data.strainEnergy(), x);
    return data.strainEnergy() > 0 && x > 3.05 ? 0 : 1;
}
