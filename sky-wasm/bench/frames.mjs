// Frame times of the wasm builds that scripts/wasm.sh bench makes (opt-level 3 or "s", with or
// without simd128), measured in node's V8 in one run, round-robin so that a shared machine's
// load falls on every build alike. Prints ms per 512 × 512 fisheye frame (renderSrgb) and
// ratios against the first build, the one the site ships.
//
// Usage: node bench/frames.mjs NAME=PATH/sky_wasm.js ...
import { createRequire } from "node:module";
import { statSync } from "node:fs";
import path from "node:path";

const require = createRequire(import.meta.url);
const builds = process.argv.slice(2).map((arg) => {
  const [name, file] = arg.split("=");
  const api = require(path.resolve(file));
  const bytes = statSync(path.join(path.dirname(file), "sky_wasm_bg.wasm")).size;
  return { name, api, bytes, renderer: api.Renderer.fisheye(512, 512) };
});
const D = Math.PI / 180;
const models = {
  preetham: (api, a) => api.Sky.preetham(40 * D, a, 3),
  "neural (preetham weights)": (api, a) => api.Sky.neural("preetham", 40 * D, a, 3),
  "aoas physical": (api, a) => api.Sky.aoasWithSun("physical", 40 * D, a),
  "daylight (sun 50° up)": (api, a) => api.Sky.daylight(40 * D, a, 0.43),
  "daylight (blend, 2° up)": (api, a) => api.Sky.daylight(88 * D, a, 0.43),
};
const out = new Uint8ClampedArray(512 * 512 * 4);
const ROUNDS = 15;
const median = (xs) => [...xs].sort((x, y) => x - y)[xs.length >> 1];

for (const b of builds) console.log(`${b.name.padEnd(22)} ${(b.bytes / 1000).toFixed(1)} KB`);
for (const [model, make] of Object.entries(models)) {
  const times = builds.map(() => []);
  for (let round = 0; round < ROUNDS; round++) {
    builds.forEach((b, k) => {
      const sky = make(b.api, round * D);
      const t0 = performance.now();
      b.renderer.renderSrgb(sky, out, sky.autoExposure());
      times[k].push(performance.now() - t0);
      sky.free();
    });
  }
  const base = median(times[0]);
  builds.forEach((b, k) => {
    const ms = median(times[k]);
    console.log(`${model.padEnd(26)} ${b.name.padEnd(22)} ${ms.toFixed(2).padStart(7)} ms/frame  ` +
      `${(base / ms).toFixed(2)}x vs ${builds[0].name}`);
  });
}
