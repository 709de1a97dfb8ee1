/**
 * The pose out: as a mesh (JSON or OBJ), an SVG or a PNG, to the API or downloaded.
 */
import { unpainted } from "../model/stiffness.js";
import type { Posing } from "../model/posing.js";
import { download, posedMesh, posedSvg, puppetSvg, type PosedPuppet, type PuppetArt } from "../store/pose-export.js";
import { action, type ButtonControl } from "./action.js";
import type { WidgetParts } from "./context.js";

/** Each triangle's painted stiffness (a copy), or undefined when none is painted. */
export function paintedStiffness(parts: Pick<WidgetParts, "posing">): Float64Array | undefined {
  const s = parts.posing.stiffness;
  return unpainted(s) ? undefined : s!.slice();
}

/** A puppet's parts as posed now (the user's depth order), with their art; undefined for other shapes. */
export function puppetArt(posing: Posing): PuppetArt[] | undefined {
  const puppet = posing.shape.puppet;
  if (!puppet) return undefined;
  return puppet.parts.map((part, k) => ({ ...part, depth: posing.depths?.[k] ?? part.depth }));
}

/** A puppet as the mesh writers take it (rest mesh, parts in the user's depth order, the deformer's joints). */
function posedPuppet(posing: Posing): PosedPuppet | undefined {
  const parts = puppetArt(posing);
  if (!parts) return undefined;
  return { mesh: posing.shape.mesh, parts, joints: posing.deformer.joints };
}

/** See `Widget.exportMesh`. */
export const exportMesh = action({
  name: "export-mesh",
  description: "The current pose as JSON or OBJ text",
  perform(parts, { format }: { format: "json" | "obj" }): string {
    const { posing, stage } = parts;
    const layers = stage.layering(posing);
    return posedMesh(posing.shape, posing.deformer.positions(), format, {
      stiffness: paintedStiffness(parts),
      layers,
      puppet: posedPuppet(posing),
    });
  },
});

/** See `Widget.exportSvg`. */
export const exportSvg = action({
  name: "export-svg",
  description: "The pose as an SVG document",
  perform(parts): string {
    const { posing, stage } = parts;
    const { deformer, shape } = posing;
    // A puppet's art: each part carried by its own sheet, back to front, a layer each.
    const art = puppetArt(posing);
    if (art && art.some((part) => part.paths.length > 0)) return puppetSvg(shape.mesh, art, deformer.positions());
    return posedSvg(shape.mesh, shape.vector, deformer.positions(), stage.layering(posing));
  },
});

/** See `Widget.exportPng`. */
export const exportPng = action({
  name: "export-png",
  description: "The rendered image (no handles) as a PNG",
  perform: (parts): Promise<Blob> => parts.stage.png(parts.posing, parts.settings),
});

type PoseFormat = "json" | "obj" | "svg" | "png";

/** The pose downloaded as a file (the toolbar's Export buttons). */
export const downloadPose = action({
  name: "download-pose",
  description: "Downloads the pose as JSON, OBJ, SVG or PNG",
  controls: (["json", "obj", "svg", "png"] as const).map((format): ButtonControl<{ format: PoseFormat }> => ({
    kind: "button",
    id: `export-${format}`,
    text: format.toUpperCase(),
    title: `Export the pose as ${format.toUpperCase()}`,
    args: { format },
  })),
  async perform(parts, { format }: { format: PoseFormat }): Promise<void> {
    const doc = parts.document;
    if (format === "png") download(doc, await exportPng.perform(parts), "pose.png");
    else if (format === "svg") download(doc, exportSvg.perform(parts), "pose.svg", "image/svg+xml");
    else {
      const type = format === "json" ? "application/json" : "text/plain";
      download(doc, exportMesh.perform(parts, { format }), `pose.${format}`, type);
    }
  },
});
