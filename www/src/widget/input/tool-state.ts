/**
 * The widget's stiffness brush: which tool a press on the shape uses (pose or paint), the
 * brush's size and value, where its outline is drawn (the pointer's place, which also shows
 * a selected handle's turning ring), and the dabs the API makes. What a
 * dab paints is {@link Posing.paint}'s; this file is the page side of it.
 */
import { METHODS } from "../model/methods.js";
import { brushSettings, checkTool, type WidgetSettings, type WidgetTool } from "../options.js";
import { coded } from "../../internal/arrays.js";
import { boneEnds } from "../model/bones.js";
import { locate } from "../model/picking.js";
import type { Posing } from "../model/posing.js";
import type { Stage } from "../view/stage.js";
import { BRUSH_SIZE_RANGE, type BrushSettings } from "../model/stiffness.js";
import type { Toolbar } from "../chrome/toolbar.js";

/** What the brush needs of the widget. */
export interface BrushHost {
  readonly settings: WidgetSettings;
  readonly posing: Posing;
  readonly stage: Stage;
  readonly toolbar: Toolbar | undefined;
  draw(): void;
  /** Runs one undoable change. */
  gesture(change: () => void): void;
}

export class Brush {
  /** Where the brush's outline is drawn (the pointer over the shape, shape units), if anywhere. */
  at: [number, number] | undefined;
  /** Whether the last press was a finger's: selected handles then show their turning rings. */
  touch = false;
  /** The bone being drawn with the bone tool: from the press to the pointer (shape units). */
  boneDraft: [number, number, number, number] | undefined;
  readonly #host: BrushHost;

  constructor(host: BrushHost) {
    this.#host = host;
  }

  /**
   * Turns the brush on (`"stiffness"`) or off (`"pose"`) and/or changes it; throws (code
   * `invalid-option`), changing nothing, for an unknown tool or a brush out of range.
   */
  setTool(tool: WidgetTool, brush: Partial<BrushSettings> = {}): void {
    const { settings, posing, stage, toolbar } = this.#host;
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
    this.#host.draw();
  }

  /** The brush (B) or the bone tool (O) on or off. */
  toggle(tool: "stiffness" | "bone" = "stiffness"): void {
    this.setTool(this.#host.settings.tool === tool ? "pose" : tool);
  }

  /** The brush's size times `factor`, within its range ([ and ]). */
  resize(factor: number): void {
    const [low, high] = BRUSH_SIZE_RANGE;
    const size = Math.round(Math.min(high, Math.max(low, this.#host.settings.brush.size * factor)));
    this.setTool(this.#host.settings.tool, { size });
  }

  /**
   * The pointer is over the canvas at `at` (or gone): the brush's outline follows it, and a
   * selected handle's turning ring shows when it comes near.
   */
  hover(at: [number, number] | undefined): void {
    this.at = at;
    if (this.#host.settings.tool === "stiffness" || this.#host.posing.handles.some((h) => h.selected)) {
      this.#host.draw();
    }
  }

  /** The brush's radius in shape units: its size in CSS pixels at the current zoom. */
  radius(): number {
    const { stage, settings } = this.#host;
    return (settings.brush.size * stage.ratio) / stage.camera.view.scale;
  }

  /** Adds a bone between two shape points in the pose on screen (see `Widget.addBone`); its index. */
  addBone(x0: number, y0: number, x1: number, y1: number): number {
    const { posing } = this.#host;
    const tolerance = 1e-9 * posing.shape.size;
    const at = (x: number, y: number) =>
      locate(posing.deformer.positionsView(), posing.shape.mesh.triangles, x, y, tolerance);
    const [from, to] = [at(x0, y0), at(x1, y1)];
    if (!from || !to) {
      throw coded(
        new Error(`a bone's ends must lie on the shape; (${from ? x1 : x0}, ${from ? y1 : y0}) does not`),
        "invalid-argument",
      );
    }
    this.#host.gesture(() => posing.bones.set([...posing.bones.list, { ends: [from, to] }]));
    return posing.bones.list.length - 1;
  }

  /** The bones' ends in the current pose (see `Widget.bones`). */
  boneEnds(): Float64Array {
    const { posing } = this.#host;
    return boneEnds(posing.bones.list, posing.deformer.positionsView(), posing.shape.mesh.triangles);
  }

  /** Removes one bone, or all (see `Widget.removeBone`, `Widget.clearBones`); undoable. */
  removeBone(index: number | "all"): void {
    const { posing } = this.#host;
    const list = posing.bones.list;
    if (index === "all") {
      if (list.length > 0) this.#host.gesture(() => posing.bones.set([]));
      return;
    }
    if (!Number.isInteger(index) || index < 0 || index >= list.length) {
      throw coded(new RangeError(`no bone ${index}; there are ${list.length}`), "invalid-argument");
    }
    this.#host.gesture(() => posing.bones.set(list.filter((_, k) => k !== index)));
  }

  /** One dab at (x, y) as a stroke of one point (see `Widget.paintAt`). */
  paintAt(x: number, y: number, value: number, radius = this.radius()): void {
    const { posing, settings } = this.#host;
    brushSettings(settings.brush, { value });
    if (!(radius > 0)) throw new RangeError(`the brush radius must be above 0, not ${radius}`);
    this.#host.gesture(() => {
      posing.paint(x, y, radius, value);
      posing.flushStiffness();
    });
  }
}
