// A haptic device's 1 kHz loop on the C++ SDK (docs/sdk.md): a simulated
// hand (0.15 kg, held by a 200 N/m, 3 N*s/m grip toward a target that goes
// 2 cm down into the demo scene's organ over 1 s and stays there) moves the
// device; each tick sends its pose and applies the force the SDK renders.
//
//   device_loop [HOST:PORT]      (default 127.0.0.1:50051, the demo scene)
//
// Prints the largest upward force felt and the state of the link.
#include <haptics/client.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

int main(int argc, char** argv) {
  const char* address = argc > 1 ? argv[1] : "127.0.0.1:50051";
  auto session = haptics::Session::Connect(address);
  if (!session.ok()) {
    std::fprintf(stderr, "connect: %s\n", session.error().ToString().c_str());
    return 1;
  }
  auto device = (*session)->OpenDevice("probe on torus", "probe");
  if (!device.ok()) {
    std::fprintf(stderr, "open: %s\n", device.error().ToString().c_str());
    return 1;
  }
  // The hand, at the probe's home (0.1, 0, 0.1).
  constexpr double kMass = 0.15, kGrip = 200, kGripDamping = 3, kTick = 1e-3;
  double z = 0.1, vz = 0, max_force = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 2000; ++k) {
    std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * k));
    const double target = 0.1 - 0.02 * std::min(1.0, k * kTick);
    haptics::Pose pose;
    pose.position_m[0] = 0.1;
    pose.position_m[2] = z;
    const haptics::TickOutput out = (*device)->Tick(pose);  // never blocks
    // The device pushes the hand back with the rendered force.
    const double a = (kGrip * (target - z) - kGripDamping * vz + out.force_n[2]) / kMass;
    vz += a * kTick;
    z += vz * kTick;
    max_force = std::max(max_force, out.force_n[2]);
  }
  const haptics::DeviceState state = (*device)->State();
  std::printf("hand at z = %.4f m; largest force up %.3f N\n", z, max_force);
  std::printf("connected %d, round trip %.2f ms, models %lld, reconnects %lld\n", state.connected,
              state.round_trip_s * 1e3, static_cast<long long>(state.models),
              static_cast<long long>(state.reconnects));
  std::printf("force_z_n=%.6f\n", max_force);
  return 0;
}
