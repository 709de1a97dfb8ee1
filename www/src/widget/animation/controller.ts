/**
 * The widget's animation, page side: the {@link Animator} with the timeline strip (when the
 * `timeline` option shows it), capture and play or pause (which the K key and a tap of
 * Space run through the registry's actions), and the exports, which draw
 * each frame with the stage's renderer ({@link Stage.picture}) and put the pose back after.
 * An export from the strip shows the busy indicator's progress bar with Cancel and
 * downloads the file; while an export runs the shape takes no input and nothing is recorded.
 */
import { animationToJson, encodeAnimation, spriteSheetTable, zipFiles } from "../../animation-files.js";
import {
  abortError,
  recordWebm,
  rgbaFrames,
  spriteSheet,
  type AnimationExportOptions,
  type AnimationExportFormat,
  type FramePainter,
  type SpriteSheet,
} from "./formats.js";
import { Animator } from "./playback.js";
import { download, posedSvg } from "../store/pose-export.js";
import type { WidgetSettings } from "../options.js";
import type { SavedAnimation } from "../store/work-store.js";
import type { Posing } from "../model/posing.js";
import type { Stage } from "../view/stage.js";
import { messageOf } from "../view/status-line.js";
import { checkFps, frameAt } from "./timeline.js";
import { TimelineStrip } from "./timeline-strip.js";
import { unpainted } from "../model/stiffness.js";

/** What the animation needs of the widget. */
export interface AnimationControllerHost {
  readonly posing: Posing;
  readonly stage: Stage;
  readonly settings: WidgetSettings;
  readonly document: Document;
  /** The pose changed outside the frame loop: draw and report it. */
  poseChanged(): void;
  emit(type: string, detail: unknown): void;
  showError(error: unknown): void;
  /** The work changed (the keeper saves it soon). */
  keep(): void;
}

/** An export's result: a file, or a sprite sheet's PNG and table. */
export type AnimationExport = Blob | SpriteSheet;

const FILE_NAMES: Record<AnimationExportFormat, string> = {
  webm: "animation.webm",
  gif: "animation.gif",
  apng: "animation.png",
  sprites: "sprites.png",
  json: "animation.json",
  svg: "animation-svg.zip",
};

export class AnimationController {
  readonly animator: Animator;
  readonly strip: TimelineStrip | undefined;
  readonly #host: AnimationControllerHost;
  #exporting: AbortController | undefined;
  /** The pose before a scrub of the strip's playhead. */
  #scrubbing = false;

