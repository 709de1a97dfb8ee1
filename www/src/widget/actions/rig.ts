/**
 * Trained rigs: training one (with the toolbar's training fields), cancelling, saving.
 */
import type { TrainProgress } from "../../defop-pool.js";
import { bounds } from "../model/geometry.js";
import { DEFAULT_RIG_SPATIAL, type RigTrainOptions } from "../model/rig.js";
import type { WidgetTrainOptions } from "../rigs/rig-manager.js";
import { download } from "../store/pose-export.js";
import { action } from "./action.js";
import type { WidgetParts } from "./context.js";
import { setMethod } from "./method.js";

/**
 * Trains a rig for the shape and handles (see `Widget.train`). From the toolbar,
 * `radiusPercent` is the training discs' radius in % of the shape's diagonal, and `pose`
 * makes the rig pose once trained (unless the method was changed meanwhile).
 */
export const train = action({
  name: "train",
  description: "Trains a rig (DefOp) for the handles placed",
  help: [
    {
      keys: "Train (toolbar)",
      does:
        "train a rig for the handles placed (in the background; keep posing); it then poses with " +
        "the method Trained (DefOp) until the handles change",
    },
  ],
  async perform(
    parts: WidgetParts,
    {
      options = {},
      onProgress,
      radiusPercent,
      pose = false,
    }: {
      options?: WidgetTrainOptions;
      onProgress?: ((progress: TrainProgress) => void) | undefined;
      radiusPercent?: number | undefined;
      pose?: boolean;
    } = {},
  ): Promise<void> {
    const { settings, posing } = parts;
    let given = options;
    if (radiusPercent !== undefined) {
      const b = bounds(posing.shape.mesh.positions);
      const diagonal = Math.hypot(b.maxX - b.minX, b.maxY - b.minY);
      given = { ...options, radius: (radiusPercent / 100) * diagonal };
    }
    const before = settings.method;
    const rig = await parts.rigs.train({ ...settings.training, ...given }, onProgress);
    // The options of the rig in use: saved with the work, so a reload finds it in the cache.
    settings.training = { ...rig.options };
    parts.toolbar?.sync(settings);
    if (!pose) return;
    // Trained: pose with it, unless the user chose another method meanwhile.
    if (settings.method === before) setMethod.perform(parts, { method: "defop" });
    parts.stage.status.succeeded();
  },

  controls: [
    {
      kind: "custom",
      id: "train",
      build(kit, place, perform, init) {
        const s = init.settings;
        const group = place.group;
        const energy = kit.select(
          [
            { value: "sarap", label: "S-ARAP" },
            { value: "arap", label: "ARAP" },
          ],
          s.training.energy ?? "sarap",
        );
        energy.name = "rig-energy";
        kit.labelled(group, "Energy ", energy);
        const basis = kit.select(
          ["tps", "linear", "quadratic", "cubic"].map((b) => ({ value: b, label: b === "tps" ? "TPS" : b })),
          s.training.basis ?? "tps",
        );
        basis.name = "rig-basis";
        kit.labelled(group, "Basis ", basis);
        const samples = kit.number(s.training.samples ?? 200, 1, 100_000, 1);
        samples.name = "rig-samples";
        kit.labelled(group, "Samples ", samples);
        const spatial = kit.number(s.training.spatial ?? DEFAULT_RIG_SPATIAL, 0, 100_000, 1);
        spatial.name = "rig-spatial";
        spatial.title =
          "Size of the reduced spatial basis (0: every mesh vertex; default 100, as accurate and 17 times faster to pose); smaller poses faster and saves smaller files";
        kit.labelled(group, "Reduced ", spatial);
        const sampling = kit.select(
          [
            { value: "disc", label: "discs" },
            { value: "voronoi", label: "cells" },
            { value: "mixed", label: "mixed" },
          ],
          s.training.sampling ?? "disc",
        );
        sampling.name = "rig-sampling";
        sampling.title =
          "Sampling: where training draws each handle's targets. discs: in a disc about it; cells: in its " +
          "Voronoi cell among the handles (reaching further, within the shape's box grown by the radius); " +
          "mixed: each sample from one or the other";
        // No visible label and short options (the title explains them), so that the panel
        // keeps to its rows in a small widget.
        sampling.setAttribute("aria-label", "Sampling");
        group.append(sampling);
        const radius = kit.number(15, 0.1, 1000, "any");
        radius.name = "rig-radius";
        radius.value = "";
        radius.placeholder = "15";
        radius.title =
          "Radius of the training discs (and the margin of the cells' box), in % of the shape's diagonal (empty: 15)";
        kit.labelled(group, "Radius % ", radius);
        const button = kit.button(
          group,
          "Train",
          "Train a rig for these handles (DefOp), in workers; posing goes on meanwhile",
          () => {
            const options = {
              energy: energy.value as "sarap" | "arap",
              basis: basis.value as NonNullable<RigTrainOptions["basis"]>,
              samples: Number(samples.value),
              spatial: Number(spatial.value),
              sampling: sampling.value as NonNullable<RigTrainOptions["sampling"]>,
            };
            perform({ options, radiusPercent: radius.value === "" ? undefined : Number(radius.value), pose: true });
          },
        );
        return {
          showRig(state) {
            button.disabled = state.training;
          },
          sync(settings) {
            energy.value = settings.training.energy ?? "sarap";
            basis.value = settings.training.basis ?? "tps";
            samples.value = String(settings.training.samples ?? 200);
            spatial.value = String(settings.training.spatial ?? DEFAULT_RIG_SPATIAL);
            sampling.value = settings.training.sampling ?? "disc";
          },
        };
      },
      failed(error, kit) {
        if ((error as Error | undefined)?.name !== "AbortError") return false;
        kit.cancelled("Training cancelled; nothing changed.");
        return true;
      },
    },
  ],
});

export const cancelTraining = action({
  name: "cancel-training",
  description: "Stops the training under way",
  perform: (parts): void => parts.rigs.cancel(),
});

/**
 * The rig's operator file (operator, mesh and training's settings), as "Save rig" downloads
 * it; `precision: "single"` stores its coefficients as 32-bit floats (about half the size).
 */
export const rigFile = action({
  name: "rig-file",
  description: "The trained rig's operator file",
  perform(parts, { precision = "double" }: { precision?: "double" | "single" } = {}): Uint8Array {
    const rig = parts.posing.rig;
    if (!rig) throw new Error("there is no trained rig to save; Train one first");
    return rig.toBytes({ precision });
  },
});

export const saveRig = action({
  name: "save-rig",
  description: "Downloads the trained rig",
  perform(parts): void {
    download(parts.document, new Blob([rigFile.perform(parts, {}) as Uint8Array<ArrayBuffer>]), "rig.defop");
  },

  controls: [
    {
      kind: "button",
      id: "save-rig",
      text: "Save rig",
      title: "Download the trained rig (.defop)",
      showRig: (state) => ({ disabled: !state.hasRig }),
    },
  ],
});
