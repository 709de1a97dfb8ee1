/**
 * The widget's toolbar, made from the registry of actions: this file only says where each
 * action's controls go (groups, and the tool panel over the stage) and how a control of
 * each kind looks; what a control does, its text and its tooltip are its action's. Every
 * control has a label and is reachable with the keyboard. On narrow screens the tools fold
 * away behind a "☰ Tools" button, the Edit group staying in reach.
 */
import type {
  AnyAction,
  ButtonControl,
  Control,
  ControlKit,
  ControlPlace,
  ControlView,
  ToolbarInit,
} from "../actions/action.js";
import type { ButtonState, RigButtonState, ToolbarView } from "../actions/context.js";
import { ACTIONS } from "../actions/registry.js";
import type { WidgetSettings } from "../options.js";
import { Cancelled } from "../shapes/shape-maker.js";

/** Where the controls go, by id (a control's `id`), group by group. */
const LAYOUT: readonly { label: string; in: "bar" | "quick"; controls: readonly string[] }[] = [
  { label: "Shape", in: "bar", controls: ["shape", "open", "part", "remesh"] },
  { label: "Method", in: "bar", controls: ["method", "no-foldovers"] },
  { label: "Display", in: "bar", controls: ["wireframe", "field", "flipped", "paper-mode", "hud"] },
  { label: "Tools", in: "bar", controls: ["tool"] },
  { label: "Trained rig", in: "bar", controls: ["train", "save-rig", "open-rig", "region", "compare"] },
  // Always in reach, also with the tools folded away.
  { label: "Edit", in: "quick", controls: ["undo", "redo", "reset", "fit", "help"] },
  { label: "Handles", in: "bar", controls: ["clear-handles", "bring-forward", "send-back", "start-over"] },
  { label: "Session", in: "bar", controls: ["record", "replay", "save-session", "load-session"] },
  { label: "Export", in: "bar", controls: ["export-json", "export-obj", "export-svg", "export-png"] },
];

/** The tool panel's sections: the brush's controls (after the tool's own fields), the bones' and the joints'. */
const PANEL = {
  brush: ["clear-stiffness"],
  bones: { text: "Drag from end to end; Alt-click removes ", controls: ["clear-bones"] },
  joints: { text: "Drag a joint to move it; click where two parts overlap to add one ", controls: ["remove-joint"] },
} as const;

/** The toolbar, as the widget holds it. */
export interface Toolbar extends ToolbarView {
  element: HTMLElement;
  /** The tool's controls (the brush's, or the bones'), shown while that tool is on; the widget puts it on the stage. */
  brushPanel: HTMLElement;
}

/** Carries out an action (its result, which may be a promise). */
export type Perform = (action: AnyAction, args: unknown) => unknown;

/**
 * A control's action: run, and a failure reported (a custom control may report its own
 * kind; a cancelled one says so as information), every field then back to the settings in
 * force. False when it threw at once.
 */
function guarded(perform: Perform, kit: ControlKit, action: AnyAction, control: Control<unknown>) {
  const failed = (error: unknown): void => {
    if (control.kind === "custom" && control.failed?.(error, kit)) return;
    if (error instanceof Cancelled) kit.cancelled(error.message);
    else kit.failed(error);
  };
  return (args: unknown): boolean => {
    try {
      const result = perform(action, args);
      if (result instanceof Promise) result.catch(failed);
      return true;
    } catch (error) {
      failed(error);
      return false;
    }
  };
}

/** Builds the toolbar: each action's controls in the layout's places. */
export function buildToolbar(
  document: Document,
  perform: Perform,
  init: ToolbarInit,
  messages: Pick<ControlKit, "succeeded" | "failed" | "cancelled">,
): Toolbar {
  const element = document.createElement("div");
  element.className = "toolbar";
  // On narrow screens the tools fold away behind this button (see style.ts).
  const more = document.createElement("button");
  more.type = "button";
  more.className = "more";
  more.textContent = "☰ Tools";
  more.setAttribute("aria-expanded", "false");
  more.addEventListener("click", () => {
    const open = element.classList.toggle("open");
    more.setAttribute("aria-expanded", String(open));
  });
  const quick = document.createElement("div");
  quick.className = "quick";
  const bar = document.createElement("div");
  bar.className = "tools";
  bar.setAttribute("role", "toolbar");
  bar.setAttribute("aria-label", "Posing tools");
  element.append(more, quick, bar);

  const kit = controlKit(document, messages);
  // The tool's own controls float over the stage while it is on, so the toolbar stays short
  // and the stage keeps its size (the widget puts the panel on the stage).
  const panel = document.createElement("div");
  panel.className = "brush-panel";
  const section = (label: string): HTMLElement => {
    const s = document.createElement("div");
    s.className = "tool-controls";
    s.setAttribute("role", "group");
    s.setAttribute("aria-label", label);
    return s;
  };
  const brush = section("Stiffness brush");
  const bones = section("Bones");
  const joints = section("Joints");
  panel.append(brush, bones, joints);
  const showTool = (tool: WidgetSettings["tool"]): void => {
    panel.classList.toggle("hidden", tool === "pose");
    brush.classList.toggle("hidden", tool !== "stiffness");
    bones.classList.toggle("hidden", tool !== "bone");
    joints.classList.toggle("hidden", tool !== "joint");
  };

  const controls = new Map<string, { action: AnyAction; control: Control<unknown> }>();
  for (const action of ACTIONS.values()) {
    for (const control of (action.controls ?? []) as Control<unknown>[]) controls.set(control.id, { action, control });
  }
  const views: ControlView[] = [];
  const place = (id: string, group: HTMLElement): void => {
    const found = controls.get(id);
    if (!found) throw new Error(`the toolbar's layout names ${id}, which no action has`);
    const run = guarded(perform, kit, found.action, found.control);
    const view = buildControl(kit, { group, brush, bones, joints, showTool }, found.control, run, init);
    if (view) views.push(view);
  };
  for (const { label, in: where, controls: ids } of LAYOUT) {
    const g = document.createElement("div");
    g.className = "group";
    g.setAttribute("role", "group");
    g.setAttribute("aria-label", label);
    (where === "quick" ? quick : bar).append(g);
    for (const id of ids) place(id, g);
  }
  for (const id of PANEL.brush) place(id, brush);
  bones.append(PANEL.bones.text);
  for (const id of PANEL.bones.controls) place(id, bones);
  joints.append(PANEL.joints.text);
  for (const id of PANEL.joints.controls) place(id, joints);
  showTool(init.settings.tool);

  return {
    element,
    brushPanel: panel,
    refresh: (state) => views.forEach((v) => v.refresh?.(state)),
    showShape: (value, vertices, parts) => views.forEach((v) => v.showShape?.(value, vertices, parts)),
    showRig: (state) => views.forEach((v) => v.showRig?.(state)),
    addShape: (option) => views.forEach((v) => v.addShape?.(option)),
    sync: (settings) => views.forEach((v) => v.sync?.(settings)),
  };
}

