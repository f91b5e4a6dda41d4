// A five-minute tour of the span element (pure C++/Eigen, no Simbody needed):
//  1. the Table 1 vertical span hanging a 1000 kg payload: axial force along it;
//  2. its transverse frequencies against the taut string;
//  3. the difference the paper-literal energy makes.
#include <SimbodyReeving/SpanModel.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>

using namespace SimbodyReeving;

int main() {
    const RopeProperties rope{0.6205, 16.5e6, 30.9};  // Table 1: rhoA [kg/m], EA [N], EI [N m^2]
    const double L = 20.0, payloadWeight = 1000.0 * 9.81;
    for (auto energy : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral}) {
        SpanOptions options;
        options.axialModes = 3;
        options.transverseModes = 3;
        options.elasticModel = energy;
        options.axialDynamics = AxialDynamics::Dynamic;  // PaperLiteral cannot be condensed (QuasiStatic)
        const PlanarSpanModel span(rope, options, Eigen::Vector2d(0, -9.81));

        // Sheave node at the origin, payload node straight below, stretched so P = payload weight.
        const double lambda = std::sqrt(1.0 + 2.0 * payloadWeight / rope.axialStiffness);
        Eigen::VectorXd q = Eigen::VectorXd::Zero(span.numCoordinates());
        q.segment<2>(span.r2Index()) = Eigen::Vector2d(0, -lambda * L);
        q[span.s2Index()] = L;
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q.size());

        // Linearised transverse frequencies (nodes and material coordinates held).
        SpanData<2> data;
        span.evaluate(q, zero, data);
        const int i0 = span.transverseModeIndex(0, 0), nt = span.transverseModes();
        Eigen::MatrixXd K(nt, nt);
        for (int j = 0; j < nt; ++j) {
            Eigen::VectorXd qp = q, qm = q;
            qp[i0 + j] += 1e-7;
            qm[i0 + j] -= 1e-7;
            SpanData<2> dp, dm;
            span.evaluate(qp, zero, dp);
            span.evaluate(qm, zero, dm);
            K.col(j) = -(dp.elasticForces - dm.elasticForces).segment(i0, nt) / 2e-7;
        }
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
            0.5 * (K + K.transpose()), Eigen::MatrixXd(data.massMatrix.block(i0, i0, nt, nt)));
        std::printf("%s energy (n_a = %d, n_t = %d, %d + %d quadrature points)\n",
                    energy == ElasticEnergyModel::Consistent ? "Consistent" : "PaperLiteral", span.axialModes(),
                    nt, span.quadraturePoints(Integrand::Kinetic), span.quadraturePoints(Integrand::Strain));
        std::printf("  axial force at s = 0, L/2, L: %.1f %.1f %.1f N\n", span.axialForce(q, 0),
                    span.axialForce(q, L / 2), span.axialForce(q, L));
        for (int n = 1; n <= nt; ++n) {
            const double f = std::sqrt(eig.eigenvalues()[n - 1]) / (2 * std::acos(-1.0));
            const double fString = n / (2 * L) * std::sqrt(payloadWeight / rope.massPerLength);
            std::printf("  transverse mode %d: %.4f Hz (taut string %.4f Hz, ratio %.4f)\n", n, f, fString,
                        f / fString);
        }
    }
    return 0;
}
