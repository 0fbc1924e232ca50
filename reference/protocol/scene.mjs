// The resolved scene of a load request (docs/engine-protocol.md), checked field by field so that
// a malformed one is answered with an error naming the field, and the rules every adapter shares:
// pair materials, the wire's geometry, the contact convention.
import { InputError } from './errors.mjs';
import { sub, dot, norm, normalize, quatNormalize, quatRotate, add } from './math.mjs';

class SceneError extends InputError {}

function isVec(v, n) {
  return Array.isArray(v) && v.length === n && v.every((x) => typeof x === 'number' && Number.isFinite(x));
}
function need(obj, key, path, test, what) {
  if (!obj || typeof obj !== 'object' || !(key in obj)) throw new SceneError(`scene: missing ${path}.${key}`);
  const v = obj[key];
  if (!test(v)) throw new SceneError(`scene: ${path}.${key} must be ${what}, not ${JSON.stringify(v)}`);
  return v;
}
const vec3 = (o, k, p) => need(o, k, p, (v) => isVec(v, 3), 'three finite numbers');
const quat = (o, k, p) => {
  const q = need(o, k, p, (v) => isVec(v, 4) && Math.hypot(...v) > 0, 'a nonzero quaternion [w, x, y, z]');
  return quatNormalize(q);
};
const finite = (o, k, p) => need(o, k, p, (v) => typeof v === 'number' && Number.isFinite(v), 'a finite number');
const nonNegative = (o, k, p) => need(o, k, p, (v) => typeof v === 'number' && Number.isFinite(v) && v >= 0, 'a finite number >= 0');
const positive = (o, k, p) => need(o, k, p, (v) => typeof v === 'number' && Number.isFinite(v) && v > 0, 'a finite number > 0');
const bool = (o, k, p) => need(o, k, p, (v) => typeof v === 'boolean', 'true or false');

function readMaterial(o, path) {
  return { friction: nonNegative(o, 'friction', path), restitution: nonNegative(o, 'restitution', path) };
}

function readBox(box, path) {
  return {
    halfExtents: need(box, 'half_extents', path, (v) => isVec(v, 3) && v.every((x) => x > 0), 'three numbers > 0'),
    position: vec3(box, 'position', path),
    orientation: quat(box, 'orientation', path),
  };
}

function readWire(wire, path) {
  const from = vec3(wire, 'from', path);
  const to = vec3(wire, 'to', path);
  if (norm(sub(to, from)) === 0) throw new SceneError(`scene: ${path} has from == to`);
  return { from, to, anchor: vec3(wire, 'anchor', path) };
}

function readBody(body, i) {
  const path = `bodies[${i}]`;
  const fixed = bool(body, 'fixed', path);
  const boxes = need(body, 'boxes', path, (v) => Array.isArray(v) && v.length > 0, 'a nonempty array');
  // A fixed body's mass and inertia are never used (it has infinite mass).
  const inertia = fixed ? null : need(body, 'inertia', path,
    (v) => Array.isArray(v) && v.length === 3 && v.every((row) => isVec(row, 3)), 'a 3x3 matrix');
  const out = {
    name: typeof body.name === 'string' ? body.name : `body ${i}`,
    fixed,
    mass: fixed ? null : positive(body, 'mass', path),
    centerOfMass: fixed ? [0, 0, 0] : vec3(body, 'center_of_mass', path),
    inertia,
    position: vec3(body, 'position', path),
    orientation: quat(body, 'orientation', path),
    velocity: fixed ? [0, 0, 0] : vec3(body, 'velocity', path),
    angularVelocity: fixed ? [0, 0, 0] : vec3(body, 'angular_velocity', path),
    material: readMaterial(body, path),
    boxes: boxes.map((b, k) => readBox(b, `${path}.boxes[${k}]`)),
    wire: body.wire == null ? null : readWire(body.wire, `${path}.wire`),
  };
  if (out.wire && fixed) throw new SceneError(`scene: ${path} is fixed and on a wire`);
  return out;
}

// The checked scene: { name, dt, gravity, ground: {normal (unit), offset} | null, groundMaterial,
// effects, damping, bodies }.
export function readScene(scene) {
  const dt = positive(scene, 'dt', 'scene');
  const gravity = vec3(scene, 'gravity', 'scene');
  let ground = null;
  if (scene.ground != null) {
    const normal = need(scene.ground, 'normal', 'scene.ground', (v) => isVec(v, 3) && Math.hypot(...v) > 0, 'a nonzero vector');
    ground = { normal: normalize(normal), offset: finite(scene.ground, 'offset', 'scene.ground') / norm(normal) };
  }
  const effects = {};
  for (const key of ['friction', 'restitution', 'damping', 'gyroscopic'])
    effects[key] = bool(scene.effects, key, 'scene.effects');
  const damping = {
    linear: nonNegative(scene.damping, 'linear', 'scene.damping'),
    angular: nonNegative(scene.damping, 'angular', 'scene.damping'),
  };
  const bodies = need(scene, 'bodies', 'scene', Array.isArray, 'an array').map(readBody);
  const groundMaterial = ground ? readMaterial(scene.ground_material, 'scene.ground_material') : null;
  return { name: String(scene.name ?? 'scene'), dt, gravity, ground, groundMaterial, effects, damping, bodies };
}

// The contact law shared by every engine: friction sqrt(mu_a mu_b), restitution max(e_a, e_b),
// each zero when its effect is off.
export function pairMaterial(effects, a, b) {
  return {
    friction: effects.friction ? Math.sqrt(a.friction * b.friction) : 0,
    restitution: effects.restitution ? Math.max(a.restitution, b.restitution) : 0,
  };
}

// The wire of a body: unit direction along from -> to, its length, and where along it the
// anchor starts (s0, clamped to the segment), from the body's pose at load.
export function wireGeometry(body) {
  const { from, to, anchor } = body.wire;
  const length = norm(sub(to, from));
  const axis = normalize(sub(to, from));
  const anchorWorld = add(body.position, quatRotate(body.orientation, anchor));
  const s0 = Math.min(Math.max(dot(sub(anchorWorld, from), axis), 0), length);
  return { axis, length, anchorWorld, s0 };
}

// Distinct points of one manifold: engines that repeat a point (Rapier's box-box) would count it
// twice; two points closer than this are one.
const kSamePointDistance = 1e-6; // m: far below any box's size, far above float32 rounding at 1 m
export function withoutDuplicates(contacts) {
  const kept = [];
  for (const c of contacts) {
    if (!kept.some((k) => k.a === c.a && k.b === c.b && norm(sub(k.position, c.position)) < kSamePointDistance))
      kept.push(c);
  }
  return kept;
}

export { SceneError };
