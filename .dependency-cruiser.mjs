/**
 * The imports check of www/src (`npm test`'s imports-ts, `npx depcruise www/src`): no
 * import circle, type-only imports included (they are circles of meaning all the same),
 * and the layering ARCHITECTURE.md states. TypeScript's `./x.js` specifiers resolve to
 * `x.ts` through tsconfig.json.
 */
export default {
  forbidden: [
    {
      name: "no-circular",
      comment: "Imports run one way: a type lives in the file that owns it, and users import it from there.",
      severity: "error",
      from: {},
      to: { circular: true },
    },
    {
      name: "core-without-widget",
      comment: "The public core API (www/src/*.ts, internal/) knows nothing of the widget.",
      severity: "error",
      from: { path: "^www/src/(internal/|[^/]+\\.ts$)", pathNot: "^www/src/index\\.ts$" },
      to: { path: "^www/src/widget/" },
    },
    {
      name: "public-leaves",
      comment:
        "errors.ts and core-types.ts import nothing: internal/ uses them, and the public declarations that re-export them never reach wasm-bindgen's.",
      severity: "error",
      from: { path: "^www/src/(errors|core-types)\\.ts$" },
      to: {},
    },
    {
      name: "model-at-the-bottom",
      comment: "widget/model/ (what is posed) imports only the core and itself.",
      severity: "error",
      from: { path: "^www/src/widget/model/" },
      to: { path: "^www/src/widget/", pathNot: "^www/src/widget/model/" },
    },
    {
      name: "view-below-the-page",
      comment: "widget/view/ draws; it never imports the actions, the chrome, the input or the facade.",
      severity: "error",
      from: { path: "^www/src/widget/view/" },
      to: {
        path: "^www/src/widget/(actions|chrome|input|rigs|shapes|animation)/|^www/src/widget/(widget|element)\\.ts$",
      },
    },
    {
      name: "actions-below-chrome-and-input",
      comment: "The registry is read by the toolbar, the help and the input; it imports none of them.",
      severity: "error",
      from: { path: "^www/src/widget/actions/" },
      to: { path: "^www/src/widget/(chrome|input)/|^www/src/widget/(widget|element)\\.ts$" },
    },
  ],
  options: {
    doNotFollow: { path: "node_modules" },
    exclude: { path: "^www/pkg/" },
    tsPreCompilationDeps: true,
    tsConfig: { fileName: "tsconfig.json" },
  },
};
