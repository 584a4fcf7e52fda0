// The three.js demo (www/three.html) in Debian's Chromium, WebGL2 on SwiftShader: it renders
// without a console error, the sky follows the time slider, the lit objects take the sky's
// colour (white-blue at noon, warm at sunset) read from the canvas, every model and both lights
// draw, the physical daylight sky (the default) draws the blue hour and the night, and the light
// probe's irradiance (three's SphericalHarmonics3) is sky-core's.
//
// SKY_WASM_SITE: the built site; SKY_WASM_ARTIFACTS: where the screenshot goes.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { mkdir } from "node:fs/promises";
import path from "node:path";
import { SWIFTSHADER, launch, serve } from "./harness.mjs";

const root = path.resolve(import.meta.dirname, "../../..");
const site = process.env.SKY_WASM_SITE ?? path.join(root, "target/wasm/site");
const artifacts = process.env.SKY_WASM_ARTIFACTS ?? path.join(root, "target/wasm/artifacts");

let server, browser, page, url, problems;

before(async () => {
  ({ server, url } = await serve(site));
  ({ browser, page, problems } = await launch(SWIFTSHADER));
  await page.goto(`${url}three.html`);
  await page.waitForSelector("body[data-ready=true]", { timeout: 60_000 });
});

after(async () => {
  await browser?.close();
  server?.close();
});

/** Sets controls (id → value) and waits for the redraw (the demo draws on `input`). */
async function set(controls) {
  await page.evaluate((controls) => {
    for (const [id, value] of Object.entries(controls)) {
      const el = document.getElementById(id);
      el.value = String(value);
      el.dispatchEvent(new Event("input", { bubbles: true }));
    }
  }, controls);
  assert.equal(await page.textContent("#error"), "", `no error after ${JSON.stringify(controls)}`);
}

/** RGB of the canvas at a pixel (x from the left, y from the top), mean over a 5 × 5 patch. */
async function rgbAt([x, y]) {
  return page.evaluate(([x, y]) => {
    const gl = window.skyDemo.renderer.getContext();
    const d = new Uint8Array(4 * 25);
    gl.readPixels(x - 2, gl.drawingBufferHeight - 1 - y - 2, 5, 5, gl.RGBA, gl.UNSIGNED_BYTE, d);
    const sum = [0, 0, 0];
    for (let k = 0; k < 25; k++) for (let c = 0; c < 3; c++) sum[c] += d[4 * k + c];
    return sum.map((s) => s / 25);
  }, [x, y]);
}

/** The whole canvas, as RGBA bytes. */
async function canvasPixels() {
  const b64 = await page.evaluate(() => {
    const gl = window.skyDemo.renderer.getContext();
    const d = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
    gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, d);
    let s = "";
    for (let k = 0; k < d.length; k += 0x8000) s += String.fromCharCode(...d.subarray(k, k + 0x8000));
    return btoa(s);
  });
  return Buffer.from(b64, "base64");
}

const sunSide = () => page.evaluate(() => window.skyDemo.sunSidePixel());
const skyPixel = [450, 30]; // high in the northern sky
const show = (c) => c.map((v) => v.toFixed(0)).join(", ");

test("the page renders without a console error, the daylight sky by default", async () => {
  assert.deepEqual(problems, []);
  assert.equal(await page.inputValue("#model"), "daylight", "the page opens on the daylight sky");
  assert.equal(await page.evaluate(() => window.skyDemo.sky.model), "daylight");
  const px = await canvasPixels();
  const colours = new Set();
  for (let k = 0; k < px.length; k += 4) colours.add((px[k] << 16) | (px[k + 1] << 8) | px[k + 2]);
  assert.ok(colours.size > 500, `the scene has ${colours.size} distinct colours`);
});

for (const light of ["environment", "probe"]) {
  test(`${light}: at noon the white sphere is white-blue, at sunset warm; the sky follows the time`, async () => {
    await set({ model: "preetham", light, turbidity: 3, time: 13 * 60 });
    const noonSky = await rgbAt(skyPixel);
    const noon = await rgbAt(await sunSide());
    const noonPixels = await canvasPixels();
    await set({ time: 20 * 60 + 50 }); // the sun about 0.3° high in the north-west
    const sunsetSky = await rgbAt(skyPixel);
    const sunset = await rgbAt(await sunSide());
    const sunsetPixels = await canvasPixels();
    console.log(`  ${light}: white sphere, sun side: noon (${show(noon)}), sunset (${show(sunset)}); sky: noon (${show(noonSky)}), sunset (${show(sunsetSky)})`);
    assert.ok(noon[2] >= noon[0] && noon[2] >= noon[1] * 0.95, `noon sphere white-blue: ${noon}`);
    assert.ok(Math.min(...noon) > 0.45 * Math.max(...noon), `noon sphere near white, not saturated: ${noon}`);
    assert.ok(sunset[0] > 1.15 * sunset[2] && sunset[0] >= sunset[1], `sunset sphere warm: ${sunset}`);
    assert.ok(noonSky[2] > noonSky[0], `noon sky blue: ${noonSky}`);
    const changed = noonPixels.filter((v, k) => Math.abs(v - sunsetPixels[k]) > 8).length;
    assert.ok(changed > 0.3 * noonPixels.length, `the time changed ${changed} of ${noonPixels.length} values`);
    assert.deepEqual(problems, []);
  });
}

