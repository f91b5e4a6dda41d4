#include "SimbodyReeving/element/WrapStationMap.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace SimbodyReeving {
namespace {
// A planar rope's points and vectors in 3D (z = 0); a spatial rope's as they are.
template <int Dim>
Eigen::Vector3d lift(const Eigen::Matrix<double, Dim, 1>& v) {
    if constexpr (Dim == 2)
        return Eigen::Vector3d(v[0], v[1], 0.0);
    else
        return v;
}
}  // namespace

template <int Dim>
Eigen::Vector3d WrapStationMap<Dim>::upDirection() const {
    const Eigen::Vector3d g = lift<Dim>(rope_->span(0).gravity());
    // mutation-site: up-direction
    return g.norm() > 0 ? Eigen::Vector3d(-g / g.norm()) : Eigen::Vector3d(0.0, 1.0, 0.0);
}

template <int Dim>
void WrapStationMap<Dim>::evaluate(const Eigen::VectorXd& stations, const Eigen::VectorXd& stationRates,
                              WrapStationMapData& data) const {
    evaluateMap(stations, &stationRates, data);
}

template <int Dim>
void WrapStationMap<Dim>::evaluatePositions(const Eigen::VectorXd& stations, WrapStationMapData& data) const {
    evaluateMap(stations, nullptr, data);
}

