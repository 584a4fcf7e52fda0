#!/usr/bin/env bash
# Cross-target checks: sky-core builds without std or alloc for a Cortex-M4F, a RISC-V
# microcontroller and wasm32, and the firmware examples agree with the host under qemu: the f32
# skies on a Cortex-M4F (mps2-an386), the fixed-point neural sky on a Cortex-M3 (lm3s6965evb)
# and a Cortex-M0 (microbit), and the lighting controller's day on all three; every example on
# RISC-V (riscv32imac, qemu-system-riscv32's virt machine) and the controller's day on
# riscv32imc (no atomics) too. The sensor-driven controller (four days through the
# self-calibration, its state carried across a restart) runs on the Cortex-M4F, the Cortex-M3
# and RISC-V, with and without the self-calibration. The controller's flash on the Cortex-M0 is
# held to 48,000 B (decimal kilobytes, not KiB), and what it is made of is printed (the largest
# symbols); then the measured lines (`measured | ...`): that flash, the weather controller's
# with and without the self-calibration and their difference, and the estimator's RAM as each
# board printed it.
#
# Then it counts the lighting controller's executed instructions per step on the three
# Cortex-M cores and on RISC-V, and per calibrated step on the Cortex-M4F, the M3 and RISC-V,
# under qemu's -icount (firmware/src/bin/controller_instructions.rs,
# calibration_instructions.rs): `scripts/cross.sh instructions` does only that.
#
# Uses Debian's rustc-web with -Zbuild-std (shared/DESIGN.md, "Toolchains"); the settings live in
# scripts/cross/config.toml (workspace builds) and firmware/.cargo/config.toml (the firmware).
# Cross output goes to target/cross, apart from the host build. Runs from any directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cross_config="$root/scripts/cross/config.toml"
target_dir="$root/target/cross"
qemu="$root/.tools/qemu/usr/bin/qemu-system-arm"
qemu_riscv="$root/.tools/qemu-misc/usr/bin/qemu-system-riscv32"
# The controller's flash budget on the Cortex-M0 in bytes of text: issue 27's "48 KB" read as
# decimal, 48,000 B (not 48 KiB = 49,152 B), a 64 KiB part with room left.
controller_flash_limit=48000
bare_metal_targets=(thumbv7em-none-eabihf riscv32imac-unknown-none-elf)
# The firmware below builds sky-core for both bare-metal targets the same way (core only), so
# the workspace's own build needs only the Cortex-M4F (whose core the defmt build reuses) and
# wasm32, which has no firmware.
targets=(thumbv7em-none-eabihf wasm32-unknown-unknown)

step() { printf '\n==> %s\n' "$*"; }
mode=${1:-all}
case "$mode" in
  all | instructions) ;;
  *)
    echo "usage: scripts/cross.sh [instructions]  (instructions: only the controller's instruction counts)" >&2
    exit 2
    ;;
esac

step "setup: toolchain, linker and qemu"
"$root/scripts/setup.sh"
# Cargo honours the [unstable] table (build-std) only when it sees this in its own environment;
# the config's [env] entry reaches rustc but not cargo itself.
export RUSTC_BOOTSTRAP=1

# Builds firmware binary $4 for target $1 (features $5, may be empty), prints its size and runs it
# under qemu on machine $2 with CPU $3 and any further qemu arguments; fails the script unless
# it exits 0. What it printed is kept beside the ELF (<elf>.qemu.log) for the measured lines.
firmware() {
  local target=$1 machine=$2 cpu=$3 bin=$4 features=${5:-}
  shift 5
  local built="$target_dir/$target/release/$bin"
  # A build with features is kept beside the default one as <bin>-<features>.
  local elf=$built${features:+-$features}

  step "firmware: build $bin for $target ($machine)${features:+ with $features}"
  # Run from firmware/, so that firmware/.cargo/config.toml is found.
  (cd "$root/firmware" && cargo build --release --locked --target "$target" --bin "$bin" \
    --target-dir "$target_dir" ${features:+--features "$features"})
  [ -z "$features" ] || cp "$built" "$elf"

  step "firmware: size of $bin on $machine (text = flash: vectors, code, constants; data + bss = static RAM)"
  if command -v llvm-size >/dev/null; then
    llvm-size "$elf"
  else
    readelf -S --wide "$elf" | grep -E '\.(vector_table|text|rodata|data|bss) '
  fi

  step "firmware: run $bin under qemu ($machine, $cpu)"
  # The microbit machine has its one CPU built in (qemu refuses -cpu there); RISC-V's virt
  # machine boots the ELF itself (-bios none: no OpenSBI, machine mode from 0x80000000).
  local qemu_bin=$qemu cpu_args=(-cpu "$cpu")
  [ "$machine" = microbit ] && cpu_args=()
  case "$target" in riscv32*) qemu_bin=$qemu_riscv cpu_args=(-cpu "$cpu" -bios none) ;; esac
  local status=0
  # With pipefail, the pipeline's status is qemu's (or timeout's) unless tee fails.
  timeout 120 "$qemu_bin" -machine "$machine" "${cpu_args[@]}" -nographic "$@" \
    -semihosting-config enable=on,target=native -kernel "$elf" | tee "$elf.qemu.log" || status=$?
  if [ "$status" -ne 0 ]; then
    [ "$status" -eq 124 ] && echo "FAIL: qemu timed out after 120 s" >&2
    echo "FAIL: $bin on $machine exited with status $status" >&2
    exit 1
  fi
}

