// Each model's generated shader on a GPU in Debian's Chromium, headless, against sky-core's CPU
// values (sky-wasm's `Sky.rgbBatch`) at the same 1,792 view directions: the GLSL ES 3.00 text
// in WebGL2 (ANGLE on SwiftShader) rendered into an RGBA32F target (EXT_color_buffer_float)
// and read back, and the WGSL text in WebGPU (Dawn on SwiftShader's Vulkan) run as a compute
// shader. The bound: 1e-3 relative per channel where sky-core's linear radiance is above 1e-3
// of the image's peak (in magnitude: the daylight sky's twilight blue may have a negative
// channel); and exactly 0 where sky-core's is 0 (every direction below the horizon: sky-core's
// one below-horizon rule, its crate docs' "Conventions"). The daylight sky is checked by day, in
// both blends of its networks, in civil and nautical twilight, at -18° and below it.
//
// Then three.js's SkyMesh with the daylight sky, rendered into a float cube map: its automatic
// exposure holds the exposed mean luminance of the sky at middle grey from the -18° sky to noon,
// over ten decades of luminance.
//
// SKY_WASM_SITE: the built site (scripts/wasm.sh build).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import { SWIFTSHADER, launch, serve } from "./harness.mjs";

const root = path.resolve(import.meta.dirname, "../../..");
const site = process.env.SKY_WASM_SITE ?? path.join(root, "target/wasm/site");
const BOUND = 1e-3;
const FLOOR = 1e-3;

let server, browser, page, url, problems;

before(async () => {
  ({ server, url } = await serve(site, {
    "/gpu.html": "<!doctype html><title>gpu</title><link rel=\"icon\" href=\"data:,\">" +
      "<script type=\"importmap\">{ \"imports\": { \"three\": \"/vendor/three/three.module.js\" } }</script>",
  }));
  ({ browser, page, problems } = await launch(SWIFTSHADER));
  await page.goto(`${url}gpu.html`);
  await page.evaluate(async () => {
    const wasm = await import("/pkg/sky_wasm.js");
    await wasm.default();
    window.wasm = wasm;
    window.shaders = await import("/pkg/shaders.js");
  });
});

after(async () => {
  await browser?.close();
  server?.close();
});

/** The skies: [label, constructor name, arguments] of sky-wasm's `Sky`. */
const DEG = Math.PI / 180;
const SKIES = [
  ["preetham, sun 30° from the zenith, turbidity 2.5", "preetham", [30 * DEG, 1.0, 2.5]],
  ["preetham, sun 70°, turbidity 4", "preetham", [70 * DEG, -2.0, 4]],
  ["preetham, sun 88°, turbidity 6", "preetham", [88 * DEG, 3.0, 6]],
  ["neural (preetham weights), sun 30°, turbidity 2.5", "neural", ["preetham", 30 * DEG, 1.0, 2.5]],
  ["neural (preetham weights), sun 85°, turbidity 5", "neural", ["preetham", 85 * DEG, -2.0, 5]],
  ["neural (hosek weights), sun 45°, turbidity 2", "neural", ["hosek", 45 * DEG, 0.5, 2]],
  ["neural (hosek weights), sun 80°, turbidity 8", "neural", ["hosek", 80 * DEG, 2.5, 8]],
  ["aoas physical (noon)", "aoas", ["physical"]],
  ["aoas physical, sun 75°", "aoasWithSun", ["physical", 75 * DEG, -2.0]],
  ["aoas coral, sun 60°", "aoasWithSun", ["coral", 60 * DEG, 1.0]],
  ["sh 3 bands, sun 40°, turbidity 3", "sh", [40 * DEG, 0.3, 3, 3]],
  ["sh 7 bands, sun 75°, turbidity 5", "sh", [75 * DEG, -1.2, 5, 7]],
  // The daylight sky (sun zenith, azimuth, aerosol optical depth): one network by day, two in
  // the day-to-dusk blend (sun zenith 86°-90°) and the dusk-to-night blend (96°-98°).
  ["daylight, noon (sun 20° from the zenith), aod 0.38", "daylight", [20 * DEG, 1.0, 0.38]],
  ["daylight, sun 60°, aod 0.05", "daylight", [60 * DEG, -2.0, 0.05]],
  ["daylight, day-to-dusk blend (sun 2° up), aod 0.8", "daylight", [88 * DEG, 2.5, 0.8]],
  ["daylight, civil twilight (sun 3° down), aod 0.38", "daylight", [93 * DEG, 0.5, 0.38]],
  ["daylight, dusk-to-night blend (sun 7° down), aod 0.2", "daylight", [97 * DEG, -1.0, 0.2]],
  ["daylight, nautical twilight (sun 10° down), aod 0.38", "daylight", [100 * DEG, 3.0, 0.38]],
  ["daylight, astronomical night (sun 18° down), aod 0.38", "daylight", [108 * DEG, -2.5, 0.38]],
  ["daylight, sun 30° down (the -18° sky), aod 0.6", "daylight", [120 * DEG, 1.5, 0.6]],
];

