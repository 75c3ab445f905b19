#!/usr/bin/python3
"""A Python client of scallopd: the points of a world's rectangle as CSV.

Prints `id,x,y` rows exactly as `scallop plane` does for the same world and
rectangle (ids in decimal, coordinates with 17 significant digits), reading
every page of GetPoints or, with --stream, the chunks of StreamPoints. A world
with a radius field (--radius-noise, or a named one) prints `id,x,y,r`, r
being the spacing the field wants at the point.
Stubs come from generate_stubs.sh; put their folder on PYTHONPATH.

With --tls-ca (and --tls-cert/--tls-key for mutual TLS) it speaks TLS; a
token from --token-file or the SCALLOP_TOKEN environment variable (kept out
of shell history) goes with every call as "authorization: Bearer TOKEN".

--encoding exact or quantised asks for the compact encodings of
docs/wire.md (decode_points below decodes them: exact gives the same
doubles, quantised coordinates within 2^-13 d); packed, the default, is the
plain arrays.

--server takes HOST:PORT or any gRPC target (dns:///HOST:PORT,
ipv4:A:PORT,B:PORT): calls are balanced round_robin over its addresses and
the idempotent calls (GetPoints here) retried on UNAVAILABLE, with the
service config of the C++ client library (SERVICE_CONFIG).

  ./generate_stubs.sh /tmp/scallop-py
  PYTHONPATH=/tmp/scallop-py ./scallop_points.py --server 127.0.0.1:50051 \
      --seed 7 --rect=0,0,40,40   # "=": argparse reads "-5,..." as a flag
"""
import argparse
import json
import math
import os
import struct
import sys

import grpc

from scallop.v1 import scallop_pb2, scallop_pb2_grpc

ALGORITHMS = {
    "a1": scallop_pb2.ALGORITHM_A1,
    "a2": scallop_pb2.ALGORITHM_A2,
    "a3": scallop_pb2.ALGORITHM_A3,
}

ENCODINGS = {
    "packed": scallop_pb2.POINT_ENCODING_PACKED,
    "exact": scallop_pb2.POINT_ENCODING_EXACT,
    "quantised": scallop_pb2.POINT_ENCODING_QUANTISED,
}


