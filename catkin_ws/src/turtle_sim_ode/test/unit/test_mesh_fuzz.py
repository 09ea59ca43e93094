"""Property-based tests of the mesh loaders (issue #26): generated STL (binary and ASCII), OBJ and Collada files with
hostile numbers, counts and structure. Each is read on its own, then spawned as the collision of a static model and
as the visual of a model in front of a camera that renders (as when an image topic has a subscriber). Whatever the
file: reading gives finite triangles (at most MAX_TRIANGLES) or a ModelError naming the file; the spawn is a clean
refusal or a success; the camera renders, every depth NaN or within its clip range; the world steps on with sim time
advancing and every pose finite; all within test_fuzz's answer time (a ratio to a reference spawn); nothing is written but the file the test writes in its scratch folder.

CI runs a bounded number of examples with a fixed seed; scripts/fuzz_sim.sh runs many more."""
from __future__ import annotations

import math
import os
import struct
import sys
import time
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import numpy as np
import pytest
from conftest import FIXTURES, PACKAGE_ROOT
from hypothesis import event, given, seed
from hypothesis import strategies as st
from test_camera import CAMERA_URDF
from test_fuzz import CLEAN_REFUSALS, FUZZ, HOSTILE_NUMBERS, HOSTILE_TEXTS, SEED, assert_answered_in_time, rarely
from workspace_testing.timing import timed

from turtle_sim_ode.models.meshes import MAX_TRIANGLES, read_mesh
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.world.simulation import Simulation

sys.path.insert(0, str(FIXTURES))
from make_meshes import box_triangles, collada  # noqa: E402

STEPS_AFTER = 100
CLIP = (0.05, 8.0)  # CAMERA_URDF's depth camera clip range

plausible = st.floats(min_value=-2.0, max_value=2.0).map(lambda v: 0.0 if abs(v) < sys.float_info.min else v)
hostile_text = st.one_of(st.sampled_from([repr(v) for v in HOSTILE_NUMBERS] + HOSTILE_TEXTS), st.floats().map(repr))
number_text = rarely(plausible.map(repr), hostile_text, 12)
floats32 = rarely(plausible, st.sampled_from([math.nan, math.inf, -math.inf, 3.4e38, -3.4e38, 1e-45]), 12)
index_text = rarely(
    st.integers(min_value=0, max_value=12).map(str),
    st.sampled_from(["-1", "0", "10" * 10, "1e20", "inf", "nan", "x", "3.5", "99999999999999999999999", "-0"]),
    10,
)
counts = st.integers(min_value=1, max_value=12)


def good_triangles(draw: Callable) -> List[Tuple[Tuple[float, float, float], ...]]:
    """A small box, so that a file that parses has something to collide and draw."""
    low = tuple(draw(plausible) for _ in range(3))
    size = tuple(draw(st.floats(min_value=0.05, max_value=0.5)) for _ in range(3))
    return box_triangles(low, tuple(a + b for a, b in zip(low, size)))  # type: ignore[arg-type]


@st.composite
def binary_stls(draw: Callable) -> Tuple[str, bytes]:
    triangles = good_triangles(draw)[: draw(counts)]
    vertices = [[draw(floats32) if draw(st.integers(0, 20)) == 0 else c for v in t for c in v] for t in triangles]
    records = b"".join(struct.pack("<12fH", 0.0, 0.0, 0.0, *values, 0) for values in vertices)
    header = draw(st.sampled_from([b"binary", b"solid looks ascii", b""])).ljust(80, b" ")
    count = draw(rarely(st.just(len(triangles)), st.sampled_from([0, 1, len(triangles) + 1, 2**32 - 1, 2**31]), 6))
    tail = draw(rarely(st.just(b""), st.binary(max_size=60), 8))
    return "mesh.stl", header + struct.pack("<I", count) + records + tail


