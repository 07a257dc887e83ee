// The operator web page in a real browser (Debian's chromium, headless, driven by
// playwright-core) against the real controller stack on loopback: the page loads and draws the
// arm, power-on from the page powers the arm (read back from shared memory with hapticctrl-hmi),
// a force slider moves the handle, the emergency stop latches, losing the LCM bridge or the web
// bridge is shown, and the reason of a controller that stopped or failed safe is shown. Screenshots go to
// $HAPTICCTRL_ARTIFACTS.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { openPage } from './support/browser.mjs';
import { Stack, until } from './support/stack.mjs';

const artifacts = process.env.HAPTICCTRL_ARTIFACTS ?? 'test-artifacts/web';
mkdirSync(artifacts, { recursive: true });

const stack = new Stack('view');
let browser;
let page;
let pageErrors = [];

/** window.hapticctrl, the page's own status object, as plain JSON. */
const pageStatus = () => page.evaluate(() => {
  const s = window.hapticctrl;
  return {
    connected: s.connected,
    webgl: s.webgl,
    framesReceived: s.framesReceived,
    framesRendered: s.view?.framesRendered ?? 0,
    modelMismatchM: s.modelMismatchM,
    remote: s.hello?.remote_commands,
    arm: s.frame?.arm,
    scene: s.frame?.scene,
    silent: s.frame?.controller_silent,
    plots: s.plots.counts(),
  };
});
const alarm = () => page.locator('[data-testid=alarm]');
const alarmText = async () => ((await alarm().isVisible()) ? alarm().innerText() : '');
const shot = (name) => page.screenshot({ path: join(artifacts, `${name}.png`) });
const OPERATOR_ARROW = [0xf0, 0xc0, 0x40];
const RENDERED_ARROW = [0xff, 0x4f, 0xd8];
/** Pixels a force arrow needs to be seen at a glance (a 1024 x 768 page). */
const MIN_ARROW_PIXELS = 40;
/**
 * The 3D canvas as drawn: its distinct colours (every 97th pixel) and how many pixels are within
 * a small distance of `rgb` (antialiased edges half counted; none asked: 0).
 */
const canvasPixels = (rgb = null) => page.evaluate((colour) => {
  const source = document.getElementById('scene');
  const copy = document.createElement('canvas');
  copy.width = source.width;
  copy.height = source.height;
  const context = copy.getContext('2d');
  context.drawImage(source, 0, 0);
  const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
  const seen = new Set();
  let near = 0;
  for (let i = 0; i < pixels.length; i += 4) {
    if (i % (4 * 97) === 0) seen.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
    if (!colour) continue;
    const d = Math.abs(pixels[i] - colour[0]) + Math.abs(pixels[i + 1] - colour[1]) + Math.abs(pixels[i + 2] - colour[2]);
    if (d < 40) near += 1;
  }
  return { colours: seen.size, near };
}, rgb);
const colourPixels = async (rgb) => (await canvasPixels(rgb)).near;

before(async () => {
  await stack.start();
  ({ browser, page, pageErrors } = await openPage());
});

after(async () => {
  await browser?.close();
  await stack.stop();
  writeFileSync(join(artifacts, 'processes.log'), stack.logs());
});

test('the page loads, connects and draws the arm and the spheres', async () => {
  await page.goto(stack.url);
  const s = await until(async () => {
    const status = await pageStatus();
    return status.framesReceived > 5 && status.scene && status.framesRendered > 0 ? status : null;
  }, { timeoutMs: 10000 });
  assert.ok(s, `no live frames: ${JSON.stringify(await pageStatus())}\n${stack.logs()}`);
  assert.equal(s.connected, true);
  assert.equal(s.webgl, true, 'WebGL unavailable');
  assert.equal(s.remote, true);
  assert.ok(s.modelMismatchM < 0.002, `the page's kinematics put the handle ${s.modelMismatchM} m off`);
  // The canvas holds a picture, not a blank clear colour: count distinct colours.
  const { colours } = await canvasPixels();
  assert.ok(colours > 20, `the 3D canvas looks empty (${colours} colours)`);
  assert.deepEqual(pageErrors, []);
  await shot('01-loaded');
});

test('power on from the page powers the arm', async () => {
  assert.equal(stack.status().powered, false);
  await page.click('[data-testid=power-on]');
  assert.ok(await until(() => stack.status().powered), 'the core did not power on');
  await until(async () => (await page.locator('[data-testid=power]').innerText()) === 'powered');
  assert.equal(await page.locator('[data-testid=power]').innerText(), 'powered');
});

