"""``python3 -m bench.camera_peers`` (in scripts/lib): the renderers issue #15 names (pyrender offscreen on OSMesa
and on EGL, Open3D's ray casting) against our rays in C, on the same frames of bench.camera's room. The scene
(primitives, camera poses along the robot's circle, lens, light) goes to scripts/lib/peers/renderer_peers.py as JSON,
our depth images as .npz; that script runs in the venv .cache/renderer-venv (made on first use: peers.venv), one
process per renderer. Ours is timed here:
CameraSensor.render on each frame, which rebuilds its primitive table from the scene every frame."""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import subprocess
import sys
import tempfile
import time
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
from bench.camera import CAMERAS, MODEL, PACKAGE, turtlebot_in_room
from peers.venv import venv_with
from ros_run.process_stats import cpu_ticks

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
VENV = os.path.join(REPO, ".cache", "renderer-venv")
PEER_SCRIPT = os.path.join(REPO, "scripts", "lib", "peers", "renderer_peers.py")
# Library: (pip installs in order, the check that they work). pyrender pins PyOpenGL 3.1.0, whose OSMesa binding
# lacks what pyrender calls: 3.1.7 over it (pip warns of the pin, pyrender runs).
LIBRARIES: Dict[str, Tuple[List[List[str]], str]] = {
    "pyrender": ([["pyrender"], ["PyOpenGL==3.1.7"]], "import pyrender, OpenGL; assert OpenGL.__version__ == '3.1.7'"),
    "open3d": ([["open3d", "trimesh"]], "import open3d, trimesh"),
}
RENDERERS = (("pyrender-osmesa", "pyrender"), ("pyrender-egl", "pyrender"), ("open3d", "open3d"))
RENDERERS += (("open3d-static", "open3d"),)
PIP_TIMEOUT_S = 900
PEER_TIMEOUT_S = 900
GAP_STEPS = 1500  # 1.5 s of sim time between frames: 0.75 rad along the circle


def describe(row: np.ndarray) -> Dict[str, Any]:
    """A row of the C kernel's primitive table (sensors.ray_kernel.shape_row) as the peers' JSON has it."""
    from turtle_sim_ode.sensors.ray_kernel import BOX, CAPSULE, CYLINDER, PLANE, SPHERE

    kind = int(row[0])
    colour = row[16:19].tolist()
    if kind == PLANE:
        return {"type": "plane", "normal": row[4:7].tolist(), "offset": float(row[13]), "colour": colour}
    shape = {"type": {BOX: "box", SPHERE: "sphere", CYLINDER: "cylinder", CAPSULE: "capsule"}[kind]}
    shape.update(position=row[1:4].tolist(), rotation=row[4:13].reshape(3, 3).tolist(), colour=colour)
    if kind == BOX:
        shape["half_extents"] = row[13:16].tolist()
    else:
        shape.update(radius=float(row[13]), length=float(row[14]))
    return shape


def export_scene(directory: str, frames: int, repeats: int, threads: int) -> Tuple[str, str, Dict[str, Any]]:
    """Drives the robot along its circle, and at ``frames`` moments GAP_STEPS apart writes what the camera sees and
    times our render ``repeats`` times per size on ``threads`` (0: every CPU): (scene JSON path, our depths' .npz
    path, our timings)."""
    from turtle_sim_ode.sensors.camera import AMBIENT, GROUND_COLOR, SKY_COLOR, SUN_DIRECTION, CameraSensor
    from turtle_sim_ode.sensors.ray_kernel import primitive_row

    sim, _ = turtlebot_in_room(CAMERAS[0])
    config, model, ground = sim.plugins[MODEL].cameras[0], sim.models[MODEL], sim.physics.ground
    sensors, setup_s = [], []
    for width, height, _ in CAMERAS:
        start = time.perf_counter()
        sized = dataclasses.replace(config, width=width, height=height)
        sensors.append(CameraSensor(sim.physics, model, sized, threads=threads or None))
        setup_s.append(time.perf_counter() - start)
        if not sensors[-1].uses_ray_kernel:
            raise RuntimeError("libturtle_sim_ode_rays.so is not built: run scripts/build.sh")
    scene_frames: List[Dict[str, Any]] = []
    depths: List[List[np.ndarray]] = [[] for _ in sensors]
    frame_s: List[List[float]] = [[] for _ in sensors]
    for _ in range(frames):
        for _ in range(GAP_STEPS):
            sim.step()
        table, _ = sim.scene.drawables(sim.physics, model)  # the room has no meshes
        rows = list(table) + [primitive_row(ground, GROUND_COLOR)]
        position, rotation = sensors[0].optical_pose()
        camera = {"position": position.tolist(), "rotation": rotation.tolist()}
        scene_frames.append({"camera": camera, "primitives": [describe(row) for row in rows]})
        for index, sensor in enumerate(sensors):
            for _ in range(repeats):
                start = time.perf_counter()
                frame = sensor.render(sim.scene)
                frame_s[index].append(time.perf_counter() - start)
            depths[index].append(frame.depth)
    light = -np.asarray(SUN_DIRECTION)
    scene = {
        "near": config.near,
        "far": config.far,
        "ambient": AMBIENT,
        "sky": list(SKY_COLOR),
        "light": (light / np.linalg.norm(light)).tolist(),
        "sizes": [
            {"width": s.config.width, "height": s.config.height, "focal": s.focal_length, "cx": s.cx, "cy": s.cy}
            for s in sensors
        ],
        "frames": scene_frames,
    }
    scene_path, ours_path = os.path.join(directory, "scene.json"), os.path.join(directory, "ours.npz")
    with open(scene_path, "w") as scene_file:
        json.dump(scene, scene_file)
    np.savez(ours_path, **{"depth_%dx%d" % (w, h): np.array(d) for (w, h, _), d in zip(CAMERAS, depths)})
    sizes = [
        {
            "width": width,
            "height": height,
            "setup_ms": setup * 1e3,
            "ms_per_frame_best": min(times) * 1e3,
            "ms_per_frame_median": float(np.median(times)) * 1e3,
            "frames": len(times),
        }
        for (width, height, _), setup, times in zip(CAMERAS, setup_s, frame_s)
    ]
    return scene_path, ours_path, {"renderer": "C rays (ours)", "status": "ok", "sizes": sizes}


