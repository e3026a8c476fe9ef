"""A small textured COLLADA cube for the viewer tests (written at test time, no binary data).

Each face of the 0.4 m cube shows a 2 x 2 checker of pure red and pure blue: a viewer that
drew the DAE without its texture shows one flat colour (trimesh's white) instead.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

RED = (255, 0, 0)
BLUE = (0, 0, 255)

_FACES = (
    ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
    ((0, 0, -1), (-1, 0, 0), (0, 1, 0)),
    ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
    ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ((0, 1, 0), (1, 0, 0), (0, 0, -1)),
    ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
)

_DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="checker-img"><init_from>{image}</init_from></image></library_images>
  <library_effects><effect id="checker-fx"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>checker-img</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><lambert><diffuse><texture texture="samp" texcoord="UV"/></diffuse>
    </lambert></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="checker"><instance_effect url="#checker-fx"/></material>
  </library_materials>
  <library_geometries><geometry id="cube"><mesh>
    <source id="pos"><float_array id="pos-a" count="{nv3}">{positions}</float_array>
      <technique_common><accessor source="#pos-a" count="{nv}" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="uv"><float_array id="uv-a" count="{nv2}">{uvs}</float_array>
      <technique_common><accessor source="#uv-a" count="{nv}" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/>
      </accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles material="mat" count="{nf}">
      <input semantic="VERTEX" source="#verts" offset="0"/>
      <input semantic="TEXCOORD" source="#uv" offset="1" set="0"/>
      <p>{indices}</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="cube-node">
    <instance_geometry url="#cube"><bind_material><technique_common>
      <instance_material symbol="mat" target="#checker">
        <bind_vertex_input semantic="UV" input_semantic="TEXCOORD" input_set="0"/>
      </instance_material></technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""


def write_textured_cube(directory: Path, name: str = "cube") -> Path:
    """Write ``<name>.dae`` and its ``<name>.png`` texture into ``directory``; return the DAE."""
    from PIL import Image

    image = np.zeros((64, 64, 3), np.uint8)
    image[:32, :32] = image[32:, 32:] = RED
    image[:32, 32:] = image[32:, :32] = BLUE
    Image.fromarray(image).save(directory / f"{name}.png")
    positions: list[float] = []
    uvs: list[float] = []
    indices: list[int] = []
    for n, u, w in _FACES:
        base = len(positions) // 3
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            positions += [0.2 * (n[i] + a * u[i] + b * w[i]) for i in range(3)]
            uvs += [(a + 1) / 2, (b + 1) / 2]
        for tri in ((0, 1, 2), (0, 2, 3)):
            for k in tri:
                indices += [base + k, base + k]
    text = _DAE.format(
        image=f"{name}.png",
        nv=len(positions) // 3,
        nv3=len(positions),
        nv2=len(uvs),
        nf=len(indices) // 6,
        positions=" ".join(f"{p:g}" for p in positions),
        uvs=" ".join(f"{t:g}" for t in uvs),
        indices=" ".join(map(str, indices)),
    )
    path = directory / f"{name}.dae"
    path.write_text(text)
    return path
