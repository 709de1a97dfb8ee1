/**
 * Pointer gestures as a small state machine (no DOM: `pointer-events.ts` feeds it). Each
 * pointer that is down is in one state, an object of a small class that handles its moves,
 * its release and, for a held handle, the long press:
 *
 * - idle (no state): a press decides where the pointer goes ({@link Gestures.down});
 * - `dragging-handle`: a press on a handle, or on the shape (which adds a handle there and
 *   grabs it); moving drags it, releasing lets go (it stays as a pin); a long still press
 *   with a finger or pen on a handle that existed removes it;
 * - `turning`: a press on the ring round the selected handle, or an Alt-press on a handle;
 *   the handle (and the region about it) turns as the pointer goes round it;
 * - `painting`: with the stiffness brush, a press paints (with Alt, erases) until released;
 * - `drawing-bone`: with the bone tool, a press starts a bone that the pointer stretches
 *   and its release adds (with Alt, a press removes the bone under it);
 * - `moving-joint`: with the joint tool, a press on a joint takes it (a press elsewhere
 *   adds one there), the pointer moves it, and its release puts it down;
 * - `panning`: a press on the background, a middle-button press, or any press while Space
 *   is held moves the view;
 * - `pinching`: two pointers moving the view (fingers): their midpoint pans, their
 *   distance zooms about it. A second finger off the handles while the first moves the
 *   view, or just added a handle and has not moved, starts a pinch (the handle is given
 *   back: the user meant to pinch).
 *
 * Several pointers are in states of their own at once, so several fingers drag several
 * handles. What each gesture changes is the host's (the widget's posing and view).
 */

/** Press time after which a still finger or pen on a handle removes it. */
export const LONG_PRESS_MS = 650;
/** How far (CSS pixels) a press may wander and still count as still. */
export const STILL_PIXELS = 6;
/** A second finger this soon after a first one that added a handle makes a pinch instead. */
export const PINCH_WINDOW_MS = 350;

/** A pointer's press or move, as the machine reads it. */
export interface PointerSample {
  id: number;
  /** Client (CSS) pixels. */
  client: [number, number];
  /** The point in shape units. */
  shape: [number, number];
  kind: "mouse" | "pen" | "touch";
  /** The mouse button pressed (0 main, 1 middle); 0 for moves. */
  button: number;
  alt: boolean;
  shift: boolean;
}

/** What the gestures do; the widget implements it. */
export interface GestureHost {
  /** The handle near a shape point, or -1. */
  handleAt(x: number, y: number): number;
  /** The selected handle whose turning ring is at a shape point, or -1. */
  ringAt(x: number, y: number): number;
  /** What a press on the shape does (the tool in use). */
  tool(): "pose" | "stiffness" | "bone" | "joint";
  /** Whether presses pan the view instead (Space is held). */
  panMode(): boolean;
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
  /** A press off the shape: clears the selection unless `additive`, ends the gesture. */
  pressedOff(additive: boolean): void;
  /** Starts turning a handle from a shape point; false if another pointer holds it. */
  grabTurn(index: number, pointerId: number, x: number, y: number): boolean;
  /** The pointer turning a handle moved to a shape point. */
  turn(pointerId: number, x: number, y: number): void;
  /** A brush stroke begins or goes on at a shape point; `erase` with Alt. */
  paint(pointerId: number, x: number, y: number, erase: boolean): void;
  /** The brush stroke of the pointer ends. */
  paintEnd(pointerId: number): void;
  /** The bone tool's press (`erase`: Alt, removes the bone there) or drag at a shape point. */
  bone(x: number, y: number, erase: boolean): void;
  /** The bone tool's release: the bone drawn is added. */
  boneEnd(): void;
  /** The joint tool's press (`pressed`) or drag at a shape point. */
  joint(x: number, y: number, pressed: boolean): void;
  /** The joint tool's release: the joint moved is put down. */
  jointEnd(): void;
  /** Moves the view by (dx, dy) CSS pixels. */
  pan(dx: number, dy: number): void;
  /** Zooms the view by `factor` about a point given in client pixels. */
  zoom(clientX: number, clientY: number, factor: number): void;
}

/** The names of the states (`idle` for a pointer that is not down). */
export type GestureName =
  "idle" | "dragging-handle" | "turning" | "painting" | "drawing-bone" | "moving-joint" | "panning" | "pinching";

/** Where a pointer pressed and last was, in client pixels. */
interface Track {
  readonly touch: boolean;
  readonly start: [number, number];
  last: [number, number];
}