/** Directions in all: 1,536 over the upper hemisphere, 64 near the sun, 192 below the horizon. */
const N = 1792;

/** In the page: N directions (x, y, z) — 32 zenith rings × 48 azimuths over the upper
 * hemisphere, 64 within 4° of the sun, and 4 rings × 48 below the horizon (1e-5 below it to
 * near the nadir) — the CPU's values and the GPU's. */
async function measure(ctor, args, api) {
  return page.evaluate(async ({ ctor, args, api, N }) => {
    const { Sky } = window.wasm;
    const sky = Sky[ctor](...args);
    const model = sky.model;
    const shader = window.shaders[model];
    const params = sky.shaderParams();
    const [sz, sa] = [sky.sunZenith, sky.sunAzimuth];
    const dirs = new Float32Array(N * 4);
    const put = (i, t, p) => dirs.set([Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t), 0], 4 * i);
    let n = 0;
    for (let i = 0; i < 32; i++) for (let k = 0; k < 48; k++) put(n++, ((i + 0.5) / 32) * (Math.PI / 2), ((k + 0.5) / 48) * 2 * Math.PI);
    // Near the sun: rings at 0.5°-4° around it (sun-centred frame rotated to the sun).
    const s = [Math.sin(sz) * Math.cos(sa), Math.sin(sz) * Math.sin(sa), Math.cos(sz)];
    const e1 = [-Math.sin(sa), Math.cos(sa), 0];
    const e2 = [s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]];
    for (let r = 0; r < 8; r++) for (let k = 0; k < 8; k++) {
      const g = (0.5 + r * 0.5) * (Math.PI / 180), a = (k / 8) * 2 * Math.PI;
      const d = [0, 1, 2].map((c) => Math.cos(g) * s[c] + Math.sin(g) * (Math.cos(a) * e1[c] + Math.sin(a) * e2[c]));
      dirs.set([...d, 0], 4 * n++);
    }
    // Below the horizon: z = −1e-5 (past sky-core's tolerance of 1e-6), −0.01, −0.3, −0.9.
    for (const z of [1e-5, 0.01, 0.3, 0.9]) for (let k = 0; k < 48; k++) {
      const p = ((k + 0.25) / 48) * 2 * Math.PI, r = Math.sqrt(1 - z * z);
      dirs.set([r * Math.cos(p), r * Math.sin(p), -z, 0], 4 * n++);
    }
    const xyz = new Float32Array(N * 3);
    for (let i = 0; i < N; i++) xyz.set(dirs.subarray(4 * i, 4 * i + 3), 3 * i);
    const cpu = Array.from(sky.rgbBatch(xyz));
    sky.free();

    let gpu;
    if (api === "webgl2") {
      const canvas = document.createElement("canvas");
      const gl = canvas.getContext("webgl2");
      if (!gl) throw new Error("no WebGL2");
      if (!gl.getExtension("EXT_color_buffer_float")) throw new Error("no EXT_color_buffer_float");
      const [w, h] = [64, N / 64];
      const compile = (type, text) => {
        const sh = gl.createShader(type);
        gl.shaderSource(sh, text);
        gl.compileShader(sh);
        if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(sh));
        return sh;
      };
      const prog = gl.createProgram();
      gl.attachShader(prog, compile(gl.VERTEX_SHADER, "#version 300 es\nvoid main() { vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }"));
      gl.attachShader(prog, compile(gl.FRAGMENT_SHADER, `#version 300 es
precision highp float;
precision highp int;
${shader.glsl}
uniform highp sampler2D directions;
out vec4 color;
void main() {
    vec3 d = texelFetch(directions, ivec2(gl_FragCoord.xy), 0).xyz;
    color = vec4(sky_radiance(d), 1.0);
}`));
      gl.linkProgram(prog);
      if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
      gl.useProgram(prog);
      gl.uniform4fv(gl.getUniformLocation(prog, `sky_${model}`), params);
      const tex = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, w, h, 0, gl.RGBA, gl.FLOAT, dirs);
      for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
      gl.uniform1i(gl.getUniformLocation(prog, "directions"), 0);
      const target = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, target);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, w, h, 0, gl.RGBA, gl.FLOAT, null);
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
      if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error("float target incomplete");
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.viewport(0, 0, w, h);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      const out = new Float32Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.FLOAT, out);
      gpu = Array.from(out);
    } else {
      const adapter = await navigator.gpu?.requestAdapter();
      if (!adapter) throw new Error("no WebGPU adapter");
      const device = await adapter.requestDevice();
      const code = `${shader.wgsl}
@group(0) @binding(1) var<storage, read> directions: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> radiance: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i < arrayLength(&directions)) {
        radiance[i] = vec4<f32>(sky_radiance(directions[i].xyz), 1.0);
    }
}`;
      const module = device.createShaderModule({ code });
      const info = await module.getCompilationInfo();
      const errors = info.messages.filter((m) => m.type === "error");
      if (errors.length) throw new Error(errors.map((m) => m.message).join("\n"));
      const buffer = (data, usage) => {
        const b = device.createBuffer({ size: data.byteLength, usage, mappedAtCreation: true });
        new Float32Array(b.getMappedRange()).set(data);
        b.unmap();
        return b;
      };
      const U = GPUBufferUsage;
      const uniforms = buffer(params, U.UNIFORM);
      const input = buffer(dirs, U.STORAGE);
      const output = device.createBuffer({ size: dirs.byteLength, usage: U.STORAGE | U.COPY_SRC });
      const readback = device.createBuffer({ size: dirs.byteLength, usage: U.MAP_READ | U.COPY_DST });
      const pipeline = device.createComputePipeline({ layout: "auto", compute: { module, entryPoint: "main" } });
      const bind = device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [uniforms, input, output].map((buf, binding) => ({ binding, resource: { buffer: buf } })),
      });
      const enc = device.createCommandEncoder();
      const pass = enc.beginComputePass();
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bind);
      pass.dispatchWorkgroups(N / 64);
      pass.end();
      enc.copyBufferToBuffer(output, 0, readback, 0, dirs.byteLength);
      device.queue.submit([enc.finish()]);
      await readback.mapAsync(GPUMapMode.READ);
      gpu = Array.from(new Float32Array(readback.getMappedRange()));
      readback.unmap();
      device.destroy();
    }
    return { model, cpu, gpu };
  }, { ctor, args, api, N });
}

