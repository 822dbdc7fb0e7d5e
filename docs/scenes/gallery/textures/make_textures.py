#!/usr/bin/env python3
"""Writes the ribbon textures of the gallery scenes (README "Textured ribbons") into this folder:
  gradient.png   256x4: white-hot to orange to a dark red, opaque to clear along u (stretch)
  chevrons.png   64x32: chevrons pointing along the motion, white on clear (per segment, tiled,
                 distance)
  slash_noise.png 256x64: a pale blue slash, bright at its outer edge (v = 0), its alpha a noise
                 that repeats along u (scrolled and eroded)
Only Python's standard library: the PNGs are written by hand (8-bit RGBA, no filtering).
  python3 docs/scenes/gallery/textures/make_textures.py"""
import math
import os
import random
import struct
import zlib


def write_png(path, width, height, texel):
    rows = b"".join(
        b"\x00" + b"".join(bytes(texel(x, y)) for x in range(width)) for y in range(height))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


def byte(v):
    return max(0, min(255, int(round(255 * v))))


def mix(a, b, t):
    return [a[i] + (b[i] - a[i]) * t for i in range(len(a))]


def gradient(x, y, width=256):
    u = (x + 0.5) / width
    stops = [(0.0, [1, 1, 0.9]), (0.3, [1, 0.6, 0.15]), (1.0, [0.5, 0.05, 0.02])]
    c = stops[-1][1]
    for (a, ca), (b, cb) in zip(stops, stops[1:]):
        if a <= u <= b:
            c = mix(ca, cb, (u - a) / (b - a))
            break
    return [byte(c[0]), byte(c[1]), byte(c[2]), byte((1 - u) ** 1.5)]


def chevron(x, y, width=64, height=32):
    u, v = (x + 0.5) / width, (y + 0.5) / height
    # A chevron's point leads (towards the head, u = 0); soft by a texel.
    w = (u - 0.6 * abs(v - 0.5)) % 1.0
    a = max(0.0, min(1.0, (0.45 - abs(w - 0.45) * 2.0) * width / 4.0 + 0.5))
    return [255, 255, 255, byte(a)]


def noise_table(period, seed):
    rng = random.Random(seed)
    return [[rng.random() for _ in range(period)] for _ in range(period)]


def value_noise(table, u, v):
    """Smooth value noise on a grid that wraps in both directions."""
    n = len(table)
    x, y = u * n, v * n
    x0, y0 = int(math.floor(x)), int(math.floor(y))
    fx, fy = x - x0, y - y0
    sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)

    def at(i, j):
        return table[j % n][i % n]

    top = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * sx
    bottom = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * sx
    return top + (bottom - top) * sy


TABLES = [noise_table(p, 7 + p) for p in (4, 8, 16, 32)]


def slash_noise(x, y, width=256, height=64):
    u, v = (x + 0.5) / width, (y + 0.5) / height
    # Streaks along the motion: the noise varies three times faster across (v) than along (u).
    n = sum(value_noise(t, u, v * 3.0) * 0.5 ** i for i, t in enumerate(TABLES)) / 1.875
    # Bright, dense at the outer edge (v = 0), thinning towards the inner one.
    a = max(0.0, min(1.0, (n - 0.3) * 3.0)) * (1.0 - 0.5 * v)
    c = mix([1.0, 1.0, 1.0], [0.45, 0.7, 1.0], min(1.0, v * 1.5))
    return [byte(c[0]), byte(c[1]), byte(c[2]), byte(a)]


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    write_png(os.path.join(here, "gradient.png"), 256, 4, gradient)
    write_png(os.path.join(here, "chevrons.png"), 64, 32, chevron)
    write_png(os.path.join(here, "slash_noise.png"), 256, 64, slash_noise)