@st.composite
def ascii_stls(draw: Callable) -> Tuple[str, bytes]:
    lines = ["solid fuzz"]
    for triangle in good_triangles(draw)[: draw(counts)]:
        lines += ["facet normal 0 0 0", "outer loop"]
        for vertex in triangle:
            values = [draw(number_text) if draw(st.integers(0, 12)) == 0 else repr(c) for c in vertex]
            lines.append("vertex " + " ".join(values[: draw(rarely(st.just(3), st.integers(0, 4), 20))]))
        lines += ["endloop", "endfacet"]
    lines.append("endsolid fuzz")
    if draw(st.integers(0, 10)) == 0:  # structure: a line dropped, doubled or garbled
        at = draw(st.integers(0, len(lines) - 1))
        lines[at : at + 1] = draw(st.sampled_from([[], [lines[at]] * 2, ["facet", "vertex"], ["\x00\xff"]]))
    return "mesh.STL", "\n".join(lines).encode("utf-8", "surrogatepass")


@st.composite
def objs(draw: Callable) -> Tuple[str, bytes]:
    triangles = good_triangles(draw)[: draw(counts)]
    lines = []
    for triangle in triangles:
        for vertex in triangle:
            lines.append(
                "v " + " ".join(draw(number_text) if draw(st.integers(0, 12)) == 0 else repr(c) for c in vertex)
            )
    for index in range(len(triangles)):
        corners = [str(3 * index + k + 1) for k in range(3)]
        if draw(st.integers(0, 8)) == 0:
            corners[draw(st.integers(0, 2))] = draw(index_text)
        if draw(st.integers(0, 10)) == 0:
            corners = [c + "/1/1" for c in corners] + draw(st.lists(index_text, max_size=3))
        lines.append("f " + " ".join(corners))
    lines += draw(
        st.lists(st.sampled_from(["vt 0 0", "vn 0 0 1", "o part", "# comment", "f", "v", "usemtl x"]), max_size=3)
    )
    return "mesh.obj", "\n".join(lines).encode()


