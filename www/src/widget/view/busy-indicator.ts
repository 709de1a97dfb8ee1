/**
 * The busy indicator: long work shows a panel with its stage, a progress bar when the
 * fraction done is known, and a Cancel button when the work can be cancelled; work
 * shorter than {@link BUSY_DELAY_MS} never shows.
 */

/** Work that takes long enough to show: its stage, and how far it is when known. */
export interface BusyState {
  label: string;
  /** Fraction done, 0 to 1; undefined when unknown (an indeterminate bar). */
  progress?: number;
  /** Set when the work can be stopped. */
  cancel?: () => void;
}

/** Shown only for work that lasts longer than this (milliseconds). */
export const BUSY_DELAY_MS = 200;

export class BusyIndicator {
  readonly element: HTMLElement;
  readonly #label: HTMLElement;
  readonly #bar: HTMLProgressElement;
  readonly #cancel: HTMLButtonElement;
  #onCancel: (() => void) | undefined;
  #timer: ReturnType<typeof setTimeout> | undefined;
  #since = 0;

  /** `className`: its look and place (the stage's other indicator is `"training"`). */
  constructor(document: Document, className = "busy") {
    this.element = document.createElement("div");
    this.element.className = `${className} hidden`;
    this.element.setAttribute("role", "progressbar");
    this.element.setAttribute("aria-live", "polite");
    this.#label = document.createElement("span");
    this.#bar = document.createElement("progress");
    this.#cancel = document.createElement("button");
    this.#cancel.type = "button";
    this.#cancel.textContent = "Cancel";
    this.#cancel.addEventListener("click", () => this.#onCancel?.());
    this.element.append(this.#label, this.#bar, this.#cancel);
  }

  /** Whether work is under way (shown or about to be). */
  get busy(): boolean {
    return this.#since > 0;
  }

  /** Starts or updates the work's state; it becomes visible after {@link BUSY_DELAY_MS}. */
  update(state: BusyState): void {
    if (this.#since === 0) {
      this.#since = performance.now();
      this.#timer = setTimeout(() => this.element.classList.remove("hidden"), BUSY_DELAY_MS);
    }
    const seconds = (performance.now() - this.#since) / 1000;
    this.#label.textContent = seconds >= 1 ? `${state.label} (${seconds.toFixed(0)} s)` : state.label;
    if (state.progress === undefined) {
      this.#bar.removeAttribute("value");
      this.element.removeAttribute("aria-valuenow");
    } else {
      this.#bar.value = state.progress;
      this.element.setAttribute("aria-valuenow", String(Math.round(100 * state.progress)));
    }
    this.element.setAttribute("aria-valuetext", this.#label.textContent);
    this.#onCancel = state.cancel;
    this.#cancel.classList.toggle("hidden", state.cancel === undefined);
  }

  done(): void {
    clearTimeout(this.#timer);
    this.#since = 0;
    this.#onCancel = undefined;
    this.element.classList.add("hidden");
  }
}
