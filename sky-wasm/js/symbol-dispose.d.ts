
// Appended by scripts/wasm.sh pack. The classes above have `[Symbol.dispose]()` (for `using`),
// which TypeScript's lib declares from esnext.disposable on: with an older "lib" (es2022, say)
// the property would fail to type-check (TS2550). Its declaration, as lib.esnext.disposable
// and @types/node have it (identical declarations merge, so newer libs accept it too):
declare global {
  interface SymbolConstructor {
    readonly dispose: unique symbol;
  }
}
