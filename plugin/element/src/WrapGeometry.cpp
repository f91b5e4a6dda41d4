#include "SimbodyReeving/element/WrapGeometry.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace SimbodyReeving {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kTwoPi = 6.283185307179586476925286766559;

std::string str(const Vec3& v) {
    std::ostringstream os;
    os.precision(9);
    os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return os.str();
}

/// One end of the span as the solver sees it: unit axis, its radial vector and in-plane tangent.
struct EndState {
    bool circle = false;
    Vec3 c = Vec3::Zero();  // point or centre
    Vec3 n = Vec3::UnitZ();
    double R = 0;
    int sigma = 1;
    Vec3 e = Vec3::Zero();  // radial (circle)
    Vec3 w = Vec3::Zero();  // n x e
    Vec3 T = Vec3::Zero();  // tangent point (or the point)

    void setRadial(const Vec3& radial) {
        e = radial - n * n.dot(radial);
        e.normalize();
        w = n.cross(e);
        T = c + R * e;
    }
};

EndState makeEnd(const TangencyEnd& end) {
    EndState s;
    s.c = end.position();
    s.T = s.c;
    s.circle = end.isCircle();
    if (s.circle) {
        validateGrooveCircle(end.groove());
        s.n = end.groove().axis.normalized();
        s.R = end.groove().radius;
        s.sigma = end.groove().wrapSense;
    } else if (!s.c.allFinite()) {
        throw std::invalid_argument("computeSpanTangency: point end " + str(s.c) + " is not finite");
    }
    return s;
}

/// Radial vector of the tangent from point p to the circle (arriving: the rope goes from p to the
/// circle; else it leaves the circle towards p).
Vec3 pointTangentRadial(const EndState& k, const Vec3& p, bool arriving) {
    Vec3 d = p - k.c;
    d -= k.n * k.n.dot(d);
    const double rho = d.norm();
    if (!(rho > k.R * (1 + 1e-12))) {
        std::ostringstream os;
        os.precision(9);
        os << "computeSpanTangency: no tangent from " << str(p) << " to the groove circle of radius " << k.R
           << " m at " << str(k.c) << ": the point's projection onto the groove's plane lies at " << rho
           << " m from the centre, on or inside the circle";
        throw std::domain_error(os.str());
    }
    const Vec3 dh = d / rho;
    const double cb = k.R / rho;
    const double sb = std::sqrt((rho - k.R) * (rho + k.R)) / rho;
    const double side = arriving ? k.sigma : -k.sigma;
    return cb * dh + side * sb * k.n.cross(dh);
}

/// The tangency matrix K: d[F_start, F_end] = K d[phi_start, phi_end] with F = D . e at each circle
/// end, D = T_end - T_start (also the matrix of the rates' and accelerations' equations).
struct Tangency2x2 {
    double k00 = 1, k01 = 0, k10 = 0, k11 = 1;
};

Tangency2x2 tangencyMatrix(const EndState& a, const EndState& b) {
    const Vec3 D = b.T - a.T;
    Tangency2x2 K;
    if (a.circle) {
        K.k00 = D.dot(a.w);
        K.k01 = b.circle ? b.R * b.w.dot(a.e) : 0.0;
    }
    if (b.circle) {
        K.k10 = a.circle ? -a.R * a.w.dot(b.e) : 0.0;
        K.k11 = D.dot(b.w);
    }
    return K;
}

/// Solves K x = r for the unknown angles of the circle ends (x = 0 at point ends).
void solveTangency(const EndState& a, const EndState& b, const Tangency2x2& K, double ra, double rb, double& xa,
                   double& xb) {
    xa = 0;
    xb = 0;
    const double scale = (b.T - a.T).norm();
    auto singular = []() {
        throw std::domain_error(
            "computeSpanTangency: singular tangency: the span runs along a groove's axis (fleet angle 90 degrees)");
    };
    if (a.circle && b.circle) {
        const double det = K.k00 * K.k11 - K.k01 * K.k10;
        if (!(std::abs(det) > 1e-14 * scale * scale)) singular();
        xa = (ra * K.k11 - K.k01 * rb) / det;
        xb = (K.k00 * rb - K.k10 * ra) / det;
    } else if (a.circle) {
        if (!(std::abs(K.k00) > 1e-14 * scale)) singular();
        xa = ra / K.k00;
    } else if (b.circle) {
        if (!(std::abs(K.k11) > 1e-14 * scale)) singular();
        xb = rb / K.k11;
    }
}

