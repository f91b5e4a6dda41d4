#pragma once
/// @file
/// Internal to the element layer (not installed): the scratch of a RopeModel evaluation, held by
/// RopeData behind a pointer so it stays out of the public headers.

#include "SimbodyReeving/element/AxialCondensation.h"
#include "SimbodyReeving/element/BandedLU.h"
#include "SimbodyReeving/element/GrooveArc.h"
#include "SimbodyReeving/element/RopeModel.h"
#include "SimbodyReeving/element/WrapStationMap.h"
#include "StoredRope.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace SimbodyReeving::detail {

/// One structural entry of the constraint Jacobian C_z: dC_row / dz_col (col < nw + nd: independent or
/// dependent coordinates; the Fixed material coordinates carry no column).
struct JacobianEntry {
    int row = 0, col = 0;
    double value = 0;
};

template <int Dim>
struct RopeWorkspace {
    const RopeModel<Dim>* model = nullptr;  ///< the model of the last computeDynamics (lazy reduction)
    Eigen::VectorXd velocityForcesZ;  ///< Q_v of all spans scattered into z (for the recovery)
    Eigen::VectorXd zddot, inertialLoad, massTimesAcceleration;  ///< scratch of the recovery
    std::vector<SpanData<Dim>> spans;
    std::vector<GrooveArcData<Dim>> arcs;  ///< per wrapped node (RopeModel::arc)
    std::vector<StoredRopeTerms<Dim>> storedRope;  ///< per drum with stored rope (RopeModel::setStoredRope)
    /// External coordinates and rates packed from the NodeMatrix forms of the API.
    Eigen::VectorXd packedX, packedXdot;
    /// A planar rope with wrapped nodes evaluated from its stations (the NodeMatrix forms): the
    /// map's x, xdot, J and b, and whether nodeMass, nodeForce and the modal reduction have been
    /// carried over to the stations (RopeModel::dynamicsToStations).
    WrapStationMapData stationMap, stationPositionMap;
    bool stationMode = false;
    Eigen::MatrixXd stationScratch, stationProductX, stationProductSX, stationReducedMG;
    Eigen::VectorXd stationReducedQ;
    /// The reduction to the stations' own buffers (RopeModel::dynamicsToStations): S b (nx x 1),
    /// J^T S J and the modal coupling at the stations, swapped with data.nodeMass, data.nodeForce
    /// (with stationForce) and modalCoupling while stationMode holds, so that each keeps its shape
    /// between evaluations; xddot = J Yddot of recoverInertialStrain.
    Eigen::MatrixXd stationMassBias, stationNodeMass, stationModalCoupling;
    Eigen::VectorXd stationAccelerations;
    bool stationBuffersSwapped = false;  ///< data.nodeForce holds the station-level h_Y (stationForce the x-level buffer)
    bool stationMassSwapped = false;     ///< and data.nodeMass, modalCoupling their station-level values
    /// A query's stations and, when they are not those of stationMap or stationPositionMap, its
    /// own positions-only map.
    Eigen::VectorXd queryStations;
    WrapStationMapData queryMap;
    Eigen::VectorXd stationForce;
    std::vector<EndStrain<Dim>> firstEnd, secondEnd;
    std::vector<AxialCondensationData<Dim>> condensation;  ///< per span (ropes with condensed spans)
    std::vector<Eigen::VectorXd> spanQ, spanQdot;
    // Per gripping node (RopeModel::setGrip): the surface speed Ydot_s + sigma R phidot [m/s] and 1 / lambda.
    Eigen::VectorXd gripSurfaceSpeeds, gripInverseStretch;
    Eigen::VectorXd gripXdot;  // xdot with a gripping node's rate the groove's (its stored ring's law)
    Eigen::VectorXd w;                    ///< independent velocities [xdot (node blocks, sdot_driven); qdot_m]
    /// The velocity-level results (computeDynamics) belong to the positions of the span coordinates,
    /// the velocities w and these dependent coordinates [s; q_condensed; nu]; cleared by
    /// solveDependentCoordinates, which overwrites the workspace's position-level part.
    bool dynamicsCurrent = false;
    Eigen::VectorXd dynamicsDependents;
    Eigen::VectorXd dynamicsX;  ///< the external coordinates of the last computeDynamics (ropes with arcs)
    // ---- the chain solve (every evaluation)
    std::vector<JacobianEntry> jacobian;  ///< C_z, row by row, each (row, column) once
    std::vector<int> rowSlot;                ///< per column of z: its entry in rowPending, or -1
    std::vector<JacobianEntry> rowPending;   ///< the row being merged (RopeModel::evaluateConstraints)
    /// The recorded structure of `jacobian`: per term added, the entry it lands in (valid for the
    /// model structure patternId while patternValid).
    std::vector<int> putTarget;
    std::uint64_t patternId = 0;
    bool patternValid = false;
    /// Per entry of `jacobian` (recorded with it): its offset in the band of C_d (dependentLu,
    /// newtonLu; -1 on an independent column), and in the KKT band at (row, column) and at
    /// (column, row) (-1 on an external column).
    std::vector<std::ptrdiff_t> dependentOffset, kktOffset, kktTransposedOffset;
    /// Entries of C_z on the external coordinates x, by column (counting sort of `jacobian`).
    std::vector<int> externalColumnStart, externalColumnRow;
    std::vector<double> externalColumnValue;
    BandedLU dependentLu;  ///< C_d in chain order (RopeModel::dependentRowPos_ / dependentColPos_), computeDynamics
    BandedLU newtonLu;     ///< the same at the Newton iterates (kept apart from the dynamics' one)
    BandedLU kktLu;        ///< [M_yy C_y^T; C_y 0] in chain order (RopeModel::kktPos_ / kktRowPos_)
    Eigen::VectorXd chainSolution;  ///< right-hand sides / solutions of the KKT system, row-major
    Eigen::VectorXd supportBlock;   ///< M_xy Y + C_x^T Mu for them, row-major
    Eigen::VectorXd productBlock;   ///< right-hand sides / solutions of multiplyByNodeMass
    std::vector<char> liveProductRow;  ///< per external coordinate: its row of X is nonzero
    std::vector<double> productX, productSX;  ///< X and S X of multiplyByNodeMass, row-major
    int productColumns = -1;        ///< columns of the last multiplyByNodeMass (-1: none since computeDynamics)
    Eigen::MatrixXd modalProduct;   ///< S xddot of modalAccelerations without the formed columns
    bool nodeMassFormed = true;     ///< nodeMass and modalCoupling formed by the last computeDynamics
    std::vector<int> solvedColumns; ///< the external coordinates whose column of S is formed
    Eigen::VectorXd rowScratch, dependentScratch, dependentAccelerations;
    Eigen::VectorXd Qz, bias;
    Eigen::VectorXd cd;                   ///< dependent accelerations at wdot = 0: -C_d^-1 bias
    Eigen::VectorXd newtonResidual, newtonStep;         ///< dependent-coordinate Newton
    Eigen::VectorXd newtonStart;                        ///< the iterate a damped step starts from
    Eigen::MatrixXd modalCoupling;  ///< qddot_m = modalFree - modalCoupling xddot
    Eigen::VectorXd modalFree;
    // ---- the dense reduced equations (RopeData::reducedMass / reducedForce, computed on demand)
    bool reducedValid = false;
    Eigen::MatrixXd Mz, Mbar, Cd, Cw;     ///< rope mass; constraint Jacobian on dependents / independents
    Eigen::MatrixXd Gd;                   ///< rates of the dependent coordinates = Gd w
    Eigen::MatrixXd MwdGd, MddGd;         ///< products in G^T Mz G
    Eigen::VectorXd Qbar, Qd;
    Eigen::PartialPivLU<Eigen::MatrixXd> constraintLu;  ///< of the dense C_d
};

}  // namespace SimbodyReeving::detail
