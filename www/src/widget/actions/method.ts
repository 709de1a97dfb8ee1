/**
 * The deformation method and its lambda.
 */
import { METHODS, type MethodPreset } from "../model/methods.js";
import { oneShapeNote } from "../model/puppet.js";
import { action } from "./action.js";
import type { WidgetParts } from "./context.js";

/** See `Widget.setMethod`. */
export const setMethod = action({
  name: "method",
  description: "Changes the deformation method and/or lambda",
  perform(
    parts: WidgetParts,
    { method, lambda = parts.settings.lambda }: { method: MethodPreset; lambda?: number },
  ): void {
    parts.posing.setMethod(method, lambda);
    const note = parts.posing.shape.puppet && oneShapeNote(method);
    if (note) parts.stage.status.info(note);
  },

  controls: [
    {
      kind: "custom",
      id: "method",
      build(kit, place, perform, init) {
        const methods = Object.entries(METHODS).map(([value, m]) => ({ value, label: m.label }));
        const method = kit.select(methods, init.settings.method);
        method.name = "method";
        kit.labelled(place.group, "Method ", method);
        const lambda = kit.number(init.settings.lambda, 0.01, 1e6, "any");
        lambda.name = "lambda";
        kit.labelled(place.group, "λ ", lambda);
        const changed = (): void => {
          const chosen = method.value as MethodPreset;
          // A note about the method (a puppet posed as one shape) stays shown.
          if (perform({ method: chosen, lambda: Number(lambda.value) }) && !oneShapeNote(chosen)) kit.succeeded();
        };
        method.addEventListener("change", changed);
        lambda.addEventListener("change", changed);
        return {
          sync(settings) {
            method.value = settings.method;
            lambda.value = String(settings.lambda);
          },
        };
      },
    },
  ],
});
