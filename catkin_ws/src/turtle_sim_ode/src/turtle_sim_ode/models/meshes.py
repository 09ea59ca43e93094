"""Collision and visual meshes: STL (binary and ASCII, read with numpy-stl), Wavefront OBJ and Collada (.dae)
triangles, from the bytes models.resources read; ``load_meshes``, which fills a parsed model's <mesh> collisions with
them, and ``mesh_file`` and ``scaled_mesh``, which the cameras read visual meshes with.

The files are read as Gazebo classic reads them (gazebo/common/STLLoader.cc, OBJLoader.cc, ColladaLoader.cc): an STL
or OBJ as it is, in metres; a Collada file with its <unit meter> and node transforms applied but its <up_axis>
ignored (ColladaLoader::Load reads only <unit> from <asset>): a file marked Y_UP keeps its axes, its Z is up, as in
Gazebo (TurtleBot3's Y_UP walls stand there as their Z says). Whatever a file holds, reading it either gives finite
triangles or raises ModelError naming the file and what is wrong in it.

numpy-stl (Debian's python3-stl) reads a 20,000-triangle binary STL in about 1 ms. pyassimp (Debian's
python3-pyassimp 5.2.5) would read all three formats, but crashes the process (SIGSEGV) on any STL on Debian 12, and
trimesh is not packaged by Debian 12: OBJ and Collada are read here with numpy and defusedxml."""
from __future__ import annotations

import io
import math
import os
import re
import warnings
from dataclasses import replace
from typing import Dict, Iterable, List, Optional, Sequence, Tuple, Union
from xml.etree.ElementTree import Element

import numpy

from turtle_sim_ode.models.resources import ResourceError, ResourcePaths
from turtle_sim_ode.models.text import ModelError, parse_xml
from turtle_sim_ode.models.description import Mesh, RobotModel
from turtle_sim_ode.models.urdf import MAX_LENGTH
from turtle_sim_ode.physics.trimesh import TriMeshData
from turtle_sim_ode.physics.trimesh import available as trimesh_available

# More triangles than any collision mesh needs; more would cost seconds to build and every step after.
MAX_TRIANGLES = 200_000
Triangles = numpy.ndarray  # (N, 3, 3) float64: N triangles of three vertices
# A Collada <triangles> or <polylist> start tag's count attribute (namespace prefix allowed).
_DAE_COUNT = re.compile(rb"<(?:[\w.-]+:)?(?:triangles|polylist)\b[^>]*?\scount\s*=\s*[\"'](\d{1,18})[\"']")


def _binary_stl_count(data: bytes) -> Optional[int]:
    """A binary STL's facet count from its header, where the file is binary (see _stl)."""
    if len(data) < 84:
        return None
    count = int.from_bytes(data[80:84], "little")
    ascii_text = data.lstrip().startswith(b"solid")
    if len(data) == 84 + 50 * count or (not ascii_text and len(data) > 84 + 50 * count):
        return count
    return None


def _counted_triangles(data: bytes, extension: str) -> Tuple[int, bool]:
    """The triangles a file holds, counted without reading its geometry, and whether that count is exact (else a
    least): a binary STL's header count, an ASCII STL's facets, an OBJ's face lines, a Collada file's <triangles>
    and <polylist> counts (a polygon is one triangle at least)."""
    if extension == ".stl":
        count = _binary_stl_count(data)
        return (count, True) if count is not None else (data.count(b"endfacet"), True)
    if extension == ".obj":
        return data.count(b"\nf ") + data.count(b"\nf\t") + int(data[:2] in (b"f ", b"f\t")), False
    return sum(int(count) for count in _DAE_COUNT.findall(data)), False


def _stl(data: bytes, what: str) -> Triangles:
    with warnings.catch_warnings():  # numpy-stl 2.9's dtype spelling, deprecated by numpy 1.24
        warnings.simplefilter("ignore", FutureWarning)
        from stl import mesh as stl_mesh  # numpy-stl; imported when a model has an STL mesh

    ascii_text = data.lstrip().startswith(b"solid")
    # Binary, whatever its header says (some begin with "solid"); bytes after the facets are ignored, as
    # STLLoader::ReadBinary reads the count's facets and stops.
    count = _binary_stl_count(data)
    if count is not None:
        records = numpy.frombuffer(data, dtype=stl_mesh.Mesh.dtype, count=count, offset=84)
        return numpy.array(records["vectors"], dtype=numpy.float64)
    if len(data) >= 84 and not ascii_text:
        count = int.from_bytes(data[80:84], "little")
        raise ModelError(f"{what}: binary STL of {count} facets needs {84 + 50 * count} bytes, has {len(data)}")
    if not ascii_text:
        raise ModelError(f"{what}: not an STL file (neither binary nor ASCII)")
    try:
        loaded = stl_mesh.Mesh.from_file(what, fh=io.BytesIO(data), calculate_normals=False, speedups=False)
    except Exception as error:  # numpy-stl raises assorted errors on bad ASCII
        raise ModelError(f"{what}: malformed ASCII STL ({error})") from None
    return numpy.array(loaded.vectors, dtype=numpy.float64)


