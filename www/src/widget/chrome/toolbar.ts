/**
 * The widget's toolbar: shape, density, method and lambda; display toggles; undo, redo,
 * reset, clear; the stiffness brush; record, replay, save and load sessions; exports; a trained rig's training
 * (energy, basis, samples, radius), files and display. Every control has a label and is
 * reachable with the keyboard.
 */
import type { WidgetTool } from "../options.js";
import type { RigTrainOptions } from "../model/rig.js";
import { BRUSH_SIZE_RANGE, BRUSH_VALUES, type BrushSettings } from "../model/stiffness.js";

/** The display toggles. */
export interface DisplayToggles {
  wireframe: boolean;
  field: boolean;
  flipped: boolean;
  paperMode: boolean;
  /** Keep triangles from folding over (a posing option beside the display's). */
  noFoldovers: boolean;
  region: boolean;
  compare: boolean;
}

export interface ToolbarActions {
  undo(): void;
  redo(): void;
  reset(): void;
  clear(): void;
  /** A shape from the list (`builtin:name` or `gallery:index`). */
  shape(value: string): void;
  remesh(vertices: number, minAngle: number): void;
  /** A file chosen with the picker. */
  open(file: File): void;
  /** Another separate part of the imported file. */
  part(index: number): void;
  method(method: string, lambda: number): void;
  display(options: DisplayToggles): void;
  /** The stiffness brush on (`"stiffness"`) or the bone tool (`"bone"`) or neither (`"pose"`), and what the brush paints. */
  brush(tool: WidgetTool, brush: BrushSettings): void;
  /** Removes every bone. */
  clearBones(): void;
  /** Every triangle back to stiffness 1. */
  clearStiffness(): void;
  /** The selected handles' parts in front of the others (1) or behind them (-1). */
  reorder(step: 1 | -1): void;
  /** Train a rig; `radiusPercent` of the shape's bounding-box diagonal, undefined for the default. */
  train(options: Omit<RigTrainOptions, "radius">, radiusPercent: number | undefined): void;
  saveRig(): void;
  openRig(file: File): void;
  hud(visible: boolean): void;
  record(): void;
  replay(): void;
  saveSession(): void;
  loadSession(file: File): void;
  export(format: "json" | "obj" | "svg" | "png"): void;
  /** Fit the shape into the view. */
  fit(): void;
  /** Open or close the help panel. */
  help(): void;
  /** Forget the saved work and start again with the default shape (shown when work is saved). */
  startOver?(): void;
}

export interface ToolbarSettings extends DisplayToggles {
  vertices: number;
  minAngle: number;
  method: string;
  lambda: number;
  hud: boolean;
  training: RigTrainOptions;
  tool: WidgetTool;
  brush: BrushSettings;
}

export interface Toolbar {
  element: HTMLElement;
  /** Enables and labels the buttons that depend on state. */
  refresh(state: { canUndo: boolean; canRedo: boolean; recording: boolean; hasSession: boolean }): void;
  /** Shows the current shape (its list value, undefined for others), vertex count and parts. */
  showShape(value: string | undefined, vertices: number, parts: { count: number; index: number }): void;
  /** Adds a shape to the list (an imported file) and shows it as the current one. */
  addShape(option: { value: string; label: string }): void;
  /** Enables the rig's buttons: Save with a rig, Train when no training runs. */
  showRig(state: { hasRig: boolean; training: boolean }): void;
  /** The tool's controls (the brush's, or the bones'), shown while that tool is on; the widget puts it on the stage. */
  brushPanel: HTMLElement;
  /** Brings every field in line with the settings (changed by keys, a load, or a refused value). */
  sync(settings: ToolbarSettings): void;
}

