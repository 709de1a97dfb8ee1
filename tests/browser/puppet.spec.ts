/**
 * A layered puppet in the app, checked in the drawn pixels: the fixture
 * `tests/fixtures/svg/layered-puppet.svg` has a torso (green #2e8b57, used by nothing else)
 * whose square 120..140 x 110..130 (SVG units, y down) lies under the arm (blue #4169e1),
 * a head over the torso's top and a hat apart (#b22222 brim, #800000 crown). At rest the
 * arm hides that square; swung up about the shoulder, with the torso pinned, the arm
 * uncovers part of it and the torso's own green shows there. The hat is drawn, and the arm
 * draws over the torso. The joint tool moves a joint (refusing a place off a part), adds
 * one where parts overlap, and removes it, each an undo step.
 */
import { expect, test } from "@playwright/test";
import { idle, mapping, open, usePrepared } from "./helpers.js";
import { BLUE, BRIM, CROWN, FACE, GREEN, grid, loadPuppet, near, screen, svgToShape } from "./puppet-fixture.js";

usePrepared();

for (const renderer of ["webgl2", "2d"] as const) {
  test(`a layered SVG loads as a puppet; the arm over the torso, the hat drawn (${renderer})`, async ({ page }) => {
    if (renderer === "2d") {
      await page.addInitScript(() => {
        const getContext = HTMLCanvasElement.prototype.getContext;
        HTMLCanvasElement.prototype.getContext = function (this: HTMLCanvasElement, type: string, options?: unknown) {
          return type === "webgl2" ? null : getContext.call(this, type, options);
        } as typeof getContext;
      });
    }
    await page.setViewportSize({ width: 900, height: 700 });
    await open(page);
    await loadPuppet(page);
    expect(await page.evaluate(() => window.akapDemo!.widget.renderer)).toBe(renderer);
    const parts = await page.evaluate(() => window.akapDemo!.widget.parts.map((p) => p.name));
    expect(parts).toEqual(["Torso", "Head", "Arm", "Hat"]);
    // The Part list (one disconnected part at a time) is not offered for a puppet.
    await expect(page.locator("#app select[name=part]").locator("xpath=..")).toBeHidden();
    await page.screenshot({ path: `test-results/puppet-rest-${renderer}.png` });

    const svg = await svgToShape(page);
    const { toCss } = await mapping(page);
    const read = await screen(page);
    // The torso's square under the arm shows the arm's blue, no green.
    const covered = await read(grid(toCss, svg, [120, 110, 140, 130], 3));
    expect(covered.filter((c) => near(c, GREEN))).toHaveLength(0);
    expect(covered.filter((c) => near(c, BLUE)).length).toBe(covered.length);
    // The torso's green shows where nothing covers it (above the belt, left of the arm).
    const open_ = await read(grid(toCss, svg, [60, 130, 120, 190], 4));
    expect(open_.filter((c) => near(c, GREEN)).length).toBe(open_.length);
    // The torso's top edge runs under the head (y 100, the head down to 110): its outline is
    // hidden there, the face's colour shows on it.
    const neck = await read([90, 95, 100, 105, 110].map((x) => toCss(...svg(x, 100))));
    for (const c of neck) expect(near(c, FACE, 16), `face ${c}`).toBe(true);
    // The hat, apart from everything: its brim and crown in their colours.
    const [brim] = await read([toCss(...svg(100, 43))]);
    expect(near(brim!, BRIM), `brim ${brim}`).toBe(true);
    const [crown] = await read([toCss(...svg(100, 30))]);
    expect(near(crown!, CROWN), `crown ${crown}`).toBe(true);
  });
}

