#include "server/frame_outbox.h"

#include "common/core/check.h"

namespace hs {

FrameOutbox::FrameOutbox(size_t capacity) : capacity_(capacity), waiting_(capacity) {
  HS_CHECK(capacity >= 1);
}

void FrameOutbox::Limit(size_t capacity) {
  std::lock_guard lock(mu_);
  HS_CHECK(capacity >= 1 && capacity <= waiting_.capacity() && waiting_.empty());
  capacity_ = capacity;
}

bool FrameOutbox::Push(std::shared_ptr<const StepSnapshot> snapshot) {
  std::lock_guard lock(mu_);
  if (closed_) return false;
  bool dropped = false;
  if (waiting_.size() >= capacity_) {
    waiting_.pop_front();
    ++dropped_;
    dropped = true;
  }
  waiting_.push_back(std::move(snapshot));
  return dropped;
}

void FrameOutbox::Close(const absl::Status& status) {
  std::lock_guard lock(mu_);
  if (closed_) return;
  closed_ = true;
  status_ = status;
}

void FrameOutbox::Abort(const absl::Status& status) {
  std::lock_guard lock(mu_);
  waiting_.clear();
  if (closed_) return;
  closed_ = true;
  status_ = status;
}

FrameOutbox::Next FrameOutbox::TakeNext() {
  std::lock_guard lock(mu_);
  Next next;
  if (writing_ || finished_) return next;
  if (!waiting_.empty()) {
    next.kind = Next::kWrite;
    next.snapshot = std::move(waiting_.front());
    next.dropped = dropped_;
    waiting_.pop_front();
    writing_ = true;
  } else if (closed_) {
    next.kind = Next::kFinish;
    next.status = status_;
    finished_ = true;
  }
  return next;
}

void FrameOutbox::WriteDone() {
  std::lock_guard lock(mu_);
  writing_ = false;
}

bool FrameOutbox::closed() const {
  std::lock_guard lock(mu_);
  return closed_;
}

uint64_t FrameOutbox::dropped() const {
  std::lock_guard lock(mu_);
  return dropped_;
}

}  // namespace hs
