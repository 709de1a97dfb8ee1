/**
 * The keyboard: a key press runs the registry's action for it (`actions/keys.ts`), except
 * Space, which held makes presses pan the view and, tapped without panning, plays or
 * pauses the animation. Keys typed into fields are left to them.
 */
import type { Action } from "../actions/action.js";
import { playPause } from "../actions/animation.js";
import { keyAction, keyFocus } from "../actions/keys.js";

/** What the keyboard needs of the widget. */
export interface KeyboardHost {
  /** The focusable root, which hears the keys. */
  readonly root: HTMLElement;
  /** The overlay, marked while Space is held. */
  readonly overlay: HTMLElement;
  /** Runs an action of the registry; a failure shows its message. */
  perform<A>(action: Action<A, unknown>, args: A): void;
}

export class Keyboard {
  readonly #host: KeyboardHost;
  #spaceHeld = false;
  /** The view was panned while Space was held (then its release does not play). */
  #spacePanned = false;

  constructor(host: KeyboardHost) {
    this.#host = host;
    host.root.addEventListener("keydown", (e) => this.#key(e));
    host.root.addEventListener("keyup", (e) => {
      if (e.key !== " " || !this.#spaceHeld) return;
      // A tap of Space (no pan while it was held) plays or pauses the animation.
      if (!this.#spacePanned && keyFocus(e.composedPath()[0] ?? null) === "other") host.perform(playPause, undefined);
      this.#setSpace(false);
    });
    host.root.addEventListener("blur", () => this.#setSpace(false), true);
  }

  /** Whether Space is held (presses then pan the view). */
  get spaceHeld(): boolean {
    return this.#spaceHeld;
  }

  /** The view was panned: while Space is held, its release then does not play. */
  panned(): void {
    if (this.#spaceHeld) this.#spacePanned = true;
  }

  #setSpace(held: boolean): void {
    this.#spaceHeld = held;
    this.#host.overlay.classList.toggle("panning", held);
  }

  #key(e: KeyboardEvent): void {
    const focus = keyFocus(e.composedPath()[0] ?? null);
    if (e.key === " " && focus === "other") {
      e.preventDefault();
      if (!e.repeat && !this.#spaceHeld) this.#spacePanned = false;
      this.#setSpace(true);
      return;
    }
    const found = keyAction(e, focus);
    if (!found) return;
    e.preventDefault();
    this.#host.perform(found.action, found.args);
  }
}
