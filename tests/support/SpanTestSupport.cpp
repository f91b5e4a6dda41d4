#include "support/SpanTestSupport.h"

#include <cmath>

namespace SimbodyReeving::test {

template <int Dim>
Eigen::VectorXd randomState(const SpanModel<Dim>& model, std::mt19937& rng, double length) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    using Vec = Eigen::Matrix<double, Dim, 1>;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model.numCoordinates());
    Vec r1;
    for (int k = 0; k < Dim; ++k) r1[k] = 3.0 * u(rng);
    // Chord direction: reference direction tilted by up to ~50 degrees.
    Vec dir = model.referenceFrame().col(0);
    for (int k = 0; k < Dim; ++k) dir[k] += 0.6 * u(rng);
    dir.normalize();
    const double stretch = 1.0 + 0.05 * u(rng);
    const Vec r2 = r1 + stretch * length * dir;
    q.template segment<Dim>(SpanModel<Dim>::r1Index()) = r1;
    q.template segment<Dim>(SpanModel<Dim>::r2Index()) = r2;
    for (int i = 0; i < model.axialModes(); ++i) q[model.axialModeIndex(i)] = 0.02 * length * u(rng) / (i + 1);
    for (int dir2 = 0; dir2 < Dim - 1; ++dir2)
        for (int i = 0; i < model.transverseModes(); ++i)
            q[model.transverseModeIndex(dir2, i)] = 0.05 * length * u(rng) / (i + 1);
    const double s1 = 5.0 * u(rng);
    q[model.s1Index()] = s1;
    q[model.s2Index()] = s1 + length;
    return q;
}

template <int Dim>
Eigen::VectorXd randomVelocity(const SpanModel<Dim>& model, std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd v(model.numCoordinates());
    for (int k = 0; k < v.size(); ++k) v[k] = scale * u(rng);
    return v;
}

template Eigen::VectorXd randomState<2>(const SpanModel<2>&, std::mt19937&, double);
template Eigen::VectorXd randomState<3>(const SpanModel<3>&, std::mt19937&, double);
template Eigen::VectorXd randomVelocity<2>(const SpanModel<2>&, std::mt19937&, double);
template Eigen::VectorXd randomVelocity<3>(const SpanModel<3>&, std::mt19937&, double);

Eigen::VectorXd centralGradient(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                                double h) {
    Eigen::VectorXd g(x.size());
    Eigen::VectorXd xp = x;
    for (int k = 0; k < x.size(); ++k) {
        xp[k] = x[k] + h;
        const double fp = f(xp);
        xp[k] = x[k] - h;
        const double fm = f(xp);
        xp[k] = x[k];
        g[k] = (fp - fm) / (2 * h);
    }
    return g;
}

double relativeError(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

void rk4Step(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, Eigen::VectorXd& y, double h) {
    const Eigen::VectorXd k1 = f(y);
    const Eigen::VectorXd k2 = f(y + 0.5 * h * k1);
    const Eigen::VectorXd k3 = f(y + 0.5 * h * k2);
    const Eigen::VectorXd k4 = f(y + h * k3);
    y += (h / 6.0) * (k1 + 2 * k2 + 2 * k3 + k4);
}

}  // namespace SimbodyReeving::test
