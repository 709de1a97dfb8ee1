/** The pointer gestures' state machine: each press's state, its transitions and what it tells its host. */
import { describe, expect, it } from "vitest";
import {
  Gestures,
  LONG_PRESS_MS,
  PINCH_WINDOW_MS,
  STILL_PIXELS,
  type GestureHost,
  type PointerSample,
} from "../../www/src/widget/input/gestures.js";

/** A host on a line of shape: handles at given x (y 0), the shape from x 0 to 10, client pixels = shape units. */
function fixture(options: { handles?: number[]; tool?: "pose" | "stiffness" | "bone" | "joint"; ring?: number } = {}) {
  const handles = [...(options.handles ?? [])];
  const calls: string[] = [];
  const held = new Map<number, number>();
  let time = 0;
  const timers: { at: number; run: () => void; cancelled: boolean }[] = [];
  let space = false;
  const host: GestureHost = {
    handleAt: (x) => handles.findIndex((h) => Math.abs(h - x) < 0.5),
    ringAt: (x) => (options.ring !== undefined && Math.abs(x - options.ring - 2) < 0.5 ? 0 : -1),
    tool: () => options.tool ?? "pose",
    panMode: () => space,
    beginGesture: () => calls.push("begin"),
    addHandleAt: (x) => {
      if (x < 0 || x > 10) return -1;
      handles.push(x);
      calls.push(`add ${x}`);
      return handles.length - 1;
    },
    grab: (index, id) => {
      if ([...held.values()].includes(index)) return false;
      held.set(id, index);
      calls.push(`grab ${index} by ${id}`);
      return true;
    },
    drag: (id, x) => calls.push(`drag ${held.get(id)} to ${x}`),
    release: (id) => {
      calls.push(`release ${held.get(id)}`);
      held.delete(id);
    },
    removeHeld: (id) => {
      calls.push(`remove ${held.get(id)}`);
      held.delete(id);
    },
    pressedOff: (additive) => calls.push(`off${additive ? " additive" : ""}`),
    grabTurn: (index, id) => {
      held.set(id, index);
      calls.push(`turn ${index}`);
      return true;
    },
    turn: (_id, x) => calls.push(`turning to ${x}`),
    paint: (_id, x, _y, erase) => calls.push(`${erase ? "erase" : "paint"} ${x}`),
    paintEnd: () => calls.push("paint end"),
    bone: (x, _y, erase) => calls.push(`bone ${x}${erase ? " erase" : ""}`),
    boneEnd: () => calls.push("bone end"),
    joint: (x, _y, pressed) => calls.push(`joint ${pressed ? "press" : "drag"} ${x}`),
    jointEnd: () => calls.push("joint end"),
    pan: (dx, dy) => calls.push(`pan ${dx} ${dy}`),
    zoom: (x, y, factor) => calls.push(`zoom ${x} ${y} ${factor}`),
  };
  const gestures = new Gestures(host, {
    now: () => time,
    later: (ms, run) => {
      const timer = { at: time + ms, run, cancelled: false };
      timers.push(timer);
      return () => (timer.cancelled = true);
    },
  });
  const sample = (id: number, x: number, more: Partial<PointerSample> = {}): PointerSample => ({
    id,
    client: [x, 0],
    shape: [x, 0],
    kind: "mouse",
    button: 0,
    alt: false,
    shift: false,
    ...more,
  });
  return {
    gestures,
    calls,
    handles,
    sample,
    holdSpace: (held: boolean) => (space = held),
    /** Time passes: due timers run. */
    wait(ms: number) {
      time += ms;
      for (const t of timers.filter((t) => !t.cancelled && t.at <= time)) {
        t.cancelled = true;
        t.run();
      }
    },
  };
}

