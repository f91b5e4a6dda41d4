#include "SimbodyReeving/element/WrapStationMap.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {
namespace {
Eigen::Vector3d lift(const Eigen::Vector2d& v) { return Eigen::Vector3d(v[0], v[1], 0.0); }
}  // namespace

Eigen::Vector2d WrapStationMap::upDirection() const {
    const Eigen::Vector2d g = rope_->span(0).gravity();
    return g.norm() > 0 ? Eigen::Vector2d(-g / g.norm()) : Eigen::Vector2d(0.0, 1.0);
}

void WrapStationMap::evaluate(const Eigen::VectorXd& stations, const Eigen::VectorXd& stationRates,
                              WrapStationMapData& data) const {
    evaluateMap(stations, &stationRates, data);
}

void WrapStationMap::evaluatePositions(const Eigen::VectorXd& stations, WrapStationMapData& data) const {
    evaluateMap(stations, nullptr, data);
}

void WrapStationMap::evaluateMap(const Eigen::VectorXd& stations, const Eigen::VectorXd* ratesOrNull,
                                 WrapStationMapData& data) const {
    const RopeModel<2>& rope = *rope_;
    const bool withRates = ratesOrNull != nullptr;
    const Eigen::VectorXd& stationRates = withRates ? *ratesOrNull : stations;
    const int N = rope.numSpans(), nY = numStationCoordinates(), nx = rope.numExternalCoordinates();
    const int nodeRows = rope.numNodeCoordinates();
    if (stations.size() != nY || stationRates.size() != nY) {
        std::ostringstream msg;
        msg << "WrapStationMap: " << stations.size() << " stations and " << stationRates.size() << " rates given for "
            << nY << " station coordinates";
        throw std::invalid_argument(msg.str());
    }
    if (!stations.allFinite() || (withRates && !stationRates.allFinite()))
        throw std::invalid_argument("WrapStationMap: the stations and their rates must be finite");
    const bool previous = data.wrapAngles.size() == N + 1 && data.arrivalAngles.size() == N + 1;
    if (!previous) {
        data.wrapAngles.setZero(N + 1);
        data.arrivalAngles.setZero(N + 1);
    }
    // An evaluation that throws leaves no wrap angles to continue from if it had none.
    struct ForgetAnglesUnlessDone {
        Eigen::VectorXd& angles;
        Eigen::VectorXd& arrival;
        bool keep;
        ~ForgetAnglesUnlessDone() {
            if (keep) return;
            angles.resize(0);
            arrival.resize(0);
        }
    } guard{data.wrapAngles, data.arrivalAngles, previous};
    const bool warm = static_cast<int>(data.tangencies.size()) == N;
    data.tangencies.resize(N);
    data.stations = stations;
    data.x.setZero(nx);
    if (withRates) {
        data.bias.setZero(nx);
        data.jacobian.setZero(nx, nY);
    } else {  // positions only: no J, b or xdot (sized 0, so that no stale ones are used)
        data.bias.resize(0);
        data.jacobian.resize(0, 0);
        data.xdot.resize(0);
    }
    auto station = [&](int k) { return Eigen::Vector2d(stations.segment<2>(2 * k)); };
    auto end = [&](int k) {
        if (!rope.isWrapped(k)) return TangencyEnd::point(lift(station(k)));
        GrooveCircle g;
        g.centre = lift(station(k));
        g.radius = rope.arc(k).radius();
        g.wrapSense = rope.arc(k).wrapSense();
        return TangencyEnd::circle(g);
    };
    // Node blocks: a point's position and a groove's centre are stations.
    for (int k = 0; k <= N; ++k) {
        const int o = rope.nodeCoordinateOffset(k) + (rope.isWrapped(k) ? RopeModel<2>::wrappedCentreOffset() : 0);
        data.x.segment<2>(o) = station(k);
        if (withRates) data.jacobian.block<2, 2>(o, 2 * k).setIdentity();
    }
    for (int d = 0; d < rope.numDrivenNodes(); ++d) {
        data.x[nodeRows + d] = stations[2 * (N + 1) + d];
        if (withRates) data.jacobian(nodeRows + d, 2 * (N + 1) + d) = 1.0;
    }
    // A wrapped node's arc length l = R alpha, alpha = sigma (phi_out - phi_in): its Jacobian row
    // and bias gather R sigma phi_out's from the span it starts (k) and -R sigma phi_in's from the
    // span it ends (k - 1).
    auto arcRow = [&](int k) { return rope.nodeCoordinateOffset(k) + RopeModel<2>::wrappedArcLengthOffset(); };
    auto arcScale = [&](int k) { return rope.arc(k).radius() * rope.arc(k).wrapSense(); };
    TangencyJacobian Jt;
    TangencyRates rates;
    for (int j = 0; j < N; ++j) {
        const TangencyEnd a = end(j), b = end(j + 1);
        try {
            const SpanTangency t = computeSpanTangency(a, b, warm ? &data.tangencies[j] : nullptr);
            data.tangencies[j] = t;
            if (withRates) {
                computeTangencyJacobian(a, b, t, Jt, false);  // planar: the grooves' axes stay +z
                EndMotion ma, mb;
                ma.velocity = lift(stationRates.segment<2>(2 * j));
                mb.velocity = lift(stationRates.segment<2>(2 * (j + 1)));
                computeTangencyRates(a, b, t, ma, mb, rates);
            }
        } catch (const std::domain_error& e) {
            std::ostringstream msg;
            msg << "WrapStationMap: span " << j << " (nodes " << j << " and " << j + 1 << "): " << e.what();
            throw std::domain_error(msg.str());
        }
        const SpanTangency& t = data.tangencies[j];
        // Jt rows [T1 (3), T2 (3), phi1, phi2], columns [p1 (3), n1 (3), p2 (3), n2 (3)]: the plane's
        // x, y of the points and the stations of nodes j (columns 0, 1) and j + 1 (6, 7).
        auto rowsOver = [&](int row, double scale, int r) {
            data.jacobian.block<1, 2>(r, 2 * j) += scale * Jt.block<1, 2>(row, 0);
            data.jacobian.block<1, 2>(r, 2 * (j + 1)) += scale * Jt.block<1, 2>(row, 6);
        };
        // A wrapped end (a drum, Driven) has one tangent point, T_in = T_out, and no arc (l = 0):
        // the rope beyond it is the drum's stored rope. Its material coordinate there is
        // Y_s + sigma R phi, phi the tangent point's angle.
        if (rope.isWrapped(j)) {
            const bool drum = j == 0;
            for (int offset : {RopeModel<2>::wrappedDepartureOffset(), RopeModel<2>::wrappedArrivalOffset()}) {
                if (!drum && offset == RopeModel<2>::wrappedArrivalOffset()) continue;
                const int o = rope.nodeCoordinateOffset(j) + offset;
                data.x.segment<2>(o) = t.start.head<2>();
                if (withRates) {
                    for (int d = 0; d < 2; ++d) {
                        rowsOver(d, 1.0, o + d);
                        data.bias[o + d] = rates.startAcceleration[d];
                    }
                }
            }
            if (withRates) {
                const int row = drum ? nodeRows + rope.drivenIndex(j) : arcRow(j);  // s_0 (below), or l
                rowsOver(6, arcScale(j), row);
                data.bias[row] += arcScale(j) * rates.startAngleAcceleration;
            }
        }
        if (rope.isWrapped(j + 1)) {
            const bool drum = j + 1 == N;
            for (int offset : {RopeModel<2>::wrappedArrivalOffset(), RopeModel<2>::wrappedDepartureOffset()}) {
                if (!drum && offset == RopeModel<2>::wrappedDepartureOffset()) continue;
                const int o = rope.nodeCoordinateOffset(j + 1) + offset;
                data.x.segment<2>(o) = t.end.head<2>();
                if (withRates) {
                    for (int d = 0; d < 2; ++d) {
                        rowsOver(3 + d, 1.0, o + d);
                        data.bias[o + d] = rates.endAcceleration[d];
                    }
                }
            }
            if (withRates) {
                if (!drum) {
                    rowsOver(7, -arcScale(j + 1), arcRow(j + 1));
                    data.bias[arcRow(j + 1)] -= arcScale(j + 1) * rates.endAngleAcceleration;
                }
                if (rope.drivenIndex(j + 1) >= 0) {  // s_in = Y_s + sigma R phi_in (below)
                    const int row = nodeRows + rope.drivenIndex(j + 1);
                    rowsOver(7, arcScale(j + 1), row);
                    data.bias[row] += arcScale(j + 1) * rates.endAngleAcceleration;
                }
            }
        }
    }
    // The path must turn at each wrapped node the way its rope wraps the groove: a sense given
    // the wrong way would wrap the rope around the groove's far side (a figure of eight). Checked
    // where alpha starts (no previous evaluation), on the path through the neighbours and the
    // groove's centre (a wrapped drum at an end counts at its tangent point: it may be large
    // against the distance to its neighbour); from there alpha is continued, and a wrap angle
    // falling through 0 (the rope leaving the groove) is for the caller to stop at.
    auto pathPoint = [&](int j) {
        if (j == 0 && rope.isWrapped(0)) return Eigen::Vector2d(data.tangencies[0].start.head<2>());
        if (j == N && rope.isWrapped(N)) return Eigen::Vector2d(data.tangencies[N - 1].end.head<2>());
        return station(j);
    };
    for (int k = 1; k < N && !previous; ++k) {
        if (!rope.isWrapped(k)) continue;
        const Eigen::Vector2d in = station(k) - pathPoint(k - 1), out = pathPoint(k + 1) - station(k);
        const double turn = in[0] * out[1] - in[1] * out[0];
        const int sigma = rope.arc(k).wrapSense();
        if (sigma * turn < -1e-9 * in.norm() * out.norm()) {
            std::ostringstream msg;
            msg << "WrapStationMap: node " << k << ": the rope's path turns " << (turn > 0 ? "counter-clockwise" : "clockwise")
                << " about the plane normal there (from node " << k - 1 << " past the groove's centre to node " << k + 1
                << ") but its wrap sense is " << (sigma > 0 ? "+1" : "-1");
            throw std::domain_error(msg.str());
        }
    }
    // Arc lengths l = R alpha, alpha = sigma (phi_out - phi_in) (continuous with the previous alpha).
    for (int k = 1; k < N; ++k) {
        if (!rope.isWrapped(k)) continue;
        const GrooveArc<2>& arc = rope.arc(k);
        GrooveCircle g;
        g.centre = lift(station(k));
        g.radius = arc.radius();
        g.wrapSense = arc.wrapSense();
        const double alpha = previous ? wrapAngle(g, data.tangencies[k - 1].endRadial, data.tangencies[k].startRadial,
                                                  data.wrapAngles[k])
                                      : wrapAngle(g, data.tangencies[k - 1].endRadial, data.tangencies[k].startRadial);
        data.wrapAngles[k] = alpha;
        data.x[arcRow(k)] = arc.radius() * alpha;
    }
    // A wrapped Driven node grips the rope on its groove: the material coordinate at the arriving
    // tangent point is s_in = Y_s + sigma R phi_in, phi_in the tangent point's angle about the
    // centre, counter-clockwise from "up" (against gravity in the plane; +y without gravity) and
    // continuous with the previous evaluation's, so the departing span starts at
    // Y_s + sigma R phi_out = s_in + l (the rope does not slide on the groove). Its Jacobian row and
    // bias were gathered with the spans' (phi_in's row of the span arriving there).
    for (int k = 0; k <= N; ++k) {
        if (rope.drivenIndex(k) < 0 || !rope.isWrapped(k)) continue;
        // (A drum at the rope's start: the tangent point where span 0 leaves it.)
        const Eigen::Vector3d& radial = k > 0 ? data.tangencies[k - 1].endRadial : data.tangencies[0].startRadial;
        const Eigen::Vector2d up = upDirection();
        const double measured = std::atan2(up[0] * radial[1] - up[1] * radial[0], up[0] * radial[0] + up[1] * radial[1]);
        double phi = measured;
        if (previous) phi = data.arrivalAngles[k] + std::remainder(measured - data.arrivalAngles[k], 2 * M_PI);
        data.arrivalAngles[k] = phi;
        data.x[nodeRows + rope.drivenIndex(k)] += arcScale(k) * phi;
    }
    if (withRates) {
        // Row bands: the first and last non-zero column of each row.
        data.jacobianRowStart.resize(static_cast<std::size_t>(nx));
        data.jacobianRowWidth.resize(static_cast<std::size_t>(nx));
        for (int r = 0; r < nx; ++r) {
            int first = 0, last = -1;
            for (int c = 0; c < nY; ++c)
                if (data.jacobian(r, c) != 0.0) {
                    if (last < 0) first = c;
                    last = c;
                }
            data.jacobianRowStart[static_cast<std::size_t>(r)] = first;
            data.jacobianRowWidth[static_cast<std::size_t>(r)] = last - first + 1;
        }
        multiplyByStationJacobian(data, stationRates, data.xdot);
    }
    guard.keep = true;
}

