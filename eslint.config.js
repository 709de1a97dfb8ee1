import js from "@eslint/js";
import tseslint from "typescript-eslint";

export default tseslint.config(
  { ignores: ["dist", "www/pkg", "www/lib", "target", "node_modules", "test-results", "playwright-report"] },
  js.configs.recommended,
  ...tseslint.configs.strict,
  {
    // The package check's consumer project: a page's scripts and its workers.
    files: ["tests/package/consumer/**/*.js"],
    languageOptions: { globals: { self: "readonly", Worker: "readonly", URL: "readonly" } },
  },
  {
    languageOptions: { globals: { window: "readonly", document: "readonly", console: "readonly" } },
    rules: {
      // With noUncheckedIndexedAccess, typed-array reads inside checked loops need `!`.
      "@typescript-eslint/no-non-null-assertion": "off",
    },
  },
);
