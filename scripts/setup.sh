#!/usr/bin/env bash
# Installs what the test command needs beyond the machine's Rust toolchain, idempotently:
#  - Debian's rustc-web + its std source (cross builds with -Zbuild-std) and lld (linker);
#  - qemu-system-arm, unpacked into .tools/qemu (apt would replace the machine's backported qemu-utils);
#  - for sky-wasm (scripts/wasm.sh): Debian's chromium (the browser tests' browser), node and npm,
#    wasm-bindgen-cli at the exact version of the wasm-bindgen crate in Cargo.lock (in
#    .tools/wasm-bindgen: wasm-bindgen, and wasm-bindgen-test-runner for the wasm-bindgen tests),
#    and the npm packages of sky-wasm/package-lock.json (`npm ci`).
# The cargo-installed tools (wasm-bindgen-cli, cargo-fuzz) are built once per machine, into a
# folder per version under $SKY_TOOLS_CACHE (default ${XDG_CACHE_HOME:-~/.cache}/sky-tools),
# and linked from .tools: a fresh clone on a machine that has them installs nothing, and two
# checkouts that pin different versions do not replace each other's.
# Safe to run again: every step checks first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tools="$root/.tools"
tools_cache=${SKY_TOOLS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/sky-tools}
mkdir -p "$tools" "$tools_cache"

# cached_install NAME VERSION CRATE [CARGO_ARGS...]: `cargo install CRATE --version =VERSION`
# into $tools_cache/NAME-VERSION unless it is there (a finished install leaves .complete), then
# .tools/NAME links to it.
cached_install() {
  local name=$1 version=$2 crate=$3
  shift 3
  local dir="$tools_cache/$name-$version"
  if [ ! -f "$dir/.complete" ]; then
    echo "setup: cargo install $crate $version into $dir (a few minutes, once per machine)"
    rm -rf "$dir.tmp"
    cargo install -q "$crate" --version "=$version" --root "$dir.tmp" "$@"
    touch "$dir.tmp/.complete"
    rm -rf "$dir"
    mv "$dir.tmp" "$dir"
  fi
  if [ "$(readlink "$tools/$name" 2>/dev/null)" != "$dir" ]; then
    rm -rf "$tools/$name"
    ln -s "$dir" "$tools/$name"
  fi
}

# version_at_least HAVE NEED: true when dotted version HAVE >= NEED.
version_at_least() { [ "$(printf '%s\n%s\n' "$2" "$1" | sort -V | head -n 1)" = "$2" ]; }
# The first dotted number a command prints (empty if it is missing).
version_of() { "$@" 2>/dev/null | grep -oE '[0-9]+(\.[0-9]+)+' | head -n 1 || true; }

# Debian's rustc-web builds the cross targets with -Zbuild-std: it must be at least the
# workspace's MSRV (a stale package list offers 1.85), so an older one is upgraded.
msrv=$(sed -n 's/^rust-version = "\(.*\)"/\1/p' "$root/Cargo.toml")
# node --test and its reporters, playwright-core: Debian 12 ships 18.
node_min=18

need_apt=()
rustc_web=$(version_of /usr/bin/rustc --version)
if [ -z "$rustc_web" ] || ! version_at_least "$rustc_web" "$msrv" ||
  [ ! -d /usr/lib/rustlib/src/rust/library ]; then
  need_apt+=(rustc-web cargo-web rust-web-src)
fi
command -v ld.lld >/dev/null || need_apt+=(lld)
[ -x /usr/bin/chromium ] || need_apt+=(chromium)
node_version=$(version_of node --version)
if [ -z "$node_version" ] || ! version_at_least "$node_version" "$node_min"; then
  need_apt+=(nodejs)
fi
command -v npm >/dev/null || need_apt+=(npm)
# Python for the skymodels wheel (scripts/python.sh): python3 >= 3.9 with venv and pip.
python_min=3.9
python_version=$(version_of python3 --version)
if [ -z "$python_version" ] || ! version_at_least "$python_version" "$python_min"; then
  need_apt+=(python3)
fi
python3 -c 'import ensurepip, venv' 2>/dev/null || need_apt+=(python3-venv)

qemu_libs=(libaio1 libbpf1 libcapstone4 libfdt1 libfuse3-3 libibverbs1 libnuma1 libpixman-1-0
  libpmem1 librdmacm1 libslirp0 liburing2 libvdeplug2 libglib2.0-0 libgnutls30 libsasl2-2
  libseccomp2 libjpeg62-turbo libpng16-16 libzstd1)
if [ ! -x "$tools/qemu/usr/bin/qemu-system-arm" ]; then
  for p in "${qemu_libs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || need_apt+=("$p"); done
fi

export DEBIAN_FRONTEND=noninteractive
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "setup: apt-get install ${need_apt[*]}"
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${need_apt[@]}" >/dev/null
fi
rustc_web=$(version_of /usr/bin/rustc --version)
if [ -z "$rustc_web" ] || ! version_at_least "$rustc_web" "$msrv"; then
  echo "setup: /usr/bin/rustc is ${rustc_web:-missing}; the cross builds need rustc-web >= $msrv" >&2
  exit 1
