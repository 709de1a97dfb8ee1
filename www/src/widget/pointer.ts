/**
 * Pointer gestures on the widget's overlay (mouse, pen and touch through pointer events):
 * a press on the shape adds a handle there and grabs it, a press on a handle grabs it,
 * moving drags it, releasing lets go (it stays as a pin). A long still press with a finger
 * or pen on an existing handle removes it, as does a double-click. Each pointer has its
 * own record, so several fingers drag several handles at once.
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
}

/** Press time after which a still finger or pen on a handle removes it. */
export const LONG_PRESS_MS = 650;
/** How far (CSS pixels) a press may wander and still count as still. */
const STILL_PIXELS = 6;

interface Press {
  start: [number, number];
  last: [number, number];
  timer: ReturnType<typeof setTimeout> | undefined;
}

export class PointerInput {
  readonly #element: HTMLElement;
  readonly #host: PointerHost;
  readonly #presses = new Map<number, Press>();
  readonly #listeners: [string, (e: Event) => void][];

  constructor(element: HTMLElement, host: PointerHost) {
    this.#element = element;
    this.#host = host;
    this.#listeners = [
      ["pointerdown", (e) => this.#down(e as PointerEvent)],
      ["pointermove", (e) => this.#move(e as PointerEvent)],
      ["pointerup", (e) => this.#up(e as PointerEvent)],
      ["pointercancel", (e) => this.#up(e as PointerEvent)],
      ["dblclick", (e) => this.#host.removeAt(...this.#shape(e as MouseEvent))],
      ["contextmenu", (e) => e.preventDefault()],
    ];
    for (const [type, listener] of this.#listeners) element.addEventListener(type, listener);
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
    if (!host.accepting() || e.button > 0) return;
    host.focus();
    const [x, y] = this.#shape(e);
    let index = host.handleAt(x, y);
    const existed = index >= 0;
    host.beginGesture();
    if (!existed) index = host.addHandleAt(x, y);
    if (index < 0) {
      host.pressedOff(e.shiftKey);
      return;
    }
    if (!host.grab(index, e.pointerId, x, y, e.shiftKey)) return;
    e.preventDefault();
    this.#element.setPointerCapture(e.pointerId);
    const press: Press = { start: [e.clientX, e.clientY], last: [e.clientX, e.clientY], timer: undefined };
    if (existed && e.pointerType !== "mouse") {
      press.timer = setTimeout(() => {
        const [dx, dy] = [press.last[0] - press.start[0], press.last[1] - press.start[1]];
        if (this.#presses.get(e.pointerId) === press && Math.hypot(dx, dy) < STILL_PIXELS) {
          this.#presses.delete(e.pointerId);
          host.removeHeld(e.pointerId);
        }
      }, LONG_PRESS_MS);
    }
    this.#presses.set(e.pointerId, press);
  }

  #move(e: PointerEvent): void {
    const press = this.#presses.get(e.pointerId);
    if (!press) return;
    press.last = [e.clientX, e.clientY];
    this.#host.drag(e.pointerId, ...this.#shape(e));
  }

  #up(e: PointerEvent): void {
    const press = this.#presses.get(e.pointerId);
    if (!press) return;
    clearTimeout(press.timer);
    this.#presses.delete(e.pointerId);
    if (this.#element.hasPointerCapture(e.pointerId)) this.#element.releasePointerCapture(e.pointerId);
    this.#host.release(e.pointerId);
  }
}