export function buildToolbar(
  document: Document,
  actions: ToolbarActions,
  init: {
    shapes: { value: string; label: string }[];
    methods: { value: string; label: string }[];
    settings: ToolbarSettings;
  },
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
  const group = (label: string, parent = bar): HTMLElement => {
    const g = document.createElement("div");
    g.className = "group";
    g.setAttribute("role", "group");
    g.setAttribute("aria-label", label);
    parent.append(g);
    return g;
  };
  const labelled = (parent: HTMLElement, text: string, control: HTMLElement): void => {
    control.setAttribute("aria-label", text.trim());
    const label = document.createElement("label");
    label.append(text, control);
    parent.append(label);
  };
  const button = (
    parent: HTMLElement,
    text: string,
    title: string,
    onClick: () => void,
    name = text,
  ): HTMLButtonElement => {
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = text;
    b.title = title;
    b.dataset.action = name.toLowerCase().replace(/\s+/g, "-");
    b.addEventListener("click", onClick);
    parent.append(b);
    return b;
  };
  const select = (options: { value: string; label: string }[], value: string): HTMLSelectElement => {
    const s = document.createElement("select");
    for (const o of options) s.append(new Option(o.label, o.value, false, o.value === value));
    return s;
  };
  const checkbox = (parent: HTMLElement, text: string, checked: boolean, onChange: () => void): HTMLInputElement => {
    const c = document.createElement("input");
    c.type = "checkbox";
    c.checked = checked;
    c.addEventListener("change", onChange);
    const label = document.createElement("label");
    label.append(c, text);
    parent.append(label);
    return c;
  };
  const number = (value: number, min: number, max: number, step: number | "any"): HTMLInputElement => {
    const n = document.createElement("input");
    n.type = "number";
    n.min = String(min);
    n.max = String(max);
    n.step = String(step);
    n.value = String(value);
    return n;
  };

  const s = init.settings;
  const shapeGroup = group("Shape");
  const shape = select(init.shapes, init.shapes[0]?.value ?? "");
  shape.name = "shape";
  labelled(shapeGroup, "Shape ", shape);
  shape.addEventListener("change", () => actions.shape(shape.value));
  const picker = document.createElement("input");
  picker.type = "file";
  picker.accept = ".svg,.png,.jpg,.jpeg,.webp,.gif,.obj,.json,.defop,image/*";
  picker.className = "hidden";
  picker.name = "shape-file";
  picker.addEventListener("change", () => {
    const chosen = picker.files?.[0];
    if (chosen) actions.open(chosen);
    picker.value = "";
  });
  shapeGroup.append(picker);
  button(
    shapeGroup,
    "Open…",
    "Open an SVG, an image, a mesh (OBJ, JSON), a session or a rig (.defop); or drop a file on the shape",
    () => picker.click(),
    "open",
  );
  const part = select([], "");
  part.name = "part";
  labelled(shapeGroup, "Part ", part);
  part.parentElement!.classList.add("hidden");
  part.addEventListener("change", () => actions.part(Number(part.value)));
  const vertices = number(s.vertices, 100, 50_000, 100);
  vertices.name = "vertices";
  labelled(shapeGroup, "Vertices ", vertices);
  const minAngle = number(s.minAngle, 0, 34, 1);
  minAngle.name = "min-angle";
  labelled(shapeGroup, "Min angle ", minAngle);
  const remesh = (): void => actions.remesh(Number(vertices.value), Number(minAngle.value));
  vertices.addEventListener("change", remesh);
  minAngle.addEventListener("change", remesh);

  const methodGroup = group("Method");
  const method = select(init.methods, s.method);
  method.name = "method";
  labelled(methodGroup, "Method ", method);
  const lambda = number(s.lambda, 0.01, 1e6, "any");
  lambda.name = "lambda";
  labelled(methodGroup, "λ ", lambda);
  const changeMethod = (): void => actions.method(method.value, Number(lambda.value));
  method.addEventListener("change", changeMethod);
  lambda.addEventListener("change", changeMethod);

  const view = group("Display");
  const display = (): void =>
    actions.display({
      wireframe: wireframe.checked,
      field: field.checked,
      flipped: flipped.checked,
      paperMode: paper.checked,
      noFoldovers: noFoldovers.checked,
      region: region.checked,
      compare: compare.checked,
    });
  const wireframe = checkbox(view, "Wireframe (W)", s.wireframe, display);
  wireframe.name = "wireframe";
  const field = checkbox(view, "Field (V)", s.field, display);
  field.name = "field";
  const flipped = checkbox(view, "Flipped", s.flipped, display);
  flipped.name = "flipped";
  const paper = checkbox(view, "Paper mode", s.paperMode, display);
  const noFoldovers = checkbox(methodGroup, "No foldovers", s.noFoldovers, display);
  noFoldovers.name = "no-foldovers";
  noFoldovers.parentElement!.title =
    "Split a step that would flip a triangle, and stop short where even small pieces would";
  paper.name = "paper-mode";
  const hud = checkbox(view, "HUD", s.hud, () => actions.hud(hud.checked));
  hud.name = "hud";

  const stiffnessGroup = group("Tools");
  const setBrush = (tool = toolList.value as WidgetTool): void =>
    actions.brush(tool, {
      size: Number(brushSize.value),
      value: Number(brushValue.value),
    });
  // The tools exclude each other: one list (short, so the toolbar keeps its rows).
  const toolList = select(
    [
      { value: "pose", label: "Pose" },
      { value: "stiffness", label: "Brush (B)" },
      { value: "bone", label: "Bones (O)" },
    ],
    s.tool,
  );
  toolList.name = "tool";
  toolList.title =
    "What a press on the shape does: pose with handles; paint stiffness with the brush (stiff regions bend less, " +
    "Alt-drag erases); draw bones (drag from end to end; each moves as one rigid piece, AKAP and ARAP; Alt-click removes one)";
  labelled(stiffnessGroup, "Tool ", toolList);
  toolList.addEventListener("change", () => setBrush());
  const brushValue = select(
    BRUSH_VALUES.map((v) => ({
      value: String(v),
      label: v === 1 ? "×1 (erase)" : v < 1 ? `×${v} (softer)` : `×${v}`,
    })),
    String(s.brush.value),
  );
  brushValue.name = "brush-value";
  // The tool's own controls float over the stage while it is on, so the toolbar stays short
  // and the stage keeps its size (the widget puts the panel on the stage): the brush's
  // value, size and Clear, or the bones' hint and Clear bones.
  const toolPanel = document.createElement("div");
  toolPanel.className = "brush-panel";
  const brushControls = document.createElement("div");
  brushControls.className = "tool-controls";
  brushControls.setAttribute("role", "group");
  brushControls.setAttribute("aria-label", "Stiffness brush");
  const boneControls = document.createElement("div");
  boneControls.className = "tool-controls";
  boneControls.setAttribute("role", "group");
  boneControls.setAttribute("aria-label", "Bones");
  toolPanel.append(brushControls, boneControls);
  labelled(brushControls, "Paint ", brushValue);
  const brushSize = number(s.brush.size, BRUSH_SIZE_RANGE[0], BRUSH_SIZE_RANGE[1], 1);
  brushSize.name = "brush-size";
  labelled(brushControls, "Size px ", brushSize);
  brushValue.addEventListener("change", () => setBrush());
  brushSize.addEventListener("change", () => setBrush());
  button(brushControls, "Clear", "Every triangle back to stiffness 1", actions.clearStiffness, "clear-stiffness");
  boneControls.append("Drag from end to end; Alt-click removes ");
  button(boneControls, "Clear bones", "Remove every bone", actions.clearBones, "clear-bones");
  const showTool = (tool: WidgetTool): void => {
    toolPanel.classList.toggle("hidden", tool === "pose");
    brushControls.classList.toggle("hidden", tool !== "stiffness");
    boneControls.classList.toggle("hidden", tool !== "bone");
  };
  showTool(s.tool);

  const rigGroup = group("Trained rig");
  const energy = select(
    [
      { value: "sarap", label: "S-ARAP" },
      { value: "arap", label: "ARAP" },
    ],
    s.training.energy ?? "sarap",
  );
  energy.name = "rig-energy";
  labelled(rigGroup, "Energy ", energy);
  const basis = select(
    ["tps", "linear", "quadratic", "cubic"].map((b) => ({ value: b, label: b === "tps" ? "TPS" : b })),
    s.training.basis ?? "tps",
  );
  basis.name = "rig-basis";
  labelled(rigGroup, "Basis ", basis);
  const samples = number(s.training.samples ?? 200, 1, 100_000, 1);
  samples.name = "rig-samples";
  labelled(rigGroup, "Samples ", samples);
  const spatial = number(s.training.spatial ?? 0, 0, 100_000, 1);
  spatial.name = "rig-spatial";
  spatial.title =
    "Size of the reduced spatial basis (0: every mesh vertex); smaller poses faster and saves smaller files";
  labelled(rigGroup, "Reduced ", spatial);
  const radius = number(15, 0.1, 1000, "any");
  radius.name = "rig-radius";
  radius.value = "";
  radius.placeholder = "15";
  radius.title = "Radius of the training discs, in % of the shape's diagonal (empty: 15)";
  labelled(rigGroup, "Radius % ", radius);
  const train = button(
    rigGroup,
    "Train",
    "Train a rig for these handles (DefOp), in workers; posing goes on meanwhile",
    () => {
      const options = {
        energy: energy.value as "sarap" | "arap",
        basis: basis.value as NonNullable<RigTrainOptions["basis"]>,
        samples: Number(samples.value),
        spatial: Number(spatial.value),
      };
      actions.train(options, radius.value === "" ? undefined : Number(radius.value));
    },
  );
  const saveRig = button(rigGroup, "Save rig", "Download the trained rig (.defop)", actions.saveRig);
  const rigFile = document.createElement("input");
  rigFile.type = "file";
  rigFile.accept = ".defop,application/octet-stream";
  rigFile.className = "hidden";
  rigFile.name = "rig-file";
  rigFile.addEventListener("change", () => {
    const chosen = rigFile.files?.[0];
    if (chosen) actions.openRig(chosen);
    rigFile.value = "";
  });
  rigGroup.append(rigFile);
  button(rigGroup, "Open rig…", "Open a trained rig (.defop): it poses at once", () => rigFile.click(), "open-rig");
  const region = checkbox(rigGroup, "Region", s.region, display);
  region.name = "region";
  const compare = checkbox(rigGroup, "Compare", s.compare, display);
  compare.name = "compare";

  // Always in reach, also with the tools folded away.
  const edit = group("Edit", quick);
  const undo = button(edit, "Undo", "Undo the last gesture (Ctrl+Z)", actions.undo);
  const redo = button(edit, "Redo", "Redo (Ctrl+Shift+Z or Ctrl+Y)", actions.redo);
  button(edit, "Reset", "Back to the rest pose", actions.reset);
  button(edit, "Fit", "Fit the shape into the view (F)", actions.fit);
  button(edit, "?", "Gestures and keys (?)", actions.help, "help");
  const tidy = group("Handles");
  button(tidy, "Clear handles", "Remove every handle", actions.clear);
  button(
    tidy,
    "Forward",
    "Bring the selected handle's part in front of the others (Ctrl+] or Page Up)",
    () => actions.reorder(1),
    "bring-forward",
  );
  button(
    tidy,
    "Back",
    "Send the selected handle's part behind the others (Ctrl+[ or Page Down)",
    () => actions.reorder(-1),
    "send-back",
  );
  if (actions.startOver) {
    button(tidy, "Start over", "Forget the saved work and start again with the default shape", actions.startOver);
  }

  const session = group("Session");
  const record = button(session, "Record", "Record the interaction", actions.record);
  const replay = button(session, "Replay", "Replay the last recording", actions.replay);
  const save = button(session, "Save", "Save the last recording as JSON", actions.saveSession, "save-session");
  const file = document.createElement("input");
  file.type = "file";
  file.accept = ".json,application/json";
  file.className = "hidden";
  file.name = "session-file";
  file.addEventListener("change", () => {
    const chosen = file.files?.[0];
    if (chosen) actions.loadSession(chosen);
    file.value = "";
  });
  session.append(file);
  button(session, "Load", "Load a recorded session and replay it", () => file.click(), "load-session");

  const out = group("Export");
  for (const format of ["json", "obj", "svg", "png"] as const) {
    button(
      out,
      format.toUpperCase(),
      `Export the pose as ${format.toUpperCase()}`,
      () => actions.export(format),
      `export-${format}`,
    );
  }

  return {
    element,
    brushPanel: toolPanel,
    refresh(state) {
      undo.disabled = !state.canUndo;
      redo.disabled = !state.canRedo;
      record.textContent = state.recording ? "Stop" : "Record";
      record.classList.toggle("active", state.recording);
      replay.disabled = !state.hasSession || state.recording;
      save.disabled = !state.hasSession;
    },
    showShape(value, count, parts) {
      if (value !== undefined) shape.value = value;
      vertices.value = String(count);
      part.replaceChildren(
        ...Array.from({ length: parts.count }, (_, i) => new Option(`${i + 1} of ${parts.count}`, String(i))),
      );
      part.value = String(parts.index);
      part.parentElement!.classList.toggle("hidden", parts.count < 2);
    },
    showRig(state) {
      saveRig.disabled = !state.hasRig;
      train.disabled = state.training;
    },
    addShape(option) {
      shape.append(new Option(option.label, option.value));
      shape.value = option.value;
    },
    sync(settings) {
      minAngle.value = String(settings.minAngle);
      wireframe.checked = settings.wireframe;
      field.checked = settings.field;
      flipped.checked = settings.flipped;
      paper.checked = settings.paperMode;
      noFoldovers.checked = settings.noFoldovers;
      region.checked = settings.region;
      compare.checked = settings.compare;
      energy.value = settings.training.energy ?? "sarap";
      basis.value = settings.training.basis ?? "tps";
      samples.value = String(settings.training.samples ?? 200);
      spatial.value = String(settings.training.spatial ?? 0);
      method.value = settings.method;
      lambda.value = String(settings.lambda);
      toolList.value = settings.tool;
      showTool(settings.tool);
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
}