@st.composite
def colladas(draw: Callable) -> Tuple[str, bytes]:
    text = collada(good_triangles(draw), meter=1.0, up=draw(st.sampled_from(["Z_UP", "Y_UP", "X_UP", "junk"])))
    edits: Dict[str, Callable] = {
        'meter="1"': lambda: 'meter="%s"' % draw(rarely(st.sampled_from(["1", "0.0254", "0.001"]), hostile_text, 4)),
        'offset="0"': lambda: 'offset="%s"' % draw(rarely(st.just("0"), index_text, 4)),
        'stride="3"': lambda: 'stride="%s"' % draw(rarely(st.just("3"), index_text, 4)),
        "<translate>0.5 0 0</translate>": lambda: draw(
            st.sampled_from(
                [
                    "<translate>%s 0 0</translate>" % draw(number_text),
                    "<rotate>0 0 1 %s</rotate>" % draw(number_text),
                    "<scale>%s 1 1</scale>" % draw(number_text),
                    "<matrix>%s</matrix>" % " ".join(draw(number_text) for _ in range(draw(st.sampled_from([16, 15])))),
                    "<translate>0.5 0 0</translate>",
                ]
            )
        ),
        "<p>0 1 2 ": lambda: "<p>%s %s %s " % (draw(index_text), draw(index_text), draw(index_text)),
        '<instance_geometry url="#box-mesh"/>': lambda: '<instance_geometry url="#box-mesh"/>'
        * draw(rarely(st.just(1), st.sampled_from([0, 2, 50]), 6)),
        '<float_array id="box-positions-array" count="108">0': lambda: '<float_array id="box-positions-array" '
        'count="108">' + draw(number_text),
    }
    for anchor, replacement in edits.items():
        if draw(st.integers(0, 3)) == 0:
            text = text.replace(anchor, replacement(), 1)
    if draw(st.integers(0, 15)) == 0:  # nodes nested deep, or the document cut short
        text = draw(st.sampled_from([text.replace("<node ", "<node><node><node ", 1), text[: len(text) // 2]]))
        text = text.replace("</node>", "</node></node></node>", 1) if "<node><node>" in text else text
    if draw(st.integers(0, 15)) == 0:
        text = text.replace("<triangles", "<polylist", 1).replace(
            "</triangles>", "<vcount>%s</vcount></polylist>" % " ".join(draw(st.lists(index_text, max_size=14))), 1
        )
    return "mesh.dae", text.encode()


meshes = st.one_of(binary_stls(), ascii_stls(), objs(), colladas())


def checked_read(name: str, data: bytes) -> None:
    try:
        triangles = read_mesh(data, name)
    except ModelError as error:
        assert name in str(error), error
        event("refused: " + str(error).split(": ", 1)[-1][:40])
        return
    assert 0 < len(triangles) <= MAX_TRIANGLES and np.isfinite(triangles).all()
    event("read")


@FUZZ
@seed(int(SEED or 0))
@given(mesh=meshes)
def test_generated_mesh_files_are_read_as_finite_triangles_or_refused_naming_them(mesh: Tuple[str, bytes]) -> None:
    name, data = mesh
    _, seconds = timed(lambda: checked_read(name, data))
    assert_answered_in_time(seconds)


@pytest.fixture(scope="module")
def scratch(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("mesh_fuzz")


def listing(folder: Path) -> List[Tuple[str, int, float]]:
    """The files under ``folder`` with size and time (Python's own bytecode caches aside)."""
    files = (p for p in folder.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    return sorted((str(p), p.stat().st_size, p.stat().st_mtime) for p in files)


def model_with(uri: str, as_visual: bool) -> str:
    """A static model 1.5 m ahead of the camera with the mesh as its collision, or as the visual of a box."""
    mesh = f"<mesh><uri>{uri}</uri></mesh>"
    box = "<box><size>0.2 0.2 0.2</size></box>"
    collision = f'<collision name="c"><geometry>{box if as_visual else mesh}</geometry></collision>'
    visual = f'<visual name="v"><geometry>{mesh}</geometry></visual>' if as_visual else ""
    return f"""<sdf version="1.6"><model name="m"><static>true</static><link name="l">{collision}{visual}</link>
      </model></sdf>"""


@FUZZ
@seed(int(SEED or 0))
@given(mesh=meshes, as_visual=st.booleans())
def test_generated_meshes_spawned_before_a_camera_never_stop_the_world(scratch: Path, mesh, as_visual: bool) -> None:
    name, data = mesh
    (scratch / name).write_bytes(data)
    package_files = listing(PACKAGE_ROOT / "test")
    sim = Simulation()
    sim.resources = ResourcePaths({"scratch": str(scratch)}, [], [str(scratch)])
    urdf = CAMERA_URDF.format(
        kind="depth", plugin="libgazebo_ros_openni_kinect.so", fov=1.047, width=24, height=18, z=0.1
    )
    sim.spawn_urdf("cam", urdf, (0, 0, 0.05, 0, 0, 0))
    camera = CameraSensor(sim.physics, sim.models["cam"], sim.plugins["cam"].cameras[0])
    started = time.perf_counter()
    try:
        sim.spawn_sdf("m", model_with(f"package://scratch/{name}", as_visual), (1.5, 0, 0.15, 0, 0, 0))
        event("spawned")
    except CLEAN_REFUSALS as error:
        assert name in str(error), error
        event("refused")
    frame = camera.render(sim.scene)
    warnings = sim.scene.take_warnings()
    assert all(name in warning for warning in warnings), warnings
    event("visual warned" if warnings else "no warning")
    assert_answered_in_time(time.perf_counter() - started)
    depth = frame.depth[np.isfinite(frame.depth)]
    assert ((depth >= CLIP[0] - 1e-6) & (depth <= CLIP[1] + 1e-6)).all()
    before = sim.sim_time
    for _ in range(STEPS_AFTER):
        sim.step()
    assert sim.sim_time == pytest.approx(before + STEPS_AFTER * sim.physics.time_step)
    for model in sim.models.values():
        for link in model.links:
            position, quaternion = model.link_pose(link)
            assert all(math.isfinite(v) for v in position + quaternion)
    assert listing(PACKAGE_ROOT / "test") == package_files
    assert os.listdir(scratch) == [name] or set(os.listdir(scratch)) <= {"mesh.stl", "mesh.STL", "mesh.obj", "mesh.dae"}
