// Links against an installed SimbodyReeving and evaluates one planar span.
#include <SimbodyReeving/SpanModel.h>

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
    std::printf("axial force %.3f N, strain energy %.6f J\n", span.axialForce(q, 10.0), data.strainEnergy());
    return data.strainEnergy() > 0 ? 0 : 1;
}
