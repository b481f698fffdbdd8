#pragma once
// Step length as a knob of the accuracy sweep: a tool approaching a surface
// at growing distances per step (what the contact query then reports, and
// how late), and a ball passing a thin plate (what discrete checks miss).

namespace hs::accuracy {

/// Registers the "Approach/..." and "Tunnelling/..." benchmarks; their
/// points go to accuracy_results.h's Record.
void RegisterStepLengthBenchmarks();

}  // namespace hs::accuracy
