# Type stubs of the haptics package (the client SDK, docs/sdk.md).
from types import TracebackType
from typing import Callable, Optional, Self, Sequence, Tuple

Vector = Tuple[float, float, float]
Quaternion = Tuple[float, float, float, float]

__version__: str
CONNECTED: int
HAS_MODEL: int
TOUCHING: int
CLAMPED: int
BEYOND_VALIDITY: int

class Error(Exception):
    code: str
    message: str
    def __init__(self, code: str, message: str) -> None: ...

class Pose:
    @property
    def position(self) -> Vector: ...
    @property
    def orientation(self) -> Quaternion: ...

class Contact:
    object: str
    colliding: bool
    penetrating: bool
    depth: float
    @property
    def normal(self) -> Vector: ...
    @property
    def points(self) -> list[Vector]: ...
    @property
    def time_of_impact(self) -> Optional[float]: ...

class Plane:
    object: str
    gap: float
    stiffness: float
    damping: float
    separating: bool
    @property
    def point(self) -> Vector: ...
    @property
    def normal(self) -> Vector: ...

class LocalModel:
    revision: int
    proxy_pose: Pose
    validity_radius: float
    force_clamp: float
    touching: bool
    planes: list[Plane]

class ToolFrame:
    tool: str
    holder: str
    device_pose: Pose
    proxy_pose: Pose
    force_clamped: bool
    contacts: list[Contact]
    @property
    def force(self) -> Vector: ...
    @property
    def torque(self) -> Vector: ...
    @property
    def local_model(self) -> Optional[LocalModel]: ...

class Frame:
    step: int
    time: float
    dropped_frames: int
    missed_steps: int
    tools: list[ToolFrame]

class SceneInfo:
    name: str
    step: int
    step_s: float
    triangles: int
    devices: int
    viewers: int
    revision: int

class ModelInfo:
    model_id: str
    vertices: int
    triangles: int

class DeviceState:
    connected: bool
    round_trip_s: float
    model_age_s: float
    beyond_validity_ticks: int
    reconnects: int
    frames: int
    models: int
    rejected_poses: int
    closed: bool
    @property
    def last_error(self) -> Optional[str]: ...

class _Closing:
    """Closed by close() or at the end of a with block (stubs only)."""
    def close(self) -> None: ...
    def __enter__(self) -> Self: ...
    def __exit__(
        self,
        exc_type: Optional[type[BaseException]],
        exc: Optional[BaseException],
        tb: Optional[TracebackType],
    ) -> None: ...

class Device(_Closing):
    def tick(
        self, position: Sequence[float], orientation: Sequence[float] = (1.0, 0.0, 0.0, 0.0)
    ) -> Tuple[Vector, Vector]: ...
    @property
    def flags(self) -> int: ...
    def state(self) -> DeviceState: ...

class Watcher(_Closing):
    def latest(self) -> Optional[Frame]: ...
    @property
    def frames(self) -> int: ...
    @property
    def ended(self) -> bool: ...
    def status(self) -> Optional[str]: ...

class Session(_Closing):
    def health(self) -> str: ...
    def scenes(self) -> list[SceneInfo]: ...
    def create_scene(self, path: str, name: Optional[str] = None) -> SceneInfo: ...
    def replace_scene(self, path: str, name: Optional[str] = None) -> SceneInfo: ...
    def delete_scene(self, name: str) -> None: ...
    def upload_model(self, path: str, name: Optional[str] = None) -> ModelInfo: ...
    def delete_model(self, model_id: str) -> None: ...
    def device(
        self,
        scene: str,
        tool: str,
        *,
        rate_hz: float = 250.0,
        frame_rate_hz: float = 0.0,
        local_model: bool = True,
        max_passivity_damping: float = 30.0,
        tick_s: float = 0.001,
        take_over: bool = False,
        open_timeout: float = 0.0,
    ) -> Device: ...
    def watch(
        self,
        scene: str,
        *,
        poses: bool = True,
        contacts: bool = True,
        forces: bool = True,
        local_model: bool = False,
        frame_rate_hz: float = 0.0,
        on_frame: Optional[Callable[[Frame], None]] = None,
        open_timeout: float = 0.0,
    ) -> Watcher: ...

def connect(
    address: str,
    *,
    tls_ca: Optional[str] = None,
    tls_cert: Optional[str] = None,
    tls_key: Optional[str] = None,
    tls_server_name: Optional[str] = None,
    token: Optional[str] = None,
    token_file: Optional[str] = None,
    connect_timeout: float = 5.0,
    call_timeout: float = 10.0,
) -> Session: ...
