#pragma once
/// @file
/// A rope's external coordinates as functions of its node stations (pure C++/Eigen): the tangent
/// points and arc lengths of its wrapped nodes from the anchor points and groove centres that
/// bodies carry, with their Jacobian and bias accelerations, and the rope's effective mass and
/// force carried over to the stations. Planar ropes (RopeModel<2>) and spatial ones (RopeModel<3>,
/// the grooves' axes NodeWrap::axis).

#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapGeometry.h"

#include <Eigen/Core>

#include <vector>

namespace SimbodyReeving {

/// Results of a WrapStationMap evaluation.
struct WrapStationMapData {
    Eigen::VectorXd stations;  ///< Y, the stations this evaluation is at [m]
    /// Input, per Driven index (empty: all 0): the creep c of a node that grips the rope
    /// (RopeModel::setGrip, RopeData::gripCreep), whose driven station Y includes it. A groove
    /// placement that follows Y (WalkingGroove) follows the groove's own coordinate Y - c [m].
    Eigen::VectorXd gripCreep;
    Eigen::VectorXd x;     ///< the rope's external coordinates (RopeModel layout) [m]
    Eigen::VectorXd xdot;  ///< their rates J Ydot [m/s]
    /// b = xddot at Yddot = 0 (the tangency's second derivatives at these rates) [m/s^2].
    Eigen::VectorXd bias;
    Eigen::MatrixXd jacobian;  ///< J = dx/dY (numExternalCoordinates x numStationCoordinates)
    /// Per row of J, the first of its non-zero columns [start, start + width): a row depends on the
    /// stations of at most three neighbouring nodes, or on one driven s (the products below skip the rest).
    std::vector<int> jacobianRowStart;
    std::vector<int> jacobianRowWidth;  ///< per row of J, the number of its non-zero columns
    std::vector<SpanTangency> tangencies;  ///< per span: its tangent points, direction, length
    /// Per node: the wrap angle alpha [rad] of a wrapped node (0 at point nodes). Also the
    /// previous values the next evaluation keeps alpha continuous with (wrapAngle).
    Eigen::VectorXd wrapAngles;
    /// Per node: phi_in [rad] at a wrapped Driven node, the arriving tangent point's angle about
    /// the groove's centre, counter-clockwise about the groove's axis from "up" (against the
    /// rope's gravity, projected onto the groove's plane; +y without gravity), continuous with the
    /// previous evaluation's (0 at other nodes).
    Eigen::VectorXd arrivalAngles;
    /// Per span: the fleet angle gamma [rad] at its start (SpanTangency; 0 at a point end and in a
    /// planar rope), the angle between the span and the groove's plane there.
    Eigen::VectorXd startFleetAngles;
    Eigen::VectorXd endFleetAngles;  ///< per span: the fleet angle gamma [rad] at its end (as startFleetAngles)
};

/// out = J X, over J's row bands (map.jacobianRowStart, jacobianRowWidth).
void multiplyByStationJacobian(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                               Eigen::MatrixXd& out);
/// out = J x for one column x.
void multiplyByStationJacobian(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                               Eigen::VectorXd& out);
/// out = J^T X, over J's row bands.
void multiplyByStationJacobianTransposed(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                         Eigen::MatrixXd& out);
/// out = J^T x for one column x.
void multiplyByStationJacobianTransposed(const WrapStationMapData& map, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                         Eigen::VectorXd& out);
/// out = A J, over J's row bands.
void multiplyStationJacobianFromLeft(const Eigen::Ref<const Eigen::MatrixXd>& A, const WrapStationMapData& map,
                                     Eigen::MatrixXd& out);

/// A rope's external coordinates as functions of the stations its bodies carry.
///
/// The rope's (RopeModel<Dim>) external coordinates x follow from its stations
///     Y = [p_0, ..., p_N, a_1, ..., a_m (Dim each), s at the Driven nodes],
/// p_k the position of an end or point node, and the groove centre c_k of a wrapped node
/// (NodeWrap); a_i the axis station of the i-th node whose groove axis turns with its body
/// (NodeWrap::turningAxis, 3D), its axis n_k = a_i - c_k: what the bodies carry. Each span's ends follow from its two nodes by the wrap
/// geometry (computeSpanTangency: point-to-circle and circle-to-circle, open or crossed; the groove
/// axis the plane's normal +z in a planar rope, NodeWrap::axis in a spatial one, where a span may
/// leave a groove's plane at a fleet angle; the sense the node's NodeWrap::wrapSense), and each wrapped node's
/// arc length from its two tangent points, l = R alpha (wrapAngle, continuous from the previous
/// evaluation's alpha). So x = Phi(Y), xdot = J Ydot and xddot = J Yddot + b, with J and b from the
/// tangency's analytic first and second time derivatives (computeTangencyRates). A spatial
/// wrapped node's axis entries of x are its NodeWrap::axis, constant (their J rows and b are
/// zero), or, for a turning axis, n = a_i - c_k (rows +I at a_i, -I at c_k; the tangency's axis
/// columns carried over to those stations, its bias at the axis' rate ndot = adot_i - cdot_k).
///
/// At a wrapped Driven node (a sheave that grips the rope: it does not slide on the groove) the
/// station Y_s is the material coordinate at the groove's "up" point (against gravity, projected
/// onto the groove's plane in 3D), so the
/// rope's material coordinate where it arrives on the groove is s_k = Y_s + sigma R phi_in, phi_in
/// the arriving tangent point's angle from "up" (WrapStationMapData::arrivalAngles; where the
/// groove's axis turns, "up"'s projection turns with it: phi's rate gains a (n x g_up) . ndot /
/// (1 - a^2), a = n . g_up, in J and its derivative in b), and the
/// departing span starts at s_k + l = Y_s + sigma R phi_out. For a sheave turning by theta about
/// the plane normal, Y_s = s_ref - sigma R theta. A wrapped end node (a winch drum) has one tangent
/// point, that of the span it starts or ends (point-to-circle or circle-to-circle), and no arc:
/// T_in = T_out there, l = 0, and the rope's material coordinate at it is Y_s + sigma R phi (phi
/// that tangent point's angle from "up"). The sense check (the path turning at each wrapped
/// interior node the way its rope wraps the groove) counts a wrapped end at its tangent point.
///
/// A coupling that moves the stations then sees the rope through
///     S_Y = J^T S J,   h_Y = J^T (h - S b),
/// S, h the rope's RopeData::nodeMass and nodeForce at x, xdot (the supports' force on the rope is
/// f = S xddot - h, so on the stations J^T f = S_Y Yddot - h_Y): stationNodeMass and
/// stationNodeForce. Lagrange's equations in Y follow by the chain rule, so the rope's T + U stays
/// the invariant it is in x.
template <int Dim>
class WrapStationMap {
public:
    using Vec = Eigen::Matrix<double, Dim, 1>;  ///< a point or vector [m]
    /// @param rope the rope whose nodes are mapped (it must outlive the map); without wrapped nodes
    ///        the map is the identity.
    explicit WrapStationMap(const RopeModel<Dim>& rope) : rope_(&rope) {}

