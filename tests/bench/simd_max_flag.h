#pragma once
// The benchmarks' --simd_max flag: the best SIMD target the engine's
// kernels may dispatch to at run time (Google Highway), so that one machine
// times its targets against each other, and valgrind, which runs no
// AVX-512, can count instructions on a machine that has it.

#include <ostream>

namespace hs {

/// Takes `--simd_max=NAME` (a target this machine runs: AVX3, AVX2, SSE4,
/// ...) out of argv, leaving the other arguments in order, and keeps
/// Highway from dispatching to any better target. False, with a line on
/// `err` naming the targets this machine runs, when NAME is none of them
/// (a bench's main then exits 2); true and nothing changed when the flag
/// is absent.
bool TakeSimdMaxFlag(int& argc, char** argv, std::ostream& err);

}  // namespace hs
