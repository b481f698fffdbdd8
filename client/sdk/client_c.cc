// The C API (haptics/client_c.h) over the C++ one.
#include "haptics/client_c.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>

#include "haptics/client.h"

struct hs_session {
  std::unique_ptr<haptics::Session> session;
};

struct hs_device {
  std::unique_ptr<haptics::Device> device;
};

namespace {

thread_local std::string last_error;

void Fail(const haptics::Error& error) { last_error = error.ToString(); }
void FailArgument(const char* what) { last_error = std::string("INVALID_ARGUMENT: ") + what; }

// A field of a caller's struct when its struct_size covers it, else
// `fallback`: a caller built against an older, shorter struct.
#define HS_FIELD(s, field, fallback)                                                             \
  ((s) != nullptr && (s)->struct_size >=                                                         \
                         offsetof(std::remove_cv_t<std::remove_pointer_t<decltype(s)>>, field) + \
                             sizeof((s)->field)                                                  \
       ? (s)->field                                                                              \
       : (fallback))

std::string Text(const char* s) { return s == nullptr ? std::string() : std::string(s); }

}  // namespace

extern "C" {

const char* hs_version(void) {
#define HS_STR2(x) #x
#define HS_STR(x) HS_STR2(x)
  return HS_STR(HAPTICS_CLIENT_VERSION_MAJOR) "." HS_STR(HAPTICS_CLIENT_VERSION_MINOR) "." HS_STR(
      HAPTICS_CLIENT_VERSION_PATCH);
}

hs_session* hs_session_open(const char* address, const hs_session_options* o) {
  if (address == nullptr) {
    FailArgument("no address");
    return nullptr;
  }
  haptics::SessionOptions options;
  options.tls.ca_file = Text(HS_FIELD(o, tls_ca_file, nullptr));
  options.tls.cert_file = Text(HS_FIELD(o, tls_cert_file, nullptr));
  options.tls.key_file = Text(HS_FIELD(o, tls_key_file, nullptr));
  options.tls.server_name = Text(HS_FIELD(o, tls_server_name, nullptr));
  options.token = Text(HS_FIELD(o, token, nullptr));
  options.token_file = Text(HS_FIELD(o, token_file, nullptr));
  if (const double s = HS_FIELD(o, connect_timeout_s, 0.0); s > 0) options.connect_timeout_s = s;
  if (const double s = HS_FIELD(o, call_timeout_s, 0.0); s > 0) options.call_timeout_s = s;
  haptics::Result<std::unique_ptr<haptics::Session>> session =
      haptics::Session::Connect(address, options);
  if (!session.ok()) {
    Fail(session.error());
    return nullptr;
  }
  return new hs_session{*std::move(session)};
}

void hs_session_close(hs_session* session) { delete session; }

int hs_session_health(hs_session* session, char* buffer, size_t size) {
  if (session == nullptr || buffer == nullptr || size == 0) {
    FailArgument("no session or buffer");
    return -1;
  }
  haptics::Result<std::string> health = session->session->Health();
  if (!health.ok()) {
    Fail(health.error());
    return -1;
  }
  std::strncpy(buffer, health->c_str(), size - 1);
  buffer[size - 1] = '\0';
  return 0;
}

int hs_session_create_scene(hs_session* session, const char* spec_file, const char* name) {
  if (session == nullptr || spec_file == nullptr) {
    FailArgument("no session or file");
    return -1;
  }
  haptics::Result<haptics::SceneInfo> info = session->session->CreateScene(spec_file, Text(name));
  if (!info.ok()) {
    Fail(info.error());
    return -1;
  }
  return 0;
}

int hs_session_delete_scene(hs_session* session, const char* name) {
  if (session == nullptr || name == nullptr) {
    FailArgument("no session or name");
    return -1;
  }
  if (const haptics::Error error = session->session->DeleteScene(name); !error.ok()) {
    Fail(error);
    return -1;
  }
  return 0;
}

hs_device* hs_device_open(hs_session* session, const char* scene, const char* tool,
                          const hs_device_options* o) {
  if (session == nullptr || scene == nullptr || tool == nullptr) {
    FailArgument("no session, scene or tool");
    return nullptr;
  }
  haptics::DeviceOptions options;
  if (const double hz = HS_FIELD(o, rate_hz, 0.0); hz > 0) options.rate_hz = hz;
  if (const double s = HS_FIELD(o, tick_s, 0.0); s > 0) options.tick_s = s;
  options.take_over = HS_FIELD(o, take_over, 0) != 0;
  options.open_timeout_s = HS_FIELD(o, open_timeout_s, 0.0);
  if (const double hz = HS_FIELD(o, frame_rate_hz, 0.0); hz > 0) options.frame_rate_hz = hz;
  options.local_model = HS_FIELD(o, server_force, 0) == 0;
  haptics::Result<std::unique_ptr<haptics::Device>> device =
      session->session->OpenDevice(scene, tool, options);
  if (!device.ok()) {
    Fail(device.error());
    return nullptr;
  }
  return new hs_device{*std::move(device)};
}

int hs_device_tick_flags(hs_device* device, const double position_m[3],
                         const double orientation_wxyz[4], double force_n[3], double torque_nm[3],
                         uint32_t* flags) {
  if (device == nullptr || position_m == nullptr || orientation_wxyz == nullptr ||
      force_n == nullptr) {
    // No message: writing the thread's error string could allocate.
    if (force_n != nullptr) force_n[0] = force_n[1] = force_n[2] = 0;
    return HS_TICK_INVALID_ARGUMENT;
  }
  haptics::Pose pose;
  std::memcpy(pose.position_m, position_m, sizeof pose.position_m);
  std::memcpy(pose.orientation_wxyz, orientation_wxyz, sizeof pose.orientation_wxyz);
  const haptics::TickOutput out = device->device->Tick(pose);
  std::memcpy(force_n, out.force_n, sizeof out.force_n);
  if (torque_nm != nullptr) std::memcpy(torque_nm, out.torque_nm, sizeof out.torque_nm);
  if (flags != nullptr) *flags = out.flags;
  return out.ok() ? HS_TICK_OK : HS_TICK_INVALID_POSE;
}

int hs_device_tick(hs_device* device, const double position_m[3], const double orientation_wxyz[4],
                   double force_n[3], double torque_nm[3]) {
  return hs_device_tick_flags(device, position_m, orientation_wxyz, force_n, torque_nm, nullptr);
}

int hs_device_state_get(const hs_device* device, hs_device_state* state) {
  if (device == nullptr || state == nullptr) {
    FailArgument("no device or state");
    return -1;
  }
  const haptics::DeviceState s = device->device->State();
  hs_device_state full{};
  full.struct_size = sizeof full;
  full.connected = s.connected ? 1 : 0;
  full.round_trip_s = s.round_trip_s;
  full.model_age_s = s.model_age_s;
  full.beyond_validity_ticks = s.beyond_validity_ticks;
  full.reconnects = s.reconnects;
  full.frames = s.frames;
  full.models = s.models;
  full.rejected_poses = s.rejected_poses;
  full.closed = s.closed ? 1 : 0;
  // Only as much as the caller's struct holds.
  const size_t size = std::min(state->struct_size, sizeof full);
  std::memcpy(reinterpret_cast<char*>(state) + sizeof(size_t),
              reinterpret_cast<const char*>(&full) + sizeof(size_t),
              size > sizeof(size_t) ? size - sizeof(size_t) : 0);
  return 0;
}

void hs_device_close(hs_device* device) { delete device; }

const char* hs_last_error(void) { return last_error.c_str(); }

}  // extern "C"
