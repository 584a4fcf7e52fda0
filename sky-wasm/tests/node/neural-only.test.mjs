// The neural-only build (`--no-default-features --features neural`, scripts/wasm.sh build: the
// .wasm for a page that draws the neural sky alone) in node: it exports the neural sky and the
// renderers and nothing of the other models, and it computes what the build with every model
// computes, bit for bit (the same sky-core and sky-wasm code; the other models left out).
//
// Input (written by scripts/wasm.sh): SKY_WASM_NODE_PKG, the `--target nodejs` bindings of the
// build with every model; SKY_WASM_NEURAL_NODE_PKG, those of the neural-only build.
import { test } from "node:test";
import assert from "node:assert/strict";
import { createRequire } from "node:module";
import path from "node:path";

const root = path.resolve(import.meta.dirname, "../../..");
const require = createRequire(import.meta.url);
const full = require(path.resolve(process.env.SKY_WASM_NODE_PKG ?? path.join(root, "target/wasm/node/sky_wasm.js")));
const neural = require(path.resolve(process.env.SKY_WASM_NEURAL_NODE_PKG ?? path.join(root, "target/wasm/neural/node/sky_wasm.js")));

test("the neural-only build exports the neural sky and the renderers, and no other model", () => {
  assert.equal(typeof neural.Sky.neural, "function");
  for (const name of ["rgb", "rgbBatch", "shaderParams", "autoExposure", "free"]) {
    assert.equal(typeof neural.Sky.prototype[name], "function", `sky.${name}`);
  }
  for (const name of ["fisheye", "panorama"]) {
    assert.equal(typeof neural.Renderer[name], "function", `Renderer.${name}`);
  }
  for (const name of ["renderSrgb", "renderDifferenceSrgb", "renderLinear"]) {
    assert.equal(typeof neural.Renderer.prototype[name], "function", `renderer.${name}`);
  }
  for (const name of ["preetham", "neuralFromBytes", "aoas", "aoasWithSun", "sh", "shUnfiltered", "daylight"]) {
    assert.equal(neural.Sky[name], undefined, `Sky.${name} is left out`);
  }
  assert.equal(neural.Sky.prototype.irradiance, undefined, "sky.irradiance is left out");
  assert.equal(neural.Renderer.sphere, undefined, "Renderer.sphere is left out");
  for (const name of ["DaylightDay", "SunPosition", "aoasPresets", "daylightMinAod"]) {
    assert.equal(neural[name], undefined, `${name} is left out`);
  }
});

// The skies compared: both shipped weight sets, suns high and low, turbidities across the range.
const skies = [
  ["preetham", 0.2, 0.3, 2.2],
  ["preetham", 1.5, -2.0, 5.5],
  ["hosek", 0.9, 4.0, 1.5],
  ["hosek", 1.3, 1.0, 9.0],
];

test("its values, images, exposures and shader parameters equal the full build's", () => {
  const dirs = new Float32Array(3 * 50);
  for (let k = 0; k < 50; k++) {
    const [z, a] = [(k * 0.037) % 1.6, k * 0.61];
    dirs.set([Math.sin(z) * Math.cos(a), Math.sin(z) * Math.sin(a), Math.cos(z)], 3 * k);
  }
  for (const args of skies) {
    const [a, b] = [full.Sky.neural(...args), neural.Sky.neural(...args)];
    const what = args.join(", ");
    assert.deepEqual(b.rgbBatch(dirs), a.rgbBatch(dirs), `rgbBatch, ${what}`);
    assert.deepEqual(b.rgb(0.4, 2), a.rgb(0.4, 2), `rgb, ${what}`);
    assert.equal(b.autoExposure(), a.autoExposure(), `autoExposure, ${what}`);
    assert.deepEqual(b.shaderParams(), a.shaderParams(), `shaderParams, ${what}`);
    for (const kind of ["fisheye", "panorama"]) {
      const [ra, rb] = [full.Renderer[kind](48, 40), neural.Renderer[kind](48, 40)];
      const [sa, sb] = [new Uint8ClampedArray(48 * 40 * 4), new Uint8ClampedArray(48 * 40 * 4)];
      ra.renderSrgb(a, sa, a.autoExposure());
      rb.renderSrgb(b, sb, b.autoExposure());
      assert.deepEqual(sb, sa, `${kind} renderSrgb, ${what}`);
      assert.ok(sb.some((v, i) => i % 4 !== 3 && v > 0), `${kind} is not black, ${what}`);
      const [la, lb] = [new Float32Array(48 * 40 * 3), new Float32Array(48 * 40 * 3)];
      ra.renderLinear(a, la);
      rb.renderLinear(b, lb);
      assert.deepEqual(lb, la, `${kind} renderLinear, ${what}`);
      ra.free();
      rb.free();
    }
    a.free();
    b.free();
  }
});

test("its errors carry the full build's messages", () => {
  const message = (f) => {
    try {
      f();
    } catch (e) {
      assert.ok(e instanceof Error, String(e));
      return e.message;
    }
    assert.fail("no error thrown");
  };
  for (const f of [
    (m) => m.Sky.neural("perez", 0.5, 0, 3),
    (m) => m.Sky.neural("preetham", 0.5, 0, 9),
    (m) => m.Sky.neural("hosek", 1.7, 0, 3),
    (m) => m.Sky.neural("hosek", 0.5, NaN, 3),
    (m) => m.Renderer.fisheye(0, 4),
    (m) => m.Renderer.panorama(8, 4).renderSrgb(m.Sky.neural("hosek", 0.5, 0, 3), new Uint8ClampedArray(7), 1),
  ]) {
    const expected = message(() => f(full));
    assert.equal(message(() => f(neural)), expected);
  }
  assert.equal(message(() => neural.Sky.neural("preetham", 0.5, 0, 9)),
    "turbidity = 9 is outside the valid range [2, 6]");
});
