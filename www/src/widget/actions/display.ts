/**
 * Actions on what is shown: the view (zoom, fit, pan), the display toggles, the HUD, the
 * help panel and the status line.
 */
import type { WidgetSettings } from "../options.js";
import { action, type CheckboxControl, type Gesture } from "./action.js";
import type { WidgetParts } from "./context.js";

/** Zoom step of the + and - keys. */
export const ZOOM_STEP = 1.25;

/** The display toggles (and `paperMode` and `noFoldovers` of posing, which sit beside them). */
export type DisplayToggles = Pick<
  WidgetSettings,
  "wireframe" | "field" | "flipped" | "paperMode" | "noFoldovers" | "region" | "compare"
>;

/** Zooms the view by `factor` about its centre, or fits the pose on screen into it (`"fit"`). */
function zoomView(parts: WidgetParts, factor: number | "fit"): void {
  const { stage, posing } = parts;
  if (factor === "fit") stage.camera.fit(posing.deformer.positionsView());
  else stage.camera.zoom(stage.glCanvas.width / 2, stage.glCanvas.height / 2, factor);
  parts.draw();
}

export const zoom = action({
  name: "zoom",
  description: "Zooms the view about its centre, or fits the pose into it",
  help: [{ keys: "Wheel or pinch; + and -", does: "zoom" }],
  keys: [
    { keys: ["+", "="], args: { factor: ZOOM_STEP } },
    { keys: ["-"], args: { factor: 1 / ZOOM_STEP } },
  ],
  perform: (parts, { factor }: { factor: number | "fit" }): void => zoomView(parts, factor),
});

export const pan: Gesture = {
  name: "pan",
  description: "Moves the view with the pointer",
  help: [{ keys: "Drag the background, Space-drag, two fingers", does: "pan the view" }],
};

export const fit = action({
  name: "fit",
  description: "Fits the pose on screen into the view",
  help: [{ keys: "F or 0", does: "fit the shape in view" }],
  keys: [{ keys: ["f", "0"] }],
  controls: [{ kind: "button", id: "fit", text: "Fit", title: "Fit the shape into the view (F)" }],
  perform: (parts): void => zoomView(parts, "fit"),
});

/**
 * Display options, and `paperMode` and `noFoldovers` of posing; `region` and `compare`
 * concern a trained rig.
 */
export const display = action({
  name: "display",
  description: "Changes display options (and paper mode, no foldovers)",
  controls: (
    [
      ["no-foldovers", "No foldovers", "noFoldovers"],
      ["wireframe", "Wireframe (W)", "wireframe"],
      ["field", "Field (V)", "field"],
      ["flipped", "Flipped", "flipped"],
      ["paper-mode", "Paper mode", "paperMode"],
      ["region", "Region", "region"],
      ["compare", "Compare", "compare"],
    ] as const
  ).map(([id, text, setting]): CheckboxControl<Partial<DisplayToggles>> => ({
    kind: "checkbox",
    id,
    text,
    ...(setting === "noFoldovers"
      ? { title: "Split a step that would flip a triangle, and stop short where even small pieces would" }
      : {}),
    checked: (settings) => settings[setting],
    args: (checked) => ({ [setting]: checked }),
  })),
  perform(parts, options: Partial<DisplayToggles>): void {
    const { settings, posing, frames, rigs } = parts;
    Object.assign(settings, options);
    if (options.field) frames.lastField = posing.deformer.field();
    if (options.compare) rigs.compareSoon();
    parts.rigChanged();
  },
});

/** The wireframe (W) or the field (V) on or off, the toolbar following. */
export const toggle = action({
  name: "toggle",
  description: "Turns the wireframe or the velocity field on or off",
  help: [
    { keys: "W", does: "wireframe" },
    { keys: "V", does: "velocity field arrows" },
  ],
  keys: [
    { keys: ["w"], args: { what: "wireframe" } },
    { keys: ["v"], args: { what: "field" } },
  ],
  perform(parts, { what }: { what: "wireframe" | "field" }): void {
    display.perform(parts, { [what]: !parts.settings[what] });
    parts.toolbar?.sync(parts.settings);
  },
});

export const hud = action({
  name: "hud",
  description: "Shows or hides the heads-up display",
  controls: [
    {
      kind: "checkbox",
      id: "hud",
      text: "HUD",
      checked: (settings) => settings.hud,
      args: (checked) => ({ visible: checked }),
    },
  ],
  perform: (parts, { visible }: { visible: boolean }): void => parts.showHud(visible),
});

export const help = action({
  name: "help",
  description: "Opens or closes the help panel",
  help: [{ keys: "?", does: "this help" }],
  keys: [{ keys: ["?"] }],
  controls: [{ kind: "button", id: "help", text: "?", title: "Gestures and keys (?)" }],
  perform: (parts, { open }: { open?: boolean } = {}): void => parts.toggleHelp(open),
});

export const showMessage = action({
  name: "show-message",
  description: "Shows a message in the status line until the next action that succeeds",
  perform(parts, { message, kind = "info" }: { message: string; kind?: "info" | "error" }): void {
    if (kind === "error") parts.showError(new Error(message));
    else parts.stage.status.info(message);
  },
});