/** One control of `action` in `place`; how it follows the widget's state. */
function buildControl(
  kit: ControlKit,
  place: ControlPlace,
  control: Control<unknown>,
  perform: (args: unknown) => boolean,
  init: ToolbarInit,
): ControlView | undefined {
  switch (control.kind) {
    case "button":
      return buttonControl(kit, place.group, control, perform, init);
    case "file": {
      const picker = kit.filePicker(place.group, control.accept, control.input, (file) => perform(control.args(file)));
      kit.button(place.group, control.text, control.title, () => picker.click(), control.id);
      return undefined;
    }
    case "checkbox": {
      const box = kit.checkbox(place.group, control.text, control.checked(init.settings), () =>
        perform(control.args(box.checked)),
      );
      box.name = control.id;
      if (control.title) box.parentElement!.title = control.title;
      return { sync: (settings) => (box.checked = control.checked(settings)) };
    }
    case "custom":
      return control.build(kit, place, perform, init);
  }
}

function buttonControl(
  kit: ControlKit,
  parent: HTMLElement,
  control: ButtonControl<unknown>,
  perform: (args: unknown) => boolean,
  init: ToolbarInit,
): ControlView | undefined {
  if (control.offered && !control.offered(init)) return undefined;
  const b = kit.button(parent, control.text, control.title, () => perform(control.args), control.id);
  const { refresh, showRig } = control;
  return {
    ...(refresh && {
      refresh(state: ButtonState) {
        const shown = refresh(state);
        if (shown.disabled !== undefined) b.disabled = shown.disabled;
        if (shown.text !== undefined) b.textContent = shown.text;
        if (shown.active !== undefined) b.classList.toggle("active", shown.active);
      },
    }),
    ...(showRig && {
      showRig(state: RigButtonState) {
        b.disabled = showRig(state).disabled;
      },
    }),
  };
}

/** The DOM of each kind of control, labelled alike, and the messages of an action. */
function controlKit(document: Document, messages: Pick<ControlKit, "succeeded" | "failed" | "cancelled">): ControlKit {
  return {
    document,
    ...messages,
    labelled(parent, text, control) {
      control.setAttribute("aria-label", text.trim());
      const label = document.createElement("label");
      label.append(text, control);
      parent.append(label);
    },
    button(parent, text, title, onClick, name = text) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = text;
      b.title = title;
      b.dataset.action = name.toLowerCase().replace(/\s+/g, "-");
      b.addEventListener("click", onClick);
      parent.append(b);
      return b;
    },
    select(options, value) {
      const s = document.createElement("select");
      for (const o of options) s.append(new Option(o.label, o.value, false, o.value === value));
      return s;
    },
    checkbox(parent, text, checked, onChange) {
      const c = document.createElement("input");
      c.type = "checkbox";
      c.checked = checked;
      c.addEventListener("change", onChange);
      const label = document.createElement("label");
      label.append(c, text);
      parent.append(label);
      return c;
    },
    number(value, min, max, step) {
      const n = document.createElement("input");
      n.type = "number";
      n.min = String(min);
      n.max = String(max);
      n.step = String(step);
      n.value = String(value);
      return n;
    },
    filePicker(parent, accept, name, chosen) {
      const picker = document.createElement("input");
      picker.type = "file";
      picker.accept = accept;
      picker.className = "hidden";
      picker.name = name;
      picker.addEventListener("change", () => {
        const file = picker.files?.[0];
        if (file) chosen(file);
        picker.value = "";
      });
      parent.append(picker);
      return picker;
    },
  };
}
