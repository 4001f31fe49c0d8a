#!/usr/bin/env python3
"""Writes the example image set of scenes/species/painted_birch.json (issue #16): a leaf (colour
with the outline in alpha, normal map, translucency), bark (colour, normal) and a season column
(seed 000 §4.6: one column, top = season 1, 0 = 1 January; transparent rows = no leaves).
Colours are sRGB as an image editor stores them. Standard library only; deterministic:

    python3 scenes/species/images/make_images.py   # rewrites the PNGs next to this script
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write_png(name, width, height, channels, pixel):
    """pixel(x, y) -> tuple of `channels` floats in [0, 1]; y = 0 is the top row."""
    color_type = {1: 0, 3: 2, 4: 6}[channels]
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # no filter
        for x in range(width):
            for v in pixel(x, y)[:channels]:
                rows.append(max(0, min(255, int(round(v * 255.0)))))
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(png)


def hash01(x, y, seed):
    h = (x * 374761393 + y * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65535.0


def smooth_noise(u, v, cells, seed):
    """Value noise on a `cells` grid, tiling over [0, 1)^2."""
    x, y = u * cells, v * cells
    x0, y0 = int(math.floor(x)), int(math.floor(y))
    tx, ty = x - x0, y - y0
    tx, ty = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)
    c = lambda i, j: hash01((x0 + i) % cells, (y0 + j) % cells, seed)
    return (c(0, 0) * (1 - tx) + c(1, 0) * tx) * (1 - ty) + (c(0, 1) * (1 - tx) + c(1, 1) * tx) * ty


# Leaf: a birch-like ovate blade, base at the bottom of the image (v = 0), tip at the top.
LEAF = 64


def leaf_uv(x, y):
    return (x + 0.5) / LEAF, 1.0 - (y + 0.5) / LEAF


def half_width(v):
    if v < 0.08 or v > 0.98:
        return 0.0
    s = (v - 0.08) / 0.9
    return 0.46 * math.sin(math.pi * s ** 0.8) * (1.0 - 0.25 * s)


def leaf_height(u, v):
    """Vein relief: midrib and seven secondary veins per side."""
    d = abs(u - 0.5)
    mid = max(0.0, 1.0 - d / 0.025)
    sec = 0.0
    for k in range(7):
        start = 0.16 + 0.11 * k
        line = start + 0.9 * d  # veins run up and out
        sec = max(sec, max(0.0, 1.0 - abs(v - line) / 0.018) * 0.6)
    return max(mid, sec)


def leaf_color(x, y):
    u, v = leaf_uv(x, y)
    w = half_width(v)
    inside = abs(u - 0.5) < w - 0.01 * math.sin(60 * v) ** 2  # small teeth
    if not inside:
        return (0.0, 0.0, 0.0, 0.0)
    n = smooth_noise(u, v, 8, 3) - 0.5
    h = leaf_height(u, v)
    return (0.32 + 0.10 * n + 0.10 * h, 0.52 + 0.12 * n + 0.10 * h, 0.16 + 0.05 * n + 0.04 * h, 1.0)


def leaf_normal(x, y):
    u, v = leaf_uv(x, y)
    e = 1.0 / LEAF
    du = (leaf_height(u + e, v) - leaf_height(u - e, v)) / (2 * e)
    dv = (leaf_height(u, v + e) - leaf_height(u, v - e)) / (2 * e)
    # Veins are grooves on the upper side: the normal leans towards them.
    n = (0.015 * du, 0.015 * dv, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    thickness = 0.25 + 0.5 * leaf_height(u, v)
    return tuple(0.5 + 0.5 * c / length for c in n) + (thickness,)


def leaf_translucency(x, y):
    u, v = leaf_uv(x * 2, y * 2)  # 32 x 32
    return (0.65 - 0.35 * leaf_height(u, v),)


# Bark: birch, white with dark horizontal lenticels and a few black patches; tiles.
BARK = 64


def bark_mark(u, v):
    band = smooth_noise(u * 0.25, v, 24, 11)
    patch = smooth_noise(u, v, 4, 12)
    return min(1.0, max(0.0, (band - 0.72) * 6.0) + max(0.0, (patch - 0.78) * 5.0))


def bark_color(x, y):
    u, v = x / BARK, y / BARK
    m = bark_mark(u, v)
    g = 0.86 + 0.08 * (smooth_noise(u, v, 16, 13) - 0.5)
    return (g * (1 - m) + 0.12 * m, g * (1 - m) + 0.11 * m, g * 0.97 * (1 - m) + 0.10 * m)


def bark_normal(x, y):
    u, v = x / BARK, y / BARK
    e = 1.0 / BARK
    dv = (bark_mark(u, v + e) - bark_mark(u, v - e)) / (2 * e)
    n = (0.0, 0.02 * dv, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(0.5 + 0.5 * c / length for c in n)


# Season column, 24 rows, top row = season 1 (= 1 January a year later).
SEASON_KEYS = [  # (season, sRGB colour, presence)
    (0.00, (0.30, 0.40, 0.12), 0.0), (0.28, (0.30, 0.40, 0.12), 0.0), (0.30, (0.55, 0.75, 0.25), 1.0),
    (0.45, (0.33, 0.52, 0.16), 1.0), (0.70, (0.36, 0.50, 0.14), 1.0), (0.78, (0.85, 0.70, 0.15), 1.0),
    (0.86, (0.80, 0.45, 0.10), 1.0), (0.88, (0.70, 0.40, 0.10), 0.0), (1.00, (0.30, 0.40, 0.12), 0.0)]
SEASON_ROWS = 24


def season(x, y):
    s = 1.0 - (y + 0.5) / SEASON_ROWS
    for (a, ca, pa), (b, cb, pb) in zip(SEASON_KEYS, SEASON_KEYS[1:]):
        if a <= s <= b:
            t = (s - a) / (b - a)
            return tuple(ca[i] + (cb[i] - ca[i]) * t for i in range(3)) + (pa + (pb - pa) * t,)
    return SEASON_KEYS[-1][1] + (0.0,)


if __name__ == "__main__":
    write_png("birch_leaf.png", LEAF, LEAF, 4, leaf_color)
    write_png("birch_leaf_n.png", LEAF, LEAF, 4, leaf_normal)
    write_png("birch_leaf_t.png", 32, 32, 1, leaf_translucency)
    write_png("birch_bark.png", BARK, BARK, 3, bark_color)
    write_png("birch_bark_n.png", BARK, BARK, 3, bark_normal)
    write_png("birch_season.png", 1, SEASON_ROWS, 4, season)
