// MuJoCo 3.14 (npm @mujoco/mujoco, the official WebAssembly build, float64) as a protocol engine:
// the resolved scene becomes an MJCF model, stepped with mj_step. See docs/reference-engines.md
// for what maps and what cannot.
import loadMujoco from '@mujoco/mujoco';
import { serve } from '../protocol/engine_server.mjs';
import { readScene, pairMaterial, wireGeometry, SceneError } from '../protocol/scene.mjs';
import {
  add, sub, scale, cross, quatConjugate, quatRotate, quatToMatrix, matVec, matMul, transpose,
} from '../protocol/math.mjs';

const PACKAGE_VERSION = '3.14.0';

// MuJoCo's enumerations by the names its XML uses (mjtSolver, mjtCone, mjtIntegrator).
const SOLVERS = ['PGS', 'CG', 'Newton'];
const CONES = ['pyramidal', 'elliptic'];
const INTEGRATORS = ['Euler', 'RK4', 'implicit', 'implicitfast'];

// A scene whose bodies do not all share one material needs an explicit <pair> per geom pair
// (MuJoCo mixes geom friction by max, not sqrt(mu_a mu_b)); beyond this many the model would be
// mostly pairs: refuse with a clear error.
const kMaxExplicitPairs = 20000;

// The settings: MuJoCo's own option fields and its geom defaults, read from a compiled empty
// model at start-up so that each default is the engine's.
function settingsTable(opt, solref, solimp) {
  return [
    { key: 'solver', kind: 'choice', choices: SOLVERS, default: SOLVERS[opt.solver], what: 'constraint solver (mjOption.solver)' },
    { key: 'iterations', kind: 'integer', min: 1, max: 10000, default: opt.iterations, what: 'main solver iterations per step' },
    { key: 'tolerance', kind: 'number', min: 0, max: 1, default: opt.tolerance, what: 'main solver tolerance (0: run every iteration)' },
    { key: 'ls_iterations', kind: 'integer', min: 1, max: 10000, default: opt.ls_iterations, what: 'line-search iterations (CG, Newton)' },
    { key: 'noslip_iterations', kind: 'integer', min: 0, max: 10000, default: opt.noslip_iterations, what: 'no-slip post-solver iterations (0: off)' },
    { key: 'noslip_tolerance', kind: 'number', min: 0, max: 1, default: opt.noslip_tolerance, what: 'no-slip solver tolerance' },
    { key: 'cone', kind: 'choice', choices: CONES, default: CONES[opt.cone], what: 'friction cone' },
    { key: 'impratio', kind: 'number', min: 1e-4, max: 1e4, default: opt.impratio, what: 'frictional-to-normal impedance ratio' },
    { key: 'integrator', kind: 'choice', choices: INTEGRATORS, default: INTEGRATORS[opt.integrator], what: 'numerical integrator' },
    { key: 'solref_timeconst', kind: 'number', unit: 's', min: 1e-6, max: 10, default: solref[0], what: 'contact solref[0]: time constant of the soft contact' },
    { key: 'solref_dampratio', kind: 'number', min: 1e-3, max: 100, default: solref[1], what: 'contact solref[1]: damping ratio (pairs with restitution e > 0 use the ratio that gives e instead)' },
    { key: 'solimp_dmin', kind: 'number', min: 1e-4, max: 0.9999, default: solimp[0], what: 'contact solimp[0]: impedance at zero penetration' },
    { key: 'solimp_dmax', kind: 'number', min: 1e-4, max: 0.9999, default: solimp[1], what: 'contact solimp[1]: impedance at width' },
    { key: 'solimp_width', kind: 'number', unit: 'm', min: 0, max: 1, default: solimp[2], what: 'contact solimp[2]: penetration over which impedance goes from dmin to dmax' },
    { key: 'solimp_midpoint', kind: 'number', min: 0, max: 1, default: solimp[3], what: 'contact solimp[3]: midpoint of the impedance curve' },
    { key: 'solimp_power', kind: 'number', min: 1, max: 100, default: solimp[4], what: 'contact solimp[4]: power of the impedance curve' },
  ];
}

// MuJoCo has no coefficient of restitution: a soft contact is a damped spring, and a linear
// damped spring of damping ratio z returns a fraction e = exp(-z pi / sqrt(1 - z^2)) of the
// approach speed. The ratio that gives e (for 0 < e < 1) replaces solref's ratio for that pair.
export function dampRatioForRestitution(e, dampratio) {
  if (e <= 0) return dampratio;
  if (e >= 1) return 0;
  const l = Math.log(e);
  return -l / Math.sqrt(Math.PI * Math.PI + l * l);
}

// Damping and the removal of the gyroscopic term are forces the adapter applies each step.
const needsBodyForces = (scene) => scene.effects.damping || !scene.effects.gyroscopic;

