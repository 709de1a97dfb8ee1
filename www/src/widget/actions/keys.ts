/**
 * The keyboard's side of the registry: which action a key press runs, and where a key
 * press happened. Keys typed into a text field or list belong to it: no shortcut fires
 * there, and Space and Enter on a button or checkbox press it.
 */
import { bindingArgs, type AnyAction, type KeyFocus, type KeyPress } from "./action.js";
import { ACTIONS } from "./registry.js";

/** A key press's command: the action's name as `kind`, with its arguments. */
export type KeyCommand = { kind: string } & Record<string, unknown>;

/** The action a key press runs, with its arguments; undefined for keys the widget leaves alone. */
export function keyAction(
  press: KeyPress,
  focus: KeyFocus = "other",
): { action: AnyAction; args: unknown } | undefined {
  if (focus === "text") return undefined;
  const key = press.key.toLowerCase();
  if (focus === "control" && (key === " " || key === "enter")) return undefined;
  for (const action of ACTIONS.values()) {
    for (const binding of action.keys ?? []) {
      const found = bindingArgs(binding, press);
      if (found) return { action, args: found.args };
    }
  }
  return undefined;
}

/** The command of a key press (the action's name and arguments), or undefined. */
export function keyCommand(press: KeyPress, focus: KeyFocus = "other"): KeyCommand | undefined {
  const found = keyAction(press, focus);
  return found && { kind: found.action.name, ...(found.args as object | undefined) };
}

/** Where a key event came from, by the element that has focus inside the widget. */
export function keyFocus(target: EventTarget | null): KeyFocus {
  const element = target as HTMLElement | null;
  if (!element || typeof element.tagName !== "string") return "other";
  const tag = element.tagName.toLowerCase();
  if (tag === "textarea" || tag === "select" || element.isContentEditable) return "text";
  if (tag === "input") {
    const type = (element as HTMLInputElement).type;
    return ["checkbox", "radio", "button", "submit", "reset", "file", "color", "range"].includes(type)
      ? "control"
      : "text";
  }
  return tag === "button" || tag === "summary" ? "control" : "other";
}