namespace {
template <class Out>
void jacobianTimes(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X, Out& out) {
    const Eigen::MatrixXd& J = map.jacobian;
    out.setZero(J.rows(), X.cols());
    for (Eigen::Index r = 0; r < J.rows(); ++r) {
        const int s = map.jacobianRowStart[static_cast<std::size_t>(r)], w = map.jacobianRowWidth[static_cast<std::size_t>(r)];
        if (w > 0) out.row(r).noalias() = J.row(r).segment(s, w) * X.middleRows(s, w);
    }
}

template <class Out>
void jacobianTransposedTimes(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X, Out& out) {
    const Eigen::MatrixXd& J = map.jacobian;
    out.setZero(J.cols(), X.cols());
    for (Eigen::Index r = 0; r < J.rows(); ++r) {
        const int s = map.jacobianRowStart[static_cast<std::size_t>(r)], w = map.jacobianRowWidth[static_cast<std::size_t>(r)];
        if (w > 0) out.middleRows(s, w).noalias() += J.row(r).segment(s, w).transpose() * X.row(r);
    }
}

}  // namespace

void multiplyByStationJacobian(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                               Eigen::MatrixXd& out) {
    jacobianTimes(map, X, out);
}
void multiplyByStationJacobian(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                               Eigen::VectorXd& out) {
    jacobianTimes(map, X, out);
}
void multiplyByStationJacobianTransposed(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                         Eigen::MatrixXd& out) {
    jacobianTransposedTimes(map, X, out);
}
void multiplyByStationJacobianTransposed(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                         Eigen::VectorXd& out) {
    jacobianTransposedTimes(map, X, out);
}

