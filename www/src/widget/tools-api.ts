/**
 * The widget's API for the tools that change how the shape deforms or is drawn: depth
 * order, painted stiffness and bones (README "Embedding"). {@link Widget} extends it and
 * gives it the parts it acts on.
 */
import type { Brush } from "./input/tool-state.js";
import type { WidgetSettings, WidgetTool } from "./options.js";
import type { Posing } from "./model/posing.js";
import { unpainted, type BrushSettings } from "./model/stiffness.js";

/** What the tools act on: the widget's posing, brush and settings, its undo and its status line. */
export interface ToolParts {
  readonly posing: Posing;
  readonly brush: Brush;
  readonly settings: WidgetSettings;
  /** Runs one undoable change. */
  gesture(change: () => void): void;
  /** Shows a message under the shape. */
  info(message: string): void;
}

export abstract class WidgetTools {
  /** The widget's parts these methods act on. */
  protected abstract get tools(): ToolParts;

  // ---------------------------------------------------------------- depth order

  /**
   * Brings the selected handles' parts in front of every other part (each part of the
   * shape belongs to its nearest handle); they stay there when dragged. Undoable; false
   * when no handle is selected.
   */
  bringForward(): boolean {
    return this.#reorder(1);
  }

  /** Sends the selected handles' parts behind every other part (see {@link bringForward}). */
  sendBack(): boolean {
    return this.#reorder(-1);
  }

  /** Each handle's layer, in handle order (higher is in front). */
  handleLayers(): number[] {
    return this.tools.posing.handles.map((h) => h.layer);
  }

  #reorder(step: 1 | -1): boolean {
    let moved = false;
    if (this.tools.posing.handles.some((h) => h.selected))
      this.tools.gesture(() => (moved = this.tools.posing.reorder(step)));
    else this.tools.info("Select a handle first (click it) to bring its part forward or send it back.");
    return moved;
  }

  // ---------------------------------------------------------------- stiffness

  /** What a press on the shape does: pose, paint stiffness with the brush, or draw bones. */
  get tool(): WidgetTool {
    return this.tools.settings.tool;
  }

  /** The brush's size (CSS pixels) and the value it paints. */
  get brush(): BrushSettings {
    return { ...this.tools.settings.brush };
  }

  /**
   * Chooses the tool (`"pose"`, `"stiffness"`: the brush, `"bone"`: drawing bones) and/or
   * changes the brush; throws (code `invalid-option`), changing nothing, for an unknown tool
   * or a brush out of range.
   */
  setTool(tool: WidgetTool, brush: Partial<BrushSettings> = {}): void {
    this.tools.brush.setTool(tool, brush);
  }

  /** Each triangle's painted stiffness (a copy), or undefined when none is painted. */
  stiffness(): Float64Array | undefined {
    const s = this.tools.posing.stiffness;
    return unpainted(s) ? undefined : s!.slice();
  }

  /**
   * Paints every triangle (one value per triangle, 0.001 to 1000; undefined for none), as
   * one undoable step; throws, changing nothing, for bad values. Used by AKAP and ARAP; kept
   * (and shown) under the other methods.
   */
  setStiffness(values: ArrayLike<number> | undefined): void {
    const copy = values === undefined ? undefined : Float64Array.from(values);
    this.tools.gesture(() => this.tools.posing.setStiffness(copy));
  }

  /**
   * One dab of the brush at the shape point (x, y) in the pose on screen, as a stroke of
   * one point: `value` (default the brush's) on the triangles whose centroids lie within
   * `radius` shape units (default the brush's size on screen). Undoable.
   */
  paintAt(x: number, y: number, value = this.tools.settings.brush.value, radius?: number): void {
    this.tools.brush.paintAt(x, y, value, radius);
  }

  /**
   * Adds a bone from (x0, y0) to (x1, y1), points of the shape in the pose on screen: the
   * triangles its segment meets move as one rigid body from now on (AKAP and ARAP). Returns
   * its index; undoable. Throws (code `invalid-argument`), changing nothing, for an end off
   * the shape, a segment that leaves it, a bone touching another (leave a joint of free
   * triangles between them), or a method without bones.
   */
  addBone(x0: number, y0: number, x1: number, y1: number): number {
    return this.tools.brush.addBone(x0, y0, x1, y1);
  }

  /** The bones' ends in the current pose: x0 y0 x1 y1 per bone. */
  bones(): Float64Array {
    return this.tools.brush.boneEnds();
  }

  /** Removes bone `index` (undoable); throws (code `invalid-argument`) for no such bone. */
  removeBone(index: number): void {
    this.tools.brush.removeBone(index);
  }

  /** Removes every bone (undoable). */
  clearBones(): void {
    this.tools.brush.removeBone("all");
  }
}
