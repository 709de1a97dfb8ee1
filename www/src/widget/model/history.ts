/**
 * Undo and redo, one entry per gesture (a drag, an added or removed handle, a reset, a
 * nudge). The caller saves the state before a gesture with {@link History.push}; undo
 * hands back that state and keeps the current one for redo.
 */
export class History<State> {
  readonly #undo: State[] = [];
  #redo: State[] = [];

  /** @param limit how many gestures can be undone; older ones are forgotten. */
  constructor(readonly limit = 100) {
    if (!(limit >= 1)) throw new RangeError(`history limit is ${limit}, expected at least 1`);
  }

  /** Records the state before a new gesture; the redo list is dropped. */
  push(before: State): void {
    this.#undo.push(before);
    if (this.#undo.length > this.limit) this.#undo.shift();
    this.#redo = [];
  }

  /** The state to return to, given the current one (kept for redo); undefined if none. */
  undo(current: State): State | undefined {
    const previous = this.#undo.pop();
    if (previous !== undefined) this.#redo.push(current);
    return previous;
  }

  /** The state undone last, given the current one (kept for undo); undefined if none. */
  redo(current: State): State | undefined {
    const next = this.#redo.pop();
    if (next !== undefined) this.#undo.push(current);
    return next;
  }

  get canUndo(): boolean {
    return this.#undo.length > 0;
  }

  get canRedo(): boolean {
    return this.#redo.length > 0;
  }

  clear(): void {
    this.#undo.length = 0;
    this.#redo = [];
  }
}
