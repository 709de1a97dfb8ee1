/**
 * Pointer gestures on the widget's overlay (mouse, pen and touch through pointer events):
 * a press on the shape adds a handle there and grabs it, a press on a handle grabs it,
 * moving drags it, releasing lets go (it stays as a pin). A long still press with a finger
 * or pen on an existing handle removes it, as does a double-click. Each pointer has its
 * own record, so several fingers drag several handles at once.
 *
 * A press on the ring round the selected handle, or an Alt-press on a handle, turns the
 * handle (and the region about it) as the pointer goes round it. The ring shows when a
 * mouse or pen comes near the handle; after a finger's press it shows round every
 * selected handle (a finger cannot hover).
 *
 * With the stiffness brush on, a press on the shape paints instead (with Alt, erases) until
 * it is released; the pointer's place, pressed or not, is reported for the brush's outline.
 *
 * The view: a press on the background, a middle-button press or any press while Space is
 * held pans; two fingers that are not both on handles pan and pinch-zoom (a finger that
 * had just added a handle gives it back when the second finger arrives); the wheel zooms
 * about the pointer.
 */

/** What the gestures do; the widget implements it. */
export interface PointerHost {
  /** False while the widget does not take input (a replay runs). */
  accepting(): boolean;
  focus(): void;
  /** Shape coordinates of a point given in client (CSS) pixels. */
  toShape(clientX: number, clientY: number): [number, number];
  /** The handle near a shape point, or -1. */
  handleAt(x: number, y: number): number;
  /** Saves the state for undo before a gesture (once for overlapping gestures). */
  beginGesture(): void;
  /** Adds a handle at a shape point if the point is on the shape: its index, or -1. */
  addHandleAt(x: number, y: number): number;
  /** Starts dragging a handle from a shape point; false if another pointer holds it. */
  grab(index: number, pointerId: number, x: number, y: number, additive: boolean): boolean;
  drag(pointerId: number, x: number, y: number): void;
  /** Lets go of the handle (it becomes a pin) and ends the gesture if no pointer is down. */
  release(pointerId: number): void;
  /** Removes the handle the pointer holds. */
  removeHeld(pointerId: number): void;
  /** Removes the handle at a shape point, if any. */
  removeAt(x: number, y: number): void;
  /** A press off the shape: clears the selection unless `additive`, ends the gesture. */
  pressedOff(additive: boolean): void;
  /** The selected handle whose turning ring is at a shape point, or -1. */
  ringAt(x: number, y: number): number;
  /** Starts turning a handle from a shape point; false if another pointer holds it. */
  grabTurn(index: number, pointerId: number, x: number, y: number): boolean;
  /** The pointer turning a handle moved to a shape point. */
  turn(pointerId: number, x: number, y: number): void;
  /** Whether presses on the shape paint stiffness instead of posing (the brush is on). */
  painting(): boolean;
  /** A brush stroke (one per pointer) begins or goes on at a shape point; `erase` with Alt. */
  paint(pointerId: number, x: number, y: number, erase: boolean): void;
  /** The brush stroke of the pointer ends. */
  paintEnd(pointerId: number): void;
  /** Where a mouse or pen is over the overlay (shape units), undefined once it leaves. */
  hover(at: [number, number] | undefined): void;
  /** A press began with a finger (`true`) or a mouse or pen: a finger cannot hover, so selected handles then show their turning rings. */
  pressedWith(touch: boolean): void;
  /** Whether presses pan the view instead of posing (Space is held). */
  panMode(): boolean;
  /** Moves the view by (dx, dy) CSS pixels. */
  pan(dx: number, dy: number): void;
  /** Zooms the view by `factor` about a point given in client pixels. */
  zoom(clientX: number, clientY: number, factor: number): void;
}

/** Press time after which a still finger or pen on a handle removes it. */
export const LONG_PRESS_MS = 650;
/** How far (CSS pixels) a press may wander and still count as still. */
const STILL_PIXELS = 6;
/** A second finger this soon after a first one that added a handle makes a pinch instead. */
const PINCH_WINDOW_MS = 350;

interface Press {
  /** Drags a handle, turns one, paints, or moves the view. */
  kind: "handle" | "turn" | "paint" | "view";
  touch: boolean;
  start: [number, number];
  last: [number, number];
  timer: ReturnType<typeof setTimeout> | undefined;
  /** When a handle press added its handle (0 if it grabbed an existing one). */
  added: number;
}

export class PointerInput {
  readonly #element: HTMLElement;
  readonly #host: PointerHost;
  readonly #presses = new Map<number, Press>();
  readonly #listeners: [string, (e: Event) => void, AddEventListenerOptions?][];

  constructor(element: HTMLElement, host: PointerHost) {
    this.#element = element;
    this.#host = host;
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
    for (const press of this.#presses.values()) clearTimeout(press.timer);
    this.#presses.clear();
  }

  #shape(e: MouseEvent): [number, number] {
    return this.#host.toShape(e.clientX, e.clientY);
  }