/** A state of a pointer that is down. */
abstract class PointerGesture {
  abstract readonly name: GestureName;
  constructor(readonly track: Track) {}
  /** The pointer moved (its track is updated after). */
  abstract move(machine: Gestures, sample: PointerSample): void;
  /** The pointer was released or cancelled. */
  abstract up(machine: Gestures, id: number): void;
  /** Whether it has stayed within {@link STILL_PIXELS} of its press. */
  get still(): boolean {
    const { start, last } = this.track;
    return Math.hypot(last[0] - start[0], last[1] - start[1]) < STILL_PIXELS;
  }
}

class DraggingHandle extends PointerGesture {
  readonly name = "dragging-handle";
  /** When the press added its handle (undefined if it grabbed an existing one). */
  readonly added: number | undefined;
  constructor(track: Track, added: number | undefined) {
    super(track);
    this.added = added;
  }
  move(machine: Gestures, sample: PointerSample): void {
    machine.host.drag(sample.id, ...sample.shape);
  }
  up(machine: Gestures, id: number): void {
    machine.host.release(id);
  }
  /** A long still press removes the handle (the pointer is then idle). */
  longPress(machine: Gestures, id: number): void {
    if (!this.still) return;
    machine.leave(id);
    machine.host.removeHeld(id);
  }
  /** A second finger starts a pinch with this one when it just added its handle and has not moved. */
  pinchable(now: number): boolean {
    return this.added !== undefined && this.still && now - this.added <= PINCH_WINDOW_MS;
  }
}

class Turning extends PointerGesture {
  readonly name = "turning";
  move(machine: Gestures, sample: PointerSample): void {
    machine.host.turn(sample.id, ...sample.shape);
  }
  up(machine: Gestures, id: number): void {
    machine.host.release(id);
  }
}

class Painting extends PointerGesture {
  readonly name = "painting";
  move(machine: Gestures, sample: PointerSample): void {
    machine.host.paint(sample.id, ...sample.shape, sample.alt);
  }
  up(machine: Gestures, id: number): void {
    machine.host.paintEnd(id);
  }
}

class DrawingBone extends PointerGesture {
  readonly name = "drawing-bone";
  move(machine: Gestures, sample: PointerSample): void {
    machine.host.bone(...sample.shape, sample.alt);
  }
  up(machine: Gestures): void {
    machine.host.boneEnd();
  }
}

class MovingJoint extends PointerGesture {
  readonly name = "moving-joint";
  move(machine: Gestures, sample: PointerSample): void {
    machine.host.joint(...sample.shape, false);
  }
  up(machine: Gestures): void {
    machine.host.jointEnd();
  }
}

/** One pointer moving the view. */
class Panning extends PointerGesture {
  readonly name: GestureName = "panning";
  move(machine: Gestures, sample: PointerSample): void {
    const previous = this.track.last;
    machine.host.pan(sample.client[0] - previous[0], sample.client[1] - previous[1]);
  }
  up(): void {
    // Nothing to let go of: the view stays where it was moved.
  }
}

/** A pointer moving the view with another: the pair's midpoint pans, their distance zooms about it. */
class Pinching extends Panning {
  override readonly name = "pinching";
  constructor(
    track: Track,
    readonly partner: Track,
  ) {
    super(track);
  }
  override move(machine: Gestures, sample: PointerSample): void {
    const [previous, now, other] = [this.track.last, sample.client, this.partner.last];
    const before = [(previous[0] + other[0]) / 2, (previous[1] + other[1]) / 2];
    const after = [(now[0] + other[0]) / 2, (now[1] + other[1]) / 2];
    const spanBefore = Math.hypot(previous[0] - other[0], previous[1] - other[1]);
    const spanAfter = Math.hypot(now[0] - other[0], now[1] - other[1]);
    machine.host.pan(after[0]! - before[0]!, after[1]! - before[1]!);
    if (spanBefore > 1 && spanAfter > 1) machine.host.zoom(after[0]!, after[1]!, spanAfter / spanBefore);
  }
}

/** What a press that took its pointer into a state needs done by the page (capture, preventDefault). */
export type Pressed = GestureName | undefined;

export class Gestures {
  readonly host: GestureHost;
  readonly #states = new Map<number, PointerGesture>();
  readonly #timers = new Map<number, () => void>();
  readonly #now: () => number;
  readonly #later: (ms: number, run: () => void) => () => void;

  /**
   * `now` (milliseconds) and `later` (runs `run` after `ms`, returning its cancel) default
   * to the page's clock and timers; tests give their own.
   */
  constructor(
    host: GestureHost,
    clock: { now?: () => number; later?: (ms: number, run: () => void) => () => void } = {},
  ) {
    this.host = host;
    this.#now = clock.now ?? (() => performance.now());
    this.#later =
      clock.later ??
      ((ms, run) => {
        const timer = setTimeout(run, ms);
        return () => clearTimeout(timer);
      });
  }

