/**
 * The page's side of pointer gestures: mouse, pen and touch through pointer events on the
 * widget's overlay, turned into samples for the gesture state machine (`gestures.ts`),
 * with the pointer captured while it is down; the wheel zooms about the pointer, a
 * double-click removes the handle under it, and a mouse or pen's place (pressed or not) is
 * reported for the brush's outline and the turning rings.
 */
import { Gestures, type GestureHost, type PointerSample } from "./gestures.js";

/** What the page side needs beyond the gestures' host. */
export interface PointerHost extends GestureHost {
  /** False while the widget does not take input (a replay runs). */
  accepting(): boolean;
  focus(): void;
  /** Shape coordinates of a point given in client (CSS) pixels. */
  toShape(clientX: number, clientY: number): [number, number];
  /** Removes the handle at a shape point, if any (a double-click). */
  removeAt(x: number, y: number): void;
  /** Where a mouse or pen is over the overlay (shape units), undefined once it leaves. */
  hover(at: [number, number] | undefined): void;
  /** A press began with a finger (`true`) or a mouse or pen: a finger cannot hover, so selected handles then show their turning rings. */
  pressedWith(touch: boolean): void;
}

export class PointerInput {
  /** The gestures of the pointers that are down. */
  readonly gestures: Gestures;
  readonly #element: HTMLElement;
  readonly #host: PointerHost;
  readonly #listeners: [string, (e: Event) => void, AddEventListenerOptions?][];

  constructor(element: HTMLElement, host: PointerHost) {
    this.#element = element;
    this.#host = host;
    this.gestures = new Gestures(host);
    this.#listeners = [
      ["pointerdown", (e) => this.#down(e as PointerEvent)],
      ["pointermove", (e) => this.#move(e as PointerEvent)],
      ["pointerleave", () => this.#host.hover(undefined)],
      ["pointerup", (e) => this.#up(e as PointerEvent)],
      ["pointercancel", (e) => this.#up(e as PointerEvent)],
      ["dblclick", (e) => this.#host.removeAt(...this.#shape(e as MouseEvent))],
      ["contextmenu", (e) => e.preventDefault()],
      ["wheel", (e) => this.#wheel(e as WheelEvent), { passive: false }],
    ];
    for (const [type, listener, options] of this.#listeners) element.addEventListener(type, listener, options);
  }

  /** Stops listening and cancels pending long presses. */
  destroy(): void {
    for (const [type, listener] of this.#listeners) this.#element.removeEventListener(type, listener);
    this.gestures.clear();
  }

  #shape(e: MouseEvent): [number, number] {
    return this.#host.toShape(e.clientX, e.clientY);
  }

  #sample(e: PointerEvent, shape = this.#shape(e)): PointerSample {
    return {
      id: e.pointerId,
      client: [e.clientX, e.clientY],
      shape,
      kind: e.pointerType === "touch" ? "touch" : e.pointerType === "pen" ? "pen" : "mouse",
      button: e.button,
      alt: e.altKey,
      shift: e.shiftKey,
    };
  }

  #down(e: PointerEvent): void {
    const host = this.#host;
    if (!host.accepting() || e.button > 1) return;
    host.focus();
    host.pressedWith(e.pointerType === "touch");
    if (this.gestures.down(this.#sample(e)) === undefined) return;
    e.preventDefault();
    this.#element.setPointerCapture(e.pointerId);
  }

  #move(e: PointerEvent): void {
    const touch = e.pointerType === "touch";
    const shape = touch ? undefined : this.#shape(e);
    if (shape) this.#host.hover(shape);
    if (this.gestures.stateOf(e.pointerId) !== "idle") this.gestures.move(this.#sample(e, shape));
  }

  #up(e: PointerEvent): void {
    if (this.gestures.stateOf(e.pointerId) === "idle") return;
    if (this.#element.hasPointerCapture(e.pointerId)) this.#element.releasePointerCapture(e.pointerId);
    this.gestures.up(e.pointerId);
  }

  #wheel(e: WheelEvent): void {
    if (!this.#host.accepting()) return;
    e.preventDefault();
    // Lines and pages as pixels; a notch of about 100 px zooms by about 16%.
    const pixels = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
    this.#host.zoom(e.clientX, e.clientY, Math.exp(-pixels * 0.0015));
  }
}
