// Tests of the wasm-bindgen build in node (scripts/wasm.sh test): parity with native sky-core
// for every model, JavaScript exceptions carrying sky-core's messages, and the image calls.
//
// Inputs (written by scripts/wasm.sh): SKY_WASM_NODE_PKG, the `--target nodejs` bindings;
// SKY_NATIVE_VALUES, the JSON of `cargo run -p sky-wasm --example native_values`.
import { test } from "node:test";
import assert from "node:assert/strict";
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";
import path from "node:path";

const root = path.resolve(import.meta.dirname, "../../..");
const pkg = process.env.SKY_WASM_NODE_PKG ?? path.join(root, "target/wasm/node/sky_wasm.js");
const nativePath = process.env.SKY_NATIVE_VALUES ?? path.join(root, "target/wasm/native_values.json");
const { Sky, Renderer, aoasPresets } = createRequire(import.meta.url)(pkg);
const native = JSON.parse(readFileSync(nativePath, "utf8"));

const RELATIVE_BOUND = 1e-6;

function build({ kind, args, file }) {
  switch (kind) {
    case "preetham": return Sky.preetham(...args);
    case "neural": return Sky.neural(...args);
    case "neuralFromBytes": return Sky.neuralFromBytes(readFileSync(path.join(root, file)), ...args);
    case "aoas": return Sky.aoas(...args);
    case "aoasWithSun": return Sky.aoasWithSun(...args);
    case "sh": return Sky.sh(...args);
    default: throw new Error(`unknown sky kind ${kind}`);
  }
}

/** Largest |got − want| / |want| (0/0 counts as 0, anything/0 as infinite). `want` holds the
 * shortest decimals of native f32 values: read back as f32 they are those values exactly. */
function worstRelative(got, wantDecimal) {
  const want = Float32Array.from(wantDecimal);
  assert.equal(got.length, want.length);
  let worst = 0;
  for (let i = 0; i < want.length; i++) {
    const d = Math.abs(got[i] - want[i]);
    if (d === 0) continue;
    worst = Math.max(worst, want[i] === 0 ? Infinity : d / Math.abs(want[i]));
  }
  return worst;
}

const models = new Set(native.skies.map((s) => s.sky.kind));
test("the native values cover every model", () => {
  for (const kind of ["preetham", "neural", "neuralFromBytes", "aoas", "aoasWithSun", "sh"]) {
    assert.ok(models.has(kind), kind);
  }
  assert.equal(native.skies.filter((s) => s.sky.kind === "aoas").length, aoasPresets().length);
});

for (const { sky: spec, rgb, fisheyeLinear } of native.skies) {
  const name = `${spec.kind}(${spec.args.join(", ")})`;
  test(`parity with native sky-core, per direction: ${name}`, () => {
    const sky = build(spec);
    const got = native.directions.flatMap(([z, a]) => Array.from(sky.rgb(z, a)));
    sky.free();
    const worst = worstRelative(got, rgb);
    console.log(`  ${name}: ${rgb.length} values, worst relative difference ${worst}`);
    assert.ok(worst <= RELATIVE_BOUND, `worst relative difference ${worst} > ${RELATIVE_BOUND}`);
  });
  test(`parity with native sky-core, fisheye image: ${name}`, () => {
    const sky = build(spec);
    const { width, height } = native.fisheye;
    const renderer = Renderer.fisheye(width, height);
    const out = new Float32Array(width * height * 3);
    renderer.renderLinear(sky, out);
    sky.free();
    renderer.free();
    const worst = worstRelative(out, fisheyeLinear);
    assert.ok(worst <= RELATIVE_BOUND, `worst relative difference ${worst} > ${RELATIVE_BOUND}`);
  });
}

