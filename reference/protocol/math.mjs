// Small vector, quaternion ([w, x, y, z]) and 3x3 matrix helpers for the adapters.

export const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const norm = (a) => Math.sqrt(dot(a, a));
export const normalize = (a) => scale(a, 1 / norm(a));

export function quatMultiply(p, q) {
  return [
    p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
    p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
    p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
    p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0],
  ];
}
export const quatConjugate = (q) => [q[0], -q[1], -q[2], -q[3]];
export function quatNormalize(q) {
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  return [q[0] / n, q[1] / n, q[2] / n, q[3] / n];
}
export function quatRotate(q, v) {
  const r = quatMultiply(quatMultiply(q, [0, v[0], v[1], v[2]]), quatConjugate(q));
  return [r[1], r[2], r[3]];
}
export function quatToMatrix(q) {
  const [w, x, y, z] = q;
  return [
    [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
    [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
    [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
  ];
}
// The rotation [w, x, y, z] of a proper orthonormal matrix (Shepperd's method).
export function matrixToQuat(m) {
  const trace = m[0][0] + m[1][1] + m[2][2];
  let q;
  if (trace > 0) {
    const s = 2 * Math.sqrt(1 + trace);
    q = [s / 4, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s];
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const s = 2 * Math.sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
    q = [(m[2][1] - m[1][2]) / s, s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s];
  } else if (m[1][1] > m[2][2]) {
    const s = 2 * Math.sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
    q = [(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s];
  } else {
    const s = 2 * Math.sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
    q = [(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4];
  }
  return quatNormalize(q);
}

export const matVec = (m, v) => [dot(m[0], v), dot(m[1], v), dot(m[2], v)];
export const transpose = (m) => [0, 1, 2].map((i) => [m[0][i], m[1][i], m[2][i]]);
export function matMul(a, b) {
  const bt = transpose(b);
  return a.map((row) => bt.map((col) => dot(row, col)));
}

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
// { values: [l0, l1, l2], vectors: V } with m = V diag(values) V^T, V's columns the axes, det V = +1.
export function symmetricEigen(m) {
  const a = m.map((row) => row.slice());
  let v = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const kSweeps = 50; // Jacobi converges quadratically: a handful of sweeps reach rounding
  for (let sweep = 0; sweep < kSweeps; ++sweep) {
    const off = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2;
    const diag = a[0][0] ** 2 + a[1][1] ** 2 + a[2][2] ** 2;
    if (off <= 1e-30 * diag) break;
    for (const [p, q] of [[0, 1], [0, 2], [1, 2]]) {
      if (a[p][q] === 0) continue;
      const theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
      const t = Math.sign(theta || 1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
      const c = 1 / Math.sqrt(t * t + 1);
      const s = t * c;
      const rot = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
      rot[p][p] = c; rot[q][q] = c; rot[p][q] = s; rot[q][p] = -s;
      const next = matMul(matMul(transpose(rot), a), rot);
      for (let i = 0; i < 3; ++i) for (let j = 0; j < 3; ++j) a[i][j] = next[i][j];
      v = matMul(v, rot);
    }
  }
  const det = dot(v.map((r) => r[0]), cross(v.map((r) => r[1]), v.map((r) => r[2])));
  if (det < 0) for (const row of v) row[2] = -row[2];
  return { values: [a[0][0], a[1][1], a[2][2]], vectors: v };
}
