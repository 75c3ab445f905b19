#!/usr/bin/env python3
"""Writes the seeds of fuzz/corpus that are binary: request protos (through
`protoc --encode`, from the text below) and small PNG files (written here by
hand, chunk by chunk, so no imaging library is needed). The text seeds of the
other corpora are kept as files. Run from anywhere: fuzz/make-seeds.py."""
import pathlib
import struct
import subprocess
import zlib

FUZZ = pathlib.Path(__file__).resolve().parent
PROTO = FUZZ.parent / "proto"

# (file, selector byte of request_fuzzer.cc, message type, text format)
REQUESTS = [
    ("get_points_default", 0, "GetPointsRequest", "rect { x0: 0 y0: 0 x1: 8 y1: 8 }"),
    ("get_points_inline_a1", 0, "GetPointsRequest",
     "world { seed: 7 min_distance: 0.5 algorithm: ALGORITHM_A1 density: 1.5 } "
     "rect { x0: -3 y0: -3 x1: 2 y1: 2 } page_size: 10"),
    ("get_points_named_token", 0, "GetPointsRequest",
     'world_name: "sparse" rect { x0: -4 y0: -4 x1: 4 y1: 4 } page_size: 3 page_token: "01abcdef"'),
    ("get_points_far", 0, "GetPointsRequest",
     "world { seed: 3 min_distance: 1 algorithm: ALGORITHM_A2 generator_version: 3 } "
     "rect { x0: 4294967290 y0: -4294967296 x1: 4294967296 y1: -4294967290 }"),
    ("get_points_exact", 0, "GetPointsRequest",
     "world { seed: 5 min_distance: 1 algorithm: ALGORITHM_A3 } "
     "rect { x0: -20 y0: 1e9 x1: 5 y1: 1000000012 } encoding: POINT_ENCODING_EXACT"),
    ("get_points_quantised", 0, "GetPointsRequest",
     "rect { x0: -9 y0: -9 x1: 9 y1: 9 } page_size: 7 encoding: POINT_ENCODING_QUANTISED"),
    ("get_points_layers", 0, "GetPointsRequest",
     'world_name: "forest" rect { x0: -6 y0: -6 x1: 6 y1: 6 } page_size: 9 layers: "rocks"'),
    ("get_points_inline_layers", 0, "GetPointsRequest",
     "world { seed: 2 algorithm: ALGORITHM_A3 layers { name: \"big\" min_distance: 4 } "
     "layers { name: \"small\" radius_field { noise { r_min: 1 r_max: 2 frequency: 0.05 } } } "
     "exclusions { first: \"big\" second: \"small\" distance: 1.5 } } "
     "rect { x0: -5 y0: -5 x1: 5 y1: 5 } encoding: POINT_ENCODING_EXACT"),
    ("nearest_layer", 3, "NearestRequest",
     'world_name: "forest" layer: "rocks" positions { xs: [0.5, 9] ys: [0.5, -3] }'),
    ("stream_points", 1, "StreamPointsRequest",
     "world { seed: 1 min_distance: 1 algorithm: ALGORITHM_A3 } rect { x0: 0 y0: 0 x1: 1000 y1: 1000 }"),
    ("verify", 2, "VerifyRequest", 'world_name: "default" rect { x0: 10 y0: 10 x1: 50 y1: 60 }'),
    ("nearest", 3, "NearestRequest", "positions { xs: [0.5, 100, -7.25] ys: [0.5, -3, 1e6] }"),
    ("nearest_inline", 3, "NearestRequest",
     "world { seed: 9 min_distance: 0.25 algorithm: ALGORITHM_A3 } positions { xs: [1] ys: [2] }"),
    ("noise_grid", 4, "NoiseGridRequest",
     "origin_x: -8 origin_y: 3 step: 0.5 width: 16 height: 9 channel: NOISE_CHANNEL_F2_MINUS_F1"),
    ("noise_grid_ids", 4, "NoiseGridRequest",
     'world_name: "sparse" step: 2 width: 4 height: 4 channel: NOISE_CHANNEL_ID'),
    ("follow", 5, "FollowRequest",
     "viewport { x0: 0 y0: 0 x1: 64 y1: 48 } velocity_x: 10 velocity_y: -2 keep_margin: 16 "
     "held_regions { i: 0 j: 0 } held_regions { i: -1 j: 2 } sequence: 1"),
    ("describe", 6, "DescribeWorldRequest", 'world_name: "default"'),
    ("describe_inline", 6, "DescribeWorldRequest",
     "world { seed: 18446744073709551615 min_distance: 1e-3 algorithm: ALGORITHM_A1 density: 2 }"),
]


def encode(message_type, text):
    return subprocess.run(
        ["protoc", f"--encode=scallop.v1.{message_type}", "-I", str(PROTO),
         str(PROTO / "scallop/v1/scallop.proto")],
        input=text.encode(), capture_output=True, check=True).stdout


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))


def png(width, height, bit_depth, colour_type, rows, extra=b""):
    header = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    raw = b"".join(b"\x00" + row for row in rows)  # filter type 0 on every row
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + extra +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def main():
    requests = FUZZ / "corpus/request_fuzzer"
    requests.mkdir(parents=True, exist_ok=True)
    for name, selector, message_type, text in REQUESTS:
        (requests / name).write_bytes(bytes([selector]) + encode(message_type, text))

    rasters = FUZZ / "corpus/raster_png_fuzzer"
    rasters.mkdir(parents=True, exist_ok=True)
    gray8 = [bytes((16 * x + 64 * y) % 256 for x in range(4)) for y in range(3)]
    (rasters / "gray8_4x3.png").write_bytes(png(4, 3, 8, 0, gray8))
    gray16 = [struct.pack(">HH", 0, 65535), struct.pack(">HH", 4096, 30000)]
    (rasters / "gray16_2x2.png").write_bytes(png(2, 2, 16, 0, gray16))
    rgb = [bytes([255, 0, 0, 0, 255, 0])]
    (rasters / "rgb_2x1.png").write_bytes(png(2, 1, 8, 2, rgb))
    palette = chunk(b"PLTE", bytes([0, 0, 0, 255, 255, 255]))
    (rasters / "palette_2x2.png").write_bytes(png(2, 2, 8, 3, [b"\x00\x01", b"\x01\x00"], palette))
    gray1 = [bytes([0b10100000])]
    (rasters / "gray1_3x1.png").write_bytes(png(3, 1, 1, 0, gray1))
    # A header that claims a huge image over a tiny body: refused before decoding.
    (rasters / "huge_header.png").write_bytes(png(16384, 16384, 8, 0, [b"\x00"]))
    (rasters / "truncated.png").write_bytes(png(4, 3, 8, 0, gray8)[:40])


if __name__ == "__main__":
    main()
