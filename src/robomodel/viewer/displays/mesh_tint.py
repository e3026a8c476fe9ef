"""RViz 2's tint of a MESH_RESOURCE marker's embedded materials by the marker's ``color``.

Transcribed from ros2/rviz at f7112b1, rviz_default_plugins/.../markers/
mesh_resource_marker.cpp: with ``mesh_use_embedded_materials`` each of the file's materials
is cloned with an extra pass (``cloneMaterials``, lines 210-225: lit, alpha-blended, no depth
write) and ``updateMaterialColor`` (lines 227-270) sets the material's own pass to alpha
``a`` and the extra pass to ``(r, g, b)`` with alpha ``min(a, 0.5)``, drawn over it. Both
passes blend (``SBT_TRANSPARENT_ALPHA``) unless ``a`` reaches rviz_rendering's
``unit_alpha_threshold`` (0.9998) or the colour is all zero, when the material's pass
replaces what is behind it (``SBT_REPLACE``: opaque). A part without a material takes the
marker's default material, which has one pass only: the "extra" pass is that pass, so it is
``(r, g, b)`` at alpha ``min(a, 0.5)`` (black and opaque for an all-zero colour).

Over a background ``bg`` the two passes give ``t w + (m a + bg (1 - a)) (1 - w)`` (``m`` the
material's colour, ``t`` the marker's, ``w = min(a, 0.5)``): one colour
``(t w + m a (1 - w)) / alpha`` at ``alpha = 1 - (1 - a)(1 - w)``. viser cannot tint a glTF,
so the colours (a textured part's texels) are mixed here before the mesh is sent; RViz's
lighting of the tint pass (ambient ``0.5 (r, g, b)``) is the page's lighting of the mix.
"""

from __future__ import annotations

import functools
import io
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Tint", "embedded_tint", "tinted_glb", "tinted_rgb", "without_material"]

_UNIT_ALPHA = 0.9998  # rviz_rendering material_manager.hpp unit_alpha_threshold


@dataclass(frozen=True, slots=True)
class Tint:
    """How a marker's colour changes its mesh's embedded materials.

    Attributes:
        rgb: The marker's colour (0..1).
        weight: The tint pass's alpha, ``min(a, 0.5)``; 0: the material as it is.
        alpha: The material pass's alpha (1: opaque, replacing what is behind).
    """

    rgb: tuple[float, float, float]
    weight: float
    alpha: float

    @property
    def opacity(self) -> float:
        """The tinted material's opacity (both passes together)."""
        return 1.0 - (1.0 - self.alpha) * (1.0 - self.weight)


def embedded_tint(r: float, g: float, b: float, a: float) -> Tint:
    """The tint of a marker with ``color`` (r, g, b, a), each 0..1."""
    if r == g == b == a == 0:
        return Tint((0.0, 0.0, 0.0), 0.0, 1.0)  # no tint, opaque
    a = min(1.0, max(0.0, a))
    rgb = (_unit(r), _unit(g), _unit(b))
    return Tint(rgb, min(a, 0.5), 1.0 if a >= _UNIT_ALPHA else a)


def without_material(r: float, g: float, b: float, a: float) -> tuple[tuple[float, float, float], float]:  # fmt: skip
    """The colour (0..1) and opacity of a part without a material of its own (RViz's default
    material, whose one pass takes the tint pass's colour and alpha)."""
    tint = embedded_tint(r, g, b, a)
    return tint.rgb, (1.0 if tint.alpha == 1.0 else tint.weight)


def tinted_rgb(rgb: ArrayLike, tint: Tint) -> NDArray[np.float64]:
    """Material colours ``rgb`` (shape (..., 3), 0..1) as the two passes draw them."""
    m = np.asarray(rgb, dtype=np.float64)
    if tint.weight == 0.0:
        untinted: NDArray[np.float64] = m.copy()
        return untinted
    w, a = tint.weight, tint.alpha
    return (np.asarray(tint.rgb) * w + m * a * (1.0 - w)) / tint.opacity


@functools.lru_cache(maxsize=8)  # a marker re-sent is not re-encoded; the keys are the cached parts
def tinted_glb(glb: bytes, tint: Tint) -> bytes:
    """A binary glTF with every material's base colour (its texture's texels, or its factor)
    tinted, and the tint's opacity; the mesh and UVs as they were."""
    if tint.weight == 0.0 and tint.alpha == 1.0:
        return glb  # an all-zero colour: the file's own materials
    from PIL import Image

    from robomodel.viewer._deps import import_trimesh

    trimesh = import_trimesh()
    scene = trimesh.load(io.BytesIO(glb), file_type="glb")
    for geometry in scene.geometry.values():
        material = getattr(geometry.visual, "material", None)
        if material is None or not hasattr(material, "baseColorFactor"):
            continue
        factor = np.asarray(material.baseColorFactor if material.baseColorFactor is not None else (255,) * 4, float) / 255  # fmt: skip
        texture = material.baseColorTexture
        if texture is not None:
            texels = np.asarray(texture.convert("RGBA"), dtype=np.float64) / 255
            texels[..., :3] = tinted_rgb(texels[..., :3] * factor[:3], tint)
            material.baseColorTexture = Image.fromarray(_to_uint8(texels), "RGBA")
            factor[:3] = 1.0
        else:
            factor[:3] = tinted_rgb(factor[:3], tint)
        factor[3] *= tint.opacity
        material.baseColorFactor = _to_uint8(factor)
        material.alphaMode = "BLEND" if factor[3] < 1.0 else "OPAQUE"
    return bytes(scene.export(file_type="glb"))


def _unit(v: float) -> float:
    return min(1.0, max(0.0, float(v)))


def _to_uint8(values: NDArray[np.float64]) -> NDArray[np.uint8]:
    return np.floor(np.clip(values, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)
