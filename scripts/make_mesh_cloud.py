#!/usr/bin/env python3
"""Writes data/meshes/cumulus.obj: a closed cauliflower-shaped mesh, the kind an artist would
model for a cumulus (seed 002's artists bake such meshes into voxel clouds). A sphere of
1 km diameter with a flat base, its surface pushed out by a dozen rounded turrets.
Deterministic; run it again to regenerate the file (`nephele voxelize` bakes it)."""
import math
import random
import sys

random.seed(2)
radius_m = 500.0
turrets = [(random.uniform(0, 2 * math.pi), random.uniform(0.1, 1.2), random.uniform(0.18, 0.35),
            random.uniform(0.5, 0.9)) for _ in range(14)]


def radius(theta, phi):
    """Surface radius towards (azimuth theta, elevation phi): the turrets' bumps added."""
    d = (math.cos(phi) * math.cos(theta), math.cos(phi) * math.sin(theta), math.sin(phi))
    r = 1.0
    for az, el, width, height in turrets:
        c = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
        cos_angle = sum(a * b for a, b in zip(c, d))
        angle = math.acos(max(-1.0, min(1.0, cos_angle)))
        if angle < width * 2.5:
            r += height * 0.35 * math.exp(-(angle / width) ** 2)
    return radius_m * r


rings, segments = 32, 64
vertices = [(0.0, 0.0, -radius_m)]  # south pole, flattened below
for i in range(1, rings):
    phi = -math.pi / 2 + math.pi * i / rings
    for j in range(segments):
        theta = 2 * math.pi * j / segments
        r = radius(theta, phi)
        vertices.append((r * math.cos(phi) * math.cos(theta), r * math.cos(phi) * math.sin(theta),
                         r * math.sin(phi)))
vertices.append((0.0, 0.0, radius(0.0, math.pi / 2)))  # north pole
base_z = -0.35 * radius_m  # the flat base: everything below is pressed onto it
vertices = [(x, y, max(z, base_z) - base_z) for x, y, z in vertices]

faces = []
ring = lambda i, j: 2 + (i - 1) * segments + j % segments  # 1-based OBJ index
for j in range(segments):
    faces.append((1, ring(1, j + 1), ring(1, j)))
for i in range(1, rings - 1):
    for j in range(segments):
        a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
        faces.append((a, b, c))
        faces.append((a, c, d))
top = len(vertices)
for j in range(segments):
    faces.append((top, ring(rings - 1, j), ring(rings - 1, j + 1)))

out = sys.stdout if len(sys.argv) < 2 else open(sys.argv[1], "w")
out.write("# nephele: a cumulus mesh to bake into a voxel cloud (scripts/make_mesh_cloud.py)\n")
for v in vertices:
    out.write("v %.1f %.1f %.1f\n" % v)
for f in faces:
    out.write("f %d %d %d\n" % f)
