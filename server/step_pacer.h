#pragma once
// When a scene steps, and what a late step cost: the scene runner's clock
// rules, as a pure class fed with clock readings (it reads no clock), so
// that tests drive it step by step with readings of their own.
//
// The rules:
// - Without devices, or while one of them is silent, a step starts each
//   period (the deadline).
// - Devices clock the steps: once every attached device has sent a pose
//   since the last step, the next step starts at once, but not sooner
//   than 3/4 of a period after the last (a device faster than the scene
//   speeds it up by 4/3 at most). Devices that came first set the phase:
//   the next deadline is a period and a quarter later, so that a pose a
//   little late joins its step instead of waiting a whole period.
// - A step that starts more than one period after its deadline skips the
//   steps it missed (counted) rather than running a burst.
// - Off the CPU: the misses of one late start are counted "off the CPU"
//   when the stepping thread had used less than a period of CPU time
//   since the step before began, and that step took less than a period
//   (wall time, so its workers' share counts as stepping): the thread lost
//   the time waiting, for a core, a lock or its wake-up, not stepping. All
//   the misses of one late start count alike. This is the one statement
//   of the rule; frames (missed_steps_off_cpu), metrics
//   (hs_missed_steps_off_cpu_total) and the load test report it.

#include <algorithm>
#include <cstdint>

namespace hs {

class StepPacer {
 public:
  /// Steps of `period_ns`; the runner started at `now_ns` (steady clock)
  /// with `cpu_ns` of thread CPU time used.
  StepPacer(int64_t period_ns, int64_t now_ns, int64_t cpu_ns);

  /// No step starts before this (3/4 of a period after the last start).
  int64_t earliest_ns() const { return last_start_ns_ + period_ns_ * 3 / 4; }
  /// A step starts at the latest then, devices or not.
  int64_t deadline_ns() const { return deadline_ns_; }
  /// When the next step starts: at earliest_ns() once every device has
  /// sent a pose since the last (`devices_fresh`), else at the deadline
  /// and not before earliest_ns(). The runner sleeps until then, once a
  /// step unless woken by the devices: each sleep costs a wake-up late by
  /// tens of microseconds on a virtual machine, and a first sleep to
  /// earliest_ns() would make every step of a 10 kHz scene start later
  /// than the one before, by that wake-up less a quarter period.
  int64_t start_ns(bool devices_fresh) const {
    return devices_fresh ? earliest_ns() : std::max(earliest_ns(), deadline_ns_);
  }

  /// What a step's start tells.
  struct Start {
    /// How late the step starts after its deadline; 0 when devices
    /// clocked it before.
    int64_t lag_ns = 0;
    /// Steps missed before this one (skipped, not run).
    int64_t missed = 0;
    /// Whether those were missed off the CPU (the rule above).
    bool off_cpu = false;
  };
  /// A step starts at `now_ns`, the thread having used `cpu_ns` of CPU
  /// time; `devices_clocked` when every device's pose came before the
  /// deadline.
  Start StepStarts(int64_t now_ns, int64_t cpu_ns, bool devices_clocked);
  /// The step that started last took `step_ns` of wall time.
  void StepEnded(int64_t step_ns) { last_step_ns_ = step_ns; }

 private:
  const int64_t period_ns_;
  int64_t last_start_ns_;
  int64_t cpu_at_last_start_ns_;
  int64_t last_step_ns_ = 0;
  int64_t deadline_ns_;
};

}  // namespace hs