void multiplyStationJacobianFromLeft(const Eigen::Ref<const Eigen::MatrixXd>& A, const WrapStationMapData& map,
                                     Eigen::MatrixXd& out) {
    const Eigen::MatrixXd& J = map.jacobian;
    out.setZero(A.rows(), J.cols());
    for (Eigen::Index r = 0; r < J.rows(); ++r) {
        const int s = map.jacobianRowStart[static_cast<std::size_t>(r)], w = map.jacobianRowWidth[static_cast<std::size_t>(r)];
        if (w > 0) out.middleCols(s, w).noalias() += A.col(r) * J.row(r).segment(s, w);
    }
}

void WrapStationMap::stationNodeMass(const WrapStationMapData& map, const RopeData<2>& ropeData,
                                     Eigen::MatrixXd& SY) const {
    const int nx = rope_->numExternalCoordinates();
    if (ropeData.nodeMass.rows() != nx || ropeData.nodeMass.cols() != nx)
        throw std::invalid_argument("WrapStationMap::stationNodeMass: the rope's nodeMass is not formed (" +
                                    std::to_string(ropeData.nodeMass.rows()) + " x " +
                                    std::to_string(ropeData.nodeMass.cols()) + " for " + std::to_string(nx) +
                                    " external coordinates)");
    Eigen::MatrixXd SJ;
    multiplyStationJacobianFromLeft(ropeData.nodeMass, map, SJ);
    multiplyByStationJacobianTransposed(map, SJ, SY);
}

void WrapStationMap::stationNodeForce(const WrapStationMapData& map, const RopeData<2>& ropeData,
                                      Eigen::VectorXd& hY) const {
    const int nx = rope_->numExternalCoordinates();
    Eigen::VectorXd f = ropeData.nodeForce;
    if (ropeData.nodeMass.rows() == nx && ropeData.nodeMass.cols() == nx) {
        f.noalias() -= ropeData.nodeMass * map.bias;
    } else {
        Eigen::MatrixXd Sb;
        rope_->multiplyByNodeMass(ropeData, map.bias, Sb);
        f -= Sb.col(0);
    }
    multiplyByStationJacobianTransposed(map, f, hY);
}

}  // namespace SimbodyReeving