test('the surface the controller renders on the handle is drawn while the hand pushes on it', async () => {
  // J2: pushed toward the demo's fixed sphere's centre, the handle meets its surface, which the
  // controller renders in its servo cycle: the page draws its plane and says what it renders.
  // Toward the centre, right after power-on, where the demo put the spheres: after the slider
  // tests, pushed along +x from off the line of centres, the push's part along the surface beat
  // its friction and the handle slid around the sphere (3 of 3 beside stress-ng, 2026-12-05).
  const toward = await page.evaluate(() => {
    const f = window.hapticctrl.frame;
    const d = f.scene.fixed_center.map((c, i) => c - f.arm.handle_pose[i]);
    const n = Math.hypot(...d);
    return d.map((x) => Math.round((8 * x) / n / 0.5) * 0.5); // 8 N, the sliders' 0.5 N steps
  });
  try {
    for (const [i, axis] of ['Fx', 'Fy', 'Fz'].entries()) {
      await page.locator(`[data-testid=slider-${axis}]`).fill(String(toward[i]));
    }
    const surface = () => page.evaluate(() => {
      const v = window.hapticctrl.view;
      const c = window.hapticctrl.frame?.coupling;
      return { visible: !!v?.surface.visible, force: c?.surface_force ?? 0,
        normal: c?.surface_normal, text: document.getElementById('surface').textContent };
    });
    const s = await until(async () => {
      const now = await surface();
      return now.visible && now.force > 4 ? now : null;
    }, { timeoutMs: 8000 });
    assert.ok(s, `no rendered surface: ${JSON.stringify(await surface())} pushed ${JSON.stringify(toward)}`);
    assert.ok(Math.abs(Math.hypot(...s.normal) - 1) < 1e-3, `a unit normal: ${JSON.stringify(s.normal)}`);
    assert.match(s.text, /N · [0-9.]+ mm deep/);
    // The force rendered on the hand is drawn too (J8: 0 of its pixels in 4 screenshots with
    // -5.97 N): pointing out of the sphere, over it.
    // Counted on the frames drawn in the next 2 s (at most 25 a second; software WebGL on a
    // loaded machine draws fewer), the push held all along.
    let pixels = 0;
    await until(async () => (pixels = await colourPixels(RENDERED_ARROW)) >= MIN_ARROW_PIXELS, { timeoutMs: 2000 });
    const rendered = await page.evaluate(() => Math.hypot(...window.hapticctrl.frame.arm.rendered_wrench.slice(0, 3)));
    console.log(`rendered arrow: ${pixels} pixels at ${rendered.toFixed(2)} N`);
    assert.ok(pixels >= MIN_ARROW_PIXELS, `${rendered} N rendered drew ${pixels} pixels`);
    await shot('03-surface');
  } finally {
    await page.click('[data-testid=release]'); // a failure here must not hold 5 N into the next test
  }
  assert.ok(await until(() => Math.abs(stack.status().operator_wrench[0]) < 0.1), 'the force was not released');
});

test('a force slider moves the handle', async () => {
  const before = stack.status().handle_pose;
  await page.locator('[data-testid=slider-Fy]').fill('5');
  try {
    const moved = await until(() => {
      const now = stack.status();
      return now.handle_pose[1] - before[1] > 0.01 && now.operator_wrench[1] > 4 ? now : null;
    }, { timeoutMs: 8000 });
    assert.ok(moved, `the handle did not move along +y: ${JSON.stringify(stack.status())}`);
    const s = await until(async () => {
      const status = await pageStatus();
      return status.arm && status.arm.handle_pose[1] - before[1] > 0.01 ? status : null;
    });
    assert.ok(s, 'the page did not show the handle moving');
    assert.ok(s.plots.force > 10 && s.plots.latency > 3 && s.plots.rtt > 0, JSON.stringify(s.plots));
    await page.waitForTimeout(1500); // let the plots fill for the picture
    await shot('02-force-applied');
  } finally {
    await page.click('[data-testid=release]'); // a failure here must not hold 5 N into the next test
  }
  assert.ok(await until(() => Math.abs(stack.status().operator_wrench[1]) < 0.1), 'the force was not released');
});

