#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_simplify (Testing/Fuzz/corpus/simplify).

Each seed is a header of 16 bytes and points of 7 bytes (flag, 3 x int16);
see the layout at the top of FuzzSimplify.cxx. Run from anywhere:
    python3 Testing/Fuzz/make_corpus.py
"""
import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus", "simplify")


def header(mode=0, count=20, cell=0, alpha=0.125, tol=0, spc=8.0, seed=1,
           scale=0, offset=0, link=2.0, weight=1.0, options=None):
    """options: the 4 bytes of the feature-preserving mode's options (sets mode bit 7)."""
    a = max(0, min(255, round((alpha + 0.05) / 0.6 * 255)))
    if options is not None:
        mode |= 128
    return bytes([mode, count & 255, count >> 8, cell, a, tol, round(spc * 8), seed,
                  (scale + 30) % 61, offset, round(link * 64), round(weight * 16),
                  *(options or (0, 0, 0, 0))])


def point(x, y, z, flag=7):
    c = [max(-32767, min(32767, round(v * 32767))) for v in (x, y, z)]
    return struct.pack("<Bhhh", flag, *c)


def sphere(n, rng, r=0.9):
    pts = []
    for _ in range(n):
        v = [rng.gauss(0, 1) for _ in range(3)]
        l = math.sqrt(sum(t * t for t in v)) or 1.0
        pts.append([r * t / l for t in v])
    return pts


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = random.Random(1)
    seeds = {}
    ball = sphere(200, rng)
    seeds["sphere"] = header(count=20) + b"".join(point(*p) for p in ball)
    seeds["sphere-snap-tolerance"] = header(mode=1, count=30, tol=160) + b"".join(point(*p) for p in ball)
    seeds["sphere-weight-normals"] = header(mode=2 | 32, count=25, seed=9) + b"".join(point(*p) for p in ball)
    wave = [(x / 10 - 0.9, y / 10 - 0.9, 0.2 * math.sin(x) * math.cos(y)) for x in range(19) for y in range(19)]
    seeds["wave-cellsize"] = header(count=40, cell=120) + b"".join(point(*p) for p in wave)
    seeds["plane"] = header(mode=4, count=10) + b"".join(point(*p) for p in ball[:100])
    seeds["line"] = header(mode=8, count=7) + b"".join(point(*p) for p in ball[:60])
    seeds["one-point"] = header(mode=12, count=3) + b"".join(point(*p) for p in ball[:20])
    seeds["nan-inf"] = header(count=15) + b"".join(
        point(*p, flag=(i % 3) + 16 * (i % 5) if i % 4 == 0 else 7) for i, p in enumerate(ball[:120]))
    seeds["duplicates"] = header(count=12) + b"".join(
        point(*p, flag=3 if i % 2 else 7) for i, p in enumerate(ball[:120]))
    seeds["utm-float"] = header(mode=16, count=20, scale=2, offset=128 + 2 * 7) + b"".join(point(*p) for p in ball)
    seeds["outliers"] = header(count=20) + b"".join(
        point(*p, flag=5 if i % 50 == 0 else 7) for i, p in enumerate(ball))
    seeds["tiny"] = header(count=10, scale=-25) + b"".join(
        point(*p, flag=6 if i % 3 == 0 else 7) for i, p in enumerate(ball[:90]))
    strip = [(rng.uniform(-1, 1), rng.uniform(-1, 1) * 1e-4, 0.0) for _ in range(150)]
    seeds["strip"] = header(count=15, scale=3) + b"".join(point(*p) for p in strip)
    seeds["all-pass-through"] = header(count=5000) + b"".join(point(*p) for p in ball[:50])
    # The feature-preserving mode's options (FuzzSimplify.cxx, ApplyFeatureOptions).
    seeds["options-all-off"] = header(count=25, options=(255, 64 | 5, 0, 0)) + b"".join(point(*p) for p in ball)
    seeds["options-long-lloyd"] = header(count=40, options=(0, 3 | 3 << 2 | 3 << 4 | 128, 0, 15 | 3 << 4 | 2 << 6)) + \
        b"".join(point(*p) for p in wave)
    seeds["options-fine-cells"] = header(count=30, options=(0, 0, 15 | 1 << 4, 1 << 4 | 3 << 6)) + \
        b"".join(point(*p) for p in ball)
    seeds["options-large-cells"] = header(count=150, options=(2, 2 << 2, 1 | 14 << 4, 8)) + \
        b"".join(point(*p) for p in ball)
    seeds["options-duplicates"] = header(count=12, options=(1 | 32 | 128, 1, 15 << 4, 0)) + b"".join(
        point(*p, flag=3 if i % 2 else 7) for i, p in enumerate(ball[:120]))
    for name, blob in seeds.items():
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(blob)
    print(f"{len(seeds)} seeds in {OUT}")


if __name__ == "__main__":
    main()
