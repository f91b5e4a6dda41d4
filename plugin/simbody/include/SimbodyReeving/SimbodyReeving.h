#pragma once
/// @file
/// Everything a Simbody application needs to add ropes to a SimTK::MultibodySystem: the
/// ReevingSubsystem and its node kinds, the slack monitor, the drives' work meter, the
/// interpolating time stepper, integrators by name and the Visualizer helpers. The element layer
/// (SimbodyReeving/element/) comes with it; scene builders are in SimbodyReeving/scenes/.

#include "SimbodyReeving/simbody/Integrators.h"
#include "SimbodyReeving/simbody/InterpolatingTimeStepper.h"
#include "SimbodyReeving/simbody/MotionWorkMeter.h"
#include "SimbodyReeving/simbody/ReevingSubsystem.h"
#include "SimbodyReeving/simbody/SlackMonitor.h"
#include "SimbodyReeving/simbody/Visualization.h"
