#include "client/json_text.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hs::cli {
namespace {

// One "key: value" line per field in order; objects flatten with dots,
// arrays of objects with indices; strings bare, everything else as JSON.
TEST(JsonTextTest, FlattensObjectsAndArraysOfObjects) {
  const nlohmann::ordered_json j = {
      {"scene", "probe on torus"},
      {"steps", 60},
      {"force", {{"max_n", 2.5}, {"clamped", false}}},
      {"position", {0.1, 0.2, 0.3}},
      {"empty", nlohmann::ordered_json::array()},
      {"tools", {{{"name", "probe"}, {"contacts", 2}}, {{"name", "stylus"}, {"contacts", 0}}}},
      {"missing", nullptr}};
  std::ostringstream out;
  PrintJsonAsText(j, "", out);
  EXPECT_EQ(out.str(),
            "scene: probe on torus\n"
            "steps: 60\n"
            "force.max_n: 2.5\n"
            "force.clamped: false\n"
            "position: [0.1,0.2,0.3]\n"
            "empty: []\n"
            "tools[0].name: probe\n"
            "tools[0].contacts: 2\n"
            "tools[1].name: stylus\n"
            "tools[1].contacts: 0\n"
            "missing: null\n");
}

// Every key is written after the prefix given.
TEST(JsonTextTest, PrefixComesFirst) {
  std::ostringstream out;
  PrintJsonAsText({{"a", {{"b", 1}}}}, "run.", out);
  EXPECT_EQ(out.str(), "run.a.b: 1\n");
}

}  // namespace
}  // namespace hs::cli
