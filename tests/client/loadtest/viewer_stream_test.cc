#include "client/loadtest/viewer_stream.h"

#include <gtest/gtest.h>

#include <thread>

#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

// A viewer counts the scene's frames until the scene is deleted; once the
// test's own watcher has seen 20 frames the viewer has had its share, and
// its frames and drops cover the steps it saw.
TEST(ViewerStreamTest, CountsUntilTheSceneGoes) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("s"));
  ViewerStream viewer(server.sessions(), "s");
  std::thread run([&] { viewer.Run(SendSchedule::Clock::now()); });
  grpc::ClientContext context;
  haptics::v1::WatchRequest request;
  request.set_scene("s");
  auto watcher = server.sessions().Watch(&context, request);
  haptics::v1::Frame frame;
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(watcher->Read(&frame));
  haptics::v1::DeleteSceneRequest remove;
  remove.set_scene("s");
  haptics::v1::DeleteSceneResponse removed;
  ASSERT_TRUE(
      server.scenes().DeleteScene(hs::testing::ContextWithin(5).get(), remove, &removed).ok());
  run.join();
  context.TryCancel();
  const StreamReport report = viewer.Report(1.0);
  EXPECT_GT(report.frames, 0);
  EXPECT_EQ(report.frames + report.dropped_frames, report.last_step - report.first_step + 1);
  EXPECT_EQ(report.sent, 0);
}

// Stop ends a viewer whose scene goes on; frames before its start are not
// counted.
TEST(ViewerStreamTest, StopEndsIt) {
  hs::testing::TestServer server;
  server.Create(hs::testing::SmallScene("s"));
  ViewerStream viewer(server.sessions(), "s");
  std::thread run([&] { viewer.Run(SendSchedule::Clock::now() + std::chrono::hours(1)); });
  viewer.Stop();
  run.join();
  EXPECT_EQ(viewer.Report(1.0).frames, 0);
}

}  // namespace
}  // namespace hs::cli