const fmt = (v) => (Array.isArray(v) ? v.map((x) => String(x)).join(' ') : String(v));

// Fixed frames of one scene body in the model, from its description at load.
function bodyXml(body, index, geomNames, geomAttributes) {
  const lines = [];
  const name = `body${index}`;
  lines.push(`<body name="${name}" pos="${fmt(body.position)}" quat="${fmt(body.orientation)}">`);
  if (!body.fixed) {
    if (body.wire) {
      const wire = wireGeometry(body);
      // The slide comes first so that its axis stays fixed in the world while the ball turns the
      // body about the anchor; the axis is written in the body's frame at load.
      const axisLocal = quatRotate(quatConjugate(body.orientation), wire.axis);
      lines.push(`<joint name="${name}_slide" type="slide" pos="${fmt(body.wire.anchor)}" axis="${fmt(axisLocal)}"` +
        ` limited="true" range="${fmt([-wire.s0, wire.length - wire.s0])}"/>`);
      lines.push(`<joint name="${name}_ball" type="ball" pos="${fmt(body.wire.anchor)}"/>`);
    } else {
      lines.push(`<freejoint name="${name}_free"/>`);
    }
    const I = body.inertia;
    lines.push(`<inertial pos="${fmt(body.centerOfMass)}" mass="${fmt(body.mass)}"` +
      ` fullinertia="${fmt([I[0][0], I[1][1], I[2][2], I[0][1], I[0][2], I[1][2]])}"/>`);
  }
  body.boxes.forEach((box, k) => {
    const geom = `${name}_box${k}`;
    geomNames.push(geom);
    lines.push(`<geom name="${geom}" type="box" size="${fmt(box.halfExtents)}" pos="${fmt(box.position)}"` +
      ` quat="${fmt(box.orientation)}" ${geomAttributes}/>`);
  });
  lines.push('</body>');
  return lines.join('\n');
}

function contactAttributes(material, settings, friction) {
  const condim = friction ? 3 : 1;
  const ratio = dampRatioForRestitution(material.restitution, settings.solref_dampratio);
  return {
    condim,
    friction: material.friction,
    solref: [settings.solref_timeconst, ratio],
    solimp: [settings.solimp_dmin, settings.solimp_dmax, settings.solimp_width, settings.solimp_midpoint, settings.solimp_power],
  };
}

// The model of a scene: { xml, geomBody } with geomBody[g] the scene index of geom g's body
// (-1 for the ground), in the order MuJoCo numbers geoms (depth-first through the body tree).
export function sceneToMjcf(scene, settings) {
  const { effects } = scene;
  const materials = scene.bodies.map((b) => b.material).concat(scene.groundMaterial ? [scene.groundMaterial] : []);
  const shared = materials.every((m) => m.friction === materials[0].friction && m.restitution === materials[0].restitution);
  const sharedMaterial = materials.length ? pairMaterial(effects, materials[0], materials[0]) : { friction: 0, restitution: 0 };

  // One material for all: every geom carries it (MuJoCo's max mixing of equal values is exact).
  // Otherwise: every geom's own collisions are off and each pair that may touch is explicit.
  let geomAttributes;
  if (shared) {
    const c = contactAttributes(sharedMaterial, settings, effects.friction);
    geomAttributes = `condim="${c.condim}" friction="${fmt([c.friction, 0.005, 0.0001])}" solref="${fmt(c.solref)}" solimp="${fmt(c.solimp)}"`;
  } else {
    geomAttributes = 'contype="0" conaffinity="0"';
  }

  const geomNames = [];
  const geomBody = [];
  const world = [];
  if (scene.ground) {
    const { normal, offset } = scene.ground;
    world.push(`<geom name="ground" type="plane" size="0 0 1" pos="${fmt(scale(normal, offset))}" zaxis="${fmt(normal)}" ${geomAttributes}/>`);
    geomNames.push('ground');
    geomBody.push(-1);
  }
  scene.bodies.forEach((body, i) => {
    const before = geomNames.length;
    world.push(bodyXml(body, i, geomNames, geomAttributes));
    for (let k = before; k < geomNames.length; ++k) geomBody.push(i);
  });

  const pairs = [];
  if (!shared) {
    const materialOf = (i) => (i < 0 ? scene.groundMaterial : scene.bodies[i].material);
    const isFixed = (i) => i < 0 || scene.bodies[i].fixed;
    for (let g = 0; g < geomNames.length; ++g) {
      for (let h = g + 1; h < geomNames.length; ++h) {
        const [i, j] = [geomBody[g], geomBody[h]];
        if (i === j || (isFixed(i) && isFixed(j))) continue;
        if (pairs.length >= kMaxExplicitPairs)
          throw new SceneError(`scene ${scene.name}: bodies of different materials need one MuJoCo <pair> per pair of boxes; more than ${kMaxExplicitPairs} are too many`);
        const c = contactAttributes(pairMaterial(effects, materialOf(i), materialOf(j)), settings, effects.friction);
        pairs.push(`<pair geom1="${geomNames[g]}" geom2="${geomNames[h]}" condim="${c.condim}"` +
          ` friction="${fmt([c.friction, c.friction, 0.005, 0.0001, 0.0001])}" solref="${fmt(c.solref)}" solimp="${fmt(c.solimp)}"/>`);
      }
    }
  }

  const option = `<option timestep="${fmt(scene.dt)}" gravity="${fmt(scene.gravity)}" solver="${settings.solver}"` +
    ` iterations="${settings.iterations}" tolerance="${fmt(settings.tolerance)}" ls_iterations="${settings.ls_iterations}"` +
    ` noslip_iterations="${settings.noslip_iterations}" noslip_tolerance="${fmt(settings.noslip_tolerance)}"` +
    ` cone="${settings.cone}" impratio="${fmt(settings.impratio)}" integrator="${settings.integrator}"/>`;
  const xml = `<mujoco model="boxpile">\n<compiler angle="radian" inertiafromgeom="false"/>\n${option}\n` +
    `<worldbody>\n${world.join('\n')}\n</worldbody>\n` +
    (pairs.length ? `<contact>\n${pairs.join('\n')}\n</contact>\n` : '') + '</mujoco>\n';
  return { xml, geomBody };
}

