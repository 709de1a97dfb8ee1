/** The widget's CSS, inside its shadow root (nothing leaks into the page). */
export const WIDGET_CSS = `
:host { all: initial; display: block; width: 100%; height: 100%; }
.widget {
  display: flex; flex-direction: column; width: 100%; height: 100%; min-height: 200px;
  font: 13px/1.35 system-ui, sans-serif; color: #2b1a0c; background: #f6f1e7; outline: none;
}
.widget:focus-visible { box-shadow: inset 0 0 0 2px #1d3557; }
.toolbar {
  display: flex; flex-wrap: wrap; gap: 0.3em 1em; align-items: center; padding: 0.35em 0.6em;
  border-bottom: 1px solid #dccfb8; background: #efe6d6;
}
.toolbar .quick, .toolbar .tools { display: contents; }
.toolbar .more { display: none; }
.group { display: flex; gap: 0.35em; align-items: center; flex-wrap: wrap; }
label { display: inline-flex; gap: 0.25em; align-items: center; white-space: nowrap; }
input[type="number"] { width: 5.5em; }
button { font: inherit; padding: 0.15em 0.6em; border: 1px solid #b9a78a; border-radius: 4px; background: #fffaf1; cursor: pointer; }
button:disabled { opacity: 0.45; cursor: default; }
button.active { background: #c0392b; color: white; border-color: #8e261b; }
button:focus-visible, select:focus-visible, input:focus-visible { outline: 2px solid #1d3557; outline-offset: 1px; }
.hidden { display: none !important; }
.brush-panel {
  position: absolute; left: 0.6em; bottom: 2.4em; display: flex; gap: 0.4em; align-items: center;
  padding: 0.35em 0.6em; border-radius: 8px; background: rgba(255, 250, 241, 0.95);
  box-shadow: 0 2px 12px rgba(0, 0, 0, 0.2);
}
.tool-controls { display: flex; gap: 0.4em; align-items: center; }
.stage { position: relative; flex: 1 1 auto; min-height: 0; overflow: hidden; }
canvas.mesh, canvas.overlay { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
canvas.overlay { touch-action: none; cursor: crosshair; }
canvas.overlay.panning { cursor: grab; }
.status { position: absolute; left: 0.6em; bottom: 0.4em; right: 0.6em; pointer-events: none; }
.status.info, .status.error { background: rgba(255, 255, 255, 0.88); padding: 0.2em 0.4em; border-radius: 4px; width: fit-content; }
.status.error { color: #a00; font-weight: bold; }
.hud {
  position: absolute; right: 0.5em; top: 0.5em; padding: 0.4em 0.6em; border-radius: 6px;
  background: rgba(20, 28, 40, 0.78); color: #e8f1ff; pointer-events: none;
}
.hud.clear { opacity: 0.1; }
.hud pre { margin: 0 0 0.3em; font: 11px/1.35 ui-monospace, monospace; }
.hud canvas { display: block; width: 240px; height: 48px; }
.busy {
  position: absolute; left: 50%; top: 40%; transform: translate(-50%, -50%); display: flex; gap: 0.6em;
  align-items: center; padding: 0.6em 0.9em; border-radius: 8px; background: rgba(255, 250, 241, 0.95);
  box-shadow: 0 2px 12px rgba(0, 0, 0, 0.2);
}
.busy progress { width: 10em; }
.training {
  position: absolute; left: 0.6em; top: 0.6em; display: flex; gap: 0.6em; align-items: center;
  padding: 0.4em 0.6em; border-radius: 8px; background: rgba(255, 250, 241, 0.95);
  box-shadow: 0 2px 12px rgba(0, 0, 0, 0.2);
}
.training progress { width: 8em; }
.help {
  position: absolute; inset: 1em; max-width: 34em; margin: auto; height: fit-content; max-height: calc(100% - 2em);
  overflow: auto; padding: 0.8em 1.1em; border-radius: 8px; background: #fffaf1; box-shadow: 0 4px 24px rgba(0, 0, 0, 0.3);
}
.help h2 { font-size: 1.1em; margin: 0 0 0.5em; }
.help dl { display: grid; grid-template-columns: max-content 1fr; gap: 0.25em 1em; margin: 0 0 0.8em; }
.help dt { font-weight: bold; }
.help dd { margin: 0; }
.timeline {
  display: flex; flex-wrap: wrap; gap: 0.3em 0.6em; align-items: center; padding: 0.35em 0.6em;
  border-top: 1px solid #dccfb8; background: #efe6d6;
}
.timeline .track {
  position: relative; flex: 1 1 12em; min-width: 8em; height: 1.9em; border-radius: 4px;
  background: repeating-linear-gradient(90deg, #fffaf1 0 calc(50% - 1px), #e4d8c3 calc(50% - 1px) 50%);
  border: 1px solid #b9a78a; cursor: pointer; touch-action: none;
}
.timeline .playhead { position: absolute; top: -2px; bottom: -2px; width: 2px; margin-left: -1px; background: #1d3557; pointer-events: none; }
.timeline .marker {
  position: absolute; top: 50%; width: 0.9em; height: 0.9em; min-width: 0; min-height: 0; padding: 0;
  transform: translate(-50%, -50%) rotate(45deg); background: #c8773a; border: 1px solid #5a2d0c; border-radius: 2px;
}
.timeline .marker.selected { background: #c0392b; box-shadow: 0 0 0 2px #1d3557; }
.timeline .readout { font-variant-numeric: tabular-nums; min-width: 13em; }
.timeline input.fps { width: 3.5em; }
/* Narrow widgets (phones): the tools fold behind a button, targets are finger-sized and the
   HUD is one small block out of the way. */
.compact .toolbar { gap: 0.3em; padding: 0.25em 0.4em; }
.compact .toolbar .more { display: inline-block; }
.compact .toolbar .quick { display: flex; gap: 0.3em; }
.compact .toolbar .tools { display: none; }
.compact .toolbar.open .tools { display: flex; flex-wrap: wrap; gap: 0.3em 0.8em; width: 100%; }
.compact button, .compact select, .compact input[type="number"] { min-height: 44px; min-width: 44px; }
.compact label:has(input[type="checkbox"]) { min-height: 44px; }
.compact input[type="checkbox"] { width: 22px; height: 22px; }
.compact .hud { top: auto; bottom: 2.4em; padding: 0.25em 0.4em; }
.compact .hud pre { font-size: 10px; }
.compact .hud canvas { display: none; }
.compact .timeline { gap: 0.25em 0.4em; padding: 0.25em 0.4em; }
.compact .timeline .track { flex-basis: 100%; order: 9; height: 2.6em; }
.compact .timeline .readout, .compact .timeline label:has(input.fps) { display: none; }
.compact .timeline select { max-width: 7em; }
.compact .timeline .marker { width: 1.4em; height: 1.4em; }
.compact .help dl { grid-template-columns: 1fr; }
.compact .help dd { margin-bottom: 0.4em; }
`;
