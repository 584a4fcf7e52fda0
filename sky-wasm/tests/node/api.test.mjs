// Tests of the shipped module's JavaScript surface in node (scripts/wasm.sh test): the
// `--target nodejs` bindings of the wasm-release .wasm after wasm-opt, called as a page calls
// them. What the Rust code computes (every model's values against native sky-core, sky-core's
// error messages, wrong-length outputs, the images) is tested from Rust by the wasm-bindgen
// tests (sky-wasm/tests/wasm.rs); here only what the bindings add: the exported names and
// getters, exceptions thrown as JavaScript Errors, and strings, bytes and typed arrays passed
// across.
//
// One parity check stays here, on purpose: the Rust tests run the compiled code before wasm-opt
// (which must follow wasm-bindgen), so the shipped, wasm-opt'ed module is compared with native
// sky-core here, every sky of the native values at every direction through `Sky.rgb`.
//
// Input (written by scripts/wasm.sh): SKY_WASM_NODE_PKG, the `--target nodejs` bindings;
// SKY_NATIVE_VALUES, the native values (sky-wasm/examples/native_values.rs).
import { test } from "node:test";
import assert from "node:assert/strict";
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";
import path from "node:path";

const root = path.resolve(import.meta.dirname, "../../..");
const pkg = process.env.SKY_WASM_NODE_PKG ?? path.join(root, "target/wasm/node/sky_wasm.js");
const { Sky, Renderer, DaylightDay, aoasPresets, daylightMinAod, daylightMaxAod, daylightDefaultAod } =
  createRequire(import.meta.url)(pkg);
const nativeFile = process.env.SKY_NATIVE_VALUES ?? path.join(root, "target/wasm/native_values.json");

test("the API is exported under its JavaScript names", () => {
  for (const name of ["preetham", "neural", "neuralFromBytes", "aoas", "aoasWithSun", "sh", "shUnfiltered", "daylight"]) {
    assert.equal(typeof Sky[name], "function", `Sky.${name}`);
  }
  for (const name of ["rgb", "rgbBatch", "shaderParams", "irradiance", "autoExposure", "free"]) {
    assert.equal(typeof Sky.prototype[name], "function", `sky.${name}`);
  }
  for (const name of ["fisheye", "panorama", "sphere"]) {
    assert.equal(typeof Renderer[name], "function", `Renderer.${name}`);
  }
  for (const name of ["renderSrgb", "renderDifferenceSrgb", "renderLinear", "free"]) {
    assert.equal(typeof Renderer.prototype[name], "function", `renderer.${name}`);
  }
  assert.equal(typeof DaylightDay.at, "function", "DaylightDay.at");
  for (const name of ["times", "elevationDeg", "globalLux", "diffuseLux", "directLux", "x", "y", "cctK", "melanopicEdiLux"]) {
    assert.ok(Object.getOwnPropertyDescriptor(DaylightDay.prototype, name)?.get, `daylightDay.${name} getter`);
  }
  assert.deepEqual([daylightMinAod(), daylightMaxAod(), daylightDefaultAod()].map((v) => Number(v.toFixed(6))), [0.05, 0.8, 0.38]);
  const presets = aoasPresets();
  assert.ok(Array.isArray(presets) && presets.includes("coral"), String(presets));
});

test("getters, and rgb as a Float32Array", () => {
  const sky = Sky.neural("hosek", 0.6, 2.5, 7);
  assert.equal(sky.model, "neural");
  assert.equal(sky.sunZenith, Math.fround(0.6));
  assert.equal(sky.sunAzimuth, Math.fround(2.5));
  const rgb = sky.rgb(0.3, 1);
  assert.ok(rgb instanceof Float32Array, String(rgb));
  assert.equal(rgb.length, 3);
  assert.ok(rgb.every((c) => c > 0 && Number.isFinite(c)), String(rgb));
  assert.equal(Sky.aoas("coral").model, "aoas");
  const r = Renderer.panorama(32, 8);
  assert.deepEqual([r.width, r.height], [32, 8]);
  sky.free();
  r.free();
});

