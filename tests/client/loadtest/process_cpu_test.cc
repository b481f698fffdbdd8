#include "client/loadtest/process_cpu.h"

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace hs::cli {
namespace {

// Burns CPU in this thread until this process has used `seconds` more.
void Burn(double seconds) {
  const double until = OwnCpuSeconds() + seconds;
  volatile double x = 0;
  while (OwnCpuSeconds() < until) x = x + 1;
}

// This process's CPU time grows as it computes, read through /proc as
// through getrusage; /proc counts whole clock ticks, so the two agree
// within a tick or two.
TEST(ProcessCpuTest, ThisProcessCpuGrows) {
  const std::optional<double> before = ProcessCpuSeconds(getpid());
  ASSERT_TRUE(before.has_value());
  Burn(0.05);
  const std::optional<double> after = ProcessCpuSeconds(getpid());
  ASSERT_TRUE(after.has_value());
  EXPECT_GT(*after, *before);
  EXPECT_NEAR(*after, OwnCpuSeconds(), 0.05);
}

// A process that does not exist has no CPU figure.
TEST(ProcessCpuTest, NoSuchProcess) { EXPECT_FALSE(ProcessCpuSeconds(-1).has_value()); }

// The process listening on a loopback port is found: this one, for a
// socket it listens on; a port nobody listens on finds none.
TEST(ProcessCpuTest, FindsTheListener) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  socklen_t size = sizeof(address);
  ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size), 0);
  const int port = ntohs(address.sin_port);
  EXPECT_FALSE(FindListeningPid(port).has_value());  // bound, not listening
  ASSERT_EQ(listen(fd, 1), 0);
  EXPECT_EQ(FindListeningPid(port), getpid());
  close(fd);
}

}  // namespace
}  // namespace hs::cli
