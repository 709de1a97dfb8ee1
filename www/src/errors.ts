/**
 * The codes of the `Error`s akap throws, and how to tell one. A leaf (it imports nothing):
 * the core, its internal helpers and the widget all use it; public through `core.ts`.
 */

/**
 * The `code` of the `Error`s akap throws for bad input or a failed step: a small, closed
 * set that stays the same from version to version (messages may be reworded), in the
 * order of the table in docs/errors.md. Defined in Rust (`akap::ErrorCode`); `errorCodes()` of the
 * WebAssembly module lists the same, which the tests compare.
 */
export const ERROR_CODES = [
  "invalid-argument",
  "invalid-option",
  "invalid-outline",
  "invalid-mesh",
  "invalid-joint",
  "limit",
  "import",
  "not-positive-definite",
  "overflow",
  "no-convergence",
  "out-of-memory",
  "internal",
] as const;

/** One of {@link ERROR_CODES}. */
export type ErrorCode = (typeof ERROR_CODES)[number];

/** An `Error` thrown by akap, with its {@link ErrorCode} to switch on. */
export interface AkapError extends Error {
  code: ErrorCode;
}

/**
 * Whether `error` is an `Error` thrown by akap with a code: a refused argument, option,
 * outline, mesh or file, a limit, a failed step. (Using a freed object, calling before
 * `init` finished and a stopped instance throw `Error`s without a code.)
 */
export function isAkapError(error: unknown): error is AkapError {
  const code = (error as { code?: unknown } | null)?.code;
  return error instanceof Error && (ERROR_CODES as readonly unknown[]).includes(code);
}
