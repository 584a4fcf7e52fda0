#!/usr/bin/env bash
# The one test command (README, CI): installs what the project needs, then runs every check.
#
#   scripts/test.sh         every check (CI runs this)
#   scripts/test.sh quick   the edit loop: fmt, clippy and the workspace's tests (unit,
#                           integration, doctests) only
#
# Every check:
#   host:  fmt, clippy (-D warnings), rustdoc (-D warnings), all workspace tests and doctests
#          (among them sky-train/tests/module_graph.rs: sky-train's modules import without cycles),
#          the micromath accuracy test with sky-core's `micromath` feature on,
#          sky-core's examples, `cargo publish --dry-run` of the publishable crates,
#          coverage-guided fuzzing of the decoders of outside input (scripts/fuzz.sh: one
#          libFuzzer run per target, 12 s each), the sh blocks of README.md and docs/
#          (scripts/doc-blocks.sh; their Rust blocks are doctests of tests/src/lib.rs)
#   cross: sky-core for thumbv7em / riscv32imac / wasm32 without std or alloc, and the firmware
#          examples under qemu checked against host-computed values (scripts/cross.sh)
#   wasm:  sky-wasm built for wasm32, its wasm-bindgen tests in node (parity with native sky-core,
#          errors, images), node tests of its JavaScript surface, the demos' browser tests and
#          every GPU shader against sky-core (WebGL2 and WebGPU on SwiftShader) in Debian's
#          chromium, and the npm tarball installed into a scratch project (scripts/wasm.sh test)
#   python: the skymodels wheel (sky-py, PyO3 + maturin, abi3) built, installed into a fresh
#          virtual environment with its declared dependencies only, and its pytest suite run
#          there against sky-core's own values (scripts/python.sh test)
#
# Two lanes run side by side on the machine's cores: the host lane (clippy, doc, the workspace
# tests, micromath, publish) in target/debug, and the other lane (setup, cross, wasm, fuzz,
# python, doc blocks; the host lane needs nothing setup installs, so it starts at once) in
# target/cross, target/wasm, fuzz/target, target/python and target/release. They share no build
# directory, so neither waits for the other's cargo lock, and each fills the other's
# single-threaded stretches (link-time optimisation, qemu, fuzzing, the browser). The other
# lane's output is printed when it ends; the first failure in either lane stops both. Each
# step's time is printed at the end (docs/testing.md has a run's figures).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
mode=${1:-all}
case "$mode" in
  all | quick) ;;
  *)
    echo "usage: scripts/test.sh [quick]" >&2
    exit 2
    ;;
esac
start=$(date +%s)
times=$(mktemp)
lane_log=$(mktemp)
lane_done=$(mktemp)
lane_pid=
# On a failure in the host lane (set -e ends the script there), the other lane is stopped and
# its output so far printed.
cleanup() {
  local status=$?
  if [ -n "$lane_pid" ]; then
    kill -- "-$lane_pid" 2>/dev/null || true
    wait "$lane_pid" 2>/dev/null || true
    printf '\nFAIL: the host lane (above), exit status %d; the other lane was stopped. Its output so far:\n' \
      "$status" >&2
    cat "$lane_log"
  fi
  rm -f "$times" "$lane_log" "$lane_done"
}
trap cleanup EXIT

# step LANE NAME COMMAND...: runs COMMAND under a heading, records its wall time.
step() {
  local lane=$1 name=$2 began
  shift 2
  # A failure in the other lane stops the host lane at its next step.
  if [ "$lane" = host ] && [ -s "$lane_done" ] && [ "$(cat "$lane_done")" != 0 ]; then
    echo "the other lane failed (its output follows)" >&2
    exit 1
  fi
  began=$(date +%s)
  printf '\n==> %s (at %d s)\n' "$name" "$((began - start))"
  "$@"
  printf '%-5s %5d s  %s\n' "$lane" "$(($(date +%s) - began))" "$name" >>"$times"
}

summary() {
  printf '\nstep times (wall, both lanes side by side):\n'
  cat "$times"
}

# The publish dry run builds each crate from its packaged sources, which are no workspace: with
# the workspace's dev profile given again here, the dependencies the tests built are reused
# instead of built once more unoptimised. The packaged crates themselves are built anew either
# way, and only to see that they build: unoptimised (sky-train at opt-level 2 took most of the
# step).
dev_profile=(--config 'profile.dev.debug="line-tables-only"'
  --config 'profile.dev.build-override.debug="line-tables-only"'
  --config 'profile.dev.package."*".opt-level=2'
  --config 'profile.dev.package.sky-core.opt-level=0'
  --config 'profile.dev.package.sky-train.opt-level=0')

