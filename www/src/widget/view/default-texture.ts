/**
 * The default texture of built-in shapes: a warm fill with a grid of "icing" lines, so
 * that the deformation shows inside the shape and not only at its outline.
 */
export function defaultTexture(size = 1024): HTMLCanvasElement {
  const canvas = document.createElement("canvas");
  canvas.width = size;
  canvas.height = size;
  const ctx = canvas.getContext("2d");
  if (!ctx) return canvas;
  const gradient = ctx.createLinearGradient(0, 0, size, size);
  gradient.addColorStop(0, "#d08545");
  gradient.addColorStop(1, "#b8672e");
  ctx.fillStyle = gradient;
  ctx.fillRect(0, 0, size, size);
  const cells = 24;
  for (let k = 0; k <= cells; k++) {
    const at = (k / cells) * size;
    ctx.strokeStyle = k % 4 === 0 ? "rgba(255, 244, 225, 0.85)" : "rgba(255, 236, 205, 0.45)";
    ctx.lineWidth = k % 4 === 0 ? 4 : 2;
    ctx.beginPath();
    ctx.moveTo(at, 0);
    ctx.lineTo(at, size);
    ctx.moveTo(0, at);
    ctx.lineTo(size, at);
    ctx.stroke();
  }
  return canvas;
}
