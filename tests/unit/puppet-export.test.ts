/** SVG export of a posed puppet: each part's art carried by its own sheet, back to front. */
import { beforeAll, describe, expect, it } from "vitest";
import { importPuppet, init, meshFromJson, meshFromObj, type ImportedPuppet } from "../../www/src/index.js";
import { posedMesh, puppetSvg } from "../../www/src/widget/store/pose-export.js";

beforeAll(async () => {
  await init();
});

// A torso (x 20 to 50, y 10 to 70 once y points up) with a button where the arm covers it
// (x 42 to 48, y 55 to 63, inside the overlap), and an arm in front (x 40 to 90, y 53 to
// 65) overlapping the shoulder.
const LAYERED = `<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" viewBox="0 0 100 100">
  <g inkscape:groupmode="layer" inkscape:label="torso">
    <rect x="20" y="30" width="30" height="60" fill="#3366cc"/>
    <rect x="42" y="37" width="6" height="8" fill="#ffcc00"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="arm">
    <rect x="40" y="35" width="50" height="12" fill="#cc3333"/>
  </g>
</svg>`;

/** Every number pair of absolute path data (M, L, Z only), y flipped back up. */
function points(d: string): [number, number][] {
  const numbers = d.match(/-?[\d.]+(?:e[-+]?\d+)?/g)!.map(Number);
  const result: [number, number][] = [];
  for (let i = 0; i < numbers.length; i += 2) result.push([numbers[i]!, -numbers[i + 1]!]);
  return result;
}

/** The layers of an SVG document in order: each `<g>`'s label and its paths' points. */
function layers(svg: string): { label: string; id: string; paths: [number, number][][] }[] {
  const groups = [
    ...svg.matchAll(/<g id="([^"]*)" inkscape:groupmode="layer" inkscape:label="([^"]*)">([\s\S]*?)<\/g>/g),
  ];
  return groups.map(([, id, label, body]) => ({
    id: id!,
    label: label!,
    paths: [...body!.matchAll(/ d="([^"]*)"/g)].map(([, d]) => points(d!)),
  }));
}

/** The area of a part's sheet: the sum of its triangles' areas. */
function sheetArea(puppet: ImportedPuppet, part: number, positions = puppet.positions): number {
  let area = 0;
  for (const t of puppet.parts[part]!.triangles) {
    const at = (k: number, axis: number): number => positions[2 * puppet.triangles[3 * t + k]! + axis]!;
    area += ((at(1, 0) - at(0, 0)) * (at(2, 1) - at(0, 1)) - (at(1, 1) - at(0, 1)) * (at(2, 0) - at(0, 0))) / 2;
  }
  return area;
}

