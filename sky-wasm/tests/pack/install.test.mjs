// The npm tarball of `scripts/wasm.sh pack`, installed into a scratch project as a user would
// (`npm install ./sky-wasm-VERSION.tgz three@0.187.0 @types/three@0.187.0`, from npm's cache of
// `npm ci`), then used there: its manifest, licences and README; in node (the package's three
// entry points, `await init()`, values against the package's own Sky, SkyMesh's errors); in
// pages served from that project (import map onto node_modules; bundled by esbuild and by
// Vite, the tools of sky-wasm/package-lock.json), a SkyMesh drawn with WebGL2 in Debian's
// Chromium; its types checked by tsc with lib es2022; and every JavaScript block of README.md
// and docs/ run there as written: a block that imports from `node:` in node, the others in a
// page.
//
// SKY_WASM_TARBALL: the tarball.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdir, mkdtemp, readFile, readdir, rm, stat, symlink, writeFile } from "node:fs/promises";
import { tmpdir } from "node:os";
import path from "node:path";
import { SWIFTSHADER, launch, serve } from "../browser/harness.mjs";

const root = path.resolve(import.meta.dirname, "../../..");
const tarball = process.env.SKY_WASM_TARBALL;
const DEV = JSON.parse(await readFile(path.join(root, "sky-wasm/package.json"), "utf8")).devDependencies;
const THREE = DEV.three;
/** The tools from sky-wasm's own node_modules (setup's `npm ci`), run on the scratch project. */
const bin = (name) => path.join(root, "sky-wasm/node_modules/.bin", name);

let scratch;