test("the torso hidden under the arm shows once the arm swings up about the shoulder", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadPuppet(page);
  const svg = await svgToShape(page);
  const { toCss } = await mapping(page);

  // The shoulder: the arm/torso joint moved (with the joint tool) to where the arm leaves the torso.
  const joints = await page.evaluate(() => window.akapDemo!.widget.joints);
  const armTorso = joints.findIndex((j) => j.parts[0] === 2 && j.parts[1] === 0);
  expect(armTorso, "a joint holds the arm to the torso").toBeGreaterThanOrEqual(0);
  const shoulder = svg(137, 120);
  await page.locator("#app select[name=tool]").selectOption("joint");
  await expect(page.locator("#app .brush-panel")).toContainText("Remove joint");
  await page.mouse.move(...toCss(...joints[armTorso]!.point));
  await page.mouse.down();
  await page.mouse.move(...toCss(...shoulder), { steps: 6 });
  await page.mouse.up();
  const moved = (await page.evaluate(() => window.akapDemo!.widget.joints))[armTorso]!;
  expect(moved.parts).toEqual([2, 0]);
  expect(Math.hypot(moved.point[0] - shoulder[0], moved.point[1] - shoulder[1])).toBeLessThan(
    (await mapping(page)).unit * 2,
  );
  await page.screenshot({ path: "test-results/puppet-joint-tool.png" });

  // Pose (J again, the widget focused by the drag): pins on the torso (low and middle), and
  // the hand swung a quarter turn up about the shoulder.
  await page.keyboard.press("j");
  expect(await page.evaluate(() => window.akapDemo!.widget.tool)).toBe("pose");
  for (const [x, y] of [
    [80, 200],
    [80, 150],
  ] as const)
    await page.mouse.click(...toCss(...svg(x, y)));
  const hand = svg(193, 120);
  const radius = Math.hypot(hand[0] - moved.point[0], hand[1] - moved.point[1]);
  const swing = (degrees: number): [number, number] => {
    const a = (degrees * Math.PI) / 180;
    return toCss(moved.point[0] + radius * Math.cos(a), moved.point[1] + radius * Math.sin(a));
  };
  const hatBefore = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    return Array.from(w.parts[3]!.triangles).map((f) => w.positions()[2 * w.mesh.triangles[3 * f]!]!);
  });
  await page.mouse.move(...swing(0));
  await page.mouse.down();
  for (let degrees = 5; degrees <= 90; degrees += 5) await page.mouse.move(...swing(degrees), { steps: 3 });
  await page.mouse.up();
  await idle(page);
  await page.screenshot({ path: "test-results/puppet-swung.png" });

  // The arm turned: the hand is above the shoulder now.
  const handNow = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions().slice(4, 6)));
  expect(handNow[1]! - moved.point[1]).toBeGreaterThan(0.8 * radius);
  // The hat, free, did not move at all.
  const hatAfter = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    return Array.from(w.parts[3]!.triangles).map((f) => w.positions()[2 * w.mesh.triangles[3 * f]!]!);
  });
  expect(hatAfter).toEqual(hatBefore);

  // The torso's square that the arm hid: the arm, turned about x = 137, leaves x 120..130 of it.
  const read = await screen(page);
  const uncovered = await read(grid(toCss, svg, [120, 110, 130, 130], 2.5, 6));
  const green = uncovered.filter((c) => near(c, GREEN)).length;
  expect(green, "the torso's own art shows where the arm was").toBeGreaterThan(uncovered.length / 2);
  // The hat is still drawn.
  const [crown] = await read([toCss(...svg(100, 30))]);
  expect(near(crown!, CROWN)).toBe(true);

  // Re-meshed, the pose carries over part by part: the arm stays up, the torso shows.
  await page.evaluate(() => window.akapDemo!.widget.remesh(900));
  await idle(page);
  const handAfter = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions().slice(4, 6)));
  expect(Math.hypot(handAfter[0]! - handNow[0]!, handAfter[1]! - handNow[1]!)).toBeLessThan(0.02 * radius);
  const again = await screen(page);
  const shown = await again(grid(toCss, svg, [120, 110, 130, 130], 2.5, 6));
  expect(shown.filter((c) => near(c, GREEN)).length).toBeGreaterThan(shown.length / 2);
  await page.screenshot({ path: "test-results/puppet-swung-remeshed.png" });

  // The SVG export is itself a layered file, a layer per part back to front (each part's
  // art carried by its own sheet: tests/unit/puppet-export.test.ts), and the mesh export
  // carries the parts.
  const exported = await page.evaluate(() => window.akapDemo!.widget.exportSvg());
  const labels = [...exported.matchAll(/inkscape:label="([^"]*)"/g)].map((m) => m[1]);
  expect(labels).toEqual(["Torso", "Head", "Arm", "Hat"]);
  const mesh = await page.evaluate(() => window.akapDemo!.widget.exportMesh("json"));
  expect(JSON.parse(mesh).parts.map((p: { name: string }) => p.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
});

test("the joint tool refuses a joint moved off its parts, adds one where parts overlap, and removes it", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadPuppet(page);
  const svg = await svgToShape(page);
  const { toCss } = await mapping(page);
  const before = await page.evaluate(() => window.akapDemo!.widget.joints);
  await page.evaluate(() => window.akapDemo!.widget.setTool("joint"));

  // A joint dragged off the arm (to the torso's lower left): refused, said, unchanged.
  const armTorso = before.findIndex((j) => j.parts[0] === 2 && j.parts[1] === 0);
  await page.mouse.move(...toCss(...before[armTorso]!.point));
  await page.mouse.down();
  await page.mouse.move(...toCss(...svg(70, 210)), { steps: 5 });
  await page.mouse.up();
  await expect(page.locator("#app .status")).toContainText("must lie on both");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(before);

  // A click on the arm's hand, over nothing: no joint (only one part there).
  await page.mouse.click(...toCss(...svg(195, 120)));
  await expect(page.locator("#app .status")).toContainText("two parts");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(before);

  // A click where the arm lies over the torso (their overlap is SVG 120..140 x 110..130), at
  // the point of it farthest from the joints: a second arm/torso joint there.
  const candidates: [number, number][] = [];
  for (let x = 122; x <= 138; x += 2) for (let y = 112; y <= 128; y += 2) candidates.push(svg(x, y));
  const gap = (p: [number, number]) => Math.min(...before.map((j) => Math.hypot(p[0] - j.point[0], p[1] - j.point[1])));
  const at = candidates.reduce((a, b) => (gap(b) > gap(a) ? b : a));
  await page.mouse.click(...toCss(...at));
  const added = await page.evaluate(() => window.akapDemo!.widget.joints);
  expect(added).toHaveLength(before.length + 1);
  const joint = added.at(-1)!;
  expect(joint.parts).toEqual([2, 0]);
  expect(Math.hypot(joint.point[0] - at[0], joint.point[1] - at[1])).toBeLessThan((await mapping(page)).unit * 2);

  // Selected: Delete removes it; undo brings it back, undo again takes the add back.
  await page.keyboard.press("Delete");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(before);
  await page.keyboard.press("Control+z");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(added);
  await page.keyboard.press("Control+z");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(before);

  // The API refuses a joint whose point is off its parts, changing nothing.
  const code = await page.evaluate(() => {
    try {
      window.akapDemo!.widget.setJoints([{ point: [1e6, 1e6], parts: [2, 0] }]);
      return "accepted";
    } catch (error) {
      return (error as { code?: string }).code;
    }
  });
  expect(code).toBe("invalid-joint");
  expect(await page.evaluate(() => window.akapDemo!.widget.joints)).toEqual(before);
});