if [ "$mode" = all ]; then # (the checks below, up to `fi`, are left unindented)
step "sky-core: dependency tree for the bare-metal targets (normal dependencies, features)"
for target in "${bare_metal_targets[@]}"; do
  echo "-- $target"
  tree=$(cd "$root" && cargo tree -p sky-core -e normal --target "$target" --prefix none \
    --format '{p} [{f}]')
  echo "$tree"
  if grep -E '[[,](std|alloc)[],]' <<<"$tree"; then
    echo "FAIL: a dependency of sky-core enables its std or alloc feature for $target" >&2
    exit 1
  fi
done

step "sky-core: build (lib only, core only) for ${targets[*]}"
# The cross sysroot holds no prebuilt library for these targets, and build-std builds only
# `core`: a crate anywhere in sky-core's tree that used `std` or `alloc` would fail to compile
# here ("can't find crate"). So this build succeeding (and the firmware's, for RISC-V) is itself
# the proof that sky-core and its dependencies need neither.
# Built with the firmware's release profile (firmware/Cargo.toml), so that the firmware's builds
# for the Cortex-M4F reuse this core instead of building their own.
target_args=()
for target in "${targets[@]}"; do target_args+=(--target "$target"); done
firmware_profile=(--config 'profile.release.opt-level="s"' --config 'profile.release.lto=true'
  --config 'profile.release.codegen-units=1' --config 'profile.release.debug=true')
(cd "$root" && cargo build -p sky-core --lib --release "${target_args[@]}" \
  --config "$cross_config" "${firmware_profile[@]}" --target-dir "$target_dir")

step "sky-core: build with the defmt feature for thumbv7em-none-eabihf"
(cd "$root" && cargo build -p sky-core --lib --release --features defmt \
  --target thumbv7em-none-eabihf --config "$cross_config" "${firmware_profile[@]}" \
  --target-dir "$target_dir")

# Each run: target, board (qemu machine and CPU), binary. The target picks the board's memory
# map in firmware/build.rs; every binary checks its values against the host's and exits 0 or 1.
# A fourth field names firmware features: such a build shares the target folder (and its
# core) and is kept beside the default one as <bin>-<features>, for its size next to it
# (docs/firmware.md, "Flash and RAM"); micromath's is built first, so that the sky-firmware
# left in the folder is the default one.
runs=(
  "thumbv7em-none-eabihf mps2-an386 cortex-m4 sky-firmware micromath"  # Preetham and neural,
  "thumbv7em-none-eabihf mps2-an386 cortex-m4 sky-firmware"            # f32: micromath, libm
  "thumbv7m-none-eabi lm3s6965evb cortex-m3 fixed-neural"              # fixed-point neural
  "thumbv6m-none-eabi microbit cortex-m0 fixed-neural"                 # fixed-point, ARMv6-M
  "thumbv7em-none-eabihf mps2-an386 cortex-m4 controller"              # controller's day, FPU
  "thumbv7m-none-eabi lm3s6965evb cortex-m3 controller"                # the same, soft float
  "thumbv6m-none-eabi microbit cortex-m0 controller"                   # the same, ARMv6-M
  "thumbv7em-none-eabihf mps2-an386 cortex-m4 weather-controller"      # sensors, calibrated, FPU
  "thumbv7m-none-eabi lm3s6965evb cortex-m3 weather-controller"        # the same, soft float
  "thumbv7em-none-eabihf mps2-an386 cortex-m4 weather-controller-uncalibrated" # without the
  "thumbv7m-none-eabi lm3s6965evb cortex-m3 weather-controller-uncalibrated"   # calibration
  "riscv32imac-unknown-none-elf virt rv32 sky-firmware"                # RISC-V: every example
  "riscv32imac-unknown-none-elf virt rv32 fixed-neural"
  "riscv32imac-unknown-none-elf virt rv32 controller"
  "riscv32imac-unknown-none-elf virt rv32 weather-controller"
  "riscv32imac-unknown-none-elf virt rv32 weather-controller-uncalibrated"
  "riscv32imc-unknown-none-elf virt rv32 controller"                   # RV32 without atomics
)
for run in "${runs[@]}"; do
  read -r target machine cpu bin features <<<"$run"
  firmware "$target" "$machine" "$cpu" "$bin" "${features:-}"
