/**
 * Actions that change the shape: a built-in shape, an outline, a file (by picker, drop or
 * URL) and its parts, re-meshing, and starting over.
 */
import { builtinShapes, type Outline } from "../../core.js";
import { fetchFile, fileKind, fileLimits } from "../shapes/shape-files.js";
import { action } from "./action.js";
import type { WidgetParts } from "./context.js";
import { loadSession } from "./session.js";

/** See `Widget.loadRig`. */
export const loadRig = action({
  name: "open-rig",
  description: "Opens a trained rig (an operator file): its shape, posed by it at once",
  help: [{ keys: "Drop a .defop file", does: "open a trained rig: it poses at once" }],
  perform: (parts, { source }: { source: string | Blob | Uint8Array | ArrayBuffer }): Promise<void> =>
    parts.rigs.open(source, (change) => parts.gesture(change)),

  controls: [
    {
      kind: "file",
      id: "open-rig",
      text: "Open rig…",
      title: "Open a trained rig (.defop): it poses at once",
      input: "rig-file",
      accept: ".defop,application/octet-stream",
      args: (file) => ({ source: file }),
    },
  ],
});

/** See `Widget.loadFile`. */
export const open = action({
  name: "open",
  description: "Loads a shape, session or rig from a file",
  async perform(parts, { file, name = (file as File).name ?? "file" }: { file: Blob; name?: string }): Promise<void> {
    if (/\.defop$/i.test(name)) return loadRig.perform(parts, { source: file });
    if (fileKind(name, file.type) === "json" && file.size <= fileLimits().bytes) {
      const text = await file.text();
      if (/"format"\s*:\s*"akap-session"/.test(text)) return loadSession.perform(parts, { file });
    }
    await parts.loader.open(file, name);
  },

  controls: [
    {
      kind: "file",
      id: "open",
      text: "Open…",
      title: "Open an SVG, an image, a mesh (OBJ, JSON), a session or a rig (.defop); or drop a file on the shape",
      input: "shape-file",
      accept: ".svg,.png,.jpg,.jpeg,.webp,.gif,.obj,.json,.defop,image/*",
      args: (file) => ({ file }),
    },
  ],
});

/** See `Widget.loadUrl`. */
export const loadUrl = action({
  name: "load-url",
  description: "Loads a shape, session or rig file by URL",
  async perform(parts, { url }: { url: string }): Promise<void> {
    const response = await fetchFile(url);
    const name = decodeURIComponent(new URL(url, parts.document.baseURI).pathname.split("/").pop() ?? url);
    await open.perform(parts, { file: await response.blob(), name });
  },
});

/** See `Widget.setShape`. */
export const setShape = action({
  name: "set-shape",
  description: "Switches to a built-in shape, or re-meshes the current one",
  perform: (parts, { name, vertices }: { name: string | undefined; vertices: number }): Promise<void> =>
    parts.loader.setShape(name, vertices),
});

/** See `Widget.setOutline`. */
export const setOutline = action({
  name: "set-outline",
  description: "Shows a custom outline instead",
  perform: (parts, { outline, vertices }: { outline: Outline; vertices: number }): Promise<void> =>
    parts.loader.setOutline(outline, vertices),
});

/** A shape from the toolbar's list: `builtin:name`, `gallery:index` or `file:index` (a file opened before). */
export const chooseShape = action({
  name: "shape",
  description: "Shows a shape from the list: built-in, the gallery's, or a file opened before",
  async perform(parts: WidgetParts, { value }: { value: string }): Promise<void> {
    const [kind, rest] = [value.slice(0, value.indexOf(":")), value.slice(value.indexOf(":") + 1)];
    if (kind === "builtin") await setShape.perform(parts, { name: rest, vertices: parts.settings.vertices });
    else if (kind === "file") await parts.loader.show(parts.loader.files[Number(rest)]!, 0);
    else await loadUrl.perform(parts, { url: parts.gallery[Number(rest)]!.url });
  },

  controls: [
    {
      kind: "custom",
      id: "shape",
      build(kit, place, perform, init) {
        const options = [
          ...builtinShapes().map((name) => ({ value: `builtin:${name}`, label: name })),
          ...init.gallery.map((item, i) => ({ value: `gallery:${i}`, label: item.name })),
        ];
        const shape = kit.select(options, options[0]?.value ?? "");
        shape.name = "shape";
        kit.labelled(place.group, "Shape ", shape);
        shape.addEventListener("change", () => perform({ value: shape.value }));
        return {
          showShape(value) {
            if (value !== undefined) shape.value = value;
          },
          addShape(option) {
            shape.append(new Option(option.label, option.value));
            shape.value = option.value;
          },
        };
      },
    },
  ],
});

/** See `Widget.choosePart`. */
export const choosePart = action({
  name: "part",
  description: "Shows another separate part of the last imported file",
  perform: (parts: WidgetParts, { index }: { index: number }): Promise<void> => parts.loader.choosePart(index),

  controls: [
    {
      kind: "custom",
      id: "part",
      build(kit, place, perform) {
        const part = kit.select([], "");
        part.name = "part";
        kit.labelled(place.group, "Part ", part);
        part.parentElement!.classList.add("hidden");
        part.addEventListener("change", () => perform({ index: Number(part.value) }));
        return {
          showShape(_value, _vertices, parts) {
            part.replaceChildren(
              ...Array.from({ length: parts.count }, (_, i) => new Option(`${i + 1} of ${parts.count}`, String(i))),
            );
            part.value = String(parts.index);
            part.parentElement!.classList.toggle("hidden", parts.count < 2);
          },
        };
      },
    },
  ],
});

/** See `Widget.remesh`. */
export const remesh = action({
  name: "remesh",
  description: "Re-meshes the shape to about a vertex count and a smallest angle, carrying the pose",
  perform: (parts: WidgetParts, { vertices, minAngle }: { vertices: number; minAngle: number }): Promise<void> =>
    parts.loader.remesh(vertices, minAngle),

  controls: [
    {
      kind: "custom",
      id: "remesh",
      build(kit, place, perform, init) {
        const vertices = kit.number(init.settings.vertices, 100, 50_000, 100);
        vertices.name = "vertices";
        kit.labelled(place.group, "Vertices ", vertices);
        const minAngle = kit.number(init.settings.minAngle, 0, 34, 1);
        minAngle.name = "min-angle";
        kit.labelled(place.group, "Min angle ", minAngle);
        const changed = (): void => {
          perform({ vertices: Number(vertices.value), minAngle: Number(minAngle.value) });
        };
        vertices.addEventListener("change", changed);
        minAngle.addEventListener("change", changed);
        return {
          showShape(_value, count) {
            vertices.value = String(count);
          },
          sync(settings) {
            minAngle.value = String(settings.minAngle);
          },
        };
      },
    },
  ],
});

/** See `Widget.startOver`. */
export const startOver = action({
  name: "start-over",
  description: "Forgets the saved work and starts again with the default shape",
  async perform(parts: WidgetParts): Promise<void> {
    await parts.keeper?.store.clear();
    parts.animation.animator.clear();
    parts.loader.startOver();
    parts.syncToolbar();
  },

  controls: [
    {
      kind: "button",
      id: "start-over",
      text: "Start over",
      title: "Forget the saved work and start again with the default shape",
      offered: (init) => init.keepsWork,
    },
  ],
});
