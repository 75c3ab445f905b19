#!/usr/bin/env bash
# Installs Scallop's build and test dependencies on Debian 12, as root.
# Idempotent: packages already present are skipped, so a second run is quick.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libgtest-dev libgmock-dev libbenchmark-dev
  libcgal-dev libgmp-dev libmpfr-dev
  libboost-dev libboost-system-dev
  libprotobuf-dev protobuf-compiler libgrpc++-dev protobuf-compiler-grpc
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libyaml-cpp-dev libfftw3-dev libpng-dev libssl-dev
  python3 python3-grpcio python3-protobuf python3-yaml
  openssl  # the tests make their TLS certificates with it
  nginx    # e2e_nginx_test runs deploy/nginx/ in front of three replicas
  # The web viewer's test (tests/e2e/viewer_test.py): headless Chromium
  # driven through chromedriver by Selenium.
  chromium chromium-driver python3-selenium
  # scripts/test-portability.sh: a Clang build, and an aarch64 cross build of
  # the core and its golden tests (arm64 multiarch libraries) run under qemu.
  clang g++-aarch64-linux-gnu qemu-user
  # The libFuzzer targets (fuzz/, docs/fuzzing.md): Clang's libFuzzer runtime.
  libfuzzer-14-dev
  libgtest-dev:arm64 libboost-dev:arm64 libcgal-dev:arm64 libgmp-dev:arm64
  libmpfr-dev:arm64 libfftw3-dev:arm64 libpng-dev:arm64
)

# The :arm64 packages need the architecture known to dpkg (then apt-get
# update below, which runs since they are missing).
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps: arm64 is not a dpkg architecture; run as root" >&2
    exit 1
  fi
  dpkg --add-architecture arm64
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps: missing packages (${missing[*]}); run as root" >&2
    exit 1
  fi
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all packages present"
fi
