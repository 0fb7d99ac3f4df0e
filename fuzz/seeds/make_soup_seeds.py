#!/usr/bin/env python3
"""Writes the seeds of the soup and filter harnesses (fuzz/seeds/soup) in the encoding of
fuzz/soup_bytes.hpp: a byte of vertex count, a byte per coordinate (grid value (b - 120) / 4,
codes 240+ for NaN, infinities and huge values), three signed bytes per face.
    /usr/bin/python3 fuzz/seeds/make_soup_seeds.py
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def coord(v):
    if isinstance(v, str):
        return {"nan": 240, "inf": 241, "-inf": 242, "huge": 243, "tiny": 245}[v]
    b = int(round(v * 4)) + 120
    assert 0 <= b < 240
    return b


def soup(positions, faces):
    out = bytearray([len(positions)])
    for p in positions:
        out += bytes(coord(c) for c in p)
    for f in faces:
        out += bytes(i & 0xFF for i in f)
    return bytes(out)


def grid(n, bump=0.0):
    pts = [(x * 1.0, y * 1.0, bump * ((x * 7 + y * 3) % 5 - 2) / 4) for y in range(n) for x in range(n)]
    faces = []
    for y in range(n - 1):
        for x in range(n - 1):
            a = y * n + x
            faces += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    return pts, faces


def main():
    d = os.path.join(HERE, "soup")
    os.makedirs(d, exist_ok=True)
    tetra = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2)]
    tetra_faces = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
    octa = [(2, 0, 0), (-2, 0, 0), (0, 2, 0), (0, -2, 0), (0, 0, 2), (0, 0, -2)]
    octa_faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    seeds = {
        "tetrahedron": soup(tetra, tetra_faces),
        "octahedron": soup(octa, octa_faces),
        "grid-4": soup(*grid(4, bump=1.0)),
        "grid-6-noisy": soup(*grid(6, bump=2.0)),
        # two fans meeting at vertex 0 (a bow tie), three faces on edge 1-2, one face flipped
        "bowtie": soup([(0, 0, 0), (2, 1, 0), (2, -1, 0), (-2, 1, 0), (-2, -1, 0)], [(0, 1, 2), (0, 3, 4)]),
        "fin": soup([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)], [(0, 1, 2), (1, 0, 3), (0, 1, 4)]),
        "flipped": soup(tetra, [(0, 2, 1), (0, 3, 1), (1, 2, 3), (0, 3, 2)]),
        # welded duplicates, a repeated index, a collinear face, an index past the end
        "duplicates": soup(tetra + [(0, 0, 0), (2, 0, 0)], tetra_faces + [(4, 5, 3), (0, 0, 1), (0, 1, 1)]),
        "collinear": soup([(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0)], [(0, 1, 2), (0, 1, 3)]),
        "out-of-range": soup(tetra, tetra_faces + [(0, 1, 126)]),
        "nan": soup([(0, 0, 0), ("nan", 0, 0), (0, 1, 0)], [(0, 1, 2)]),
        "huge": soup([(0, 0, 0), ("huge", 0, 0), (0, "huge", 0), (0, 0, "tiny")], tetra_faces),
    }
    for name, data in seeds.items():
        with open(os.path.join(d, name + ".bin"), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
