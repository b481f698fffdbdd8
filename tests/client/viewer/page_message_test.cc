// What a viewer page may send: the three messages it sends are read; every
// other message, and every pose that is not finite, rigid and near, is
// refused with a reason, so that it is never forwarded.

#include "client/viewer/page_message.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

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

}  // namespace
}  // namespace hs::cli
