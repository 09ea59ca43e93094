"""Collision and visual meshes: STL (binary and ASCII, read with numpy-stl), Wavefront OBJ and Collada (.dae)
triangles, from the bytes models.resources read; ``load_meshes``, which fills a parsed model's <mesh> collisions with
them, and ``mesh_file`` and ``scaled_mesh``, which the cameras read visual meshes with.

numpy-stl (Debian's python3-stl) reads a 20,000-triangle binary STL in about 1 ms. pyassimp (Debian's
python3-pyassimp 5.2.5) would read all three formats, but crashes the process (SIGSEGV) on any STL on Debian 12, and
trimesh is not packaged by Debian 12: OBJ and Collada are read here with numpy and defusedxml."""
from __future__ import annotations

import io
import math
import os
import warnings
from dataclasses import replace
from typing import Dict, List, Optional, Sequence, Tuple
from xml.etree.ElementTree import Element

import numpy

from turtle_sim_ode.models.resources import ResourceError, ResourcePaths
from turtle_sim_ode.models.text import ModelError, parse_xml
from turtle_sim_ode.models.urdf import MAX_LENGTH, Mesh, RobotModel

# More triangles than any collision mesh needs; more would cost seconds to build and every step after.
MAX_TRIANGLES = 200_000
Triangles = numpy.ndarray  # (N, 3, 3) float64: N triangles of three vertices


def _stl(data: bytes, what: str) -> Triangles:
    with warnings.catch_warnings():  # numpy-stl 2.9's dtype spelling, deprecated by numpy 1.24
        warnings.simplefilter("ignore", FutureWarning)
        from stl import mesh as stl_mesh  # numpy-stl; imported when a model has an STL mesh

    if len(data) >= 84:
        count = int.from_bytes(data[80:84], "little")
        if len(data) == 84 + 50 * count:  # binary, whatever its header says (some begin with "solid")
            records = numpy.frombuffer(data, dtype=stl_mesh.Mesh.dtype, count=count, offset=84)
            return numpy.array(records["vectors"], dtype=numpy.float64)
    if not data.lstrip().startswith(b"solid"):
        raise ModelError(f"{what}: not an STL file (neither binary nor ASCII)")
    try:
        loaded = stl_mesh.Mesh.from_file(what, fh=io.BytesIO(data), calculate_normals=False, speedups=False)
    except Exception as error:  # numpy-stl raises assorted errors on bad ASCII
        raise ModelError(f"{what}: malformed ASCII STL ({error})") from None
    return numpy.array(loaded.vectors, dtype=numpy.float64)


def _fan(polygon: Sequence[int]) -> List[Tuple[int, int, int]]:
    return [(polygon[0], polygon[i], polygon[i + 1]) for i in range(1, len(polygon) - 1)]


def _obj(data: bytes, what: str) -> Triangles:
    vertices: List[Tuple[float, float, float]] = []
    faces: List[Tuple[int, int, int]] = []
    try:
        for line in data.decode("utf-8", "replace").splitlines():
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
            elif parts[0] == "f":
                indices = []
                for part in parts[1:]:
                    index = int(part.split("/")[0])
                    indices.append(index - 1 if index > 0 else len(vertices) + index)
                faces.extend(_fan(indices))
    except (ValueError, IndexError):
        raise ModelError(f"{what}: malformed OBJ line '{line.strip()[:60]}'") from None
    return _gather(numpy.array(vertices, dtype=numpy.float64).reshape(-1, 3), faces, what)


def _gather(vertices: numpy.ndarray, faces: Sequence[Tuple[int, int, int]], what: str) -> Triangles:
    index = numpy.array(faces, dtype=numpy.int64).reshape(-1, 3)
    if index.size and (index.min() < 0 or index.max() >= len(vertices)):
        raise ModelError(f"{what}: a face refers to a vertex that does not exist")
    return vertices[index]


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _children(element: Element, name: str) -> List[Element]:
    return [child for child in element if _local(child.tag) == name]


def _child(element: Element, name: str) -> Optional[Element]:
    found = _children(element, name)
    return found[0] if found else None


def _numbers(element: Optional[Element], what: str) -> List[float]:
    try:
        return [float(value) for value in (element.text or "").split()] if element is not None else []
    except ValueError:
        raise ModelError(f"{what}: malformed Collada number list") from None


