/**
 * Actions on the pose and its handles: undo and redo, reset, adding, removing, selecting,
 * nudging and reordering handles; and the pointer gestures on handles, described here for
 * the help (the input's state machine performs them).
 */
import { action, type Gesture } from "./action.js";
import { stepDepth } from "../model/puppet.js";
import { removeJoint } from "./tools.js";
import type { WidgetParts } from "./context.js";

/** Undo (or redo, `forward`); a success clears the messages. */
function travel(parts: WidgetParts, forward: boolean): boolean {
  const moved = parts.posing.travel(forward);
  if (moved) parts.stage.status.succeeded();
  return moved;
}

export const addHandle = action({
  name: "add-handle",
  description: "Adds a handle at a shape point (shape units); its index, or -1 off the shape",
  help: [{ keys: "Click or tap the shape", does: "add a handle there and drag it right away" }],
  perform(parts, { x, y }: { x: number; y: number }): number {
    const posing = parts.posing;
    const point = posing.pointAt(x, y);
    if (!point) return -1;
    parts.gesture(() => posing.addHandle(point));
    return posing.handles.length - 1;
  },
});

export const dragHandle: Gesture = {
  name: "drag-handle",
  description: "Drags a handle with the pointer",
  help: [{ keys: "Drag a handle", does: "pose; the other handles are pins and stay" }],
};

export const removeHandle = action({
  name: "remove-handle",
  description: "Removes a handle by index",
  help: [{ keys: "Double-click, or long-press, a handle", does: "remove it" }],
  perform(parts, { index }: { index: number }): void {
    const posing = parts.posing;
    if (!(index >= 0 && index < posing.handles.length)) throw new RangeError(`there is no handle ${index}`);
    parts.gesture(() => {
      posing.handles.splice(index, 1);
      posing.applyHandles();
    });
  },
});

export const selectHandle: Gesture = {
  name: "select-handle",
  description: "Selects handles with the pointer",
  help: [{ keys: "Click a handle, Shift-click for more", does: "select" }],
};

/** Moves the selected handles by (dx, dy) CSS pixels, y up. */
export const nudge = action({
  name: "nudge",
  description: "Moves the selected handles by a few pixels",
  help: [{ keys: "Arrows (Shift: ×10)", does: "nudge the selected handles by 1 px" }],
  keys: (
    [
      ["arrowleft", -1, 0],
      ["arrowright", 1, 0],
      ["arrowup", 0, 1],
      ["arrowdown", 0, -1],
    ] as const
  ).map(([key, x, y]) => ({
    keys: [key],
    args: (press: { shiftKey: boolean }) => ({ dx: x * (press.shiftKey ? 10 : 1), dy: y * (press.shiftKey ? 10 : 1) }),
  })),
  perform(parts, { dx, dy }: { dx: number; dy: number }): void {
    const { posing, stage } = parts;
    const selected = posing.handles.filter((h) => h.selected);
    const unit = stage.ratio / stage.camera.view.scale;
    const [x, y] = [dx * unit, dy * unit];
    if (selected.length === 0) return;
    parts.gesture(() => posing.nudge(selected, x, y));
  },
});

/** Removes the selected handles (with the joint tool, the selected joint). */
export const deleteSelected = action({
  name: "delete",
  description: "Removes the selected handles (with the joint tool, the selected joint)",
  help: [
    { keys: "Delete or Backspace", does: "remove the selected handles (with the joint tool, the selected joint)" },
  ],
  keys: [{ keys: ["delete", "backspace"] }],
  perform(parts): void {
    const posing = parts.posing;
    if (parts.settings.tool === "joint" && posing.selectedJoint !== undefined) {
      removeJoint.perform(parts, {});
      return;
    }
    const keep = posing.handles.filter((h) => !h.selected);
    if (keep.length < posing.handles.length) {
      parts.gesture(() => {
        posing.handles = keep;
        posing.applyHandles();
      });
    }
  },
});

export const deselect = action({
  name: "deselect",
  description: "Deselects every handle and closes the help",
  help: [{ keys: "Esc", does: "deselect; close this panel" }],
  keys: [{ keys: ["escape"] }],
  perform(parts): void {
    if (parts.helpOpen()) parts.toggleHelp(false);
    parts.posing.handles.forEach((h) => (h.selected = false));
    parts.draw();
  },
});

