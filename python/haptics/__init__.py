"""The haptic simulation service's client SDK (docs/sdk.md).

    import haptics
    with haptics.connect("127.0.0.1:50051") as session:
        with session.device("probe on torus", "probe") as device:
            force, torque = device.tick(position=(0.1, 0, 0.085))

Every call that fails raises haptics.Error, whose ``code`` is the gRPC
status name ("NOT_FOUND", "UNAVAILABLE", ...).
"""

from . import _client


class Error(Exception):
    """A failed call: ``code`` is the gRPC status name, ``message`` why."""

    def __init__(self, code, message):
        super().__init__(f"{code}: {message}")
        self.code = code
        self.message = message


_client.set_error_type(Error)

# Flags of Device.flags after a tick (haptics/device.h's TickFlag).
CONNECTED = 1
HAS_MODEL = 2
TOUCHING = 4
CLAMPED = 8
BEYOND_VALIDITY = 16

connect = _client.connect
Session = _client.Session
Device = _client.Device
Watcher = _client.Watcher
Frame = _client.Frame
__version__ = _client.version()

__all__ = [
    "BEYOND_VALIDITY", "CLAMPED", "CONNECTED", "Device", "Error", "Frame", "HAS_MODEL",
    "Session", "TOUCHING", "Watcher", "connect",
]