test("a handle goes on the front-most part; Back sends that part behind; MLS says it poses one shape; re-meshing keeps the puppet", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadPuppet(page);
  const svg = await svgToShape(page);
  const { toCss } = await mapping(page);
  const depth = (name: string) =>
    page.evaluate((name) => window.akapDemo!.widget.parts.find((p) => p.name === name)!.depth, name);
  // The part of the square under the arm away from the handle (its disc covers the rest).
  const square = grid(toCss, svg, [120, 110, 131, 121], 2, 4);

  // A click where the arm lies over the torso: the handle is the arm's (selected, as added).
  await page.mouse.click(...toCss(...svg(137, 127)));
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(1);
  const [arm, torso] = [await depth("Arm"), await depth("Torso")];
  expect(arm).toBeGreaterThan(torso);
  // Back: the arm goes one step back, behind the head; again, behind the torso.
  await page.getByRole("button", { name: "Back" }).click();
  expect(await depth("Arm")).toBeGreaterThan(await depth("Torso"));
  await page.getByRole("button", { name: "Back" }).click();
  expect(await depth("Arm")).toBeLessThan(await depth("Torso"));
  let read = await screen(page);
  expect((await read(square)).filter((c) => near(c, GREEN)).length).toBe(square.length);
  // Undone: the arm is over the torso again.
  await page.keyboard.press("Control+z");
  await page.keyboard.press("Control+z");
  expect(await depth("Arm")).toBe(arm);
  read = await screen(page);
  expect((await read(square)).filter((c) => near(c, BLUE)).length).toBe(square.length);

  // Moving least squares has no sheets: the status line says the puppet is posed as one shape.
  await page.locator("#app select[name=method]").selectOption("mls");
  await expect(page.locator("#app .status")).toContainText("whole puppet as one shape");
  await page.locator("#app select[name=method]").selectOption("akap");

  // Re-meshed at about half the vertices: still a puppet of the same parts and joints.
  const before = await page.evaluate(() => ({
    vertices: window.akapDemo!.widget.vertexCount,
    joints: window.akapDemo!.widget.joints,
  }));
  await page.evaluate(() => window.akapDemo!.widget.remesh(800));
  await idle(page);
  const after = await page.evaluate(() => ({
    vertices: window.akapDemo!.widget.vertexCount,
    parts: window.akapDemo!.widget.parts.map((p) => p.name),
    joints: window.akapDemo!.widget.joints,
    handles: window.akapDemo!.widget.handleCount,
  }));
  expect(after.vertices).toBeLessThan(0.75 * before.vertices);
  expect(after.parts).toEqual(["Torso", "Head", "Arm", "Hat"]);
  expect(after.joints).toEqual(before.joints);
  expect(after.handles).toBe(1);
  read = await screen(page);
  expect((await read(square)).filter((c) => near(c, BLUE)).length).toBe(square.length);
  await page.screenshot({ path: "test-results/puppet-remeshed.png" });
});

test("a rig trains on the puppet with its joints, and a joint moved leaves it stale", async ({ page }) => {
  await open(page);
  await loadPuppet(page);
  await page.evaluate(() => window.akapDemo!.widget.remesh(600));
  await idle(page);
  const svg = await svgToShape(page);
  const { toCss } = await mapping(page);
  for (const [x, y] of [
    [80, 200],
    [190, 120],
  ] as const)
    await page.mouse.click(...toCss(...svg(x, y)));
  const state = await page.evaluate(async () => {
    const w = window.akapDemo!.widget;
    await w.train({ samples: 8, energy: "arap", workers: 0, cache: false });
    return w.rig.state;
  });
  expect(state).toBe("ready");
  // The joint moved (with the joint tool's call): the rig was trained with the old one.
  const stale = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    const joints = w.joints.map((j) => ({ ...j, point: [...j.point] as [number, number] }));
    const arm = joints.findIndex((j) => j.parts[0] === 2);
    joints[arm]!.point[0] += 0.5 / w.view.scale;
    w.setJoints(joints);
    return w.rig.state;
  });
  expect(stale).toBe("stale");
});
