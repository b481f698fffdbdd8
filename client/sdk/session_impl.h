#pragma once
// What a Session shares with the Devices and Watchers it opens: the
// channel and the options it was made with.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "haptics/session.h"

namespace haptics {

// Hidden: the Session class is exported, its state is not.
class [[gnu::visibility("hidden")]] Session::Impl {
 public:
  std::string address;
  SessionOptions options;
  std::shared_ptr<grpc::Channel> channel;
};

}  // namespace haptics
