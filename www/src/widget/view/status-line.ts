/**
 * The widget's status line. Messages have a kind: information (neutral: "this file has 3
 * parts") or an error (red, saying what went wrong and what to do). A message stays until
 * the next action that succeeds, so an error cannot flash by unread, and an old message
 * never sits under a newer result.
 */

export type StatusKind = "info" | "error";

export class StatusLine {
  readonly element: HTMLElement;
  #kind: StatusKind | undefined;

  constructor(document: Document) {
    this.element = document.createElement("div");
    this.element.className = "status";
    this.element.setAttribute("role", "status");
    this.element.setAttribute("aria-live", "polite");
  }

  /** What is shown now, if anything. */
  get kind(): StatusKind | undefined {
    return this.#kind;
  }

  get text(): string {
    return this.element.textContent ?? "";
  }

  info(message: string): void {
    this.#show("info", message);
  }

  error(message: string): void {
    this.#show("error", message);
  }

  /** An action succeeded: whatever was shown is out of date. */
  succeeded(): void {
    if (this.#kind === undefined) return;
    this.#kind = undefined;
    this.element.textContent = "";
    this.element.classList.remove("error", "info");
  }

  #show(kind: StatusKind, message: string): void {
    this.#kind = kind;
    this.element.textContent = message;
    this.element.classList.toggle("error", kind === "error");
    this.element.classList.toggle("info", kind === "info");
  }
}

/** What an error says: its message, or the thrown value as text. */
export function messageOf(error: unknown): string {
  return error instanceof Error ? error.message : String(error);
}