export const undo = action({
  name: "undo",
  description: "Undoes the last gesture; false when there is none",
  help: [{ keys: "Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y", does: "undo, redo" }],
  keys: [{ keys: ["z"], mod: true, shift: false }],
  controls: [
    {
      kind: "button",
      id: "undo",
      text: "Undo",
      title: "Undo the last gesture (Ctrl+Z)",
      refresh: (state) => ({ disabled: !state.canUndo }),
    },
  ],
  perform: (parts): boolean => travel(parts, false),
});

export const redo = action({
  name: "redo",
  description: "Redoes the gesture undone last; false when there is none",
  keys: [
    { keys: ["z"], mod: true, shift: true },
    { keys: ["y"], mod: true },
  ],
  controls: [
    {
      kind: "button",
      id: "redo",
      text: "Redo",
      title: "Redo (Ctrl+Shift+Z or Ctrl+Y)",
      refresh: (state) => ({ disabled: !state.canRedo }),
    },
  ],
  perform: (parts): boolean => travel(parts, true),
});

export const reset = action({
  name: "reset",
  description: "Back to the rest pose; handles stay, at their rest places",
  controls: [{ kind: "button", id: "reset", text: "Reset", title: "Back to the rest pose" }],
  perform(parts): void {
    parts.gesture(() => parts.posing.reset());
  },
});

export const clearHandles = action({
  name: "clear-handles",
  description: "Removes every handle (the pose stays)",
  controls: [{ kind: "button", id: "clear-handles", text: "Clear handles", title: "Remove every handle" }],
  perform(parts): void {
    const posing = parts.posing;
    if (posing.handles.length === 0) return;
    parts.gesture(() => {
      posing.handles = [];
      posing.applyHandles();
    });
  },
});

/**
 * The selected handles' parts in front of every other part (`step` 1) or behind them
 * (-1); undoable; false when no handle is selected.
 */
export const layer = action({
  name: "layer",
  description: "Brings the selected handles' parts to the front, or sends them to the back",
  help: [
    {
      keys: "Ctrl+] or Page Up, Ctrl+[ or Page Down",
      does: "bring the selected handle's part in front of the others, send it behind (a dragged part comes to the front by itself)",
    },
  ],
  keys: [
    { keys: ["]"], mod: true, args: { step: 1 } },
    { keys: ["["], mod: true, args: { step: -1 } },
    { keys: ["pageup"], args: { step: 1 } },
    { keys: ["pagedown"], args: { step: -1 } },
  ],
  controls: [
    {
      kind: "button",
      id: "bring-forward",
      text: "Forward",
      title: "Bring the selected handle's part in front of the others (Ctrl+] or Page Up)",
      args: { step: 1 },
    },
    {
      kind: "button",
      id: "send-back",
      text: "Back",
      title: "Send the selected handle's part behind the others (Ctrl+[ or Page Down)",
      args: { step: -1 },
    },
  ],
  perform(parts, { step }: { step: 1 | -1 }): boolean {
    const posing = parts.posing;
    let moved = false;
    const puppet = posing.shape.puppet;
    if (puppet) {
      // A puppet's parts move one step in depth: the parts of the selected handles.
      const chosen = [
        ...new Set(posing.handles.filter((h) => h.selected).map((h) => puppet.partOf[h.point.triangle]!)),
      ];
      if (chosen.length === 0) {
        parts.stage.status.info(
          "Select a handle on a part first (click it) to bring the part forward or send it back.",
        );
        return false;
      }
      // Nothing to undo when no part can move.
      if (chosen.some((k) => posing.depths && stepDepth(posing.depths, k, step))) {
        parts.gesture(() => {
          for (const part of chosen) moved = posing.reorderPart(part, step) || moved;
        });
      }
      if (!moved) {
        const names = chosen.map((k) => puppet.parts[k]!.name).join(", ");
        parts.stage.status.info(
          `${names} ${chosen.length === 1 ? "is" : "are"} already at the ${step > 0 ? "front" : "back"}.`,
        );
      }
      return moved;
    }
    if (posing.handles.some((h) => h.selected)) parts.gesture(() => (moved = posing.reorder(step)));
    else parts.stage.status.info("Select a handle first (click it) to bring its part forward or send it back.");
    return moved;
  },
});
