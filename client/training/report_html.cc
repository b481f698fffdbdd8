#include "client/training/report_html.h"

#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "absl/strings/escaping.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"

namespace hs::cli {
namespace {

std::string Html(const std::string& text) {
  return absl::StrReplaceAll(text,
                             {{"&", "&amp;"}, {"<", "&lt;"}, {">", "&gt;"}, {"\"", "&quot;"}});
}

std::string InlinePng(const std::string& file, const std::string& alt) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return "<img alt=\"" + Html(alt) + "\" src=\"data:image/png;base64," +
         absl::Base64Escape(bytes.str()) + "\">";
}

// The summary's rows: what, and the figure with its unit. Rounded to what
// a trainee can act on: a tenth of a point, a centimetre of path, a
// hundredth of a newton.
std::vector<std::pair<std::string, std::string>> SummaryRows(const ScoreSummary& s) {
  return {
      {"Completed", s.completed ? "yes" : "no"},
      {"Duration", absl::StrFormat("%.2f s", s.duration_s)},
      {"Targets reached", absl::StrFormat("%d of %d", s.targets_reached, s.targets)},
      {"Path length", absl::StrFormat("%.2f m", s.path_length_m)},
      {"Economy (path / shortest path)", absl::StrFormat("%.2f", s.economy)},
      {"Largest force", absl::StrFormat("%.2f N", s.max_force_n)},
      {"Time over a force limit", absl::StrFormat("%.2f s", s.force_limit_exceeded_s)},
      {"Impulse beyond the limit", absl::StrFormat("%.3f N&middot;s", s.excess_impulse_ns)},
      {"Forbidden contacts", absl::StrFormat("%d", s.forbidden_contacts)},
      {"Jerk (rms)", absl::StrFormat("%.1f m/s&sup3;", s.jerk_rms)},
  };
}

}  // namespace

std::string UtcMinute(std::chrono::system_clock::time_point at) {
  const std::time_t t = std::chrono::system_clock::to_time_t(at);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

std::string ReportHtml(const ReportInput& in, std::chrono::system_clock::time_point written,
                       const std::vector<std::string>& pngs) {
  const ScoreSummary& s = in.summary;
  std::ostringstream h;
  h << "<!doctype html><html><head><meta charset=\"utf-8\"><title>" << Html(in.exercise->name)
    << "</title><style>body{font-family:sans-serif;margin:2em;max-width:1100px}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:4px 8px;"
       "text-align:left}img{max-width:100%;display:block;margin:1em 0}</style></head><body>"
    << "<h1>" << Html(in.exercise->name) << "</h1><p>Tool <b>" << Html(in.exercise->tool)
    << "</b> in scene <b>" << Html(in.scene) << "</b>, " << UtcMinute(written)
    << "; ended: " << Html(in.ended) << "</p>"
    << "<h2>Score " << absl::StrFormat("%.1f", s.score) << " / 100"
    << (s.completed ? "" : " (not completed)") << "</h2><table>";
  // The rows' texts are ours, their entities meant.
  for (const auto& [what, figure] : SummaryRows(s)) {
    h << "<tr><th>" << what << "</th><td>" << figure << "</td></tr>";
  }
  h << "</table><h2>Targets</h2><table><tr><th>target</th><th>reached</th><th>at</th>"
       "<th>largest force</th></tr>";
  for (const TargetResult& t : s.target_results) {
    h << "<tr><td>" << Html(t.name) << "</td><td>" << (t.reached ? "yes" : "no") << "</td><td>"
      << (t.reached ? absl::StrFormat("%.2f s", t.reached_at_s) : "") << "</td><td>"
      << absl::StrFormat("%.2f N", t.max_force_n) << "</td></tr>";
  }
  h << "</table><h2>Forbidden contacts</h2>";
  if (s.forbidden_list.empty()) h << "<p>None.</p>";
  for (const ForbiddenContact& f : s.forbidden_list) {
    h << "<p>" << Html(f.object) << " at " << absl::StrFormat("%.2f", f.start_s) << " s for "
      << absl::StrFormat("%.2f", f.duration_s) << " s, up to "
      << absl::StrFormat("%.2f", f.max_force_n) << " N</p>";
  }
  for (const std::string& png : pngs) {
    h << InlinePng(png, std::filesystem::path(png).stem().string());
  }
  h << "</body></html>\n";
  return h.str();
}

}  // namespace hs::cli