/** The worst relative difference per channel above the floor, and how many directions it
 * covered; how many directions sky-core makes black, and at how many of them the GPU is not. */
function compare({ cpu, gpu }) {
  const peak = Math.max(...cpu.map(Math.abs));
  let worst = 0, at = -1, counted = 0, nonFinite = 0, black = 0, notBlack = 0;
  for (let i = 0; i < N; i++) {
    if ([0, 1, 2].every((c) => cpu[3 * i + c] === 0)) {
      black++;
      if ([0, 1, 2].some((c) => gpu[4 * i + c] !== 0)) notBlack++;
    }
    let any = false;
    for (let c = 0; c < 3; c++) {
      const want = cpu[3 * i + c], got = gpu[4 * i + c];
      if (!Number.isFinite(got)) nonFinite++;
      if (Math.abs(want) > FLOOR * peak) {
        any = true;
        const e = Math.abs(got - want) / Math.abs(want);
        if (e > worst) [worst, at] = [e, i];
      }
    }
    if (any) counted++;
  }
  return { worst, at, counted, nonFinite, peak, black, notBlack };
}

for (const api of ["webgl2", "webgpu"]) {
  test(`${api}: every model's shader agrees with sky-core to ${BOUND} relative at ${N} directions, 0 below the horizon`, async () => {
    for (const [label, ctor, args] of SKIES) {
      const r = compare(await measure(ctor, args, api));
      console.log(`  ${api} ${label}: max relative difference ${r.worst.toExponential(2)} over ${r.counted} directions above ${FLOOR} of the peak (${r.peak.toPrecision(4)})`);
      assert.equal(r.nonFinite, 0, `${label}: non-finite GPU values`);
      assert.ok(r.counted >= 1000, `${label}: only ${r.counted} directions above the floor`);
      assert.ok(r.worst <= BOUND, `${label}: ${r.worst} at direction ${r.at}`);
      assert.ok(r.black >= 192, `${label}: sky-core black at only ${r.black} directions (192 below the horizon)`);
      assert.equal(r.notBlack, 0, `${label}: the GPU is not black at ${r.notBlack} of sky-core's ${r.black} black directions`);
    }
    assert.deepEqual(problems, []);
  });
}