void rotateRadial(EndState& s, double dphi) {
    if (!s.circle || dphi == 0) return;
    s.setRadial(std::cos(dphi) * s.e + std::sin(dphi) * s.w);
}

/// The two ends at the solution held by `t`.
void restoreEnds(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency& t, EndState& a,
                 EndState& b) {
    a = makeEnd(start);
    b = makeEnd(end);
    if (a.circle) a.setRadial(t.startRadial);
    if (b.circle) b.setRadial(t.endRadial);
}

}  // namespace

void validateGrooveCircle(const GrooveCircle& circle) {
    if (!circle.centre.allFinite())
        throw std::invalid_argument("GrooveCircle: centre " + str(circle.centre) + " is not finite");
    if (!circle.axis.allFinite() || !(circle.axis.norm() > 0))
        throw std::invalid_argument("GrooveCircle: axis " + str(circle.axis) + " must be finite and non-zero");
    if (!std::isfinite(circle.radius) || !(circle.radius > 0))
        throw std::invalid_argument("GrooveCircle: radius " + std::to_string(circle.radius) +
                                    " m must be finite and > 0");
    if (circle.wrapSense != 1 && circle.wrapSense != -1)
        throw std::invalid_argument("GrooveCircle: wrapSense " + std::to_string(circle.wrapSense) +
                                    " must be +1 or -1");
}

SpanTangency computeSpanTangency(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency* warmStart) {
    EndState a = makeEnd(start), b = makeEnd(end);
    SpanTangency out;
    if (a.circle && !b.circle) {
        a.setRadial(pointTangentRadial(a, b.c, false));
    } else if (!a.circle && b.circle) {
        b.setRadial(pointTangentRadial(b, a.c, true));
    } else if (a.circle && b.circle) {
        const bool warm = warmStart != nullptr && warmStart->startRadial.allFinite() &&
                          warmStart->endRadial.allFinite() && warmStart->startRadial.squaredNorm() > 0.5 &&
                          warmStart->endRadial.squaredNorm() > 0.5;
        if (warm) {
            a.setRadial(warmStart->startRadial);
            b.setRadial(warmStart->endRadial);
        } else {
            a.setRadial(pointTangentRadial(a, b.c, false));
            b.setRadial(pointTangentRadial(b, a.T, true));
            for (int k = 0; k < 2; ++k) {
                a.setRadial(pointTangentRadial(a, b.T, false));
                b.setRadial(pointTangentRadial(b, a.T, true));
            }
        }
        // Newton on the radial angles: F = [D . e_a, D . e_b] = 0.
        const double size = (b.c - a.c).norm() + a.R + b.R;
        const double tolerance = 1e-15 * size;
        double last = INFINITY;
        int it = 0;
        for (; it < 50; ++it) {
            const Vec3 D = b.T - a.T;
            const double fa = D.dot(a.e), fb = D.dot(b.e);
            const double residual = std::max(std::abs(fa), std::abs(fb));
            if (residual <= tolerance || (it > 3 && residual >= 0.5 * last && residual < 1e3 * tolerance)) break;
            last = residual;
            double da = 0, db = 0;
            solveTangency(a, b, tangencyMatrix(a, b), -fa, -fb, da, db);
            rotateRadial(a, da);
            rotateRadial(b, db);
        }
        const Vec3 D = b.T - a.T;
        const double residual = std::max(std::abs(D.dot(a.e)), std::abs(D.dot(b.e)));
        if (!(residual < 1e3 * tolerance)) {
            std::ostringstream os;
            os << "computeSpanTangency: the common tangent of the groove circles at " << str(a.c) << " and "
               << str(b.c) << " did not converge (residual " << residual << " m after " << it << " iterations)";
            throw std::domain_error(os.str());
        }
        out.newtonIterations = it;
    }
    const Vec3 D = b.T - a.T;
    out.length = D.norm();
    if (!(out.length > 0)) throw std::domain_error("computeSpanTangency: the span's two ends coincide at " + str(a.T));
    out.direction = D / out.length;
    // The tangent of the given senses: the rope travels on in the groove's sense at each circle end.
    auto checkSense = [&](const EndState& s, const char* which) {
        if (!s.circle) return;
        if (!(s.sigma * s.w.dot(out.direction) > 0)) {
            std::ostringstream os;
            os << "computeSpanTangency: no tangent of the groove's wrap sense " << s.sigma << " at the span's "
               << which << " (groove circle at " << str(s.c) << ", radius " << s.R
               << " m): the circles overlap or the solve reached the other tangent";
            throw std::domain_error(os.str());
        }
    };
    checkSense(a, "start");
    checkSense(b, "end");
    out.start = a.T;
    out.end = b.T;
    if (a.circle) {
        out.startRadial = a.e;
        out.startFleetAngle = std::asin(std::max(-1.0, std::min(1.0, out.direction.dot(a.n))));
    }
    if (b.circle) {
        out.endRadial = b.e;
        out.endFleetAngle = std::asin(std::max(-1.0, std::min(1.0, out.direction.dot(b.n))));
    }
    return out;
}

