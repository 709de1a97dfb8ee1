/**
 * The timeline strip under the stage: Key (capture the pose at the playhead), Play/Pause,
 * Loop, Delete key, the selected key's easing, the track (key markers to select and drag,
 * the playhead to drag: scrubbing shows each frame's pose), the time readout, fps, and
 * "Export animation" with its formats. It only shows and asks; {@link StripActions} does.
 * Delete or Backspace in the strip deletes the selected key; on the track, the arrows move
 * the playhead a frame back or on, Home and End to the ends.
 */
import { ANIMATION_FORMATS, type AnimationExportFormat } from "./formats.js";
import { EASINGS, FPS_RANGE, type Easing } from "./timeline.js";

export interface StripActions {
  capture(): void;
  playPause(): void;
  loop(on: boolean): void;
  deleteKey(index: number): void;
  easing(index: number, easing: Easing): void;
  select(index: number | undefined): void;
  moveKey(index: number, time: number): void;
  /** The playhead dragged: `phase` "start", "move" (show that time) or "end". */
  scrub(time: number, phase: "start" | "move" | "end"): void;
  fps(fps: number): void;
  export(format: AnimationExportFormat): void;
}

/** What the strip shows. */
export interface StripState {
  keys: readonly { time: number; easing: Easing }[];
  selected: number | undefined;
  /** The playhead, seconds. */
  time: number;
  frame: number;
  frameCount: number;
  fps: number;
  playing: boolean;
  loop: boolean;
}

const FORMAT_LABELS: Record<AnimationExportFormat, string> = {
  webm: "WebM video",
  gif: "Animated GIF",
  apng: "Animated PNG (APNG)",
  sprites: "PNG sprite sheet + JSON table",
  json: "JSON animation (for game engines)",
  svg: "SVG per frame (zip)",
};

/** The seconds the track spans: a second past the last key (and the playhead), at least 2. */
export function trackSpan(lastKey: number, playhead: number): number {
  return Math.max(2, Math.ceil(Math.max(lastKey, playhead) + 1));
}

export class TimelineStrip {
  readonly element: HTMLElement;
  readonly #actions: StripActions;
  readonly #play: HTMLButtonElement;
  readonly #loop: HTMLInputElement;
  readonly #delete: HTMLButtonElement;
  readonly #easing: HTMLSelectElement;
  readonly #track: HTMLElement;
  readonly #playhead: HTMLElement;
  readonly #readout: HTMLElement;
  readonly #fps: HTMLInputElement;
  readonly #export: HTMLSelectElement;
  #state: StripState | undefined;
  #span = 2;
  #markers: HTMLButtonElement[] = [];

