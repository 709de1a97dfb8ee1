/**
 * The heads-up display: frames per second, milliseconds per stage, mesh size, live
 * distortion and a sparkline of recent frame times (the 16.7 ms line marks 60 fps); with a
 * trained rig, its evaluation time and rate, and a line on the rig's state.
 */
import type { Metrics, Timings } from "../../core.js";

export interface FrameReport {
  /** When the frame ran (performance.now()). */
  time: number;
  /** Milliseconds of solver work and drawing in this frame. */
  work: number;
  /** Solver stages summed over the frame's substeps. */
  timings: Timings;
  substeps: number;
  metrics: Metrics;
  /** Milliseconds of a trained rig's evaluation, when the frame was posed by one. */
  evaluationMs?: number;
  /** A step stopped short to keep triangles from folding over. */
  clamped?: boolean;
}

const SPARK_FRAMES = 120;

function metricsLine(m: Metrics): string {
  return `E_area ${m.areaDistortion.toFixed(4)}  E_angle ${m.angleDistortion.toFixed(4)}  flipped ${m.flipped}`;
}

export class Hud {
  readonly element: HTMLElement;
  readonly #text: HTMLElement;
  readonly #spark: HTMLCanvasElement;
  readonly #works: number[] = [];
  readonly #times: number[] = [];
  #lastText = 0;

  constructor(document: Document) {
    this.element = document.createElement("div");
    this.element.className = "hud";
    this.element.setAttribute("aria-label", "Performance and distortion");
    this.#text = document.createElement("pre");
    this.#spark = document.createElement("canvas");
    this.#spark.width = SPARK_FRAMES * 2;
    this.#spark.height = 48;
    this.#spark.setAttribute("aria-hidden", "true");
    this.element.append(this.#text, this.#spark);
  }

  /** Shows the mesh, the method and the pose's distortion (before any frame ran). */
  showMesh(vertices: number, triangles: number, method: string, metrics: Metrics): void {
    this.#vertices = vertices;
    this.#triangles = triangles;
    this.#method = method;
    this.#works.length = 0;
    this.#times.length = 0;
    this.#last = undefined;
    this.showMetrics(metrics);
    this.#drawSpark();
  }

  /** Shows the distortion of a pose reached outside the frame loop (undo, reset, a load). */
  showMetrics(metrics: Metrics): void {
    this.#metrics = metrics;
    clearTimeout(this.#trailing);
    this.#trailing = undefined;
    this.#last = this.#last === undefined ? undefined : { ...this.#last, metrics };
    this.#text.textContent = this.#last
      ? this.#lines(this.#last)
      : [
          this.#method,
          `${this.#vertices} vertices, ${this.#triangles} triangles`,
          metricsLine(metrics),
          ...(this.#rig ? [this.#rig] : []),
          "click the shape to add a handle",
        ].join("\n");
  }

  /** A line on the trained rig (its state, a comparison), or none. */
  showRig(line: string | undefined): void {
    if (line === this.#rig) return;
    this.#rig = line;
    if (this.#last) this.#text.textContent = this.#lines(this.#last);
    else this.showMetrics(this.#metrics);
  }

  /** The method's name (after a switch). */
  showMethod(method: string): void {
    this.#method = method;
    this.#text.textContent = this.#last ? this.#lines(this.#last) : this.#text.textContent;
  }

  #vertices = 0;
  #triangles = 0;
  #method = "";
  #rig: string | undefined;
  #metrics: Metrics = { areaDistortion: 0, angleDistortion: 0, flipped: 0 };
  #last: FrameReport | undefined;
  #trailing: ReturnType<typeof setTimeout> | undefined;

  /**
   * Adds a frame. The text refreshes at most four times a second, and always shows the
   * last frame's figures once frames stop.
   */
  report(frame: FrameReport): void {
    this.#works.push(frame.work);
    if (this.#works.length > SPARK_FRAMES) this.#works.shift();
    this.#times.push(frame.time);
    while (this.#times.length > 0 && this.#times[0]! < frame.time - 1000) this.#times.shift();
    this.#drawSpark();
    this.#last = frame;
    const wait = 250 - (frame.time - this.#lastText);
    if (wait > 0) {
      this.#trailing ??= setTimeout(() => {
        this.#trailing = undefined;
        if (this.#last) this.#write(this.#last);
      }, wait);
      return;
    }
    this.#write(frame);
  }

  #write(frame: FrameReport): void {
    this.#lastText = frame.time;
    this.#text.textContent = this.#lines(frame);
  }

  #lines(frame: FrameReport): string {
    const t = frame.timings;
    const e = frame.evaluationMs;
    return [
      `${this.#method}   ${this.#times.length} fps   ${frame.work.toFixed(1)} ms/frame (${frame.substeps} steps)`,
      e === undefined
        ? `assembly ${t.assembly.toFixed(1)}  factor ${t.factorisation.toFixed(1)}  solve ${t.solve.toFixed(1)}  spiral ${t.integration.toFixed(1)} ms`
        : `rig evaluation ${e.toFixed(3)} ms (${e > 0 ? Math.round(1000 / e).toLocaleString("en") : "∞"} per second)`,
      `${this.#vertices} vertices, ${this.#triangles} triangles`,
      metricsLine(frame.metrics),
      ...(frame.clamped ? ["no foldovers: stopped short, a further step would fold triangles"] : []),
      ...(this.#rig ? [this.#rig] : []),
    ].join("\n");
  }

  /** Stops pending updates (the widget is going away). */
  destroy(): void {
    clearTimeout(this.#trailing);
  }

  #drawSpark(): void {
    const ctx = this.#spark.getContext("2d");
    if (!ctx) return;
    const { width, height } = this.#spark;
    ctx.clearRect(0, 0, width, height);
    const top = Math.max(33.4, ...this.#works);
    const y = (ms: number): number => height - (ms / top) * (height - 2) - 1;
    ctx.strokeStyle = "rgba(192, 57, 43, 0.7)";
    ctx.setLineDash([3, 3]);
    ctx.beginPath();
    ctx.moveTo(0, y(1000 / 60));
    ctx.lineTo(width, y(1000 / 60));
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.strokeStyle = "#e8f1ff";
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    this.#works.forEach((ms, i) => {
      const x = (i / (SPARK_FRAMES - 1)) * width;
      if (i === 0) ctx.moveTo(x, y(ms));
      else ctx.lineTo(x, y(ms));
    });
    ctx.stroke();
  }
}
