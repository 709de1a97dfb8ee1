/**
 * `<akap-deformer>`: the posing widget as a custom element.
 *
 * ```html
 * <script type="module">
 *   import { defineElement } from "akap";
 *   defineElement();
 * </script>
 * <akap-deformer shape="gingerbread" vertices="1200" hud="false" style="height: 400px"></akap-deformer>
 * ```
 * Attributes (read when the element is connected): `shape`, `src` (an SVG, image or mesh
 * file to pose instead), `operator` (a trained rig's `.defop` file: its shape posed at once
 * by the rig, no training), `texture` (an image URL), `region`, `compare`,
 * `vertices`, `method`, `lambda`, `controls`, `hud`, `wireframe`, `field`, `timeline` (the
 * animation's strip), `fps` (`"false"` turns a default-on feature off). The element fires the
 * widget's events (`akap-ready`, `akap-pose`, `akap-handles`, `akap-error`, `akap-frame`);
 * `element.widget` is the {@link Widget}.
 */
import { mount, type MethodPreset, type Widget, type WidgetOptions } from "./widget.js";

/** What `document.querySelector("akap-deformer")` gives after {@link defineElement}. */
export interface AkapDeformerElement extends HTMLElement {
  /** The widget, once mounted (after `akap-ready`). */
  readonly widget: Widget | undefined;
  /** Resolves with the widget once it is mounted. */
  readonly ready: Promise<Widget>;
}

/**
 * Registers `<akap-deformer>` (or another tag name) once; later calls do nothing. The
 * class is made here, not at import, so that importing the package works in Node.
 */
export function defineElement(tag = "akap-deformer"): void {
  if (typeof customElements === "undefined" || customElements.get(tag)) return;
  customElements.define(
    tag,
    class extends HTMLElement implements AkapDeformerElement {
      #widget: Widget | undefined;
      #mounting: Promise<Widget> | undefined;

      get widget(): Widget | undefined {
        return this.#widget;
      }

      get ready(): Promise<Widget> {
        return this.#mounting ?? Promise.reject(new Error("the element is not in a document"));
      }

      connectedCallback(): void {
        if (this.#mounting) return;
        if (!this.style.display) this.style.display = "block";
        this.#mounting = mount(this, elementOptions(this));
        this.#mounting.then(
          (widget) => {
            if (this.isConnected) this.#widget = widget;
            else widget.destroy();
          },
          (error: unknown) => {
            const message = error instanceof Error ? error.message : String(error);
            this.textContent = `akap-deformer: ${message}`;
            this.dispatchEvent(new CustomEvent("akap-error", { detail: { message } }));
          },
        );
      }

      disconnectedCallback(): void {
        this.#widget?.destroy();
        this.#widget = undefined;
        this.#mounting = undefined;
      }
    },
  );
}

/** Widget options from the element's attributes. */
function elementOptions(element: HTMLElement): WidgetOptions {
  const text = (name: string): string | undefined => element.getAttribute(name) ?? undefined;
  const flag = (name: string): boolean | undefined => {
    const value = element.getAttribute(name);
    return value === null ? undefined : value !== "false";
  };
  const num = (name: string): number | undefined => {
    const value = element.getAttribute(name);
    if (value === null) return undefined;
    const n = Number(value);
    if (!Number.isFinite(n)) throw new Error(`attribute ${name}="${value}" is not a number`);
    return n;
  };
  const options: WidgetOptions = {};
  const assign = <K extends keyof WidgetOptions>(key: K, value: WidgetOptions[K] | undefined): void => {
    if (value !== undefined) options[key] = value;
  };
  assign("shape", text("shape"));
  assign("texture", text("texture"));
  assign("src", text("src"));
  assign("operator", text("operator"));
  assign("region", flag("region"));
  assign("compare", flag("compare"));
  assign("vertices", num("vertices"));
  assign("method", text("method") as MethodPreset | undefined);
  assign("lambda", num("lambda"));
  assign("controls", flag("controls"));
  assign("hud", flag("hud"));
  assign("wireframe", flag("wireframe"));
  assign("field", flag("field"));
  assign("timeline", flag("timeline"));
  assign("fps", num("fps"));
  return options;
}
