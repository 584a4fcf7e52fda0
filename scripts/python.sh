#!/usr/bin/env bash
# The Python package `skymodels` (sky-py/, PyO3 + maturin; docs/python.md).
#
#   scripts/python.sh build [--physical]  the abi3 wheel into target/python/wheels/; prints its
#                                         file name and size
#   scripts/python.sh test [--physical]   sky-py's fmt and clippy (with the physical feature
#                                         either way), the wheel, then a fresh
#                                         virtual environment with the wheel and its declared
#                                         dependencies only (numpy), an import there, pytest
#                                         added and the tests (sky-py/tests) run against the
#                                         values of sky-core itself, printed by
#                                         sky-py/reference (part of scripts/test.sh)
#   scripts/python.sh bench               the wheel against a pure-Python loop and pvlib over
#                                         10^6 times (sky-py/bench/daylight.py), in a virtual
#                                         environment of its own with pvlib from PyPI
#
# --physical builds the wheel with the physical spectral atmosphere (sky-py's `physical`
# feature: sky-train inside) and runs its tests too.
#
# Build directory: target/python (its own: sky-py is a workspace of its own, with a lean
# release profile). maturin and pytest come from .tools/python (scripts/setup.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

usage() {
  echo "usage: scripts/python.sh build|test|bench [--physical]" >&2
  exit 2
}
mode=${1:-}
[ $# -gt 0 ] && shift
case "$mode" in build | test | bench) ;; *) usage ;; esac
features=()
variant=default
for arg in "$@"; do
  case "$arg" in
    --physical) features=(--features physical) variant=physical ;;
    *) usage ;;
  esac
done

py_tools="$root/.tools/python"
if [ ! -x "$py_tools/bin/maturin" ] || [ ! -x "$py_tools/bin/pytest" ]; then
  echo "scripts/python.sh: .tools/python has no maturin or pytest: run scripts/setup.sh" >&2
  exit 1
fi
export CARGO_TARGET_DIR="$root/target/python"
manifest=sky-py/Cargo.toml
wheels="$CARGO_TARGET_DIR/wheels/$variant"

# build: the wheel, checked to be the one abi3 wheel for CPython >= 3.9 (its tag cp39-abi3).
build() {
  local began=$SECONDS
  rm -rf "$wheels"
  "$py_tools/bin/maturin" build --release --locked --quiet -m "$manifest" --out "$wheels" \
    --interpreter python3 "${features[@]}"
  wheel=$(echo "$wheels"/skymodels-*.whl)
  case "$(basename "$wheel")" in
    skymodels-*-cp39-abi3-*.whl) ;;
    *)
      echo "FAIL: $wheel is not an abi3 wheel for CPython >= 3.9 (tag cp39-abi3)" >&2
      exit 1
      ;;
  esac
  printf 'wheel %s: %d bytes (%s), built in %d s\n' "$(basename "$wheel")" \
    "$(stat -c %s "$wheel")" "$variant" "$((SECONDS - began))"
}

# A fresh virtual environment in $1 with the wheel and what it declares (pip resolves numpy).
fresh_venv() {
  python3 -m venv "$1"
  "$1/bin/python" -m pip install -q --disable-pip-version-check "$wheel"
}

case "$mode" in
  build)
    build
    ;;
  test)
    cargo fmt --manifest-path "$manifest" --all -- --check
    # Clippy always with the `physical` feature, so that its code (cfg-gated, no other path
    # without it) compiles and is linted even where the wheel is built without it: a check build
    # of sky-train's dependencies, 20 s on a quiet machine, 40 s in the full test command.
    cargo clippy --release --locked --quiet --manifest-path "$manifest" --workspace \
      --all-targets --features physical -- -D warnings
    build
    cargo build --release --locked --quiet --manifest-path "$manifest" -p sky-py-reference \
      "${features[@]}"
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    began=$SECONDS
    fresh_venv "$work/venv"
    # Only the declared dependencies are there: the package imports and computes without pytest.
    "$work/venv/bin/python" -c '
import importlib.metadata as metadata
import skymodels
d = skymodels.daylight(48.21, 16.37, "2026-06-21T11:00")
assert d["global_illuminance"] > 50_000, d
names = sorted(m.metadata["Name"] for m in metadata.distributions())
print("skymodels", skymodels.__version__, "imports and computes in an environment of:", ", ".join(names),
      "(pip and setuptools come with venv)")
'
    "$work/venv/bin/python" -m pip install -q --disable-pip-version-check "pytest>=8"
    printf 'fresh virtual environment with the wheel and pytest: %d s\n' "$((SECONDS - began))"
    PYTHONDONTWRITEBYTECODE=1 SKY_PY_REFERENCE="$CARGO_TARGET_DIR/release/sky-py-reference" \
      SKY_PY_VARIANT="$variant" \
      "$work/venv/bin/python" -m pytest -q -p no:cacheprovider sky-py/tests
    ;;
  bench)
    build
    bench_venv="$CARGO_TARGET_DIR/bench-venv"
    rm -rf "$bench_venv"
    fresh_venv "$bench_venv"
    "$bench_venv/bin/python" -m pip install -q --disable-pip-version-check pvlib
    "$bench_venv/bin/python" -m pip list --disable-pip-version-check 2>/dev/null |
      grep -iE '^(numpy|pandas|pvlib|skymodels) ' | tr -s ' ' | paste -sd ';' | sed 's/^/versions: /'
    nice -n 0 "$bench_venv/bin/python" sky-py/bench/daylight.py
    ;;
esac
