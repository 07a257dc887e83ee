// The page's forward kinematics (bridges/web/www/kinematics.js) against the numbers the C++ model
// is checked with (arm_model/models/virtuose6d_class.arm: the ready pose puts the handle at
// (0.628, 0, 0.227) m, cross-checked with Orocos KDL).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { axisRotation, forwardKinematics, handleMismatch } from '../../bridges/web/www/kinematics.js';

/** The shipped model's kinematic lines, read from the model file itself. */
function shippedModel() {
  const text = readFileSync(new URL('../../arm_model/models/virtuose6d_class.arm', import.meta.url), 'utf8');
  const joints = [];
  let handle = null;
  let section = null;
  const axes = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] };
  for (const raw of text.split('\n')) {
    const line = raw.replace(/#.*/, '').trim();
    const header = line.match(/^\[(joint \d|handle)\]$/);
    if (header) {
      section = header[1];
      if (section.startsWith('joint')) joints.push({});
      continue;
    }
    const [key, value] = line.split('=').map((s) => s?.trim());
    if (!section || !value) continue;
    if (section.startsWith('joint') && key === 'origin') joints.at(-1).origin = value.split(/\s+/).map(Number);
    if (section.startsWith('joint') && key === 'axis') joints.at(-1).axis = axes[value] ?? value.split(/\s+/).map(Number);
    if (section === 'handle' && key === 'origin') handle = value.split(/\s+/).map(Number);
  }
  return { joints, handle };
}

const close = (a, b, tolerance = 1e-3) => a.every((v, i) => Math.abs(v - b[i]) < tolerance);

test('the ready pose puts the handle where the C++ model does', () => {
  const { handle } = forwardKinematics(shippedModel(), [0, -0.6, 1.2, 0, -0.6, 0]);
  assert.ok(close(handle, [0.628, 0, 0.227]), `handle at ${handle}`);
});

test('the zero pose stretches the arm along x at shoulder height', () => {
  const model = shippedModel();
  const { joints, handle } = forwardKinematics(model, [0, 0, 0, 0, 0, 0]);
  assert.ok(close(joints[1], [0, 0, 0.25]));
  assert.ok(close(handle, [0.74, 0, 0.25]), `handle at ${handle}`);
  const yawed = forwardKinematics(model, [Math.PI / 2, 0, 0, 0, 0, 0]).handle;
  assert.ok(close(yawed, [0, 0.74, 0.25]), `yawed handle at ${yawed}`);
});

test('rotations are proper and mismatches are measured in metres', () => {
  const r = axisRotation([0, 0, 2], Math.PI / 2); // axis need not be unit
  assert.ok(close(r[0], [0, -1, 0], 1e-12) && close(r[1], [1, 0, 0], 1e-12));
  const model = shippedModel();
  const q = [0.3, -0.5, 1.0, 0.2, -0.4, 0.1];
  const { handle } = forwardKinematics(model, q);
  assert.ok(handleMismatch(model, q, [...handle, 0, 0, 0, 1]) < 1e-12);
  assert.ok(Math.abs(handleMismatch(model, q, [handle[0] + 0.01, handle[1], handle[2]]) - 0.01) < 1e-12);
});
