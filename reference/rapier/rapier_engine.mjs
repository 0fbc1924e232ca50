// Rapier (npm @dimforge/rapier3d-compat 0.21.0, WebAssembly, float32) as a protocol engine.
// docs/reference-engines.md says how each scene field maps and what cannot be matched.
import RAPIER from '@dimforge/rapier3d-compat';
import { serve } from '../protocol/engine_server.mjs';
import { readScene, pairMaterial, wireGeometry, withoutDuplicates } from '../protocol/scene.mjs';
import { add, sub, scale, dot, quatRotate, matrixToQuat, symmetricEigen } from '../protocol/math.mjs';

const PACKAGE_VERSION = '0.21.0';

// The JS API has no half-space: the ground is a static cuboid whose top face is the plane.
// Its half thickness is small so that float32 keeps the face within 2.4e-7 m (the rounding at
// 2 m) while no box of the scenes can pass through it in a step; its half width covers any scene.
const kGroundHalfThickness = 2; // m
const kGroundHalfWidth = 1000; // m


// Rapier's default contact spring (IntegrationParameters::contact_natural_frequency, Hz): the JS
// API can set it but not read it back; load checks the value through contact_erp.
const kDefaultContactNaturalFrequency = 30;

function settingsTable(p) {
  return [
    { key: 'num_solver_iterations', kind: 'integer', min: 1, max: 1000, default: p.numSolverIterations, what: 'solver iterations per step (each with its internal PGS and stabilization passes)' },
    { key: 'num_internal_pgs_iterations', kind: 'integer', min: 1, max: 1000, default: p.numInternalPgsIterations, what: 'PGS iterations inside each solver iteration' },
    { key: 'contact_natural_frequency', kind: 'number', unit: 'Hz', min: 0.01, max: 1e6, default: kDefaultContactNaturalFrequency, what: 'natural frequency of the soft contact constraint' },
    { key: 'normalized_allowed_linear_error', kind: 'number', unit: 'm', min: 0, max: 1, default: p.normalizedAllowedLinearError, what: 'penetration left uncorrected (times length_unit)' },
    { key: 'normalized_prediction_distance', kind: 'number', unit: 'm', min: 0, max: 1, default: p.normalizedPredictionDistance, what: 'distance at which speculative contacts start (times length_unit)' },
    { key: 'max_ccd_substeps', kind: 'integer', min: 1, max: 100, default: p.maxCcdSubsteps, what: 'continuous collision detection substeps (bodies with ccd)' },
    { key: 'length_unit', kind: 'number', unit: 'm', min: 1e-3, max: 1e3, default: p.lengthUnit, what: 'typical object size scaling the normalized tolerances' },
    { key: 'can_sleep', kind: 'boolean', default: true, what: 'bodies may fall asleep when at rest (RigidBodyDesc default)' },
    { key: 'ccd', kind: 'boolean', default: false, what: 'continuous collision detection on every dynamic body (RigidBodyDesc default off)' },
  ];
}

const vec = (v) => ({ x: v[0], y: v[1], z: v[2] });
const rot = (q) => ({ w: q[0], x: q[1], y: q[2], z: q[3] });
const arr = (v) => [v.x, v.y, v.z];
const quatArr = (r) => [r.w, r.x, r.y, r.z];

class RapierEngine {
  name = 'rapier';
  precision = 'float32';
  version = `@dimforge/rapier3d-compat ${PACKAGE_VERSION} (Rapier, WebAssembly, node ${process.versions.node})`;
  settings = [];
  world = null;

  async init() {
    await RAPIER.init();
    this.version = `@dimforge/rapier3d-compat ${RAPIER.version()} (Rapier, WebAssembly, node ${process.versions.node})`;
    const defaults = new RAPIER.World(vec([0, 0, 0]));
    this.settings = settingsTable(defaults.integrationParameters);
    this.defaultErp = defaults.integrationParameters.contact_erp;
    defaults.free();
  }

