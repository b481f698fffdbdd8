#include "tests/bench/step_length_knob.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/bench/accuracy_results.h"
#include "tests/bench/accuracy_shapes.h"
#include "tests/common/contact/brute_force_depth.h"

namespace hs::accuracy {
namespace {

// How each step of a moving object is checked.
enum class Check { kDiscrete, kSubSteps, kContinuous };

std::string StepLabel(Check check, double step_m) {
  const char* names[] = {"discrete", "sub-steps", "continuous"};
  char label[48];
  std::snprintf(label, sizeof label, "%s %.1f mm", names[static_cast<int>(check)], step_m * 1e3);
  return label;
}

double MicrosecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
      .count();
}

// Approach: the 1,280-face sphere of the resolution sweep moves along each
// of Configs' 16 directions D toward the slab, `step_m` per step, from
// 20 mm (plus a phase of the step grid) before its smooth original would
// touch. h is the travel past that first touch: the smooth sphere's depth
// along D at h > 0 is h itself (analytic), so a check reporting at h has
// let the tool sink h deep first (the overshoot).
constexpr double kApproach = 0.02;
constexpr int kPhases = 4;
// Sub-steps of at most 1 mm bound the overshoot; the paper's rule (shorter
// than the smallest box edge, 4 cm here) would make one sub-step at every
// step length swept, i.e. the discrete check.
constexpr double kSubStepTravel = 0.001;

struct Approach {
  const Body* tool;
  const Body* slab;
  Isometry3d X_touch;  // the smooth sphere touching z = 0
  Vector3d D;
  Isometry3d At(double h) const {
    Isometry3d X = X_touch;
    X.translation() += h * D;
    return X;
  }
};

// What one step check reported.
struct Report {
  bool colliding = false;
  double h = 0;            // travel of the pose the contact is reported at
  double first_touch = 0;  // travel at which it says the tool first touched
  double depth_m = 0;
};

Report CheckStep(const Approach& a, Check check, double h_from, double step_m) {
  PosedObject tool = a.tool->posed();
  const int n =
      check == Check::kSubSteps ? 1 + static_cast<int>(std::floor(step_m / kSubStepTravel)) : 1;
  for (int k = 1; k <= n; ++k) {
    const double h = h_from + step_m * k / n;
    tool.X_WO = a.At(h);
    const ContactSet set =
        *ComputeContact(tool, a.slab->posed(),
                        {.direction_W = check == Check::kContinuous ? step_m * a.D : a.D,
                         .continuous = check == Check::kContinuous});
    if (!set.colliding) continue;
    const double first_touch =
        set.time_of_impact ? h_from + *set.time_of_impact * step_m : h - set.depth_m;
    return {true, h, first_touch, set.depth_m};
  }
  return {};
}

// Runs approach `a` from phase `phase` of the step grid until a check
// reports contact (or the tool is 5 cm past the surface: a miss); times
// each step check into `us`, the reporting one also into `contact_us`.
Report RunApproach(const Approach& a, Check check, double step_m, double phase,
                   std::vector<double>* us, std::vector<double>* contact_us) {
  for (double h = -kApproach - phase * step_m; h < 0.05; h += step_m) {
    const auto start = std::chrono::steady_clock::now();
    const Report report = CheckStep(a, check, h, step_m);
    const double t = MicrosecondsSince(start);
    if (us) us->push_back(t);
    if (report.colliding) {
      if (contact_us) contact_us->push_back(t);
      return report;
    }
  }
  return {};
}

void BM_Approach(benchmark::State& state, Check check, double step_m) {
  const Shape shape = Sphere(3);
  const auto tool = testing_bodies::MakeBody(shape.object);
  const auto slab = Slab(BvType::kObbRss);
  std::vector<Approach> approaches;
  for (const Config& c : Configs(shape)) {
    Isometry3d X_touch = c.X_WO;
    X_touch.translation() -= c.depth * c.D;
    approaches.push_back({tool.get(), slab.get(), X_touch, c.D});
  }
  Point point{"step length", StepLabel(check, step_m)};
  point.depth_error_m = point.brute_error_m = point.overshoot_m = point.first_touch_error_m = 0;
  int missed = 0;
  for (const Approach& a : approaches) {
    for (int p = 0; p < kPhases; ++p) {
      const Report r = RunApproach(a, check, step_m, (p + 0.5) / kPhases, nullptr, nullptr);
      if (!r.colliding) {
        ++missed;
        continue;
      }
      const PosedObject m{&tool->object, &tool->model, a.At(r.h)};
      const double brute = static_cast<double>(
          reference::ComputeBruteForceDepth(m, slab->posed(), a.D, 1e-9).depth_m);
      point.depth_error_m = std::max(point.depth_error_m, std::abs(r.depth_m - std::max(r.h, 0.0)));
      point.brute_error_m = std::max(point.brute_error_m, std::abs(r.depth_m - brute));
      point.overshoot_m = std::max(point.overshoot_m, r.h);
      point.first_touch_error_m = std::max(point.first_touch_error_m, std::abs(r.first_touch));
    }
  }
  if (missed > 0) std::cerr << point.label << ": " << missed << " approaches never reported\n";
  std::vector<double> us, contact_us;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++;
    RunApproach(approaches[k % approaches.size()], check, step_m,
                (k / approaches.size() % kPhases + 0.5) / kPhases, &us, &contact_us);
  }
  SetPercentiles(contact_us, point);
  point.contact_step_us = point.median_us;
  SetPercentiles(us, point);
  state.counters["p99_us"] = point.p99_us;
  state.counters["contact_us"] = point.contact_step_us;
  state.counters["overshoot_m"] = point.overshoot_m;
  Record(point);
}

