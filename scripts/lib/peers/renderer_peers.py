#!/usr/bin/env python3
"""The renderers issue #15 names as alternatives to our rays in C, on the scene scripts/lib/bench/camera_peers.py exports
from bench.camera's room: run by the Python of the venv .cache/renderer-venv (camera_peers makes it), one renderer
per process (PyOpenGL picks its platform once, at import).

Renderers (``--renderer``):
  pyrender-osmesa  pyrender's OffscreenRenderer on OSMesa (PYOPENGL_PLATFORM=osmesa; PyOpenGL >= 3.1.5, pyrender
                   pins 3.1.0, which lacks OSMesaCreateContextAttribs);
  pyrender-egl     the same on EGL (PYOPENGL_PLATFORM=egl), Mesa's software device (llvmpipe), no display; there
                   pyrender draws into a 4x multisampled framebuffer and blits it, so a pixel's depth is a sample's
                   off its centre (on OSMesa it uses no framebuffer objects: one sample, at the centre);
  open3d           Open3D's RaycastingScene (Embree) rebuilt every frame with the bodies where they are now (it has
                   no way to move a geometry once added), a ray per pixel, shaded in numpy as our camera shades;
  open3d-static    the same with the scene built once: only right for a world where nothing but the camera moves.
Every frame first puts every primitive where the frame has it, as a simulator that does not track which bodies moved
must, then renders colour and depth (metres along the optical axis, NaN where nothing is hit). The meshes are
trimesh's (spheres: icospheres of 642 vertices, cylinders 64 sections), the ground a square of 2 (far + reach) a side.

System packages this needed on Debian 12 (apt-get install -y; not in scripts/install_deps.sh: an optional
benchmark): libosmesa6 (OSMesa); libegl-mesa0, libgl1-mesa-dri (EGL, llvmpipe; installed here already); libusb-1.0-0
(Open3D's import fails without libusb-1.0.so.0).

Writes JSON (``--out``): per image size, setup ms (meshes, scene, context), ms per frame (best, median), the median
of the scene update alone, and the depth's agreement with our C rays' depth of the same frames (``--ours``, .npz).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import Any, Callable, Dict, List, Sequence, Tuple

AGREE_M = 0.01  # depths closer than this agree


def pose_matrix(position: Sequence[float], rotation: Sequence[Sequence[float]]) -> Any:
    import numpy as np

    pose = np.eye(4)
    pose[:3, :3] = rotation
    pose[:3, 3] = position
    return pose


def frame_about(axis: Any) -> Any:
    """A rotation whose third column is the unit vector ``axis``."""
    import numpy as np

    helper = [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0]
    first = np.cross(helper, axis)
    first /= np.linalg.norm(first)
    return np.column_stack([first, np.cross(axis, first), axis])


def ground_mesh(primitive: Dict[str, Any], half_side: float) -> Any:
    """The plane n.x = offset as a square of 2 ``half_side`` a side about the point nearest the origin, facing n."""
    import numpy as np
    import trimesh

    normal = np.asarray(primitive["normal"], dtype=float)
    rotation = frame_about(normal)
    centre = normal * primitive["offset"]
    corners = [
        centre + half_side * (a * rotation[:, 0] + b * rotation[:, 1]) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))
    ]
    return trimesh.Trimesh(vertices=np.array(corners), faces=[[0, 1, 2], [0, 2, 3]], process=False)


def shape_mesh(primitive: Dict[str, Any], half_side: float) -> Any:
    """A primitive's mesh in its own frame (the plane's in the world)."""
    import trimesh

    kind = primitive["type"]
    if kind == "box":
        return trimesh.creation.box(extents=[2.0 * h for h in primitive["half_extents"]])
    if kind == "sphere":
        return trimesh.creation.icosphere(subdivisions=3, radius=primitive["radius"])
    if kind == "cylinder":
        return trimesh.creation.cylinder(radius=primitive["radius"], height=primitive["length"], sections=64)
    if kind == "capsule":
        return trimesh.creation.capsule(height=primitive["length"], radius=primitive["radius"], count=[32, 32])
    return ground_mesh(primitive, half_side)


def moving(primitive: Dict[str, Any]) -> bool:
    return primitive["type"] != "plane"


class Scene:
    """The exported scene: lens, light, frames (camera pose + primitives) and the meshes of frame 0's primitives."""

    def __init__(self, path: str) -> None:
        import numpy as np

        with open(path) as scene_file:
            data = json.load(scene_file)
        self.data = data
        self.frames: List[Dict[str, Any]] = data["frames"]
        reach = max(np.linalg.norm(frame["camera"]["position"]) for frame in self.frames)
        self.half_side = data["far"] + reach
        self.meshes = [shape_mesh(primitive, self.half_side) for primitive in self.frames[0]["primitives"]]
        self.light = np.asarray(data["light"], dtype=float)  # unit vector towards the sun

    def poses(self, frame: Dict[str, Any]) -> List[Any]:
        """Each primitive's pose (4x4) in ``frame``; the plane's meshes are in the world already."""
        import numpy as np

        return [pose_matrix(p["position"], p["rotation"]) if moving(p) else np.eye(4) for p in frame["primitives"]]


