# Dockerfile - dashpotd on Debian 12: a build stage that compiles and stages `make install`, and a slim
# runtime stage with the daemon, the CLI, the OpenAPI document, the browser page and only the four runtime
# libraries.
#
#   docker build -t dashpot:0.1.0 .
#   docker run --rm -p 8080:8080 dashpot:0.1.0
#   curl -s localhost:8080/healthz
#   make image        # the same with podman or docker, and without a registry (docs/operations.md)
#
# Settings are DASHPOT_* environment variables (docs/http.md, "Settings"); this image sets the four a
# container needs and leaves the rest at the daemon's defaults. Set the port with DASHPOT_PORT, not --port:
# the HEALTHCHECK reads it. Kubernetes ignores HEALTHCHECK and uses the probes of deploy/kubernetes.
# tests/test_manifests.sh checks this file without a container engine (stages, user, packages against the
# binaries' shared libraries, the build from the .dockerignore'd context); tests/test_install.sh runs the
# HEALTHCHECK command against the installed daemon.

FROM debian:12 AS build
RUN apt-get update \
 && apt-get install -y --no-install-recommends build-essential pkg-config libgsl-dev libcjson-dev libmicrohttpd-dev \
 && rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY . .
RUN make -j"$(nproc)" all \
 && make install DESTDIR=/stage PREFIX=/usr/local \
 && strip /stage/usr/local/bin/dashpotd /stage/usr/local/bin/dashpot

FROM debian:12-slim AS runtime
# The shared libraries dashpotd and dashpot link (readelf -d; tests/test_manifests.sh keeps this list exact).
RUN apt-get update \
 && apt-get install -y --no-install-recommends libmicrohttpd12 libcjson1 libgsl27 libgslcblas0 \
 && rm -rf /var/lib/apt/lists/* \
 && groupadd --system --gid 10001 dashpot \
 && useradd --system --uid 10001 --gid 10001 --no-create-home --home-dir /nonexistent \
        --shell /usr/sbin/nologin dashpot
COPY --from=build /stage/usr/local/bin/dashpotd /stage/usr/local/bin/dashpot /usr/local/bin/
COPY --from=build /stage/usr/local/share/dashpot/ /usr/local/share/dashpot/
ENV DASHPOT_BIND=0.0.0.0 \
    DASHPOT_PORT=8080 \
    DASHPOT_OPENAPI=/usr/local/share/dashpot/openapi.yaml \
    DASHPOT_WEB_DIR=/usr/local/share/dashpot/web
# Numeric, so that Kubernetes' runAsNonRoot can verify it without reading /etc/passwd.
USER 10001:10001
WORKDIR /
EXPOSE 8080
# No curl in the image (it would bring libcurl and a dozen libraries for one probe): bash, which every Debian
# image has, opens the TCP connection itself, sends a bare HTTP/1.0 GET /healthz and wants a 200 status line.
# Docker's --timeout bounds a daemon that accepts but never answers.
HEALTHCHECK --interval=30s --timeout=3s --start-period=5s --retries=3 \
    CMD ["bash", "-c", "exec 3<>/dev/tcp/127.0.0.1/${DASHPOT_PORT:-8080} && printf 'GET /healthz HTTP/1.0\\r\\n\\r\\n' >&3 && head -c 12 <&3 | grep -q '^HTTP/1\\.[01] 200$'"]
STOPSIGNAL SIGTERM
ENTRYPOINT ["/usr/local/bin/dashpotd"]
