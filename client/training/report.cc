#include "client/training/report.h"

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "client/training/report_html.h"
#include "client/training/score_output.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

using nlohmann::ordered_json;

// Plots keep at most this many points of a run (every n-th frame).
constexpr size_t kMaxPlotPoints = 4000;

// Runs `script` through gnuplot. Written by hand: gnuplot is the plotting
// tool the project uses (docs' plots), and a pipe to it is all it takes.
absl::Status Gnuplot(const std::string& script) {
  FILE* pipe = popen("gnuplot", "w");
  if (!pipe) return absl::InternalError("cannot run gnuplot");
  fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  if (status != 0) return absl::InternalError("gnuplot failed on the report's plots");
  return absl::OkStatus();
}

// Every n-th trace point, n such that at most kMaxPlotPoints remain.
std::vector<const TracePoint*> Thinned(const std::vector<TracePoint>& trace) {
  const size_t stride = std::max<size_t>(1, (trace.size() + kMaxPlotPoints - 1) / kMaxPlotPoints);
  std::vector<const TracePoint*> out;
  for (size_t i = 0; i < trace.size(); i += stride) out.push_back(&trace[i]);
  return out;
}

std::string Quoted(const std::string& text) {
  return "\"" + absl::StrReplaceAll(text, {{"\\", "\\\\"}, {"\"", "\\\""}}) + "\"";
}

std::string ForcePlot(const ReportInput& in, const std::string& png) {
  std::ostringstream s;
  s << "reset\nset terminal pngcairo size 900,380\nset output " << Quoted(png) << "\n"
    << "set xlabel \"time (s)\"\nset ylabel \"force on the device (N)\"\nset key top left\n"
    << "set grid\n";
  double top = in.summary.max_force_n;
  for (const ForceLimit& l : in.exercise->force_limits) top = std::max(top, l.limit_n);
  s << "set yrange [0:" << 1.25 * std::max(top, 0.1) << "]\n$run << EOD\n";
  for (const TracePoint* p : Thinned(*in.trace)) {
    s << p->t_s << " " << p->force_n << " " << (p->limit_n > 0 ? absl::StrCat(p->limit_n) : "NaN")
      << "\n";
  }
  s << "EOD\nplot $run using 1:2 with lines lw 2 title \"|F|\", "
    << "$run using 1:3 with lines dt 2 lw 2 lc rgb \"red\" title \"limit of the object pressed\"";
  for (const ForceLimit& l : in.exercise->force_limits) {
    s << ", " << l.limit_n << " with lines dt 3 lc rgb \"gray\" title "
      << Quoted("limit: " + l.object);
  }
  s << "\n";
  return s.str();
}

// A view of the path (axes `a`, `b` of x, y, z) with the targets' and
// forbidden balls as their outlines (ellipses where the axes' scales differ).
void PathView(const ReportInput& in, int a, int b, const char* title, std::ostringstream& s) {
  const char* names[] = {"x (m)", "y (m)", "z (m)"};
  // From above, metres alike on both axes; from the side, heights are
  // small against the width: each axis its own scale.
  s << (b == 1 ? "set size ratio -1\n" : "set size noratio\n");
  // The ranges take in the path and every ball (objects do not autoscale).
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  auto take = [&](const Vector3d& p, double r) {
    lo = lo.cwiseMin(p - Vector3d::Constant(r));
    hi = hi.cwiseMax(p + Vector3d::Constant(r));
  };
  for (const TracePoint& p : *in.trace) take(p.p_WD, 0);
  for (const Target& t : in.exercise->targets) take(t.region.center_W, t.region.radius_m);
  for (const Forbidden& f : in.exercise->forbidden) {
    if (f.region) take(f.region->center_W, f.region->radius_m);
  }
  const Vector3d margin = 0.05 * (hi - lo).cwiseMax(Vector3d::Constant(0.01));
  s << "set xrange [" << lo[a] - margin[a] << ":" << hi[a] + margin[a] << "]\nset yrange ["
    << lo[b] - margin[b] << ":" << hi[b] + margin[b] << "]\n";
  s << "unset object\nunset label\nset title " << Quoted(title) << "\nset xlabel "
    << Quoted(names[a]) << "\nset ylabel " << Quoted(names[b]) << "\n";
  int object = 1;
  for (const Target& t : in.exercise->targets) {
    s << "set object " << object++ << " ellipse at " << t.region.center_W[a] << ","
      << t.region.center_W[b] << " size " << 2 * t.region.radius_m << "," << 2 * t.region.radius_m
      << " fc rgb \"forest-green\" fs transparent solid 0.25\n"
      << "set label " << Quoted(t.name) << " at " << t.region.center_W[a] << ","
      << t.region.center_W[b] << " center\n";
  }
  for (const Forbidden& f : in.exercise->forbidden) {
    if (!f.region) continue;
    s << "set object " << object++ << " ellipse at " << f.region->center_W[a] << ","
      << f.region->center_W[b] << " size " << 2 * f.region->radius_m << ","
      << 2 * f.region->radius_m << " fc rgb \"red\" fs transparent solid 0.25\n";
  }
  s << "plot $path using " << a + 1 << ":" << b + 1 << " with lines lw 2 title \"device\"\n";
}

