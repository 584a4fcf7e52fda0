// Frame times of the wasm builds that scripts/wasm.sh bench makes (opt-level 3 or "s", with or
// without simd128), measured in node's V8 in one run, round-robin so that a shared machine's
// load falls on every build alike. Prints ms per 512 × 512 fisheye frame (renderSrgb) and
// ratios against the first build, the one the site ships; and µs per sky built (the constructor,
// which a page calls whenever the sun or the atmosphere moves). Builds of fewer models (the
// neural-only build) are measured on the models they have.
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
// Each model by its constructor's name and arguments (the sun's azimuth `a` moves a degree a
// round); a build without the constructor (a build of fewer models) is left out of its lines.
const models = {
  preetham: ["preetham", (a) => [40 * D, a, 3]],
  "neural (preetham weights)": ["neural", (a) => ["preetham", 40 * D, a, 3]],
  "aoas physical": ["aoasWithSun", (a) => ["physical", 40 * D, a]],
  "sh (7 bands)": ["sh", (a) => [40 * D, a, 3, 7]],
  "daylight (sun 50° up)": ["daylight", (a) => [40 * D, a, 0.43]],
  "daylight (blend, 2° up)": ["daylight", (a) => [88 * D, a, 0.43]],
};
const out = new Uint8ClampedArray(512 * 512 * 4);
const ROUNDS = 15;
// Skies built per timed construction: the constructors take microseconds.
const SKIES = 200;
const median = (xs) => [...xs].sort((x, y) => x - y)[xs.length >> 1];

// times[k]: the round-robin measurements of builds[k] (null for a build without the model).
function roundRobin(has, measure) {
  const times = builds.map((b) => (has(b) ? [] : null));
  for (let round = 0; round < ROUNDS; round++) {
    builds.forEach((b, k) => times[k]?.push(measure(b, round)));
  }
  return times;
}

function print(label, unit, times) {
  const first = times.findIndex((t) => t);
  const base = median(times[first]);
  builds.forEach((b, k) => {
    if (!times[k]) return;
    const v = median(times[k]);
    console.log(`${label.padEnd(34)} ${b.name.padEnd(22)} ${v.toFixed(2).padStart(7)} ${unit}  ` +
      `${(base / v).toFixed(2)}x vs ${builds[first].name}`);
  });
}

for (const b of builds) console.log(`${b.name.padEnd(22)} ${(b.bytes / 1000).toFixed(1)} KB`);
for (const [model, [ctor, args]] of Object.entries(models)) {
  const has = (b) => typeof b.api.Sky[ctor] === "function";
  print(model, "ms/frame", roundRobin(has, (b, round) => {
    const sky = b.api.Sky[ctor](...args(round * D));
    const t0 = performance.now();
    b.renderer.renderSrgb(sky, out, sky.autoExposure());
    const ms = performance.now() - t0;
    sky.free();
    return ms;
  }));
  print(`${model}, sky built`, "µs/sky  ", roundRobin(has, (b, round) => {
    const t0 = performance.now();
    for (let k = 0; k < SKIES; k++) b.api.Sky[ctor](...args((round + k / SKIES) * D)).free();
    return ((performance.now() - t0) * 1000) / SKIES;
  }));
}
