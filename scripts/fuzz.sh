#!/usr/bin/env bash
# Coverage-guided fuzzing of every decoder of outside input (fuzz/fuzz_targets/), with libFuzzer
# through cargo-fuzz (installed by scripts/setup.sh into .tools/cargo-fuzz):
#   scripts/fuzz.sh [SECONDS]   builds the targets, then runs each for SECONDS (default 25; seven
#                               targets, 175 s in all), starting from the seeds in fuzz/corpus/
# Prints per target the executions, the coverage reached (libFuzzer's `cov`: instrumented edges,
# and `ft`: features) and the corpus size; exits non-zero on the first crash, leak, timeout or
# out-of-memory, whose input libFuzzer writes to fuzz/artifacts/TARGET/.
# Limits per input (libFuzzer's flags, below): 10 s (-timeout), 2 GiB resident (-rss_limit_mb),
# no single allocation above 1 GiB (-malloc_limit_mb; the capture loader's largest frame takes
# 384 MiB, image_io::MAX_IMAGE_PIXELS), inputs up to 64 KiB (-max_len: larger than every seed).
# The sanitizer is `none`: the code under test is safe Rust (address errors cannot happen in
# it), and `none` works with the stable toolchain; libFuzzer still guides by coverage.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-25}
cargo_fuzz="${SKY_CARGO_FUZZ:-$root/.tools/cargo-fuzz/bin/cargo-fuzz}"
TARGETS=(weight_file capture_frame capture_manifest style_file stdin_csv measurements physical_cache)

cd "$root/fuzz"
"$cargo_fuzz" build --sanitizer none --release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for target in "${TARGETS[@]}"; do
  mkdir -p "$work/$target" "artifacts/$target"
  # New inputs go to the scratch folder; the repository's seeds are read only.
  if ! "$cargo_fuzz" run --sanitizer none --release "$target" "$work/$target" "corpus/$target" -- \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -max_len=65536 -print_final_stats=1 -close_fd_mask=3 \
    -artifact_prefix="artifacts/$target/" >"$work/$target.log" 2>&1; then
    tail -n 40 "$work/$target.log"
    echo "fuzz $target: FAILED (input in fuzz/artifacts/$target/)"
    exit 1
  fi
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$work/$target.log" | tail -n 1)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$target.log")
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$done_line")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$done_line")
  corp=$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<<"$done_line")
  printf 'fuzz %-17s %9s executions in %s s, coverage %s edges (%s features), corpus %s inputs, no crash\n' \
    "$target" "$execs" "$seconds" "$cov" "$ft" "$corp"
done
