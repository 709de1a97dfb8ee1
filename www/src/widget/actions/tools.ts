/**
 * The tools (pose, the stiffness brush, bones, a puppet's joints) and what they change:
 * painted stiffness, bones and joints, through the toolbar, keys B, O, J, [ and ], and the
 * public API.
 */
import { coded } from "../../internal/arrays.js";
import { boneEnds } from "../model/bones.js";
import { METHODS } from "../model/methods.js";
import type { PuppetJoint } from "../../core.js";
import { BRUSH_SIZE_RANGE, BRUSH_VALUES, type BrushSettings } from "../model/stiffness.js";
import { brushSettings, checkTool, type WidgetTool } from "../options.js";
import { action } from "./action.js";
import type { WidgetParts } from "./context.js";

/** Brush size step of the [ and ] keys. */
export const BRUSH_STEP = 1.25;

/**
 * Chooses the tool (`"pose"`, `"stiffness"`: the brush, `"bone"`: drawing bones,
 * `"joint"`: a puppet's joints) and/or changes the brush; throws (code `invalid-option`),
 * changing nothing, for an unknown tool or a brush out of range.
 */
export const setTool = action({
  name: "tool",
  description: "Chooses what a press on the shape does (pose, paint stiffness, draw bones, edit joints) and the brush",
  perform(parts: WidgetParts, { tool, brush = {} }: { tool: WidgetTool; brush?: Partial<BrushSettings> }): void {
    const { settings, posing, stage, toolbar } = parts;
    checkTool(tool);
    settings.brush = brushSettings(settings.brush, brush);
    settings.tool = tool;
    toolbar?.sync(settings);
    if (tool === "stiffness" && !posing.deformer.hasStiffness) {
      stage.status.info(
        `${METHODS[settings.method].label} has no stiffness: the painting is kept, and used by AKAP and ARAP.`,
      );
    }
    if (tool === "bone" && !posing.deformer.hasBones) {
      stage.status.info(`${METHODS[settings.method].label} has no bones: choose AKAP or ARAP to draw them.`);
    }
    if (tool === "joint" && !posing.shape.puppet) {
      stage.status.info("Only a puppet has joints: open an SVG whose layers (top-level groups) are its parts.");
    }
    parts.draw();
  },

  controls: [
    {
      kind: "custom",
      id: "tool",
      build(kit, place, perform, init) {
        const s = init.settings;
        const changed = (): void => {
          perform({
            tool: toolList.value as WidgetTool,
            brush: { size: Number(brushSize.value), value: Number(brushValue.value) },
          });
        };
        // The tools exclude each other: one list (short, so the toolbar keeps its rows).
        const toolList = kit.select(
          [
            { value: "pose", label: "Pose" },
            { value: "stiffness", label: "Brush (B)" },
            { value: "bone", label: "Bones (O)" },
            { value: "joint", label: "Joints (J)" },
          ],
          s.tool,
        );
        toolList.name = "tool";
        toolList.title =
          "What a press on the shape does: pose with handles; paint stiffness with the brush (stiff regions bend less, " +
          "Alt-drag erases); draw bones (drag from end to end; each moves as one rigid piece, AKAP and ARAP; Alt-click removes one); " +
          "edit a puppet's joints (drag one to move it, click where two parts overlap to add one, Delete removes it)";
        kit.labelled(place.group, "Tool ", toolList);
        toolList.addEventListener("change", changed);
        // The brush's value and size float over the stage with the tool's panel.
        const brushValue = kit.select(
          BRUSH_VALUES.map((v) => ({
            value: String(v),
            label: v === 1 ? "×1 (erase)" : v < 1 ? `×${v} (softer)` : `×${v}`,
          })),
          String(s.brush.value),
        );
        brushValue.name = "brush-value";
        kit.labelled(place.brush, "Paint ", brushValue);
        const brushSize = kit.number(s.brush.size, BRUSH_SIZE_RANGE[0], BRUSH_SIZE_RANGE[1], 1);
        brushSize.name = "brush-size";
        kit.labelled(place.brush, "Size px ", brushSize);
        brushValue.addEventListener("change", changed);
        brushSize.addEventListener("change", changed);
        return {
          sync(settings) {
            toolList.value = settings.tool;
            place.showTool(settings.tool);
            brushSize.value = String(settings.brush.size);
            if (!BRUSH_VALUES.some((v) => String(v) === brushValue.value && v === settings.brush.value)) {
              // A value set through the API that the list lacks is shown as one more choice.
              const value = String(settings.brush.value);
              if (!Array.from(brushValue.options).some((o) => o.value === value))
                brushValue.append(new Option(`×${value}`, value));
              brushValue.value = value;
            }
          },
        };
      },
    },
  ],
});