test("errors are thrown as JavaScript Errors carrying the message", () => {
  assert.throws(() => Sky.preetham(0.5, 0, 9), (e) => e instanceof Error &&
    e.message === "turbidity = 9 is outside the valid range [2, 6]");
  assert.throws(() => Sky.daylight(1.7, 0, 0.9), (e) => e instanceof Error &&
    e.message === "aerosol optical depth = 0.9 is outside the valid range [0.05, 0.8]");
  assert.throws(() => Sky.daylight(3.5, 0, 0.43), (e) => e instanceof Error &&
    e.message === "sun zenith [rad] = 3.5 is outside the valid range [0, 3.1415927]");
  const r = Renderer.fisheye(8, 4);
  assert.throws(() => r.renderLinear(Sky.preetham(0.5, 0, 3), new Float32Array(5)), (e) =>
    e instanceof Error && e.message === "out has length 5, but a 8x4 image needs 96 (3 per pixel)");
});

test("a weight file passes as a Node Buffer or a Uint8Array", () => {
  const buffer = readFileSync(path.join(root, "sky-core/weights/preetham.skyn"));
  const fromBuffer = Sky.neuralFromBytes(buffer, 0.8, 3, 4).rgb(0.5, 1);
  const fromArray = Sky.neuralFromBytes(new Uint8Array(buffer), 0.8, 3, 4).rgb(0.5, 1);
  assert.ok(fromBuffer.every((c) => c > 0), String(fromBuffer));
  assert.deepEqual(fromArray, fromBuffer);
});

test("renderers write into the caller's typed arrays", () => {
  const sky = Sky.preetham(0.5, 0, 3);
  const r = Renderer.fisheye(16, 16);
  const rgba = new Uint8ClampedArray(16 * 16 * 4).fill(7);
  r.renderSrgb(sky, rgba, sky.autoExposure());
  const centre = (8 * 16 + 8) * 4;
  assert.equal(rgba[centre + 3], 255, "opaque sky at the centre");
  assert.ok(rgba[centre + 2] > 7, "blue written at the centre");
  assert.deepEqual(Array.from(rgba.subarray(0, 4)), [0, 0, 0, 0], "the corner cleared");
  const linear = new Float32Array(16 * 16 * 3);
  r.renderLinear(sky, linear);
  assert.ok(linear[(8 * 16 + 8) * 3 + 2] > 0, "linear blue at the centre");
});

test("the shipped module (after wasm-opt) gives native sky-core's values to 1e-6", () => {
  const native = JSON.parse(readFileSync(nativeFile, "utf8"));
  assert.ok(native.skies.length >= 10, `${native.skies.length} skies`);
  assert.ok(native.skies.filter((s) => s.sky.kind === "daylight").length >= 4, "daylight skies");
  for (const { sky: { kind, args }, rgb } of native.skies) {
    const call = kind === "neuralFromBytes"
      ? [readFileSync(path.join(root, args[0])), ...args.slice(1)] : args;
    const sky = Sky[kind](...call);
    let worst = 0;
    native.directions.forEach(([zenith, azimuth], k) => {
      sky.rgb(zenith, azimuth).forEach((v, c) => {
        const want = rgb[3 * k + c];
        worst = Math.max(worst, Math.abs(v - want) / Math.max(Math.abs(want), 1e-30));
      });
    });
    sky.free();
    assert.ok(worst <= 1e-6, `${kind}(${JSON.stringify(args)}): worst relative difference ${worst}`);
  }
});

