#!/usr/bin/env bash
# sky-wasm: the WebAssembly build, the demo site and its tests.
#
#   scripts/wasm.sh build [DIR]   build the .wasm (profile wasm-release, simd128), run wasm-bindgen
#                                 (web + TypeScript types; node bindings for the tests) and write
#                                 the demo site to DIR (default target/wasm/site); also the
#                                 neural-only build (`--no-default-features --features neural`,
#                                 in target/wasm/neural: web and node bindings); print both
#                                 sizes and fail above their goals (200 KB, 40 KB)
#                                 (pkg/ also holds the GPU shaders' module shaders.js and the
#                                 three.js drop-in three.js; vendor/three/ is the pinned three)
#   scripts/wasm.sh pack          build, then write the npm package (package.json with the crate's
#                                 version and repository, the .wasm, JS and TypeScript bindings
#                                 and their snippets/ (sky-wasm/js/f32-text.js), node.js (the
#                                 node entry point), shaders.js, three.js, the README and
#                                 licences) to target/wasm/package and `npm pack` it into
#                                 target/wasm/sky-wasm-VERSION.tgz
#   scripts/wasm.sh serve [PORT]  serve the built site on http://127.0.0.1:PORT/ (default 8000)
#   scripts/wasm.sh test          build, then three suites:
#                                 - wasm-bindgen tests (sky-wasm/tests/wasm.rs), compiled for
#                                   wasm32 like the shipped .wasm and run in node by
#                                   wasm-bindgen-test-runner: every model's values equal the
#                                   native build of sky-core's (native_values example) to 1e-6
#                                   relative, sky-core's errors reach JsError with its message,
#                                   wrong-length outputs fail, the images are not blank;
#                                 - node tests (tests/node/) of the shipped module's JavaScript
#                                   surface: exported names, thrown Errors, typed arrays; the
#                                   neural-only build against it (bit for bit);
#                                 - browser tests (the demo in Debian's chromium through
#                                   playwright-core; prints the frame times the demo measures;
#                                   its daylight plot against native sky-core's values;
#                                   screenshot in target/wasm/artifacts), each model's GLSL
#                                   shader in WebGL2 (SwiftShader) against sky-core, the
#                                   three.js demo page;
#                                 - the packed tarball installed into a scratch project and
#                                   imported there, in node and in a page
#   scripts/wasm.sh bench         build the shipped .wasm (opt-level 3, simd128), the neural-only
#                                 one and two peers (no simd128; opt-level "s") and print their
#                                 sizes and frame times measured in one node run (not part of
#                                 the test command)
#
# The wasm32 toolchain is Debian's rustc-web with -Zbuild-std (shared/DESIGN.md, "Toolchains"),
# configured in scripts/wasm/config.toml; its output goes to target/wasm, apart from the host build.
# The wasm-bindgen tests share that target dir, profile and flags, so they reuse the built std
# and dependencies.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/target/wasm"
site_default="$out/site"
bindgen="$root/.tools/wasm-bindgen/bin/wasm-bindgen"
test_runner="$root/.tools/wasm-bindgen/bin/wasm-bindgen-test-runner"
step() { printf '\n==> %s\n' "$*"; }

# wasm_cargo COMMAND TARGET_DIR [CARGO_ARGS...]: cargo COMMAND on sky-wasm for wasm32, profile
# wasm-release.
wasm_cargo() {
  local command=$1 dir=$2
  shift 2
  local lld
  lld="$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin/rust-lld"
  # Cargo honours [unstable] build-std only when it sees RUSTC_BOOTSTRAP in its own environment;
  # set for this cargo alone, since host builds with it would not reuse the test command's.
  (cd "$root" && RUSTC_BOOTSTRAP=1 cargo "$command" -p sky-wasm --locked \
    --target wasm32-unknown-unknown --profile wasm-release --target-dir "$dir" \
    --config "$root/scripts/wasm/config.toml" \
    --config "target.wasm32-unknown-unknown.linker='$lld'" "${immediate_abort[@]}" "$@")
}
# A panic (sky-core has none; a bug would be one) traps at once, without the formatting code and
# location strings that panic = "abort" keeps: 10 KB of .wasm. The profile cannot say so on the
# stable host toolchain (Cargo refuses the manifest), so the flag goes to rustc here, for the
# tests too (the same flags let them reuse the built std and dependencies; a failing assertion
# then traps without its message, and the runner names the test).
immediate_abort=(--config "target.wasm32-unknown-unknown.rustflags=['-Zunstable-options','-Cpanic=immediate-abort']")
compile_wasm() { wasm_cargo build "$1" --lib "${@:2}"; }
simd128=(--config "target.wasm32-unknown-unknown.rustflags=['-C','target-feature=+simd128']")

