/**
 * What actions act on: the widget's parts (the model, the stage, the managers) and the few
 * things only the widget does (undoable gestures, messages, events). The `Widget` class
 * makes one of these and hands it to every action's `perform`; nothing else sees it.
 */
import type { Posing } from "../model/posing.js";
import type { GalleryItem, WidgetSettings } from "../options.js";
import type { AnimationController } from "../animation/controller.js";
import type { FrameLoop } from "../view/frame-loop.js";
import type { Stage } from "../view/stage.js";
import type { ShapeLoader } from "../shapes/shape-loader.js";
import type { RigManager } from "../rigs/rig-manager.js";
import type { WorkKeeper } from "../store/work-store.js";
import type { Session } from "../../session.js";

/** What buttons show of the widget's state (`Toolbar.refresh` and `Toolbar.showRig`). */
export interface ButtonState {
  canUndo: boolean;
  canRedo: boolean;
  recording: boolean;
  hasSession: boolean;
}

export interface RigButtonState {
  hasRig: boolean;
  training: boolean;
}

/** What the widget's parts may tell the toolbar (the toolbar in `chrome/` implements it). */
export interface ToolbarView {
  /** Enables and labels the buttons that depend on state. */
  refresh(state: ButtonState): void;
  /** Shows the current shape (its list value, undefined for others), vertex count and parts. */
  showShape(value: string | undefined, vertices: number, parts: { count: number; index: number }): void;
  /** Adds a shape to the list (an imported file) and shows it as the current one. */
  addShape(option: { value: string; label: string }): void;
  /** Enables the rig's buttons: Save with a rig, Train when no training runs. */
  showRig(state: RigButtonState): void;
  /** Brings every field in line with the settings (changed by keys, a load, or a refused value). */
  sync(settings: WidgetSettings): void;
}

export interface WidgetParts {
  /** The element the widget was mounted into (events are dispatched on it). */
  readonly target: HTMLElement;
  readonly document: Document;
  /** The widget's element in its shadow root (`data-replaying`, `data-idle`). */
  readonly root: HTMLElement;
  readonly settings: WidgetSettings;
  readonly posing: Posing;
  readonly stage: Stage;
  readonly frames: FrameLoop;
  readonly loader: ShapeLoader;
  readonly rigs: RigManager;
  readonly animation: AnimationController;
  readonly toolbar: ToolbarView | undefined;
  /** Keeps the work across reloads (with `storageKey`). */
  readonly keeper: WorkKeeper | undefined;
  readonly gallery: readonly GalleryItem[];
  /** The last recorded or loaded session. */
  lastSession: Session | undefined;
  /** Runs one complete gesture (an undoable unit) that is not a drag; messages are then out of date. */
  gesture(change: () => void): void;
  /** Asks for the picture to be drawn in the next animation frame. */
  draw(): void;
  /** Draws the picture now. */
  render(): void;
  /** Whether the widget was destroyed. */
  destroyed(): boolean;
  /** Shows an error in the status line (and the `akap-error` event). */
  showError(error: unknown): void;
  /** Dispatches an event on the widget's element. */
  emit(type: string, detail: unknown): void;
  /** Undo, redo, record and replay buttons as the history and recording say. */
  refreshButtons(): void;
  /** Every field of the toolbar back to the settings in force. */
  syncToolbar(): void;
  /** The rig, its state, the shape, handles or method changed: HUD, toolbar, picture. */
  rigChanged(): void;
  /** Opens or closes the help panel (toggles without an argument). */
  toggleHelp(open?: boolean): void;
  helpOpen(): boolean;
  /** Shows or hides the heads-up display. */
  showHud(visible: boolean): void;
}
