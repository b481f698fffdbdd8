#!/usr/bin/env python3
"""The haptics Python package against the haptic-server at $HS_SERVER with
the demo scene (tests/client/sdk/with_server.sh starts one): the probe, a
2 cm cube at (0.1, 0, 0.1), over the organ, a torus of 400 N/m whose top is
at z = 0.08 m under it."""
import ast
import math
import os
import tempfile
import threading
import time
import unittest

import haptics

SERVER = os.environ["HS_SERVER"]
SCENE = "probe on torus"
PRESSED = (0.1, 0.0, 0.085)  # 5 mm into the organ


def press(device, max_ticks=10000):
    """Down from the probe's home to PRESSED in 100 ticks, then held until the
    probe touches; the last (force, torque)."""
    for k in range(101):
        device.tick(position=(0.1, 0.0, 0.1 - 0.015 * k / 100))
        time.sleep(0.001)
    for _ in range(max_ticks):
        force, torque = device.tick(position=PRESSED)
        if device.flags & haptics.TOUCHING and force[2] > 1:
            break
        time.sleep(0.001)
    return force, torque


class SessionTest(unittest.TestCase):
    def test_health_and_scenes(self):
        # The server serves the demo scene; a scene file makes another, which
        # goes again.
        with haptics.connect(SERVER) as session:
            self.assertEqual(session.health(), "SERVING")
            self.assertEqual([s.name for s in session.scenes()], [SCENE])
            with tempfile.TemporaryDirectory() as folder:
                path = os.path.join(folder, "ball.json")
                with open(path, "w", encoding="utf-8") as f:
                    f.write('{"name": "ball", "objects": [{"name": "ball", "kind": '
                            '"OBJECT_KIND_TOOL", "model": {"procedural": {"sphere": '
                            '{"radiusM": 0.01}}}}]}')
                info = session.create_scene(path)
                self.assertEqual(info.name, "ball")
            self.assertEqual(sorted(s.name for s in session.scenes()), ["ball", SCENE])
            session.delete_scene("ball")

    def test_errors_name_the_grpc_status(self):
        # A scene that is not there: haptics.Error with code NOT_FOUND.
        with haptics.connect(SERVER) as session:
            with self.assertRaises(haptics.Error) as caught:
                session.device("nowhere", "probe")
            self.assertEqual(caught.exception.code, "NOT_FOUND")
            self.assertTrue(str(caught.exception).startswith("NOT_FOUND: "))
            with self.assertRaises(haptics.Error) as caught:
                session.delete_scene("nowhere")
            self.assertEqual(caught.exception.code, "NOT_FOUND")
        with self.assertRaises(haptics.Error) as caught:
            haptics.connect("127.0.0.1:1", connect_timeout=0.3)
        self.assertEqual(caught.exception.code, "UNAVAILABLE")


class DeviceTest(unittest.TestCase):
    def test_pressing_feels_the_organ(self):
        # 5 mm into 400 N/m: about 2 N up (the mesh's top face lies up to
        # 0.8 mm under the torus's); a bad pose raises INVALID_ARGUMENT.
        with haptics.connect(SERVER) as session:
            with session.device(SCENE, "probe") as device:
                force, _ = press(device)
                self.assertAlmostEqual(force[2], 2.0, delta=0.32)
                state = device.state()
                self.assertTrue(state.connected)
                self.assertGreater(state.models, 0)
                with self.assertRaises(haptics.Error) as caught:
                    device.tick(position=(math.nan, 0, 0))
                self.assertEqual(caught.exception.code, "INVALID_ARGUMENT")

    def test_without_the_local_model_the_servers_force_is_felt(self):
        # local_model=False: the force of the newest frame, the same 2 N
        # once the server has held the pressed pose for half a second.
        with haptics.connect(SERVER) as session:
            with session.device(SCENE, "probe", local_model=False, frame_rate_hz=100) as device:
                press(device, max_ticks=500)  # it never says it touches
                force, _ = device.tick(position=PRESSED)
                self.assertAlmostEqual(force[2], 2.0, delta=0.32)
                self.assertTrue(device.flags & haptics.CONNECTED)
                self.assertEqual(device.state().models, 0)

    def test_watch_sees_the_contact(self):
        # A viewer's callback sees the probe's contact with the organ.
        with haptics.connect(SERVER) as session:
            seen = threading.Event()

            def on_frame(frame):
                for tool in frame.tools:
                    if tool.tool == "probe" and any(c.object == "organ" for c in tool.contacts):
                        seen.set()

            with session.watch(SCENE, poses=False, on_frame=on_frame) as watcher:
                with session.device(SCENE, "probe") as device:
                    press(device)
                    for _ in range(10000):
                        if seen.is_set():
                            break
                        device.tick(position=PRESSED)
                        time.sleep(0.001)
                self.assertTrue(seen.is_set())
                frame = watcher.latest()
                self.assertIsNotNone(frame)
                self.assertGreater(frame.step, 0)


class StubsTest(unittest.TestCase):
    def test_stubs_name_what_the_module_has(self):
        # Every class, member, function and parameter __init__.pyi declares
        # is in the module (pybind11's signatures name the parameters).
        stubs = os.path.join(os.path.dirname(haptics.__file__), "__init__.pyi")
        with open(stubs, encoding="utf-8") as f:
            tree = ast.parse(f.read())
        classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}

        def members(node):
            for base in node.bases:
                if isinstance(base, ast.Name) and base.id in classes:
                    yield from members(classes[base.id])
            for item in node.body:
                if isinstance(item, ast.AnnAssign):
                    yield item.target.id, None
                elif isinstance(item, ast.FunctionDef) and item.name != "__init__":
                    yield item.name, item

        def check_parameters(runtime, function, where):
            names = [a.arg for a in function.args.args + function.args.kwonlyargs if a.arg != "self"]
            signature = (runtime.__doc__ or "").split("\n", 1)[0]
            for name in names:
                self.assertIn(f"{name}:", signature, f"{where}: parameter {name}")

        for name, node in classes.items():
            if name.startswith("_") or name == "Error":
                continue  # stubs only, or plain Python
            runtime = getattr(haptics, name, None) or getattr(haptics._client, name, None)
            self.assertIsNotNone(runtime, f"class {name}")
            for member, function in members(node):
                self.assertTrue(hasattr(runtime, member), f"{name}.{member}")
                if function is not None and not member.startswith("__") and \
                        not any(isinstance(d, ast.Name) and d.id == "property"
                                for d in function.decorator_list):
                    check_parameters(getattr(runtime, member), function, f"{name}.{member}")
        for node in tree.body:
            if isinstance(node, ast.FunctionDef):
                self.assertTrue(hasattr(haptics, node.name), node.name)
                check_parameters(getattr(haptics, node.name), node, node.name)
            elif isinstance(node, ast.AnnAssign):
                self.assertTrue(hasattr(haptics, node.target.id), node.target.id)


if __name__ == "__main__":
    unittest.main()