/** The brush (B), the bone tool (O) or the joint tool (J) on, or back to posing. */
function toggleTool(parts: WidgetParts, tool: "stiffness" | "bone" | "joint"): void {
  setTool.perform(parts, { tool: parts.settings.tool === tool ? "pose" : tool });
}

export const brush = action({
  name: "brush",
  description: "Turns the stiffness brush on or off",
  help: [
    {
      keys: "B; drag on the shape",
      does: "stiffness brush: paint stiff (blue) or soft (orange) regions; Alt-drag erases; B again to pose",
    },
  ],
  keys: [{ keys: ["b"] }],
  perform: (parts): void => toggleTool(parts, "stiffness"),
});

export const brushSize = action({
  name: "brush-size",
  description: "Makes the brush smaller or larger",
  help: [{ keys: "[ and ]", does: "brush smaller, larger" }],
  keys: [
    { keys: ["["], args: { factor: 1 / BRUSH_STEP } },
    { keys: ["]"], args: { factor: BRUSH_STEP } },
  ],
  perform(parts, { factor }: { factor: number }): void {
    const [low, high] = BRUSH_SIZE_RANGE;
    const size = Math.round(Math.min(high, Math.max(low, parts.settings.brush.size * factor)));
    setTool.perform(parts, { tool: parts.settings.tool, brush: { size } });
  },
});

export const bones = action({
  name: "bones",
  description: "Turns the bone tool on or off",
  help: [
    {
      keys: "O; drag on the shape",
      does: "bone tool: draw a bone from end to end (it moves as one rigid piece, AKAP and ARAP); Alt-click removes one; O again to pose",
    },
  ],
  keys: [{ keys: ["o"] }],
  perform: (parts): void => toggleTool(parts, "bone"),
});

export const jointTool = action({
  name: "joints",
  description: "Turns the joint tool on or off",
  help: [
    {
      keys: "J; drag on a puppet",
      does: "joint tool: drag a joint to move it (it stays on both its parts), click where two parts overlap to add one, Delete removes the selected one; J again to pose",
    },
  ],
  keys: [{ keys: ["j"] }],
  perform: (parts): void => toggleTool(parts, "joint"),
});

/**
 * Replaces a puppet's joints (the deformer analyses its systems again), as one undoable
 * step; throws (code `invalid-joint`), changing nothing, for a part out of range or a point
 * not on both parts.
 */
export const setJoints = action({
  name: "set-joints",
  description: "Replaces a puppet's joints",
  perform(parts, { joints }: { joints: readonly PuppetJoint[] }): void {
    parts.gesture(() => parts.posing.setJoints(joints));
  },
});

/** Removes a puppet's joint by index (default: the one selected with the joint tool); undoable. */
export const removeJoint = action({
  name: "remove-joint",
  description: "Removes a puppet's joint by index, or the selected one",
  perform(parts, { index }: { index?: number }): void {
    const posing = parts.posing;
    const joints = posing.joints;
    const at = index ?? posing.selectedJoint;
    if (at === undefined) {
      parts.stage.status.info("Select a joint first (click it with the joint tool).");
      return;
    }
    if (!Number.isInteger(at) || at < 0 || at >= joints.length) {
      throw coded(new RangeError(`no joint ${at}; there are ${joints.length}`), "invalid-argument");
    }
    parts.gesture(() => {
      posing.setJoints(joints.filter((_, k) => k !== at));
      posing.selectedJoint = undefined;
    });
  },

  controls: [
    {
      kind: "button",
      id: "remove-joint",
      text: "Remove joint",
      title: "Remove the selected joint (Delete)",
      args: {},
    },
  ],
});

