#!/usr/bin/env python3
"""Writes tests/data/sky_64x32.hdr: the small equirectangular environment map the golden tests use (--environment).

A 64x32 Radiance HDR (RGBE, flat scanlines), in the mapping of docs/shading.md "The environment" (u = 0.5 looks down
-Z, u grows towards +X, v = 0 is straight up), made so that an orientation error shows:
  - above the horizon a sky from deep blue (zenith) to pale blue (horizon), tinted by quadrant of u;
  - a sun disc (radiance 20) in the -Z/+X quadrant, 35 degrees up;
  - below the horizon ground in four colours by quadrant of u: red around +Z (u = 0, the seam), green around -X
    (u = 0.25), blue around -Z (u = 0.5), yellow around +X (u = 0.75), darker towards the nadir.
Standard library only: python3 tests/data/make_sky_hdr.py [OUT]
"""
import math
import os
import sys

WIDTH, HEIGHT = 64, 32
QUADRANT = [(1.0, 0.25, 0.2), (0.25, 0.9, 0.25), (0.25, 0.35, 1.0), (1.0, 0.85, 0.2)]   # +Z, -X, -Z, +X
SUN_U, SUN_V, SUN_RADIUS = 0.625, 0.5 - 35.0 / 180.0, 0.12   # direction of the sun; radius in radians


def direction(u, v):
    phi = (u - 0.5) * 2.0 * math.pi      # 0 at -Z, +pi/2 at +X
    theta = v * math.pi                  # 0 straight up
    s = math.sin(theta)
    return (s * math.sin(phi), math.cos(theta), -s * math.cos(phi))


def radiance(x, y):
    u, v = (x + 0.5) / WIDTH, (y + 0.5) / HEIGHT
    # Quadrant centred on +Z, -X, -Z, +X (u = 0, 0.25, 0.5, 0.75).
    q = QUADRANT[int(math.floor(u * 4.0 + 0.5)) % 4]
    if v < 0.5:                          # sky: zenith to horizon, a tenth of the quadrant's colour
        t = v / 0.5
        c = [(0.15 + 0.6 * t) * b + 0.1 * qc for b, qc in zip((0.35, 0.55, 1.0), q)]
        d, s = direction(u, v), direction(SUN_U, SUN_V)
        if math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(d, s))))) < SUN_RADIUS:
            c = [20.0, 18.0, 14.0]
        return c
    t = (v - 0.5) / 0.5                  # ground: horizon to nadir
    return [qc * (0.6 - 0.4 * t) for qc in q]


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(c[0] * scale), int(c[1] * scale), int(c[2] * scale), exponent + 128])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "sky_64x32.hdr")
    data = bytearray(b"#?RADIANCE\n# tests/data/make_sky_hdr.py\nFORMAT=32-bit_rle_rgbe\n\n")
    data += b"-Y %d +X %d\n" % (HEIGHT, WIDTH)
    for y in range(HEIGHT):
        row = b"".join(rgbe(radiance(x, y)) for x in range(WIDTH))
        assert row[0:2] != b"\x02\x02", "a flat scanline must not start like an RLE one"
        data += row
    with open(out, "wb") as f:
        f.write(data)


if __name__ == "__main__":
    main()
