#pragma once
// The one lock order of a scene's runtime, checked at run time.
//
// A thread that holds a lock of some level takes only locks of a higher
// level. The levels follow the calls between the runner's parts:
//   SceneRunner::scene_mu_  (10) the scene; held while the stepping thread
//                                takes the step's poses from the registry
//                                and while Replace re-maps its tools
//   StreamRegistry::mu_     (20) streams, poses, who holds which tool
//   FrameFanOut's queue and its sink-call gate (30), never one inside the
//                                other
//   SceneRunner::wake_mu_   (40) what wakes the stepping thread
// Locks of no level (kLeaf) are taken last and call nothing while held: a
// FrameOutbox's, the recorder's queue.
//
// No lock of these is held while a stream (FrameSink) is called: the frames
// thread calls sinks between FrameFanOut's gate calls, and a sink never
// calls back into the runner (SceneRunner checks, FrameFanOut::InSinkCall).

namespace hs {

enum class LockLevel : int {
  kLeaf = 0,
  kScene = 10,
  kStreams = 20,
  kFrames = 30,
  kWake = 40,
};

/// Records that the calling thread takes a lock of `level`; aborts (with
/// both levels) when it already holds one of the same or a higher level.
/// kLeaf is not recorded.
void LockOrderAcquire(LockLevel level);
/// Records that the calling thread let go of a lock of `level`.
void LockOrderRelease(LockLevel level);

}  // namespace hs