def _fan(polygon: Sequence[int]) -> List[Tuple[int, int, int]]:
    return [(polygon[0], polygon[i], polygon[i + 1]) for i in range(1, len(polygon) - 1)]


def _obj(data: bytes, what: str) -> Triangles:
    """Vertices and faces (1-based indices, negative ones counted back from the last vertex, as OBJLoader's
    tinyobjloader reads them); other statements are skipped."""
    vertices: List[Tuple[float, float, float]] = []
    faces: List[Tuple[int, int, int]] = []
    for number, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
        parts = line.split()
        if not parts or parts[0] not in ("v", "f"):
            continue
        try:
            if parts[0] == "v":
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
                continue
            indices = []
            for part in parts[1:]:
                index = int(part.split("/")[0])
                position = index - 1 if index > 0 else len(vertices) + index
                if index == 0 or not 0 <= position < len(vertices):
                    raise ModelError(
                        f"{what}: OBJ line {number}: face index {_shown_number(index)} refers to a vertex that does "
                        f"not exist ({len(vertices)} so far)"
                    )
                indices.append(position)
        except (ValueError, IndexError) as error:
            if isinstance(error, ModelError):
                raise
            raise ModelError(f"{what}: malformed OBJ line {number} '{line.strip()[:60]}'") from None
        faces.extend(_fan(indices))
    return _gather(numpy.array(vertices, dtype=numpy.float64).reshape(-1, 3), faces, what)


def _shown_number(value: float) -> str:
    """A number as a message shows it: long ones shortened."""
    text = str(value)
    return text if len(text) <= 24 else text[:10] + "..." + text[-10:]


def _gather(vertices: numpy.ndarray, faces: Sequence[Tuple[int, int, int]], what: str) -> Triangles:
    try:
        index = numpy.array(faces, dtype=numpy.int64).reshape(-1, 3)
    except OverflowError:  # an index beyond 2**63
        raise ModelError(f"{what}: a face refers to a vertex that does not exist") from None
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
    if element is None:
        return []
    try:
        return [float(value) for value in (element.text or "").split()]
    except ValueError as error:
        raise ModelError(
            f"{what}: Collada <{_local(element.tag)}> holds a value that is not a number ({error})"
        ) from None


def _indices(element: Optional[Element], what: str) -> List[int]:
    """Whole numbers >= 0 (<p>, <vcount>): anything else is refused naming the tag."""
    if element is None:
        return []
    values = []
    for word in (element.text or "").split():
        try:
            values.append(int(word))
        except ValueError:
            raise ModelError(
                f"{what}: Collada <{_local(element.tag)}> holds {word[:24]!r}, not a whole number"
            ) from None
    if values and min(values) < 0:
        raise ModelError(f"{what}: Collada <{_local(element.tag)}> holds the negative index {min(values)}")
    return values


def _whole_attribute(element: Element, name: str, default: int, what: str, low: int, high: int) -> int:
    """An integer attribute (an <input offset>, an <accessor stride>) in [low, high]; ModelError naming it."""
    text = element.get(name, str(default))
    try:
        value = int(text)
    except ValueError:
        value = None
    if value is None or not low <= value <= high:
        raise ModelError(
            f'{what}: Collada <{_local(element.tag)} {name}="{text[:24]}"> is not a whole number from {low} to {high}'
        )
    return value


