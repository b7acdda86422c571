#!/usr/bin/env python3
"""Pixel facts of a PNG for the review tests (no PIL): the count and the
centroid of the pixels of each exact color of rscene-diff --review's
palette, in the top ROWS rows (the picture, above the legend band).

usage: review_png.py FILE [ROWS]
prints: NAME COUNT CX CY per palette color, then `size W H`.
usage: review_png.py --find SHOT IMAGE
prints `at X Y` where IMAGE appears pixel for pixel in SHOT (a browser's
screenshot), or `absent`."""
import struct
import sys
import zlib

PALETTE = {"added": (30, 200, 60), "removed": (230, 30, 30), "changed": (255, 140, 0), "ghost": (40, 120, 255)}


def decode(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, "unsupported PNG"
            bpp = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(height):
        f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, bpp, rows


def find(shot, image):
    sw, sh, sb, srows = decode(shot)
    iw, ih, ib, irows = decode(image)
    first = [b"".join(bytes(r[x * ib:x * ib + 3]) for x in range(iw)) for r in irows]
    for y in range(sh - ih + 1):
        line = b"".join(bytes(srows[y][x * sb:x * sb + 3]) for x in range(sw))
        x = line.find(first[0])
        while x >= 0:
            if x % 3 == 0:
                px = x // 3
                if all(b"".join(bytes(srows[y + k][(px + i) * sb:(px + i) * sb + 3]) for i in range(iw)) == first[k]
                       for k in range(ih)):
                    print("at", px, y)
                    return
            x = line.find(first[0], x + 1)
    print("absent")


def main():
    if sys.argv[1] == "--find":
        find(sys.argv[2], sys.argv[3])
        return
    width, height, bpp, rows = decode(sys.argv[1])
    top = int(sys.argv[2]) if len(sys.argv) > 2 else height
    for name, rgb in PALETTE.items():
        n = sx = sy = 0
        for y in range(top):
            line = rows[y]
            for x in range(width):
                if tuple(line[x * bpp:x * bpp + 3]) == rgb:
                    n, sx, sy = n + 1, sx + x, sy + y
        print(name, n, sx // n if n else -1, sy // n if n else -1)
    print("size", width, height)


main()
