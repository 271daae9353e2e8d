"""The travel of a tillage tool (a [[mesh]] with a [mesh.motion]) through its bed, and the steady
window of its pass: shared by scripts/plot_draft.py and scripts/tillage_study.py.

The travel direction d is that of the tool's first non-zero keyframe velocity; the tool moves at
the speed u(t) = v(t)·d, linear between keyframes and zero outside them (docs/input.md,
[mesh.motion]); it must never move against d. Along d, the tool at t = 0 spans [back, front]
(its STL vertices placed by scale, rotation and offset) and its length is front − back; the bed
spans the domain's extent along d, [near face, far face] (the bin the bed fills). The steady
window runs from the time the tool's front has gone ENTRY past the bed's near face (default: the
tool's length, so the whole tool is in the bed) to the earliest of: the time its front is MARGIN
before the far face (default: the tool's length again), the last keyframe (the tool stops) and
the end of the run. An empty window is an error.
"""
import math
import pathlib
import struct
import tomllib
from dataclasses import dataclass


class SceneError(Exception):
    """A scene (or its mesh) that the travel rule cannot use; the message names the file."""


@dataclass(frozen=True)
class Tool:
    """The [[mesh]] named `name`, number `index` of the scene `path`, and its motion."""
    path: pathlib.Path
    name: str
    index: int
    mesh: dict
    travel: tuple
    up: tuple
    times: tuple
    velocities: tuple
    in_implement: bool  # moved by the [[implement]] that names it, not by its own motion

    def speeds(self):
        """The keyframe speeds along the travel."""
        return [dot(v, self.travel) for v in self.velocities]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def load_scene(path):
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as error:
        raise SceneError(f"cannot read the scene {path}: {error}") from None


def find_tool(scene, path, name):
    """The moving mesh `name` of `scene` (read from `path`) as a Tool."""
    path = pathlib.Path(path)
    meshes = scene.get("mesh", [])
    index = next((i for i, m in enumerate(meshes) if m.get("name", f"mesh{i}") == name), None)
    if index is None:
        raise SceneError(f"{path} has no [[mesh]] named '{name}'")
    implement = next((im for im in scene.get("implement", []) if name in im.get("meshes", [])),
                     None)
    motion = (implement if implement else meshes[index]).get("motion", {})
    moving = [v for v in motion.get("velocities", []) if any(c != 0 for c in v)]
    if not moving:
        raise SceneError(f"mesh '{name}' of {path} does not move "
                         "(no non-zero [mesh.motion] or [implement.motion] velocity)")
    if "times" not in motion:
        raise SceneError(f"mesh '{name}' of {path}: its motion has no times")
    gravity = scene.get("simulation", {}).get("gravity", [0, 0, -9.81])
    default_up = [-c for c in gravity] if any(c != 0 for c in gravity) else [0, 0, 1]
    up = unit((implement or {}).get("up", default_up))
    forward = unit(moving[0])
    if implement:  # the implement's frame, as the solver makes it: forward normal to up
        forward = implement.get("forward", moving[0])
        forward = unit([f - dot(forward, up) * u for f, u in zip(forward, up)])
    return Tool(path, name, index, meshes[index], forward, up, tuple(motion["times"]),
                tuple(tuple(v) for v in motion["velocities"]), implement is not None)


def read_stl_vertices(path):
    """The corners of every triangle of a binary or ASCII STL file (docs/input.md, [[mesh]])."""
    data = pathlib.Path(path).read_bytes()
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack("<I", data[80:84])[0]:
        count = struct.unpack("<I", data[80:84])[0]
        return [struct.unpack_from("<3f", data, 84 + 50 * i + 12 * (k + 1))
                for i in range(count) for k in range(3)]
    words = data.decode(errors="replace").split()
    return [tuple(float(w) for w in words[i + 1:i + 4])
            for i, word in enumerate(words) if word == "vertex"]


def rotate(v, axis, angle):
    """`v` turned by `angle` (rad, right-handed) about the unit vector `axis` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    k_cross_v, k_dot_v = cross(axis, v), dot(axis, v)
    return tuple(v[i] * c + k_cross_v[i] * s + axis[i] * k_dot_v * (1 - c) for i in range(3))


def tool_extent(tool):
    """(back, front): the tool's extent along its travel at t = 0."""
    mesh = tool.mesh
    stl = tool.path.parent / mesh.get("file", "")
    try:
        vertices = read_stl_vertices(stl)
    except (OSError, ValueError) as error:
        raise SceneError(f"cannot read the mesh file {stl} of {tool.path}: {error}") from None
    if not vertices:
        raise SceneError(f"the mesh file {stl} of {tool.path} has no triangle")
    axis = unit(mesh.get("rotation_axis", [0, 0, 1]))
    angle = mesh.get("rotation_angle", math.radians(mesh.get("rotation_degrees", 0.0)))
    scale, offset = mesh.get("scale", 1.0), mesh.get("offset", [0, 0, 0])
    along = [dot(rotate([scale * c for c in v], axis, angle), tool.travel) for v in vertices]
    shift = dot(offset, tool.travel)
    return min(along) + shift, max(along) + shift


def domain_extent(scene, direction):
    """The extent of the scene's domain box along the unit vector `direction`."""
    low, high = scene["domain"]["min"], scene["domain"]["max"]
    corners = [[(low, high)[(k >> a) & 1][a] for a in range(3)] for k in range(8)]
    along = [dot(c, direction) for c in corners]
    return min(along), max(along)


def time_at_travel(times, speeds, distance):
    """The first time at which the tool has travelled `distance` (speeds >= 0, linear between
    keyframes, zero outside them); None when it never does."""
    if distance <= 0:
        return 0.0
    travelled = 0.0
    for t0, t1, u0, u1 in zip(times, times[1:], speeds, speeds[1:]):
        step = (u0 + u1) / 2 * (t1 - t0)
        if step > 0 and travelled + step >= distance:
            rest, slope = distance - travelled, (u1 - u0) / (t1 - t0)
            # u0·τ + slope·τ²/2 = rest, the root written so that neither term cancels
            return t0 + 2 * rest / (u0 + math.sqrt(max(0.0, u0 * u0 + 2 * slope * rest)))
        travelled += step
    return None


def steady_window(tool, scene, run_end, entry=None, margin=None):
    """(start, end) of the steady window of the tool's pass (the rule in this module's
    docstring); entry and margin default to the tool's length along its travel."""
    speeds = tool.speeds()
    if min(speeds) < 0:
        raise SceneError(f"mesh '{tool.name}' of {tool.path} moves against its travel at times; "
                         "the steady window needs a forward pass (give --steady)")
    back, front = tool_extent(tool)
    near, far = domain_extent(scene, tool.travel)
    entry = front - back if entry is None else entry
    margin = front - back if margin is None else margin
    start = time_at_travel(tool.times, speeds, near + entry - front)
    leaving = time_at_travel(tool.times, speeds, far - margin - front)
    end = min(t for t in (run_end, tool.times[-1], leaving) if t is not None)
    if start is None or start >= end:
        reached = "never" if start is None else f"at {start:.4g} s"
        raise SceneError(
            f"no steady window for mesh '{tool.name}' of {tool.path}: its front is {entry:.4g} m "
            f"into the bed {reached}, and the window must end by {end:.4g} s (the tool "
            f"{margin:.4g} m before the bed's far face, its last keyframe or the run's end)")
    return start, end
