"""A MESH_RESOURCE marker with ``mesh_use_embedded_materials`` and a non-zero ``color``: RViz 2
draws a tint pass ``(r, g, b)`` at alpha ``min(a, 0.5)`` over each embedded material, whose own
pass takes alpha ``a`` (mesh_resource_marker.cpp updateMaterialColor); the viewer mixes the
colours into what it sends (the browser check: test_marker_text_mesh_browser.py)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

from robomodel.viewer.displays.marker_geometry import marker_drawables
from robomodel.viewer.displays.mesh_tint import (
    embedded_tint,
    tinted_glb,
    tinted_rgb,
    without_material,
)
from robomodel.viewer.meshes import MeshPart, load_mesh_file
from tests.viewer.test_markers import marker
from tests.viewer.textured import write_textured_cube


def _two_passes(material_rgb: np.ndarray, rgba: tuple[float, float, float, float], background: np.ndarray) -> np.ndarray:  # fmt: skip
    """What Ogre draws, pass by pass: the material at alpha ``a`` (replacing the background
    from rviz_rendering's unit alpha 0.9998 on), then the tint pass alpha-blended over it."""
    r, g, b, a = rgba
    if a >= 0.9998 or rgba == (0, 0, 0, 0):
        drawn = material_rgb
    else:
        drawn = material_rgb * a + background * (1 - a)
    w = min(a, 0.5)
    return np.array([r, g, b]) * w + drawn * (1 - w)


@pytest.mark.parametrize("rgba", [(0.0, 0.0, 1.0, 1.0), (0.0, 0.0, 1.0, 0.4), (0.2, 0.9, 0.1, 0.7),
                                  (0.0, 0.0, 0.0, 0.0), (1.0, 1.0, 0.0, 0.2)])  # fmt: skip
def test_one_tinted_colour_and_opacity_draw_as_rviz_s_two_passes(rgba: tuple[float, float, float, float]) -> None:  # fmt: skip
    tint = embedded_tint(*rgba)
    red = np.array([1.0, 0.0, 0.0])
    colour = tinted_rgb(red, tint)
    for background in (np.zeros(3), np.ones(3), np.array([0.3, 0.6, 0.2])):
        one_layer = colour * tint.opacity + background * (1 - tint.opacity)
        np.testing.assert_allclose(one_layer, _two_passes(red, rgba, background), atol=1e-9)


def test_blue_over_red_is_half_and_half_and_an_all_zero_colour_does_not_tint() -> None:
    tint = embedded_tint(0.0, 0.0, 1.0, 1.0)
    assert (tint.weight, tint.opacity) == (0.5, 1.0)
    np.testing.assert_allclose(tinted_rgb([1.0, 0.0, 0.0], tint), [0.5, 0.0, 0.5])
    none = embedded_tint(0.0, 0.0, 0.0, 0.0)
    np.testing.assert_allclose(tinted_rgb([1.0, 0.0, 0.0], none), [1.0, 0.0, 0.0])
    assert none.opacity == 1.0
    # a part without a material: RViz's default material is the tint pass itself
    assert without_material(0.0, 1.0, 0.0, 0.8) == ((0.0, 1.0, 0.0), 0.5)
    assert without_material(0.0, 1.0, 0.0, 1.0) == ((0.0, 1.0, 0.0), 1.0)
    assert without_material(0.0, 0.0, 0.0, 0.0) == ((0.0, 0.0, 0.0), 1.0)  # black, opaque


def _texels(glb: bytes) -> tuple[np.ndarray, object]:
    import trimesh

    (geometry,) = trimesh.load(io.BytesIO(glb), file_type="glb").geometry.values()
    material = geometry.visual.material
    return np.asarray(material.baseColorTexture.convert("RGB")), material


def test_a_textured_part_is_sent_with_its_texels_tinted(tmp_path: Path) -> None:
    parts = load_mesh_file(write_textured_cube(tmp_path))
    m = marker(type_=10, rgb=(0.0, 0.0, 1.0))
    m.mesh_resource, m.mesh_use_embedded_materials = "file:///cube.dae", True
    (drawable,) = marker_drawables(m, lambda uri: parts)
    texels, material = _texels(drawable.kwargs["glb_data"])
    before, _ = _texels(parts[0].glb)
    red, blue = np.all(before == (255, 0, 0), axis=2), np.all(before == (0, 0, 255), axis=2)
    assert red.any() and blue.any() and (red | blue).all()
    assert (texels[red] == (128, 0, 128)).all() and (texels[blue] == (0, 0, 255)).all()
    assert material.alphaMode == "OPAQUE"
    m.color.a = 0.4  # see-through: alpha 1 - 0.6 * 0.6 in the material
    (drawable,) = marker_drawables(m, lambda uri: parts)
    texels, material = _texels(drawable.kwargs["glb_data"])
    assert material.alphaMode == "BLEND" and material.baseColorFactor[3] == round(0.64 * 255)
    assert tuple(texels[red][0]) == (96, 0, 159)  # (0.4 blue + 0.4 * 0.6 red) / 0.64
    assert tinted_glb(parts[0].glb, embedded_tint(0.0, 0.0, 0.0, 0.0)) == parts[0].glb


def test_an_untextured_part_s_own_colour_is_tinted_and_a_part_without_one_takes_rviz_s_default() -> None:  # fmt: skip
    triangle = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.uint32))  # fmt: skip
    own, bare = MeshPart(*triangle, (1.0, 0.0, 0.0, 1.0)), MeshPart(*triangle, None)
    m = marker(type_=10, rgb=(0.0, 0.0, 1.0))
    m.mesh_resource, m.mesh_use_embedded_materials = "file:///two.dae", True
    m.color.a = 0.8
    tinted, default = marker_drawables(m, lambda uri: (own, bare))
    assert tinted.kwargs["color"] == (113, 0, 142)  # (0.5 blue + 0.8 * 0.5 red) / 0.9
    assert tinted.kwargs["opacity"] == pytest.approx(0.9)
    assert default.kwargs["color"] == (0, 0, 255) and default.kwargs["opacity"] == 0.5
    m.mesh_use_embedded_materials = False  # the marker's colour for every part
    assert [d.kwargs["color"] for d in marker_drawables(m, lambda uri: (own, bare))] == [(0, 0, 255)] * 2  # fmt: skip