/**
 * Paints every triangle (one value per triangle, 0.001 to 1000; undefined for none), as
 * one undoable step; throws, changing nothing, for bad values.
 */
export const setStiffness = action({
  name: "set-stiffness",
  description: "Paints every triangle's stiffness, or none",
  perform(parts, { values }: { values: ArrayLike<number> | undefined }): void {
    const copy = values === undefined ? undefined : Float64Array.from(values);
    parts.gesture(() => parts.posing.setStiffness(copy));
  },

  controls: [
    {
      kind: "button",
      id: "clear-stiffness",
      text: "Clear",
      title: "Every triangle back to stiffness 1",
      args: { values: undefined },
    },
  ],
});

/** The brush's radius in shape units: its size in CSS pixels at the current zoom. */
export function brushRadius(parts: Pick<WidgetParts, "settings" | "stage">): number {
  const { stage, settings } = parts;
  return (settings.brush.size * stage.ratio) / stage.camera.view.scale;
}

/** One dab of the brush at (x, y) in the pose on screen, as a stroke of one point (see `Widget.paintAt`). */
export const paintAt = action({
  name: "paint-at",
  description: "Paints one dab of the brush at a shape point",
  perform(parts, { x, y, value, radius }: { x: number; y: number; value?: number; radius?: number }): void {
    const { posing, settings } = parts;
    const v = value ?? settings.brush.value;
    const r = radius ?? brushRadius(parts);
    brushSettings(settings.brush, { value: v });
    if (!(r > 0)) throw new RangeError(`the brush radius must be above 0, not ${r}`);
    parts.gesture(() => {
      posing.paint(x, y, r, v);
      posing.flushStiffness();
    });
  },
});

/** Adds a bone between two shape points in the pose on screen (see `Widget.addBone`); its index. */
export const addBone = action({
  name: "add-bone",
  description: "Adds a bone between two points of the shape",
  perform(parts, { x0, y0, x1, y1 }: { x0: number; y0: number; x1: number; y1: number }): number {
    const posing = parts.posing;
    const tolerance = 1e-9 * posing.shape.size;
    const at = (x: number, y: number) => posing.pointAt(x, y, tolerance);
    const [from, to] = [at(x0, y0), at(x1, y1)];
    if (!from || !to) {
      throw coded(
        new Error(`a bone's ends must lie on the shape; (${from ? x1 : x0}, ${from ? y1 : y0}) does not`),
        "invalid-argument",
      );
    }
    parts.gesture(() => posing.bones.set([...posing.bones.list, { ends: [from, to] }]));
    return posing.bones.list.length - 1;
  },
});

/** Removes one bone, or all (see `Widget.removeBone`, `Widget.clearBones`); undoable. */
export const removeBone = action({
  name: "remove-bone",
  description: "Removes a bone by index, or every bone",
  perform(parts, { index }: { index: number | "all" }): void {
    const posing = parts.posing;
    const list = posing.bones.list;
    if (index === "all") {
      if (list.length > 0) parts.gesture(() => posing.bones.set([]));
      return;
    }
    if (!Number.isInteger(index) || index < 0 || index >= list.length) {
      throw coded(new RangeError(`no bone ${index}; there are ${list.length}`), "invalid-argument");
    }
    parts.gesture(() => posing.bones.set(list.filter((_, k) => k !== index)));
  },

  controls: [
    { kind: "button", id: "clear-bones", text: "Clear bones", title: "Remove every bone", args: { index: "all" } },
  ],
});

/** The bones' ends in the current pose: x0 y0 x1 y1 per bone. */
export function currentBoneEnds(parts: Pick<WidgetParts, "posing">): Float64Array {
  const { posing } = parts;
  return boneEnds(posing.bones.list, posing.deformer.positionsView(), posing.shape.mesh.triangles);
}
