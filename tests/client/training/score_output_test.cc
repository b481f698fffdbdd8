// A run's summary as JSON (every field under its documented name, in order)
// and as one line for people.

#include "client/training/score_output.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hs::cli {
namespace {

// A run with every field set to a value of its own, one reached and one
// missed target, and one forbidden contact.
ScoreSummary SampleRun() {
  ScoreSummary s;
  s.score = 71.5;
  s.completed = false;
  s.duration_s = 12.25;
  s.targets_reached = 1;
  s.targets = 2;
  s.path_length_m = 0.375;
  s.economy = 1.5;
  s.max_force_n = 3.25;
  s.force_limit_exceeded_s = 0.125;
  s.excess_impulse_ns = 0.0625;
  s.forbidden_contacts = 1;
  s.jerk_rms = 9.75;
  s.target_results = {{.name = "east", .reached = true, .reached_at_s = 2.5, .max_force_n = 1.75},
                      {.name = "west"}};
  s.forbidden_list = {{.object = "table", .start_s = 4.5, .duration_s = 0.25, .max_force_n = 0.5}};
  return s;
}

// The documented keys in their order, each holding its field's value; the
// targets' and forbidden contacts' lists in the run's order.
TEST(ScoreOutputTest, JsonHoldsEveryFieldByName) {
  const ScoreSummary s = SampleRun();
  const nlohmann::ordered_json json = SummaryJson(s);
  std::vector<std::string> keys;
  for (const auto& [key, value] : json.items()) keys.push_back(key);
  EXPECT_EQ(keys,
            (std::vector<std::string>{
                "score", "completed", "duration_s", "targets_reached", "targets", "path_length_m",
                "economy", "max_force_n", "force_limit_exceeded_s", "excess_impulse_ns",
                "forbidden_contacts", "jerk_rms", "target_results", "forbidden_list"}));
  EXPECT_EQ(json["score"], s.score);
  EXPECT_EQ(json["completed"], s.completed);
  EXPECT_EQ(json["duration_s"], s.duration_s);
  EXPECT_EQ(json["targets_reached"], s.targets_reached);
  EXPECT_EQ(json["targets"], s.targets);
  EXPECT_EQ(json["path_length_m"], s.path_length_m);
  EXPECT_EQ(json["economy"], s.economy);
  EXPECT_EQ(json["max_force_n"], s.max_force_n);
  EXPECT_EQ(json["force_limit_exceeded_s"], s.force_limit_exceeded_s);
  EXPECT_EQ(json["excess_impulse_ns"], s.excess_impulse_ns);
  EXPECT_EQ(json["forbidden_contacts"], s.forbidden_contacts);
  EXPECT_EQ(json["jerk_rms"], s.jerk_rms);
  EXPECT_EQ(json["target_results"], nlohmann::ordered_json::parse(R"([
      {"name": "east", "reached": true, "reached_at_s": 2.5, "max_force_n": 1.75},
      {"name": "west", "reached": false, "reached_at_s": 0, "max_force_n": 0}])"));
  EXPECT_EQ(json["forbidden_list"], nlohmann::ordered_json::parse(R"([
      {"object": "table", "start_s": 4.5, "duration_s": 0.25, "max_force_n": 0.5}])"));
}

// Empty lists are empty arrays, not null.
TEST(ScoreOutputTest, EmptyListsAreArrays) {
  const nlohmann::ordered_json json = SummaryJson(ScoreSummary{});
  EXPECT_TRUE(json["target_results"].is_array());
  EXPECT_TRUE(json["target_results"].empty());
  EXPECT_TRUE(json["forbidden_list"].is_array());
}

// One line with every figure and its unit.
TEST(ScoreOutputTest, OneLineForPeople) {
  std::ostringstream out;
  PrintSummary(SampleRun(), out);
  EXPECT_EQ(out.str(),
            "score 71.5 / 100, not completed in 12.25 s: targets 1 of 2, path 0.375 m (economy "
            "1.5), max force 3.25 N, over the limit 0.125 s (excess 0.0625 N*s), forbidden "
            "contacts 1, jerk rms 9.75 m/s^3\n");
}

}  // namespace
}  // namespace hs::cli
