// Forward kinematics of the arm model the web bridge sends ({"type":"model"}), chained exactly
// as rt_core's ArmDynamics::forward_kinematics: each joint sits at its origin in the previous
// link frame and turns its link about its own axis. Plain arrays, no three.js: unit-tested with
// node --test (tests/web/kinematics_test.mjs).

/** 3x3 rotation about unit axis `a` by `angle` (Rodrigues), row-major [[...],[...],[...]]. */
export function axisRotation(a, angle) {
  const n = Math.hypot(a[0], a[1], a[2]) || 1;
  const [x, y, z] = [a[0] / n, a[1] / n, a[2] / n];
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  const t = 1 - c;
  return [
    [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
    [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
    [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
  ];
}

export function multiply(r, m) {
  return r.map((row) => [0, 1, 2].map((j) => row[0] * m[0][j] + row[1] * m[1][j] + row[2] * m[2][j]));
}

export function apply(r, v) {
  return r.map((row) => row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
}

/**
 * Joint positions (base frame) and the handle point for joint angles `q`.
 * @returns {{joints: number[][], rotations: number[][][], handle: number[]}}
 */
export function forwardKinematics(model, q) {
  let rotation = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  let position = [0, 0, 0];
  const joints = [];
  const rotations = [];
  model.joints.forEach((joint, i) => {
    const offset = apply(rotation, joint.origin);
    position = position.map((p, k) => p + offset[k]);
    rotation = multiply(rotation, axisRotation(joint.axis, q[i] ?? 0));
    joints.push(position);
    rotations.push(rotation);
  });
  const tip = apply(rotation, model.handle);
  return { joints, rotations, handle: position.map((p, k) => p + tip[k]) };
}

/** Distance (m) between the drawn handle and the controller's handle position. */
export function handleMismatch(model, q, handlePose) {
  const { handle } = forwardKinematics(model, q);
  return Math.hypot(handle[0] - handlePose[0], handle[1] - handlePose[1], handle[2] - handlePose[2]);
}
