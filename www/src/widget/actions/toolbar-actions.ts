/**
 * What the toolbar's controls do: each calls the widget's public API, and an action that
 * fails says why (a cancelled one says so as information) with every field back to the
 * settings in force.
 */
import { builtinShapes } from "../../core.js";
import { METHODS, type MethodPreset } from "../model/methods.js";
import type { GalleryItem, WidgetTool } from "../options.js";
import { Cancelled } from "../shapes/shape-maker.js";
import { download } from "../store/pose-export.js";
import type { RigTrainOptions } from "../model/rig.js";
import type { BrushSettings } from "../model/stiffness.js";
import {
  buildToolbar,
  type DisplayToggles,
  type Toolbar,
  type ToolbarActions,
  type ToolbarSettings,
} from "../chrome/toolbar.js";
import { bounds } from "../model/geometry.js";
import type { Widget } from "../widget.js";

/** What the actions need beyond the widget's public API. */
export interface ActionHost {
  readonly gallery: readonly GalleryItem[];
  /** Shows the `index`-th file opened so far again. */
  showFile(index: number): Promise<void>;
  /** Whether the work is kept (then "Start over" is offered). */
  readonly keepsWork: boolean;
  failed(error: unknown): void;
  cancelled(message: string): void;
  succeeded(): void;
  showHud(visible: boolean): void;
  help(): void;
}

/** The widget's toolbar: its lists (built-in shapes, the gallery, the methods) and its actions. */
export function widgetToolbar(
  document: Document,
  widget: Widget,
  settings: ToolbarSettings,
  host: ActionHost,
): Toolbar {
  return buildToolbar(document, toolbarActions(widget, host), {
    shapes: [
      ...builtinShapes().map((name) => ({ value: `builtin:${name}`, label: name })),
      ...host.gallery.map((item, i) => ({ value: `gallery:${i}`, label: item.name })),
    ],
    methods: Object.entries(METHODS).map(([value, m]) => ({ value, label: m.label })),
    settings,
  });
}

export function toolbarActions(widget: Widget, host: ActionHost): ToolbarActions {
  const guard =
    <A extends unknown[]>(action: (...args: A) => unknown) =>
    (...args: A): void => {
      const failed = (error: unknown): void => {
        if (error instanceof Cancelled) host.cancelled(error.message);
        else host.failed(error);
      };
      try {
        const result = action(...args);
        if (result instanceof Promise) result.catch(failed);
      } catch (error) {
        failed(error);
      }
    };
  const doc = widget.target.ownerDocument;
  return {
    undo: guard(() => widget.undo()),
    redo: guard(() => widget.redo()),
    reset: guard(() => widget.reset()),
    clear: guard(() => widget.clearHandles()),
    shape: guard(async (value: string) => {
      const [kind, rest] = [value.slice(0, value.indexOf(":")), value.slice(value.indexOf(":") + 1)];
      if (kind === "builtin") await widget.setShape(rest);
      else if (kind === "file") await host.showFile(Number(rest));
      else await widget.loadUrl(host.gallery[Number(rest)]!.url);
    }),
    remesh: guard((vertices: number, minAngle: number) => widget.remesh(vertices, minAngle)),
    open: guard((file: File) => widget.loadFile(file)),
    part: guard((index: number) => widget.choosePart(index)),
    method: guard((method: string, lambda: number) => {
      widget.setMethod(method as MethodPreset, lambda);
      host.succeeded();
    }),
    display: guard((options: DisplayToggles) => widget.setDisplay(options)),
    brush: guard((tool: WidgetTool, brush: BrushSettings) => widget.setTool(tool, brush)),
    clearBones: guard(() => widget.clearBones()),
    clearStiffness: guard(() => widget.setStiffness(undefined)),
    reorder: guard((step: 1 | -1) => (step > 0 ? widget.bringForward() : widget.sendBack())),
    train: (options: Omit<RigTrainOptions, "radius">, radiusPercent: number | undefined) => {
      const run = async () => {
        const mesh = widget.mesh;
        const b = bounds(mesh.positions);
        const diagonal = Math.hypot(b.maxX - b.minX, b.maxY - b.minY);
        const radius = radiusPercent === undefined ? undefined : (radiusPercent / 100) * diagonal;
        const before = widget.method.method;
        await widget.train({ ...options, ...(radius === undefined ? {} : { radius }) });
        // Trained: pose with it, unless the user chose another method meanwhile.
        if (widget.method.method === before) widget.setMethod("defop");
        host.succeeded();
      };
      run().catch((error: unknown) => {
        if ((error as Error | undefined)?.name === "AbortError") host.cancelled("Training cancelled; nothing changed.");
        else host.failed(error);
      });
    },
    saveRig: guard(() => download(doc, new Blob([widget.rigFile() as Uint8Array<ArrayBuffer>]), "rig.defop")),
    openRig: guard((file: File) => widget.loadRig(file)),
    hud: (visible: boolean) => host.showHud(visible),
    record: guard(() => (widget.recording ? widget.stopRecording() : widget.startRecording())),
    replay: guard(() => (widget.lastSession ? widget.replay(widget.lastSession) : undefined)),
    saveSession: guard(() => {
      if (!widget.lastSession) return;
      download(doc, widget.lastSession.json, "session.akap.json", "application/json");
    }),
    loadSession: guard((file: File) => widget.loadSession(file)),
    export: guard(async (format: "json" | "obj" | "svg" | "png") => {
      if (format === "png") download(doc, await widget.exportPng(), "pose.png");
      else if (format === "svg") download(doc, widget.exportSvg(), "pose.svg", "image/svg+xml");
      else {
        const type = format === "json" ? "application/json" : "text/plain";
        download(doc, widget.exportMesh(format), `pose.${format}`, type);
      }
    }),
    fit: () => widget.zoom("fit"),
    help: () => host.help(),
    ...(host.keepsWork ? { startOver: guard(() => widget.startOver()) } : {}),
  };
}
