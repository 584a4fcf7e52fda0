#!/usr/bin/env bash
# Installs what the test command needs beyond the machine's Rust toolchain, idempotently:
#  - Debian's rustc-web + its std source (cross builds with -Zbuild-std) and lld (linker);
#  - qemu-system-arm, unpacked into .tools/qemu (apt would replace the machine's backported qemu-utils).
# Safe to run again: every step checks first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tools="$root/.tools"
mkdir -p "$tools"

need_apt=()
[ -x /usr/bin/rustc ] && [ -d /usr/lib/rustlib/src/rust/library ] || need_apt+=(rustc-web rust-web-src)
command -v ld.lld >/dev/null || need_apt+=(lld)

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

if [ ! -x "$tools/qemu/usr/bin/qemu-system-arm" ]; then
  echo "setup: unpacking qemu-system-arm into .tools/qemu"
  dl=$(mktemp -d) && chmod a+rwx "$dl"
  (cd "$dl" && apt-get download -qq qemu-system-arm >/dev/null)
  mkdir -p "$tools/qemu.tmp"
  dpkg-deb -x "$dl"/qemu-system-arm_*.deb "$tools/qemu.tmp"
  rm -rf "$tools/qemu" "$dl"
  mv "$tools/qemu.tmp" "$tools/qemu"
fi
"$tools/qemu/usr/bin/qemu-system-arm" --version | head -n 1
/usr/bin/rustc --version