  #down(e: PointerEvent): void {
    const host = this.#host;
    if (!host.accepting() || e.button > 1) return;
    host.focus();
    const touch = e.pointerType === "touch";
    host.pressedWith(touch);
    const client: [number, number] = [e.clientX, e.clientY];
    if (e.button === 1 || host.panMode()) {
      this.#begin(e, { kind: "view", touch, start: client, last: client, timer: undefined, added: 0 });
      return;
    }
    const [x, y] = this.#shape(e);
    if (host.painting() && !(touch && this.#pinchWith())) {
      host.beginGesture();
      host.paint(e.pointerId, x, y, e.altKey);
      this.#begin(e, { kind: "paint", touch, start: client, last: client, timer: undefined, added: 0 });
      return;
    }
    let index = host.handleAt(x, y);
    const ring = index < 0 ? host.ringAt(x, y) : -1;
    if ((index >= 0 && e.altKey) || ring >= 0) {
      host.beginGesture();
      if (!host.grabTurn(Math.max(index, ring), e.pointerId, x, y)) return;
      this.#begin(e, { kind: "turn", touch, start: client, last: client, timer: undefined, added: 0 });
      return;
    }
    const existed = index >= 0;
    if (touch && !existed && this.#pinchWith()) {
      this.#begin(e, { kind: "view", touch, start: client, last: client, timer: undefined, added: 0 });
      return;
    }
    host.beginGesture();
    if (!existed) index = host.addHandleAt(x, y);
    if (index < 0) {
      host.pressedOff(e.shiftKey);
      this.#begin(e, { kind: "view", touch, start: client, last: client, timer: undefined, added: 0 });
      return;
    }
    if (!host.grab(index, e.pointerId, x, y, e.shiftKey)) return;
    const press: Press = {
      kind: "handle",
      touch,
      start: client,
      last: client,
      timer: undefined,
      added: existed ? 0 : performance.now(),
    };
    if (existed && e.pointerType !== "mouse") {
      press.timer = setTimeout(() => {
        const [dx, dy] = [press.last[0] - press.start[0], press.last[1] - press.start[1]];
        if (this.#presses.get(e.pointerId) === press && Math.hypot(dx, dy) < STILL_PIXELS) {
          this.#presses.delete(e.pointerId);
          host.removeHeld(e.pointerId);
        }
      }, LONG_PRESS_MS);
    }
    this.#begin(e, press);
  }

  #begin(e: PointerEvent, press: Press): void {
    e.preventDefault();
    this.#element.setPointerCapture(e.pointerId);
    this.#presses.set(e.pointerId, press);
  }

  /**
   * Whether a new finger off the handles starts a pinch with the one finger already down:
   * yes if that finger moves the view, or just added a handle and has not moved (the handle
   * is taken back, since the user meant to pinch).
   */
  #pinchWith(): boolean {
    const touches = [...this.#presses.entries()].filter(([, p]) => p.touch);
    if (touches.length !== 1) return false;
    const [id, other] = touches[0]!;
    if (other.kind === "view") return true;
    const still = Math.hypot(other.last[0] - other.start[0], other.last[1] - other.start[1]) < STILL_PIXELS;
    if (other.added === 0 || !still || performance.now() - other.added > PINCH_WINDOW_MS) return false;
    this.#presses.delete(id);
    this.#host.removeHeld(id);
    other.kind = "view";
    this.#presses.set(id, other);
    return true;
  }

  #move(e: PointerEvent): void {
    if (e.pointerType !== "touch") this.#host.hover(this.#shape(e));
    const press = this.#presses.get(e.pointerId);
    if (!press) return;
    const previous = press.last;
    press.last = [e.clientX, e.clientY];
    if (press.kind === "handle") {
      this.#host.drag(e.pointerId, ...this.#shape(e));
      return;
    }
    if (press.kind === "paint") {
      this.#host.paint(e.pointerId, ...this.#shape(e), e.altKey);
      return;
    }
    if (press.kind === "turn") {
      this.#host.turn(e.pointerId, ...this.#shape(e));
      return;
    }
    const views = [...this.#presses.values()].filter((p) => p.kind === "view");
    if (views.length < 2) {
      this.#host.pan(press.last[0] - previous[0], press.last[1] - previous[1]);
      return;
    }
    // Two fingers: the pair's midpoint pans, their distance zooms about it.
    const other = views.find((p) => p !== press)!;
    const before = [(previous[0] + other.last[0]) / 2, (previous[1] + other.last[1]) / 2];
    const after = [(press.last[0] + other.last[0]) / 2, (press.last[1] + other.last[1]) / 2];
    const spanBefore = Math.hypot(previous[0] - other.last[0], previous[1] - other.last[1]);
    const spanAfter = Math.hypot(press.last[0] - other.last[0], press.last[1] - other.last[1]);
    this.#host.pan(after[0]! - before[0]!, after[1]! - before[1]!);
    if (spanBefore > 1 && spanAfter > 1) this.#host.zoom(after[0]!, after[1]!, spanAfter / spanBefore);
  }

  #up(e: PointerEvent): void {
    const press = this.#presses.get(e.pointerId);
    if (!press) return;
    clearTimeout(press.timer);
    this.#presses.delete(e.pointerId);
    if (this.#element.hasPointerCapture(e.pointerId)) this.#element.releasePointerCapture(e.pointerId);
    if (press.kind === "handle" || press.kind === "turn") this.#host.release(e.pointerId);
    if (press.kind === "paint") this.#host.paintEnd(e.pointerId);
  }

  #wheel(e: WheelEvent): void {
    if (!this.#host.accepting()) return;
    e.preventDefault();
    // Lines and pages as pixels; a notch of about 100 px zooms by about 16%.
    const pixels = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
    this.#host.zoom(e.clientX, e.clientY, Math.exp(-pixels * 0.0015));
  }
}
