#!/usr/bin/env bash
# The one test command (README, CI): installs what the project needs, then runs every check.
#   host:  fmt, clippy (-D warnings), rustdoc (-D warnings), all workspace tests and doctests
#          (among them sky-train/tests/module_graph.rs: sky-train's modules import without cycles),
#          the micromath accuracy test with sky-core's `micromath` feature on,
#          sky-core's examples, `cargo publish --dry-run` of the publishable crates,
#          coverage-guided fuzzing of the decoders of outside input (scripts/fuzz.sh: six
#          libFuzzer targets, 25 s each), the sh blocks of README.md and docs/
#          (scripts/doc-blocks.sh; their Rust blocks are doctests of tests/src/lib.rs)
#   cross: sky-core for thumbv7em / riscv32imac / wasm32 without std or alloc, and the firmware
#          examples under qemu (Cortex-M4F; fixed point on Cortex-M3 and M0) checked against
#          host-computed values
#   wasm:  sky-wasm built for wasm32, its wasm-bindgen tests in node (parity with native sky-core,
#          errors, images), node tests of its JavaScript surface, the demos' browser tests and
#          every GPU shader against sky-core (WebGL2 and WebGPU on SwiftShader) in Debian's
#          chromium, and the npm tarball installed into a scratch project (scripts/wasm.sh test)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { printf '\n==> %s (at %d s)\n' "$*" "$(( $(date +%s) - start ))"; }

step "setup"
scripts/setup.sh

step "cargo fmt --check (the workspace, and the firmware outside it)"
cargo fmt --all -- --check
(cd firmware && cargo fmt -- --check)

step "cargo clippy --all-targets -D warnings"
cargo clippy --workspace --all-targets --locked -- -D warnings

step "cargo doc (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

step "cargo test (workspace: unit, integration, doc tests)"
cargo test --workspace --locked

step "sky-core's micromath feature: each model's error against its f64 reference"
cargo test --locked -p sky-tests --features micromath --test micromath

step "sky-core's examples run"
for example in preetham controller; do
  cargo run --locked -q -p sky-core --example "$example" >/dev/null
done

step "cargo publish --dry-run: sky-core, sky-gpu and sky-train package and build from their packaged sources"
cargo publish --workspace --dry-run --locked --allow-dirty

step "coverage-guided fuzzing (libFuzzer): every decoder of outside input, 25 s each"
scripts/fuzz.sh 25

step "the sh and toml blocks of README.md and docs/ run as written"
scripts/doc-blocks.sh

step "cross targets and firmware under qemu"
scripts/cross.sh

step "sky-wasm: wasm build, wasm-bindgen tests and node tests, browser tests of the demo"
scripts/wasm.sh test

printf '\nall checks passed in %d s\n' "$(( $(date +%s) - start ))"