before(async () => {
  assert.ok(tarball, "SKY_WASM_TARBALL names the packed tarball (scripts/wasm.sh pack)");
  scratch = await mkdtemp(path.join(tmpdir(), "sky-wasm-scratch-"));
  await writeFile(path.join(scratch, "package.json"), JSON.stringify({ name: "scratch", private: true, type: "module" }));
  execFileSync("npm", ["install", "--prefer-offline", "--no-audit", "--no-fund", "--loglevel=error", tarball, `three@${THREE}`, `@types/three@${DEV["@types/three"]}`],
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

test("the manifest names the repository, homepage and issue tracker of Cargo.toml's repository", async () => {
  const pkg = JSON.parse(await readFile(path.join(scratch, "node_modules/sky-wasm/package.json"), "utf8"));
  const cargo = await readFile(path.join(root, "Cargo.toml"), "utf8");
  const repository = cargo.match(/\[workspace\.package\][^[]*?repository = "([^"]+)"/)[1];
  assert.match(repository, /^https:\/\/github\.com\/[^/]+\/[^/]+$/);
  assert.deepEqual(pkg.repository, { type: "git", url: `git+${repository}.git`, directory: "sky-wasm" });
  assert.equal(pkg.homepage, `${repository}#readme`);
  assert.deepEqual(pkg.bugs, { url: `${repository}/issues` });
});

test("the tarball carries the licence texts of its declared licence, MIT OR Apache-2.0", async () => {
  const pkg = JSON.parse(await readFile(path.join(scratch, "node_modules/sky-wasm/package.json"), "utf8"));
  assert.equal(pkg.license, "MIT OR Apache-2.0");
  const listed = execFileSync("tar", ["-tzf", tarball], { encoding: "utf8" }).split("\n");
  const text = (f) => readFile(path.join(scratch, "node_modules/sky-wasm", f), "utf8");
  assert.ok(listed.includes("package/LICENSE-MIT") && listed.includes("package/LICENSE-APACHE"), listed.join(" "));
  const mit = await text("LICENSE-MIT");
  assert.match(mit, /^MIT License/);
  assert.match(mit, /Permission is hereby granted, free of charge/);
  const apache = await text("LICENSE-APACHE");
  assert.match(apache, /Apache License\s+Version 2\.0, January 2004/);
  assert.match(apache, /END OF TERMS AND CONDITIONS/);
  // The same texts as the repository's, which the Rust crates declare too.
  assert.equal(mit, await readFile(path.join(root, "LICENSE-MIT"), "utf8"));
  assert.equal(apache, await readFile(path.join(root, "LICENSE-APACHE"), "utf8"));
});

test("the package's README names the daylight sky and the day's daylight, and the HTTP server", async () => {
  const readme = await readFile(path.join(scratch, "node_modules/sky-wasm/README.md"), "utf8");
  assert.match(readme, /Sky\.daylight\(/);
  assert.match(readme, /DaylightDay\.at/);
  assert.match(readme, /HTTP/);
  assert.match(readme, /file:\/\/.*CORS/s);
  assert.match(readme, /esbuild/);
  assert.match(readme, /Vite/);
});

test("node: `await init()`, as in a page, then the daylight sky and a SkyMesh", () => {
  const script = `
    import { readFileSync } from "node:fs";
    import { createRequire } from "node:module";
    import init, { initSync, Sky, DaylightDay, daylightDefaultAod } from "sky-wasm";
    import { SkyMesh, fromSkyFrame } from "sky-wasm/three";
    const mode = process.argv[1];
    if (mode === "init") await init();
    else initSync({ module: readFileSync(createRequire(import.meta.url).resolve("sky-wasm/sky_wasm_bg.wasm")) });
    const aod = daylightDefaultAod();
    const sky = Sky.daylight(94 * Math.PI / 180, Math.PI, aod);
    const mesh = new SkyMesh({ model: "neural" });
    mesh.material.uniforms.sunPosition.value.copy(fromSkyFrame(Math.sin(0.7), 0, Math.cos(0.7)));
    mesh.update();
    const day = DaylightDay.at(2026, 6, 21, 36000, 39600, 1800, 48.21, 16.37, 190, aod);
    console.log(JSON.stringify({
      zenith: Array.from(sky.rgb(0, 0)),
      ground: Array.from(sky.rgb(2.5, 0)),
      uniform: Array.from(mesh.material.uniforms.sky_neural.value.slice(0, 8)),
      lux: Array.from(day.globalLux),
    }));`;
  const run = (mode) => JSON.parse(execFileSync("node", ["--input-type=module", "-e", script, mode], { cwd: scratch, encoding: "utf8" }));
  const viaInit = run("init");
  // The same module as initSync's (the "node" condition re-exports the bindings).
  assert.deepEqual(viaInit, run("initSync"));
  assert.ok(viaInit.zenith.every((c) => c > 0 && c < 1000), `blue hour's zenith, cd/m²: ${viaInit.zenith}`);
  assert.ok(viaInit.zenith[2] > viaInit.zenith[0], `a blue zenith: ${viaInit.zenith}`);
  assert.deepEqual(viaInit.ground, [0, 0, 0]);
  assert.ok(viaInit.uniform.some((c) => c !== 0), "the SkyMesh got its sky's parameters");
  assert.equal(viaInit.lux.length, 3);
  assert.ok(viaInit.lux.every((e) => e > 10_000), `Vienna's June morning, lux: ${viaInit.lux}`);
});

test("SkyMesh: a model it cannot draw is the same clear Error from the constructor and from .model", () => {
  const script = `
    import init from "sky-wasm";
    import { SkyMesh, MODELS } from "sky-wasm/three";
    await init();
    const out = {};
    for (const model of ["nope", "Preetham", ""]) {
      const seen = [];
      try { new SkyMesh({ model }); seen.push("constructed"); } catch (e) { seen.push(e.constructor.name + ": " + e.message); }
      const mesh = new SkyMesh();
      mesh.model = model;
      try { mesh.update(); seen.push("updated"); } catch (e) { seen.push(e.constructor.name + ": " + e.message); }
      mesh.onBeforeRender();
      seen.push(mesh.error);
      out[model] = seen;
    }
    console.log(JSON.stringify({ out, models: MODELS }));`;
  const { out, models } = JSON.parse(execFileSync("node", ["--input-type=module", "-e", script], { cwd: scratch, encoding: "utf8" }));
  for (const [model, [fromConstructor, fromUpdate, fromRender]] of Object.entries(out)) {
    const message = `model = "${model}" is not one of ${models.join(", ")}`;
    assert.equal(fromConstructor, `Error: ${message}`);
    assert.equal(fromUpdate, `Error: ${message}`);
    assert.equal(fromRender, message, "onBeforeRender keeps the message in .error");
  }
});

test("tsc (lib es2022 and esnext, strict) type-checks a program using the package's types", async () => {
  const dir = path.join(scratch, "ts");
  await mkdir(dir, { recursive: true });
  await writeFile(path.join(dir, "main.ts"), `
import * as THREE from "three";
import init, { Sky, DaylightDay, daylightDefaultAod, initSync } from "sky-wasm";
import * as shaders from "sky-wasm/shaders";
import { SkyMesh, skyEnvironment, skyLightProbe, MODELS, type SkyModel } from "sky-wasm/three";

await init();
const sky: Sky = Sky.daylight(1.6, Math.PI, daylightDefaultAod());
const zenith: Float32Array | number[] = sky.rgb(0, 0);
sky[Symbol.dispose]();
const day: DaylightDay = DaylightDay.at(2026, 6, 21, 0, 86399, 300, 48.21, 16.37, 190, 0.1);
const lux: Float32Array = day.globalLux;
const model: SkyModel = MODELS[1];
const mesh = new SkyMesh({ model, turbidity: 3, ev100: null });
mesh.material.uniforms.sunPosition.value.set(0.3, 0.5, -0.8);
const renderer = new THREE.WebGLRenderer();
const scene = new THREE.Scene();
scene.add(mesh);
scene.environment = skyEnvironment(renderer, mesh).texture;
scene.add(skyLightProbe(new THREE.Vector3(0, 1, 0), 3, 1));
const glsl: string = shaders.neural.glsl;
export { zenith, lux, glsl, initSync };
`);
  // Without three (whose 2.7 s of declarations main.ts checks once): esnext's own
  // Symbol.dispose beside the package's declaration, and a bundler's resolution.
  await writeFile(path.join(dir, "core.ts"), `
import init, { Sky } from "sky-wasm";
import * as shaders from "sky-wasm/shaders";
await init();
const sky: Sky = Sky.preetham(0.8, 0, 3);
sky[Symbol.dispose]();
export const wgsl: string = shaders.preetham.wgsl;
`);
  for (const [file, lib, module, resolution] of [["main.ts", "es2022,dom", "nodenext", "nodenext"], ["core.ts", "esnext,dom", "esnext", "bundler"]]) {
    try {
      execFileSync(bin("tsc"), ["--noEmit", "--strict", "--target", "es2022", "--lib", lib, "--module", module,
        "--moduleResolution", resolution, path.join(dir, file)],
      { cwd: scratch, encoding: "utf8", stdio: "pipe" });
    } catch (e) {
      assert.fail(`tsc --lib ${lib} --moduleResolution ${resolution} ${file}:\n${e.stdout}${e.stderr}`);
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

/** A page's module: `init` (the bundler's way), then a daylight SkyMesh (the README's snippet)
 * drawn by a level camera looking north, the sun 30° up behind it, its pixels above and below
 * the horizon, and the daylight sky on the CPU. */
const bundledPage = (initLines) => `import * as THREE from "three";
import { Sky, daylightDefaultAod } from "sky-wasm";
import { SkyMesh } from "sky-wasm/three";
${initLines}
const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById("c"), preserveDrawingBuffer: true });
renderer.toneMapping = THREE.ACESFilmicToneMapping;
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(60, 4 / 3, 0.1, 2000);
camera.lookAt(0, 0, -1);
const sky = new SkyMesh({ model: "daylight" });
sky.scale.setScalar(1000);
sky.material.uniforms.sunPosition.value.set(0.3, 0.5, 0.8);
scene.add(sky);
renderer.render(scene, camera);
const gl = renderer.getContext();
const pixel = (x, y) => {
  const p = new Uint8Array(4);
  gl.readPixels(x, y, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, p);
  return Array.from(p.subarray(0, 3));
};
const daylight = Sky.daylight(94 * Math.PI / 180, Math.PI, daylightDefaultAod());
document.body.dataset.result = JSON.stringify({
  sky: pixel(80, 100), ground: pixel(80, 20), error: sky.error, zenith: Array.from(daylight.rgb(0, 0)),
});
`;
const PAGE_HTML = `<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,">
<canvas id="c" width="160" height="120"></canvas>`;

test("browser: pages bundled by esbuild and by Vite from the package draw its sky, black below the horizon", async () => {
  // esbuild: the .wasm through the file loader (the package README's recipe).
  const esbuild = path.join(scratch, "esbuild");
  await mkdir(esbuild, { recursive: true });
  await writeFile(path.join(esbuild, "main.js"), bundledPage(`import init from "sky-wasm";
import wasmUrl from "sky-wasm/sky_wasm_bg.wasm";
await init({ module_or_path: wasmUrl });`));
  execFileSync(bin("esbuild"), ["main.js", "--bundle", "--format=esm", "--loader:.wasm=file", "--outdir=dist", "--log-level=warning"],
    { cwd: esbuild, stdio: "inherit" });
  await writeFile(path.join(esbuild, "dist/index.html"), `${PAGE_HTML}<script type="module" src="./main.js"></script>`);
  // Vite: `await init()` as in a page without a bundler; Vite emits the .wasm itself.
  const vite = path.join(scratch, "vite");
  await mkdir(vite, { recursive: true });
  await writeFile(path.join(vite, "main.js"), bundledPage(`import init from "sky-wasm";
await init();`));
  await writeFile(path.join(vite, "index.html"), `${PAGE_HTML}<script type="module" src="./main.js"></script>`);
  execFileSync(bin("vite"), ["build", "--logLevel", "warn"], { cwd: vite, stdio: "inherit" });
  const built = await readdir(path.join(vite, "dist/assets"));
  assert.ok(built.some((f) => f.endsWith(".wasm")), `Vite emitted the .wasm: ${built}`);

  const { browser, page, problems } = await launch(SWIFTSHADER);
  try {
    for (const [name, dist] of [["esbuild", path.join(esbuild, "dist")], ["vite", path.join(vite, "dist")]]) {
      const { server, url } = await serve(dist);
      try {
        await page.goto(url);
        await page.waitForSelector("body[data-result]", { timeout: 60_000 });
        const r = JSON.parse(await page.getAttribute("body", "data-result"));
        console.log(`  ${name} page: sky pixel (${r.sky}), ground pixel (${r.ground}), daylight zenith ${r.zenith.map((c) => c.toPrecision(3))} cd/m²`);
        assert.deepEqual(problems, [], `${name}: no console error, no failed request`);
        assert.equal(r.error, null);
        assert.ok(r.sky[2] > r.sky[0] && r.sky[2] > 40, `${name}: a blue sky above the horizon: ${r.sky}`);
        // Every sky is black below the horizon (sky-core's one rule; the neural sky once glowed
        // orange there).
        assert.deepEqual(r.ground, [0, 0, 0], `${name}: black below the horizon`);
        assert.ok(r.zenith.every((c) => c > 0) && r.zenith[2] > r.zenith[0], `${name}: blue hour's zenith ${r.zenith}`);
      } finally {
        server.close();
      }
    }
  } finally {
    await browser.close();
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