# The dry run verifies each crate against the others through a local registry. Cargo trusts a
# registry's crate never to change: it extracts it into $CARGO_HOME/registry/src/-<hash>/ once,
# and keeps what it built from it by version alone. So a later dry run from the same checkout
# would build the earlier sources of sky-core and sky-gpu instead of this one's: their
# extractions go first, and so do the units the last dry run built from them (recorded in
# target/debug/.publish-dry-run-units).
publish_dry_run() {
  local src="${CARGO_HOME:-$HOME/.cargo}/registry/src" fingerprints=target/debug/.fingerprint
  local record=target/debug/.publish-dry-run-units before
  rm -rf "$src"/-*/sky-core-* "$src"/-*/sky-gpu-* "$src"/-*/sky-train-*
  if [ -f "$record" ]; then
    while read -r unit; do rm -rf "${fingerprints:?}/$unit"; done <"$record"
  fi
  before=$(ls "$fingerprints")
  cargo publish --workspace --dry-run --locked --allow-dirty "${dev_profile[@]}"
  comm -13 <(sort <<<"$before") <(ls "$fingerprints" | sort) | grep -E '^sky-(core|gpu|train)-' \
    >"$record" || true
}

examples() {
  for example in preetham controller; do
    cargo run --locked -q -p sky-core --example "$example" >/dev/null
  done
}

fmt() {
  cargo fmt --all -- --check
  (cd firmware && cargo fmt -- --check)
}

# The lane beside the host's: each of its steps has its own build directory.
other_lane() {
  step other "setup: what the cross, wasm, fuzz and python steps need (apt packages, qemu, the cargo-installed tools, npm packages, maturin and pytest)" \
    scripts/setup.sh
  step other "cross targets and firmware under qemu" scripts/cross.sh
  step other "sky-wasm: wasm build, wasm-bindgen tests and node tests, browser tests of the demo" \
    scripts/wasm.sh test
  step other "coverage-guided fuzzing (libFuzzer): every decoder of outside input, 12 s each" \
    scripts/fuzz.sh 12
  step other "skymodels: the Python wheel (abi3), in a fresh virtual environment, against sky-core" \
    scripts/python.sh test
  # Last: a block of docs/browser.md reads the site the wasm step built.
  step other "the sh and toml blocks of README.md and docs/ run as written" scripts/doc-blocks.sh
}

step host "cargo fmt --check (the workspace, and the firmware outside it)" fmt

if [ "$mode" = quick ]; then
  step host "cargo clippy --all-targets -D warnings" \
    cargo clippy --workspace --all-targets --locked -- -D warnings
  step host "cargo test (workspace: unit, integration, doc tests)" cargo test --workspace --locked
  summary
  printf '\nquick checks passed in %d s (the whole suite: scripts/test.sh)\n' "$(($(date +%s) - start))"
  exit 0
fi

# Job control gives the other lane a process group of its own, which a failure here ends.
set -m
{
  # (Not `( … ) || status=$?`: inside a `||`, bash ignores set -e.)
  set +e
  (
    set -euo pipefail
    other_lane
  )
  status=$?
  echo "$status" >"$lane_done"
  exit "$status"
} >"$lane_log" 2>&1 &
lane_pid=$!
set +m

step host "cargo clippy --all-targets -D warnings" \
  cargo clippy --workspace --all-targets --locked -- -D warnings
RUSTDOCFLAGS="-D warnings" step host "cargo doc (warnings are errors)" \
  cargo doc --workspace --no-deps --locked --quiet
step host "cargo test (workspace: unit, integration, doc tests)" cargo test --workspace --locked
# The feature changes sky-core, so sky-train (the AOAS reference, a dependency of the tests)
# is compiled again: unoptimised, as its part of these tests takes milliseconds (2.5 minutes of
# the step at opt-level 2, seconds at 0).
step host "sky-core's micromath feature: each model's error against its f64 reference" \
  cargo test --locked -p sky-tests --features micromath --test micromath \
  --config 'profile.dev.package.sky-train.opt-level=0'
step host "sky-core's examples run" examples
step host "cargo publish --dry-run: sky-core, sky-gpu and sky-train package and build from their packaged sources" \
  publish_dry_run

printf '\n==> the host lane passed at %d s; waiting for the other lane (setup, cross, wasm, fuzz, python, doc blocks)\n' \
  "$(($(date +%s) - start))"
lane_status=0
wait "$lane_pid" || lane_status=$?
lane_pid=
printf '\n==> the other lane: setup, cross, wasm, fuzz, python, doc blocks (its output, in order)\n'
cat "$lane_log"
if [ "$lane_status" -ne 0 ]; then
  printf '\nFAIL: the other lane (above), exit status %d\n' "$lane_status" >&2
  exit "$lane_status"
fi
summary
printf '\nall checks passed in %d s\n' "$(($(date +%s) - start))"
