/**
 * The animation's exports, from frames drawn by the stage's own renderer (so an exported
 * frame is the picture the stage draws): a WebM video (`MediaRecorder` on a canvas stream
 * with one `requestFrame()` per frame: as many video frames as animation frames, at 1/fps
 * intervals), a PNG sprite sheet (the frames in rows, left to right) with its frame table,
 * animated GIF and APNG, the animation as JSON (mesh, keys, every frame's positions) and a
 * zip of one SVG per frame. Every export reports its progress, stops on its `signal`
 * (rejecting with an `AbortError`) and yields to the page between frames.
 */

/** The formats of {@link exportAnimation}. */
export type AnimationExportFormat = "webm" | "gif" | "apng" | "sprites" | "json" | "svg";
export const ANIMATION_FORMATS: readonly AnimationExportFormat[] = ["webm", "gif", "apng", "sprites", "json", "svg"];

export interface AnimationExportOptions {
  /** Hears `done` of `total` frames after each one. */
  onProgress?: (done: number, total: number) => void;
  /** Stops the export: the promise rejects with an `AbortError`. */
  signal?: AbortSignal;
}

/** A sprite sheet: the PNG and its frame table (JSON text). */
export interface SpriteSheet {
  png: Blob;
  table: string;
}

/** What the exports draw from. */
export interface FramePainter {
  readonly count: number;
  readonly fps: number;
  /** Draws frame `index` as the stage draws it and returns the canvas (the same canvas each call). */
  draw(index: number): HTMLCanvasElement;
}

/** The largest side of a canvas browsers make (Chromium's and Firefox's limit). */
export const MAX_CANVAS_SIDE = 16384;
/** The largest sprite sheet, in pixels (a quarter of Chromium's canvas area limit). */
export const MAX_SHEET_PIXELS = 1 << 26;

/** An `AbortError` as `fetch` and the encoders reject with. */
export function abortError(message = "the export was cancelled"): Error {
  const error = new Error(message);
  error.name = "AbortError";
  return error;
}

function checkSignal(signal: AbortSignal | undefined): void {
  if (signal?.aborted) throw abortError();
}

/** Lets the page draw and handle input (a Cancel click, say) between frames. */
const yieldToPage = (ms = 0) => new Promise<void>((resolve) => setTimeout(resolve, ms));

/** The WebM type MediaRecorder records here, best first; undefined where none is supported. */
export function webmType(): string | undefined {
  if (typeof MediaRecorder === "undefined") return undefined;
  return ["video/webm;codecs=vp9", "video/webm;codecs=vp8", "video/webm"].find((t) => MediaRecorder.isTypeSupported(t));
}

/**
 * Records the frames as a WebM video in real time (the recorder stamps frames by the
 * clock): one frame every 1/fps, the last one given again at the end so that it lasts
 * 1/fps too. Refused where MediaRecorder or WebM is missing (Node).
 * MediaRecorder writes no duration into the file's header; players find it by reading on.
 */
export async function recordWebm(painter: FramePainter, options: AnimationExportOptions = {}): Promise<Blob> {
  const type = webmType();
  if (type === undefined) {
    throw new Error(
      typeof MediaRecorder === "undefined"
        ? "WebM export needs MediaRecorder, which this environment lacks (browsers have it; Node does not)"
        : "this browser's MediaRecorder cannot record WebM video",
    );
  }
  const { onProgress, signal } = options;
  checkSignal(signal);
  const canvas = painter.draw(0);
  const stream = canvas.captureStream(0);
  const track = stream.getVideoTracks()[0] as CanvasCaptureMediaStreamTrack | undefined;
  if (!track) throw new Error("this browser cannot capture a canvas as video");
  const recorder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 8_000_000 });
  const chunks: Blob[] = [];
  recorder.addEventListener("dataavailable", (e) => {
    if (e.data.size > 0) chunks.push(e.data);
  });
  const stopped = new Promise<void>((resolve) => recorder.addEventListener("stop", () => resolve()));
  recorder.start();
  const interval = 1000 / painter.fps;
  const start = performance.now();
  try {
    for (let i = 0; i < painter.count; i++) {
      checkSignal(signal);
      if (i > 0) painter.draw(i);
      track.requestFrame();
      onProgress?.(i + 1, painter.count);
      // The next frame at its time (the last one held for a frame's time too).
      await yieldToPage(Math.max(0, start + (i + 1) * interval - performance.now()));
    }
    // The last frame again, so that it is shown for its 1/fps (a stream's last frame has no
    // length; a player seeking near the end would show the one before it).
    checkSignal(signal);
    painter.draw(painter.count - 1); // drawn again: a canvas not drawn on since gives no frame
    track.requestFrame();
    await yieldToPage(interval);
  } finally {
    recorder.stop();
    track.stop();
    await stopped;
  }
  checkSignal(signal);
  return new Blob(chunks, { type: "video/webm" });
}