  constructor(document: Document, actions: StripActions) {
    this.#actions = actions;
    const make = <K extends keyof HTMLElementTagNameMap>(tag: K, className = "") => {
      const e = document.createElement(tag);
      if (className) e.className = className;
      return e;
    };
    const button = (text: string, title: string, onClick: () => void) => {
      const b = make("button");
      b.type = "button";
      b.textContent = text;
      b.title = title;
      b.addEventListener("click", onClick);
      return b;
    };
    this.element = make("div", "timeline");
    this.element.setAttribute("role", "group");
    this.element.setAttribute("aria-label", "Animation timeline");
    const key = button("Key", "Capture the pose as a key at the playhead (K)", () => actions.capture());
    key.className = "key-button";
    this.#play = button("Play", "Play or pause the animation (Space)", () => actions.playPause());
    this.#play.className = "play";
    const loopLabel = make("label");
    this.#loop = make("input");
    this.#loop.type = "checkbox";
    this.#loop.addEventListener("change", () => actions.loop(this.#loop.checked));
    loopLabel.append(this.#loop, "Loop");
    this.#delete = button("Delete key", "Delete the selected key (Delete)", () => {
      if (this.#state?.selected !== undefined) actions.deleteKey(this.#state.selected);
    });
    this.#delete.className = "delete-key";
    this.#easing = make("select");
    this.#easing.setAttribute("aria-label", "Easing into the selected key");
    this.#easing.title = "How the handles move into the selected key";
    for (const e of EASINGS) this.#easing.append(new Option(e === "ease" ? "Ease in-out" : "Linear", e));
    this.#easing.addEventListener("change", () => {
      if (this.#state?.selected !== undefined) actions.easing(this.#state.selected, this.#easing.value as Easing);
    });
    this.#track = make("div", "track");
    this.#track.setAttribute("aria-label", "Timeline: drag the playhead to scrub, a key to move it");
    // The playhead by keyboard: arrows a frame back or on, Home and End the ends.
    this.#track.tabIndex = 0;
    this.#track.setAttribute("role", "slider");
    this.#track.addEventListener("keydown", (e) => {
      const state = this.#state;
      if (!state) return;
      const end = state.keys.at(-1)?.time ?? 0;
      const step = 1 / state.fps;
      const to = { ArrowLeft: state.time - step, ArrowRight: state.time + step, Home: 0, End: end }[e.key];
      if (to === undefined) return;
      e.preventDefault();
      e.stopPropagation();
      const time = Math.round(Math.max(0, to) * state.fps) / state.fps;
      actions.scrub(time, "start");
      actions.scrub(time, "end");
    });
    this.#playhead = make("div", "playhead");
    this.#track.append(this.#playhead);
    this.#readout = make("span", "readout");
    this.#readout.setAttribute("aria-live", "off");
    const fpsLabel = make("label");
    this.#fps = make("input");
    this.#fps.type = "number";
    [this.#fps.min, this.#fps.max, this.#fps.step] = [String(FPS_RANGE[0]), String(FPS_RANGE[1]), "1"];
    this.#fps.className = "fps";
    this.#fps.addEventListener("change", () => actions.fps(Number(this.#fps.value)));
    fpsLabel.append("fps", this.#fps);
    this.#export = make("select");
    this.#export.className = "export-animation";
    this.#export.setAttribute("aria-label", "Export animation");
    this.#export.append(new Option("Export animation…", ""));
    for (const f of ANIMATION_FORMATS) this.#export.append(new Option(FORMAT_LABELS[f], f));
    this.#export.addEventListener("change", () => {
      const format = this.#export.value as AnimationExportFormat | "";
      this.#export.value = "";
      if (format) actions.export(format);
    });
    this.element.append(key, this.#play, loopLabel, this.#delete, this.#easing, this.#track);
    this.element.append(this.#readout, fpsLabel, this.#export);
    this.#bindTrack();
    this.element.addEventListener("keydown", (e) => {
      const tag = (e.composedPath()[0] as HTMLElement | undefined)?.tagName.toLowerCase();
      if ((e.key === "Delete" || e.key === "Backspace") && tag !== "input" && tag !== "select") {
        e.stopPropagation();
        e.preventDefault();
        if (this.#state?.selected !== undefined) actions.deleteKey(this.#state.selected);
      }
    });
  }

  /** Shows the animation's state. */
  show(state: StripState): void {
    this.#state = state;
    this.#span = trackSpan(state.keys.at(-1)?.time ?? 0, state.time);
    const doc = this.element.ownerDocument;
    while (this.#markers.length > state.keys.length) this.#markers.pop()!.remove();
    while (this.#markers.length < state.keys.length) {
      const marker = doc.createElement("button");
      marker.type = "button";
      marker.className = "marker";
      const index = this.#markers.length;
      marker.addEventListener("pointerdown", (e) => this.#dragMarker(e, index));
      marker.addEventListener("click", () => this.#actions.select(index));
      this.#markers.push(marker);
      this.#track.append(marker);
    }
    state.keys.forEach((k, i) => {
      const marker = this.#markers[i]!;
      marker.style.left = `${(100 * k.time) / this.#span}%`;
      marker.classList.toggle("selected", i === state.selected);
      marker.title = `Key ${i + 1} at ${k.time.toFixed(2)} s (${k.easing}); drag to move`;
      marker.setAttribute("aria-label", marker.title);
      marker.dataset.time = String(k.time);
    });
    this.#playhead.style.left = `${(100 * state.time) / this.#span}%`;
    this.#track.setAttribute("aria-valuemin", "0");
    this.#track.setAttribute("aria-valuemax", String(this.#span));
    this.#track.setAttribute("aria-valuenow", String(state.time));
    this.#track.setAttribute("aria-valuetext", `${state.time.toFixed(2)} seconds`);
    this.#play.textContent = state.playing ? "Pause" : "Play";
    this.#play.classList.toggle("active", state.playing);
    this.#play.disabled = state.keys.length === 0;
    this.#loop.checked = state.loop;
    this.#delete.disabled = state.selected === undefined;
    this.#easing.disabled = state.selected === undefined || state.selected === 0;
    if (state.selected !== undefined) this.#easing.value = state.keys[state.selected]!.easing;
    this.#export.disabled = state.keys.length === 0;
    const end = state.keys.at(-1)?.time ?? 0;
    this.#readout.textContent =
      `${state.time.toFixed(2)} s / ${end.toFixed(2)} s` +
      (state.frameCount > 0 ? ` · frame ${Math.min(state.frame, state.frameCount - 1) + 1}/${state.frameCount}` : "");
    if (this.element.ownerDocument.activeElement !== this.#fps) this.#fps.value = String(state.fps);
  }

  /** The time (seconds, on the frame grid) at a client x on the track. */
  #timeAt(clientX: number): number {
    const rect = this.#track.getBoundingClientRect();
    const fps = this.#state?.fps ?? 24;
    const t = (Math.min(Math.max(clientX - rect.left, 0), rect.width) / Math.max(1, rect.width)) * this.#span;
    return Math.round(t * fps) / fps;
  }

  #bindTrack(): void {
    this.#track.addEventListener("pointerdown", (e) => {
      if ((e.target as HTMLElement).classList.contains("marker")) return;
      e.preventDefault();
      this.#track.setPointerCapture(e.pointerId);
      this.#actions.scrub(this.#timeAt(e.clientX), "start");
      const move = (m: PointerEvent) => this.#actions.scrub(this.#timeAt(m.clientX), "move");
      const up = (u: PointerEvent) => {
        this.#track.removeEventListener("pointermove", move);
        this.#track.removeEventListener("pointerup", up);
        this.#track.removeEventListener("pointercancel", up);
        this.#actions.scrub(this.#timeAt(u.clientX), "end");
      };
      this.#track.addEventListener("pointermove", move);
      this.#track.addEventListener("pointerup", up);
      this.#track.addEventListener("pointercancel", up);
    });
  }

  /** A key's marker follows the pointer; the key moves there on release (a click selects it). */
  #dragMarker(e: PointerEvent, index: number): void {
    const marker = this.#markers[index]!;
    e.preventDefault();
    e.stopPropagation();
    marker.setPointerCapture(e.pointerId);
    const from = e.clientX;
    let moved = false;
    const move = (m: PointerEvent) => {
      moved ||= Math.abs(m.clientX - from) > 3;
      if (moved) marker.style.left = `${(100 * this.#timeAt(m.clientX)) / this.#span}%`;
    };
    const up = (u: PointerEvent) => {
      marker.removeEventListener("pointermove", move);
      marker.removeEventListener("pointerup", up);
      marker.removeEventListener("pointercancel", up);
      if (moved && u.type === "pointerup") this.#actions.moveKey(index, this.#timeAt(u.clientX));
      else this.#actions.select(index);
      marker.focus({ preventScroll: true });
    };
    marker.addEventListener("pointermove", move);
    marker.addEventListener("pointerup", up);
    marker.addEventListener("pointercancel", up);
  }
}