# The C++ client library's service config (client/library/service_config.h;
# tests/e2e/python_client_test.sh checks that the two agree): round_robin,
# and retries of the pure reads on UNAVAILABLE (a replica that went away).
# Streams are not retried: a retry would send again what was received.
SERVICE_CONFIG = {
    "loadBalancingConfig": [{"round_robin": {}}],
    "methodConfig": [{
        "name": [{"service": "scallop.v1.Scallop", "method": method} for method in (
            "GetPoints", "Nearest", "NoiseGrid", "DescribeWorld", "GetServerInfo", "Verify")],
        "retryPolicy": {
            "maxAttempts": 4,
            "initialBackoff": "0.1s",
            "maxBackoff": "1s",
            "backoffMultiplier": 2,
            "retryableStatusCodes": ["UNAVAILABLE"],
        },
    }],
}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--server", default="127.0.0.1:50051", help="HOST:PORT or gRPC target (dns:///HOST:PORT, ipv4:A:P,B:P)")
    parser.add_argument("--world", help="name of a world configured on the server")
    parser.add_argument("--seed", type=int, help="seed of an inline world (0..2^64-1)")
    parser.add_argument("--min-distance", type=float, default=1.0)
    parser.add_argument("--algorithm", choices=sorted(ALGORITHMS), default="a3")
    parser.add_argument("--density", type=float, default=0.0, help="r'/2r; 0: default")
    parser.add_argument("--radius-noise", metavar="R_MIN,R_MAX,FREQUENCY[,OCTAVES]",
                        help="an inline world's noise radius field (instead of --min-distance)")
    parser.add_argument("--radius-noise-seed", type=int, default=0, help="the noise's own seed")
    parser.add_argument("--rect", required=True, help="X0,Y0,X1,Y1 (half-open)")
    parser.add_argument("--stream", action="store_true", help="use StreamPoints")
    parser.add_argument("--page-size", type=int, default=0)
    parser.add_argument("--encoding", choices=sorted(ENCODINGS), default="packed",
                        help="how points travel (docs/wire.md)")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per call")
    parser.add_argument("--tls-ca", help="PEM roots that sign the server (turns TLS on)")
    parser.add_argument("--tls-cert", help="PEM client certificate, for mutual TLS")
    parser.add_argument("--tls-key", help="PEM private key of --tls-cert")
    parser.add_argument("--token-file", help="file whose first line is the bearer token")
    return parser.parse_args(argv)


def world_choice(arguments):
    """The oneof world_choice of a request: a name, an inline world or neither."""
    if arguments.world is not None:
        return {"world_name": arguments.world}
    if arguments.seed is not None:
        world = scallop_pb2.World(
            seed=arguments.seed, min_distance=arguments.min_distance,
            algorithm=ALGORITHMS[arguments.algorithm], density=arguments.density)
        if arguments.radius_noise is not None:
            world.radius_field.noise.CopyFrom(noise_field(arguments))
        return {"world": world}
    return {}


def noise_field(arguments):
    """--radius-noise as a NoiseRadiusField; octaves and gain 0 mean the server's defaults."""
    values = [float(v) for v in arguments.radius_noise.split(",")]
    if len(values) not in (3, 4):
        raise ValueError("--radius-noise: expected R_MIN,R_MAX,FREQUENCY[,OCTAVES]")
    return scallop_pb2.NoiseRadiusField(
        r_min=values[0], r_max=values[1], frequency=values[2],
        octaves=int(values[3]) if len(values) == 4 else 0,
        noise_seed=arguments.radius_noise_seed)


def read_file(flag, path):
    try:
        with open(path, "rb") as file:
            return file.read()
    except OSError as error:
        raise ValueError(f"{flag}: cannot read '{path}': {error.strerror}") from error


def open_channel(arguments):
    """Plaintext, TLS or mutual TLS, as the --tls-* options ask."""
    options = [("grpc.service_config", json.dumps(SERVICE_CONFIG))]
    if not (arguments.tls_ca or arguments.tls_cert):
        return grpc.insecure_channel(arguments.server, options=options)
    if bool(arguments.tls_cert) != bool(arguments.tls_key):
        raise ValueError("--tls-cert and --tls-key: give both or neither")
    credentials = grpc.ssl_channel_credentials(
        root_certificates=arguments.tls_ca and read_file("--tls-ca", arguments.tls_ca),
        private_key=arguments.tls_key and read_file("--tls-key", arguments.tls_key),
        certificate_chain=arguments.tls_cert and read_file("--tls-cert", arguments.tls_cert))
    return grpc.secure_channel(arguments.server, credentials, options=options)


def call_metadata(arguments):
    """The bearer token, from --token-file or SCALLOP_TOKEN, as call metadata."""
    token = os.environ.get("SCALLOP_TOKEN", "")
    if arguments.token_file:
        lines = read_file("--token-file", arguments.token_file).decode().splitlines()
        token = lines[0].strip() if lines else ""
        if not token:
            raise ValueError(f"--token-file: '{arguments.token_file}' has no token")
    return [("authorization", f"Bearer {token}")] if token else []


def parse_rect(text):
    values = [float(v) for v in text.split(",")]
    if len(values) != 4:
        raise ValueError("--rect: expected X0,Y0,X1,Y1")
    return scallop_pb2.Rect(x0=values[0], y0=values[1], x1=values[2], y1=values[3])


SIGN = 1 << 63
MASK64 = (1 << 64) - 1


def ordered_bits(value):
    """A double's bits mapped monotonically onto 0..2^64-1 (EncodedRegion in the proto)."""
    bits = struct.unpack("<Q", struct.pack("<d", value))[0]
    return ~bits & MASK64 if bits & SIGN else bits | SIGN


def from_ordered_bits(bits):
    bits = bits & ~SIGN if bits & SIGN else ~bits & MASK64
    return struct.unpack("<d", struct.pack("<Q", bits))[0]


def decode_axis(data, width, edge, side, quantised):
    """One axis of an EncodedRegion: offsets of `width` bytes from the low edge."""
    offsets = [int.from_bytes(data[k:k + width], "little") for k in range(0, len(data), width)]
    if quantised:
        quantum = math.ldexp(side, -8 * width)
        return [edge + (cell + 0.5) * quantum for cell in offsets]
    base = ordered_bits(edge)
    return [from_ordered_bits((base + offset) & MASK64) for offset in offsets]


def decode_points(points):
    """(ids, xs, ys) of a Points message: its packed arrays, or its encoded regions decoded."""
    if not points.HasField("encoded"):
        return list(points.ids), list(points.xs), list(points.ys)
    encoded = points.encoded
    side, b = encoded.region_side, encoded.id_index_bits
    g = (64 - b) // 2
    quantised = encoded.encoding == scallop_pb2.POINT_ENCODING_QUANTISED
    ids, xs, ys = [], [], []
    for region in encoded.regions:
        runs = list(region.index_runs)
        first_id = (region.i % (1 << g)) << (g + b) | (region.j % (1 << g)) << b
        index = 0
        for skip, take in zip(runs[0::2], runs[1::2]):
            index += skip
            ids.extend(first_id | k for k in range(index, index + take))
            index += take
        # The low edges as the server computes them: i * S, one double product.
        region_xs = decode_axis(region.x_offsets, region.x_offset_bytes, float(region.i) * side,
                                side, quantised)
        region_ys = decode_axis(region.y_offsets, region.y_offset_bytes, float(region.j) * side,
                                side, quantised)
        if len(runs) % 2 or not len(region_xs) == len(region_ys) == len(ids) - len(xs):
            raise ValueError(f"malformed encoded region ({region.i}, {region.j})")
        xs.extend(region_xs)
        ys.extend(region_ys)
    return ids, xs, ys


def points_of_pages(stub, arguments, rect):
    """Every page of GetPoints, following next_page_token."""
    token = ""
    while True:
        response = stub.GetPoints(scallop_pb2.GetPointsRequest(
            rect=rect, page_size=arguments.page_size, page_token=token,
            encoding=ENCODINGS[arguments.encoding],
            **world_choice(arguments)), timeout=arguments.timeout,
            metadata=arguments.metadata)
        yield response.points
        token = response.next_page_token
        if not token:
            return


def points_of_stream(stub, arguments, rect):
    """The chunks of StreamPoints, one region each."""
    request = scallop_pb2.StreamPointsRequest(
        rect=rect, encoding=ENCODINGS[arguments.encoding], **world_choice(arguments))
    for chunk in stub.StreamPoints(request, timeout=arguments.timeout,
                                   metadata=arguments.metadata):
        yield chunk.points


def main(argv):
    arguments = parse_arguments(argv)
    try:
        rect = parse_rect(arguments.rect)
        world_choice(arguments)  # a bad --radius-noise exits 2 before any call
        arguments.metadata = call_metadata(arguments)
        channel = open_channel(arguments)
    except ValueError as error:
        print(f"scallop_points: {error}", file=sys.stderr)
        return 2
    with channel:
        stub = scallop_pb2_grpc.ScallopStub(channel)
        read = points_of_stream if arguments.stream else points_of_pages
        out = sys.stdout
        header = None
        try:
            for points in read(stub, arguments, rect):
                ids, xs, ys = decode_points(points)
                if not ids:
                    continue
                if header is None:  # a field world's points carry radii
                    header = "id,x,y,r\n" if points.radii else "id,x,y\n"
                    out.write(header)
                if points.radii:
                    for point_id, x, y, r in zip(ids, xs, ys, points.radii):
                        out.write(f"{point_id},{x:.17g},{y:.17g},{r:.17g}\n")
                else:
                    for point_id, x, y in zip(ids, xs, ys):
                        out.write(f"{point_id},{x:.17g},{y:.17g}\n")
            if header is None:
                out.write("id,x,y,r\n" if arguments.radius_noise else "id,x,y\n")
        except grpc.RpcError as error:
            print(f"scallop_points: {error.code().name}: {error.details()}", file=sys.stderr)
            return 1
        except ValueError as error:
            print(f"scallop_points: INTERNAL: {error}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
