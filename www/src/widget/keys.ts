/** The widget's keyboard shortcuts, as commands (pure: the widget carries them out). */

export type KeyCommand =
  | { kind: "undo" }
  | { kind: "redo" }
  | { kind: "delete" }
  /** Move the selected handles by (dx, dy) CSS pixels, y up. */
  | { kind: "nudge"; dx: number; dy: number }
  | { kind: "deselect" }
  | { kind: "toggle"; what: "wireframe" | "field" };

export interface KeyPress {
  key: string;
  ctrlKey: boolean;
  metaKey: boolean;
  altKey: boolean;
  shiftKey: boolean;
}

/** The command of a key press, or undefined for keys the widget leaves alone. */
export function keyCommand(e: KeyPress): KeyCommand | undefined {
  const mod = e.ctrlKey || e.metaKey;
  const key = e.key.toLowerCase();
  if (mod && key === "z") return { kind: e.shiftKey ? "redo" : "undo" };
  if (mod && key === "y") return { kind: "redo" };
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
  if (key === "f") return { kind: "toggle", what: "field" };
  return undefined;
}
