#include "SimbodyReeving/simbody/Integrators.h"

#include <stdexcept>

namespace SimbodyReeving {

const std::vector<std::string>& integratorNames() {
    static const std::vector<std::string> names{"rk-merson", "rk3", "rk-feldberg", "cpodes",
                                                "verlet", "semi-explicit-euler2", "explicit-euler"};
    return names;
}

std::unique_ptr<SimTK::Integrator> makeIntegrator(const std::string& name, const SimTK::System& system) {
    if (name == "rk-merson") return std::make_unique<SimTK::RungeKuttaMersonIntegrator>(system);
    if (name == "rk3") return std::make_unique<SimTK::RungeKutta3Integrator>(system);
    if (name == "rk-feldberg") return std::make_unique<SimTK::RungeKuttaFeldbergIntegrator>(system);
    if (name == "cpodes") return std::make_unique<SimTK::CPodesIntegrator>(system);
    if (name == "verlet") return std::make_unique<SimTK::VerletIntegrator>(system);
    if (name == "semi-explicit-euler2") return std::make_unique<SimTK::SemiExplicitEuler2Integrator>(system);
    if (name == "explicit-euler") return std::make_unique<SimTK::ExplicitEulerIntegrator>(system);
    std::string known;
    for (const auto& n : integratorNames()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown integrator '" + name + "' (known: " + known + ")");
}

}  // namespace SimbodyReeving
