/**
 * The registry of the widget's actions: every command in one list, in the order the help
 * panel shows them (the pointer's gestures among them, described for the help). The
 * toolbar builds its controls from it, the keyboard finds the action of a key in it, the
 * help panel lists its lines, and the `Widget` class's public methods perform its actions.
 */
import type { AnyAction, Gesture, HelpLine } from "./action.js";
import {
  captureKey,
  deleteKey,
  exportAnimation,
  moveKey,
  pause,
  play,
  playPause,
  seek,
  setKeyEasing,
} from "./animation.js";
import { display, fit, help, hud, pan, showMessage, toggle, zoom } from "./display.js";
import { downloadPose, exportMesh, exportPng, exportSvg } from "./export.js";
import {
  addHandle,
  clearHandles,
  deleteSelected,
  deselect,
  dragHandle,
  layer,
  nudge,
  redo,
  removeHandle,
  reset,
  selectHandle,
  undo,
} from "./handles.js";
import { setMethod } from "./method.js";
import { cancelTraining, rigFile, saveRig, train } from "./rig.js";
import { loadSession, record, replay, saveSession } from "./session.js";
import { chooseShape, choosePart, loadRig, loadUrl, open, remesh, setOutline, setShape, startOver } from "./shape.js";
import {
  addBone,
  bones,
  brush,
  brushSize,
  jointTool,
  paintAt,
  removeBone,
  removeJoint,
  setJoints,
  setStiffness,
  setTool,
} from "./tools.js";

/** Every action and gesture, in the help panel's order (those without help lines after). */
export const REGISTRY: readonly (AnyAction | Gesture)[] = [
  addHandle,
  dragHandle,
  removeHandle,
  selectHandle,
  nudge,
  deleteSelected,
  deselect,
  undo,
  zoom,
  pan,
  captureKey,
  playPause,
  seek,
  fit,
  toggle,
  brush,
  brushSize,
  bones,
  jointTool,
  layer,
  train,
  loadRig,
  help,
  // Without a line in the help:
  redo,
  reset,
  clearHandles,
  display,
  hud,
  showMessage,
  open,
  loadUrl,
  setShape,
  setOutline,
  chooseShape,
  choosePart,
  remesh,
  startOver,
  setMethod,
  setTool,
  setStiffness,
  paintAt,
  addBone,
  removeBone,
  setJoints,
  removeJoint,
  record,
  replay,
  saveSession,
  loadSession,
  cancelTraining,
  rigFile,
  saveRig,
  exportMesh,
  exportSvg,
  exportPng,
  downloadPose,
  play,
  pause,
  moveKey,
  deleteKey,
  setKeyEasing,
  exportAnimation,
];

/** The actions (gestures left out), by name. */
export const ACTIONS: ReadonlyMap<string, AnyAction> = new Map(
  REGISTRY.filter((entry): entry is AnyAction => "perform" in entry).map((a) => [a.name, a]),
);

/** The help panel's lines, in order. */
export function helpLines(): HelpLine[] {
  return REGISTRY.flatMap((entry) => entry.help ?? []);
}
