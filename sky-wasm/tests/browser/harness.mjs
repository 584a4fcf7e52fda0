// What the browser tests share: a static file server on the loopback and Debian's Chromium
// through playwright-core (which never downloads a browser), with the page's console errors,
// page errors and failed requests collected.
import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import path from "node:path";
import { chromium } from "playwright-core";

const TYPES = {
  ".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript", ".css": "text/css",
  ".wasm": "application/wasm", ".ts": "text/plain", ".json": "application/json", ".png": "image/png",
};

/** Chromium's flags for every test (shared/DESIGN.md). */
export const BASE_ARGS = ["--no-sandbox", "--disable-background-networking",
  "--disable-component-update", "--disable-sync", "--no-first-run"];
/** Without a GPU: the 2-D canvas demo. */
export const NO_GPU = [...BASE_ARGS, "--disable-gpu"];
/** WebGL2 through ANGLE on SwiftShader (CPU Vulkan), and WebGPU on SwiftShader's Vulkan. */
export const SWIFTSHADER = [...BASE_ARGS, "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
  "--enable-unsafe-webgpu", "--enable-features=Vulkan", "--use-vulkan=swiftshader",
  "--use-webgpu-adapter=swiftshader"];

/** Serves the folder `root` on 127.0.0.1 (a free port); `pages` maps paths to inline HTML. */
export async function serve(folder, pages = {}) {
  const root = path.resolve(folder);
  const server = createServer(async (req, res) => {
    const rel = decodeURIComponent(new URL(req.url, "http://localhost").pathname);
    if (pages[rel]) return res.writeHead(200, { "content-type": "text/html" }).end(pages[rel]);
    const file = path.join(root, rel.endsWith("/") ? rel + "index.html" : rel);
    if (!file.startsWith(root)) return res.writeHead(403).end();
    try {
      const body = await readFile(file);
      res.writeHead(200, { "content-type": TYPES[path.extname(file)] ?? "application/octet-stream" }).end(body);
    } catch {
      res.writeHead(404).end();
    }
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  return { server, url: `http://127.0.0.1:${server.address().port}/` };
}

/** Debian's Chromium with `args`, and a page whose problems land in the returned array. */
export async function launch(args, viewport = { width: 1200, height: 900 }) {
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium", args });
  const page = await browser.newPage({ viewport });
  const problems = [];
  page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()}`));
  page.on("response", (r) => { if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`); });
  return { browser, page, problems };
}
