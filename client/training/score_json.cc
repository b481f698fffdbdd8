#include "client/training/score_json.h"

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

}  // namespace hs::cli
