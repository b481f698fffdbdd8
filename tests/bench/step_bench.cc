// Step time of the bundled demo scenes: every effect a stream gets by
// default on, beside what a haptic device needs (its force, with friction:
// the proxy alone, no collision list or contact sets), what a remote device
// needs (that and its local contact model) and what a viewer that shows
// collisions needs (collision), in the same run. Prints
// the median and p99 step time of each; the target is 1 kHz with margin,
// p99 under 500 us on scenes of 50,000 triangles (fine_organ). Also the
// heap allocations per step (a global operator new counter): none in
// steady state (docs/simulation.md). Every scene also steps at 10 kHz
// (step_s 0.0001) with a haptic device's needs, the path's poses
// interpolated ten to a 1 kHz sample; the target there is p99 at or under
// 100 us.
//
// Step times move with the machine's speed and load as much as with the
// code, so the run first times a yardstick, FCL's exhaustive contact query
// on Table 1 #4 (contact_bench's Table1/case4/fcl_contacts), and each step
// figure is also printed over its median (`p99_per_fcl4` and the like):
// ratios from different machines and runs compare, where microseconds do
// not (scripts/bench.sh --check compares them with docs/benchmarks/).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "client/pose_args.h"
#include "common/api/scene_file.h"
#include "tests/bench/fcl_query.h"
#include "tests/bench/simd_max_flag.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/contact/table1_cases.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

struct DemoScene {
  const char* name;
  const char* scene;
  const char* path;
};

constexpr DemoScene kScenes[] = {
    {"probe_on_torus", "probe_on_torus.textproto", "press_and_slide.csv"},
    {"peg_in_hole", "peg_in_hole.textproto", "peg_in_hole.csv"},
    {"linked_rings", "linked_rings.textproto", "linked_rings.csv"},
    {"fine_organ", "fine_organ.textproto", "fine_organ.csv"},  // 50,000 triangles
};

// What a haptic device needs: its force, with friction.
const EffectSet kHapticDevice{Effect::kForce, Effect::kFriction};
// What a remote device needs: that and its local contact model.
const EffectSet kRemoteDevice{Effect::kForce, Effect::kFriction, Effect::kLocalModel};

std::vector<Isometry3d> ReadPath(const std::string& file) {
  std::vector<Isometry3d> poses;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    poses.push_back(*cli::ParsePose(line));
  }
  return poses;
}

// The yardstick: Table 1 #4 (index 3), where FCL's query takes about as
// long as the slowest steps.
constexpr int kYardstickCase = 3;

// Every timed call of the yardstick in this process, microseconds.
std::vector<double>& YardstickCallsUs() {
  static std::vector<double> calls;
  return calls;
}

double TimedYardstickCallUs(const FclQuery& query) {
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(query.Run().numContacts());
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
      .count();
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The yardstick's median call. A run whose filter left the yardstick
// benchmark out times it here, once, so that every run has its ratios.
double YardstickMedianUs() {
  std::vector<double>& calls = YardstickCallsUs();
  if (calls.empty()) {
    const FclQuery query(table1::GetCase(kYardstickCase), true);
    for (int k = 0; k < 50; ++k) calls.push_back(TimedYardstickCallUs(query));
  }
  return Median(calls);
}

// Wall time per call, as the steps are timed; registered first, so that
// the step benchmarks are divided by the machine's speed of the same run.
void BM_Yardstick(benchmark::State& state) {
  const FclQuery query(table1::GetCase(kYardstickCase), true);
  for (auto _ : state) YardstickCallsUs().push_back(TimedYardstickCallUs(query));
  state.counters["median_us"] = YardstickMedianUs();
}

// `path` with `per_sample` poses per sample, the ones between interpolated
// (translation linearly, rotation by slerp): the same motion at a higher
// rate.
std::vector<Isometry3d> Resampled(const std::vector<Isometry3d>& path, int per_sample) {
  if (per_sample == 1 || path.size() < 2) return path;
  std::vector<Isometry3d> out;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const Eigen::Quaterniond a(path[k].linear()), b(path[k + 1].linear());
    for (int j = 0; j < per_sample; ++j) {
      const double f = static_cast<double>(j) / per_sample;
      Isometry3d X = Isometry3d::Identity();
      X.linear() = a.slerp(f, b).toRotationMatrix();
      X.translation() = (1 - f) * path[k].translation() + f * path[k + 1].translation();
      out.push_back(X);
    }
  }
  out.push_back(path.back());
  return out;
}