test('forces from 0.5 to 35 N show as arrows drawn over the spheres, visible at each size', async () => {
  // J8: at 1 cm per newton 0.5 N drew 5 mm inside the demo's 3 cm sphere and 35 N ran off the
  // view; drawn with the depth test the arrows were hidden by the sphere (H5). Judged by the
  // operator arrow's pixels on the canvas, once it shows the force that arrived (the page may
  // still draw frames sent while the force rose: 1.17 N of 2 seen beside stress-ng, 2026-12-04).
  const drawn = () => page.evaluate(() => {
    const a = window.hapticctrl.view?.arrows.operator;
    if (!a?.visible) return null;
    const last = (part) => !part.material.depthTest && part.material.transparent && part.renderOrder > 0;
    return { length: a.line.scale.y + a.cone.scale.y, overLine: last(a.line), overCone: last(a.cone) };
  });
  const arrowFor = async (force, newtons) => {
    for (const [i, axis] of ['Fx', 'Fy', 'Fz'].entries()) {
      await page.locator(`[data-testid=slider-${axis}]`).fill(String(force[i]));
    }
    const expected = 0.04 + 0.04 * Math.log2(1 + newtons);
    assert.ok(await until(() => Math.abs(Math.hypot(...stack.status().operator_wrench.slice(0, 3)) - newtons) < 0.1),
      `${newtons} N never arrived`);
    let arrow = null;
    await until(async () => {
      arrow = (await drawn()) ?? arrow;
      return arrow && Math.abs(arrow.length - expected) < 0.002;
    });
    assert.ok(arrow && Math.abs(arrow.length - expected) < 0.002, `arrow ${JSON.stringify(arrow)} for ${newtons} N, not ${expected} m`);
    assert.ok(arrow.overLine && arrow.overCone, JSON.stringify(arrow));
    await page.waitForTimeout(200); // the frame that shows it drawn (at most 25 a second)
    return colourPixels(OPERATOR_ARROW);
  };
  try {
    const small = await arrowFor([0, 0, 0.5], 0.5);
    await shot('02-arrow-0.5N');
    const large = await arrowFor([20, 20, 20], Math.sqrt(3) * 20);
    await shot('02-arrow-35N');
    console.log(`operator arrow: ${small} pixels at 0.5 N, ${large} at 34.6 N`);
    assert.ok(small >= MIN_ARROW_PIXELS, `0.5 N drew ${small} pixels`);
    assert.ok(large > 2 * small, `34.6 N drew ${large} pixels, 0.5 N ${small}`);
  } finally {
    await page.click('[data-testid=release]'); // a failure here must not hold the force into the next test
  }
  assert.ok(await until(() => Math.hypot(...stack.status().operator_wrench.slice(0, 3)) < 0.1), 'the force was not released');
});

test('a client whose data comes late shows in the link badge, not as a list of events', async () => {
  // J8: an unsteady link filled the events list (11 of the last 11 after 25 s were "client data
  // stale" / "fresh"). Four drop-outs of the demo (stopped 150 ms each): the core flags its data
  // stale after 5 ms, and the badge counts them.
  const client = stack.processes.client.child;
  try {
    for (let i = 0; i < 4; i += 1) {
      client.kill('SIGSTOP');
      await new Promise((resolve) => setTimeout(resolve, 150));
      client.kill('SIGCONT');
      await new Promise((resolve) => setTimeout(resolve, 250));
    }
  } finally {
    client.kill('SIGCONT');
  }
  // At least two of the four (LCM may drop an event on a loaded machine). No upper bound: a
  // machine busy beside the test makes its own (16 and 26 in 10 s in CI beside the sanitizer
  // builds, 2026-12-05), and the badge counts what the core reported; one each is app.js's
  // (onsets only, code 1), not a figure this test can hold on such a machine.
  const badge = () => page.locator('[data-testid=client-link]').innerText();
  const counted = async () => Number((/^link: (\d+) drop-outs in 10 s$/.exec(await badge()) ?? [])[1] ?? 0);
  assert.ok(await until(async () => (await counted()) >= 2), `badge: '${await badge()}'`);
  console.log(`link badge: '${await badge()}' after 4 drop-outs`);
  const listed = await page.locator('[data-testid=events] li').allInnerTexts();
  assert.ok(!listed.some((t) => /client data (stale|fresh)/.test(t)), listed.join('\n'));
  await shot('04-link-drop-outs');
});

test('the emergency stop button latches the stop, and reset clears it', async () => {
  await page.click('[data-testid=estop]');
  assert.ok(await until(() => stack.status().emergency_stop), 'the e-stop did not latch');
  assert.equal(stack.status().powered, false);
  await until(async () => (await alarmText()).includes('EMERGENCY STOP'));
  assert.match(await alarmText(), /EMERGENCY STOP latched/);
  assert.equal(await page.locator('[data-testid=estop]').innerText(), 'E-STOP LATCHED');
  await shot('03-estop-latched');
  await page.click('[data-testid=reset]');
  assert.ok(await until(() => !stack.status().emergency_stop), 'the reset did not clear the e-stop');
  assert.ok(await until(async () => (await alarmText()) === ''), 'the alarm stayed');
});