def run_peer(renderer: str, library: str, paths: Tuple[str, str], repeats: int, threads: int) -> Dict[str, Any]:
    """One renderer's figures from renderer_peers.py, or {"status": "unavailable: why"}."""
    installs, check = LIBRARIES[library]
    python, how = venv_with(VENV, installs, check, PIP_TIMEOUT_S)
    if python is None:
        return {"renderer": renderer, "status": "unavailable: " + how}
    out = os.path.join(os.path.dirname(paths[0]), renderer + ".json")
    command = [python, PEER_SCRIPT, "--renderer", renderer, "--scene", paths[0], "--ours", paths[1], "--out", out]
    command += ["--repeats", str(repeats), "--threads", str(threads)]
    try:
        run = subprocess.run(command, check=False, capture_output=True, text=True, timeout=PEER_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return {"renderer": renderer, "status": "unavailable: took over %d s" % PEER_TIMEOUT_S}
    if run.returncode != 0:
        last = (run.stdout + run.stderr).strip().splitlines()[-1:] or ["exit status %d" % run.returncode]
        return {"renderer": renderer, "status": "unavailable: " + last[0][-200:]}
    with open(out) as out_file:
        measured = json.load(out_file)
    measured.update(status="ok", venv=how)
    return measured


def compare(frames: int, repeats: int, threads: int) -> Dict[str, Any]:
    """Ours and every peer on ``frames`` frames, each rendered ``repeats`` times, all with ``threads`` threads (0:
    each one's default; ours: every CPU), and the share of CPU ticks the host stole meanwhile."""
    ticks = cpu_ticks()
    with tempfile.TemporaryDirectory(prefix="camera_peers_") as directory:
        scene_path, ours_path, ours = export_scene(directory, frames, repeats, threads)
        rows = [ours] + [run_peer(r, lib, (scene_path, ours_path), repeats, threads) for r, lib in RENDERERS]
    total, stolen = (after - before for after, before in zip(cpu_ticks(), ticks))
    return {
        "frames": frames,
        "repeats": repeats,
        "threads": threads,
        "steal_share": stolen / max(total, 1),
        "rows": rows,
    }


def cell(row: Dict[str, Any], index: int, ours: Dict[str, Any]) -> str:
    """'median (best) ms, ratio to ours' for one image size."""
    size, base = row["sizes"][index], ours["sizes"][index]["ms_per_frame_median"]
    ratio = size["ms_per_frame_median"] / base
    return "%.1f (%.1f), %.2fx" % (size["ms_per_frame_median"], size["ms_per_frame_best"], ratio)


def table(result: Dict[str, Any]) -> str:
    ours = result["rows"][0]
    names = ["%dx%d" % (size["width"], size["height"]) for size in ours["sizes"]]
    header = ["renderer"] + ["%s ms/frame median (best), x ours" % name for name in names]
    header += ["setup ms (%s)" % " / ".join(names), "scene update ms", "centre depth diff", "pixels within 1 cm"]
    lines = ["| " + " | ".join(header + ["status"]) + " |", "|" + "---|" * (len(header) + 1)]
    for row in result["rows"]:
        if row["status"] != "ok":
            lines.append("| %s |%s %s |" % (row["renderer"], " - |" * len(header[1:]), row["status"]))
            continue
        sizes: Sequence[Dict[str, Any]] = row["sizes"]
        cells = [row["renderer"]] + [cell(row, index, ours) for index in range(len(sizes))]
        cells.append(" / ".join("%.0f" % size["setup_ms"] for size in sizes))
        if row is ours:  # its primitive table is rebuilt inside render; the depths are the reference
            cells += ["in frame", "reference", "reference"]
        else:
            cells.append(" / ".join("%.1f" % size["update_ms_median"] for size in sizes))
            cells.append("%.1f mm" % (1e3 * max(size["centre_diff_m_max"] for size in sizes)))
            cells.append("%.1f%%" % (100 * min(size["agree_share_min"] for size in sizes)))
        status = "ok" + (": " + sizes[0]["gl_renderer"] if "gl_renderer" in sizes[0] else "")
        lines.append("| " + " | ".join(cells + [status]) + " |")
    lines.append(
        "%d frames x %d renders each, peers on %s thread(s); CPU stolen by the host meanwhile: %.1f%%"
        % (result["frames"], result["repeats"], result["threads"] or "default", 100 * result["steal_share"])
    )
    return "\n".join(lines)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="4 frames, 2 repeats")
    parser.add_argument(
        "--peer-threads", type=int, default=1, help="threads of every renderer, ours too (0: each one's default)"
    )
    parser.add_argument("--peers-json", help="write the peers' figures to this file")
    args = parser.parse_args(argv)
    sys.path.insert(0, os.path.join(PACKAGE, "src"))
    peers = compare(4, 2, args.peer_threads) if args.quick else compare(8, 3, args.peer_threads)
    print(table(peers))
    if args.peers_json:
        with open(args.peers_json, "w") as out:
            json.dump(peers, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