// Steps `demo` along its path at `rate_hz` (1,000: the scene's own step),
// `per_step` of the path's 1 kHz samples a step (0.1: ten steps from one
// sample to the next). `surface_only`: the device reads its local model's
// surface alone, as the SDK's does (Scene::SetSurfaceOnly).
void BM_Step(benchmark::State& state, const DemoScene& demo, EffectSet needs, int threads,
             int rate_hz, double per_step, bool surface_only) {
  const std::string dir = hs::ScenesDir() + "/";
  absl::StatusOr<haptics::v1::SceneSpec> spec = ReadSceneFile(dir + demo.scene);
  if (!spec.ok()) {
    state.SkipWithError(std::string(spec.status().message()).c_str());
    return;
  }
  spec->set_step_s(1.0 / rate_hz);
  absl::StatusOr<LoadedScene> loaded = BuildScene(*spec, dir);
  if (!loaded.ok()) {
    state.SkipWithError(std::string(loaded.status().message()).c_str());
    return;
  }
  loaded->scene->SetNeeded(needs);
  (void)loaded->scene->SetSurfaceOnly(loaded->tools.front(), surface_only);
  if (absl::Status s = loaded->scene->SetThreads(threads); !s.ok()) {
    state.SkipWithError(std::string(s.message()).c_str());
    return;
  }
  const std::vector<Isometry3d> path = Resampled(
      ReadPath(dir + demo.path), static_cast<int>(std::lround(rate_hz / 1000.0 / per_step)));
  std::vector<double> step_us;
  step_us.reserve(1 << 20);
  size_t i = 0;
  // Allocations are counted after four walks there and back (warm-up: the
  // buffers a step reuses grow to what the path needs, on every thread that
  // steps a part of it).
  const size_t warm_up = 8 * path.size();
  long step_allocations = 0;
  long counted_steps = 0;
  for (auto _ : state) {
    // Walk the device path forth and back so that the motion stays smooth.
    const size_t k = i % (2 * path.size());
    const Isometry3d& X = path[k < path.size() ? k : 2 * path.size() - 1 - k];
    ++i;
    (void)loaded->scene->SetDevicePose(loaded->tools.front(), X);
    const long allocations_before = AllocationCount();
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(loaded->scene->Step());
    if (i > warm_up) {
      step_allocations += AllocationCount() - allocations_before;
      ++counted_steps;
    }
    step_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(step_us.begin(), step_us.end());
  const double yardstick_us = YardstickMedianUs();
  auto report = [&](const std::string& name, double us) {
    state.counters[name + "_us"] = us;
    state.counters[name + "_per_fcl4"] = us / yardstick_us;
  };
  report("p50", step_us[step_us.size() / 2]);
  report("p99", step_us[std::min(step_us.size() - 1, step_us.size() * 99 / 100)]);
  if (needs.Has(Effect::kLocalModel) && !step_us.empty()) {
    // Mean over every step the scene took, warm-up included.
    const StageStats& local_model = loaded->scene->stats()[static_cast<int>(Effect::kLocalModel)];
    report("local_model",
           1e-3 * static_cast<double>(local_model.total_ns) / static_cast<double>(step_us.size()));
  }
  state.counters["allocs_per_step"] =
      counted_steps > 0 ? static_cast<double>(step_allocations) / counted_steps : 0.0;
}

// One thread, and the server's default (haptic-server --threads-per-scene:
// one per core, at most 4).
void Register() {
  benchmark::RegisterBenchmark("Yardstick/fcl_contacts_case4", BM_Yardstick);
  const int server_threads =
      static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 4u));
  for (const int threads : {1, server_threads}) {
    const std::string suffix = "/threads:" + std::to_string(threads);
    for (const DemoScene& demo : kScenes) {
      const std::string name = std::string("Step/") + demo.name;
      benchmark::RegisterBenchmark((name + "/all_effects" + suffix).c_str(), BM_Step, demo,
                                   EffectSet::Default(), threads, 1000, 1.0, false);
      benchmark::RegisterBenchmark((name + "/force_only" + suffix).c_str(), BM_Step, demo,
                                   kHapticDevice, threads, 1000, 1.0, false);
      // The SDK's remote device, which reads the surface alone.
      benchmark::RegisterBenchmark((name + "/remote_device" + suffix).c_str(), BM_Step, demo,
                                   kRemoteDevice, threads, 1000, 1.0, true);
      // A hand's speed: the paths' 1 mm a step slowed to 0.1 mm (0.1 m/s).
      benchmark::RegisterBenchmark((name + "/remote_device_hand" + suffix).c_str(), BM_Step, demo,
                                   kRemoteDevice, threads, 1000, 0.1, true);
      // A device that reads the model's planes (one that does not say it
      // reads the surface alone): every model has both.
      benchmark::RegisterBenchmark((name + "/remote_device_planes" + suffix).c_str(), BM_Step, demo,
                                   kRemoteDevice, threads, 1000, 1.0, false);
      benchmark::RegisterBenchmark((name + "/collision_only" + suffix).c_str(), BM_Step, demo,
                                   EffectSet{Effect::kCollision}, threads, 1000, 1.0, false);
      benchmark::RegisterBenchmark((name + "/force_only_10khz" + suffix).c_str(), BM_Step, demo,
                                   kHapticDevice, threads, 10000, 1.0, false);
    }
    if (server_threads == 1) break;  // one run is both
  }
}

}  // namespace
}  // namespace hs

int main(int argc, char** argv) {
  if (!hs::TakeSimdMaxFlag(argc, argv, std::cerr)) return 2;
  hs::Register();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
