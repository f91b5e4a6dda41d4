// The driven angles' parent turns (DrivenAngle.h): what turns a wrapped gripping groove's pin
// angle into the sheave's own.

#include "DrivenAngle.h"

#include <cmath>

namespace SimbodyReeving {
namespace detail {

double ParentTurnAngle::parentTurn(const DrivenAngleSite& site) const {
    const SimTK::MobilizedBody& parent = site.pin.getParentMobilizedBody();
    if (parent.isGround()) return 0.0;
    // The parent's rotation R_GP about the pin axis a (a planar rope: R_GP turns about a alone):
    // the angle from e to R_GP e, e perpendicular to a.
    const SimTK::UnitVec3 a(axis);
    const SimTK::UnitVec3 e = a.perp();
    const SimTK::Vec3 turned = parent.getBodyRotation(site.state) * e;
    return std::atan2(SimTK::dot(a, SimTK::cross(SimTK::Vec3(e), turned)), SimTK::dot(SimTK::Vec3(e), turned));
}

double TurningAxisAngle::parentTurn(const DrivenAngleSite& site) const {
    const SimTK::MobilizedBody& parent = site.pin.getParentMobilizedBody();
    if (parent.isGround()) return 0.0;
    // The angle of a parent direction about the pin axis from "up" projected onto the groove's
    // plane, now less with the parent at Ground's orientation.
    const SimTK::Vec3 up = site.gripUp;
    auto angle = [&up](const SimTK::Vec3& n, const SimTK::Vec3& direction) {
        const SimTK::Vec3 u = (up - n * SimTK::dot(n, up)).normalize();
        return std::atan2(SimTK::dot(n, SimTK::cross(u, direction)), SimTK::dot(u, direction));
    };
    const SimTK::Rotation& R_GP = parent.getBodyRotation(site.state);
    return std::remainder(angle(R_GP * parentAxis, R_GP * parentPerp) - angle(parentAxis, parentPerp), 2 * SimTK::Pi);
}

}  // namespace detail
}  // namespace SimbodyReeving
