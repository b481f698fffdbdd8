#pragma once
// Counts heap allocations: linking allocation_counter.cc into a binary
// replaces its global operator new and delete.

namespace hs {

/// Calls to any global operator new since the program started.
long AllocationCount();

}  // namespace hs