describe("pointer gestures", () => {
  it("a press on the shape adds a handle and drags it; the release leaves it as a pin", () => {
    const { gestures, calls, sample } = fixture();
    expect(gestures.stateOf(1)).toBe("idle");
    expect(gestures.down(sample(1, 3))).toBe("dragging-handle");
    gestures.move(sample(1, 4));
    gestures.up(1);
    expect(gestures.stateOf(1)).toBe("idle");
    expect(calls).toEqual(["begin", "add 3", "grab 0 by 1", "drag 0 to 4", "release 0"]);
  });

  it("a press on a handle grabs it; one another pointer holds is refused", () => {
    const { gestures, calls, sample } = fixture({ handles: [5] });
    expect(gestures.down(sample(1, 5))).toBe("dragging-handle");
    expect(gestures.down(sample(2, 5))).toBeUndefined();
    expect(gestures.stateOf(2)).toBe("idle");
    expect(calls).toEqual(["begin", "grab 0 by 1", "begin"]);
  });

  it("an Alt-press on a handle, or a press on its ring, turns it", () => {
    const alt = fixture({ handles: [5] });
    expect(alt.gestures.down(alt.sample(1, 5, { alt: true }))).toBe("turning");
    alt.gestures.move(alt.sample(1, 6));
    alt.gestures.up(1);
    expect(alt.calls).toEqual(["begin", "turn 0", "turning to 6", "release 0"]);
    const ring = fixture({ handles: [5], ring: 5 });
    expect(ring.gestures.down(ring.sample(1, 7))).toBe("turning");
  });

  it("a press off the shape clears the selection and pans; so do the middle button and Space", () => {
    const { gestures, calls, sample, holdSpace } = fixture();
    expect(gestures.down(sample(1, 20, { shift: true }))).toBe("panning");
    gestures.move(sample(1, 23));
    gestures.up(1);
    expect(calls).toEqual(["begin", "off additive", "pan 3 0"]);
    expect(gestures.down(sample(2, 3, { button: 1 }))).toBe("panning");
    gestures.up(2);
    holdSpace(true);
    expect(gestures.down(sample(3, 3))).toBe("panning");
  });

  it("the brush paints (Alt erases) and the bone tool draws a bone, each until released", () => {
    const brush = fixture({ tool: "stiffness", handles: [5] });
    expect(brush.gestures.down(brush.sample(1, 5))).toBe("painting");
    brush.gestures.move(brush.sample(1, 6, { alt: true }));
    brush.gestures.up(1);
    expect(brush.calls).toEqual(["begin", "paint 5", "erase 6", "paint end"]);
    const bone = fixture({ tool: "bone" });
    expect(bone.gestures.down(bone.sample(1, 2))).toBe("drawing-bone");
    bone.gestures.move(bone.sample(1, 8));
    bone.gestures.up(1);
    expect(bone.calls).toEqual(["begin", "bone 2", "bone 8", "bone end"]);
  });

  it("the joint tool takes (or adds) a joint on press, moves it with the pointer and puts it down on release", () => {
    const joint = fixture({ tool: "joint", handles: [5] });
    expect(joint.gestures.down(joint.sample(1, 5))).toBe("moving-joint");
    joint.gestures.move(joint.sample(1, 7));
    joint.gestures.up(1);
    expect(joint.gestures.stateOf(1)).toBe("idle");
    // A handle under the press is not grabbed: the press is the joint tool's.
    expect(joint.calls).toEqual(["begin", "joint press 5", "joint drag 7", "joint end"]);
  });

  it("a long still press of a pen on a handle removes it; a mouse's, or a press that moved, does not", () => {
    const pen = fixture({ handles: [5] });
    pen.gestures.down(pen.sample(1, 5, { kind: "pen" }));
    pen.wait(LONG_PRESS_MS - 1);
    expect(pen.gestures.stateOf(1)).toBe("dragging-handle");
    pen.wait(1);
    expect(pen.gestures.stateOf(1)).toBe("idle");
    expect(pen.calls.at(-1)).toBe("remove 0");
    pen.gestures.up(1);
    expect(pen.calls.at(-1)).toBe("remove 0");

    const mouse = fixture({ handles: [5] });
    mouse.gestures.down(mouse.sample(1, 5));
    mouse.wait(2 * LONG_PRESS_MS);
    expect(mouse.gestures.stateOf(1)).toBe("dragging-handle");

    const moved = fixture({ handles: [5] });
    moved.gestures.down(moved.sample(1, 5, { kind: "touch" }));
    moved.gestures.move(moved.sample(1, 5 + STILL_PIXELS, { kind: "touch" }));
    moved.wait(LONG_PRESS_MS);
    expect(moved.gestures.stateOf(1)).toBe("dragging-handle");
  });

  it("a second finger just after one that added a handle pinches: the handle is given back", () => {
    const { gestures, calls, sample, wait } = fixture();
    const touch = { kind: "touch" } as const;
    expect(gestures.down(sample(1, 2, touch))).toBe("dragging-handle");
    wait(PINCH_WINDOW_MS - 10);
    expect(gestures.down(sample(2, 8, touch))).toBe("pinching");
    expect(gestures.stateOf(1)).toBe("pinching");
    expect(calls).toEqual(["begin", "add 2", "grab 0 by 1", "remove 0"]);
    // Apart from 6 to 8 pixels: the midpoint moves by 1, the view zooms by 8/6 about it.
    gestures.move(sample(2, 10, touch));
    expect(calls.slice(-2)).toEqual(["pan 1 0", `zoom 6 0 ${8 / 6}`]);
    gestures.up(1);
    expect(gestures.stateOf(2)).toBe("panning");
  });

  it("a second finger later drags a handle of its own; two fingers off the shape pinch", () => {
    const late = fixture();
    const touch = { kind: "touch" } as const;
    late.gestures.down(late.sample(1, 2, touch));
    late.wait(PINCH_WINDOW_MS + 1);
    expect(late.gestures.down(late.sample(2, 8, touch))).toBe("dragging-handle");
    expect(late.gestures.stateOf(1)).toBe("dragging-handle");

    const off = fixture();
    expect(off.gestures.down(off.sample(1, 20, touch))).toBe("panning");
    expect(off.gestures.down(off.sample(2, 5, touch))).toBe("pinching");
    expect(off.gestures.stateOf(1)).toBe("pinching");
    expect(off.handles).toEqual([]);
  });
});
