#!/usr/bin/env bash
# Generates the Python messages and gRPC stubs of scallop.v1 into OUT_DIR with
# Debian's protoc and grpc_python_plugin (protobuf-compiler,
# protobuf-compiler-grpc); the runtime is python3-grpcio and python3-protobuf.
# Usage: generate_stubs.sh OUT_DIR
set -euo pipefail
out=${1:?usage: generate_stubs.sh OUT_DIR}
proto_root="$(cd "$(dirname "$0")/../../proto" && pwd)"
mkdir -p "$out"
protoc --proto_path="$proto_root" --python_out="$out" --grpc_out="$out" \
  --plugin=protoc-gen-grpc="$(command -v grpc_python_plugin)" \
  "$proto_root/scallop/v1/scallop.proto"
