// sky-wasm in node (the package's "node" export condition): sky_wasm.js as it is, with an
// `init()` that works there too. The bindings' `init()` fetches `new URL("sky_wasm_bg.wasm",
// import.meta.url)`, and node's fetch cannot load a file: URL ("TypeError: fetch failed"):
// called without a module, this `init` reads the .wasm beside this file and instantiates
// that. Everything else, `initSync` included, is sky_wasm.js's own export (one instance of
// the module, shared with sky-wasm/three).
import { readFile } from "node:fs/promises";
import bindingsInit from "./sky_wasm.js";

export * from "./sky_wasm.js";

/** sky_wasm.js's `init`; without an argument, the package's own .wasm read from disk. */
export default async function init(moduleOrPath) {
  if (moduleOrPath === undefined) {
    moduleOrPath = { module_or_path: await readFile(new URL("./sky_wasm_bg.wasm", import.meta.url)) };
  }
  return bindingsInit(moduleOrPath);
}
