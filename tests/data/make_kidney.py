#!/usr/bin/env python3
"""Writes kidney.obj: a coarse, closed, non-convex organ-like control mesh
(128 triangles, metres) for the accuracy sweep, which refines it with
assimp's Catmull-Clark subdivision up to ~200,000 triangles. Deterministic:
no randomness, fixed print precision. Run from tests/data."""
import math

LON, LAT = 8, 9  # meridians; latitude bands (poles are fans)
A, B, C = 0.045, 0.025, 0.018  # half length, width, thickness of the bean
BEND = 9.0  # 1/m: bends the long axis into an arc, hollowing the inner side
DENT, DENT_W = 0.012, 0.02  # hilum: a dent in the middle of the inner side


def point(theta, phi):
    # Unit sphere -> ellipsoid -> bent bean with a dent on its inner (+y) side.
    sx, sy, sz = math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)
    x, y, z = A * sx, B * sy, C * sz
    y -= BEND * x * x
    y -= DENT * math.exp(-(x / DENT_W) ** 2) * max(0.0, sy) ** 2
    return x, y, z


verts = [point(0.0, 0.0)]
for i in range(1, LAT):
    for j in range(LON):
        verts.append(point(math.pi * i / LAT, 2 * math.pi * j / LON))
verts.append(point(math.pi, 0.0))
south = len(verts)  # 1-based index of the last vertex

def ring(i, j):  # 1-based OBJ index of ring i (1..LAT-1), meridian j
    return 2 + (i - 1) * LON + j % LON

faces = []
for j in range(LON):
    faces.append((1, ring(1, j), ring(1, j + 1)))
    for i in range(1, LAT - 1):
        a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
        faces += [(a, b, c), (a, c, d)]
    faces.append((south, ring(LAT - 1, j + 1), ring(LAT - 1, j)))

with open("kidney.obj", "w") as f:
    f.write("# kidney.obj: written by make_kidney.py; %d vertices, %d triangles, metres\n"
            % (len(verts), len(faces)))
    for v in verts:
        f.write("v %.6f %.6f %.6f\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % t)