def pyrender_renderer(scene: Scene, size: Dict[str, Any]) -> Tuple[Callable, Callable]:
    """(update(frame), render() -> (rgb, depth)) for pyrender, its scene and offscreen context made here."""
    import numpy as np
    import pyrender

    data = scene.data
    view = pyrender.Scene(bg_color=list(data["sky"]) + [1.0], ambient_light=[data["ambient"]] * 3)
    nodes = []
    for mesh, primitive in zip(scene.meshes, scene.frames[0]["primitives"]):
        material = pyrender.MetallicRoughnessMaterial(
            baseColorFactor=list(primitive["colour"]) + [1.0], metallicFactor=0.0, roughnessFactor=1.0
        )
        nodes.append(view.add(pyrender.Mesh.from_trimesh(mesh, material=material, smooth=False), pose=np.eye(4)))
    # OpenGL samples pixel i at i + 0.5 where our rays go through i: the principal point half a pixel on.
    camera = pyrender.IntrinsicsCamera(
        size["focal"], size["focal"], size["cx"] + 0.5, size["cy"] + 0.5, znear=data["near"], zfar=data["far"]
    )
    camera_node = view.add(camera, pose=np.eye(4))
    sun = np.eye(4)  # a directional light shines along its node's -z
    sun[:3, :3] = frame_about(scene.light)
    view.add(pyrender.DirectionalLight(intensity=3.0), pose=sun)
    renderer = pyrender.OffscreenRenderer(size["width"], size["height"])
    gl_flip = np.diag([1.0, -1.0, -1.0])  # optical (z forward, y down) to OpenGL's camera (z back, y up)

    def update(frame: Dict[str, Any]) -> None:
        for node, pose in zip(nodes, scene.poses(frame)):
            view.set_pose(node, pose)
        view.set_pose(
            camera_node, pose_matrix(frame["camera"]["position"], np.dot(frame["camera"]["rotation"], gl_flip))
        )

    def render() -> Tuple[Any, Any]:
        rgb, depth = renderer.render(view)
        depth = depth.astype(np.float32)
        depth[depth <= 0.0] = np.nan
        return rgb, depth

    return update, render


def gl_renderer_name() -> str:
    from OpenGL import GL

    return GL.glGetString(GL.GL_RENDERER).decode()


def open3d_renderer(scene: Scene, size: Dict[str, Any], threads: int, static: bool) -> Tuple[Callable, Callable]:
    """(update(frame), render() -> (rgb, depth)) for Open3D's RaycastingScene; ``static``: built once, here."""
    import numpy as np
    import open3d as o3d

    data = scene.data
    width, height = size["width"], size["height"]
    optical = np.ones((height, width, 3))
    optical[:, :, 0] = (np.arange(width) - size["cx"]) / size["focal"]
    optical[:, :, 1] = ((np.arange(height) - size["cy"]) / size["focal"])[:, None]
    templates = [(np.asarray(m.vertices), o3d.core.Tensor(np.asarray(m.faces, dtype=np.uint32))) for m in scene.meshes]
    colours = np.array([p["colour"] for p in scene.frames[0]["primitives"]] + [data["sky"]])
    rays = np.empty((height, width, 6), dtype=np.float32)
    state: Dict[str, Any] = {}

    def build(frame: Dict[str, Any]) -> Any:
        world = o3d.t.geometry.RaycastingScene()
        for (vertices, faces), pose in zip(templates, scene.poses(frame)):
            placed = (vertices @ pose[:3, :3].T + pose[:3, 3]).astype(np.float32)
            world.add_triangles(o3d.core.Tensor(placed), faces)
        return world

    if static:
        state["world"] = build(scene.frames[0])

    def update(frame: Dict[str, Any]) -> None:
        if not static:
            state["world"] = build(frame)
        state["camera"] = frame["camera"]

    def render() -> Tuple[Any, Any]:
        rays[:, :, :3] = state["camera"]["position"]
        rays[:, :, 3:] = optical @ np.asarray(state["camera"]["rotation"]).T  # optical z = 1: t_hit is the depth
        hits = state["world"].cast_rays(o3d.core.Tensor(rays), nthreads=threads)
        depth = hits["t_hit"].numpy()
        ids = hits["geometry_ids"].numpy().astype(np.int64)
        missed = ~(depth <= data["far"])
        ids[missed] = len(colours) - 1
        lit = np.clip(hits["primitive_normals"].numpy() @ scene.light, 0.0, 1.0)
        shade = (data["ambient"] + (1.0 - data["ambient"]) * lit)[:, :, None] * colours[ids]
        shade[missed] = data["sky"]
        depth[missed] = np.nan
        return (shade * 255.0 + 0.5).astype(np.uint8), depth.astype(np.float32)

    return update, render