build() {
  local site=${1:-$site_default}
  step "setup"
  "$root/scripts/setup.sh"

  # The neural-only build first: both builds share the target dir (and its std), and the last
  # one leaves its .wasm at the path below.
  local wasm="$out/wasm32-unknown-unknown/wasm-release/sky_wasm.wasm"
  step "sky-wasm, the neural sky alone: build for wasm32-unknown-unknown (--no-default-features --features neural)"
  compile_wasm "$out" "${simd128[@]}" --no-default-features --features neural
  rm -rf "$out/neural"
  "$bindgen" --target web --remove-name-section --out-dir "$out/neural/pkg" "$wasm"
  "$bindgen" --target nodejs --remove-name-section --out-dir "$out/neural/node" "$wasm"

  step "sky-wasm: build for wasm32-unknown-unknown (profile wasm-release, simd128)"
  compile_wasm "$out" "${simd128[@]}"

  step "wasm-bindgen: the site's module and TypeScript types, and node bindings for the tests"
  rm -rf "$site.tmp" "$out/node"
  mkdir -p "$site.tmp"
  cp -r "$root/sky-wasm/www/." "$site.tmp/"
  # The name section (function names for stack traces) is a fifth of the file: left out.
  "$bindgen" --target web --remove-name-section --out-dir "$site.tmp/pkg" "$wasm"
  "$bindgen" --target nodejs --remove-name-section --out-dir "$out/node" "$wasm"
  # The GPU shaders' module (generated by `sky-train export --format js`), the three.js drop-in
  # and their types sit beside the bindings, as in the npm package; the demo's three is the
  # pinned one of sky-wasm/package-lock.json.
  cp "$root"/sky-wasm/js/{shaders,three}.{js,d.ts} "$site.tmp/pkg/"
  mkdir -p "$site.tmp/vendor/three"
  cp "$root"/sky-wasm/node_modules/three/build/three.{module,core}.js "$site.tmp/vendor/three/"
  # Binaryen's size optimiser (npm `binaryen`, pinned in sky-wasm/package-lock.json; Debian's is
  # too old for this rustc's output): 214 KB -> 194 KB with the settings of the wasm-release
  # profile; the tests below run the optimised file. The producers and target-features sections
  # (which toolchain built it, with which wasm features; 283 bytes) are not needed to run it.
  local wasm_opt="$root/sky-wasm/node_modules/.bin/wasm-opt"
  for f in "$site.tmp/pkg/sky_wasm_bg.wasm" "$out/node/sky_wasm_bg.wasm" \
    "$out/neural/pkg/sky_wasm_bg.wasm" "$out/neural/node/sky_wasm_bg.wasm"; do
    "$wasm_opt" -Oz --strip-producers --strip-target-features "$f" -o "$f.opt" && mv "$f.opt" "$f"
  done
  rm -rf "$site"
  mv "$site.tmp" "$site"

  step "size of the .wasm: every model (Preetham, neural with both weight sets, AOAS, SH, the daylight sky; DaylightDay; SPA), and the neural sky alone"
  local failed=0
  wasm_size "every model" "$site/pkg/sky_wasm_bg.wasm" 200000 || failed=1
  wasm_size "neural only" "$out/neural/pkg/sky_wasm_bg.wasm" 40000 || failed=1
  echo "site written to $site; the neural-only build in $out/neural"
  if [ "$failed" = 1 ]; then
    echo "a .wasm is over its size goal (docs/browser.md, \"Size\")" >&2
    exit 1
  fi
}

# wasm_size LABEL FILE GOAL: prints FILE's size (and gzipped) against GOAL bytes; fails above it.
wasm_size() {
  local bytes gz
  bytes=$(stat -c %s "$2")
  gz=$(gzip -9c "$2" | wc -c)
  awk -v l="$1" -v b="$bytes" -v g="$gz" -v goal="$3" 'BEGIN {
    printf "sky_wasm_bg.wasm, %s: %d bytes (%.1f KB; %.1f KB gzipped); goal at most %d KB: %s\n",
      l, b, b / 1000, g / 1000, goal / 1000, (b <= goal ? "met" : "NOT met")
    exit (b <= goal ? 0 : 1) }'
}