def _node_matrix(node: Element, what: str) -> numpy.ndarray:
    """The node's own transform (<matrix>, <translate>, <rotate>, <scale> in order)."""
    matrix = numpy.eye(4)
    for child in node:
        kind, values = _local(child.tag), None
        if kind not in ("matrix", "translate", "rotate", "scale"):
            continue
        values = _numbers(child, what)
        step = numpy.eye(4)
        if kind == "matrix" and len(values) == 16:
            step = numpy.array(values).reshape(4, 4)
        elif kind == "translate" and len(values) == 3:
            step[:3, 3] = values
        elif kind == "scale" and len(values) == 3:
            step[:3, :3] = numpy.diag(values)
        elif kind == "rotate" and len(values) == 4:
            axis, angle = numpy.array(values[:3]), math.radians(values[3])
            norm = numpy.linalg.norm(axis)
            if norm > 0:
                x, y, z = axis / norm
                c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
                step[:3, :3] = [
                    [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                    [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                    [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
                ]
        else:
            raise ModelError(f"{what}: malformed Collada <{kind}>")
        matrix = matrix @ step
    return matrix


def _dae_geometry(geometry: Element, what: str) -> Triangles:
    mesh = _child(geometry, "mesh")
    if mesh is None:
        return numpy.zeros((0, 3, 3))
    sources: Dict[str, numpy.ndarray] = {}
    for source in _children(mesh, "source"):
        values = _numbers(_child(source, "float_array"), what)
        accessor = source.find(".//{*}accessor")
        stride = int(accessor.get("stride", "3")) if accessor is not None else 3
        if stride >= 3 and values:
            sources[source.get("id", "")] = numpy.array(values[: len(values) // stride * stride]).reshape(-1, stride)[
                :, :3
            ]
    positions: Dict[str, numpy.ndarray] = {}
    for vertices in _children(mesh, "vertices"):
        for shared in _children(vertices, "input"):
            if shared.get("semantic") == "POSITION":
                positions[vertices.get("id", "")] = sources.get(shared.get("source", "").lstrip("#"))
    triangles = []
    for primitive in mesh:
        kind = _local(primitive.tag)
        if kind not in ("triangles", "polylist"):
            continue
        inputs = _children(primitive, "input")
        stride = max(int(i.get("offset", "0")) for i in inputs) + 1 if inputs else 1
        vertex_input = next((i for i in inputs if i.get("semantic") == "VERTEX"), None)
        if vertex_input is None:
            continue
        points = positions.get(vertex_input.get("source", "").lstrip("#"))
        if points is None:
            raise ModelError(f"{what}: Collada <{kind}> refers to positions that do not exist")
        indices = [int(v) for v in _numbers(_child(primitive, "p"), what)][
            int(vertex_input.get("offset", "0")) :: stride
        ]
        if kind == "triangles":
            faces = [tuple(indices[i : i + 3]) for i in range(0, len(indices) - 2, 3)]
        else:
            faces, start = [], 0
            for count in (int(v) for v in _numbers(_child(primitive, "vcount"), what)):
                faces.extend(_fan(indices[start : start + count]))
                start += count
        triangles.append(_gather(points, faces, what))
    return numpy.concatenate(triangles) if triangles else numpy.zeros((0, 3, 3))


def _dae(data: bytes, what: str) -> Triangles:
    root = parse_xml(data.decode("utf-8", "replace"), f"Collada {what}")
    geometries = {g.get("id", ""): g for g in root.iter() if _local(g.tag) == "geometry"}
    asset = _child(root, "asset")
    unit = asset.find("{*}unit") if asset is not None else None
    meter = float(unit.get("meter", "1")) if unit is not None else 1.0
    up = asset.find("{*}up_axis") if asset is not None else None
    top = numpy.diag([meter, meter, meter, 1.0])
    if up is not None and (up.text or "").strip() == "Y_UP":  # Y up to Gazebo's Z up
        top = top @ numpy.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1.0]])
    triangles: List[numpy.ndarray] = []

    def visit(node: Element, parent: numpy.ndarray, depth: int) -> None:
        if depth > 64:
            raise ModelError(f"{what}: Collada nodes nested deeper than 64")
        matrix = parent @ _node_matrix(node, what)
        for instance in _children(node, "instance_geometry"):
            geometry = geometries.get(instance.get("url", "").lstrip("#"))
            if geometry is not None:
                local = _dae_geometry(geometry, what)
                flat = numpy.c_[local.reshape(-1, 3), numpy.ones(len(local) * 3)] @ matrix.T
                triangles.append(flat[:, :3].reshape(-1, 3, 3))
        for child in _children(node, "node"):
            visit(child, matrix, depth + 1)

    scenes = [s for s in root.iter() if _local(s.tag) == "visual_scene"]
    if scenes:
        for node in _children(scenes[0], "node"):
            visit(node, top, 0)
    else:  # no scene: every geometry as it is
        for geometry in geometries.values():
            local = _dae_geometry(geometry, what)
            flat = numpy.c_[local.reshape(-1, 3), numpy.ones(len(local) * 3)] @ top.T
            triangles.append(flat[:, :3].reshape(-1, 3, 3))
    return numpy.concatenate(triangles) if triangles else numpy.zeros((0, 3, 3))


_READERS = {".stl": _stl, ".obj": _obj, ".dae": _dae}


def read_mesh(data: bytes, name: str) -> Triangles:
    """The triangles of mesh file ``name`` (its extension says the format) from its bytes; ModelError if the
    format is unknown, the file malformed, empty, not finite, or over MAX_TRIANGLES triangles."""
    reader = _READERS.get(os.path.splitext(name)[1].lower())
    if reader is None:
        raise ModelError(f"mesh '{name}': unsupported format (STL, OBJ and Collada .dae are read)")
    triangles = reader(data, f"mesh '{name}'")
    if len(triangles) == 0:
        raise ModelError(f"mesh '{name}' has no triangles")
    if len(triangles) > MAX_TRIANGLES:
        raise ModelError(f"mesh '{name}' has {len(triangles)} triangles, more than the {MAX_TRIANGLES} allowed")
    if not numpy.isfinite(triangles).all():
        raise ModelError(f"mesh '{name}' has vertices that are not finite numbers")
    return triangles


def scaled_mesh(triangles: Triangles, scale: Sequence[float], what: str) -> Tuple[numpy.ndarray, numpy.ndarray]:
    """(vertices (N, 3) float64, faces (M, 3) int64): shared vertices, scaled, degenerate triangles dropped;
    ModelError beyond MAX_LENGTH or if no triangle is left."""
    scaled = triangles.reshape(-1, 3) * numpy.array(scale, dtype=numpy.float64)
    if numpy.abs(scaled).max() > MAX_LENGTH:
        raise ModelError(f"{what}: vertices beyond {MAX_LENGTH:g} m with scale {tuple(scale)}")
    vertices, inverse = numpy.unique(scaled, axis=0, return_inverse=True)
    faces = inverse.reshape(-1, 3)
    faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])]
    if len(faces) == 0:
        raise ModelError(f"{what}: every triangle is degenerate at scale {tuple(scale)}")
    return vertices, faces