void computeTangencyRates(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency& tangency,
                          const EndMotion& startMotion, const EndMotion& endMotion, TangencyRates& rates) {
    EndState a, b;
    restoreEnds(start, end, tangency, a, b);
    const Tangency2x2 K = tangencyMatrix(a, b);
    const Vec3 D = b.T - a.T;

    // First derivatives. edot = phidot w - n (e . n'): the part at phidot = 0 first.
    auto radialRate0 = [](const EndState& s, const EndMotion& m) -> Vec3 {
        return s.circle ? Vec3(-s.n * s.e.dot(m.axisRate)) : Vec3::Zero();
    };
    const Vec3 ea0 = radialRate0(a, startMotion), eb0 = radialRate0(b, endMotion);
    const Vec3 Dd0 = (endMotion.velocity + b.R * eb0) - (startMotion.velocity + a.R * ea0);
    // d/dt (D . e) = Ddot . e + D . edot = 0.
    const double ra = a.circle ? -(Dd0.dot(a.e) + D.dot(ea0)) : 0.0;
    const double rb = b.circle ? -(Dd0.dot(b.e) + D.dot(eb0)) : 0.0;
    double pa = 0, pb = 0;
    solveTangency(a, b, K, ra, rb, pa, pb);
    const Vec3 ea = ea0 + pa * a.w, eb = eb0 + pb * b.w;
    const Vec3 va = startMotion.velocity + a.R * ea, vb = endMotion.velocity + b.R * eb;
    rates.startAngleRate = pa;
    rates.endAngleRate = pb;
    rates.startVelocity = va;
    rates.endVelocity = vb;

    // Second derivatives: eddot = phiddot w + phidot wdot - n' (e . n') - n (edot . n' + e . n''),
    // wdot = n' x e + n x edot; the part at phiddot = 0 first.
    auto radialAcc0 = [](const EndState& s, const EndMotion& m, const Vec3& ed, double phidot) -> Vec3 {
        if (!s.circle) return Vec3::Zero();
        const Vec3 wd = m.axisRate.cross(s.e) + s.n.cross(ed);
        return phidot * wd - m.axisRate * s.e.dot(m.axisRate) - s.n * (ed.dot(m.axisRate) + s.e.dot(m.axisAcceleration));
    };
    const Vec3 eaa0 = radialAcc0(a, startMotion, ea, pa), ebb0 = radialAcc0(b, endMotion, eb, pb);
    const Vec3 Ddd0 = (endMotion.acceleration + b.R * ebb0) - (startMotion.acceleration + a.R * eaa0);
    const Vec3 Dd = vb - va;
    // d2/dt2 (D . e) = Dddot . e + 2 Ddot . edot + D . eddot = 0.
    const double sa = a.circle ? -(Ddd0.dot(a.e) + 2 * Dd.dot(ea) + D.dot(eaa0)) : 0.0;
    const double sb = b.circle ? -(Ddd0.dot(b.e) + 2 * Dd.dot(eb) + D.dot(ebb0)) : 0.0;
    double qa = 0, qb = 0;
    solveTangency(a, b, K, sa, sb, qa, qb);
    rates.startAngleAcceleration = qa;
    rates.endAngleAcceleration = qb;
    rates.startAcceleration = startMotion.acceleration + a.R * (eaa0 + qa * a.w);
    rates.endAcceleration = endMotion.acceleration + b.R * (ebb0 + qb * b.w);
}

