"""Textures of visuals for the cameras: an SDF ``<material><script>`` whose ``<uri>``s name folders of Ogre material
scripts (``*.material``) and of their images, and whose ``<name>`` is a material there with a texture, as Gazebo's
own models and gazebo_models' (checkerboard_plane, ...) write them. The material's first ``texture`` (in a
``texture_unit``) is the image the cameras draw; it is read from the script folders or the other ``<uri>`` folders,
as Ogre's resource locations find it. Images are decoded with Pillow to RGB floats in 0..1."""
from __future__ import annotations

import io
import os
import re
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple
from xml.etree.ElementTree import Element

import numpy as np

from turtle_sim_ode.models.materials import GAZEBO_MATERIALS
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.text import ModelError

# "material NAME" opens a block; "texture FILE ..." inside a texture_unit names the image.
_MATERIAL = re.compile(r"^\s*material\s+(\S+)")
_TEXTURE = re.compile(r"^\s*texture\s+(\S+)")
MAX_TEXTURE_PIXELS = 4096 * 4096


@dataclass(frozen=True)
class MaterialScript:
    """An SDF ``<material><script>``: its ``<uri>`` folders and material ``<name>``."""

    uris: Tuple[str, ...]
    name: str


def sdf_material_script(visual: Element) -> Optional[MaterialScript]:
    """The ``<material><script>`` of an SDF ``<visual>`` that names folders (None for Gazebo's built-in scripts,
    drawn in their colour: see models.materials)."""
    script = visual.find("material/script")
    if script is None:
        return None
    name = (script.findtext("name") or "").strip()
    uris = tuple((uri.text or "").strip() for uri in script.findall("uri") if (uri.text or "").strip())
    if not name or name in GAZEBO_MATERIALS or not any(not uri.startswith("file://media/") for uri in uris):
        return None
    return MaterialScript(uris, name)


def script_textures(text: str) -> Dict[str, str]:
    """Material name -> the file of its first texture, for every material of an Ogre material script that has
    one (comments dropped)."""
    found: Dict[str, str] = {}
    current = None
    for line in text.splitlines():
        line = line.split("//", 1)[0]
        opened = _MATERIAL.match(line)
        if opened:
            current = opened.group(1)
            continue
        texture = _TEXTURE.match(line)
        if texture and current is not None and current not in found:
            found[current] = texture.group(1)
    return found


def decode_image(data: bytes, what: str) -> np.ndarray:
    """An image file's pixels as (H, W, 3) float32 RGB in 0..1 (alpha dropped); ModelError naming ``what`` if
    Pillow cannot read it or it is larger than MAX_TEXTURE_PIXELS."""
    from PIL import Image, UnidentifiedImageError  # only worlds with textures need Pillow

    try:
        with Image.open(io.BytesIO(data)) as image:
            if image.width * image.height > MAX_TEXTURE_PIXELS:
                raise ModelError(f"{what}: {image.width}x{image.height} pixels, more than {MAX_TEXTURE_PIXELS}")
            pixels = np.asarray(image.convert("RGB"), dtype=np.float32) / 255.0
    except (UnidentifiedImageError, OSError, ValueError) as error:
        raise ModelError(f"{what}: not an image Pillow reads ({error})") from None
    return pixels


def read_texture(resources: ResourcePaths, script: MaterialScript, base: Optional[str]) -> np.ndarray:
    """The texture image of ``script``'s material; ModelError saying what is missing."""
    listed = [resources.resolve(uri, base) for uri in script.uris]
    folders = [folder for folder in listed if not folder.endswith(".material")]
    files = [folder for folder in listed if folder.endswith(".material")]
    for folder in folders:
        files += _material_files(folder)
    for path in files:
        _, text = resources.read(path)
        texture = script_textures(text.decode("utf-8", "replace")).get(script.name)
        if texture is None:
            continue
        for folder in folders:
            candidate = f"{folder}/{texture}"
            if os.path.isfile(candidate):
                _, data = resources.read(candidate)
                return decode_image(data, candidate)
        raise ModelError(f"material '{script.name}' ({path}): texture '{texture}' is in none of {folders}")
    raise ModelError(f"material '{script.name}': no material script of {list(script.uris)} gives it a texture")


def _material_files(folder: str) -> List[str]:
    if not os.path.isdir(folder):
        return []
    return [os.path.join(folder, name) for name in sorted(os.listdir(folder)) if name.endswith(".material")]


def texture_lookup(texture: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The texels at texture coordinates ``u``, ``v`` (0..1, u to the image's right, v down, wrapping as Ogre's
    default address mode): nearest texel, (N, 3)."""
    height, width = texture.shape[:2]
    columns = np.floor(np.mod(u, 1.0) * width).astype(np.int64) % width
    rows = np.floor(np.mod(v, 1.0) * height).astype(np.int64) % height
    return texture[rows, columns]
