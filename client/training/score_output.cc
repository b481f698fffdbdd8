#include "client/training/score_output.h"

namespace hs::cli {

nlohmann::ordered_json SummaryJson(const ScoreSummary& s) {
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetResult& t : s.target_results) {
    targets.push_back({{"name", t.name},
                       {"reached", t.reached},
                       {"reached_at_s", t.reached_at_s},
                       {"max_force_n", t.max_force_n}});
  }
  nlohmann::ordered_json forbidden = nlohmann::ordered_json::array();
  for (const ForbiddenContact& f : s.forbidden_list) {
    forbidden.push_back({{"object", f.object},
                         {"start_s", f.start_s},
                         {"duration_s", f.duration_s},
                         {"max_force_n", f.max_force_n}});
  }
  return {{"score", s.score},
          {"completed", s.completed},
          {"duration_s", s.duration_s},
          {"targets_reached", s.targets_reached},
          {"targets", s.targets},
          {"path_length_m", s.path_length_m},
          {"economy", s.economy},
          {"max_force_n", s.max_force_n},
          {"force_limit_exceeded_s", s.force_limit_exceeded_s},
          {"excess_impulse_ns", s.excess_impulse_ns},
          {"forbidden_contacts", s.forbidden_contacts},
          {"jerk_rms", s.jerk_rms},
          {"target_results", targets},
          {"forbidden_list", forbidden}};
}

void PrintSummary(const ScoreSummary& s, std::ostream& out) {
  out << "score " << s.score << " / 100, " << (s.completed ? "completed" : "not completed")
      << " in " << s.duration_s << " s: targets " << s.targets_reached << " of " << s.targets
      << ", path " << s.path_length_m << " m (economy " << s.economy << "), max force "
      << s.max_force_n << " N, over the limit " << s.force_limit_exceeded_s << " s (excess "
      << s.excess_impulse_ns << " N*s), forbidden contacts " << s.forbidden_contacts
      << ", jerk rms " << s.jerk_rms << " m/s^3\n";
}

}  // namespace hs::cli
