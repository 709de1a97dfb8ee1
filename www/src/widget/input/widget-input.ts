/**
 * The widget's input, wired: pointer gestures on the shape (handles, the stiffness brush,
 * bones, and the view's pan and zoom) through {@link PointerInput} and its state machine,
 * whose host this file implements on the posing and the view; keys through
 * {@link Keyboard}; and files dropped on the stage, opened as the Open button's are. What
 * each gesture changes is the posing's and the widget's; this file only routes.
 */
import { boneAt, boneEnds } from "../model/bones.js";
import type { Action } from "../actions/action.js";
import { removeHandle } from "../actions/handles.js";
import { Keyboard } from "./keyboard.js";
import { open } from "../actions/shape.js";
import type { PointerState } from "./pointer-state.js";
import type { Camera } from "../view/camera.js";
import { HANDLE_RADIUS, JOINT_RADIUS, RING_RADIUS } from "../view/overlay.js";
import { nearestPoint, pointPosition } from "../model/picking.js";
import { jointPositions, partsUnder, restPoint } from "../model/puppet.js";
import { PointerInput } from "./pointer-events.js";
import type { WidgetSettings } from "../options.js";
import type { Posing } from "../model/posing.js";
import { fromPixel } from "../view/projection.js";

/** What the input needs of the widget. */
export interface InputHost {
  readonly posing: Posing;
  /** The tool in use and the brush. */
  readonly settings: Pick<WidgetSettings, "tool" | "brush">;
  readonly camera: Camera;
  /** The focusable root (keys) and the overlay canvas (pointers, drops). */
  readonly root: HTMLElement;
  readonly overlay: HTMLCanvasElement;
  /** What the overlay shows of the pointer. */
  readonly pointer: PointerState;
  /** Device pixels per CSS pixel. */
  ratio(): number;
  /** Client (CSS) pixels to device pixels of the canvas. */
  devicePixel(clientX: number, clientY: number): [number, number];
  draw(): void;
  /** A handle moved: frames are wanted, and the loop must not settle yet. */
  moved(): void;
  /** An action succeeded (messages are out of date). */
  succeeded(): void;
  /** An action failed: its message is shown. */
  failed(error: unknown): void;
  /** Runs an action of the registry; a failure (now or when its promise rejects) shows its message. */
  perform<A>(action: Action<A, unknown>, args: A): void;
}

/** How near (CSS pixels) a press must be to a joint to take it. */
const JOINT_REACH = JOINT_RADIUS + 4;

export class WidgetInput {
  readonly #host: InputHost;
  readonly #pointer: PointerInput;
  readonly #keyboard: Keyboard;