class MujocoEngine {
  name = 'mujoco-wasm';
  precision = 'float64';
  version = `@mujoco/mujoco ${PACKAGE_VERSION} (MuJoCo, official WebAssembly build, node ${process.versions.node})`;
  settings = [];
  mj = null;
  model = null;
  data = null;

  async init() {
    this.mj = await loadMujoco();
    this.version = `@mujoco/mujoco ${PACKAGE_VERSION} (MuJoCo ${this.mj.mj_versionString()}, official WebAssembly build, node ${process.versions.node})`;
    const probe = this.mj.MjModel.from_xml_string('<mujoco><worldbody><geom type="sphere" size="1"/></worldbody></mujoco>');
    try {
      this.settings = settingsTable(probe.opt, Array.from(probe.geom_solref), Array.from(probe.geom_solimp));
    } finally {
      probe.delete();
    }
  }

  release() {
    this.data?.delete();
    this.model?.delete();
    this.buffer?.delete();
    this.data = this.model = this.buffer = null;
  }

  load(sceneJson, settings) {
    this.release();
    const scene = readScene(sceneJson);
    if (needsBodyForces(scene) && settings.integrator === 'RK4')
      throw new SceneError('the scene asks for damping or turns the gyroscopic term off, both applied between mj_step1 and mj_step2, which RK4 cannot split: choose another integrator');
    const { xml, geomBody } = sceneToMjcf(scene, settings);
    this.scene = scene;
    this.geomBody = geomBody;
    try {
      this.model = this.mj.MjModel.from_xml_string(xml);
    } catch (e) {
      throw new SceneError(`MuJoCo rejected the model of scene ${scene.name}: ${e.message ?? e}`);
    }
    this.data = new this.mj.MjData(this.model);
    this.buffer = new this.mj.DoubleBuffer(6);
    // The MuJoCo body of scene body i is i + 1 (body 0 is the world).
    this.setInitialVelocities();
    this.steps = 0;
    this.lastContacts = [];
  }

  // Scene velocities are the centre of mass's (world) and the angular velocity (world); a free
  // joint's qvel is the body origin's linear velocity (world) and the angular velocity in body
  // axes; a wire body's is the slide rate and the ball's angular velocity in body axes.
  setInitialVelocities() {
    const qvel = this.data.qvel;
    let dof = 0;
    for (const body of this.scene.bodies) {
      if (body.fixed) continue;
      const w = body.angularVelocity;
      const wBody = quatRotate(quatConjugate(body.orientation), w);
      const comArm = quatRotate(body.orientation, body.centerOfMass);
      if (body.wire) {
        const wire = wireGeometry(body);
        const anchorArm = quatRotate(body.orientation, sub(body.centerOfMass, body.wire.anchor));
        const vAnchor = sub(body.velocity, cross(w, anchorArm));
        qvel[dof] = vAnchor[0] * wire.axis[0] + vAnchor[1] * wire.axis[1] + vAnchor[2] * wire.axis[2];
        qvel.set(wBody, dof + 1);
        dof += 4;
      } else {
        qvel.set(sub(body.velocity, cross(w, comArm)), dof);
        qvel.set(wBody, dof + 3);
        dof += 6;
      }
    }
  }

