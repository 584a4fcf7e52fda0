// The npm tarball of `scripts/wasm.sh pack`, installed into a scratch project as a user would
// (`npm install ./sky-wasm-VERSION.tgz three@0.187.0`, three from npm's cache of `npm ci`), then
// imported there: in node (the package's three entry points, values against the package's own
// Sky) and in a page served from that project (import map onto node_modules, a SkyMesh
// drawn with WebGL2 in Debian's Chromium), and every JavaScript block of README.md and docs/
// run there as written: a block that imports from `node:` in node, the others in a page.
//
// SKY_WASM_TARBALL: the tarball.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtemp, readFile, readdir, rm, stat, symlink, writeFile } from "node:fs/promises";
import { tmpdir } from "node:os";
import path from "node:path";
import { SWIFTSHADER, launch, serve } from "../browser/harness.mjs";

const root = path.resolve(import.meta.dirname, "../../..");
const tarball = process.env.SKY_WASM_TARBALL;
const THREE = JSON.parse(await readFile(path.join(root, "sky-wasm/package.json"), "utf8")).devDependencies.three;

let scratch;

before(async () => {
  assert.ok(tarball, "SKY_WASM_TARBALL names the packed tarball (scripts/wasm.sh pack)");
  scratch = await mkdtemp(path.join(tmpdir(), "sky-wasm-scratch-"));
  await writeFile(path.join(scratch, "package.json"), JSON.stringify({ name: "scratch", private: true, type: "module" }));
  execFileSync("npm", ["install", "--prefer-offline", "--no-audit", "--no-fund", "--loglevel=error", tarball, `three@${THREE}`],
    { cwd: scratch, stdio: "inherit" });
});

after(async () => {
  if (scratch) await rm(scratch, { recursive: true, force: true });
});

test("the package's manifest says what it is", async () => {
  const pkg = JSON.parse(await readFile(path.join(scratch, "node_modules/sky-wasm/package.json"), "utf8"));
  const cargo = await readFile(path.join(root, "Cargo.toml"), "utf8");
  const version = cargo.match(/\[workspace\.package\][^[]*?version = "([^"]+)"/)[1];
  assert.equal(pkg.name, "sky-wasm");
  assert.equal(pkg.version, version, "the crate's version");
  assert.equal(pkg.type, "module");
  assert.equal(pkg.sideEffects, false);
  assert.deepEqual(Object.keys(pkg.exports).sort(), [".", "./package.json", "./shaders", "./sky_wasm_bg.wasm", "./three"]);
  assert.ok(pkg.types && pkg.peerDependencies.three, "types and the three peer dependency");
  for (const f of pkg.files) {
    // Every listed file is installed; a listed folder (the bindings' snippets/) holds files.
    const installed = path.join(scratch, "node_modules/sky-wasm", f);
    if ((await stat(installed)).isDirectory()) {
      const inside = await readdir(installed, { recursive: true, withFileTypes: true });
      assert.ok(inside.some((e) => e.isFile()), `${f} holds files`);
    } else {
      await readFile(installed);
    }
  }
});

test("node: import the package, its shaders and its three.js module in the scratch project", () => {
  const script = `
    import { readFileSync } from "node:fs";
    import { createRequire } from "node:module";
    import { initSync, Sky } from "sky-wasm";
    import * as shaders from "sky-wasm/shaders";
    import { SkyMesh, skyLightProbe, fromSkyFrame } from "sky-wasm/three";
    const require = createRequire(import.meta.url);
    initSync({ module: readFileSync(require.resolve("sky-wasm/sky_wasm_bg.wasm")) });
    const sky = Sky.neural("hosek", 0.7, 1.2, 4);
    const mesh = new SkyMesh({ model: "neural", weights: "hosek", turbidity: 4 });
    mesh.material.uniforms.sunPosition.value.copy(fromSkyFrame(Math.sin(0.7) * Math.cos(1.2), Math.sin(0.7) * Math.sin(1.2), Math.cos(0.7)));
    mesh.update();
    const probe = skyLightProbe(mesh.material.uniforms.sunPosition.value, 4, 1);
    console.log(JSON.stringify({
      rgb: Array.from(sky.rgb(0.3, 1.0)),
      params: Array.from(sky.shaderParams()),
      uniform: Array.from(mesh.material.uniforms.sky_neural.value),
      glsl: shaders.neural.glsl.includes("vec3 sky_radiance(vec3 dir)"),
      wgsl: shaders.neural.wgsl.includes("fn sky_radiance(dir: vec3<f32>) -> vec3<f32>"),
      probe: probe.sh.coefficients[0].toArray(),
    }));`;
  const out = JSON.parse(execFileSync("node", ["--input-type=module", "-e", script], { cwd: scratch, encoding: "utf8" }));
  assert.ok(out.rgb.every((c) => c > 0 && Number.isFinite(c)), String(out.rgb));
  assert.ok(out.glsl && out.wgsl, "both shader texts");
  assert.equal(out.params.length, 4 * 27);
  // The mesh's uniform holds the sky's parameters (its sun went through three's frame).
  const e = Math.max(...out.params.map((p, i) => Math.abs(p - out.uniform[i]) / Math.max(Math.abs(p), 1e-3)));
  assert.ok(e < 1e-5, `SkyMesh uniform vs Sky.shaderParams: ${e}`);
  assert.ok(out.probe.every((c) => c > 0), `probe band 0: ${out.probe}`);
});

