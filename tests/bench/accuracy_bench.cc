// What accuracy costs in time: the contact query over the knobs that trade
// one for the other (mesh resolution, method, bounding volume, tolerance),
// each point timed (median and p99 per query) beside its depth and normal
// error against an analytic reference; and tunnelling (passes through a
// thin plate missed) for discrete, sub-stepped and continuous collision at
// growing step lengths. Writes a Markdown table and gnuplot data to the
// directory given by --out (scripts/accuracy.sh draws docs/*.png from it).
//
// References: a sphere or a tilted torus pressed into the flat top (z = 0)
// of a large slab, along directions D drawn with a fixed seed. Moving back
// along -D, the smooth shape leaves the half-space when its lowest point
// reaches z = 0: t = -z_min / -D_z, normal +z. A mesh's vertices lie on the
// smooth surface, so its error is what its flat facets cost.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "common/contact/contact_query.h"
#include "common/model/procedural.h"
#include "tests/common/contact/contact_test_bodies.h"

namespace hs {
namespace {

using testing_bodies::Body;

// Hierarchies grown by 1e-6 of the box diagonal, as scenes build them.
std::unique_ptr<Body> MakeBody(MeshInput mesh, BvType bv) {
  return testing_bodies::MakeBody(std::move(mesh), Isometry3d::Identity(), bv);
}

std::unique_ptr<Body> Slab(BvType bv) {
  auto slab = MakeBody(MakeBox(Vector3d(1, 1, 0.2)), bv);
  slab->X_WO.translation() = Vector3d(0, 0, -0.1);
  return slab;
}

// A shape with the depth of its smooth original along D.
struct Shape {
  std::string name;
  MeshInput mesh;
  Matrix3d R_WO = Matrix3d::Identity();  // orientation in the world
  // z_min of the smooth shape with its origin at the world origin.
  double lowest_z = 0;
  // The smooth shape is the same however it is turned (a sphere): each
  // configuration turns the mesh at random, off its vertex at the pole.
  bool any_orientation = false;
};

Shape Sphere(int subdivisions) {
  constexpr double r = 0.02;
  MeshInput mesh = MakeIcosphere(r, subdivisions);
  return {"sphere", std::move(mesh), Matrix3d::Identity(), -r, true};
}

// Tilted by 0.3 rad about x: its lowest point is R sin(0.3) + r below its
// centre, and lies on no vertex ring.
Shape Torus(int major_segments) {
  constexpr double R = 0.04, r = 0.01, tilt = 0.3;
  Shape s{"torus", MakeTorus(R, r, major_segments, major_segments / 2),
          Eigen::AngleAxisd(tilt, Vector3d::UnitX()).toRotationMatrix(), -(R * std::sin(tilt) + r)};
  return s;
}

// One query configuration: a pose of the shape and D.
struct Config {
  Isometry3d X_WO;
  Vector3d D;
  double depth;  // the smooth shape's
};

std::vector<Config> Configs(const Shape& shape) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Config> configs;
  while (configs.size() < 16) {
    const Vector3d D = Vector3d(u(rng), u(rng), u(rng)).normalized();
    if (D.z() > -0.3) continue;                             // into the slab, not grazing
    const double press = 0.001 + 0.004 * (u(rng) + 1) / 2;  // 1 to 5 mm
    Isometry3d X = Isometry3d::Identity();
    X.linear() = shape.R_WO;
    if (shape.any_orientation) {
      X.linear() = Eigen::AngleAxisd(M_PI * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized())
                       .toRotationMatrix();
    }
    X.translation() = Vector3d(0.1 * u(rng), 0.1 * u(rng), -shape.lowest_z - press);
    configs.push_back({X, D, press / -D.z()});
  }
  return configs;
}

struct Point {
  std::string family, label;
  double median_us = 0, p99_us = 0;
  double depth_error_m = 0, normal_error_rad = 0;
  double missed = -1;  // tunnelling: fraction of passes missed
};
// Results in the order the benchmarks run (their registration order); a
// benchmark run again for more iterations replaces its point.
std::vector<Point>& Results() {
  static std::vector<Point> results;
  return results;
}

void Record(const Point& point) {
  for (Point& p : Results()) {
    if (p.family == point.family && p.label == point.label) {
      p = point;
      return;
    }
  }
  Results().push_back(point);
}

void Percentiles(std::vector<double>& us, Point& point) {
  std::sort(us.begin(), us.end());
  point.median_us = us[us.size() / 2];
  point.p99_us = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

struct Knobs {
  ContactMethod method = ContactMethod::kSweep3d;
  BvType bv = BvType::kObbRss;
  double relative_tolerance = 1e-9;
};

void BM_Accuracy(benchmark::State& state, const std::string& family, const std::string& label,
                 const std::function<Shape()>& make_shape, Knobs knobs) {
  const Shape shape = make_shape();
  const auto moving = MakeBody(shape.mesh, knobs.bv);
  const auto slab = Slab(knobs.bv);
  const std::vector<Config> configs = Configs(shape);
  Point point{family, label};
  for (const Config& c : configs) {
    moving->X_WO = c.X_WO;
    const ContactSet set = *ComputeContact(moving->posed(), slab->posed(),
                                           {.direction_W = c.D,
                                            .method = knobs.method,
                                            .relative_tolerance = knobs.relative_tolerance});
    point.depth_error_m = std::max(point.depth_error_m, std::abs(set.depth_m - c.depth));
    point.normal_error_rad =
        std::max(point.normal_error_rad, std::acos(std::clamp(set.normal_W.z(), -1.0, 1.0)));
  }
  std::vector<double> us;
  size_t i = 0;
  for (auto _ : state) {
    const Config& c = configs[i++ % configs.size()];
    moving->X_WO = c.X_WO;
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ComputeContact(moving->posed(), slab->posed(),
                                            {.direction_W = c.D,
                                             .method = knobs.method,
                                             .relative_tolerance = knobs.relative_tolerance}));
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  Percentiles(us, point);
  state.counters["faces"] = moving->object.num_faces();
  state.counters["p50_us"] = point.median_us;
  state.counters["p99_us"] = point.p99_us;
  state.counters["depth_err_m"] = point.depth_error_m;
  Record(point);
}

// How a 1 cm sphere passing a 1 mm plate in steps of `step_m` is checked.
enum class Check { kDiscrete, kSubSteps, kContinuous };

// Each pass starts at a different phase of the step grid; a pass is missed
// when no check along it reports a collision.
void BM_Tunnelling(benchmark::State& state, Check check, double step_m) {
  const auto ball = MakeBody(MakeIcosphere(0.005, 3), BvType::kObbRss);
  auto plate = MakeBody(MakeBox(Vector3d(0.2, 0.2, 0.001)), BvType::kObbRss);
  // Sub-steps shorter than the smallest box edge of the two (paper s.4).
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
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  const char* names[] = {"discrete", "sub-steps", "continuous"};
  Point point{"tunnelling", std::string(names[static_cast<int>(check)]) + " " +
                                std::to_string(static_cast<int>(step_m * 1e4) / 10.0).substr(0, 4) +
                                " mm"};
  Percentiles(us, point);
  point.missed = static_cast<double>(missed) / kPasses;
  state.counters["missed"] = point.missed;
  state.counters["p99_us"] = point.p99_us;
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
  for (auto [name, method] : {std::pair{"paper2d", ContactMethod::kPaper2d},
                              std::pair{"sweep3d", ContactMethod::kSweep3d}}) {
    add("method", std::string("sphere ") + name, [] { return Sphere(4); }, {.method = method});
    add("method", std::string("torus ") + name, [] { return Torus(64); }, {.method = method});
  }
  for (BvType bv : {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios, BvType::kAabb}) {
    add("bv", std::string(BvTypeName(bv)), [] { return Torus(64); }, {.bv = bv});
  }
  for (double tol : {1e-12, 1e-9, 1e-7}) {
    char label[32];
    std::snprintf(label, sizeof label, "tol %.0e", tol);
    add("tolerance", label, [] { return Torus(64); }, {.relative_tolerance = tol});
  }
  for (double step_m : {0.0005, 0.002, 0.005, 0.012, 0.03}) {
    for (Check check : {Check::kDiscrete, Check::kSubSteps, Check::kContinuous}) {
      benchmark::RegisterBenchmark(
          ("Tunnelling/" + std::to_string(static_cast<int>(check)) + "/" + std::to_string(step_m))
              .c_str(),
          [=](benchmark::State& s) { BM_Tunnelling(s, check, step_m); })
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

void WriteResults(const std::string& dir) {
  std::ofstream table(dir + "/accuracy.md");
  std::ofstream data(dir + "/accuracy.dat");
  std::ofstream tunnel(dir + "/tunnelling.dat");
  std::ofstream families(dir + "/families");  // block titles for gnuplot
  table << "| knob | point | median us | p99 us | depth error m | normal error rad |\n"
           "| --- | --- | --- | --- | --- | --- |\n";
  std::string family;
  for (const Point& p : Results()) {
    if (p.missed >= 0) continue;
    table << "| " << p.family << " | " << p.label << " | " << p.median_us << " | " << p.p99_us
          << " | " << p.depth_error_m << " | " << p.normal_error_rad << " |\n";
    // gnuplot: one block per knob, two blank lines between blocks.
    if (p.family != family) {
      if (!family.empty()) data << "\n\n";
      families << '"' << p.family << "\" ";
    }
    family = p.family;
    data << '"' << p.family << "\" \"" << p.label << "\" " << p.median_us << ' '
         << std::max(p.depth_error_m, 1e-16) << '\n';
  }
  table << "\n| tunnelling | median us per step | p99 us | passes missed |\n"
           "| --- | --- | --- | --- |\n";
  for (const Point& p : Results()) {
    if (p.missed < 0) continue;
    table << "| " << p.label << " | " << p.median_us << " | " << p.p99_us << " | " << 100 * p.missed
          << "% |\n";
    tunnel << '"' << p.label << "\" " << p.median_us << ' ' << 100 * p.missed << '\n';
  }
}

}  // namespace
}  // namespace hs

int main(int argc, char** argv) {
  std::string out = ".";
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--out=", 6) == 0) out = argv[i] + 6;
  }
  hs::Register();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  hs::WriteResults(out);
  std::cout << "wrote " << out << "/accuracy.md, accuracy.dat, tunnelling.dat\n";
  return 0;
}
