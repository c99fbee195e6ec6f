# syntax=docker/dockerfile:1
# Build: docker build -t restitution .
# Run:   docker run --rm -p 8080:8080 restitution

FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
# Dependency layer: built from the manifests alone, cached until they change.
# The manifest names the benches and examples, so they come along; .cargo sets the CPU target.
COPY Cargo.toml Cargo.lock ./
COPY .cargo ./.cargo
COPY benches ./benches
COPY examples ./examples
RUN mkdir -p src && echo "fn main() {}" > src/main.rs && echo "" > src/lib.rs \
    && cargo build --release --locked \
    && rm -rf src
COPY src ./src
RUN touch src/main.rs src/lib.rs && cargo build --release --locked --bin restitution

FROM gcr.io/distroless/cc-debian12:nonroot
COPY --from=build /src/target/release/restitution /usr/local/bin/restitution
ENV RESTITUTION_BIND=0.0.0.0:8080
EXPOSE 8080
USER nonroot
HEALTHCHECK --interval=10s --timeout=3s --retries=3 CMD ["/usr/local/bin/restitution", "healthcheck", "--addr", "127.0.0.1:8080"]
ENTRYPOINT ["/usr/local/bin/restitution"]
CMD ["serve"]