  load(sceneJson, settings) {
    this.world?.free();
    this.world = null;
    const scene = readScene(sceneJson);
    this.scene = scene;
    if (!scene.effects.gyroscopic)
      console.error(`rapier: scene ${scene.name} turns the gyroscopic term off; Rapier always includes it (its JS API has no switch)`);
    const world = new RAPIER.World(vec(scene.gravity));
    world.timestep = scene.dt;
    const p = world.integrationParameters;
    p.numSolverIterations = settings.num_solver_iterations;
    p.numInternalPgsIterations = settings.num_internal_pgs_iterations;
    p.contact_natural_frequency = settings.contact_natural_frequency;
    p.normalizedAllowedLinearError = settings.normalized_allowed_linear_error;
    p.normalizedPredictionDistance = settings.normalized_prediction_distance;
    p.maxCcdSubsteps = settings.max_ccd_substeps;
    p.lengthUnit = settings.length_unit;
    this.world = world;
    this.colliderBody = new Map(); // collider handle -> scene index (-1: the ground)
    if (scene.ground) this.addGround(scene);
    this.bodies = scene.bodies.map((body, i) => this.addBody(scene, body, i, settings));
    this.time_ = 0;
    this.lastContacts = [];
  }

  // Every collider carries sqrt(mu) with the Multiply rule, so a pair gets sqrt(mu_a) sqrt(mu_b);
  // restitution uses Max: both are boxpile's law exactly.
  colliderMaterial(desc, material) {
    const m = pairMaterial(this.scene.effects, material, material);
    return desc
      .setFriction(Math.sqrt(m.friction))
      .setFrictionCombineRule(RAPIER.CoefficientCombineRule.Multiply)
      .setRestitution(m.restitution)
      .setRestitutionCombineRule(RAPIER.CoefficientCombineRule.Max);
  }

  addGround(scene) {
    const { normal, offset } = scene.ground;
    // The cuboid's local +z is the ground's normal; its centre lies half a thickness below.
    const q = rotationFromZ(normal);
    const centre = scale(normal, offset - kGroundHalfThickness);
    const body = this.world.createRigidBody(RAPIER.RigidBodyDesc.fixed().setTranslation(...centre).setRotation(rot(q)));
    const desc = this.colliderMaterial(RAPIER.ColliderDesc.cuboid(kGroundHalfWidth, kGroundHalfWidth, kGroundHalfThickness), scene.groundMaterial);
    const collider = this.world.createCollider(desc, body);
    this.colliderBody.set(collider.handle, -1);
  }

  addBody(scene, body, index, settings) {
    let desc = body.fixed ? RAPIER.RigidBodyDesc.fixed() : RAPIER.RigidBodyDesc.dynamic();
    desc = desc.setTranslation(...body.position).setRotation(rot(body.orientation));
    if (!body.fixed) {
      const { values, vectors } = symmetricEigen(body.inertia);
      desc = desc
        .setAdditionalMassProperties(body.mass, vec(body.centerOfMass), vec(values), rot(matrixToQuat(vectors)))
        .setLinvel(...body.velocity)
        .setAngvel(vec(body.angularVelocity))
        .setCanSleep(settings.can_sleep)
        .setCcdEnabled(settings.ccd);
      const damping = scene.effects.damping ? scene.damping : { linear: 0, angular: 0 };
      desc = desc.setLinearDamping(damping.linear).setAngularDamping(damping.angular);
    }
    const rigid = this.world.createRigidBody(desc);
    for (const box of body.boxes) {
      const c = RAPIER.ColliderDesc.cuboid(...box.halfExtents)
        .setTranslation(...box.position)
        .setRotation(rot(box.orientation))
        .setDensity(0); // the body's mass properties are the scene's, set above
      const collider = this.world.createCollider(this.colliderMaterial(c, body.material), rigid);
      this.colliderBody.set(collider.handle, index);
    }
    if (body.wire) this.addWire(body, rigid);
    return rigid;
  }

