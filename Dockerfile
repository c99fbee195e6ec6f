# syntax=docker/dockerfile:1
# Build: docker build -t restitution .
# Run:   docker run --rm -p 8080:8080 restitution
# Without a Docker engine, scripts/dockerfile-stage-check replays the build
# stage on the host (CI: .ci/deploy-check); Kubernetes: deploy/kubernetes.

FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
# Dependency layer: built from the manifests alone, cached until they change.
# Cargo reads every target the manifest names (the [[bench]] and [[example]]
# entries) before building anything, so benches and examples come along.
# tests/ is not needed: the manifest names no [[test]]; the workspace's
# testkit/ (the tests' helpers, a dev-dependency) is, for its manifest. The binary is built for
# baseline x86-64 and runs its x86-64-v3 copy of the solver where the CPU has
# AVX2 and FMA (src/kernels.rs): the image runs on any x86-64 CPU.
COPY Cargo.toml Cargo.lock ./
COPY benches ./benches
COPY examples ./examples
COPY testkit ./testkit
RUN mkdir -p src && echo "fn main() {}" > src/main.rs && echo "" > src/lib.rs \
    && cargo build --release --locked \
    && rm -rf src
COPY src ./src
# COPY keeps the sources' old mtimes: without the touch, cargo would take the
# stub built above for up to date and ship it.
RUN touch src/main.rs src/lib.rs && cargo build --release --locked --bin restitution

FROM gcr.io/distroless/cc-debian12:nonroot
COPY --from=build /src/target/release/restitution /usr/local/bin/restitution
ENV RESTITUTION_BIND=0.0.0.0:8080
EXPOSE 8080
# distroless's nonroot user by number, so that Kubernetes' runAsNonRoot can verify it.
USER 65532:65532
HEALTHCHECK --interval=10s --timeout=3s --retries=3 CMD ["/usr/local/bin/restitution", "healthcheck", "--addr", "127.0.0.1:8080"]
ENTRYPOINT ["/usr/local/bin/restitution"]
CMD ["serve"]
