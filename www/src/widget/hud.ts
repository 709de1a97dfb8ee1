/**
 * The heads-up display: frames per second, milliseconds per stage, mesh size, live
 * distortion and a sparkline of recent frame times (the 16.7 ms line marks 60 fps).
 */
import type { Metrics, Timings } from "../core.js";

export interface FrameReport {
  /** When the frame ran (performance.now()). */
  time: number;
  /** Milliseconds of solver work and drawing in this frame. */
  work: number;
  /** Solver stages summed over the frame's substeps. */
  timings: Timings;
  substeps: number;
  metrics: Metrics;
}

const SPARK_FRAMES = 120;

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

  /** Shows the mesh size (before any frame ran). */
  showMesh(vertices: number, triangles: number, method: string): void {
    this.#vertices = vertices;
    this.#triangles = triangles;
    this.#method = method;
    this.#works.length = 0;
    this.#times.length = 0;
    this.#text.textContent = `${method}\n${vertices} vertices, ${triangles} triangles\ndrag the shape to add a handle`;
    this.#drawSpark();
  }

  #vertices = 0;
  #triangles = 0;
  #method = "";

  /** Adds a frame; the text refreshes at most four times a second. */
  report(frame: FrameReport): void {
    this.#works.push(frame.work);
    if (this.#works.length > SPARK_FRAMES) this.#works.shift();
    this.#times.push(frame.time);
    while (this.#times.length > 0 && this.#times[0]! < frame.time - 1000) this.#times.shift();
    this.#drawSpark();
    if (frame.time - this.#lastText < 250) return;
    this.#lastText = frame.time;
    const t = frame.timings;
    const m = frame.metrics;
    this.#text.textContent = [
      `${this.#method}   ${this.#times.length} fps   ${frame.work.toFixed(1)} ms/frame (${frame.substeps} steps)`,
      `assembly ${t.assembly.toFixed(1)}  factor ${t.factorisation.toFixed(1)}  solve ${t.solve.toFixed(1)}  spiral ${t.integration.toFixed(1)} ms`,
      `${this.#vertices} vertices, ${this.#triangles} triangles`,
      `E_area ${m.areaDistortion.toFixed(4)}  E_angle ${m.angleDistortion.toFixed(4)}  flipped ${m.flipped}`,
    ].join("\n");
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
