/* The C API (haptics/client_c.h), compiled as C, against the haptic-server
 * at $HS_SERVER with the demo scene (with_server.sh starts one): the probe
 * pressed 5 mm into the organ (400 N/m) feels about 2 N up; errors name
 * their gRPC status. Exit 0 when every check holds. */
#define _POSIX_C_SOURCE 199309L
#include "haptics/client_c.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int failures = 0;

#define CHECK(cond)                                                      \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                        \
    }                                                                    \
  } while (0)

static int starts_with(const char* text, const char* prefix) {
  return strncmp(text, prefix, strlen(prefix)) == 0;
}

static void sleep_ms(long ms) {
  struct timespec t = {0, ms * 1000000L};
  nanosleep(&t, NULL);
}

/* hs_last_error of a thread that has made no failing call: "". */
static void* last_error_elsewhere(void* out) {
  *(int*)out = strcmp(hs_last_error(), "") == 0;
  return NULL;
}

int main(void) {
  const char* address = getenv("HS_SERVER");
  if (address == NULL) {
    fprintf(stderr, "HS_SERVER is not set\n");
    return 2;
  }
  CHECK(starts_with(hs_version(), "1."));
  hs_session* session = hs_session_open(address, NULL);
  if (session == NULL) {
    fprintf(stderr, "hs_session_open: %s\n", hs_last_error());
    return 1;
  }
  char health[32];
  CHECK(hs_session_health(session, health, sizeof health) == 0);
  CHECK(strcmp(health, "SERVING") == 0);

  CHECK(hs_device_open(session, "no such scene", "probe", NULL) == NULL);
  CHECK(starts_with(hs_last_error(), "NOT_FOUND: "));
  CHECK(strstr(hs_last_error(), "no such scene") != NULL);

  /* A caller built when the options struct ended before rate_hz: the
   * rest takes its defaults. */
  hs_device_options old_options;
  memset(&old_options, 0xff, sizeof old_options);
  old_options.struct_size = sizeof(size_t);
  hs_device* device = hs_device_open(session, "probe on torus", "probe", &old_options);
  if (device == NULL) {
    fprintf(stderr, "hs_device_open: %s\n", hs_last_error());
    return 1;
  }
  const double q[4] = {1, 0, 0, 0};
  double p[3] = {0.1, 0, 0.1};
  double force[3] = {0, 0, 0}, torque[3] = {0, 0, 0};
  uint32_t flags = 0;
  for (int k = 0; k <= 100; ++k) {
    p[2] = 0.1 - 0.015 * k / 100.0;
    CHECK(hs_device_tick(device, p, q, force, torque) == HS_TICK_OK);
    sleep_ms(1);
  }
  for (int k = 0; k < 10000; ++k) {
    CHECK(hs_device_tick_flags(device, p, q, force, torque, &flags) == HS_TICK_OK);
    if ((flags & HS_FLAG_TOUCHING) && force[2] > 1) break;
    sleep_ms(1);
  }
  printf("force %.3f %.3f %.3f N, flags %u\n", force[0], force[1], force[2], flags);
  CHECK(fabs(force[2] - 2.0) < 0.32);
  CHECK(flags & HS_FLAG_CONNECTED);

  const double bad[3] = {NAN, 0, 0};
  double held[3];
  CHECK(hs_device_tick(device, bad, q, held, torque) == HS_TICK_INVALID_POSE);
  CHECK(held[2] == force[2]);
  CHECK(hs_device_tick(NULL, p, q, held, torque) == HS_TICK_INVALID_ARGUMENT);

  hs_device_state state;
  state.struct_size = sizeof state;
  CHECK(hs_device_state_get(device, &state) == 0);
  CHECK(state.connected == 1);
  CHECK(state.models > 0);
  CHECK(state.rejected_poses == 1);
  hs_device_close(device);

  /* Without the local model: the server's force at the pressed pose, the
   * same 2 N once it has held it for half a second; no model comes. */
  hs_device_options server_force;
  memset(&server_force, 0, sizeof server_force);
  server_force.struct_size = sizeof server_force;
  server_force.frame_rate_hz = 100;
  server_force.server_force = 1;
  device = hs_device_open(session, "probe on torus", "probe", &server_force);
  if (device == NULL) {
    fprintf(stderr, "hs_device_open: %s\n", hs_last_error());
    return 1;
  }
  for (int k = 0; k <= 600; ++k) {
    p[2] = k <= 100 ? 0.1 - 0.015 * k / 100.0 : 0.085;
    CHECK(hs_device_tick_flags(device, p, q, force, torque, &flags) == HS_TICK_OK);
    sleep_ms(1);
  }
  printf("server's force %.3f %.3f %.3f N, flags %u\n", force[0], force[1], force[2], flags);
  CHECK(fabs(force[2] - 2.0) < 0.32);
  CHECK(flags == HS_FLAG_CONNECTED);
  CHECK(hs_device_state_get(device, &state) == 0);
  CHECK(state.models == 0);
  hs_device_close(device);
  hs_session_close(session);

  hs_session_options quick;
  memset(&quick, 0, sizeof quick);
  quick.struct_size = sizeof quick;
  quick.connect_timeout_s = 0.3;
  CHECK(hs_session_open("127.0.0.1:1", &quick) == NULL);
  CHECK(starts_with(hs_last_error(), "UNAVAILABLE: "));
  /* The message is this thread's: another thread has none. */
  int empty_elsewhere = 0;
  pthread_t thread;
  CHECK(pthread_create(&thread, NULL, last_error_elsewhere, &empty_elsewhere) == 0);
  pthread_join(thread, NULL);
  CHECK(empty_elsewhere);
  CHECK(starts_with(hs_last_error(), "UNAVAILABLE: "));
  return failures == 0 ? 0 : 1;
}
