/**
 * What an action is: a command of the widget with its name, what it does, the keys that
 * run it, the help panel's line for it, the toolbar controls that run it, and `perform`,
 * which carries it out on the widget's parts. The registry (`registry.ts`) lists them;
 * the toolbar, the keyboard, the help panel and the `Widget` class's public methods all
 * read it, so a command is defined once. Types only, and the key matching.
 */
import type { ButtonState, RigButtonState, WidgetParts } from "./context.js";
import type { WidgetSettings } from "../options.js";

/** A key press as the keyboard reads it (a `KeyboardEvent`'s fields). */
export interface KeyPress {
  key: string;
  ctrlKey: boolean;
  metaKey: boolean;
  altKey: boolean;
  shiftKey: boolean;
}

/** Where the key press happened: a text field or list, a button or checkbox, or elsewhere. */
export type KeyFocus = "text" | "control" | "other";

/**
 * Keys that run an action. `keys` are `KeyboardEvent.key` values, lower case. With `mod`,
 * Ctrl (or Cmd) must be held (Alt is then free); without, neither Ctrl, Cmd nor Alt may be.
 * `shift`, when given, must match; `args` are the action's arguments for the press.
 */
export interface KeyBinding<A> {
  keys: readonly string[];
  mod?: boolean;
  shift?: boolean;
  args?: A | ((press: KeyPress) => A);
}

/** A line of the help panel: the gesture or keys, and what they do. */
export interface HelpLine {
  keys: string;
  does: string;
}

/** A button in the toolbar; `id` is its `data-action`. */
export interface ButtonControl<A> {
  kind: "button";
  id: string;
  text: string;
  title: string;
  args?: A;
  /** Offered only when this holds (e.g. "Start over" only while the work is kept). */
  offered?(init: ToolbarInit): boolean;
  /** Enabled, labelled and marked as the buttons' state says. */
  refresh?(state: ButtonState): { disabled?: boolean; text?: string; active?: boolean };
  /** Enabled as the rig's state says. */
  showRig?(state: RigButtonState): { disabled: boolean };
}

/** A button that opens a file picker (a hidden `<input type="file">` named `input`). */
export interface FileControl<A> {
  kind: "file";
  id: string;
  text: string;
  title: string;
  input: string;
  accept: string;
  args(file: File): A;
}

/** A checkbox for one setting, checked as the settings say. */
export interface CheckboxControl<A> {
  kind: "checkbox";
  /** Its `name`. */
  id: string;
  text: string;
  /** A tooltip on its label. */
  title?: string;
  checked(settings: WidgetSettings): boolean;
  args(checked: boolean): A;
}

/**
 * A control of its own making (lists, fields that go together): `build` puts its elements
 * into `place` with the toolbar's helpers and returns how it follows the widget's state.
 * `perform` runs the action, reporting a failure itself; it returns false when the action
 * threw (a promise's rejection is reported when it comes).
 */
export interface CustomControl<A> {
  kind: "custom";
  id: string;
  build(kit: ControlKit, place: ControlPlace, perform: (args: A) => boolean, init: ToolbarInit): ControlView;
  /** Reports an error of its own kind itself (true), instead of the toolbar's message. */
  failed?(error: unknown, kit: ControlKit): boolean;
}

export type Control<A> = ButtonControl<A> | FileControl<A> | CheckboxControl<A> | CustomControl<A>;

/** What the toolbar is made with. */
export interface ToolbarInit {
  settings: WidgetSettings;
  gallery: readonly { name: string }[];
  /** Whether the work is kept (then "Start over" is offered). */
  keepsWork: boolean;
}

/** Where a control puts its elements: its group, and the tool panel over the stage. */
export interface ControlPlace {
  group: HTMLElement;
  /** The stiffness brush's, the bones' and the joints' sections of the tool panel. */
  brush: HTMLElement;
  bones: HTMLElement;
  joints: HTMLElement;
  /** Shows the panel's section of the tool in use (or none for posing). */
  showTool(tool: WidgetSettings["tool"]): void;
}

/** How a control follows the widget: each method as `Toolbar`'s of the same name. */
export interface ControlView {
  sync?(settings: WidgetSettings): void;
  refresh?(state: ButtonState): void;
  showRig?(state: RigButtonState): void;
  showShape?(value: string | undefined, vertices: number, parts: { count: number; index: number }): void;
  addShape?(option: { value: string; label: string }): void;
}

/** The toolbar's helpers for controls (the DOM of each kind, labelled alike), and its messages. */
export interface ControlKit {
  readonly document: Document;
  labelled(parent: HTMLElement, text: string, control: HTMLElement): void;
  button(parent: HTMLElement, text: string, title: string, onClick: () => void, name?: string): HTMLButtonElement;
  select(options: readonly { value: string; label: string }[], value: string): HTMLSelectElement;
  checkbox(parent: HTMLElement, text: string, checked: boolean, onChange: () => void): HTMLInputElement;
  number(value: number, min: number, max: number, step: number | "any"): HTMLInputElement;
  /** A hidden file input in `parent` calling `chosen` with the file picked. */
  filePicker(parent: HTMLElement, accept: string, name: string, chosen: (file: File) => void): HTMLInputElement;
  /** The action went well: messages are out of date. */
  succeeded(): void;
  /** The action failed: its message shows, the fields go back to the settings. */
  failed(error: unknown): void;
  /** The action was cancelled: `message` shows as information. */
  cancelled(message: string): void;
}

/**
 * A command of the widget. `A` are its arguments (`void` for none), `R` what it returns to
 * the public API.
 */
export interface Action<A = void, R = unknown> {
  readonly name: string;
  /** What it does, in a few words. */
  readonly description: string;
  readonly keys?: readonly KeyBinding<A>[];
  /** Its lines in the help panel, in the registry's order. */
  readonly help?: readonly HelpLine[];
  readonly controls?: readonly Control<A>[];
  perform(parts: WidgetParts, args: A): R;
}

/** A gesture of the pointer, performed by the input's state machine: only its help line. */
export interface Gesture {
  readonly name: string;
  readonly description: string;
  readonly help: readonly HelpLine[];
}

/** An action of any arguments (the registry's element type). */
// eslint-disable-next-line @typescript-eslint/no-explicit-any
export type AnyAction = Action<any, unknown>;

/**
 * Makes an action (a typed identity: the arguments and result are inferred from `perform`,
 * which comes before `controls` in the definition so that their callbacks are typed by it).
 */
export function action<A = void, R = unknown>(definition: Action<A, R>): Action<A, R> {
  return definition;
}

/** The arguments `binding` gives for `press`, or undefined when it does not take the press. */
export function bindingArgs<A>(binding: KeyBinding<A>, press: KeyPress): { args: A } | undefined {
  const key = press.key.toLowerCase();
  const mod = press.ctrlKey || press.metaKey;
  if (!binding.keys.includes(key)) return undefined;
  if (binding.mod ? !mod : mod || press.altKey) return undefined;
  if (binding.shift !== undefined && binding.shift !== press.shiftKey) return undefined;
  const args = typeof binding.args === "function" ? (binding.args as (p: KeyPress) => A)(press) : binding.args;
  return { args: args as A };
}