  constructor(host: InputHost) {
    this.#host = host;
    const posing = host.posing;
    this.#keyboard = new Keyboard(host);
    const radius = () => (1.6 * HANDLE_RADIUS * host.ratio()) / host.camera.view.scale;
    this.#pointer = new PointerInput(host.overlay, {
      accepting: () => !posing.replaying,
      focus: () => host.root.focus({ preventScroll: true }),
      toShape: (clientX, clientY) => fromPixel(host.camera.view, ...host.devicePixel(clientX, clientY)),
      handleAt: (x, y) => posing.handleAt(x, y, radius()),
      beginGesture: () => posing.beginGesture(),
      addHandleAt: (x, y) => {
        const tolerance = (4 * host.ratio()) / host.camera.view.scale;
        const point = posing.pointAt(x, y, tolerance);
        if (!point) return -1;
        posing.addHandle(point);
        posing.markChanged();
        host.succeeded();
        return posing.handles.length - 1;
      },
      ringAt: (x, y) => {
        const p = posing.deformer.handlePositions();
        const px = host.ratio() / host.camera.view.scale;
        return posing.handles.findIndex((h, i) => {
          const d = Math.hypot(p[2 * i]! - x, p[2 * i + 1]! - y) / px;
          return h.selected && Math.abs(d - RING_RADIUS * HANDLE_RADIUS) <= 0.6 * HANDLE_RADIUS;
        });
      },
      grabTurn: (index, pointerId, x, y) => {
        const grabbed = posing.grabTurn(index, pointerId, x, y);
        if (grabbed) host.draw();
        return grabbed;
      },
      turn: (pointerId, x, y) => {
        posing.dragTurn(pointerId, x, y);
        posing.markChanged();
        host.moved();
      },
      grab: (index, pointerId, x, y, additive) => {
        const grabbed = posing.grab(index, pointerId, x, y, additive);
        if (grabbed) host.draw();
        return grabbed;
      },
      drag: (pointerId, x, y) => {
        posing.drag(pointerId, x, y);
        host.moved();
      },
      release: (pointerId) => {
        posing.release(pointerId);
        host.draw();
      },
      removeHeld: (pointerId) => {
        posing.removeHeld(pointerId);
        host.draw();
      },
      removeAt: (x, y) => {
        const index = posing.handleAt(x, y, radius());
        if (index >= 0) host.perform(removeHandle, { index });
      },
      pressedOff: (additive) => {
        if (!additive) posing.handles.forEach((h) => (h.selected = false));
        posing.endDragGesture();
        host.draw();
      },
      tool: () => host.settings.tool,
      paint: (_pointerId, x, y, erase) => {
        const { size, value } = host.settings.brush;
        if (posing.paint(x, y, (size * host.ratio()) / host.camera.view.scale, erase ? 1 : value)) {
          posing.markChanged();
        }
        host.pointer.hover([x, y]);
      },
      paintEnd: () => this.#strokeEnd(() => posing.flushStiffness()),
      bone: (x, y, erase) => this.#drawBone(x, y, erase),
      boneEnd: () =>
        this.#strokeEnd(() => {
          this.#endBone();
          posing.flushStiffness();
        }),
      joint: (x, y, pressed) => {
        try {
          this.#joint(x, y, pressed);
        } catch (error) {
          host.failed(error);
        }
      },
      jointEnd: () => this.#strokeEnd(() => this.#endJoint()),
      hover: (at) => host.pointer.hover(at),
      pressedWith: (touch) => {
        host.pointer.touch = touch;
      },
      panMode: () => this.#keyboard.spaceHeld,
      pan: (dx, dy) => {
        this.#keyboard.panned();
        host.camera.pan(dx * host.ratio(), dy * host.ratio());
        host.draw();
      },
      zoom: (clientX, clientY, factor) => {
        host.camera.zoom(...host.devicePixel(clientX, clientY), factor);
        host.draw();
      },
    });
    // Files dropped on the stage load like the Open button's.
    host.overlay.addEventListener("dragover", (e) => {
      if (e.dataTransfer?.types.includes("Files")) e.preventDefault();
    });
    host.overlay.addEventListener("drop", (e) => {
      const file = e.dataTransfer?.files[0];
      if (!file) return;
      e.preventDefault();
      host.perform(open, { file });
    });
  }

  destroy(): void {
    this.#pointer.destroy();
  }

  /** A brush stroke or a bone ends: `end` (a failure shows), then the gesture ends. */
  #strokeEnd(end: () => void): void {
    const { posing } = this.#host;
    try {
      end();
    } catch (error) {
      this.#host.failed(error);
    } finally {
      posing.endDragGesture();
      this.#host.draw();
    }
  }

  /**
   * The bone tool's press (or drag) at a shape point: a press starts a bone there and a
   * drag stretches it to the pointer; with Alt, a press removes the bone under it.
   */
  #drawBone(x: number, y: number, erase: boolean): void {
    const { posing, pointer: brush } = this.#host;
    if (brush.boneDraft) {
      brush.boneDraft = [brush.boneDraft[0], brush.boneDraft[1], x, y];
    } else if (erase) {
      const index = boneAt(this.#boneEnds(), x, y, this.#pixels(6));
      if (index >= 0) {
        posing.bones.set(posing.bones.list.filter((_, k) => k !== index));
        posing.markChanged();
      }
      return;
    } else {
      brush.boneDraft = [x, y, x, y];
    }
    this.#host.draw();
  }

  /** The bone tool's release: the bone drawn is added (if it is longer than a few pixels). */
  #endBone(): void {
    const { posing, pointer: brush } = this.#host;
    const draft = brush.boneDraft;
    brush.boneDraft = undefined;
    this.#host.draw();
    if (!draft || Math.hypot(draft[2] - draft[0], draft[3] - draft[1]) < this.#pixels(8)) return;
    // On a puppet, the ends on the front-most part there.
    const at = (x: number, y: number) => posing.pointAt(x, y, this.#pixels(4));
    const [from, to] = [at(draft[0], draft[1]), at(draft[2], draft[3])];
    if (!from || !to) throw new Error("a bone's ends must lie on the shape");
    posing.bones.set([...posing.bones.list, { ends: [from, to] }]);
    posing.markChanged();
    this.#host.succeeded();
  }

  /**
   * The joint tool's press or drag at a shape point (in the pose on screen). A press on a
   * joint selects it and takes it; a press where parts overlap adds a joint there, joining
   * the front-most part under the pointer to the next one under it; a drag moves the joint
   * taken (put down on release, {@link #endJoint}).
   */
  #joint(x: number, y: number, pressed: boolean): void {
    const { posing, pointer } = this.#host;
    const puppet = posing.shape.puppet;
    const draft = pointer.jointDraft;
    if (!pressed) {
      if (!draft) return;
      draft.at = [x, y];
      draft.moved ||= Math.hypot(x - draft.start[0], y - draft.start[1]) > this.#pixels(3);
      this.#host.draw();
      return;
    }
    if (!puppet || !posing.depths) {
      throw new Error("Only a puppet has joints: open an SVG whose layers (top-level groups) are its parts.");
    }
    const rest = posing.shape.mesh.positions;
    const positions = posing.deformer.positionsView();
    const joints = posing.joints;
    const at = jointPositions(puppet, joints, rest, positions, this.#pixels(2));
    const index = nearestPoint(at, x, y, this.#pixels(JOINT_REACH));
    if (index >= 0) {
      posing.selectedJoint = index;
      pointer.jointDraft = { index, start: [x, y], at: [x, y], moved: false };
      this.#host.draw();
      return;
    }
    const under = partsUnder(puppet, posing.depths, positions, posing.shape.mesh.triangles, x, y);
    posing.selectedJoint = undefined;
    this.#host.draw();
    if (under.length === 0) return;
    if (under.length < 2) {
      throw new Error(
        `A joint joins two parts where one lies over the other; only ${puppet.parts[under[0]!.part]!.name} is here.`,
      );
    }
    const [front, back] = [under[0]!, under[1]!];
    const point = pointPosition(rest, posing.shape.mesh.triangles, front.point);
    posing.setJoints([...joints, { point, parts: [front.part, back.part] }]);
    posing.selectedJoint = joints.length;
    posing.markChanged();
    this.#host.succeeded();
  }

  /** The joint tool's release: the joint taken is put down where the pointer left it (on both its parts). */
  #endJoint(): void {
    const { posing, pointer } = this.#host;
    const draft = pointer.jointDraft;
    pointer.jointDraft = undefined;
    const puppet = posing.shape.puppet;
    if (!draft?.moved || !puppet) return;
    const joints = posing.joints;
    const joint = joints[draft.index];
    if (!joint) return;
    const names = joint.parts.map((k) => puppet.parts[k]?.name ?? `part ${k}`).join(" and ");
    const rest = posing.shape.mesh.positions;
    const positions = posing.deformer.positionsView();
    const point = restPoint(puppet, joint.parts[0], rest, positions, ...draft.at);
    const refused = (why: string) => new Error(`The joint stays where it was: it must lie on both ${names}${why}`);
    if (!point) throw refused("");
    joints[draft.index] = { point, parts: joint.parts };
    try {
      posing.setJoints(joints);
    } catch (error) {
      throw refused(` (${error instanceof Error ? error.message : String(error)})`);
    }
    posing.markChanged();
    this.#host.succeeded();
  }

  #boneEnds(): Float64Array {
    const { posing } = this.#host;
    return boneEnds(posing.bones.list, posing.deformer.positionsView(), posing.shape.mesh.triangles);
  }

  /** Shape units in `n` CSS pixels at the current zoom. */
  #pixels(n: number): number {
    return (n * this.#host.ratio()) / this.#host.camera.view.scale;
  }
}