/** Columns and rows of a sheet of `count` frames of `width` x `height`: near square, within the canvas limits. */
export function sheetLayout(count: number, width: number, height: number): { columns: number; rows: number } {
  let columns = Math.max(1, Math.min(count, Math.ceil(Math.sqrt((count * height) / width))));
  columns = Math.min(columns, Math.floor(MAX_CANVAS_SIDE / width));
  const rows = Math.ceil(count / Math.max(1, columns));
  if (columns < 1 || rows * height > MAX_CANVAS_SIDE || columns * rows * width * height > MAX_SHEET_PIXELS) {
    throw new Error(
      `a sprite sheet of ${count} frames of ${width} x ${height} pixels is too large for a canvas; ` +
        "make the widget smaller or the animation shorter (or lower its fps)",
    );
  }
  return { columns, rows };
}

/**
 * The frames on one PNG, in rows of `columns` left to right, each at its canvas size;
 * `table` writes the frame table for the layout.
 */
export async function spriteSheet(
  painter: FramePainter,
  table: (layout: {
    frameWidth: number;
    frameHeight: number;
    columns: number;
    frameCount: number;
    fps: number;
  }) => string,
  options: AnimationExportOptions = {},
): Promise<SpriteSheet> {
  const { onProgress, signal } = options;
  const first = painter.draw(0);
  const [width, height] = [first.width, first.height];
  const { columns, rows } = sheetLayout(painter.count, width, height);
  const sheet = first.ownerDocument.createElement("canvas");
  sheet.width = columns * width;
  sheet.height = rows * height;
  const ctx = sheet.getContext("2d");
  if (!ctx) throw new Error("this browser cannot draw on a 2D canvas");
  for (let i = 0; i < painter.count; i++) {
    checkSignal(signal);
    ctx.drawImage(painter.draw(i), (i % columns) * width, Math.floor(i / columns) * height);
    onProgress?.(i + 1, painter.count);
    await yieldToPage();
  }
  checkSignal(signal);
  const png = await new Promise<Blob>((resolve, reject) =>
    sheet.toBlob((b) => (b ? resolve(b) : reject(new Error("the sprite sheet could not be encoded"))), "image/png"),
  );
  return {
    png,
    table: table({ frameWidth: width, frameHeight: height, columns, frameCount: painter.count, fps: painter.fps }),
  };
}

/** A frame as RGBA pixels, for the GIF and APNG encoders (`delayMs` whole milliseconds). */
export interface RgbaFrame {
  rgba: Uint8ClampedArray;
  width: number;
  height: number;
  delayMs: number;
}

/** The frames' pixels one at a time (read as they are asked for), yielding to the page between them. */
export async function* rgbaFrames(painter: FramePainter, signal?: AbortSignal): AsyncGenerator<RgbaFrame> {
  for (let i = 0; i < painter.count; i++) {
    checkSignal(signal);
    const canvas = painter.draw(i);
    const ctx = canvas.getContext("2d");
    if (!ctx) throw new Error("this browser cannot read a 2D canvas");
    const { data, width, height } = ctx.getImageData(0, 0, canvas.width, canvas.height);
    // Whole milliseconds, rounded on the running total so that the frames keep the animation's length.
    const delayMs = Math.round((1000 * (i + 1)) / painter.fps) - Math.round((1000 * i) / painter.fps);
    yield { rgba: data, width, height, delayMs };
    await yieldToPage();
  }
}
