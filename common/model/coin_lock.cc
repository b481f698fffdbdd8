#include "common/model/coin_lock.h"

#include <Inventor/SoDB.h>

namespace hs {

void InitCoinOnce() {
  static std::once_flag once;
  std::call_once(once, [] { SoDB::init(); });
}

std::unique_lock<std::mutex> LockCoin() {
  InitCoinOnce();
  // Never destroyed: a Coin call may still run during static destruction.
  static std::mutex* const mutex = new std::mutex;
  return std::unique_lock<std::mutex>(*mutex);
}

}  // namespace hs
