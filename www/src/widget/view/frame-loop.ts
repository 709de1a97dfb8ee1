/**
 * The widget's frame loop: an animation frame is asked for only while something moves or
 * is to be drawn; each frame the posing advances (its steps toward the handles' targets),
 * the distortion, field and a rig's comparison follow, the picture is drawn, the HUD and
 * the `akap-pose` event report the frame; the loop settles once nothing is dragged and
 * the pins have come to rest (or after {@link SETTLE_FRAMES} frames without input).
 * Frames of a rig on the GPU leave the pose on the CPU behind: their distortion is
 * measured when the loop settles (the HUD and the events show the last measured until then).
 */
import type { Metrics, Timings } from "../../core.js";
import type { PoseDetail, WidgetSettings } from "../options.js";
import type { Posing } from "../model/posing.js";
import type { Stage } from "./stage.js";
import { messageOf } from "./status-line.js";

/** Frames without input after which the loop stops even if pins have not settled. */
export const SETTLE_FRAMES = 240;

/** What the loop needs of the widget. */
export interface FrameHost {
  readonly posing: Posing;
  readonly stage: Stage;
  readonly settings: WidgetSettings;
  /** The widget's element in the shadow root: `data-idle` says when the loop has settled. */
  readonly root: HTMLElement;
  destroyed(): boolean;
  /** Draws the picture now. */
  render(): void;
  showError(error: unknown): void;
  /** A rig posed the frame (its comparison with the ground truth is out of date). */
  rigPosed(): void;
  /** Dispatches an event on the widget's element. */
  emit(type: string, detail: unknown): void;
}

const noTimings = (): Timings => ({
  assembly: 0,
  factorisation: 0,
  dirichletFactorisation: 0,
  solve: 0,
  integration: 0,
});

export class FrameLoop {
  /** The distortion of the pose on screen. */
  metrics: Metrics = { areaDistortion: 2, angleDistortion: 2, flipped: 0 };
  /** The last step's field, while the field is shown. */
  lastField: Float64Array | undefined;
  readonly #host: FrameHost;
  #raf = 0;
  #idleFrames = 0;
  #idleWaiters: (() => void)[] = [];
  /** A rig's frame on the GPU moved the pose since {@link metrics} were measured. */
  #metricsBehind = false;

  constructor(host: FrameHost) {
    this.#host = host;
  }

  /** Asks for a frame (once, however often asked). */
  schedule(): void {
    if (this.#raf === 0 && !this.#host.destroyed()) {
      this.#raf = requestAnimationFrame((time) => this.#frame(time));
      delete this.#host.root.dataset.idle;
    }
  }

  /** A handle moved: frames are wanted, and the loop must not settle yet. */
  moved(): void {
    this.#idleFrames = 0;
    this.schedule();
  }

  /** Resolves when no frame is pending (the pose has settled and nothing is dragged). */
  whenIdle(): Promise<void> {
    if (this.#raf === 0 && !this.#host.posing.replaying) return Promise.resolve();
    return new Promise((resolve) => this.#idleWaiters.push(resolve));
  }

  /** No more frames (the widget is going away); whoever waits for idle is let go. */
  stop(): void {
    if (this.#raf) cancelAnimationFrame(this.#raf);
    this.#raf = 0;
    for (const resolve of this.#idleWaiters.splice(0)) resolve();
  }

  /** The pose changed outside the loop: distortion, field, HUD, event. */
  poseChanged(): void {
    const { posing, settings, stage } = this.#host;
    this.metrics = posing.deformer.metrics();
    if (settings.field) this.lastField = posing.deformer.field();
    stage.hud.showMetrics(this.metrics);
    this.schedule();
    this.emitPose();
  }

  /** The `akap-pose` event for the pose on screen (with the frame's figures, if a frame moved it). */
  emitPose(frameMs = 0, steps = 0, timings = noTimings(), evaluationMs?: number, clamped = false): void {
    const detail: PoseDetail = {
      clamped,
      metrics: { ...this.metrics },
      handleCount: this.#host.posing.handles.length,
      frameMs,
      steps,
      timings,
      ...(evaluationMs === undefined ? {} : { evaluationMs }),
    };
    this.#host.emit("akap-pose", detail);
  }

  #frame(time: number): void {
    this.#raf = 0;
    const { posing, stage, settings } = this.#host;
    if (this.#host.destroyed() || posing.replaying) return;
    const started = performance.now();
    const timings = noTimings();
    let substeps = 0;
    try {
      substeps = posing.advance(timings);
      if (substeps > 0) stage.status.succeeded();
    } catch (error) {
      // The deformer is unchanged; pins stay where they are, dragged handles keep their
      // targets and are tried again next frame, in smaller steps (the core's advance).
      this.#host.showError(new Error(`${messageOf(error)}. Try a smaller move, or Undo (Ctrl+Z) or Reset.`));
    }
    const dragging = posing.dragging;
    this.#idleFrames = substeps > 0 && dragging ? 0 : this.#idleFrames + 1;
    if (substeps > 0) {
      posing.markChanged();
      // Measuring would evaluate a rig on the GPU on the CPU: done when the loop settles.
      this.#metricsBehind = posing.deformer.poseStale;
      if (!this.#metricsBehind) this.metrics = posing.deformer.metrics();
      if (settings.field) this.lastField = posing.deformer.field();
      if (settings.compare && posing.posingWithRig) this.#host.rigPosed();
    }
    this.#host.render();
    stage.keepHudClear(posing);
    if (substeps > 0) {
      const work = performance.now() - started;
      const evaluationMs = posing.evaluationMs > 0 ? posing.evaluationMs : undefined;
      const clamped = posing.clamped;
      stage.hud.report({ time, work, timings, substeps, metrics: this.metrics, evaluationMs, clamped });
      this.emitPose(work, substeps, timings, evaluationMs, clamped);
    }
    if (dragging || (substeps > 0 && this.#idleFrames < SETTLE_FRAMES)) {
      this.schedule();
    } else {
      if (this.#metricsBehind) {
        this.#metricsBehind = false;
        this.metrics = posing.deformer.metrics();
        stage.hud.showMetrics(this.metrics);
        this.emitPose();
      }
      this.#host.root.dataset.idle = "true";
      for (const resolve of this.#idleWaiters.splice(0)) resolve();
    }
  }
}