fi
node_version=$(version_of node --version)
if [ -z "$node_version" ] || ! version_at_least "$node_version" "$node_min"; then
  echo "setup: node is ${node_version:-missing}; the sky-wasm tests need node >= $node_min" >&2
  exit 1
fi

if [ ! -x "$tools/qemu/usr/bin/qemu-system-arm" ]; then
  echo "setup: unpacking qemu-system-arm into .tools/qemu"
  dl=$(mktemp -d) && chmod a+rwx "$dl"
  (cd "$dl" && apt-get download -qq qemu-system-arm >/dev/null)
  mkdir -p "$tools/qemu.tmp"
  dpkg-deb -x "$dl"/qemu-system-arm_*.deb "$tools/qemu.tmp"
  rm -rf "$tools/qemu" "$dl"
  mv "$tools/qemu.tmp" "$tools/qemu"
fi

# qemu-system-riscv32 for the RISC-V firmware (scripts/cross.sh): Debian's qemu-system-misc,
# unpacked into .tools/qemu-misc as qemu-system-arm is (the same libraries; apt would replace
# the backported qemu-utils here too). A stale package list is updated once.
if [ ! -x "$tools/qemu-misc/usr/bin/qemu-system-riscv32" ]; then
  echo "setup: unpacking qemu-system-misc into .tools/qemu-misc"
  dl=$(mktemp -d) && chmod a+rwx "$dl"
  (cd "$dl" && apt-get download -qq qemu-system-misc >/dev/null 2>&1) ||
    (apt-get update -qq && cd "$dl" && apt-get download -qq qemu-system-misc >/dev/null)
  rm -rf "$tools/qemu-misc.tmp" && mkdir -p "$tools/qemu-misc.tmp"
  dpkg-deb -x "$dl"/qemu-system-misc_*.deb "$tools/qemu-misc.tmp"
  rm -rf "$tools/qemu-misc" "$dl"
  mv "$tools/qemu-misc.tmp" "$tools/qemu-misc"
fi
"$tools/qemu-misc/usr/bin/qemu-system-riscv32" --version | head -n 1

# wasm-bindgen-cli must match the wasm-bindgen crate exactly (its output embeds the schema version).
bindgen_version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/"/, "", $3); print $3 }' "$root/Cargo.lock")
bindgen="$tools/wasm-bindgen/bin/wasm-bindgen"
test_runner="$tools/wasm-bindgen/bin/wasm-bindgen-test-runner"
# Not --locked: the CLI's own lock file pins a webpki-roots release the registry here lacks.
cached_install wasm-bindgen "$bindgen_version" wasm-bindgen-cli
if [ "$("$bindgen" --version 2>/dev/null)" != "wasm-bindgen $bindgen_version" ] ||
  [ "$("$test_runner" --version 2>/dev/null)" != "wasm-bindgen-test-runner $bindgen_version" ]; then
  echo "setup: $tools/wasm-bindgen does not run as wasm-bindgen $bindgen_version; remove $tools_cache/wasm-bindgen-$bindgen_version and rerun" >&2
  exit 1
fi

# cargo-fuzz (libFuzzer's driver) for scripts/fuzz.sh, linked as .tools/cargo-fuzz.
fuzz_version=0.13.2
cargo_fuzz="$tools/cargo-fuzz/bin/cargo-fuzz"
cached_install cargo-fuzz "$fuzz_version" cargo-fuzz
if [ "$("$cargo_fuzz" --version 2>/dev/null)" != "cargo-fuzz $fuzz_version" ]; then
  echo "setup: $cargo_fuzz does not run as cargo-fuzz $fuzz_version; remove $tools_cache/cargo-fuzz-$fuzz_version and rerun" >&2
  exit 1
fi

# The Python build and test tools (scripts/python.sh), in a virtual environment of their own,
# .tools/python: maturin builds the skymodels wheel, pytest runs its tests (in a fresh virtual
# environment with the wheel, scripts/python.sh). An older version found is upgraded.
py_tools="$tools/python"
maturin_min=1.16.0
pytest_min=8.0.0
[ -x "$py_tools/bin/python" ] || python3 -m venv "$py_tools"
for need in "maturin $maturin_min" "pytest $pytest_min"; do
  set -- $need
  have=$(version_of "$py_tools/bin/python" -m "$1" --version)
  if [ -z "$have" ] || ! version_at_least "$have" "$2"; then
    echo "setup: pip install $1>=$2 into .tools/python (found ${have:-none})"
    "$py_tools/bin/python" -m pip install -q --disable-pip-version-check --upgrade "$1>=$2"
  fi
done

# playwright-core drives Debian's chromium; it must never download a browser of its own.
export PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1
stamp="$root/sky-wasm/node_modules/.package-lock.stamp"
if ! cmp -s "$root/sky-wasm/package-lock.json" "$stamp"; then
  echo "setup: npm ci in sky-wasm"
  (cd "$root/sky-wasm" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$root/sky-wasm/package-lock.json" "$stamp"
fi

"$tools/qemu/usr/bin/qemu-system-arm" --version | head -n 1
"$bindgen" --version
"$test_runner" --version
"$cargo_fuzz" --version
/usr/bin/chromium --version 2>/dev/null | head -n 1
/usr/bin/rustc --version
"$py_tools/bin/python" -m maturin --version
"$py_tools/bin/python" -m pytest --version