// Tunnelling: a 1 cm sphere passing a 1 mm plate in steps of `step_m`, each
// pass at a different phase of the step grid; a pass is missed when no
// check along it reports a collision. Sub-steps here follow the paper's
// rule (shorter than the smallest box edge of the two, 1 mm).
void BM_Tunnelling(benchmark::State& state, Check check, double step_m) {
  const auto ball = testing_bodies::MakeBody(MakeIcosphere(0.005, 3));
  auto plate = testing_bodies::MakeBody(MakeBox(Vector3d(0.2, 0.2, 0.001)));
  const double edge = std::min(ball->object.smallest_box_edge(), plate->object.smallest_box_edge());
  const int sub_steps = check == Check::kSubSteps ? static_cast<int>(std::ceil(step_m / edge)) : 1;
  const Vector3d step(0, 0, -step_m);
  auto collides = [&](const Isometry3d& X_end) {
    ball->X_WO = X_end;
    if (check == Check::kContinuous)
      return *AreColliding(ball->posed(), plate->posed(), 1e-9, step);
    for (int k = sub_steps - 1; k >= 0; --k) {
      ball->X_WO = X_end;
      ball->X_WO.translation() -= step * k / sub_steps;
      if (*AreColliding(ball->posed(), plate->posed(), 1e-9)) return true;
    }
    return false;
  };
  constexpr int kPasses = 50;
  int missed = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    Isometry3d X = Isometry3d::Identity();
    X.translation().z() = 0.02 + step_m * pass / kPasses;
    bool hit = false;
    while (X.translation().z() > -0.02 && !hit) {
      X.translation() += step;
      hit = collides(X);
    }
    missed += !hit;
  }
  std::vector<double> us;
  Isometry3d X = Isometry3d::Identity();
  size_t i = 0;
  for (auto _ : state) {
    // Steps across the plate and back, timed one by one.
    X.translation().z() = 0.02 - std::fmod(static_cast<double>(i++) * step_m, 0.04);
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(collides(X));
    us.push_back(MicrosecondsSince(start));
  }
  Point point{"tunnelling", StepLabel(check, step_m)};
  SetPercentiles(us, point);
  point.missed = static_cast<double>(missed) / kPasses;
  state.counters["missed"] = point.missed;
  state.counters["p99_us"] = point.p99_us;
  Record(point);
}

}  // namespace

void RegisterStepLengthBenchmarks() {
  constexpr Check kChecks[] = {Check::kDiscrete, Check::kSubSteps, Check::kContinuous};
  for (double step_m : {0.0005, 0.002, 0.005, 0.012, 0.03}) {
    for (Check check : kChecks) {
      benchmark::RegisterBenchmark(("Approach/" + StepLabel(check, step_m)).c_str(),
                                   [=](benchmark::State& s) { BM_Approach(s, check, step_m); })
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (double step_m : {0.0005, 0.002, 0.005, 0.012, 0.03}) {
    for (Check check : kChecks) {
      benchmark::RegisterBenchmark(("Tunnelling/" + StepLabel(check, step_m)).c_str(),
                                   [=](benchmark::State& s) { BM_Tunnelling(s, check, step_m); })
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

}  // namespace hs::accuracy
