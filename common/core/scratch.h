#pragma once
// Buffers a computation keeps from one run to the next, so that a steady
// stream of queries allocates nothing once they are large enough, kept per
// piece of work rather than per thread. A scene's step runs its parts on
// whichever worker is free; buffers kept per thread would each grow only
// when their thread first meets a large contact, long after warm-up. A part
// that binds its own space (ScratchScope) finds the same buffers whatever
// thread runs it. Code without a bound space gets its thread's own.
//
// Written here: the buffers live deep in the contact queries, and passing
// them down every call would put them in every signature between the step
// and the leaf tests; no library keeps per-task storage of this kind.

#include <memory>
#include <vector>

namespace hs {

/// Buffers kept between runs of a piece of work: one object of each type
/// asked for, made the first time. Each use names its own type (a struct
/// local to its file), so two uses never share an object.
class ScratchSpace {
 public:
  ScratchSpace() = default;
  ScratchSpace(ScratchSpace&&) = default;
  ScratchSpace& operator=(ScratchSpace&&) = default;
  ScratchSpace(const ScratchSpace&) = delete;
  ScratchSpace& operator=(const ScratchSpace&) = delete;

  /// This space's T, default-constructed the first time it is asked for.
  /// References stay valid for the space's life.
  template <typename T>
  T& Get() {
    const void* key = &kKey<T>;
    for (const Entry& entry : entries_) {
      if (entry.key == key) return *static_cast<T*>(entry.object.get());
    }
    auto object = std::make_shared<T>();
    T& result = *object;
    entries_.push_back({key, std::move(object)});
    return result;
  }

 private:
  // One address per type: the key of its object.
  template <typename T>
  static constexpr char kKey = 0;

  struct Entry {
    const void* key;
    std::shared_ptr<void> object;  // a T; shared_ptr<void> deletes it as a T
  };
  std::vector<Entry> entries_;
};

namespace scratch_internal {
inline ScratchSpace*& Bound() {
  thread_local ScratchSpace* bound = nullptr;
  return bound;
}
}  // namespace scratch_internal

/// The space of the work this thread runs now: the innermost one a
/// ScratchScope bound, else the thread's own.
inline ScratchSpace& CurrentScratch() {
  if (ScratchSpace* bound = scratch_internal::Bound()) return *bound;
  thread_local ScratchSpace own;
  return own;
}

/// CurrentScratch().Get<T>().
template <typename T>
T& Scratch() {
  return CurrentScratch().Get<T>();
}

/// Makes `space` this thread's current space until the scope ends; scopes
/// nest.
class ScratchScope {
 public:
  explicit ScratchScope(ScratchSpace& space) : previous_(scratch_internal::Bound()) {
    scratch_internal::Bound() = &space;
  }
  ~ScratchScope() { scratch_internal::Bound() = previous_; }
  ScratchScope(const ScratchScope&) = delete;
  ScratchScope& operator=(const ScratchScope&) = delete;

 private:
  ScratchSpace* previous_;
};

}  // namespace hs
