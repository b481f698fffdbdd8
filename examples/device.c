/* A haptic device on the C API (docs/sdk.md): the demo scene's probe goes
 * 1.5 cm down from its home in 0.5 s and stays 1 s, ticking at 1 kHz.
 *
 *   device [HOST:PORT]      (default 127.0.0.1:50051, the demo scene)
 *
 * Prints the largest upward force felt. */
#define _POSIX_C_SOURCE 199309L
#include <haptics/client_c.h>
#include <stdio.h>
#include <time.h>

int main(int argc, char** argv) {
  const char* address = argc > 1 ? argv[1] : "127.0.0.1:50051";
  hs_session* session = hs_session_open(address, NULL);
  if (session == NULL) {
    fprintf(stderr, "connect: %s\n", hs_last_error());
    return 1;
  }
  hs_device* device = hs_device_open(session, "probe on torus", "probe", NULL);
  if (device == NULL) {
    fprintf(stderr, "open: %s\n", hs_last_error());
    hs_session_close(session);
    return 1;
  }
  const double orientation[4] = {1, 0, 0, 0};
  double position[3] = {0.1, 0, 0.1};
  double force[3], torque[3], max_force = 0;
  const struct timespec tick = {0, 1000000L};
  for (int k = 0; k < 1500; ++k) {
    position[2] = 0.1 - 0.015 * (k < 500 ? k / 500.0 : 1.0);
    if (hs_device_tick(device, position, orientation, force, torque) != HS_TICK_OK) break;
    if (force[2] > max_force) max_force = force[2];
    nanosleep(&tick, NULL);
  }
  printf("largest force up %.3f N\n", max_force);
  printf("force_z_n=%.6f\n", max_force);
  hs_device_close(device);
  hs_session_close(session);
  return 0;
}
