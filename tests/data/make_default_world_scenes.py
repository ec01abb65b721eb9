#!/usr/bin/env python3
"""Writes the two glTF files the golden tests use for the defaults of docs/shading.md ("Defaults"):

  tests/data/closed_room.gltf   a closed room (4 x 3 x 4, walls facing in) with a box on the floor and a camera
                                inside it, and no light: the default key light would stand outside the walls, so the
                                room is lit only if the headlight rule works.
  tests/data/mirror_sphere.gltf a mirror sphere (metallic 1, roughness 0) over a checkered floor, with no camera,
                                no light and no background: it shows the default world in the sphere and around it.

Neither file carries the renderer's own extras (rt_background, rt_ambient): they are what a glTF exporter writes.
Standard library only, deterministic: python3 tests/data/make_default_world_scenes.py [OUT_DIR]
"""
import base64
import json
import math
import os
import struct
import sys


class Builder:
    """Accumulates one glTF document: a single buffer with float32 positions/normals and uint16 indices."""

    def __init__(self, name):
        self.name = name
        self.data = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "tests/data/make_default_world_scenes.py"},
            "scene": 0,
            "scenes": [{"name": name, "nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
        }

    def material(self, name, color, metallic=0.0, roughness=1.0):
        self.doc["materials"].append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [color[0], color[1], color[2], 1.0],
            "metallicFactor": metallic, "roughnessFactor": roughness}})
        return len(self.doc["materials"]) - 1

    def _view(self, payload, target):
        while len(self.data) % 4:
            self.data.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload),
                                        "target": target})
        self.data += payload
        return len(self.doc["bufferViews"]) - 1

    def _vec3_accessor(self, values):
        payload = b"".join(struct.pack("<3f", *v) for v in values)
        accessor = {"bufferView": self._view(payload, 34962), "componentType": 5126, "count": len(values),
                    "type": "VEC3", "min": [min(v[k] for v in values) for k in range(3)],
                    "max": [max(v[k] for v in values) for k in range(3)]}
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def primitive(self, positions, normals, indices, material):
        """One triangle list; returns the primitive's dictionary (for mesh())."""
        index_payload = struct.pack("<%dH" % len(indices), *indices)
        self.doc["accessors"].append({"bufferView": self._view(index_payload, 34963), "componentType": 5123,
                                      "count": len(indices), "type": "SCALAR"})
        index_accessor = len(self.doc["accessors"]) - 1
        return {"attributes": {"POSITION": self._vec3_accessor(positions), "NORMAL": self._vec3_accessor(normals)},
                "indices": index_accessor, "material": material}

    def mesh_node(self, name, primitives):
        self.doc["meshes"].append({"name": name, "primitives": primitives})
        self.doc["nodes"].append({"name": name, "mesh": len(self.doc["meshes"]) - 1})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera_node(self, name, translation, pitch_degrees, yfov_degrees):
        """A perspective camera looking down -Z, tilted by pitch (negative: down) about +X."""
        self.doc["cameras"] = [{"type": "perspective", "perspective": {
            "yfov": math.radians(yfov_degrees), "znear": 0.01}}]
        half = math.radians(pitch_degrees) / 2.0
        self.doc["nodes"].append({"name": name, "camera": 0, "translation": list(translation),
                                  "rotation": [math.sin(half), 0.0, 0.0, math.cos(half)]})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.data),
                                "uri": "data:application/octet-stream;base64," +
                                       base64.b64encode(bytes(self.data)).decode("ascii")}]
        with open(path, "w", encoding="ascii") as f:
            json.dump(self.doc, f, indent=1, sort_keys=True)
            f.write("\n")


def quad(corners, normal, material, b):
    """Two triangles over four corners given counter-clockwise as seen from the side the normal points to."""
    return b.primitive(corners, [normal] * 4, [0, 1, 2, 0, 2, 3], material)


def box_faces(lo, hi, inward):
    """The six faces of an axis-aligned box as (corners, normal) pairs, facing out of the box or into it."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [  # outward normal, corners counter-clockwise seen from outside
        ((-1, 0, 0), [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)]),
        ((1, 0, 0), [(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)]),
        ((0, -1, 0), [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)]),
        ((0, 1, 0), [(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)]),
        ((0, 0, -1), [(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)]),
        ((0, 0, 1), [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]),
    ]
    if not inward:
        return faces
    return [(tuple(-c for c in n), list(reversed(corners))) for n, corners in faces]


def closed_room(path):
    b = Builder("closed_room")
    white = b.material("walls", (0.8, 0.8, 0.8))
    red = b.material("left wall", (0.8, 0.15, 0.1))
    green = b.material("right wall", (0.15, 0.7, 0.2))
    box = b.material("box", (0.9, 0.75, 0.3))
    wall_material = [red, green, white, white, white, white]   # -X, +X, floor, ceiling, back (-Z), front (+Z)
    room = [quad(c, n, wall_material[i], b) for i, (n, c) in enumerate(box_faces((-2, 0, -2), (2, 3, 2), True))]
    b.mesh_node("room", room)
    b.mesh_node("box", [quad(c, n, box, b) for n, c in box_faces((-0.9, 0, -1.2), (0.1, 1.0, -0.2), False)])
    b.camera_node("camera", (0.6, 1.6, 1.6), -12.0, 60.0)
    b.write(path)


def mirror_sphere(path):
    b = Builder("mirror_sphere")
    mirror = b.material("mirror", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.0)
    tiles = [b.material("tile dark", (0.15, 0.15, 0.2)), b.material("tile light", (0.8, 0.8, 0.75))]
    # A UV sphere of radius 1 at the origin: 24 segments around +Y, 12 rings.
    segments, rings = 24, 12
    positions, normals, indices = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2.0 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            positions.append(n)
            normals.append(n)
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            c = a + segments + 1
            indices += [a, c, a + 1, a + 1, c, c + 1]
    b.mesh_node("sphere", [b.primitive(positions, normals, indices, mirror)])
    # A 4 x 4 checkerboard floor just under the sphere, 1 unit per tile.
    floor = [[], []]
    for i in range(4):
        for j in range(4):
            x0, z0 = -2 + i, -2 + j
            corners = [(x0, -1.0, z0 + 1), (x0 + 1, -1.0, z0 + 1), (x0 + 1, -1.0, z0), (x0, -1.0, z0)]
            floor[(i + j) % 2].append(corners)
    primitives = []
    for k, squares in enumerate(floor):
        pos = [p for square in squares for p in square]
        idx = [q * 4 + o for q in range(len(squares)) for o in (0, 1, 2, 0, 2, 3)]
        primitives.append(b.primitive(pos, [(0.0, 1.0, 0.0)] * len(pos), idx, tiles[k]))
    b.mesh_node("floor", primitives)
    b.write(path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    closed_room(os.path.join(out, "closed_room.gltf"))
    mirror_sphere(os.path.join(out, "mirror_sphere.gltf"))


if __name__ == "__main__":
    main()
