#!/usr/bin/env python3
"""Writes a PNG for the shell tests of raster radius fields, with nothing but the standard
library (zlib), so no image package is needed.

Usage: make_gray_png.py OUT KIND WIDTH HEIGHT
  KIND ramp:   8-bit grey, v = 1 + (column + row) * 4 (capped at 255), bottom row first
  KIND masked: as ramp, but column 0 is 0 (masked)
  KIND ramp16: 16-bit grey, v = 1 + (column + row) * 1000
  KIND rgb:    8-bit colour (the loader must refuse it)
  KIND road:   8-bit, 255 but for a winding road 6 pixels wide that is 0 (masked): the README's
               forest of layers
"""
import math
import struct
import sys
import zlib


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def main():
    out, kind, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    depth, colour = (16, 0) if kind == "ramp16" else (8, 2 if kind == "rgb" else 0)
    rows = []
    # The file stores the top row first; the world's bottom row (row 0) is the file's last.
    for top in range(height):
        row = height - 1 - top
        line = bytearray([0])  # filter: none
        for column in range(width):
            if kind == "ramp16":
                line += struct.pack(">H", min(65535, 1 + (column + row) * 1000))
            elif kind == "road":
                centre = height / 2 + height / 5 * math.sin(column / width * 2 * math.pi)
                line.append(0 if abs(row + 0.5 - centre) < 3 else 255)
            elif kind == "rgb":
                line += bytes([column % 256, row % 256, 7])
            else:
                v = 0 if kind == "masked" and column == 0 else min(255, 1 + (column + row) * 4)
                line.append(v)
        rows.append(bytes(line))
    header = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    with open(out, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))


if __name__ == "__main__":
    main()