def mesh_arrays(triangles: Triangles, scale: Sequence[float], what: str) -> Tuple[Tuple, Tuple]:
    """scaled_mesh as tuples, for ode.TriMeshData."""
    vertices, faces = scaled_mesh(triangles, scale, what)
    return tuple(map(tuple, vertices.tolist())), tuple(map(tuple, faces.tolist()))


def mesh_file(
    paths: Optional[ResourcePaths], mesh: Mesh, base: Optional[str], what: str, cache: Dict[str, Triangles]
) -> Triangles:
    """The triangles of ``mesh``'s file, read through ``paths`` (relative URIs against ``base``) unless ``cache``
    (resolved path -> triangles) has them; ResourceError or ModelError naming ``what`` if it cannot be read."""
    if paths is None:
        raise ResourceError(f"{what}: not read, no ROS package path or model path to read it from")
    path = paths.resolve(mesh.uri, base)
    if path not in cache:
        _, data = paths.read(mesh.uri, base)
        cache[path] = read_mesh(data, path)
    return cache[path]


def load_meshes(robot: RobotModel, paths: Optional[ResourcePaths], base: Optional[str] = None) -> None:
    """Fill every <mesh> collision of ``robot`` with its vertices and faces, read through ``paths``
    (relative URIs against ``base``, the folder of the file the model came from); ResourceError or ModelError
    naming the file if one cannot be read. Each file is read once."""
    cache: Dict[str, Triangles] = {}
    for link in robot.links.values():
        for index, collision in enumerate(link.collisions):
            geometry = collision.geometry
            if not isinstance(geometry, Mesh) or geometry.vertices is not None:
                continue
            what = f"link '{link.name}' collision '{collision.name}' mesh '{geometry.uri}'"
            triangles = mesh_file(paths, geometry, base, what, cache)
            vertices, faces = mesh_arrays(triangles, geometry.scale, what)
            link.collisions[index] = replace(collision, geometry=replace(geometry, vertices=vertices, faces=faces))


def uses_meshes(robot: RobotModel) -> bool:
    return any(isinstance(c.geometry, Mesh) for link in robot.links.values() for c in link.collisions)