  // Forces at the centres of mass (xfrc_applied), from the velocities mj_step1 has just computed:
  // damping dP = -c_lin P dt, dL = -c_ang L dt; and, with the gyroscopic effect off, the torque
  // w x (I w) that cancels MuJoCo's gyroscopic term in I dw/dt + w x (I w) = tau (MuJoCo always
  // includes it), evaluated at the same state as its own, so that Euler's w stays constant.
  applyBodyForces() {
    const { effects, damping } = this.scene;
    const linear = effects.damping ? damping.linear : 0;
    const angular = effects.damping ? damping.angular : 0;
    const xfrc = this.data.xfrc_applied;
    this.scene.bodies.forEach((body, i) => {
      if (body.fixed) return;
      const { velocity, angularVelocity } = this.bodyVelocity(i);
      const R = quatToMatrix(this.bodyOrientation(i));
      const Lw = matVec(matMul(matMul(R, body.inertia), transpose(R)), angularVelocity);
      let torque = scale(Lw, -angular);
      if (!effects.gyroscopic) torque = add(torque, cross(angularVelocity, Lw));
      xfrc.set([...scale(velocity, -linear * body.mass), ...torque], (i + 1) * 6);
    });
  }

  bodyOrientation(i) {
    const q = this.data.xquat.subarray((i + 1) * 4, (i + 2) * 4);
    return [q[0], q[1], q[2], q[3]];
  }

  // Centre-of-mass velocity and world angular velocity (needs positions and cvel current).
  bodyVelocity(i) {
    const kBodyObject = 1; // mjOBJ_BODY: the frame at the body's centre of mass (xipos)
    this.mj.mj_objectVelocity(this.model, this.data, kBodyObject, i + 1, this.buffer, 0);
    const v = this.buffer.GetView();
    return { angularVelocity: [v[0], v[1], v[2]], velocity: [v[3], v[4], v[5]] };
  }

  step(n) {
    const { mj, model, data } = this;
    const split = needsBodyForces(this.scene);
    let seconds = 0;
    for (let k = 0; k < n; ++k) {
      const t0 = process.hrtime.bigint();
      if (split) {
        mj.mj_step1(model, data);
        this.applyBodyForces();
        mj.mj_step2(model, data);
      } else {
        mj.mj_step(model, data);
      }
      seconds += Number(process.hrtime.bigint() - t0) * 1e-9;
      this.steps += 1;
    }
    this.lastContacts = null; // read when asked: d.contact stays the step's until the next step
    this.stale = true;
    return seconds;
  }

  time() {
    return this.data ? this.data.time : 0;
  }

  // mj_step leaves positions and velocities of the start of the step in xpos, xquat and cvel:
  // recompute them for the state after it (outside the timed step).
  refresh() {
    if (!this.stale) return;
    const { mj, model, data } = this;
    mj.mj_kinematics(model, data);
    mj.mj_comPos(model, data);
    mj.mj_comVel(model, data);
    this.stale = false;
  }

  states() {
    this.refresh();
    const xpos = this.data.xpos;
    return this.scene.bodies.map((body, i) => {
      const orientation = this.bodyOrientation(i);
      const { velocity, angularVelocity } = body.fixed
        ? { velocity: [0, 0, 0], angularVelocity: [0, 0, 0] }
        : this.bodyVelocity(i);
      return {
        position: [xpos[(i + 1) * 3], xpos[(i + 1) * 3 + 1], xpos[(i + 1) * 3 + 2]],
        orientation,
        velocity,
        angular_velocity: angularVelocity,
      };
    });
  }

  // d.contact after mj_step: the contacts the step used. pos is the midpoint, frame[0..2] the
  // normal from geom1 toward geom2, dist < 0 when penetrating. boxpile's normal points from b to
  // a: a is geom2's body, b geom1's, swapped when the ground (-1) is geom2.
  readContacts() {
    const list = this.data.contact;
    const contacts = [];
    try {
      const count = this.data.ncon;
      for (let k = 0; k < count; ++k) {
        const c = list.get(k);
        try {
          let a = this.geomBody[c.geom2];
          let b = this.geomBody[c.geom1];
          const frame = c.frame;
          let normal = [frame[0], frame[1], frame[2]];
          if (a === -1) {
            [a, b] = [b, a];
            normal = scale(normal, -1);
          }
          const pos = c.pos;
          contacts.push({ a, b, position: [pos[0], pos[1], pos[2]], normal, depth: -c.dist });
        } finally {
          c.delete();
        }
      }
    } finally {
      list.delete();
    }
    this.lastContacts = contacts;
  }

  contacts() {
    if (!this.lastContacts) this.readContacts();
    return this.lastContacts;
  }
}

serve(new MujocoEngine());
