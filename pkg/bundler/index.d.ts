// `lanepf/bundler`: every class, function and type of `lanepf`, with the module already
// instantiated on import (no `init()`).
export * from '../web/lanepf.js';
