// `lanepf/bundler`: the package for bundlers (Vite, webpack 5, Rollup, esbuild), initialised
// on import. It is the `web` build (one wasm file for both entries) started with a top-level
// `await init()`: `init()` fetches `lanepf_bg.wasm` by `new URL('lanepf_bg.wasm',
// import.meta.url)`, a pattern Vite and webpack 5 turn into an emitted asset with no plugin and
// no configuration. Import the classes and call them; there is no `init()` to call.
//
// The `await init()` is a side effect, so package.json lists this file under `sideEffects`:
// a bundler may then never skip it for the re-exported bindings of ../web/lanepf.js.
import init from '../web/lanepf.js';

export * from '../web/lanepf.js';

await init();