  // The anchor held on the wire's line by a generic joint locking the two directions across it
  // (in the fixed root's frame, whose x axis is the wire), and kept between the ends by two rope
  // joints of the wire's length, one from each end.
  addWire(body, rigid) {
    const wire = wireGeometry(body);
    const frame = rotationFromX(wire.axis);
    const root = this.world.createRigidBody(RAPIER.RigidBodyDesc.fixed()
      .setTranslation(...body.wire.from).setRotation(rot(frame)));
    const anchorOnRoot = vec([wire.s0, 0, 0]);
    const lineMask = RAPIER.JointAxesMask.LinY | RAPIER.JointAxesMask.LinZ;
    const line = RAPIER.JointData.generic(anchorOnRoot, vec(body.wire.anchor), vec([1, 0, 0]), lineMask);
    this.world.createImpulseJoint(line, root, rigid, true);
    for (const end of [0, wire.length]) {
      const rope = RAPIER.JointData.rope(wire.length, vec([end, 0, 0]), vec(body.wire.anchor));
      this.world.createImpulseJoint(rope, root, rigid, true);
    }
  }

  step(n) {
    let seconds = 0;
    for (let k = 0; k < n; ++k) {
      const t0 = process.hrtime.bigint();
      this.world.step();
      seconds += Number(process.hrtime.bigint() - t0) * 1e-9;
      this.time_ += this.scene.dt;
    }
    this.lastContacts = null;
    return seconds;
  }

  time() {
    return this.time_;
  }

  states() {
    return this.bodies.map((rigid) => ({
      position: arr(rigid.translation()),
      orientation: quatArr(rigid.rotation()),
      velocity: arr(rigid.linvel()),
      angular_velocity: arr(rigid.angvel()),
    }));
  }

  // The narrow phase's manifolds of the last step. normal() points from the manifold's
  // collider 1 toward collider 2; the points are in each collider's frame, placed here with the
  // colliders' poses after the step, and their separation along the normal gives the depth
  // (contactDist keeps the value of the detection). boxpile's normal points from b to a: a is
  // collider 2's body, b collider 1's, swapped when the ground is collider 2. Box-box manifolds
  // repeat points: each is kept once. Speculative points (apart) are left out.
  contacts() {
    if (this.lastContacts) return this.lastContacts;
    const world = this.world;
    const found = [];
    const seen = new Set();
    for (const [handle1, index1] of this.colliderBody) {
      const c1 = world.getCollider(handle1);
      world.contactPairsWith(c1, (c2) => {
        const index2 = this.colliderBody.get(c2.handle);
        if (index2 === undefined) return;
        const key = handle1 < c2.handle ? `${handle1}:${c2.handle}` : `${c2.handle}:${handle1}`;
        if (seen.has(key)) return;
        seen.add(key);
        world.contactPair(c1, c2, (manifold, flipped) => {
          const [first, second] = flipped ? [c2, c1] : [c1, c2];
          const normal = arr(manifold.normal());
          for (let k = 0; k < manifold.numContacts(); ++k) {
            const p1 = toWorld(first, arr(manifold.localContactPoint1(k)));
            const p2 = toWorld(second, arr(manifold.localContactPoint2(k)));
            const depth = -dot(sub(p2, p1), normal);
            if (!(depth >= 0)) continue;
            let a = this.colliderBody.get(second.handle);
            let b = this.colliderBody.get(first.handle);
            let n = normal;
            if (a === -1) {
              [a, b] = [b, a];
              n = scale(normal, -1);
            }
            found.push({ a, b, position: scale(add(p1, p2), 0.5), normal: n, depth });
          }
        });
      });
    }
    this.lastContacts = withoutDuplicates(found);
    return this.lastContacts;
  }
}

function toWorld(collider, local) {
  return add(arr(collider.translation()), quatRotate(quatArr(collider.rotation()), local));
}

// The rotation taking +x to the unit vector n (the shortest arc).
function rotationFromX(n) {
  const c = n[0];
  if (c < -1 + 1e-12) return [0, 0, 0, 1];
  const q = [1 + c, 0, -n[2], n[1]]; // w = 1 + x . n, axis x cross n
  const len = Math.hypot(...q);
  return q.map((v) => v / len);
}

// The rotation taking +z to the unit vector n (the shortest arc).
function rotationFromZ(n) {
  const z = [0, 0, 1];
  const c = dot(z, n);
  if (c < -1 + 1e-12) return [0, 1, 0, 0];
  const axis = [-n[1], n[0], 0]; // z x n
  const w = 1 + c;
  const q = [w, axis[0], axis[1], axis[2]];
  const len = Math.hypot(...q);
  return q.map((x) => x / len);
}


serve(new RapierEngine());