    const RopeModel<Dim>& rope() const { return *rope_; }  ///< the mapped rope
    /// Number of station coordinates: Dim RopeModel::numStations() + RopeModel::numDrivenNodes()
    /// (Dim (N + 1) + numDrivenNodes() without turning groove axes).
    int numStationCoordinates() const { return Dim * rope_->numStations() + rope_->numDrivenNodes(); }

    /// x, xdot, J and b at the stations Y and their rates Ydot. data.wrapAngles, when it holds a
    /// value per node, is the previous evaluation's (alpha stays continuous through full turns);
    /// otherwise alpha is taken in [0, 2 pi).
    /// @throws std::invalid_argument if Y or Ydot has the wrong size or is not finite.
    /// @throws std::domain_error when a tangent does not exist (a station on or inside a groove
    ///         circle, overlapping grooves on a crossed span), naming the span and its nodes; or,
    ///         without previous wrap angles (where alpha starts), when the path through a wrapped
    ///         node's neighbours and centre turns against its wrap sense (the sense given the wrong
    ///         way). With previous ones alpha is continued and may fall below 0 (the rope leaving
    ///         the groove: ReevingSubsystem ends a run there). In 3D also when a wrapped Driven
    ///         node's axis is along gravity (its grip has no "up" in the groove's plane).
    void evaluate(const Eigen::VectorXd& stations, const Eigen::VectorXd& stationRates, WrapStationMapData& data) const;
    /// x (and the tangencies and wrap angles) alone, at the stations Y: what a solve of the
    /// positions or a query needs. data.jacobian, data.bias and data.xdot are left empty.
    /// @throws as evaluate.
    void evaluatePositions(const Eigen::VectorXd& stations, WrapStationMapData& data) const;

    /// S_Y = J^T S J from the rope's formed nodeMass (RopeData::formNodeMass).
    /// @throws std::invalid_argument if ropeData holds no formed nodeMass of the map's size.
    void stationNodeMass(const WrapStationMapData& map, const RopeData<Dim>& ropeData, Eigen::MatrixXd& SY) const;
    /// h_Y = J^T (h - S b) (S b by RopeModel::multiplyByNodeMass, S need not be formed).
    void stationNodeForce(const WrapStationMapData& map, const RopeData<Dim>& ropeData, Eigen::VectorXd& hY) const;

private:
    Eigen::Vector3d upDirection() const;  // -g / |g|, +y without gravity
    void evaluateMap(const Eigen::VectorXd& stations, const Eigen::VectorXd* stationRates,
                     WrapStationMapData& data) const;
    const RopeModel<Dim>* rope_;
};

extern template class WrapStationMap<2>;
extern template class WrapStationMap<3>;

}  // namespace SimbodyReeving
