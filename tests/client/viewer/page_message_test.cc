// What a viewer page may send: the three messages it sends are read; every
// other message, and every pose that is not finite, rigid and near, is
// refused with a reason, so that it is never forwarded.

#include "client/viewer/page_message.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace hs::cli {
namespace {

// A fixed seed for the properties (RC_PARAMS from the environment wins, to
// replay a failure).
const bool kSeeded = setenv("RC_PARAMS", "seed=20261202 max_success=400", /*overwrite=*/0) == 0;

// What every message the parser lets through must satisfy, whatever the
// page sent: a tool's name of 1-256 bytes, and for a pose a finite
// position within kMaxPagePositionM and a proper rotation.
void ExpectSafe(const PageMessage& message) {
  const std::string& tool =
      std::visit([](const auto& m) -> const std::string& { return m.tool; }, message);
  RC_ASSERT(!tool.empty());
  RC_ASSERT(tool.size() <= 256u);
  if (const MoveTool* move = std::get_if<MoveTool>(&message)) {
    RC_ASSERT(move->X_WD.matrix().allFinite());
    RC_ASSERT(move->X_WD.translation().norm() <= kMaxPagePositionM);
    const Matrix3d R = move->X_WD.linear();
    RC_ASSERT((R.transpose() * R - Matrix3d::Identity()).norm() < 1e-12);
    RC_ASSERT(std::abs(R.determinant() - 1) < 1e-12);
  }
}

// A message the parser read is safe; one it did not is INVALID_ARGUMENT.
void ExpectRefusedOrSafe(const absl::StatusOr<PageMessage>& message) {
  if (message.ok()) {
    ExpectSafe(*message);
  } else {
    RC_ASSERT(message.status().code() == absl::StatusCode::kInvalidArgument);
  }
}

TEST(PageMessageTest, ReadsTakePoseAndRelease) {
  absl::StatusOr<PageMessage> take = ParsePageMessage(R"({"type":"take","tool":"probe"})");
  ASSERT_TRUE(take.ok()) << take.status();
  EXPECT_EQ(std::get<TakeTool>(*take).tool, "probe");
  absl::StatusOr<PageMessage> release = ParsePageMessage(R"({"type":"release","tool":"probe"})");
  ASSERT_TRUE(release.ok());
  EXPECT_EQ(std::get<ReleaseTool>(*release).tool, "probe");
  // A quarter turn about z, slightly off unit: normalized.
  const double h = std::sqrt(0.5) * 1.0002;
  absl::StatusOr<PageMessage> pose =
      ParsePageMessage(R"({"type":"pose","tool":"probe","p":[0.1,-0.2,0.3],"q":[)" +
                       std::to_string(h) + ",0,0," + std::to_string(h) + "]}");
  ASSERT_TRUE(pose.ok()) << pose.status();
  const MoveTool& move = std::get<MoveTool>(*pose);
  EXPECT_EQ(move.X_WD.translation(), Vector3d(0.1, -0.2, 0.3));
  EXPECT_TRUE((move.X_WD.linear() * Vector3d::UnitX()).isApprox(Vector3d::UnitY(), 1e-12));
  EXPECT_NEAR((move.X_WD.linear().transpose() * move.X_WD.linear() - Matrix3d::Identity()).norm(),
              0, 1e-12);
}

TEST(PageMessageTest, RefusesWhatThePageDoesNotSend) {
  for (const char* bad : {
           "",
           "not json",
           "[1,2]",
           "{}",
           R"({"type":"take"})",
           R"({"type":"take","tool":""})",
           R"({"type":"take","tool":7})",
           R"({"type":"jump","tool":"probe"})",
           R"({"type":"take","tool":"probe","extra":1})",
           R"({"type":"pose","tool":"probe","p":[0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0],"q":[1,0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0,"x"],"q":[1,0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0,1e400],"q":[1,0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0,2000],"q":[1,0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0,0],"q":[2,0,0,0]})",
           R"({"type":"pose","tool":"probe","p":[0,0,0],"q":[0,0,0,0]})",
       }) {
    SCOPED_TRACE(bad);
    const absl::StatusOr<PageMessage> message = ParsePageMessage(bad);
    EXPECT_EQ(message.status().code(), absl::StatusCode::kInvalidArgument);
  }
  EXPECT_FALSE(ParsePageMessage(R"({"type":"take","tool":")" + std::string(300, 'x') + "\"}").ok());
}