template <int Dim>
void WrapStationMap<Dim>::evaluateMap(const Eigen::VectorXd& stations, const Eigen::VectorXd* ratesOrNull,
                                      WrapStationMapData& data) const {
    using Model = RopeModel<Dim>;
    const Model& rope = *rope_;
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
    data.startFleetAngles.setZero(N);
    data.endFleetAngles.setZero(N);
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
    const int numStations = rope.numStations();
    auto station = [&](int k) { return Vec(stations.template segment<Dim>(Dim * k)); };
    // The groove's axis: its own, or (turning with its body) from the centre to the axis station.
    auto axis = [&](int k) -> Eigen::Vector3d {
        if (rope.axisStation(k) < 0) return rope.grooveAxis(k);
        return lift<Dim>(Vec(station(rope.axisStation(k)) - station(k)));
    };
    auto axisRate = [&](int k) -> Eigen::Vector3d {
        if (rope.axisStation(k) < 0) return Eigen::Vector3d::Zero();
        const int a = rope.axisStation(k);
        return lift<Dim>(Vec(stationRates.template segment<Dim>(Dim * a) - stationRates.template segment<Dim>(Dim * k)));
    };
    // Where the groove circle lies: x(Y) along the axis from the node's position (its
    // GroovePlacement, NodeWrap::groove), Y its driven coordinate (read only by a placement that
    // follows it: such a node is Driven), with dx/dY and d2x/dY2. A centred groove's x = 0.
    auto drivenColumn = [&](int k) { return Dim * numStations + rope.drivenIndex(k); };
    auto follows = [&](int k) { return followsDriven(rope.groovePlacement(k)); };
    auto lay = [&](int k) {
        if (isAtCentre(rope.groovePlacement(k))) return GrooveLay{};
        if (!follows(k)) return layAt(rope.groovePlacement(k), 0.0);
        const int d = rope.drivenIndex(k);
        const double creep = rope.grips(k) && data.gripCreep.size() > d ? data.gripCreep[d] : 0.0;
        return layAt(rope.groovePlacement(k), stations[drivenColumn(k)] - creep);
    };
    auto groove = [&](int k) {
        GrooveCircle g;
        g.centre = lift<Dim>(station(k)) + lay(k).x * axis(k);
        g.axis = axis(k);
        g.radius = rope.arc(k).radius();
        g.wrapSense = rope.arc(k).wrapSense();
        return g;
    };
    auto end = [&](int k) {
        if (!rope.isWrapped(k)) return TangencyEnd::point(lift<Dim>(station(k)));
        return TangencyEnd::circle(groove(k));
    };
    // Node blocks: a point's position and a groove's centre are stations; a spatial groove's axis
    // is its own (constant) or turns with its body (n = a - c).
    for (int k = 0; k <= N; ++k) {
        const int o = rope.nodeCoordinateOffset(k) + (rope.isWrapped(k) ? Model::wrappedCentreOffset() : 0);
        data.x.template segment<Dim>(o) = station(k);
        if (withRates) data.jacobian.template block<Dim, Dim>(o, Dim * k).setIdentity();
        if constexpr (Dim == 3)
            if (rope.isWrapped(k)) {
                const int on = rope.nodeCoordinateOffset(k) + Model::wrappedAxisOffset();
                data.x.template segment<3>(on) = axis(k);
                if (withRates && rope.axisStation(k) >= 0) {
                    data.jacobian.template block<3, 3>(on, 3 * rope.axisStation(k)).setIdentity();
                    data.jacobian.template block<3, 3>(on, 3 * k) = -Eigen::Matrix3d::Identity();
                }
            }
    }
    for (int d = 0; d < rope.numDrivenNodes(); ++d) {
        data.x[nodeRows + d] = stations[Dim * numStations + d];
        if (withRates) data.jacobian(nodeRows + d, Dim * numStations + d) = 1.0;
    }
    // A wrapped node's arc length l = R alpha, alpha = sigma (phi_out - phi_in): its Jacobian row
    // and bias gather R sigma phi_out's from the span it starts (k) and -R sigma phi_in's from the
    // span it ends (k - 1).
    auto arcRow = [&](int k) { return rope.nodeCoordinateOffset(k) + Model::wrappedArcLengthOffset(); };
    auto arcScale = [&](int k) { return rope.arc(k).radius() * rope.arc(k).wrapSense(); };  // mutation-site: arc-length
    TangencyJacobian Jt;
    TangencyRates rates;
    for (int j = 0; j < N; ++j) {
        const TangencyEnd a = end(j), b = end(j + 1);
        try {
            const SpanTangency t = computeSpanTangency(a, b, warm ? &data.tangencies[j] : nullptr);
            data.tangencies[j] = t;
            if (withRates) {
                // (The axis columns only where a groove's axis turns.)
                computeTangencyJacobian(a, b, t, Jt, rope.axisStation(j) >= 0 || rope.axisStation(j + 1) >= 0);
                EndMotion ma, mb;
                ma.velocity = lift<Dim>(Vec(stationRates.template segment<Dim>(Dim * j)));
                mb.velocity = lift<Dim>(Vec(stationRates.template segment<Dim>(Dim * (j + 1))));
                ma.axisRate = axisRate(j);
                mb.axisRate = axisRate(j + 1);
                // A groove's centre c + x(Y) n moves at cdot + x' Ydot n + x ndot, and accelerates
                // by 2 x' Ydot ndot + x'' Ydot^2 n with the stations' and Y's second derivatives 0
                // (their shares are J's columns); a placement that does not follow Y moves with n only.
                for (auto [node, motion] : {std::pair<int, EndMotion*>{j, &ma}, std::pair<int, EndMotion*>{j + 1, &mb}}) {
                    if (isAtCentre(rope.groovePlacement(node))) continue;
                    const GrooveLay g = lay(node);
                    if (!follows(node)) {
                        motion->velocity += g.x * motion->axisRate;
                        continue;
                    }
                    const double ydot = stationRates[drivenColumn(node)];
                    motion->velocity += g.dx * ydot * axis(node) + g.x * motion->axisRate;
                    motion->acceleration = 2 * g.dx * ydot * motion->axisRate + g.ddx * ydot * ydot * axis(node);
                }
                computeTangencyRates(a, b, t, ma, mb, rates);
            }
        } catch (const std::domain_error& e) {
            std::ostringstream msg;
            msg << "WrapStationMap: span " << j << " (nodes " << j << " and " << j + 1 << "): " << e.what();
            throw std::domain_error(msg.str());
        }
        const SpanTangency& t = data.tangencies[j];
        data.startFleetAngles[j] = t.startFleetAngle;
        data.endFleetAngles[j] = t.endFleetAngle;
        // Jt rows [T1 (3), T2 (3), phi1, phi2], columns [p1 (3), n1 (3), p2 (3), n2 (3)]: the first
        // Dim coordinates of the points and the stations of nodes j (columns 0..) and j + 1 (6..).
        // A turning axis n = a - c: its columns (3.. and 9..) go to the axis station (+) and the
        // centre (-).
        // A groove's centre c + x(Y) n (n = a - c where the axis turns) adds x'(Y) n to Y's
        // column where its placement follows Y, and moves x of the centre's column to the axis
        // station's.
        auto rowsOver = [&](int row, double scale, int r) {
            for (const auto& [node, column] : {std::pair<int, int>{j, 0}, std::pair<int, int>{j + 1, 6}}) {
                const Eigen::Matrix<double, 1, Dim> Jc = scale * Jt.template block<1, Dim>(row, column);
                const GrooveLay g = lay(node);
                const double x = g.x;
                const int as = rope.axisStation(node);
                data.jacobian.template block<1, Dim>(r, Dim * node) += (as >= 0 ? 1 - x : 1.0) * Jc;
                if (as >= 0 && x != 0) data.jacobian.template block<1, Dim>(r, Dim * as) += x * Jc;
                if (follows(node) && g.dx != 0)
                    data.jacobian(r, drivenColumn(node)) +=
                        g.dx * scale * Jt.template block<1, 3>(row, column).dot(axis(node));
            }
            for (const auto& [node, column] : {std::pair<int, int>{j, 3}, std::pair<int, int>{j + 1, 9}}) {
                const int as = rope.axisStation(node);
                if (as < 0) continue;
                data.jacobian.template block<1, Dim>(r, Dim * as) += scale * Jt.template block<1, Dim>(row, column);
                data.jacobian.template block<1, Dim>(r, Dim * node) -= scale * Jt.template block<1, Dim>(row, column);
            }
        };
        // A wrapped end (a drum, Driven) has one tangent point, T_in = T_out, and no arc (l = 0):
        // the rope beyond it is the drum's stored rope. Its material coordinate there is
        // Y_s + sigma R phi, phi the tangent point's angle.
        if (rope.isWrapped(j)) {
            const bool drum = j == 0;
            for (int offset : {Model::wrappedDepartureOffset(), Model::wrappedArrivalOffset()}) {
                if (!drum && offset == Model::wrappedArrivalOffset()) continue;
                const int o = rope.nodeCoordinateOffset(j) + offset;
                data.x.template segment<Dim>(o) = t.start.template head<Dim>();
                if (withRates) {
                    for (int d = 0; d < Dim; ++d) {
                        rowsOver(d, 1.0, o + d);
                        data.bias[o + d] = rates.startAcceleration[d];
                    }
                }
            }
            if (withRates) {
                const int row = drum ? nodeRows + rope.drivenIndex(j) : arcRow(j);  // s_0 (below), or l
                rowsOver(6, arcScale(j), row);  // mutation-site: wrap-jacobian
                data.bias[row] += arcScale(j) * rates.startAngleAcceleration;
            }
        }
        if (rope.isWrapped(j + 1)) {
            const bool drum = j + 1 == N;
            for (int offset : {Model::wrappedArrivalOffset(), Model::wrappedDepartureOffset()}) {
                if (!drum && offset == Model::wrappedDepartureOffset()) continue;
                const int o = rope.nodeCoordinateOffset(j + 1) + offset;
                data.x.template segment<Dim>(o) = t.end.template head<Dim>();
                if (withRates) {
                    for (int d = 0; d < Dim; ++d) {
                        rowsOver(3 + d, 1.0, o + d);
                        data.bias[o + d] = rates.endAcceleration[d];
                    }
                }
            }
            if (withRates) {
                if (!drum) {
                    rowsOver(7, -arcScale(j + 1), arcRow(j + 1));  // mutation-site: wrap-jacobian
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
        if (j == 0 && rope.isWrapped(0)) return Eigen::Vector3d(data.tangencies[0].start);
        if (j == N && rope.isWrapped(N)) return Eigen::Vector3d(data.tangencies[N - 1].end);
        return lift<Dim>(station(j));
    };
    for (int k = 1; k < N && !previous; ++k) {
        if (!rope.isWrapped(k)) continue;
        const Eigen::Vector3d c = lift<Dim>(station(k));
        const Eigen::Vector3d in = c - pathPoint(k - 1), out = pathPoint(k + 1) - c;
        const double turn = axis(k).dot(in.cross(out));
        const int sigma = rope.arc(k).wrapSense();
        if (sigma * turn < -1e-9 * in.norm() * out.norm()) {
            std::ostringstream msg;
            msg << "WrapStationMap: node " << k << ": the rope's path turns " << (turn > 0 ? "counter-clockwise" : "clockwise")
                << " about the groove's axis there (from node " << k - 1 << " past the groove's centre to node " << k + 1
                << ") but its wrap sense is " << (sigma > 0 ? "+1" : "-1");
            throw std::domain_error(msg.str());
        }
    }
    // Arc lengths l = R alpha, alpha = sigma (phi_out - phi_in) (continuous with the previous alpha).
    for (int k = 1; k < N; ++k) {
        if (!rope.isWrapped(k)) continue;
        const GrooveArc<Dim>& arc = rope.arc(k);
        const GrooveCircle g = groove(k);
        const double alpha = previous ? wrapAngle(g, data.tangencies[k - 1].endRadial, data.tangencies[k].startRadial,
                                                  data.wrapAngles[k])
                                      : wrapAngle(g, data.tangencies[k - 1].endRadial, data.tangencies[k].startRadial);
        data.wrapAngles[k] = alpha;
        data.x[arcRow(k)] = arc.radius() * alpha;  // mutation-site: arc-length
    }
    // A wrapped Driven node grips the rope on its groove: the material coordinate at the arriving
    // tangent point is s_in = Y_s + sigma R phi_in, phi_in the tangent point's angle about the
    // centre, counter-clockwise about the groove's axis n from "up" (against gravity, projected
    // onto the groove's plane; +y without gravity) and
    // continuous with the previous evaluation's, so the departing span starts at
    // Y_s + sigma R phi_out = s_in + l (the rope does not slide on the groove). Its Jacobian row and
    // bias were gathered with the spans' (phi_in's row of the span arriving there).
    for (int k = 0; k <= N; ++k) {
        if (rope.drivenIndex(k) < 0 || !rope.isWrapped(k)) continue;
        // (A drum at the rope's start: the tangent point where span 0 leaves it.)
        const Eigen::Vector3d& radial = k > 0 ? data.tangencies[k - 1].endRadial : data.tangencies[0].startRadial;
        const Eigen::Vector3d n = axis(k);
        Eigen::Vector3d up = upDirection();
        up -= n * n.dot(up);
        if (up.norm() < 1e-9) {
            std::ostringstream msg;
            msg << "WrapStationMap: node " << k << ": the groove's axis is along gravity: a gripping groove needs an "
                << "\"up\" in its plane to measure the rope's grip from";
            throw std::domain_error(msg.str());
        }
        up.normalize();
        const double measured = std::atan2(n.dot(up.cross(radial)), up.dot(radial));
        double phi = measured;
        if (previous) phi = data.arrivalAngles[k] + std::remainder(measured - data.arrivalAngles[k], 2 * M_PI);
        data.arrivalAngles[k] = phi;
        const int row = nodeRows + rope.drivenIndex(k);
        data.x[row] += arcScale(k) * phi;
        // A turning axis turns "up"'s projection u too: phi, measured from u, changes at
        // phidot = (n x e) . edot - (n x u) . udot, the tangency's rate (gathered above) plus
        // a (n x g_up) . ndot / (1 - a^2), a = n . g_up (g_up = -g / |g|); its time derivative adds
        // adot (n x g_up) . ndot (1 + a^2) / (1 - a^2)^2 to the bias.
        if (withRates && rope.axisStation(k) >= 0) {
            const Eigen::Vector3d gUp = upDirection(), ndot = axisRate(k);
            const double a = n.dot(gUp), q = 1 - a * a, adot = ndot.dot(gUp);
            const Eigen::Vector3d nxu = n.cross(gUp);
            const Eigen::Matrix<double, 1, Dim> kappa = (arcScale(k) * a / q * nxu).template head<Dim>().transpose();
            data.jacobian.template block<1, Dim>(row, Dim * rope.axisStation(k)) += kappa;
            data.jacobian.template block<1, Dim>(row, Dim * k) -= kappa;
            data.bias[row] += arcScale(k) * adot * nxu.dot(ndot) * (1 + a * a) / (q * q);
        }
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

template <int Dim>
void WrapStationMap<Dim>::stationNodeMass(const WrapStationMapData& map, const RopeData<Dim>& ropeData,
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

template <int Dim>
void WrapStationMap<Dim>::stationNodeForce(const WrapStationMapData& map, const RopeData<Dim>& ropeData,
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

template class WrapStationMap<2>;
template class WrapStationMap<3>;

}  // namespace SimbodyReeving
