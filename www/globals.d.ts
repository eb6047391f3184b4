// The hooks the demo's pages leave on `window` for the end-to-end tests, scripts/bench-browser.mjs
// and the console (main.js, bench.js, toy.js). Their shapes are what those files assign.
interface Window {
  lanepfDemo?: unknown;
  lanepfBench?: unknown;
  toyLesson?: unknown;
}
