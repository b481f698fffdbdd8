#!/usr/bin/env python3
"""A viewer on the Python SDK (docs/sdk.md): prints each tool's contacts as
the frames come, for a while.

    viewer.py [HOST:PORT] [--scene NAME] [--duration S] [--contacts N]

Stops after S seconds (default 10) or after N frames with a contact.
"""
import argparse
import queue

import haptics

parser = argparse.ArgumentParser()
parser.add_argument("address", nargs="?", default="127.0.0.1:50051")
parser.add_argument("--scene", default="probe on torus")
parser.add_argument("--duration", type=float, default=10.0)
parser.add_argument("--contacts", type=int, default=0)
args = parser.parse_args()

frames = queue.Queue()
with haptics.connect(args.address) as session:
    # The callback runs on the watcher's thread: hand the frames over.
    with session.watch(args.scene, poses=False, forces=True, frame_rate_hz=50,
                       on_frame=frames.put):
        touching = 0
        try:
            while True:
                frame = frames.get(timeout=args.duration)
                for tool in frame.tools:
                    for c in tool.contacts:
                        print(f"step {frame.step} {tool.tool} touches {c.object}: "
                              f"depth {c.depth * 1e3:.2f} mm, force {tool.force[2]:.3f} N up",
                              flush=True)
                if any(tool.contacts for tool in frame.tools):
                    touching += 1
                    if args.contacts and touching >= args.contacts:
                        break
        except queue.Empty:
            pass
