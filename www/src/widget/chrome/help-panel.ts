/**
 * The help panel: the gestures and keys, each action's help lines in the registry's order
 * (no list of its own), opened with the `?` key or the toolbar's `?` button, closed with
 * Esc, its Close button, or `?` again.
 */
import { helpLines } from "../actions/registry.js";

export class HelpPanel {
  readonly element: HTMLElement;
  readonly #close: HTMLButtonElement;

  constructor(document: Document, onClose: () => void) {
    this.element = document.createElement("section");
    this.element.className = "help hidden";
    this.element.setAttribute("role", "dialog");
    this.element.setAttribute("aria-label", "Help: gestures and keys");
    const title = document.createElement("h2");
    title.textContent = "Gestures and keys";
    const table = document.createElement("dl");
    for (const { keys, does } of helpLines()) {
      const term = document.createElement("dt");
      term.textContent = keys;
      const definition = document.createElement("dd");
      definition.textContent = does;
      table.append(term, definition);
    }
    this.#close = document.createElement("button");
    this.#close.type = "button";
    this.#close.textContent = "Close";
    this.#close.addEventListener("click", onClose);
    this.element.append(title, table, this.#close);
  }

  get open(): boolean {
    return !this.element.classList.contains("hidden");
  }

  set open(open: boolean) {
    this.element.classList.toggle("hidden", !open);
    if (open) this.#close.focus({ preventScroll: true });
  }
}
