// What accuracy costs in time (issue 7): the contact query over the knobs
// that trade one for the other (mesh resolution of a sphere, a torus and an
// imported non-convex model; method; bounding volume; tolerance; step
// length with and without sub-steps and continuous collision), each point
// timed (median and p99 per query) beside its error against a reference;
// and tunnelling through a thin plate. Writes a Markdown table and gnuplot
// data to the directory given by --out (scripts/accuracy.sh draws
// docs/accuracy/*.png from it).
//
// References (accuracy_shapes.h): the smooth sphere and torus give the
// depth along D in closed form, so a mesh's error there is what its flat
// facets cost; the imported model has no closed form, so it is measured
// against its finest level. Every mesh is also measured against the
// long-double brute force over all its triangle pairs (the same mesh, so
// that error is the method's own).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common/contact/contact_query.h"
#include "tests/bench/accuracy_results.h"
#include "tests/bench/accuracy_shapes.h"
#include "tests/bench/step_length_knob.h"
#include "tests/common/contact/brute_force_depth.h"

namespace hs::accuracy {
namespace {

struct Knobs {
  ContactMethod method = ContactMethod::kSweep3d;
  BvType bv = BvType::kObbRss;
  double relative_tolerance = 1e-9;
};

// Brute-force depths of a shape's poses, computed once per run: Google
// Benchmark calls a benchmark again with more iterations, and the brute
// force of a 200,000-face mesh takes seconds.
struct BruteForce {
  std::vector<double> depth_m;
  double median_ms = 0;
};

const BruteForce& BruteForceOf(const std::string& key, const Body& moving, const Body& slab,
                               const std::vector<Config>& configs, double relative_tolerance) {
  static std::map<std::string, BruteForce> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  BruteForce result;
  std::vector<double> ms;
  for (const Config& c : configs) {
    const PosedObject m{&moving.object, &moving.model, c.X_WO};
    const auto start = std::chrono::steady_clock::now();
    const reference::BruteForceDepth ref =
        reference::ComputeBruteForceDepth(m, slab.posed(), c.D, relative_tolerance);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    result.depth_m.push_back(static_cast<double>(ref.depth_m));
  }
  std::sort(ms.begin(), ms.end());
  result.median_ms = ms[ms.size() / 2];
  return cache.emplace(key, std::move(result)).first->second;
}

void BM_Accuracy(benchmark::State& state, const std::string& family, const std::string& label,
                 const std::function<Shape()>& make_shape, Knobs knobs) {
  const Shape shape = make_shape();
  const auto moving = testing_bodies::MakeBody(shape.object, Isometry3d::Identity(), knobs.bv);
  const auto slab = Slab(knobs.bv);
  const std::vector<Config> configs = Configs(shape);
  char key[96];
  std::snprintf(key, sizeof key, "%s %d tol %g", shape.name.c_str(), shape.object.num_faces(),
                knobs.relative_tolerance);
  const BruteForce& brute = BruteForceOf(key, *moving, *slab, configs, knobs.relative_tolerance);
  Point point{family, label};
  point.depth_error_m = point.normal_error_rad = point.brute_error_m = 0;
  point.brute_ms = brute.median_ms;
  auto query = [&](const Config& c) {
    moving->X_WO = c.X_WO;
    return *ComputeContact(moving->posed(), slab->posed(),
                           {.direction_W = c.D,
                            .method = knobs.method,
                            .relative_tolerance = knobs.relative_tolerance});
  };
  for (size_t i = 0; i < configs.size(); ++i) {
    const ContactSet set = query(configs[i]);
    point.depth_error_m = std::max(point.depth_error_m, std::abs(set.depth_m - configs[i].depth));
    point.brute_error_m = std::max(point.brute_error_m, std::abs(set.depth_m - brute.depth_m[i]));
    point.normal_error_rad =
        std::max(point.normal_error_rad, std::acos(std::clamp(set.normal_W.z(), -1.0, 1.0)));
  }
  std::vector<double> us;
  size_t i = 0;
  for (auto _ : state) {
    const Config& c = configs[i++ % configs.size()];
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(query(c));
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  SetPercentiles(us, point);
  state.counters["faces"] = moving->object.num_faces();
  state.counters["p50_us"] = point.median_us;
  state.counters["p99_us"] = point.p99_us;
  if (shape.is_reference) point.depth_error_m = -1;
  state.counters["depth_err_m"] = point.depth_error_m;
  state.counters["brute_err_m"] = point.brute_error_m;
  Record(point);
}

void Register() {
  auto add = [](const std::string& family, const std::string& label, std::function<Shape()> shape,
                Knobs knobs) {
    benchmark::RegisterBenchmark(
        ("Accuracy/" + family + "/" + label).c_str(),
        [=](benchmark::State& s) { BM_Accuracy(s, family, label, shape, knobs); })
        ->Unit(benchmark::kMicrosecond);
  };
  for (int s = 1; s <= 6; ++s) {
    add("sphere resolution", std::to_string(20 << (2 * s)) + " faces", [s] { return Sphere(s); },
        {});
  }
  for (int m : {16, 32, 64, 128, 256, 448}) {
    add("torus resolution", std::to_string(m * m) + " faces", [m] { return Torus(m); }, {});
  }
  for (int level = 0; level < kKidneyLevels; ++level) {
    const int faces = level == 0 ? 128 : 128 * 6 << (2 * (level - 1));
    add("imported kidney resolution", std::to_string(faces) + " faces",
        [level] { return Kidney(level); }, {});
  }
  for (auto [name, method] : {std::pair{"paper2d", ContactMethod::kPaper2d},
                              std::pair{"sweep3d", ContactMethod::kSweep3d}}) {
    add("method", std::string("sphere ") + name, [] { return Sphere(4); }, {.method = method});
    add("method", std::string("torus ") + name, [] { return Torus(64); }, {.method = method});
    add("method", std::string("kidney ") + name, [] { return Kidney(2); }, {.method = method});
    add("method", std::string("box ") + name, [] { return Box(); }, {.method = method});
  }
  for (BvType bv : {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios, BvType::kAabb}) {
    add("bv", std::string(BvTypeName(bv)), [] { return Torus(64); }, {.bv = bv});
  }
  for (double tol : {1e-12, 1e-9, 1e-7}) {
    char label[32];
    std::snprintf(label, sizeof label, "tol %.0e", tol);
    add("tolerance", label, [] { return Torus(64); }, {.relative_tolerance = tol});
  }
  RegisterStepLengthBenchmarks();
}

}  // namespace
}  // namespace hs::accuracy

int main(int argc, char** argv) {
  std::string out = ".";
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--out=", 6) == 0) out = argv[i] + 6;
  }
  hs::accuracy::Register();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  hs::accuracy::WriteResults(out);
  std::cout << "wrote " << out << "/accuracy.md, accuracy.dat, step.dat, tunnelling.dat\n";
  return 0;
}
