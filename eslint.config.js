// ESLint (flat config) for the project's JavaScript: the demo (www/), the package's hand-written
// entries (pkg/worker, pkg/frames, pkg/bundler; pkg/web is generated), the scripts and the
// tests. `make lint` runs it. ESLint's recommended rules, and a few more that catch mistakes
// rather than style.
import js from '@eslint/js';
import globals from 'globals';

export default [
  { ignores: ['pkg/web/**', 'node_modules/**', 'target/**', 'test-results/**'] },
  js.configs.recommended,
  {
    languageOptions: { ecmaVersion: 2024, sourceType: 'module' },
    linterOptions: { reportUnusedDisableDirectives: 'error' },
    rules: {
      eqeqeq: ['error', 'always', { null: 'ignore' }],
      // `_`: a value left out on purpose (`const { baseline_m: _, ...rest } = camera`).
      'no-unused-vars': ['error', { argsIgnorePattern: '^_', varsIgnorePattern: '^_$', caughtErrorsIgnorePattern: '^_' }],
      'no-var': 'error',
      'prefer-const': ['error', { destructuring: 'all' }],
      'no-self-compare': 'error',
      'no-template-curly-in-string': 'error',
      'no-unreachable-loop': 'error',
      'array-callback-return': 'error',
      'no-implicit-globals': 'error',
      'no-shadow-restricted-names': 'error',
    },
  },
  // Pages and the package's page-side entries run in the browser.
  {
    files: ['www/**/*.js', 'pkg/bundler/**/*.js', 'pkg/frames/**/*.js', 'pkg/worker/index.js'],
    languageOptions: { globals: globals.browser },
  },
  // Workers: no DOM.
  {
    files: ['www/worker.js', 'www/bench-worker.js', 'pkg/worker/worker.js', 'pkg/worker/serve.js'],
    languageOptions: { globals: globals.worker },
  },
  // Node scripts and tests; the tests and scripts that drive a browser also hand it functions
  // to run in the page (`page.evaluate(() => document...)`), hence the browser's globals too.
  {
    files: ['scripts/**/*.mjs', 'tests/**/*.mjs', 'eslint.config.js'],
    languageOptions: { globals: { ...globals.node, ...globals.browser } },
  },
  // The npm package's test apps (built by Vite and webpack, run in a page or a worker).
  {
    files: ['tests/npm/fixtures/**/*.js'],
    languageOptions: { globals: { ...globals.browser, ...globals.worker } },
  },
];
