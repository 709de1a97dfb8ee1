/**
 * The deformation methods the widget offers, as presets of the core's deformer options,
 * and the way back from a session's options to a preset.
 */
import type { DeformerOptions } from "../../core.js";

/**
 * The deformation methods the widget offers: AKAP and the paper's ablations (Figure 8),
 * ARAP, and a trained rig (DefOp), which poses in closed form once trained for the
 * handles; its deformer options are AKAP's, which pose while no rig fits the handles.
 */
export const METHODS = {
  akap: { label: "AKAP", options: { method: "akap", dirichlet: true, integrator: "spiral" } },
  "akap-no-dirichlet": {
    label: "AKAP without Dirichlet step",
    options: { method: "akap", dirichlet: false, integrator: "spiral" },
  },
  "akap-linear": {
    label: "AKAP with linear steps",
    options: { method: "akap", dirichlet: true, integrator: "linear" },
  },
  "akap-simple": {
    label: "AKAP, both simplifications",
    options: { method: "akap", dirichlet: false, integrator: "linear" },
  },
  arap: { label: "ARAP (10 iterations per step)", options: { method: "arap", iterations: 10 } },
  mls: { label: "Moving least squares (rigid)", options: { method: "mls", variant: "rigid", alpha: 1 } },
  "cauchy-green": {
    label: "Cauchy-Green (conformal)",
    options: { method: "cauchy-green", cage: 64, smoothness: 1e-5 },
  },
  defop: { label: "Trained (DefOp)", options: { method: "akap", dirichlet: true, integrator: "spiral" } },
} as const satisfies Record<string, { label: string; options: DeformerOptions }>;

/**
 * A preset of the widget: a deformation method (`"akap"`, `"arap"`, `"mls"` or
 * `"cauchy-green"`, the core's `DeformerOptions.method`) with settings, named by its key
 * in {@link METHODS}.
 */
export type MethodPreset = keyof typeof METHODS;

/** Deformer options of a widget method; lambda applies to the AKAP variants (and DefOp's AKAP) only. */
export function methodOptions(method: MethodPreset, lambda: number): DeformerOptions {
  const options: DeformerOptions = { ...METHODS[method].options };
  if (options.method === "akap") options.lambda = lambda;
  return options;
}

/** The widget method (and lambda) that deformer options describe, e.g. a session's. */
export function widgetMethod(options: DeformerOptions, lambda: number): { method: MethodPreset; lambda: number } {
  if (options.method === "arap") return { method: "arap", lambda };
  if (options.method === "mls") return { method: "mls", lambda };
  if (options.method === "cauchy-green") return { method: "cauchy-green", lambda };
  const dirichlet = options.dirichlet ?? true;
  const integrator = options.integrator ?? "spiral";
  const found = (Object.keys(METHODS) as MethodPreset[]).find((key) => {
    const m: DeformerOptions = METHODS[key].options;
    return m.method === "akap" && m.dirichlet === dirichlet && m.integrator === integrator;
  });
  return { method: found ?? "akap", lambda: options.lambda ?? lambda };
}