test("rgbBatch gives rgb's values; shaderParams and irradiance reach JavaScript", () => {
  const sky = Sky.neural("preetham", 0.9, 2.0, 3);
  const angles = [[0.1, 0.2], [0.8, 2.0], [1.5, -1.0], [1.2, 3.0]];
  const dirs = new Float32Array(angles.flatMap(([t, p]) => [Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)]));
  const batch = sky.rgbBatch(dirs);
  assert.ok(batch instanceof Float32Array && batch.length === 12);
  angles.forEach(([t, p], k) => {
    const one = sky.rgb(t, p);
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(batch[3 * k + c] - one[c]) <= 1e-5 * one[c], `${k}: ${batch[3 * k + c]} vs ${one[c]}`);
  });
  assert.equal(sky.shaderParams().length, 4 * 27);
  assert.throws(() => sky.irradiance(0, 0), /SH skies/);
  assert.throws(() => Sky.aoas("smiley").shaderParams(), /without cloud noise, cloud shapes or ambiguity/);
  const sh = Sky.sh(0.9, 2.0, 3, 3);
  assert.ok(sh.irradiance(0, 0)[1] > 1000, "lux-scale irradiance from above");
  assert.equal(Sky.shUnfiltered(0.9, 2.0, 3, 3).shaderParams().length, 4 * 49);
  // The daylight sky's: two networks of 51 vec4s and the two parts' factors; [0].w is how many
  // networks share the sky (two inside a blend).
  for (const [zenith, parts] of [[0.7, 1], [1.7, 2], [2.0, 1]]) {
    const p = Sky.daylight(zenith, 0.3, 0.2).shaderParams();
    assert.equal(p.length, 4 * 104);
    assert.equal(p[3], parts, `sun zenith ${zenith}`);
  }
});

test("DaylightDay: one call per day, typed arrays, native sky-core's daylight to 1e-6", () => {
  const native = JSON.parse(readFileSync(nativeFile, "utf8"));
  assert.ok(native.daylight.length >= 4);
  for (const want of native.daylight) {
    const day = DaylightDay.at(...want.args);
    assert.ok(day.times instanceof Float64Array && day.globalLux instanceof Float32Array);
    assert.deepEqual(Array.from(day.times), want.times);
    for (const name of ["elevationDeg", "globalLux", "diffuseLux", "directLux", "x", "y", "cctK", "melanopicEdiLux"]) {
      const got = day[name];
      assert.equal(got.length, want[name].length, name);
      let worst = 0;
      want[name].forEach((w, k) => {
        // CCT: null in the native values (sky-core's None) is NaN here.
        if (w === null) return assert.ok(Number.isNaN(got[k]), `${name}[${k}] = ${got[k]}, native has none`);
        worst = Math.max(worst, w === got[k] ? 0 : Math.abs(got[k] - w) / Math.abs(w));
      });
      assert.ok(worst <= 1e-6, `${JSON.stringify(want.args)} ${name}: worst relative difference ${worst}`);
    }
    day.free();
  }
});

test("DaylightDay: bad input throws an Error naming the parameter and its range", () => {
  const vienna = [2026, 6, 21, 0, 86399, 600, 48.21, 16.37, 190];
  const cases = [
    [[...vienna, 0.9], "aerosol optical depth = 0.9 is outside the valid range [0.05, 0.8]"],
    [[2026, 6, 21, 0, 86399, 0.5, 48.21, 16.37, 190, 0.43], "step [s] = 0.5 is outside the valid range [1, 86400]"],
    [[2026, 6, 21, 0, 90000, 60, 48.21, 16.37, 190, 0.43], "end [s after 0:00 UTC] = 90000 is outside the valid range [0, 86399]"],
    [[2026, 6, 21, 0, 86399, 60, 48.21, 200, 190, 0.43], /^longitude.*200.*-180, 180/],
    [[2026, 6, 21, 0, 86399, 60, 48.21, 16.37, 6000, 0.43], "site elevation [m] = 6000 is outside the valid range [-500, 5000]"],
    [[2200, 6, 21, 0, 86399, 60, 48.21, 16.37, 190, 0.43], "year (fast sun position, Grena 2012) = 2200 is outside the valid range [2000, 2110]"],
  ];
  for (const [args, message] of cases) {
    assert.throws(() => DaylightDay.at(...args), (e) => e instanceof Error &&
      (typeof message === "string" ? e.message === message : message.test(e.message)), JSON.stringify(args));
  }
});
