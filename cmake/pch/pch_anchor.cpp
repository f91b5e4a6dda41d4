// The one source of a shared precompiled-header target (cmake/PrecompiledHeaders.cmake): the target
// exists to compile its precompiled header once for the executables that reuse it.
namespace simbodyreeving_pch {
int anchor() { return 0; }
}  // namespace simbodyreeving_pch