// JSON nested as deep as a page message may be long (the bridge reads
// 16 KiB at most) is refused, not a crash in the parser or in freeing what
// it built.
TEST(PageMessageTest, RefusesDeeplyNestedJson) {
  constexpr int kDepth = 8 << 10;
  for (const std::string& text :
       {std::string(2 * kDepth, '['), std::string(kDepth, '[') + std::string(kDepth, ']'),
        R"({"type":"take","tool":"probe","x":)" + std::string(kDepth - 40, '[') +
            std::string(kDepth - 40, ']') + "}"}) {
    EXPECT_EQ(ParsePageMessage(text).status().code(), absl::StatusCode::kInvalidArgument);
  }
}

// Any bytes at all: refused, or a message that is safe to forward.
RC_GTEST_PROP(PageMessageTest, AnyBytesAreRefusedOrSafe, (const std::string& text)) {
  ExpectRefusedOrSafe(ParsePageMessage(text));
}

// Messages shaped like the page's, with hostile parts: other types and
// tools, numbers of any size or none, arrays of other lengths, extra
// fields. Refused, or safe to forward; a plain take or release is read.
RC_GTEST_PROP(PageMessageTest, PageShapedMessagesAreRefusedOrSafe, ()) {
  const auto text_of = [](double x) {
    char out[32];
    std::snprintf(out, sizeof out, "%.17g", x);
    return std::string(out);
  };
  // Mostly numbers the page could send (positions within 600 m a side, one
  // sometimes up to twice the limit; quaternions up to 1.2e-3 off unit),
  // sometimes ones it would not.
  const auto odd = rc::gen::element<std::string>("1e400", "-1e400", "1e-400", "-0", "true", "null",
                                                 "\"1\"", "[]", "NaN", "18446744073709551616");
  const auto array = [](const std::vector<std::string>& xs) {
    std::string out = "[";
    for (size_t i = 0; i < xs.size(); ++i) out += (i ? "," : "") + xs[i];
    return out + "]";
  };
  std::vector<std::string> p, q;
  for (int i = 0; i < 3; ++i) p.push_back(text_of(*rc::gen::inRange(-600'000, 600'001) / 1e3));
  Eigen::Vector4d unit;
  for (int i = 0; i < 4; ++i) unit[i] = *rc::gen::inRange(-1000, 1001);
  if (unit.norm() > 0) unit *= (1 + *rc::gen::inRange(-12, 13) * 1e-4) / unit.norm();
  for (int i = 0; i < 4; ++i) q.push_back(text_of(unit[i]));
  for (std::vector<std::string>* xs : {&p, &q}) {
    switch (*rc::gen::inRange(0, 8)) {
      case 0:
        (*xs)[*rc::gen::inRange<size_t>(0, xs->size())] = *odd;
        break;
      case 1:
        xs->pop_back();
        break;
      case 2:
        xs->push_back("0");
        break;
      case 3:
        (*xs)[0] = text_of(*rc::gen::inRange(999'000, 2'000'001) / 1e3);
        break;
      default:
        break;
    }
  }
  const std::string type =
      *rc::gen::element<std::string>("take", "release", "pose", "pose", "pose", "jump");
  const std::string tool = *rc::gen::weightedOneOf<std::string>(
      {{3, rc::gen::just<std::string>("probe")},
       {1, rc::gen::element<std::string>("", "\\u0000", "\\ud800", "caf\\u00e9",
                                         std::string(256, 'x'), std::string(257, 'x'))},
       {1, rc::gen::arbitrary<std::string>()}});
  std::string text = R"({"type":")" + type + R"(","tool":")" + tool + "\"";
  const bool with_p = type == "pose" || *rc::gen::inRange(0, 8) == 0;
  const bool with_q = type == "pose" || *rc::gen::inRange(0, 8) == 0;
  if (with_p) text += R"(,"p":)" + array(p);
  if (with_q) text += R"(,"q":)" + array(q);
  const bool extra = *rc::gen::inRange(0, 8) == 0;
  if (extra) text += R"(,"extra":1)";
  text += "}";
  const absl::StatusOr<PageMessage> message = ParsePageMessage(text);
  RC_CLASSIFY(message.ok() && std::holds_alternative<MoveTool>(*message), "pose read");
  if ((type == "take" || type == "release") && tool == "probe" && !with_p && !with_q && !extra) {
    RC_ASSERT(message.ok());
  }
  ExpectRefusedOrSafe(message);
}

// The properties above run with a fixed seed unless RC_PARAMS says otherwise.
TEST(PageMessageTest, PropertiesAreSeeded) {
  EXPECT_TRUE(kSeeded);
  EXPECT_NE(std::getenv("RC_PARAMS"), nullptr);
}

}  // namespace
}  // namespace hs::cli
