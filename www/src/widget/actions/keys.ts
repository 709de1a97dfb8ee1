/**
 * The widget's keyboard shortcuts, as commands (pure: the widget carries them out), and
 * the list the help panel shows. Keys typed into a text field or list belong to it: no
 * shortcut fires there, and Space and Enter on a button or checkbox press it.
 */

export type KeyCommand =
  | { kind: "undo" }
  | { kind: "redo" }
  | { kind: "delete" }
  /** Move the selected handles by (dx, dy) CSS pixels, y up. */
  | { kind: "nudge"; dx: number; dy: number }
  | { kind: "deselect" }
  | { kind: "toggle"; what: "wireframe" | "field" }
  | { kind: "fit" }
  | { kind: "zoom"; factor: number }
  | { kind: "help" }
  /** The stiffness brush on or off. */
  | { kind: "brush" }
  /** The bone tool on or off. */
  | { kind: "bones" }
  /** The brush's size times `factor`. */
  | { kind: "brush-size"; factor: number }
  /** The selected handles' parts in front of the others (1) or behind them (-1). */
  | { kind: "layer"; step: 1 | -1 }
  /** Capture the pose as an animation key at the playhead. */
  | { kind: "capture-key" };

export interface KeyPress {
  key: string;
  ctrlKey: boolean;
  metaKey: boolean;
  altKey: boolean;
  shiftKey: boolean;
}

/** Where the key press happened: a text field or list, a button or checkbox, or elsewhere. */
export type KeyFocus = "text" | "control" | "other";

/** Zoom step of the + and - keys. */
export const ZOOM_STEP = 1.25;
/** Brush size step of the [ and ] keys. */
export const BRUSH_STEP = 1.25;

/** The command of a key press, or undefined for keys the widget leaves alone. */
export function keyCommand(e: KeyPress, focus: KeyFocus = "other"): KeyCommand | undefined {
  if (focus === "text") return undefined;
  const mod = e.ctrlKey || e.metaKey;
  const key = e.key.toLowerCase();
  if (focus === "control" && (key === " " || key === "enter")) return undefined;
  if (mod && key === "z") return { kind: e.shiftKey ? "redo" : "undo" };
  if (mod && key === "y") return { kind: "redo" };
  if (mod && key === "]") return { kind: "layer", step: 1 };
  if (mod && key === "[") return { kind: "layer", step: -1 };
  if (mod || e.altKey) return undefined;
  if (key === "delete" || key === "backspace") return { kind: "delete" };
  const step = e.shiftKey ? 10 : 1;
  const arrows: Record<string, [number, number]> = {
    arrowleft: [-step, 0],
    arrowright: [step, 0],
    arrowup: [0, step],
    arrowdown: [0, -step],
  };
  const arrow = arrows[key];
  if (arrow) return { kind: "nudge", dx: arrow[0], dy: arrow[1] };
  if (key === "escape") return { kind: "deselect" };
  if (key === "w") return { kind: "toggle", what: "wireframe" };
  if (key === "v") return { kind: "toggle", what: "field" };
  if (key === "f" || key === "0") return { kind: "fit" };
  if (key === "+" || key === "=") return { kind: "zoom", factor: ZOOM_STEP };
  if (key === "-") return { kind: "zoom", factor: 1 / ZOOM_STEP };
  if (key === "?") return { kind: "help" };
  if (key === "pageup") return { kind: "layer", step: 1 };
  if (key === "pagedown") return { kind: "layer", step: -1 };
  if (key === "b") return { kind: "brush" };
  if (key === "o") return { kind: "bones" };
  if (key === "k") return { kind: "capture-key" };
  if (key === "[") return { kind: "brush-size", factor: 1 / BRUSH_STEP };
  if (key === "]") return { kind: "brush-size", factor: BRUSH_STEP };
  return undefined;
}

/** Where a key event came from, by the element that has focus inside the widget. */
export function keyFocus(target: EventTarget | null): KeyFocus {
  const element = target as HTMLElement | null;
  if (!element || typeof element.tagName !== "string") return "other";
  const tag = element.tagName.toLowerCase();
  if (tag === "textarea" || tag === "select" || element.isContentEditable) return "text";
  if (tag === "input") {
    const type = (element as HTMLInputElement).type;
    return ["checkbox", "radio", "button", "submit", "reset", "file", "color", "range"].includes(type)
      ? "control"
      : "text";
  }
  return tag === "button" || tag === "summary" ? "control" : "other";
}

/** What the help panel lists: gestures and keys, in the order a new user needs them. */
export const HELP: readonly { keys: string; does: string }[] = [
  { keys: "Click or tap the shape", does: "add a handle there and drag it right away" },
  { keys: "Drag a handle", does: "pose; the other handles are pins and stay" },
  { keys: "Double-click, or long-press, a handle", does: "remove it" },
  { keys: "Click a handle, Shift-click for more", does: "select" },
  { keys: "Arrows (Shift: ×10)", does: "nudge the selected handles by 1 px" },
  { keys: "Delete or Backspace", does: "remove the selected handles" },
  { keys: "Esc", does: "deselect; close this panel" },
  { keys: "Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y", does: "undo, redo" },
  { keys: "Wheel or pinch; + and -", does: "zoom" },
  { keys: "Drag the background, Space-drag, two fingers", does: "pan the view" },
  { keys: "K", does: "animation: capture the pose as a key at the playhead (the timeline strip under the stage)" },
  { keys: "Space (tap)", does: "play or pause the animation" },
  {
    keys: "Timeline: drag the playhead (or arrows, Home, End on it); drag a key; Delete",
    does: "scrub (each frame's pose shows); move the key; delete the selected key",
  },
  { keys: "F or 0", does: "fit the shape in view" },
  { keys: "W", does: "wireframe" },
  { keys: "V", does: "velocity field arrows" },
  {
    keys: "B; drag on the shape",
    does: "stiffness brush: paint stiff (blue) or soft (orange) regions; Alt-drag erases; B again to pose",
  },
  { keys: "[ and ]", does: "brush smaller, larger" },
  {
    keys: "O; drag on the shape",
    does: "bone tool: draw a bone from end to end (it moves as one rigid piece, AKAP and ARAP); Alt-click removes one; O again to pose",
  },
  {
    keys: "Ctrl+] or Page Up, Ctrl+[ or Page Down",
    does: "bring the selected handle's part in front of the others, send it behind (a dragged part comes to the front by itself)",
  },
  {
    keys: "Train (toolbar)",
    does:
      "train a rig for the handles placed (in the background; keep posing); it then poses with " +
      "the method Trained (DefOp) until the handles change",
  },
  { keys: "Drop a .defop file", does: "open a trained rig: it poses at once" },
  { keys: "?", does: "this help" },
];
