#!/usr/bin/env python3
"""Writes tests/data/vertex_colors.gltf, the golden scene of glTF vertex colours (COLOR_0; docs/shading.md, "Vertex
colours"), in the three forms glTF allows, so that every stage's golden, agree and hits tests read each of them:

  floor     float RGB (VEC3), a different colour at each corner: the colour interpolated across a triangle
  box       unsigned byte RGBA, normalized, one colour a face: a one-coloured triangle gets exactly its colour
  screen    unsigned short RGBA, normalized, its alpha 0 at the left edge and 1 at the right, under a MASK material
            (alphaCutoff 0.5): the cut-out edge runs down its middle, for camera, shadow and mirror rays alike
  mirror    no colours beside coloured meshes (white: the base colour as it is), showing the others

A point light (KHR_lights_punctual) throws the box's and the screen's shadows on the floor.
Standard library only, deterministic: python3 tests/data/make_vertex_colors_scene.py [OUT_DIR]
"""
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_default_world_scenes import Builder, box_faces, quad  # noqa: E402

FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT = 5126, 5121, 5123


def colors(b, primitive, values, component_type):
    """Adds COLOR_0 to a primitive: float VEC3, or normalized unsigned byte/short VEC4 (values in [0, 1])."""
    if component_type == FLOAT:
        payload = b"".join(struct.pack("<3f", *v) for v in values)
        accessor = {"componentType": FLOAT, "type": "VEC3"}
    else:
        top, code = (255, "B") if component_type == UNSIGNED_BYTE else (65535, "H")
        # Each element padded to 4 bytes (glTF 2.0, 3.6.2.4): 4 bytes or 8 bytes, so no padding is needed.
        payload = b"".join(struct.pack("<4" + code, *(round(c * top) for c in v)) for v in values)
        accessor = {"componentType": component_type, "type": "VEC4", "normalized": True}
    accessor.update({"bufferView": b._view(payload, 34962), "count": len(values)})
    b.doc["accessors"].append(accessor)
    primitive["attributes"]["COLOR_0"] = len(b.doc["accessors"]) - 1
    return primitive


def vertex_colors(path):
    b = Builder("vertex_colors")
    white = b.material("white", (1.0, 1.0, 1.0))
    mirror = b.material("mirror", (0.9, 0.9, 0.9), metallic=1.0, roughness=0.0)
    screen = b.material("screen", (0.95, 0.9, 0.8))
    b.doc["materials"][screen].update({"alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True})

    # The floor, 6 x 6 at y = 0, one colour at each corner.
    floor = quad([(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], (0, 1, 0), white, b)
    colors(b, floor, [(0.9, 0.2, 0.1), (0.1, 0.8, 0.2), (0.1, 0.3, 0.9), (0.9, 0.9, 0.2)], FLOAT)
    b.mesh_node("floor", [floor])

    # The box: each face one colour, as unsigned bytes.
    face_colors = [(1.0, 0.4, 0.4, 1.0), (0.4, 1.0, 0.4, 1.0), (0.4, 0.4, 1.0, 1.0),
                   (1.0, 1.0, 0.4, 1.0), (0.4, 1.0, 1.0, 1.0), (1.0, 0.4, 1.0, 1.0)]
    box = []
    for (normal, corners), color in zip(box_faces((-1.6, 0, -0.6), (-0.6, 1.0, 0.4), False), face_colors):
        face = quad(corners, normal, white, b)
        box.append(colors(b, face, [color] * 4, UNSIGNED_BYTE))
    b.mesh_node("box", box)

    # The screen: 2 x 1.5 upright, facing +Z, alpha from 0 (left) to 1 (right) as unsigned shorts.
    corners = [(0.2, 0.2, 0.0), (2.2, 0.2, 0.0), (2.2, 1.7, 0.0), (0.2, 1.7, 0.0)]
    screen_prim = quad(corners, (0, 0, 1), screen, b)
    colors(b, screen_prim, [(1.0, 0.6, 0.2, 0.0), (0.2, 0.6, 1.0, 1.0), (0.2, 1.0, 0.6, 1.0), (1.0, 1.0, 1.0, 0.0)],
           UNSIGNED_SHORT)
    b.mesh_node("screen", [screen_prim])

    # The mirror behind them, 6 x 3 facing +Z, without colours.
    b.mesh_node("mirror", [quad([(-3, 0, -2), (3, 0, -2), (3, 3, -2), (-3, 3, -2)], (0, 0, 1), mirror, b)])

    b.camera_node("camera", (0.0, 2.4, 5.0), -22.0, 55.0)
    b.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    b.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1.0, 1.0, 1.0], "intensity": 60.0}]}}
    b.doc["nodes"].append({"name": "light", "translation": [1.5, 4.0, 3.0],
                           "extensions": {"KHR_lights_punctual": {"light": 0}}})
    b.doc["scenes"][0]["nodes"].append(len(b.doc["nodes"]) - 1)
    b.doc["asset"]["generator"] = "tests/data/make_vertex_colors_scene.py"
    b.write(path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    vertex_colors(os.path.join(out, "vertex_colors.gltf"))


if __name__ == "__main__":
    main()
