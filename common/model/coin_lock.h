#pragma once
// Coin3D keeps process-wide state (SoDB, the node and type dictionaries, the
// error handlers) and is not thread-safe. Everything in common/model that
// touches that state holds the lock returned here. Internal to common/model.

#include <mutex>

namespace hs {

/// Calls SoDB::init() once per process; safe from any thread.
void InitCoinOnce();

/// Initializes Coin if needed and locks the process-wide Coin mutex. Hold the
/// lock for as long as any Coin object (input, node, action) is alive.
std::unique_lock<std::mutex> LockCoin();

}  // namespace hs