std::string PathPlot(const ReportInput& in, const std::string& png) {
  std::ostringstream s;
  s << "reset\nset terminal pngcairo size 1000,460\nset output " << Quoted(png) << "\n"
    << "set grid\nset key bottom right\n$path << EOD\n";
  for (const TracePoint* p : Thinned(*in.trace)) {
    s << p->p_WD.x() << " " << p->p_WD.y() << " " << p->p_WD.z() << "\n";
  }
  s << "EOD\nset multiplot layout 1,2\n";
  PathView(in, 0, 1, "from above", s);
  PathView(in, 0, 2, "from the side", s);
  s << "unset multiplot\n";
  return s.str();
}

std::string AttemptsPlot(const std::vector<double>& scores, const std::string& png) {
  std::ostringstream s;
  s << "reset\nset terminal pngcairo size 700,320\nset output " << Quoted(png) << "\n"
    << "set xlabel \"attempt\"\nset ylabel \"score\"\nset yrange [0:100]\nset grid\n"
    << "set xtics 1\nunset key\n$scores << EOD\n";
  for (size_t i = 0; i < scores.size(); ++i) s << i + 1 << " " << scores[i] << "\n";
  s << "EOD\nplot $scores using 1:2 with linespoints lw 2 pt 7\n";
  return s.str();
}

}  // namespace

absl::Status WriteReport(const std::string& dir, const ReportInput& in) {
  std::vector<double> scores;
  for (const std::string& earlier : in.compare) {
    std::ifstream file(std::filesystem::path(earlier) / "report.json");
    const nlohmann::json report = nlohmann::json::parse(file, nullptr, false);
    if (!report.is_object() || !report.contains("score") || !report["score"].is_number()) {
      return absl::InvalidArgumentError(earlier + ": no report.json with a score");
    }
    scores.push_back(report["score"].get<double>());
  }
  scores.push_back(in.summary.score);
  std::error_code made;
  std::filesystem::create_directories(dir, made);
  if (made) return absl::InvalidArgumentError(dir + ": " + made.message());
  const std::filesystem::path base(dir);
  const auto written = std::chrono::system_clock::now();
  ordered_json json = {
      {"exercise", in.exercise->name},
      {"tool", in.exercise->tool},
      {"scene", in.scene},
      {"ended", in.ended},
      {"written_unix_s",
       std::chrono::duration_cast<std::chrono::seconds>(written.time_since_epoch()).count()}};
  json.update(SummaryJson(in.summary));
  json["attempt_scores"] = scores;
  std::ofstream(base / "report.json") << json.dump(2) << "\n";
  std::vector<std::string> pngs = {(base / "force.png").string(), (base / "path.png").string()};
  std::string script = ForcePlot(in, pngs[0]) + PathPlot(in, pngs[1]);
  if (!in.compare.empty()) {
    pngs.push_back((base / "attempts.png").string());
    script += AttemptsPlot(scores, pngs.back());
  }
  if (absl::Status plotted = Gnuplot(script); !plotted.ok()) return plotted;
  std::ofstream(base / "report.html") << ReportHtml(in, written, pngs);
  return absl::OkStatus();
}

}  // namespace hs::cli