// With the light probe: SwiftShader takes ~11 s per PMREM environment map (GGX filtering on
// the CPU), ~0.6 s per frame without it.
test("every model draws the sky and lights the scene", async () => {
  await set({ model: "preetham", light: "probe", time: 10 * 60 });
  let before = await canvasPixels();
  for (const model of ["neural-preetham", "neural-hosek", "aoas", "sh", "daylight", "preetham"]) {
    await set({ model });
    const now = await canvasPixels();
    const differing = now.filter((v, k) => v !== before[k]).length;
    assert.ok(differing > 1000, `${model} changed ${differing} values`);
    const sky = await rgbAt(skyPixel);
    assert.ok(sky[2] > sky[0], `${model}: a blue morning sky ${sky}`);
    before = now;
  }
  assert.deepEqual(problems, []);
});

test("the light probe's irradiance is sky-core's SH irradiance (1e-5 of the largest)", async () => {
  const r = await page.evaluate(async () => {
    const { Sky } = await import("/pkg/sky_wasm.js");
    const { skyLightProbe, fromSkyFrame } = await import("/pkg/three.js");
    const { Vector3 } = await import("three");
    let worst = 0, peak = 0;
    for (const [z, a, t] of [[0.5, 1.0, 3], [1.3, -2.0, 5], [1.55, 2.8, 2.5]]) {
      const probe = skyLightProbe(fromSkyFrame(Math.sin(z) * Math.cos(a), Math.sin(z) * Math.sin(a), Math.cos(z)), t, 1);
      const sky = Sky.sh(z, a, t, 3);
      const rows = [];
      for (let i = 0; i <= 12; i++) for (let k = 0; k < 24; k++) {
        const [nz, na] = [(i / 12) * Math.PI, (k / 24) * 2 * Math.PI];
        const n = fromSkyFrame(Math.sin(nz) * Math.cos(na), Math.sin(nz) * Math.sin(na), Math.cos(nz));
        const three = probe.sh.getIrradianceAt(n, new Vector3());
        rows.push([[three.x, three.y, three.z], Array.from(sky.irradiance(nz, na))]);
      }
      sky.free();
      const top = Math.max(...rows.map(([, want]) => Math.max(...want)));
      peak = Math.max(peak, top);
      // sky-core clamps the irradiance at zero where the 3-band series dips below it (normals
      // facing the ground); three's probe is the series itself.
      for (const [got, want] of rows) for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(Math.max(got[c], 0) - want[c]) / top);
    }
    return { worst, peak };
  });
  console.log(`  light probe vs sky-core: max difference ${r.worst.toExponential(2)} of the largest irradiance (${r.peak.toPrecision(4)})`);
  // three's constants have 6 digits (0.886227 for π/(2√π), ...).
  assert.ok(r.worst <= 1e-5, `light probe irradiance off by ${r.worst}`);
});

test("the daylight sky draws the blue hour and the night, lit by its environment map", async () => {
  const elevation = () => page.evaluate(() => Number(document.body.dataset.sunElevationDeg));
  // 21:55, the sun about 7° below the horizon; 01:05, the night's deepest sun, about 18.4° down.
  for (const [time, label] of [[21 * 60 + 55, "blue hour"], [60 + 5, "night"]]) {
    await set({ model: "daylight", light: "environment", aod: 0.38, time });
    const sun = await elevation();
    const sky = await rgbAt(skyPixel);
    const sphere = await rgbAt(await sunSide());
    console.log(`  daylight, ${label} (sun ${sun.toFixed(2)}°): sky (${show(sky)}), white sphere (${show(sphere)})`);
    assert.ok(sun < -4, `${label}: the sun ${sun}° is below the horizon`);
    assert.ok(sky[2] > sky[0] && sky[2] > 60, `${label}: a blue sky under automatic exposure: ${sky}`);
    assert.ok(sphere[2] >= sphere[0] && Math.max(...sphere) > 30, `${label}: the sphere lit by the blue sky: ${sphere}`);
  }
  assert.ok(await elevation() < -18, "the night's sun is below -18°");
  // The probe is the Preetham sky's SH, which has no night: a clear message, no exception.
  await page.evaluate(() => {
    const el = document.getElementById("light");
    el.value = "probe";
    el.dispatchEvent(new Event("input", { bubbles: true }));
  });
  assert.match(await page.textContent("#error"), /light probe .* needs the sun above the horizon/);
  assert.deepEqual(problems, []);
});

test("screenshot kept as an artifact: the blue hour in the daylight sky", async () => {
  await set({ model: "daylight", light: "environment", aod: 0.38, turbidity: 3, time: 21 * 60 + 55 });
  await mkdir(artifacts, { recursive: true });
  const file = path.join(artifacts, "three.png");
  await page.screenshot({ path: file, fullPage: true, timeout: 120_000 });
  console.log(`  screenshot: ${file}`);
  assert.deepEqual(problems, []);
});
