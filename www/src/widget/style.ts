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
.group { display: flex; gap: 0.35em; align-items: center; flex-wrap: wrap; }
label { display: inline-flex; gap: 0.25em; align-items: center; white-space: nowrap; }
input[type="number"] { width: 5.5em; }
button { font: inherit; padding: 0.15em 0.6em; border: 1px solid #b9a78a; border-radius: 4px; background: #fffaf1; cursor: pointer; }
button:disabled { opacity: 0.45; cursor: default; }
button.active { background: #c0392b; color: white; border-color: #8e261b; }
button:focus-visible, select:focus-visible, input:focus-visible { outline: 2px solid #1d3557; outline-offset: 1px; }
.hidden { display: none !important; }
.stage { position: relative; flex: 1 1 auto; min-height: 0; overflow: hidden; }
canvas.mesh, canvas.overlay { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
canvas.overlay { touch-action: none; cursor: crosshair; }
.status { position: absolute; left: 0.6em; bottom: 0.4em; pointer-events: none; }
.status.error { color: #a00; font-weight: bold; background: rgba(255, 255, 255, 0.85); padding: 0.2em 0.4em; }
.hud {
  position: absolute; right: 0.5em; top: 0.5em; padding: 0.4em 0.6em; border-radius: 6px;
  background: rgba(20, 28, 40, 0.78); color: #e8f1ff; pointer-events: none;
}
.hud pre { margin: 0 0 0.3em; font: 11px/1.35 ui-monospace, monospace; }
.hud canvas { display: block; width: 240px; height: 48px; }
`;
