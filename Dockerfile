# scallopd in a container. Two stages: the build runs the project's own
# install script on Debian 12, so the image and a developer's machine build
# alike; the runtime is debian:12-slim with only the shared libraries the two
# programs load (tests/dockerfile_test.sh checks that list against ldd).
#
#   docker build -t scallop .
#   docker run --rm -p 50051:50051 -p 9090:9090 scallop
#   docker run --rm -p 50051:50051 scallop --listen 0.0.0.0:50051 --world coast:7:1:a3

FROM debian:12 AS build
WORKDIR /src
COPY scripts/install-deps.sh scripts/
RUN bash scripts/install-deps.sh && rm -rf /var/lib/apt/lists/*
COPY . .
RUN cmake -S . -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCALLOP_BUILD_BENCH=OFF \
 && cmake --build /build -j2 --target scallopd scallop \
 && strip /build/server/scallopd /build/client/scallop

FROM debian:12-slim AS runtime
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      libgrpc++1.51 libgrpc29 libprotobuf32 libabsl20220623 libre2-9 libc-ares2 zlib1g \
      libssl3 libyaml-cpp0.7 libspdlog1.10 libfmt9 libgmp10 libgmpxx4ldbl libmpfr6 libfftw3-double3 \
      libpng16-16 \
 && rm -rf /var/lib/apt/lists/* \
 && useradd --system --uid 10001 --no-create-home --shell /usr/sbin/nologin scallop
COPY --from=build /build/server/scallopd /build/client/scallop /usr/local/bin/
USER scallop
# gRPC, and Prometheus metrics at /metrics.
EXPOSE 50051 9090
HEALTHCHECK --interval=10s --timeout=3s --start-period=5s --retries=3 \
  CMD ["scallop", "health", "--server", "127.0.0.1:50051", "--quiet"]
ENTRYPOINT ["scallopd"]
# The embedded default world (seed 1, d 1, A3) on every interface.
CMD ["--listen", "0.0.0.0:50051", "--metrics-listen", "0.0.0.0:9090"]
