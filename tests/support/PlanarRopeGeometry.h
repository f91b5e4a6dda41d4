#pragma once
/// @file
/// Test support: a planar rope's length measured from its geometry, independently of the rope
/// model's material bookkeeping. Closed forms only (no plugin code):
///   - the tangent of a straight span between two grooves (or a point and a groove) in the x-y
///     plane, each groove a circle of centre c, radius R and wrap sense sigma (+1: the rope runs
///     counter-clockwise about +z on it; a point is R = 0);
///   - a groove's wrap angle from its two tangent points;
///   - a span's material (unstretched) length from points along it and the stretch there,
///     sum |r_{i+1} - r_i| / lambda_{i+1/2}, lambda = sqrt(1 + 2 eps) the stretch of the Green
///     strain eps = P / EA.
/// So a check "spans + R alpha + stored rope = L" built from these fails when the model's arc
/// length, tangent points or drum rope disagree with the geometry, which the model's own sum
/// (s2 - s1 over the spans plus l over the arcs) cannot: that sum equals L by construction.

#include <Eigen/Core>

#include <cmath>
#include <utility>
#include <vector>

namespace SimbodyReevingTest {

/// A groove in the x-y plane: centre [m], radius [m] (0: a point), wrap sense (+1 counter-
/// clockwise about +z, -1 clockwise; ignored for a point).
struct PlanarGroove {
    Eigen::Vector2d centre;
    double radius = 0;
    int sense = 1;
};

/// z x v for v in the x-y plane.
inline Eigen::Vector2d perpendicular(const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); }

/// The tangent points (T_a, T_b) of the straight span from groove a to groove b, the rope running
/// from a to b. At each groove the rope moves along u (the unit span direction) with the centre on
/// the side sigma (z x u): T = c - sigma R (z x u). With D = c_b - c_a and
/// Delta = sigma_b R_b - sigma_a R_a, D = |T_b - T_a| u + Delta (z x u) gives
/// u = (L D - Delta z x D) / |D|^2, L = sqrt(|D|^2 - Delta^2).
inline std::pair<Eigen::Vector2d, Eigen::Vector2d> spanTangentPoints(const PlanarGroove& a, const PlanarGroove& b) {
    const Eigen::Vector2d D = b.centre - a.centre;
    const double rhoA = a.sense * a.radius, rhoB = b.sense * b.radius, delta = rhoB - rhoA;
    const double L = std::sqrt(D.squaredNorm() - delta * delta);
    const Eigen::Vector2d u = (L * D - delta * perpendicular(D)) / D.squaredNorm();
    const Eigen::Vector2d n = perpendicular(u);
    return {a.centre - rhoA * n, b.centre - rhoB * n};
}

/// The angle [rad] in [0, 2 pi) through which the rope turns on groove g from its arrival tangent
/// point to its departure tangent point, in the groove's sense.
inline double grooveWrapAngle(const PlanarGroove& g, const Eigen::Vector2d& arrival, const Eigen::Vector2d& departure) {
    const Eigen::Vector2d p = arrival - g.centre, q = departure - g.centre;
    double a = g.sense * std::atan2(p.x() * q.y() - p.y() * q.x(), p.dot(q));
    if (a < 0) a += 2 * 3.14159265358979323846;
    return a;
}

/// The angle [rad] of point p about centre c, counter-clockwise about +z from +x.
inline double polarAngle(const Eigen::Vector2d& c, const Eigen::Vector2d& p) { return std::atan2(p.y() - c.y(), p.x() - c.x()); }

/// A span's material length [m] from points along it (in order) and the Green strain at each:
/// sum over the segments of their length over the mean stretch sqrt(1 + 2 eps) of their ends.
inline double materialLengthFromGeometry(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& strains) {
    double l = 0;
    for (size_t i = 0; i + 1 < points.size(); ++i) {
        const double stretch = 0.5 * (std::sqrt(1 + 2 * strains[i]) + std::sqrt(1 + 2 * strains[i + 1]));
        l += (points[i + 1] - points[i]).norm() / stretch;
    }
    return l;
}

}  // namespace SimbodyReevingTest
