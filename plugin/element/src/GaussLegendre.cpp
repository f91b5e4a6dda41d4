#include "SimbodyReeving/element/GaussLegendre.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {

GaussLegendreRule makeGaussLegendreRule(int numPoints) {
    if (numPoints < 1 || numPoints > 200)
        throw std::invalid_argument("makeGaussLegendreRule: numPoints = " + std::to_string(numPoints) +
                                    " is outside 1..200");
    const int n = numPoints;
    GaussLegendreRule rule;
    rule.nodes.resize(n);
    rule.weights.resize(n);
    const double pi = std::acos(-1.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        // Tricomi's initial guess for the i-th root of P_n on [-1, 1] (descending order).
        double x = std::cos(pi * (i + 0.75) / (n + 0.5));
        double dp = 0.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) { p1 = x; p0 = 1.0; }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        // Recompute the derivative at the converged root for the weight.
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= n; ++k) {
            const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        dp = (n == 1) ? 1.0 : n * (x * p1 - p0) / (x * x - 1.0);
        const double w = 2.0 / ((1.0 - x * x) * dp * dp);
        // Map [-1, 1] -> [0, 1]; store ascending.
        rule.nodes[i] = 0.5 * (1.0 - x);
        rule.nodes[n - 1 - i] = 0.5 * (1.0 + x);
        rule.weights[i] = 0.5 * w;
        rule.weights[n - 1 - i] = 0.5 * w;
    }
    return rule;
}

GaussLegendreRule makeMidpointRule(int numPoints) {
    if (numPoints < 1 || numPoints > 200)
        throw std::invalid_argument("makeMidpointRule: numPoints = " + std::to_string(numPoints) +
                                    " is outside 1..200");
    GaussLegendreRule rule;
    rule.nodes.resize(numPoints);
    rule.weights.assign(numPoints, 1.0 / numPoints);
    for (int j = 0; j < numPoints; ++j) rule.nodes[j] = (j + 0.5) / numPoints;
    return rule;
}

}  // namespace SimbodyReeving
