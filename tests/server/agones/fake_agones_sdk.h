#pragma once
// A stand-in for the Agones SDK's REST endpoint in tests: an HTTP server on
// a free 127.0.0.1 port (Boost.Beast) that records every request and
// answers 200 "{}", or 503 while told to fail.

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace hs::testing {

class FakeAgonesSdk {
 public:
  struct Request {
    std::string method;  // "POST", "PUT"
    std::string target;  // "/ready"
    std::string body;
  };

  FakeAgonesSdk();
  ~FakeAgonesSdk();

  int port() const { return port_; }
  /// While true, every request is answered 503.
  void SetFailing(bool failing) { failing_ = failing; }
  /// Every request so far, in order.
  std::vector<Request> requests() const;
  /// Requests so far to `target` with `method`.
  int Count(const std::string& method, const std::string& target) const;
  /// Waits until Count(method, target) >= `count`, up to `timeout_s`
  /// seconds; true when it got there.
  bool WaitFor(const std::string& method, const std::string& target, int count = 1,
               double timeout_s = 10) const;

 private:
  void Serve();
  int CountLocked(const std::string& method, const std::string& target) const;

  std::atomic<bool> failing_{false};
  std::atomic<bool> stop_{false};
  int port_ = 0;
  mutable std::mutex mu_;
  mutable std::condition_variable cv_;
  std::vector<Request> requests_;
  struct Listener;
  std::unique_ptr<Listener> listener_;
  std::thread thread_;
};

}  // namespace hs::testing
