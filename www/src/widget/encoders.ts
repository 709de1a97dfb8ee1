/**
 * The Rust encoders the animation exports use (GIF, APNG, zip, the JSON animation and the
 * sprite sheet's table), in one place. NOT YET WIRED: they come from the `animrust` branch
 * (`www/src/animation.ts`); until it is merged these formats are refused.
 */
/* eslint-disable @typescript-eslint/no-unused-vars -- the signatures of the functions to come */
const missing = (what: string) => new Error(`${what} is not in this build yet (the Rust encoders are not merged)`);

export function encodeAnimation(
  format: "gif" | "apng",
  _frames: AsyncIterable<{ rgba: Uint8ClampedArray; width: number; height: number; delayMs: number }>,
  _options: { onProgress?: (done: number, total: number) => void; signal?: AbortSignal },
): Promise<Uint8Array> {
  return Promise.reject(missing(`${format.toUpperCase()} export`));
}

export function zipFiles(_files: { name: string; data: Uint8Array }[]): Uint8Array {
  throw missing("the zip of SVG frames");
}

export function animationToJson(_animation: unknown): string {
  throw missing("the JSON animation");
}

export function spriteSheetTable(_layout: unknown): string {
  throw missing("the sprite sheet's table");
}