/** The exposure test's suns: every 3° of elevation from -18° to 90°, and 30° below the horizon
 * (where the daylight sky is the -18° one); its atmospheres: sky-core's tables' clearest,
 * default and haziest. */
const EXPOSURE_ELEVATIONS = [...Array.from({ length: 37 }, (_, k) => -18 + 3 * k), -30];
const EXPOSURE_AODS = [0.05, 0.38, 0.8];
/** Automatic exposure's target: the sky's mean luminance to middle grey (sky-wasm's
 * `autoExposure`). */
const MIDDLE_GREY = 0.18;
/** How far the exposed mean may stray from middle grey: `autoExposure` averages 812 directions
 * of an equal-area fisheye, the test a 6 × 32 × 32 cube map (two quadratures of one integral;
 * the sun's aureole near noon is where they differ most). */
const EXPOSURE_BAND = [0.9, 1.1];

test("webgl2: SkyMesh's automatic exposure holds the daylight sky at middle grey from -18° to noon", async () => {
  const rows = await page.evaluate(async ({ elevations, aods }) => {
    const THREE = await import("three");
    const { SkyMesh, fromSkyFrame } = await import("/pkg/three.js");
    const renderer = new THREE.WebGLRenderer({ canvas: document.createElement("canvas") });
    renderer.toneMapping = THREE.NoToneMapping;
    const size = 32;
    const target = new THREE.WebGLCubeRenderTarget(size, { type: THREE.FloatType });
    const camera = new THREE.CubeCamera(0.1, 10, target);
    const scene = new THREE.Scene();
    const sky = new SkyMesh({ model: "daylight" });
    scene.add(sky);
    // Each texel's solid angle (exact, from the face's projection), the same on every face.
    const A = (x, y) => Math.atan2(x * y, Math.sqrt(x * x + y * y + 1));
    const omega = new Float64Array(size * size);
    for (let j = 0; j < size; j++) for (let i = 0; i < size; i++) {
      const [u0, u1, v0, v1] = [i, i + 1, j, j + 1].map((t) => (2 * t) / size - 1);
      omega[j * size + i] = A(u1, v1) - A(u0, v1) - A(u1, v0) + A(u0, v0);
    }
    const pixels = new Float32Array(size * size * 4);
    const out = [];
    for (const aod of aods) for (const elevation of elevations) {
      const h = (elevation * Math.PI) / 180;
      sky.material.uniforms.sunPosition.value.copy(fromSkyFrame(Math.cos(h) * Math.cos(0.4), Math.cos(h) * Math.sin(0.4), Math.sin(h)));
      sky.material.uniforms.aod.value = aod;
      sky.update();
      const scale = sky.material.uniforms.luminanceScale.value;
      camera.update(renderer, scene);
      let sum = 0, lo = Infinity, hi = 0, nonFinite = 0;
      for (let face = 0; face < 6; face++) {
        renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels, face);
        for (let k = 0; k < size * size; k++) {
          // sky-core's luminance of linear sRGB (the middle row of its sRGB -> XYZ matrix).
          const y = 0.2126 * pixels[4 * k] + 0.7152 * pixels[4 * k + 1] + 0.0722 * pixels[4 * k + 2];
          if (!Number.isFinite(y)) nonFinite++;
          sum += y * omega[k];
          if (y > 0) [lo, hi] = [Math.min(lo, y / scale), Math.max(hi, y / scale)];
        }
      }
      // The sky is 0 below the horizon: the whole sphere's integral over 2π sr is the upper
      // hemisphere's mean.
      out.push({ aod, elevation, scale, mean: sum / (2 * Math.PI), lo, hi, nonFinite, error: sky.error });
    }
    target.dispose();
    renderer.dispose();
    return out;
  }, { elevations: EXPOSURE_ELEVATIONS, aods: EXPOSURE_AODS });
  let [worstLow, worstHigh, darkest, brightest] = [Infinity, 0, Infinity, 0];
  for (const aod of EXPOSURE_AODS) {
    const of = rows.filter((r) => r.aod === aod);
    const at = (e) => of.find((r) => r.elevation === e);
    const ratios = of.map((r) => r.mean / MIDDLE_GREY);
    console.log(`  aod ${aod}: exposure ${at(90).scale.toExponential(3)} per cd/m² at noon, ${at(-18).scale.toExponential(3)} at -18° ` +
      `(${Math.log10(at(-18).scale / at(90).scale).toFixed(2)} decades); exposed mean / middle grey ${Math.min(...ratios).toFixed(4)} to ${Math.max(...ratios).toFixed(4)}`);
  }
  for (const r of rows) {
    assert.equal(r.error, null, `aod ${r.aod}, sun ${r.elevation}°: ${r.error}`);
    assert.equal(r.nonFinite, 0, `aod ${r.aod}, sun ${r.elevation}°: non-finite pixels`);
    const ratio = r.mean / MIDDLE_GREY;
    [worstLow, worstHigh] = [Math.min(worstLow, ratio), Math.max(worstHigh, ratio)];
    [darkest, brightest] = [Math.min(darkest, r.lo), Math.max(brightest, r.hi)];
    assert.ok(ratio >= EXPOSURE_BAND[0] && ratio <= EXPOSURE_BAND[1],
      `aod ${r.aod}, sun ${r.elevation}°: exposed mean ${r.mean} is ${ratio} of middle grey`);
  }
  const decades = Math.log10(brightest / darkest);
  console.log(`  sky luminance from ${darkest.toExponential(3)} cd/m² (the darkest direction, -18°) to ${brightest.toExponential(3)} (the brightest, noon): ` +
    `${decades.toFixed(2)} decades; exposed mean / middle grey ${worstLow.toFixed(4)} to ${worstHigh.toFixed(4)} over ${rows.length} skies`);
  assert.ok(decades >= 10, `the skies span ${decades} decades of luminance`);
  // -30° draws the -18° sky: the same exposure.
  for (const aod of EXPOSURE_AODS) {
    const [a, b] = [-18, -30].map((e) => rows.find((r) => r.aod === aod && r.elevation === e).scale);
    assert.ok(Math.abs(a - b) <= 1e-3 * a, `aod ${aod}: ${a} at -18°, ${b} at -30°`);
  }
  assert.deepEqual(problems, []);
});
