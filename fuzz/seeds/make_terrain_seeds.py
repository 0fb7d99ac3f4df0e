#!/usr/bin/env python3
"""Writes the seed files of the terrain harnesses (fuzz/seeds/las, fuzz/seeds/tif): small LAS point
sets and DEM GeoTIFFs laid out byte by byte after the ASPRS LAS 1.2/1.4 and TIFF 6.0 + GeoTIFF 1.0
layouts, one per variant the readers distinguish (point formats with and without RGB, the 1.4
64-bit count; strips and tiles, integer and float samples, deflate and PackBits compression,
nodata, PixelIsPoint, ModelTransformation). Standard library only; run it from anywhere:
    /usr/bin/python3 fuzz/seeds/make_terrain_seeds.py
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def grid_points(n, seed):
    """n pseudo-random points (x, y, z as LAS integers), deterministic."""
    pts, s = [], seed
    for i in range(n):
        s = (s * 1103515245 + 12345) & 0x7FFFFFFF
        x, y = (i % 5) * 100 + s % 37, (i // 5) * 100 + (s >> 8) % 41
        pts.append((x, y, (s >> 4) % 500, (2, 3, 5, 9)[i % 4], (s >> 3) % 65536))
    return pts


def las(minor, fmt, pts):
    header = 375 if minor >= 4 else (235 if minor == 3 else 227)
    rec = {0: 20, 1: 28, 2: 26, 3: 34, 6: 30, 7: 36}[fmt]
    b = bytearray(header + rec * len(pts))
    b[0:4] = b"LASF"
    b[24], b[25] = 1, minor
    struct.pack_into("<HI", b, 94, header, header)  # header size, offset to the points (no VLR)
    b[104] = fmt
    struct.pack_into("<H", b, 105, rec)
    struct.pack_into("<I", b, 107, 0 if fmt >= 6 else len(pts))
    struct.pack_into("<3d", b, 131, 0.01, 0.01, 0.01)
    struct.pack_into("<3d", b, 155, 1000.0, 2000.0, 0.0)
    if minor >= 4:
        struct.pack_into("<Q", b, 247, len(pts))
    rgb_at = {2: 20, 3: 28, 7: 30}.get(fmt)
    for i, (x, y, z, cls, c) in enumerate(pts):
        at = header + i * rec
        struct.pack_into("<3i", b, at, x, y, z)
        b[at + (16 if fmt >= 6 else 15)] = cls
        if rgb_at:
            struct.pack_into("<3H", b, at + rgb_at, c, (c * 7) % 65536, (c * 13) % 256)
    return bytes(b)


# --- TIFF -----------------------------------------------------------------------------------------
SHORT, LONG, ASCII, DOUBLE = 3, 4, 2, 12
SIZES = {SHORT: 2, LONG: 4, ASCII: 1, DOUBLE: 8}
FMT = {SHORT: "H", LONG: "I", DOUBLE: "d"}


def packbits(data):
    out, i = bytearray(), 0
    while i < len(data):
        chunk = data[i:i + 128]
        out.append(len(chunk) - 1)  # a literal run
        out += chunk
        i += 128
    return bytes(out)


def tiff(width, height, values, sample_format, bits, tile=None, compression=1, geo="scale",
         nodata=None, pixel_is_point=False):
    """Little-endian TIFF: one image, band 1, the blocks first, then the IFD and its values."""
    code = {(1, 8): "B", (1, 16): "H", (1, 32): "I", (2, 8): "b", (2, 16): "h", (2, 32): "i",
            (3, 32): "f", (3, 64): "d"}[(sample_format, bits)]
    bw, bh = (tile, tile) if tile else (width, 4)
    blocks = []
    for y0 in range(0, height, bh):
        for x0 in range(0, width if tile else 1, bw):
            cells = []
            for r in range(bh):
                for c in range(bw if tile else width):
                    y, x = y0 + r, x0 + c
                    if tile or y < height:
                        inside = y < height and x < width
                        cells.append(values[y * width + x] if inside else 0)
            raw = struct.pack("<%d%s" % (len(cells), code), *cells)
            blocks.append(zlib.compress(raw) if compression == 8 else packbits(raw) if compression == 32773 else raw)
    out = bytearray(b"II*\0\0\0\0\0")
    offsets = []
    for blk in blocks:
        offsets.append(len(out))
        out += blk
        if len(out) % 2:
            out.append(0)
    entries = [(256, LONG, [width]), (257, LONG, [height]), (258, SHORT, [bits]), (259, SHORT, [compression]),
               (262, SHORT, [1]), (277, SHORT, [1]), (284, SHORT, [1]), (339, SHORT, [sample_format])]
    if tile:
        entries += [(322, LONG, [tile]), (323, LONG, [tile]), (324, LONG, offsets),
                    (325, LONG, [len(b) for b in blocks])]
    else:
        entries += [(273, LONG, offsets), (278, LONG, [bh]), (279, LONG, [len(b) for b in blocks])]
    if geo == "scale":
        entries += [(33550, DOUBLE, [30.0, 30.0, 0.0]), (33922, DOUBLE, [0, 0, 0, 500000.0, 4100000.0, 0])]
    elif geo == "matrix":
        entries += [(34264, DOUBLE, [0.5, 0.1, 0, 10.0, 0.05, -0.5, 0, 50.0, 0, 0, 0, 0, 0, 0, 0, 1])]
    keys = [1, 1, 0, 2, 1024, 0, 1, 2 if geo == "geographic" else 1, 1025, 0, 1, 2 if pixel_is_point else 1]
    if geo == "geographic":
        entries += [(33550, DOUBLE, [0.01, 0.01, 0.0]), (33922, DOUBLE, [0, 0, 0, 7.0, 46.0, 0])]
    entries.append((34735, SHORT, keys))
    if nodata is not None:
        entries.append((42113, ASCII, list(nodata.encode() + b"\0")))
    entries.sort()
    ifd_at = len(out)
    struct.pack_into("<I", out, 4, ifd_at)
    ifd = bytearray(struct.pack("<H", len(entries)))
    extra_at = ifd_at + 2 + 12 * len(entries) + 4
    extra = bytearray()
    for tag, typ, vals in entries:
        payload = bytes(vals) if typ == ASCII else struct.pack("<%d%s" % (len(vals), FMT[typ]), *vals)
        if len(payload) <= 4:
            ifd += struct.pack("<HHI", tag, typ, len(vals)) + payload.ljust(4, b"\0")
        else:
            ifd += struct.pack("<HHII", tag, typ, len(vals), extra_at + len(extra))
            extra += payload
            if len(extra) % 2:
                extra.append(0)
    ifd += b"\0\0\0\0"
    return bytes(out + ifd + extra)


def main():
    d = os.path.join(HERE, "las")
    os.makedirs(d, exist_ok=True)
    for name, minor, fmt, n in [("v12-format0", 2, 0, 12), ("v12-format3-rgb", 2, 3, 9), ("v13-format1", 3, 1, 7),
                                ("v14-format6", 4, 6, 10), ("v14-format7-rgb", 4, 7, 8)]:
        with open(os.path.join(d, name + ".las"), "wb") as f:
            f.write(las(minor, fmt, grid_points(n, minor * 16 + fmt)))
    d = os.path.join(HERE, "tif")
    os.makedirs(d, exist_ok=True)
    w, h = 7, 6
    ramp = [(x * 3 + y * 5) % 17 for y in range(h) for x in range(w)]
    seeds = {
        "strips-int16": tiff(w, h, ramp, 2, 16),
        "strips-uint8-packbits-point": tiff(w, h, ramp, 1, 8, compression=32773, pixel_is_point=True),
        "strips-float32-deflate-nodata": tiff(w, h, [v if v != 4 else -9999.0 for v in ramp], 3, 32,
                                              compression=8, nodata="-9999"),
        "tiles-float64-matrix": tiff(w, h, [v * 0.25 for v in ramp], 3, 64, tile=16, geo="matrix"),
        "tiles-uint32-geographic": tiff(w, h, ramp, 1, 32, tile=16, geo="geographic"),
        "strips-int32-plain": tiff(w, h, ramp, 2, 32, geo="none"),
    }
    for name, data in seeds.items():
        with open(os.path.join(d, name + ".tif"), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