test('a silent controller and a lost web bridge are shown, and both recover', async () => {
  await stack.stopProcess('lcm', 'SIGKILL');
  assert.ok(await until(async () => /No telemetry from the controller/.test(await alarmText())),
    `no alarm for a silent controller: '${await alarmText()}'`);
  // The last state of a silent controller is not shown as its state now (J8).
  assert.equal(await page.locator('[data-testid=power]').innerText(), 'power: unknown');
  assert.equal(await page.locator('[data-testid=coupling]').innerText(), 'client: unknown');
  await page.click('[data-testid=power-on]'); // forwarded, but nobody applies it
  assert.ok(await until(async () => /sent, but the arm did not power on/.test(await page.locator('[data-testid=reply]').innerText())),
    'the page did not say that power-on had no effect');
  await shot('04-controller-silent');
  await stack.startLcm();
  assert.ok(await until(async () => (await alarmText()) === '', { timeoutMs: 8000 }), 'the alarm stayed after recovery');

  await stack.stopProcess('web', 'SIGKILL');
  assert.ok(await until(async () => /CONNECTION TO THE CONTROLLER LOST/.test(await alarmText())),
    `no alarm for a lost connection: '${await alarmText()}'`);
  assert.equal(await page.locator('[data-testid=link]').innerText(), 'web: lost');
  await shot('05-connection-lost');
  await stack.startWeb();
  assert.ok(await until(async () => (await pageStatus()).connected && (await alarmText()) === '', { timeoutMs: 10000 }),
    'the page did not reconnect');
});

test('a browser closed while holding a force lets the force go, and the bridge serves on', async () => {
  const second = await browser.newPage({ viewport: { width: 1024, height: 768 } });
  await second.goto(stack.url);
  await until(() => second.evaluate(() => window.hapticctrl?.hello?.remote_commands === true));
  await second.click('[data-testid=power-on]');
  await second.locator('[data-testid=slider-Fz]').fill('3');
  assert.ok(await until(() => stack.status().operator_wrench[2] > 2.5), 'the held force never arrived');
  await second.close(); // the tab goes away mid-hold: no more force messages
  const released = await until(() => Math.abs(stack.status().operator_wrench[2]) < 0.05, { timeoutMs: 3000 });
  assert.ok(released, `the force outlived the closed page: ${JSON.stringify(stack.status().operator_wrench)}`);
  const stats = await until(async () => {
    const s = await (await fetch(`${stack.url}api/stats`)).json();
    return s.server.pages === 1 ? s : null;
  });
  assert.ok(stats, 'the closed page is still counted');
  assert.ok((await pageStatus()).connected, 'the first page lost its connection');
});

test('a stopped controller shows its reason prominently', async () => {
  stack.hmi('stop');
  assert.ok(await until(async () => /stop requested/.test(await alarmText()), { timeoutMs: 8000 }),
    `no stop reason: '${await alarmText()}'`);
  assert.match(await page.locator('[data-testid=events]').innerText(), /stop requested/);
  await shot('06-controller-stopped');
});

test('a controller that fails safe shows why', async () => {
  await stack.processes.core.exited;
  // A new core made to overrun 5 cycles in a row half a second after its start.
  await stack.startCore(['--inject-overrun', '50:5']);
  assert.ok(await until(async () => /5 consecutive deadline misses/.test(await alarmText()), { timeoutMs: 10000 }),
    `no fail-safe reason: '${await alarmText()}'`);
  // H5: the banner says what happened and when, and stays after the core has gone.
  // J8: at the controller's own time (its event's), 24-hour as the panel's, not when the page
  // heard of it (12-hour).
  const banner = await alarmText();
  const at = banner.match(/^Controller failed safe: 5 consecutive deadline misses at (\d{2}):(\d{2}):(\d{2}) /);
  assert.ok(at, banner);
  const now = new Date();
  const seconds = (h, m, s) => h * 3600 + m * 60 + s;
  const late = (seconds(now.getHours(), now.getMinutes(), now.getSeconds()) - seconds(+at[1], +at[2], +at[3]) + 86400) % 86400;
  assert.ok(late < 15, `the banner's time is ${late} s before now: ${banner}`);
  await stack.processes.core.exited;
  await new Promise((resolve) => setTimeout(resolve, 500));
  assert.match(await alarmText(), /^Controller failed safe: /);
  assert.match(await page.locator('[data-testid=events]').innerText(), /fail-safe/);
  // Every event's own number is inside the panel, whatever its count of digits (list markers
  // from 10 on were clipped, H5).
  const events = await page.evaluate(() => {
    const list = document.getElementById('events');
    const left = list.getBoundingClientRect().left;
    return [...list.children].map((li) => ({ text: li.textContent, inside: li.getBoundingClientRect().left >= left,
      marker: getComputedStyle(li).listStyleType }));
  });
  assert.ok(events.length > 0);
  for (const e of events) assert.ok(e.inside && e.marker === 'none', JSON.stringify(e));
  await shot('07-failed-safe');
  assert.deepEqual(pageErrors, []);
});
