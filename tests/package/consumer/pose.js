// One definition of the consumer's check, used in Node, in the Vite app's worker and in the
// plain page's worker: the default shape meshed and rotated by its handles following an
// infinitesimal rotation; AKAP's spiral steps integrate it exactly, so every vertex must end
// rotated by the angle about the centre. Returns the largest error.
export function rotationError(akap) {
  const mesh = akap.triangulate(akap.defaultShape(), { targetEdgeLength: 0.08 });
  const deformer = new akap.Deformer(mesh.positions, mesh.triangles);
  try {
    deformer.setHandles([0, Math.floor(mesh.vertexCount / 2)]);
    const [a, cx, cy] = [0.25, 0.1, 0.6];
    const h = deformer.handlePositions();
    const velocities = [];
    for (let i = 0; i < h.length; i += 2) velocities.push(-a * (h[i + 1] - cy), a * (h[i] - cx));
    deformer.step(velocities);
    const p = deformer.positions();
    const [s, c] = [Math.sin(a), Math.cos(a)];
    let error = 0;
    for (let v = 0; v < mesh.vertexCount; v++) {
      const [x, y] = [mesh.positions[2 * v] - cx, mesh.positions[2 * v + 1] - cy];
      error = Math.max(error, Math.hypot(p[2 * v] - (cx + c * x - s * y), p[2 * v + 1] - (cy + s * x + c * y)));
    }
    return { vertices: mesh.vertexCount, error };
  } finally {
    deformer.free();
  }
}