# pack: the npm package of sky-wasm, from the built site's pkg/.
pack() {
  build
  step "npm package"
  local crate pkg="$out/package"
  # The crate's version and repository (Cargo.toml's [workspace.package]), as JSON.
  crate=$(cd "$root" && cargo metadata --format-version 1 --no-deps --locked |
    node -e 'let s = ""; process.stdin.on("data", (d) => (s += d)).on("end", () => {
      const p = JSON.parse(s).packages.find((p) => p.name === "sky-wasm");
      console.log(JSON.stringify({ version: p.version, repository: p.repository })); })')
  rm -rf "$pkg" && mkdir -p "$pkg"
  cp -r "$site_default"/pkg/* "$pkg/"
  # The node entry point (the "node" condition: `await init()` reads the .wasm from disk), the
  # README and the licences the manifest declares ("MIT OR Apache-2.0").
  cp "$root/sky-wasm/js/node.js" "$root/sky-wasm/js/README.md" "$root/LICENSE-MIT" "$root/LICENSE-APACHE" "$pkg/"
  cat "$root/sky-wasm/js/symbol-dispose.d.ts" >>"$pkg/sky_wasm.d.ts"
  # package.json: the template with the crate's version, and the repository, homepage and
  # issue tracker of the crate's repository.
  node -e 'const fs = require("fs"); const p = JSON.parse(fs.readFileSync(process.argv[1]));
    const crate = JSON.parse(process.argv[2]);
    if (!/^https:\/\/github\.com\/[^/]+\/[^/]+$/.test(crate.repository ?? ""))
      throw new Error(`Cargo.toml: repository = ${crate.repository}, not https://github.com/OWNER/NAME`);
    p.version = crate.version;
    p.repository = { type: "git", url: `git+${crate.repository}.git`, directory: "sky-wasm" };
    p.homepage = `${crate.repository}#readme`;
    p.bugs = { url: `${crate.repository}/issues` };
    fs.writeFileSync(process.argv[3], JSON.stringify(p, null, 2) + "\n");' \
    "$root/sky-wasm/js/npm-package.json" "$crate" "$pkg/package.json"
  local version
  version=$(node -p 'JSON.parse(process.argv[1]).version' "$crate")
  rm -f "$out"/sky-wasm-*.tgz
  (cd "$pkg" && npm pack --pack-destination "$out" --loglevel=error >/dev/null)
  echo "wrote $out/sky-wasm-$version.tgz ($(stat -c %s "$out/sky-wasm-$version.tgz") bytes)"
}

serve() {
  local port=${1:-8000}
  if [ ! -f "$site_default/pkg/sky_wasm_bg.wasm" ]; then
    echo "no site in $site_default: run scripts/wasm.sh build first" >&2
    exit 1
  fi
  echo "serving $site_default on http://127.0.0.1:$port/ (Ctrl-C stops)"
  exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site_default"
}

run_tests() {
  pack
  step "native sky-core values for the parity tests (host build)"
  local native="$out/native_values.json"
  (cd "$root" && cargo run -q --locked -p sky-wasm --example native_values) >"$native.tmp"
  # Replaced only when changed: the tests embed the file, and a new one rebuilds them.
  if cmp -s "$native.tmp" "$native"; then rm "$native.tmp"; else mv "$native.tmp" "$native"; fi

  step "wasm-bindgen tests in node: every model against native sky-core, errors, images"
  # Same profile, flags and target dir as the build above, whose std and dependencies it reuses
  # (scripts/wasm/config.toml); --nocapture prints each sky's worst relative difference.
  SKY_NATIVE_VALUES="$native" wasm_cargo test "$out" --test wasm "${simd128[@]}" \
    --config "target.wasm32-unknown-unknown.runner='$test_runner'" -- --nocapture

  step "node: the shipped module's JavaScript surface, and its values against native sky-core"
  (cd "$root/sky-wasm" && SKY_WASM_NODE_PKG="$out/node/sky_wasm.js" SKY_NATIVE_VALUES="$native" \
    SKY_WASM_NEURAL_NODE_PKG="$out/neural/node/sky_wasm.js" node --test tests/node/)

  step "browser: the demos and the GPU shaders in Debian's chromium (playwright-core)"
  (cd "$root/sky-wasm" && SKY_WASM_SITE="$site_default" SKY_WASM_ARTIFACTS="$out/artifacts" \
    SKY_NATIVE_VALUES="$native" node --test --test-reporter=spec tests/browser/)

  step "the npm tarball installed into a scratch project, imported in node and in a page"
  (cd "$root/sky-wasm" && SKY_WASM_TARBALL="$(ls "$out"/sky-wasm-*.tgz)" \
    node --test --test-reporter=spec tests/pack/)
}

bench() {
  build
  step "peers: opt-level 3 without simd128, opt-level \"s\" with simd128"
  compile_wasm "$out/peer-nosimd"
  compile_wasm "$out/peer-size" "${simd128[@]}" --config 'profile.wasm-release.opt-level="s"'
  for peer in peer-nosimd peer-size; do
    "$bindgen" --target nodejs --remove-name-section --out-dir "$out/$peer/node" \
      "$out/$peer/wasm32-unknown-unknown/wasm-release/sky_wasm.wasm"
  done
  step "frame times, one node run"
  node "$root/sky-wasm/bench/frames.mjs" "shipped(O3,simd128)=$out/node/sky_wasm.js" \
    "neural-only=$out/neural/node/sky_wasm.js" \
    "O3,no-simd=$out/peer-nosimd/node/sky_wasm.js" "Os,simd128=$out/peer-size/node/sky_wasm.js"
}

case "${1:-}" in
  build) shift; build "$@" ;;
  pack) pack ;;
  serve) shift; serve "$@" ;;
  test) run_tests ;;
  bench) bench ;;
  *)
    echo "usage: scripts/wasm.sh build [DIR] | pack | serve [PORT] | test | bench" >&2
    exit 2
    ;;
esac