  /** The state of pointer `id` (`idle` when it is not down). */
  stateOf(id: number): GestureName {
    return this.#states.get(id)?.name ?? "idle";
  }

  /**
   * A pointer pressed: the state it enters, or undefined when the press is not taken (a
   * handle another pointer holds). The caller has checked that input is accepted and the
   * button is the main or middle one.
   */
  down(p: PointerSample): GestureName | undefined {
    const host = this.host;
    const touch = p.kind === "touch";
    const track: Track = { touch, start: p.client, last: p.client };
    if (p.button === 1 || host.panMode()) return this.#enterView(p.id, track);
    const [x, y] = p.shape;
    const tool = host.tool();
    if (tool !== "pose" && !(touch && this.#pinchWith())) {
      host.beginGesture();
      if (tool === "bone") {
        host.bone(x, y, p.alt);
        return this.#enter(p.id, new DrawingBone(track));
      }
      if (tool === "joint") {
        host.joint(x, y, true);
        return this.#enter(p.id, new MovingJoint(track));
      }
      host.paint(p.id, x, y, p.alt);
      return this.#enter(p.id, new Painting(track));
    }
    let index = host.handleAt(x, y);
    const ring = index < 0 ? host.ringAt(x, y) : -1;
    if ((index >= 0 && p.alt) || ring >= 0) {
      host.beginGesture();
      if (!host.grabTurn(Math.max(index, ring), p.id, x, y)) return undefined;
      return this.#enter(p.id, new Turning(track));
    }
    const existed = index >= 0;
    if (touch && !existed && this.#pinchWith()) return this.#enterView(p.id, track);
    host.beginGesture();
    if (!existed) index = host.addHandleAt(x, y);
    if (index < 0) {
      host.pressedOff(p.shift);
      return this.#enterView(p.id, track);
    }
    if (!host.grab(index, p.id, x, y, p.shift)) return undefined;
    const dragging = new DraggingHandle(track, existed ? undefined : this.#now());
    this.#enter(p.id, dragging);
    if (existed && p.kind !== "mouse") {
      this.#timers.set(
        p.id,
        this.#later(LONG_PRESS_MS, () => {
          this.#timers.delete(p.id);
          if (this.#states.get(p.id) === dragging) dragging.longPress(this, p.id);
        }),
      );
    }
    return dragging.name;
  }

  /** A pointer moved (down or not: a pointer that is not down does nothing here). */
  move(p: PointerSample): void {
    const state = this.#states.get(p.id);
    if (!state) return;
    state.move(this, p);
    state.track.last = p.client;
  }

  /** A pointer was released or cancelled. */
  up(id: number): void {
    const state = this.#states.get(id);
    if (!state) return;
    this.leave(id);
    state.up(this, id);
  }

  /** Every pointer let go of, without telling the host (the widget is going away). */
  clear(): void {
    for (const cancel of this.#timers.values()) cancel();
    this.#timers.clear();
    this.#states.clear();
  }

  /** Pointer `id` leaves its state (idle now); pinch partners are regrouped. */
  leave(id: number): void {
    this.#timers.get(id)?.();
    this.#timers.delete(id);
    const state = this.#states.get(id);
    this.#states.delete(id);
    if (state instanceof Panning) this.#regroupViews();
  }

  #enter(id: number, state: PointerGesture): GestureName {
    this.#states.set(id, state);
    return state.name;
  }

  #enterView(id: number, track: Track): GestureName {
    this.#states.set(id, new Panning(track));
    this.#regroupViews();
    return this.stateOf(id);
  }

  /**
   * Pointers moving the view pan alone, or pinch with another: each view pointer pinches
   * with the first other one while there is one.
   */
  #regroupViews(): void {
    const views = [...this.#states].filter(([, s]) => s instanceof Panning);
    for (const [id, state] of views) {
      const other = views.find(([k]) => k !== id)?.[1];
      const next = other ? new Pinching(state.track, other.track) : new Panning(state.track);
      if (next.name !== state.name || (state instanceof Pinching && other && state.partner !== other.track)) {
        this.#states.set(id, next);
      }
    }
  }

  /**
   * Whether a new finger off the handles starts a pinch with the one finger already down:
   * yes if that finger moves the view, or just added a handle and has not moved (the handle
   * is taken back, and that finger now moves the view).
   */
  #pinchWith(): boolean {
    const touches = [...this.#states].filter(([, s]) => s.track.touch);
    if (touches.length !== 1) return false;
    const [id, other] = touches[0]!;
    if (other instanceof Panning) return true;
    if (!(other instanceof DraggingHandle) || !other.pinchable(this.#now())) return false;
    this.leave(id);
    this.host.removeHeld(id);
    this.#states.set(id, new Panning(other.track));
    this.#regroupViews();
    return true;
  }
}
