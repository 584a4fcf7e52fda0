#!/usr/bin/env bash
# Runs every `sh` code block of README.md, docs/*.md and the crates' READMEs as written, from the repository root
# (their output files go to out/, which git ignores), each with `set -euo pipefail`. A block
# preceded by a `<!-- slow: … -->` line is not run: the script lists it with that line, which
# says how the block is checked instead. Every `toml` block that names sky-core must require its
# current version. A block's `sky-train` is the CLI built from this checkout (what
# `cargo install --path sky-train` puts on a user's PATH). Part of scripts/test.sh.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
mkdir -p out
# The blocks' `--release` builds (this one and their `cargo run --release`) without the release
# profile's single codegen unit and link-time optimisation: the blocks run small jobs, and the
# profile as shipped took a minute and a half more of the test command's longest lane, mostly on
# one core. The commands run as written.
export CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_PROFILE_RELEASE_LTO=false
cargo build --release --locked -q -p sky-train
export PATH="$root/target/release:$PATH"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

version=$(sed -n '/^\[workspace.package\]/,/^\[/s/^version = "\(.*\)"/\1/p' Cargo.toml)
ran=0 skipped=0
for page in README.md docs/*.md sky-core/README.md sky-gpu/README.md sky-train/README.md; do
  # Split the page into one file per block: NNN.LANG (the block), NNN.where (line, slow reason).
  rm -f "$work"/[0-9]*
  awk -v dir="$work" '
    /^```/ && !inside { inside = 1; n++; lang = substr($0, 4); file = sprintf("%s/%03d.%s", dir, n, lang == "" ? "none" : lang)
                        printf "%d\t%s\n", NR, slow > sprintf("%s/%03d.where", dir, n); printf "" > file; next }
    /^```/ && inside  { inside = 0; slow = ""; next }
    inside            { print >> file; next }
    /^<!-- slow:/     { slow = $0; next }
    /[^ ]/            { slow = "" }
  ' "$page"
  for block in "$work"/*.sh "$work"/*.toml; do
    [ -e "$block" ] || continue
    IFS=$'\t' read -r line slow < "${block%.*}.where"
    case "$block" in
      *.toml)
        if grep -q '^sky-core *=' "$block" && ! grep -qE "^sky-core *= *\"${version%.*}(\.[0-9]+)?\"" "$block"; then
          echo "FAIL: $page:$line: the sky-core dependency line does not require version $version" >&2
          exit 1
        fi ;;
      *.sh)
        if [ -n "$slow" ]; then
          printf -- '-- %s:%s not run: %s\n' "$page" "$line" "$slow"
          skipped=$((skipped + 1))
          continue
        fi
        printf -- '-- %s:%s runs\n' "$page" "$line"
        if ! bash -euo pipefail "$block" > "$work/stdout"; then
          echo "FAIL: the sh block at $page:$line" >&2
          exit 1
        fi
        tail -n 2 "$work/stdout" | sed 's/^/   | /'
        ran=$((ran + 1)) ;;
    esac
  done
done
printf '\ndoc blocks: %d sh blocks ran, %d marked slow (listed above)\n' "$ran" "$skipped"
