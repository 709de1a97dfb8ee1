/**
 * What the overlay shows of the pointer: where it is over the shape (the brush's outline
 * follows it, and a selected handle's turning ring shows when it comes near), whether the
 * last press was a finger's (selected handles then show their rings: a finger cannot
 * hover), and the bone being drawn with the bone tool.
 */
import type { Posing } from "../model/posing.js";
import type { WidgetSettings } from "../options.js";

/** What the pointer's state reads of the widget. */
export interface PointerStateHost {
  readonly settings: Pick<WidgetSettings, "tool">;
  readonly posing: Posing;
  draw(): void;
}

export class PointerState {
  /** Where the pointer is over the shape (shape units), if anywhere. */
  at: [number, number] | undefined;
  /** Whether the last press was a finger's. */
  touch = false;
  /** The bone being drawn: from the press to the pointer (shape units). */
  boneDraft: [number, number, number, number] | undefined;
  /** The joint being moved with the joint tool: its index and where the pointer has it (shape units). */
  jointDraft: { index: number; start: [number, number]; at: [number, number]; moved: boolean } | undefined;
  readonly #host: PointerStateHost;

  constructor(host: PointerStateHost) {
    this.#host = host;
  }

  /** The pointer is over the canvas at `at` (or gone): drawn again when the brush or a ring shows it. */
  hover(at: [number, number] | undefined): void {
    this.at = at;
    if (this.#host.settings.tool === "stiffness" || this.#host.posing.handles.some((h) => h.selected)) {
      this.#host.draw();
    }
  }
}
