#ifndef HAPTICS_CLIENT_C_H_
#define HAPTICS_CLIENT_C_H_
/* The client SDK's C API (docs/sdk.md), in libhaptics_client as the C++
 * API. A stable ABI: structs passed in start with `struct_size` (set it to
 * sizeof the struct you were compiled with; fields past it take their
 * defaults), so that later versions may add fields at the end; functions
 * are only added. Errors: NULL or a negative number, and hs_last_error()
 * on the same thread says why ("NOT_FOUND: no scene 'x'").
 *
 * Threads: hs_device_tick may be called from a real-time thread (it
 * neither blocks, nor locks, nor allocates); every other function may
 * block on the network. */

#include <stddef.h>
#include <stdint.h>

#include "haptics/export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hs_session hs_session;
typedef struct hs_device hs_device;

typedef struct hs_session_options {
  size_t struct_size;
  /* PEM files; tls_ca_file set: TLS. NULL or "": unset. */
  const char* tls_ca_file;
  const char* tls_cert_file;
  const char* tls_key_file;
  const char* tls_server_name;
  /* The bearer token; NULL: token_file, else HAPTIC_TOKEN, else none. */
  const char* token;
  const char* token_file;
  /* Seconds; <= 0: the default (5 to connect, 10 per request). */
  double connect_timeout_s;
  double call_timeout_s;
} hs_session_options;

typedef struct hs_device_options {
  size_t struct_size;
  /* Poses sent and frames asked for per second; <= 0: 250. */
  double rate_hz;
  /* The caller's tick period, seconds; <= 0: 0.001. */
  double tick_s;
  /* Non-zero: take the tool from the device that holds it (admin role). */
  int take_over;
  /* Seconds to wait for the stream's first frame; <= 0: the session's
   * connect timeout. */
  double open_timeout_s;
  /* Frames asked for per second; <= 0: rate_hz. */
  double frame_rate_hz;
  /* Non-zero: no local model; hs_device_tick returns the force of the
   * newest frame, a round trip old (for a link of a few milliseconds). */
  int server_force;
} hs_device_options;

/* hs_device_tick's result and flags. */
enum {
  HS_TICK_OK = 0,
  HS_TICK_INVALID_POSE = -1,    /* not finite or not unit: the last force */
  HS_TICK_INVALID_ARGUMENT = -2 /* a NULL pointer: zero force */
};
enum {
  HS_FLAG_CONNECTED = 1,
  HS_FLAG_HAS_MODEL = 2,
  HS_FLAG_TOUCHING = 4,
  HS_FLAG_CLAMPED = 8,
  HS_FLAG_BEYOND_VALIDITY = 16
};

typedef struct hs_device_state {
  size_t struct_size;
  int connected;
  double round_trip_s; /* -1: none yet */
  double model_age_s;  /* -1: none yet */
  int64_t beyond_validity_ticks;
  int64_t reconnects;
  int64_t frames;
  int64_t models;
  int64_t rejected_poses;
  int closed; /* the server ended the stream for good */
} hs_device_state;

/* The library's version, "MAJOR.MINOR.PATCH". */
HAPTICS_EXPORT const char* hs_version(void);

/* options may be NULL: plaintext, no token (but HAPTIC_TOKEN). NULL on
 * failure. */
HAPTICS_EXPORT hs_session* hs_session_open(const char* address, const hs_session_options* options);
HAPTICS_EXPORT void hs_session_close(hs_session* session);
/* "SERVING", ... into buffer (at most size bytes with the NUL); 0, or -1. */
HAPTICS_EXPORT int hs_session_health(hs_session* session, char* buffer, size_t size);
/* A scene from a SceneSpec file (text, or JSON for *.json); name may be
 * NULL (the file's). 0, or -1. */
HAPTICS_EXPORT int hs_session_create_scene(hs_session* session, const char* spec_file,
                                           const char* name);
HAPTICS_EXPORT int hs_session_delete_scene(hs_session* session, const char* name);

/* options may be NULL: force, friction and the local model at 250 Hz. NULL
 * on failure (unknown scene or tool, a refused token, no server). */
HAPTICS_EXPORT hs_device* hs_device_open(hs_session* session, const char* scene, const char* tool,
                                         const hs_device_options* options);
/* One tick: never blocks. HS_TICK_OK or a negative HS_TICK_*; flags (may
 * be NULL) receives HS_FLAG_* bits. */
HAPTICS_EXPORT int hs_device_tick_flags(hs_device* device, const double position_m[3],
                                        const double orientation_wxyz[4], double force_n[3],
                                        double torque_nm[3], uint32_t* flags);
HAPTICS_EXPORT int hs_device_tick(hs_device* device, const double position_m[3],
                                  const double orientation_wxyz[4], double force_n[3],
                                  double torque_nm[3]);
/* Fills state (set state->struct_size); 0, or -1. */
HAPTICS_EXPORT int hs_device_state_get(const hs_device* device, hs_device_state* state);
HAPTICS_EXPORT void hs_device_close(hs_device* device);

/* Why the last call on this thread failed; "" when none has. */
HAPTICS_EXPORT const char* hs_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* HAPTICS_CLIENT_C_H_ */
