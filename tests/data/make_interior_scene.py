#!/usr/bin/env python3
"""Writes a large interior as glTF 2.0 (tests/default_light.cmake renders it): a hall 40 m long, 14 m wide and 12 m
high under a coffered ceiling, two rows of 24-sided columns on plinths, a gallery along each side and a floor of
tiles, about 70,000 triangles with the camera inside at eye height and no light, as a real atrium file comes. Only
the default headlight lights it: the case where a light placed from the view axis blows out the nearer walls.

usage: make_interior_scene.py OUT.gltf   (writes OUT.gltf and OUT.bin beside it)
"""
import json
import math
import os
import struct
import sys

positions, normals, indices = [], [], []
primitives = []   # (first index, count, material)


def add_quad(c, u, v, material_index):
    """Quad c +- u +- v facing cross(u, v), as two triangles (counter-clockwise from the front)."""
    n = cross(u, v)
    length = math.sqrt(sum(x * x for x in n))
    n = [x / length for x in n]
    base = len(positions)
    for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        positions.append([c[k] + su * u[k] + sv * v[k] for k in range(3)])
        normals.append(n)
    first = len(indices)
    indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
    primitives.append((first, 6, material_index))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def add_box(lo, hi, material_index):
    c = [(lo[k] + hi[k]) / 2 for k in range(3)]
    h = [(hi[k] - lo[k]) / 2 for k in range(3)]
    for axis in range(3):
        for sign in (-1, 1):
            centre = list(c)
            centre[axis] += sign * h[axis]
            a, b = (axis + 1) % 3, (axis + 2) % 3
            u, v = [0.0] * 3, [0.0] * 3
            u[a], v[b] = h[a], h[b]
            if sign < 0:
                u, v = v, u
            add_quad(centre, u, v, material_index)


def add_column(x, z, radius, height, material_index, segments=24, rings=40):
    base = len(positions)
    first = len(indices)
    for r in range(rings + 1):
        y = height * r / rings
        for s in range(segments + 1):
            a = 2 * math.pi * s / segments
            positions.append([x + radius * math.cos(a), y, z + radius * math.sin(a)])
            normals.append([math.cos(a), 0.0, math.sin(a)])
    for r in range(rings):
        for s in range(segments):
            i0 = base + r * (segments + 1) + s
            i1, i2, i3 = i0 + 1, i0 + segments + 1, i0 + segments + 2
            indices.extend([i0, i2, i1, i1, i2, i3])   # outward
    primitives.append((first, len(indices) - first, material_index))


def main():
    out = sys.argv[1]
    length, width, height = 40.0, 14.0, 12.0
    stone, floor, ceiling, wood = 0, 1, 2, 3
    # Floor tiles (1 m), walls and the ceiling's coffers.
    for i in range(40):
        for j in range(14):
            add_quad([-7.0 + j + 0.5, 0.0, -i - 0.5], [0.5, 0.0, 0.0], [0.0, 0.0, -0.5], floor)
    add_quad([-7.0, height / 2, -length / 2], [0.0, 0.0, length / 2], [0.0, height / 2, 0.0], stone)
    add_quad([7.0, height / 2, -length / 2], [0.0, 0.0, -length / 2], [0.0, height / 2, 0.0], stone)
    add_quad([0.0, height / 2, -length], [width / 2, 0.0, 0.0], [0.0, height / 2, 0.0], stone)
    add_quad([0.0, height / 2, 0.0], [-width / 2, 0.0, 0.0], [0.0, height / 2, 0.0], stone)
    for i in range(20):
        for j in range(7):
            add_box([-7.0 + 2 * j + 0.1, height - 0.4, -2 * i - 1.9], [-7.0 + 2 * j + 1.9, height, -2 * i - 0.1], ceiling)
    # Columns on plinths, and a gallery on each side at 5 m.
    for i in range(16):
        z = -2.5 - 2.3 * i
        for x in (-4.0, 4.0):
            add_box([x - 0.6, 0.0, z - 0.6], [x + 0.6, 0.5, z + 0.6], stone)
            add_column(x, z, 0.4, height - 0.4, stone)
    for x0, x1, rail in ((-7.0, -4.6, -4.7), (4.6, 7.0, 4.6)):
        add_box([x0, 5.0, -length], [x1, 5.3, 0.0], wood)            # the gallery's floor
        add_box([rail, 5.3, -length], [rail + 0.1, 6.3, 0.0], wood)   # its railing

    # The buffer: positions, normals, then one index list per material (a primitive each).
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    normal_offset = len(blob)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
    ]
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": normal_offset},
             {"buffer": 0, "byteOffset": normal_offset, "byteLength": len(blob) - normal_offset}]
    mesh_primitives = []
    for material_index in sorted({m for _, _, m in primitives}):
        chunk = []
        for first, count, m in primitives:
            if m == material_index:
                chunk.extend(indices[first:first + count])
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": 4 * len(chunk)})
        blob += b"".join(struct.pack("<I", i) for i in chunk)
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(chunk), "type": "SCALAR"})
        mesh_primitives.append({"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": len(accessors) - 1,
                                "material": material_index})
    meshes = [{"name": "hall", "primitives": mesh_primitives}]

    def material(name, colour):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour + [1.0], "metallicFactor": 0.0,
                                                       "roughnessFactor": 1.0}}

    bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
    # The camera at eye height near the entrance, looking down the hall and a little up (yfov 60 degrees).
    pitch = math.radians(8.0)
    gltf = {
        "asset": {"version": "2.0", "generator": "tests/data/make_interior_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "hall", "mesh": 0},
                  {"name": "camera", "camera": 0, "translation": [1.5, 1.7, -1.5],
                   "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": math.radians(60.0), "znear": 0.05}}],
        "meshes": meshes,
        "materials": [material("stone", [0.75, 0.72, 0.66]), material("floor", [0.55, 0.5, 0.45]),
                      material("ceiling", [0.85, 0.85, 0.82]), material("wood", [0.45, 0.3, 0.18])],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": bin_name, "byteLength": len(blob)}],
    }
    with open(os.path.join(os.path.dirname(out) or ".", bin_name), "wb") as f:
        f.write(blob)
    with open(out, "w") as f:
        json.dump(gltf, f)
    print(f"{out}: {len(indices) // 3} triangles")


if __name__ == "__main__":
    main()