  constructor(host: AnimationControllerHost) {
    this.#host = host;
    this.animator = new Animator({
      get posing() {
        return host.posing;
      },
      fps: () => host.settings.fps,
      shown: (index) => {
        host.poseChanged();
        host.emit("akap-frame", { index, time: index / host.settings.fps });
      },
      changed: () => {
        this.refresh();
        host.keep();
      },
      info: (message) => host.stage.status.info(message),
    });
    if (host.settings.timeline) {
      const guard =
        <A extends unknown[]>(action: (...args: A) => unknown) =>
        (...args: A): void => {
          try {
            const result = action(...args);
            if (result instanceof Promise) result.catch((error: unknown) => this.#failed(error));
            else host.stage.status.succeeded();
          } catch (error) {
            this.#failed(error);
          }
        };
      const a = this.animator;
      this.strip = new TimelineStrip(host.document, {
        capture: guard(() => this.capture()),
        playPause: guard(() => this.playPause()),
        loop: guard((on: boolean) => {
          a.loop = on;
          this.refresh();
        }),
        deleteKey: guard((index: number) => a.deleteKey(index)),
        easing: guard((index: number, easing) => a.setEasing(index, easing)),
        select: guard((index: number | undefined) => {
          a.selected = index;
          this.refresh();
        }),
        moveKey: guard((index: number, time: number) => a.moveKey(index, time)),
        scrub: guard((time: number, phase: "start" | "move" | "end") => this.scrub(time, phase)),
        fps: guard((fps: number) => this.setFps(fps)),
        export: guard((format: AnimationExportFormat) => this.exportToFile(format)),
      });
    }
    this.refresh();
  }

  /** The strip shows the animation's state again. */
  refresh(): void {
    const a = this.animator;
    this.strip?.show({
      keys: a.timeline.keys,
      selected: a.selected,
      time: a.time,
      frame: a.playhead,
      frameCount: a.frameCount,
      fps: this.#host.settings.fps,
      playing: a.playing,
      loop: a.loop,
    });
  }

  /** Captures a key (see `Widget.captureKey`). */
  capture(time?: number, easing?: "linear" | "ease"): number {
    const index = this.animator.capture(time, easing);
    this.#host.stage.status.succeeded();
    return index;
  }

  /** Plays, or pauses playback under way; a refusal shows as an error. */
  playPause(): void {
    const a = this.animator;
    if (a.playing) a.pause();
    else
      a.play().catch((error: unknown) => {
        this.#failed(error);
      });
  }

  /** The strip's playhead dragged: each frame shown; press to release is one undoable step. */
  scrub(time: number, phase: "start" | "move" | "end"): void {
    const a = this.animator;
    const posing = this.#host.posing;
    if (phase === "start") {
      a.pause();
      if (a.frameCount > 0) {
        posing.beginGesture();
        posing.markChanged();
        this.#scrubbing = true;
      }
    }
    const index = frameAt(time, this.#host.settings.fps);
    if (this.#scrubbing) {
      if (index !== a.playhead || phase === "start") a.show(index);
    } else {
      a.playhead = index;
      this.refresh();
    }
    if (phase === "end" && this.#scrubbing) {
      this.#scrubbing = false;
      posing.endDragGesture();
    }
  }

  /** Another frame rate: the playhead keeps its time; frames are computed again. */
  setFps(fps: number): void {
    checkFps(fps);
    const time = this.animator.time;
    this.animator.pause();
    this.#host.settings.fps = fps;
    this.animator.playhead = frameAt(time, fps);
    this.refresh();
  }

  /**
   * The animation in `format` (see `Widget.exportAnimation`): each frame shown and drawn
   * by the stage's renderer, the pose put back after.
   */
  async export(format: AnimationExportFormat, options: AnimationExportOptions = {}): Promise<AnimationExport> {
    if (this.#exporting) throw new Error("an animation export is running already; wait for it or cancel it");
    const a = this.animator;
    // Every frame computed first: a video's frames then come at an even pace.
    const count = a.frames().all().length;
    a.pause();
    const { posing, stage, settings, document } = this.#host;
    const controller = new AbortController();
    const signal = options.signal ? AbortSignal.any([options.signal, controller.signal]) : controller.signal;
    if (signal.aborted) throw abortError();
    this.#exporting = controller;
    const before = posing.snapshot();
    // Meanwhile the shape takes no input, the frame loop rests and nothing is recorded.
    posing.releasePointers();
    posing.replaying = true;
    const playhead = a.playhead;
    const canvas = document.createElement("canvas");
    const painter: FramePainter = {
      count,
      fps: settings.fps,
      draw: (index) => {
        a.show(index);
        return stage.picture(posing, settings, canvas);
      },
    };
    const opts = { ...options, signal };
    try {
      switch (format) {
        case "webm":
          return await recordWebm(painter, opts);
        case "gif":
        case "apng": {
          // The frames come one at a time (the encoder cannot know their count): the total is ours.
          const onProgress = (done: number) => options.onProgress?.(done, count);
          const bytes = await encodeAnimation(format, rgbaFrames(painter, signal), { signal, onProgress });
          return new Blob([bytes as Uint8Array<ArrayBuffer>], { type: format === "gif" ? "image/gif" : "image/apng" });
        }
        case "sprites":
          return await spriteSheet(painter, spriteSheetTable, opts);
        case "json":
          return new Blob([this.#json()], { type: "application/json" });
        case "svg":
          return this.#svgZip(opts);
        default:
          throw new RangeError(
            `unknown animation format "${String(format)}"; the formats are webm, gif, apng, sprites, json, svg`,
          );
      }
    } finally {
      this.#exporting = undefined;
      posing.replaying = false;
      posing.restore(before);
      a.playhead = playhead;
      this.refresh();
    }
  }

  /** The animation to keep with the work (undefined without keys). */
  saved(): SavedAnimation | undefined {
    // (Counting the frames forgets keys of a shape no longer posed.)
    if (this.animator.frameCount === 0) return undefined;
    const { keys, handles } = this.animator.timeline;
    if (!handles || keys.length === 0) return undefined;
    return {
      fps: this.#host.settings.fps,
      handles: { triangles: [...handles.triangles], barycentric: [...handles.barycentric] },
      keys: keys.map((k) => ({ time: k.time, easing: k.easing, targets: k.targets, pose: k.pose })),
    };
  }

  /** An animation kept with the work put back (see {@link Animator.restoreKeys}); throws, changing nothing, if it does not fit. */
  restore(saved: SavedAnimation): void {
    checkFps(saved.fps);
    this.animator.restoreKeys(saved);
    this.#host.settings.fps = saved.fps;
    this.refresh();
  }

  /** Stops the export under way (its promise rejects with an `AbortError`). */
  cancelExport(): void {
    this.#exporting?.abort();
  }

  get exporting(): boolean {
    return this.#exporting !== undefined;
  }

  /** An export from the strip: progress with Cancel, then the download. */
  async exportToFile(format: AnimationExportFormat): Promise<void> {
    const { stage, document } = this.#host;
    const label = `Exporting the animation (${format})`;
    const cancel = () => this.cancelExport();
    stage.busy.update({ label, progress: 0, cancel });
    try {
      const result = await this.export(format, {
        onProgress: (done, total) => stage.busy.update({ label, progress: done / total, cancel }),
      });
      if (result instanceof Blob) download(document, result, FILE_NAMES[format]);
      else {
        download(document, result.png, FILE_NAMES.sprites);
        download(document, result.table, "sprites.json", "application/json");
      }
      stage.status.succeeded();
    } catch (error) {
      if ((error as Error | undefined)?.name === "AbortError")
        stage.status.info("Export cancelled; nothing was saved.");
      else throw error;
    } finally {
      stage.busy.done();
    }
  }

  destroy(): void {
    this.cancelExport();
    this.animator.destroy();
  }

  #json(): string {
    const a = this.animator;
    const { shape, stiffness } = this.#host.posing;
    const mesh = shape.mesh;
    const painted = unpainted(stiffness) ? undefined : stiffness;
    return animationToJson({
      mesh: { positions: mesh.positions, triangles: mesh.triangles, stiffness: painted },
      fps: this.#host.settings.fps,
      keys: a.timeline.keys.map((k) => ({ time: k.time, easing: k.easing, handles: k.targets })),
      frames: a
        .frames()
        .all()
        .map((f) => f.positions),
    });
  }

  async #svgZip(options: AnimationExportOptions): Promise<Blob> {
    const { posing, stage } = this.#host;
    const frames = this.animator.frames();
    const encoder = new TextEncoder();
    const files: { name: string; data: Uint8Array }[] = [];
    const digits = String(frames.count - 1).length;
    for (let i = 0; i < frames.count; i++) {
      if (options.signal?.aborted) throw abortError();
      this.animator.show(i);
      const svg = posedSvg(posing.shape.mesh, posing.shape.vector, frames.frame(i).positions, stage.layering(posing));
      files.push({ name: `frame-${String(i).padStart(digits, "0")}.svg`, data: encoder.encode(svg) });
      options.onProgress?.(i + 1, frames.count);
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
    return new Blob([zipFiles(files) as Uint8Array<ArrayBuffer>], { type: "application/zip" });
  }

  #failed(error: unknown): void {
    this.#host.showError(new Error(messageOf(error)));
  }
}