def _unit_meter(asset: Optional[Element], what: str) -> float:
    """<asset><unit meter>: metres per unit (ColladaLoader::Load scales the mesh by it); finite and > 0."""
    unit = asset.find("{*}unit") if asset is not None else None
    text = unit.get("meter", "1") if unit is not None else "1"
    try:
        meter = float(text)
    except ValueError:
        meter = math.nan
    if not (math.isfinite(meter) and meter > 0):
        raise ModelError(f'{what}: Collada <unit meter="{text[:24]}"> is not a number > 0')
    return meter


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
        stride = _whole_attribute(accessor, "stride", 3, what, 1, 64) if accessor is not None else 3
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
        offsets = [_whole_attribute(i, "offset", 0, what, 0, 64) for i in inputs]
        stride = max(offsets) + 1 if inputs else 1
        vertex_input = next((i for i in inputs if i.get("semantic") == "VERTEX"), None)
        if vertex_input is None:
            continue
        points = positions.get(vertex_input.get("source", "").lstrip("#"))
        if points is None:
            raise ModelError(f"{what}: Collada <{kind}> refers to positions that do not exist")
        indices = _indices(_child(primitive, "p"), what)[offsets[inputs.index(vertex_input)] :: stride]
        if kind == "triangles":
            faces = [tuple(indices[i : i + 3]) for i in range(0, len(indices) - 2, 3)]
        else:
            faces, start = [], 0
            for count in _indices(_child(primitive, "vcount"), what):
                faces.extend(_fan(indices[start : start + count]))
                start += count
        triangles.append(_gather(points, faces, what))
    return numpy.concatenate(triangles) if triangles else numpy.zeros((0, 3, 3))


def _dae(data: bytes, what: str) -> Triangles:
    root = parse_xml(data.decode("utf-8", "replace"), f"Collada {what}")
    geometries = {g.get("id", ""): g for g in root.iter() if _local(g.tag) == "geometry"}
    # <up_axis> is not read: ColladaLoader::Load applies <unit meter> alone, so a Y_UP file's Y stays Gazebo's Y.
    meter = _unit_meter(_child(root, "asset"), what)
    top = numpy.diag([meter, meter, meter, 1.0])
    triangles: List[numpy.ndarray] = []
    read: Dict[str, Triangles] = {}  # each geometry read once, however often it is instanced
    total = [0]

    def place(key: str, geometry: Element, matrix: numpy.ndarray) -> None:
        if key not in read:
            read[key] = _dae_geometry(geometry, what)
        local = read[key]
        total[0] += len(local)
        if total[0] > MAX_TRIANGLES:  # before instances multiply a geometry beyond what memory holds
            raise ModelError(f"{what}: more than the {MAX_TRIANGLES} triangles allowed")
        flat = numpy.c_[local.reshape(-1, 3), numpy.ones(len(local) * 3)] @ matrix.T
        triangles.append(flat[:, :3].reshape(-1, 3, 3))

    def visit(node: Element, parent: numpy.ndarray, depth: int) -> None:
        if depth > 64:
            raise ModelError(f"{what}: Collada nodes nested deeper than 64")
        matrix = parent @ _node_matrix(node, what)
        for instance in _children(node, "instance_geometry"):
            key = instance.get("url", "").lstrip("#")
            if key in geometries:
                place(key, geometries[key], matrix)
        for child in _children(node, "node"):
            visit(child, matrix, depth + 1)

    scenes = [s for s in root.iter() if _local(s.tag) == "visual_scene"]
    if scenes:
        for node in _children(scenes[0], "node"):
            visit(node, top, 0)
    else:  # no scene: every geometry as it is
        for key, geometry in geometries.items():
            place(key, geometry, top)
    return numpy.concatenate(triangles) if triangles else numpy.zeros((0, 3, 3))


_READERS = {".stl": _stl, ".obj": _obj, ".dae": _dae}