def agreement(depth: Any, ours: Any) -> Dict[str, float]:
    """Centre pixel's depth difference (m) and the share of pixels whose depths agree within AGREE_M (both NaN
    counts as agreeing)."""
    import numpy as np

    height, width = ours.shape
    centre = float(abs(depth[height // 2, width // 2] - ours[height // 2, width // 2]))
    close = np.abs(np.nan_to_num(depth, nan=-1.0) - np.nan_to_num(ours, nan=-1.0)) < AGREE_M  # NaN and NaN agree
    return {"centre_diff_m": centre, "agree_share": float(np.mean(close))}


def measure(scene: Scene, size: Dict[str, Any], ours: Any, args: argparse.Namespace) -> Dict[str, Any]:
    """Setup, then every frame ``args.repeats`` times in turns (update + render each time)."""
    import numpy as np

    start = time.perf_counter()
    if args.renderer.startswith("pyrender"):
        update, render = pyrender_renderer(scene, size)
    else:
        update, render = open3d_renderer(scene, size, args.threads, args.renderer == "open3d-static")
    setup_s = time.perf_counter() - start
    frame_s, update_s = [], []
    checks = []
    for _ in range(args.repeats):
        for index, frame in enumerate(scene.frames):
            start = time.perf_counter()
            update(frame)
            updated = time.perf_counter()
            _, depth = render()
            frame_s.append(time.perf_counter() - start)
            update_s.append(updated - start)
            if len(checks) < len(scene.frames):
                checks.append(agreement(depth, ours[index]))
    result = {
        "width": size["width"],
        "height": size["height"],
        "setup_ms": setup_s * 1e3,
        "ms_per_frame_best": min(frame_s) * 1e3,
        "ms_per_frame_median": float(np.median(frame_s)) * 1e3,
        "update_ms_median": float(np.median(update_s)) * 1e3,
        "frames": len(frame_s),
        "centre_diff_m_max": max(check["centre_diff_m"] for check in checks),
        "agree_share_min": min(check["agree_share"] for check in checks),
    }
    if args.renderer.startswith("pyrender"):
        result["gl_renderer"] = gl_renderer_name()
    return result


def versions(renderer: str) -> Dict[str, str]:
    import numpy
    import trimesh

    found = {"numpy": numpy.__version__, "trimesh": trimesh.__version__, "python": sys.version.split()[0]}
    if renderer.startswith("pyrender"):
        import OpenGL
        import pyrender

        found.update(pyrender=pyrender.__version__, PyOpenGL=OpenGL.__version__)
    else:
        import open3d

        found["open3d"] = open3d.__version__
    return found


def main(argv: Sequence[str] = ()) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(
        "--renderer", required=True, choices=("pyrender-osmesa", "pyrender-egl", "open3d", "open3d-static")
    )
    parser.add_argument("--scene", required=True, help="the scene's JSON (camera_peers.export_scene)")
    parser.add_argument("--ours", required=True, help=".npz of our depth images: depth_<W>x<H> (frames, H, W)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--threads", type=int, default=1, help="renderer threads (0: the library's default)")
    args = parser.parse_args(list(argv) or None)
    if args.renderer.startswith("pyrender"):
        os.environ["PYOPENGL_PLATFORM"] = args.renderer.split("-")[1]  # before anything imports OpenGL
        if args.threads:
            os.environ["LP_NUM_THREADS"] = str(args.threads)  # llvmpipe's rasteriser threads, read at context start
    import numpy as np

    found = versions(args.renderer)  # imports the renderer's library: not part of the setup measured
    scene = Scene(args.scene)
    ours = np.load(args.ours)
    sizes = [
        measure(scene, size, ours["depth_%dx%d" % (size["width"], size["height"])], args)
        for size in scene.data["sizes"]
    ]
    with open(args.out, "w") as out:
        json.dump(
            {"renderer": args.renderer, "threads": args.threads, "versions": found, "sizes": sizes},
            out,
            indent=1,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
