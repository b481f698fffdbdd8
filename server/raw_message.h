#pragma once
// Requests as the bytes they came in. gRPC's callback API answers a
// request that does not parse with UNIMPLEMENTED (its handler gets no
// message and reports a missing method), or, on a stream, as if the client
// had closed it; services that take the bytes and parse them here answer
// INVALID_ARGUMENT instead.

#include <google/protobuf/message.h>
#include <grpcpp/support/byte_buffer.h>

#include "absl/status/status.h"

namespace hs {

/// Parses `bytes` into `message`. INVALID_ARGUMENT naming the message type
/// when they are not one.
absl::Status ParseMessage(const grpc::ByteBuffer& bytes, google::protobuf::Message& message);

/// Serializes `message` into `bytes`, replacing what they held. INTERNAL
/// when it cannot.
absl::Status SerializeMessage(const google::protobuf::Message& message, grpc::ByteBuffer& bytes);

}  // namespace hs
