/**
 * The animation: keys captured, moved, eased and deleted, playback, seeking, and the
 * animation's exports. The timeline strip (`animation/timeline-strip.ts`) has its own
 * controls; these are the keys', the help's and the public API's.
 */
import type { AnimationExport } from "../animation/controller.js";
import type { AnimationExportFormat, AnimationExportOptions } from "../animation/formats.js";
import type { Easing } from "../animation/timeline.js";
import { action } from "./action.js";

/** Captures the pose as a key at `time` s (default: the playhead); returns its index. */
export const captureKey = action({
  name: "capture-key",
  description: "Captures the pose as an animation key",
  help: [
    { keys: "K", does: "animation: capture the pose as a key at the playhead (the timeline strip under the stage)" },
  ],
  keys: [{ keys: ["k"] }],
  perform: (parts, { time, easing }: { time?: number; easing?: Easing } = {}): number =>
    parts.animation.capture(time, easing),
});

export const playPause = action({
  name: "play-pause",
  description: "Plays or pauses the animation",
  help: [{ keys: "Space (tap)", does: "play or pause the animation" }],
  perform: (parts): void => parts.animation.playPause(),
});

/** Shows the frame at `time` s (one undoable step). */
export const seek = action({
  name: "seek",
  description: "Shows the animation's frame at a time",
  help: [
    {
      keys: "Timeline: drag the playhead (or arrows, Home, End on it); drag a key; Delete",
      does: "scrub (each frame's pose shows); move the key; delete the selected key",
    },
  ],
  perform: (parts, { time }: { time: number }): void => parts.animation.animator.seek(time),
});

/** Plays from the playhead (`loop`: again and again); resolves when playback stops. */
export const play = action({
  name: "play",
  description: "Plays the animation",
  perform: (parts, options: { loop?: boolean } = {}): Promise<void> => parts.animation.animator.play(options),
});

export const pause = action({
  name: "pause",
  description: "Stops playback at the frame on screen",
  perform: (parts): void => parts.animation.animator.pause(),
});

export const moveKey = action({
  name: "move-key",
  description: "Moves a key to another time",
  perform: (parts, { index, time }: { index: number; time: number }): number =>
    parts.animation.animator.moveKey(index, time),
});

export const deleteKey = action({
  name: "delete-key",
  description: "Deletes a key",
  perform: (parts, { index }: { index: number }): void => parts.animation.animator.deleteKey(index),
});

export const setKeyEasing = action({
  name: "set-key-easing",
  description: "Sets the easing of the segment that ends at a key",
  perform: (parts, { index, easing }: { index: number; easing: Easing }): void =>
    parts.animation.animator.setEasing(index, easing),
});

export const exportAnimation = action({
  name: "export-animation",
  description: "The animation as a file",
  perform: (
    parts,
    { format, options = {} }: { format: AnimationExportFormat; options?: AnimationExportOptions },
  ): Promise<AnimationExport> => parts.animation.export(format, options),
});
