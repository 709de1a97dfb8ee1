/**
 * Actions on recorded sessions: record, replay, save and load.
 */
import { limits } from "../../core.js";
import { parseSession, type Session } from "../../session.js";
import { sessionShape } from "../model/shape.js";
import { download } from "../store/pose-export.js";
import { action } from "./action.js";
import type { WidgetParts } from "./context.js";

/**
 * Starts (`on` true) or stops (false) recording every change of the deformer, or toggles
 * it; stopping returns the session (which Replay and Save then offer).
 */
export const record = action({
  name: "record",
  description: "Starts or stops recording every change of the deformer",
  controls: [
    {
      kind: "button",
      id: "record",
      text: "Record",
      title: "Record the interaction",
      refresh: (state) => ({ text: state.recording ? "Stop" : "Record", active: state.recording }),
    },
  ],
  perform(parts, { on }: { on?: boolean } = {}): Session | undefined {
    const posing = parts.posing;
    if (on ?? !posing.recording) {
      posing.startRecording();
      return undefined;
    }
    const session = posing.stopRecording();
    if (session) parts.lastSession = session;
    parts.refreshButtons();
    return session;
  },
});

/** See `Widget.replay`; without a session, the last one recorded or loaded (if any). */
export const replay = action({
  name: "replay",
  description: "Replays a recorded session bit for bit",
  controls: [
    {
      kind: "button",
      id: "replay",
      text: "Replay",
      title: "Replay the last recording",
      refresh: (state) => ({ disabled: !state.hasSession || state.recording }),
    },
  ],
  async perform(
    parts,
    { session, stepsPerFrame = 4 }: { session?: Session | string; stepsPerFrame?: number } = {},
  ): Promise<Float64Array | undefined> {
    const given = session ?? parts.lastSession;
    if (given === undefined) return undefined;
    const s = typeof given === "string" ? parseSession(given) : given;
    await replaySession(parts, s, stepsPerFrame);
    parts.refreshButtons();
    parts.frames.poseChanged();
    return parts.posing.deformer.positions();
  },
});

export const saveSession = action({
  name: "save-session",
  description: "Downloads the last recording as JSON",
  controls: [
    {
      kind: "button",
      id: "save-session",
      text: "Save",
      title: "Save the last recording as JSON",
      refresh: (state) => ({ disabled: !state.hasSession }),
    },
  ],
  perform(parts): void {
    if (!parts.lastSession) return;
    download(parts.document, parts.lastSession.json, "session.akap.json", "application/json");
  },
});

/** See `Widget.loadSession`. */
export const loadSession = action({
  name: "load-session",
  description: "Loads a recorded session from a file and replays it",
  controls: [
    {
      kind: "file",
      id: "load-session",
      text: "Load",
      title: "Load a recorded session and replay it",
      input: "session-file",
      accept: ".json,application/json",
      args: (file) => ({ file }),
    },
  ],
  async perform(parts, { file }: { file: Blob }): Promise<void> {
    const most = limits().sessionBytes;
    if (file.size > most) throw new Error(`the session is ${file.size} bytes; sessions are limited to ${most}`);
    const session = parseSession(await file.text());
    await replay.perform(parts, { session });
    parts.lastSession = session;
    parts.refreshButtons();
  },
});

/**
 * See `Widget.replay`: the session's shape rebuilt if needed, then `Posing.replay`, drawn
 * every `stepsPerFrame` steps (`data-replaying` on the widget's element meanwhile).
 */
async function replaySession(host: WidgetParts, session: Session, stepsPerFrame: number): Promise<void> {
  const posing = host.posing;
  if (posing.replaying) throw new Error("a replay is already running");
  const shape = sessionShape(session, posing.shape);
  host.root.dataset.replaying = "true";
  try {
    await posing.replay(session, shape, async (steps) => {
      if (steps % stepsPerFrame === 0) {
        host.render();
        await new Promise((resolve) => requestAnimationFrame(resolve));
      }
      return !host.destroyed();
    });
  } finally {
    delete host.root.dataset.replaying;
  }
}