test("browser: a page served from the scratch project draws a SkyMesh", async () => {
  const page_html = `<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,">
<script type="importmap">{ "imports": {
  "three": "/node_modules/three/build/three.module.js",
  "sky-wasm": "/node_modules/sky-wasm/sky_wasm.js",
  "sky-wasm/three": "/node_modules/sky-wasm/three.js" } }</script>
<canvas id="c" width="160" height="120"></canvas>
<script type="module">
  import * as THREE from "three";
  import init from "sky-wasm";
  import { SkyMesh } from "sky-wasm/three";
  await init();
  const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById("c"), preserveDrawingBuffer: true });
  renderer.toneMapping = THREE.ACESFilmicToneMapping;
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(60, 4 / 3, 0.1, 2000);
  camera.lookAt(0, 0.5, -1);
  const sky = new SkyMesh({ model: "preetham" });
  sky.scale.setScalar(1000);
  sky.material.uniforms.sunPosition.value.set(0.3, 0.6, 0.4);
  scene.add(sky);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const px = new Uint8Array(4);
  gl.readPixels(80, 90, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  document.body.dataset.pixel = Array.from(px).join(",");
  document.body.dataset.error = sky.error ?? "";
</script>`;
  const { server, url } = await serve(scratch, { "/": page_html });
  const { browser, page, problems } = await launch(SWIFTSHADER);
  try {
    await page.goto(url);
    await page.waitForSelector("body[data-pixel]", { timeout: 60_000 });
    const [r, g, b] = (await page.getAttribute("body", "data-pixel")).split(",").map(Number);
    console.log(`  scratch page: sky pixel (${r}, ${g}, ${b})`);
    assert.equal(await page.getAttribute("body", "data-error"), "");
    assert.ok(b > r && b > 40, `a blue sky: ${r}, ${g}, ${b}`);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.close();
  }
});

/** The ```js blocks of README.md and docs/*.md: { where, code }. */
async function jsBlocks() {
  const pages = ["README.md", ...(await readdir(path.join(root, "docs"))).filter((f) => f.endsWith(".md")).map((f) => `docs/${f}`)];
  const blocks = [];
  for (const page of pages.sort()) {
    const lines = (await readFile(path.join(root, page), "utf8")).split("\n");
    for (let i = 0; i < lines.length; i++) {
      const open = lines[i].match(/^(\s*)```js\s*$/);
      if (!open) continue;
      const start = i + 1;
      const body = [];
      for (i++; i < lines.length && !/^\s*```\s*$/.test(lines[i]); i++) body.push(lines[i].slice(open[1].length));
      blocks.push({ where: `${page}:${start}`, code: body.join("\n") });
    }
  }
  return blocks;
}

test("every JavaScript block of README.md and docs/ runs as written", async () => {
  const blocks = await jsBlocks();
  assert.ok(blocks.length >= 3, `found ${blocks.length} blocks`);
  const inNode = blocks.filter((b) => /from "node:/.test(b.code));
  const inPage = blocks.filter((b) => !inNode.includes(b));
  for (const b of inNode) {
    try {
      execFileSync("node", ["--input-type=module", "-e", b.code], { cwd: scratch, encoding: "utf8", stdio: "pipe" });
    } catch (e) {
      assert.fail(`${b.where} in node: ${e.stderr || e.message}`);
    }
  }
  // The pages import the package as the docs do: by its name through an import map, or from
  // ./pkg/ as the site built by scripts/wasm.sh lays it out.
  await symlink(path.join(scratch, "node_modules/sky-wasm"), path.join(scratch, "pkg"));
  const { server, url } = await serve(scratch);
  const { browser, page, problems } = await launch(SWIFTSHADER);
  try {
    for (const b of inPage) {
      const html = `<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,">
<script type="importmap">{ "imports": {
  "three": "/node_modules/three/build/three.module.js",
  "sky-wasm": "/node_modules/sky-wasm/sky_wasm.js",
  "sky-wasm/three": "/node_modules/sky-wasm/three.js" } }</script>
<canvas width="512" height="512"></canvas>
<script type="module">
${b.code}
document.body.dataset.done = "1";
</script>`;
      const name = `block-${b.where.replace(/[^a-z0-9]+/gi, "-")}.html`;
      await writeFile(path.join(scratch, name), html);
      await page.goto(`${url}${name}`);
      await page.waitForSelector("body[data-done]", { timeout: 60_000 }).catch(() => {});
      assert.deepEqual(problems, [], `${b.where} in the browser`);
      assert.equal(await page.getAttribute("body", "data-done"), "1", `${b.where} ran to its end`);
    }
  } finally {
    await browser.close();
    server.close();
  }
  console.log(`  ran ${inNode.length} block(s) in node and ${inPage.length} in the browser`);
});
