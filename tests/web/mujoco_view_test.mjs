// The web page draws a MuJoCo scene (J3) in a real browser (Debian's chromium, headless, driven
// by playwright-core) against the real stack on loopback: core (1 ms), UDP bridge, LCM bridge,
// hapticctrl-mujoco on the shipped table with blocks, web bridge. The page draws every geom of
// the model where the engine has it; pushed by the operator (the page's force slider), the handle
// pushes the tool into the red block, whose drawn box moves along the table, and the contact
// planes the body reports are drawn. Screenshots go to $HAPTICCTRL_ARTIFACTS.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { openPage } from './support/browser.mjs';
import { Stack, until } from './support/stack.mjs';

const artifacts = process.env.HAPTICCTRL_ARTIFACTS ?? 'test-artifacts/web';
mkdirSync(artifacts, { recursive: true });

const stack = new Stack('mujoco');
let browser;
let page;
let pageErrors = [];

/** The world as the page received it and as it draws it. */
const pageWorld = () => page.evaluate(() => {
  const s = window.hapticctrl;
  return {
    world: s.frame?.world ?? null,
    drawn: s.view?.world.drawnPositions() ?? [],
    contactsDrawn: s.view?.world.drawnContacts() ?? 0,
    framesRendered: s.view?.framesRendered ?? 0,
    contactText: document.getElementById('contact').textContent,
  };
});
const shot = (name) => page.screenshot({ path: join(artifacts, `${name}.png`) });

before(async () => {
  await stack.start({ scene: 'table_blocks' });
  ({ browser, page, pageErrors } = await openPage());
});

after(async () => {
  await browser?.close();
  await stack.stop();
  writeFileSync(join(artifacts, 'mujoco-processes.log'), stack.logs());
});

test('the page draws every geom of the scene where the engine has it', async () => {
  await page.goto(stack.url);
  const w = await until(async () => {
    const s = await pageWorld();
    return s.world && s.framesRendered > 0 && s.drawn.length === s.world.geoms.length ? s : null;
  }, { timeoutMs: 15000 });
  assert.ok(w, `no world drawn: ${JSON.stringify(await pageWorld())}\n${stack.logs()}`);
  // The table, the tool, three blocks and the tower's base: every one a box.
  assert.equal(w.world.geoms.length, 6);
  assert.equal(w.world.geoms_total, 6);
  assert.ok(w.world.geoms.every((g) => g.type === 6), JSON.stringify(w.world.geoms.map((g) => g.type)));
  assert.equal(w.world.geoms.filter((g) => g.coupled).length, 1, 'the tool is the held body');
  w.drawn.forEach((p, i) => {
    assert.ok(p, `geom ${i} is not drawn`);
    const at = w.world.geoms[i].pose;
    assert.ok(Math.hypot(p[0] - at[0], p[1] - at[1], p[2] - at[2]) < 1e-9, `geom ${i} drawn at ${p}, is at ${at}`);
  });
  assert.match(w.contactText, /of 1000 steps\/s/);
  assert.deepEqual(pageErrors, []);
  await shot('mujoco-01-scene');
});

// Instrumented (ASan, TSan), the 1 ms core and the engine are slowed past the physics this judges;
// the drawing is judged above in every build.
const physics = process.env.HAPTICCTRL_SANITIZED ? { skip: 'sanitized build: drawing only' } : {};

test('pushed by the operator, the tool pushes the red block and its drawn box moves', physics, async () => {
  // Which geom is the red block: the one in front of the tool along +x (the scene's 0.06 m).
  await until(() => stack.status().powered, { timeoutMs: 10000 });
  const start = await pageWorld();
  const tool = start.world.geoms.findIndex((g) => g.coupled);
  const red = start.world.geoms.findIndex((g, i) => i !== tool
    && Math.abs(g.pose[0] - start.world.geoms[tool].pose[0] - 0.06) < 0.005
    && Math.abs(g.pose[1] - start.world.geoms[tool].pose[1]) < 0.005);
  assert.ok(red >= 0, `no block in front of the tool: ${JSON.stringify(start.world.geoms)}`);
  const table = start.world.geoms.reduce((big, g, i, all) => (g.size[0] > all[big].size[0] ? i : big), 0);
  let contactsSeen = 0;
  let moved = null;
  try {
    await page.locator('[data-testid=slider-Fx]').fill('4');
    moved = await until(async () => {
      const s = await pageWorld();
      contactsSeen = Math.max(contactsSeen, s.contactsDrawn);
      return s.drawn[red][0] - start.drawn[red][0] > 0.01 ? s : null;
    }, { timeoutMs: 15000, everyMs: 100 });
    await shot('mujoco-02-pushed');
  } finally {
    await page.click('[data-testid=release]');
  }
  assert.ok(moved, `the red block's drawn box did not move 1 cm: ${JSON.stringify(await pageWorld())}\n${stack.logs()}`);
  assert.ok(contactsSeen > 0, 'the contact planes the tool reported were never drawn');
  assert.deepEqual(moved.drawn[table], start.drawn[table], 'the table stays');
  assert.deepEqual(pageErrors, []);
});
