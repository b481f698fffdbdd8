#pragma once
// The benchmarks' --simd_max flag: the best SIMD target the engine's
// kernels may dispatch to at run time (Google Highway), so that one machine
// times its targets against each other, and valgrind, which runs no
// AVX-512, can count instructions on a machine that has it.

#include <string>

namespace hs {

/// Takes `--simd_max=NAME` (a target this machine runs: AVX3, AVX2, SSE4,
/// ...) out of argv, leaving the other arguments in order, and keeps
/// Highway from dispatching to any better target. False with `error` set
/// (the names this machine runs) when NAME is none of them; true and
/// nothing changed when the flag is absent.
bool TakeSimdMaxFlag(int& argc, char** argv, std::string& error);

}  // namespace hs