test("sky-core's errors become exceptions with its message", () => {
  assert.throws(() => Sky.preetham(0.5, 0, 9), {
    message: "turbidity = 9 is outside the valid range [2, 6]",
  });
  assert.throws(() => Sky.preetham(2, 0, 3), {
    message: /^the sun is below the horizon \(zenith 2 rad > pi\/2\)/,
  });
  assert.throws(() => Sky.preetham(0.5, NaN, 3), { message: "sun azimuth [rad] must be a finite number" });
  assert.throws(() => Sky.neural("hosek", 0.5, 0, 11), {
    message: "turbidity = 11 is outside the valid range [1, 10]",
  });
  assert.throws(() => Sky.neural("perez", 0.5, 0, 3), { message: /"perez" is not a shipped neural sky/ });
  assert.throws(() => Sky.aoas("mauve"), { message: /"mauve" is not an AOAS style preset \(one of: physical, sunrise/ });
  assert.throws(() => Sky.aoasWithSun("coral", 1.8, 0), { message: /sun is below the horizon/ });
  assert.throws(() => Sky.sh(0.5, 0, 2, 5), { message: /turbidity = 2 is outside the valid range \[2.5, 6\]/ });
  assert.throws(() => Sky.sh(0.5, 0, 3, 8), { message: "SH bands = 8 is outside the valid range [1, 7]" });
  assert.throws(() => Renderer.sphere(16).renderSrgb(Sky.preetham(0.5, 0, 3), new Uint8ClampedArray(16 * 16 * 4), 1), {
    message: "the sphere is lit by a spherical-harmonics sky: build it with Sky.sh",
  });
  assert.throws(() => Renderer.fisheye(0, 16), {
    message: "image width [px] = 0 is outside the valid range [1, 4096]",
  });
  // The weight decoder's own errors: a truncated file and a flipped byte (checksum).
  const bytes = readFileSync(path.join(root, "sky-core/weights/preetham.skyn"));
  assert.throws(() => Sky.neuralFromBytes(bytes.subarray(0, 100), 0.5, 0, 3), { message: /truncated|needed|100/i });
  const corrupt = Uint8Array.from(bytes);
  corrupt[200] ^= 1;
  assert.throws(() => Sky.neuralFromBytes(corrupt, 0.5, 0, 3), { message: /checksum|CRC/i });
});

test("an output array of the wrong length is an exception naming the sizes", () => {
  const sky = Sky.preetham(0.5, 0, 3);
  const r = Renderer.fisheye(8, 4);
  assert.throws(() => r.renderSrgb(sky, new Uint8ClampedArray(8 * 4 * 3), 1), {
    message: "out has length 96, but a 8x4 image needs 128 (4 per pixel)",
  });
  assert.throws(() => r.renderLinear(sky, new Float32Array(5)), { message: /needs 96 \(3 per pixel\)/ });
});

test("renderSrgb: opaque inside the dome, transparent outside, exposure scales", () => {
  const sky = Sky.preetham(0.5, 0, 3);
  const r = Renderer.fisheye(64, 64);
  const dim = new Uint8ClampedArray(64 * 64 * 4);
  const bright = new Uint8ClampedArray(64 * 64 * 4);
  const e = sky.autoExposure();
  assert.ok(e > 0 && e < 1e-3, `a daylight sky in cd/m² needs a small exposure, got ${e}`);
  r.renderSrgb(sky, dim, e);
  r.renderSrgb(sky, bright, 4 * e);
  const at = (img, i, j) => Array.from(img.subarray((j * 64 + i) * 4, (j * 64 + i) * 4 + 4));
  assert.deepEqual(at(dim, 0, 0), [0, 0, 0, 0], "corner outside the disc");
  const [cr, cg, cb, ca] = at(dim, 32, 32);
  assert.equal(ca, 255);
  assert.ok(cb > cr && cb > 0 && cr > 0, `zenith ${cr},${cg},${cb}`);
  const sum = (img) => img.reduce((s, v) => s + v, 0);
  assert.ok(sum(bright) > sum(dim), "two stops more exposure is brighter");
  // The difference of a sky with itself is black.
  const diff = new Uint8ClampedArray(64 * 64 * 4);
  r.renderDifferenceSrgb(sky, sky, diff, 1e6);
  for (let k = 0; k < diff.length; k += 4) assert.deepEqual(Array.from(diff.subarray(k, k + 3)), [0, 0, 0]);
});

test("the sphere lit by the SH sky is brighter on the sun's side, and matches sky-core's irradiance", () => {
  // The sun in the east (azimuth 0), 60° from the zenith: the sphere is seen from the south,
  // east to the right.
  const sky = Sky.sh(60 * Math.PI / 180, 0, 3, 5);
  const r = Renderer.sphere(64);
  const rgba = new Uint8ClampedArray(64 * 64 * 4);
  r.renderSrgb(sky, rgba, sky.autoExposure());
  const lum = (i, j) => { const k = (j * 64 + i) * 4; return rgba[k] + rgba[k + 1] + rgba[k + 2]; };
  assert.ok(lum(56, 32) > lum(8, 32) + 30, `east ${lum(56, 32)} vs west ${lum(8, 32)}`);
  assert.ok(lum(32, 8) > lum(32, 56), `top ${lum(32, 8)} vs bottom ${lum(32, 56)}`);
  assert.equal(rgba[3], 0, "corner off the sphere");
});