describe("SVG export of a posed puppet", () => {
  it("turns the arm's art with the arm, keeps the torso's in place, back to front", () => {
    const puppet = importPuppet(LAYERED, { vertices: 600 });
    expect(puppet.parts.map((p) => p.name)).toEqual(["torso", "arm"]);
    expect(puppet.joints).toHaveLength(1);
    const [TORSO, ARM] = [0, 1];
    const [jx, jy] = puppet.joints[0]!.point;
    // The arm turned a quarter turn counter-clockwise about its joint; the torso still.
    const turn = (x: number, y: number): [number, number] => [jx - (y - jy), jy + (x - jx)];
    const posed = Float64Array.from(puppet.positions);
    const armVertices = new Set(
      [...puppet.parts[ARM]!.triangles].flatMap((t) => [0, 1, 2].map((k) => puppet.triangles[3 * t + k]!)),
    );
    for (const v of armVertices) posed.set(turn(puppet.positions[2 * v]!, puppet.positions[2 * v + 1]!), 2 * v);

    // Parts given front first: the export puts them back to front all the same.
    const svg = puppetSvg(puppet, [puppet.parts[ARM]!, puppet.parts[TORSO]!], posed);
    const out = layers(svg);
    expect(out.map((l) => [l.label, l.id])).toEqual([
      ["torso", "torso"],
      ["arm", "arm"],
    ]);
    const close = (got: [number, number][], want: [number, number][]) => {
      expect(got).toHaveLength(want.length);
      got.forEach(([x, y], i) => {
        expect(Math.hypot(x - want[i]![0], y - want[i]![1])).toBeLessThan(1e-9 * 100);
      });
    };
    const rest = (path: { points: Float64Array }): [number, number][] =>
      Array.from({ length: path.points.length / 2 }, (_, i) => [path.points[2 * i]!, path.points[2 * i + 1]!]);
    // The torso's paths, the button under the arm included, where they were.
    const torsoPaths = puppet.parts[TORSO]!.paths;
    expect(out[0]!.paths).toHaveLength(torsoPaths.length);
    torsoPaths.forEach((path, i) => close(out[0]!.paths[i]!, rest(path)));
    // The button lies under the arm at rest: a whole-mesh mapping could carry it off.
    const button = rest(torsoPaths[torsoPaths.length - 1]!);
    expect(button.every(([x, y]) => x >= 40 && x <= 90 && y >= 53 && y <= 65)).toBe(true);
    // The arm's paths turned about the joint.
    const armPaths = puppet.parts[ARM]!.paths;
    expect(out[1]!.paths).toHaveLength(armPaths.length);
    armPaths.forEach((path, i) =>
      close(
        out[1]!.paths[i]!,
        rest(path).map(([x, y]) => turn(x, y)),
      ),
    );

    // The file is a layered drawing again: the same parts, in the same order, of the same
    // areas (the arm turned rigidly), still joined.
    const again = importPuppet(svg, { vertices: 600 });
    expect(again.parts.map((p) => p.name)).toEqual(["torso", "arm"]);
    expect(again.parts[0]!.depth).toBeLessThan(again.parts[1]!.depth);
    expect(Math.abs(sheetArea(again, 0) / 1800 - 1)).toBeLessThan(0.01);
    expect(Math.abs(sheetArea(again, 1) / 600 - 1)).toBeLessThan(0.01);
    expect(again.joints).toHaveLength(1);
  });

  it("keeps names as labels and makes ids XML names, unique", () => {
    const puppet = importPuppet(LAYERED, { vertices: 300 });
    const [torso, arm] = puppet.parts;
    const renamed = [
      { ...torso!, name: 'left "arm"\n& <hand>' },
      { ...arm!, name: '2 left "arm"\n& <hand>', depth: 5 },
    ];
    const svg = puppetSvg(puppet, renamed, puppet.positions);
    expect(layers(svg).map((l) => l.id)).toEqual(["left__arm_____hand_", "part-2_left__arm_____hand_"]);
    const again = importPuppet(svg, { vertices: 300 });
    expect(again.parts.map((p) => p.name)).toEqual(['left "arm"\n& <hand>', '2 left "arm"\n& <hand>']);
  });

  it("writes a posed puppet's mesh that reads back as the puppet in that pose", () => {
    const puppet = importPuppet(LAYERED, { vertices: 300 });
    const [jx, jy] = puppet.joints[0]!.point;
    // The whole puppet moved by (10, 5), the arm also turned a quarter turn about the joint:
    // the joint goes to (jx + 10, jy + 5), where neither sheet was at rest.
    const arm = new Set(
      [...puppet.parts[1]!.triangles].flatMap((t) => [0, 1, 2].map((k) => puppet.triangles[3 * t + k]!)),
    );
    const posed = Float64Array.from(puppet.positions);
    for (let v = 0; v < posed.length / 2; v++) {
      let [x, y] = [posed[2 * v]!, posed[2 * v + 1]!];
      if (arm.has(v)) [x, y] = [jx - (y - jy), jy + (x - jx)];
      posed.set([x + 10, y + 5], 2 * v);
    }
    const shape = { mesh: { triangles: puppet.triangles }, uvs: new Float64Array(posed.length) };
    const extras = { puppet: { mesh: puppet, parts: puppet.parts, joints: puppet.joints } };
    const back = meshFromJson(posedMesh(shape, posed, "json", extras));
    expect(back.parts!.map((p) => [p.name, Array.from(p.triangles)])).toEqual(
      puppet.parts.map((p) => [p.name, Array.from(p.triangles)]),
    );
    const [x, y] = back.joints![0]!.point;
    expect(Math.hypot(x - (jx + 10), y - (jy + 5))).toBeLessThan(1e-9);
    // OBJ: the parts as groups.
    const obj = meshFromObj(posedMesh(shape, posed, "obj", extras));
    expect(obj.parts!.map((p) => p.name)).toEqual(["torso", "arm"]);
  });
});