done

# What the controller's flash is made of on the Cortex-M0 (docs/firmware.md, "Flash and RAM"):
# the sections, then the largest symbols (code and named constants; the anonymous constants,
# the daylight tables and the expected values among them, are .rodata's rest), and the budget.
elf="$target_dir/thumbv6m-none-eabi/release/controller"
step "firmware: what the controller's flash is made of on the Cortex-M0 (size -A, nm --size-sort)"
size -A "$elf" | grep -E '^\.(vector_table|text|rodata|data) '
nm --size-sort -S -C --radix=d "$elf" | sort -k2,2nr | awk "NR <= 20" |
  awk '{ size = $2 + 0; $1 = $2 = ""; printf "%8d %s\n", size, substr($0, 3) }'
flash=$(size "$elf" | awk 'NR == 2 { print $1 }')
echo "controller flash on the Cortex-M0: $flash B (limit $controller_flash_limit B = 48 KB decimal)"
if [ "$flash" -gt "$controller_flash_limit" ]; then
  echo "FAIL: the controller's flash on the Cortex-M0 is over $controller_flash_limit B" >&2
  exit 1
fi

# The measured lines (docs/firmware.md, "Flash and RAM"; docs/weather.md, "Self-calibration"),
# from the builds and runs above, so that they follow any change. Flash is text (`size`:
# vectors, code and constants). The two weather controllers differ only in the estimator's
# calls (firmware/src/weather.rs), so their difference is the self-calibration's flash: the
# estimator and its clear-period detector, `step_calibrated`'s comparison with the clear sky,
# the state's saving and restoring (and the example's message printing the saved bytes).
step "firmware: measured (flash = text of the builds above; RAM as each board printed it)"
text_of() { size "$1" | awk 'NR == 2 { print $1 }'; }
echo "measured | flash | controller | Cortex-M0 (thumbv6m-none-eabi) | $flash B | limit $controller_flash_limit B"
for board in "thumbv7em-none-eabihf Cortex-M4F" "thumbv7m-none-eabi Cortex-M3" \
  "riscv32imac-unknown-none-elf RV32IMAC"; do
  read -r target name <<<"$board"
  release="$target_dir/$target/release"
  with=$(text_of "$release/weather-controller")
  without=$(text_of "$release/weather-controller-uncalibrated")
  echo "measured | flash | weather-controller (with the self-calibration) | $name | $with B | without it (weather-controller-uncalibrated) $without B | the self-calibration $((with - without)) B"
  grep -E '^(self-calibration RAM|the check.s tables)' "$release/weather-controller.qemu.log" |
    sed "s/^/measured | ram and tables | $name | /"
done
fi # mode all

# The controller step's executed instructions: under -icount every instruction advances the
# virtual clock by 2^8 ns, and the firmware reads it through SysTick (shift 8 gives each
# instruction at least 3 ticks of each board's core clock, so the counts are exact) or, on
# RISC-V, through minstret (qemu reads it from the virtual clock: 256 per instruction).
instruction_runs=(
  "thumbv7em-none-eabihf mps2-an386 cortex-m4"  # Cortex-M4F: single-precision FPU
  "thumbv7m-none-eabi lm3s6965evb cortex-m3"    # Cortex-M3: no FPU
  "thumbv6m-none-eabi microbit cortex-m0"       # Cortex-M0: no FPU, ARMv6-M
  "riscv32imac-unknown-none-elf virt rv32"       # RV32IMAC: no FPU
)
for run in "${instruction_runs[@]}"; do
  read -r target machine cpu <<<"$run"
  firmware "$target" "$machine" "$cpu" controller-instructions "" -icount shift=8,align=off,sleep=off
done
# The calibrated step's (firmware/src/bin/calibration_instructions.rs), on the weather
# controller's boards: the whole step, the peer without the calibration, and the estimator's
# parts, over every step of its series and over those with the sun up.
for run in "${instruction_runs[@]}"; do
  read -r target machine cpu <<<"$run"
  [ "$cpu" = cortex-m0 ] && continue # the weather controller's series is not run on the M0
  firmware "$target" "$machine" "$cpu" calibration-instructions "" -icount shift=8,align=off,sleep=off
done
echo "cross: all passed"
