#!/usr/bin/env python3
"""A haptic device on the Python SDK (docs/sdk.md): the demo scene's probe
goes 1.5 cm down from its home in 0.5 s and stays 1 s, ticking at about
1 kHz (Python's loop is not real time: a device's own loop would be C or
C++).

    device.py [HOST:PORT]      (default 127.0.0.1:50051, the demo scene)
"""
import sys
import time

import haptics

address = sys.argv[1] if len(sys.argv) > 1 else "127.0.0.1:50051"
with haptics.connect(address) as session:
    with session.device("probe on torus", "probe") as device:
        largest = 0.0
        start = time.monotonic()
        for k in range(1500):
            z = 0.1 - 0.015 * min(1.0, k / 500)
            force, torque = device.tick(position=(0.1, 0.0, z))
            largest = max(largest, force[2])
            time.sleep(max(0.0, start + (k + 1) * 1e-3 - time.monotonic()))
        state = device.state()
        print(f"largest force up {largest:.3f} N; round trip {state.round_trip_s * 1e3:.2f} ms")
        print(f"force_z_n={largest:.6f}")
