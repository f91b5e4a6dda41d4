#pragma once
/// @file
/// Internal to the element layer (not installed): the scratch of a RopeModel evaluation, held by
/// RopeData behind a pointer so it stays out of the public headers.

#include "SimbodyReeving/element/RopeModel.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <vector>

namespace SimbodyReeving::detail {

template <int Dim>
struct RopeWorkspace {
    Eigen::VectorXd velocityForcesZ;  ///< Q_v of all spans scattered into z (for the recovery)
    Eigen::VectorXd zddot, inertialLoad;  ///< scratch of the recovery
    std::vector<SpanData<Dim>> spans;
    std::vector<EndStrain<Dim>> firstEnd, secondEnd;
    std::vector<AxialCondensationData<Dim>> condensation;  ///< per span (ropes with condensed spans)
    std::vector<Eigen::VectorXd> spanQ, spanQdot;
    Eigen::VectorXd w;                    ///< independent velocities [rdot; qdot_m]
    Eigen::MatrixXd Mz, Mbar, Cd, Cw;     ///< rope mass; constraint Jacobian on dependents / independents
    Eigen::MatrixXd Gd;                   ///< rates of the dependent coordinates = Gd w
    Eigen::MatrixXd MwdGd, MddGd;         ///< products in G^T Mz G
    Eigen::VectorXd Qz, Qbar, Qd, bias;
    Eigen::VectorXd cd;                   ///< dependent accelerations at wdot = 0
    Eigen::PartialPivLU<Eigen::MatrixXd> constraintLu;  ///< of C_d
    Eigen::VectorXd newtonResidual, newtonStep;         ///< dependent-coordinate Newton
    Eigen::VectorXd newtonStart;                        ///< the iterate a damped step starts from
    Eigen::MatrixXd newtonJacobian;
    Eigen::PartialPivLU<Eigen::MatrixXd> newtonLu;
    Eigen::LDLT<Eigen::MatrixXd> modalMass;
    Eigen::MatrixXd modalCoupling;  ///< Mbar_mm^-1 Mbar_mn
    Eigen::VectorXd modalFree;      ///< Mbar_mm^-1 Qbar_m
};

}  // namespace SimbodyReeving::detail
