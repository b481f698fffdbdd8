// A page's device stream: it reports "held" when the server gives it the
// tool and moves the tool to the poses sent, "refused" with the server's
// word when the tool is held or missing, and "released" when it ends.

#include "client/viewer/page_device.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "absl/strings/match.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

// What a device's stream reports, from its reader thread.
class Reports {
 public:
  PageDevice::Report Sink() {
    return [this](const std::string& state, const std::string& message) {
      std::lock_guard lock(mu_);
      states_.push_back(state);
      messages_.push_back(message);
      cv_.notify_all();
    };
  }
  // Waits (at most 20 s, so that a broken stream fails rather than hangs)
  // for the `n`th report; "" when none came.
  std::string State(size_t n) {
    std::unique_lock lock(mu_);
    cv_.wait_for(lock, std::chrono::seconds(20), [&] { return states_.size() >= n; });
    return states_.size() >= n ? states_[n - 1] : "";
  }
  std::string Message(size_t n) {
    std::lock_guard lock(mu_);
    return messages_.size() >= n ? messages_[n - 1] : "";
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::vector<std::string> states_;
  std::vector<std::string> messages_;
};

class PageDeviceTest : public ::testing::Test {
 protected:
  void SetUp() override { server_.Create(hs::testing::SmallScene("pages")); }
  hs::testing::TestServer server_;
};

// The tool goes where the page's pose puts it: a watcher's frame shows the
// device pose sent (doubles both ways: exactly).
TEST_F(PageDeviceTest, HeldToolFollowsThePose) {
  Reports reports;
  PageDevice device(server_.channel(), "pages", "probe", reports.Sink());
  ASSERT_EQ(reports.State(1), "held") << reports.Message(1);
  const Isometry3d X_WD(Eigen::Translation3d(0.01, -0.02, 0.07));
  device.SendPose(X_WD);
  grpc::ClientContext context;
  pb::WatchRequest watch;
  watch.set_scene("pages");
  auto frames = server_.sessions().Watch(&context, watch);
  pb::Frame frame;
  bool moved = false;
  for (int i = 0; i < 20000 && !moved && frames->Read(&frame); ++i) {
    const pb::Vector3& p = frame.tools(0).device_pose().position_m();
    moved = Vector3d(p.x(), p.y(), p.z()) == X_WD.translation();
  }
  context.TryCancel();
  EXPECT_TRUE(moved) << frame.DebugString();
}

// A tool another device holds is refused with the server's message; once
// that device's stream ends it reports "released".
TEST_F(PageDeviceTest, HeldElsewhereIsRefusedAndEndIsReleased) {
  Reports first_reports, second_reports;
  auto first =
      std::make_unique<PageDevice>(server_.channel(), "pages", "probe", first_reports.Sink());
  ASSERT_EQ(first_reports.State(1), "held");
  {
    PageDevice second(server_.channel(), "pages", "probe", second_reports.Sink());
    EXPECT_EQ(second_reports.State(1), "refused");
    EXPECT_TRUE(absl::StrContains(second_reports.Message(1), "held by another device"))
        << second_reports.Message(1);
  }
  first.reset();
  EXPECT_EQ(first_reports.State(2), "released") << first_reports.Message(2);
}

// A tool the scene lacks is refused, NOT_FOUND.
TEST_F(PageDeviceTest, MissingToolIsRefused) {
  Reports reports;
  PageDevice device(server_.channel(), "pages", "scalpel", reports.Sink());
  EXPECT_EQ(reports.State(1), "refused");
  EXPECT_TRUE(absl::StrContains(reports.Message(1), "NOT_FOUND")) << reports.Message(1);
}

// A device opened with the tool's pose holds the tool while the page
// sends nothing, kept alive as the view server keeps it (KeepAlive); one
// opened without waits for the page's first pose, and a server whose
// device timeout passes first releases the tool. A page slowed by a
// loaded machine is such a page.
TEST(PageDeviceTimeoutTest, APoseAtOpenHoldsTheToolBeforeThePageSendsOne) {
  ServerLimits limits;
  limits.device_timeout_s = 0.3;
  hs::testing::TestServer server(limits);
  server.Create(hs::testing::SmallScene("pages", /*second_tool=*/true));
  Reports with_pose, without;
  PageDevice posed(server.channel(), "pages", "probe", with_pose.Sink(),
                   Isometry3d(Eigen::Translation3d(0, 0, 0.05)));
  PageDevice silent(server.channel(), "pages", "stylus", without.Sink());
  ASSERT_EQ(with_pose.State(1), "held") << with_pose.Message(1);
  for (int i = 0; i < 20; ++i) {  // a second: three device timeouts
    posed.KeepAlive(std::chrono::milliseconds(100));
    silent.KeepAlive(std::chrono::milliseconds(100));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(without.State(2), "refused") << without.Message(2);
  EXPECT_TRUE(absl::StrContains(without.Message(2), "no pose came")) << without.Message(2);
  // Still held: no second report, and the server still has the probe held.
  EXPECT_EQ(with_pose.Message(2), "");
  const pb::SceneInfo info = server.Get("pages");
  ASSERT_EQ(info.claimed_tools_size(), 1) << info.DebugString();
  EXPECT_EQ(info.claimed_tools(0), "probe");
}

}  // namespace
}  // namespace hs::cli
