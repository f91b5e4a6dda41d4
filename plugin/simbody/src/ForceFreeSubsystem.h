#pragma once
// Internal: the base of force subsystems that apply no force (MotionWorkMeter). The
// ReevingSubsystem's coupled solve must see every force applied before it, so it rejects force
// subsystems added after it, except these.

#include <Simbody.h>

namespace SimbodyReeving::detail {

class ForceFreeSubsystemGuts : public SimTK::ForceSubsystem::Guts {
public:
    using SimTK::ForceSubsystem::Guts::Guts;
};

}  // namespace SimbodyReeving::detail