def read_mesh(data: bytes, name: str) -> Triangles:
    """The triangles of mesh file ``name`` (its extension says the format) from its bytes; ModelError if the
    format is unknown, the file malformed, empty, not finite, or over MAX_TRIANGLES triangles."""
    extension = os.path.splitext(name)[1].lower()
    reader = _READERS.get(extension)
    if reader is None:
        raise ModelError(f"mesh '{name}': unsupported format (STL, OBJ and Collada .dae are read)")
    counted, exact = _counted_triangles(data, extension)
    if counted > MAX_TRIANGLES:  # refused before reading: a 64 MB file is counted in tens of milliseconds
        at_least = "" if exact else "at least "
        raise ModelError(f"mesh '{name}' has {at_least}{counted} triangles, more than the {MAX_TRIANGLES} allowed")
    try:
        with numpy.errstate(all="ignore"):  # overflow to inf is refused below, not warned of
            triangles = reader(data, f"mesh '{name}'")
    except ModelError:
        raise
    except (ArithmeticError, ValueError, IndexError, KeyError, TypeError, MemoryError) as error:
        # What the checks above did not foresee still names the file and the fault, never escapes as it is.
        raise ModelError(
            f"mesh '{name}': malformed {extension[1:].upper()} file ({type(error).__name__}: {error})"
        ) from None
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
    with numpy.errstate(all="ignore"):
        scaled = triangles.reshape(-1, 3) * numpy.array(scale, dtype=numpy.float64)
    if not numpy.isfinite(scaled).all() or numpy.abs(scaled).max() > MAX_LENGTH:
        raise ModelError(f"{what}: vertices beyond {MAX_LENGTH:g} m with scale {tuple(scale)}")
    vertices, inverse = numpy.unique(scaled, axis=0, return_inverse=True)
    faces = inverse.reshape(-1, 3)
    faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])]
    if len(faces) == 0:
        raise ModelError(f"{what}: every triangle is degenerate at scale {tuple(scale)}")
    return vertices, faces


def _as_tuples(array: numpy.ndarray) -> Tuple:
    return tuple(map(tuple, array.tolist()))


# Resolved path -> its triangles, or the ModelError reading it gave (not read twice either way).
MeshFiles = Dict[str, Union[Triangles, ModelError]]


def mesh_file(
    paths: Optional[ResourcePaths], mesh: Mesh, base: Optional[str], what: str, cache: MeshFiles
) -> Triangles:
    """The triangles of ``mesh``'s file, read through ``paths`` (relative URIs against ``base``) unless ``cache``
    has them; ResourceError or ModelError naming ``what`` or the file if it cannot be read."""
    if paths is None:
        raise ResourceError(f"{what}: not read, no ROS package path or model path to read it from")
    path = paths.resolve(mesh.uri, base)
    if path not in cache:
        try:
            _, data = paths.read(mesh.uri, base)
            cache[path] = read_mesh(data, path)
        except ModelError as error:
            cache[path] = error
    found = cache[path]
    if isinstance(found, ModelError):
        raise found
    return found


def read_visual_meshes(robots: Sequence[RobotModel], paths: Optional[ResourcePaths], known: Iterable[str]) -> MeshFiles:
    """The files of the <visual> meshes of ``robots`` not in ``known`` (resolved paths), read ahead of the cameras'
    first look (by the spawn service, outside the world lock); those that cannot be read are there with their error
    (the cameras warn of it when they draw the model)."""
    files: MeshFiles = {}
    if paths is None:
        return files
    skip = set(known)
    for robot in robots:
        for link in robot.links.values():
            for visual in link.visuals:
                if not isinstance(visual.geometry, Mesh):
                    continue
                try:
                    if paths.resolve(visual.geometry.uri, robot.base) not in skip:
                        mesh_file(paths, visual.geometry, robot.base, visual.geometry.uri, files)
                except ModelError:  # kept in ``files`` where the path resolved; else the cameras resolve it again
                    pass
    return files


def load_meshes(robot: RobotModel, paths: Optional[ResourcePaths], base: Optional[str] = None) -> None:
    """Fill every <mesh> collision of ``robot`` with its vertices and faces, read through ``paths``
    (relative URIs against ``base``, the folder of the file the model came from); ResourceError or ModelError
    naming the file if one cannot be read. Each file is read once."""
    cache: MeshFiles = {}
    for link in robot.links.values():
        for index, collision in enumerate(link.collisions):
            geometry = collision.geometry
            if not isinstance(geometry, Mesh) or geometry.vertices is not None:
                continue
            what = f"link '{link.name}' collision '{collision.name}' mesh '{geometry.uri}'"
            triangles = mesh_file(paths, geometry, base, what, cache)
            vertices, faces = scaled_mesh(triangles, geometry.scale, what)
            mesh = replace(geometry, vertices=_as_tuples(vertices), faces=_as_tuples(faces))
            if robot.static and trimesh_available():  # meshes collide as trimeshes on static models only (builder)
                mesh = replace(mesh, prepared=TriMeshData(vertices, faces))
            link.collisions[index] = replace(collision, geometry=mesh)


def uses_meshes(robot: RobotModel) -> bool:
    return any(isinstance(c.geometry, Mesh) for link in robot.links.values() for c in link.collisions)