void computeTangencyJacobian(const TangencyEnd& start, const TangencyEnd& end, const SpanTangency& tangency,
                             TangencyJacobian& jacobian, bool axisColumns) {
    // The rates are linear in the ends' velocities and axis rates: one column per unit rate, each
    // the first-order part of computeTangencyRates (one 2 x 2 solve on the shared K).
    jacobian.setZero();
    EndState a, b;
    restoreEnds(start, end, tangency, a, b);
    const Tangency2x2 K = tangencyMatrix(a, b);
    const Vec3 D = b.T - a.T;
    for (int col = 0; col < 12; ++col) {
        const int block = col / 3, k = col % 3;
        if ((block == 1 || block == 3) && !axisColumns) continue;
        if (block == 1 && !a.circle) continue;
        if (block == 3 && !b.circle) continue;
        Vec3 va = Vec3::Zero(), vb = Vec3::Zero(), ea0 = Vec3::Zero(), eb0 = Vec3::Zero();
        if (block == 0) va[k] = 1;
        if (block == 2) vb[k] = 1;
        if (block == 1) ea0 = -a.n * a.e[k];  // edot at phidot = 0 for the axis rate n' = unit k
        if (block == 3) eb0 = -b.n * b.e[k];
        const Vec3 Dd0 = (vb + b.R * eb0) - (va + a.R * ea0);
        const double ra = a.circle ? -(Dd0.dot(a.e) + D.dot(ea0)) : 0.0;
        const double rb = b.circle ? -(Dd0.dot(b.e) + D.dot(eb0)) : 0.0;
        double pa = 0, pb = 0;
        solveTangency(a, b, K, ra, rb, pa, pb);
        jacobian.block<3, 1>(0, col) = va + a.R * (ea0 + pa * a.w);
        jacobian.block<3, 1>(3, col) = vb + b.R * (eb0 + pb * b.w);
        jacobian(6, col) = pa;
        jacobian(7, col) = pb;
    }
}

double wrapAngle(const GrooveCircle& circle, const Vec3& arrivalRadial, const Vec3& departureRadial) {
    const Vec3 n = circle.axis.normalized();
    const double s = circle.wrapSense * n.dot(arrivalRadial.cross(departureRadial));
    const double c = arrivalRadial.dot(departureRadial);
    double alpha = std::atan2(s, c);
    if (alpha < 0) alpha += kTwoPi;
    return alpha;
}

double wrapAngle(const GrooveCircle& circle, const Vec3& arrivalRadial, const Vec3& departureRadial,
                 double previous) {
    const double alpha = wrapAngle(circle, arrivalRadial, departureRadial);
    if (!std::isfinite(previous)) return alpha;
    return alpha + kTwoPi * std::round((previous - alpha) / kTwoPi);
}

int wrapSenseFromPath(const Vec3& before, const GrooveCircle& circle, const Vec3& after) {
    if (!before.allFinite() || !after.allFinite() || !circle.centre.allFinite() || !circle.axis.allFinite() ||
        !(circle.axis.norm() > 0))
        throw std::invalid_argument("wrapSenseFromPath: the path's points and the groove's centre and axis must be finite "
                                    "(and the axis non-zero)");
    const Vec3 in = circle.centre - before, out = after - circle.centre;
    if (!(in.norm() > 0) || !(out.norm() > 0))
        throw std::invalid_argument("wrapSenseFromPath: a path point coincides with the groove's centre " +
                                    str(circle.centre));
    const Vec3 turn = in.normalized().cross(out.normalized());
    if (!(turn.norm() > 1e-9))
        throw std::invalid_argument("wrapSenseFromPath: the path " + str(before) + " -> " + str(circle.centre) +
                                    " -> " + str(after) + " is straight: the wrap sense must be given");
    const double s = circle.axis.normalized().dot(turn);
    if (!(std::abs(s) > 1e-9 * turn.norm()))
        throw std::invalid_argument("wrapSenseFromPath: the path turns in a plane containing the groove's axis " +
                                    str(circle.axis) + ": it does not wrap the groove");
    return s > 0 ? 1 : -1;
}

}  // namespace SimbodyReeving
