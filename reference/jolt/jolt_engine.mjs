// Jolt Physics (npm jolt-physics 1.1.0, WebAssembly, float32) as a protocol engine.
// docs/reference-engines.md says how each scene field maps and what cannot be matched.
import initJolt from 'jolt-physics';
import { serve } from '../protocol/engine_server.mjs';
import { readScene, pairMaterial, wireGeometry, withoutDuplicates, SceneError } from '../protocol/scene.mjs';
import { add, sub, scale, dot, cross, normalize } from '../protocol/math.mjs';

const PACKAGE_VERSION = '1.1.0';

// Object layers: what does not move and what does.
const LAYER_STATIC = 0;
const LAYER_MOVING = 1;
const NUM_LAYERS = 2;

// The WebAssembly build has a fixed 128 MiB heap and a fixed temporary allocator for each step.
// Jolt preallocates per body, body pair and contact constraint, and a step's temporary needs grow
// with them: with the room below, 2,600 boxes stepped and 3,500 exhausted the step's allocator
// (an abort, which ends the WebAssembly module). This bound keeps a margin below that.
const kMaxBodies = 2500;
const kBodyPairsPerBody = 8; // a box in a pile or a wall touches up to 8 others (4 below, 4 above)
const kContactConstraintsPerBody = 8;

// The ground is Jolt's PlaneShape, a half-space bounded laterally at this half width.
const kGroundHalfWidth = 1000; // m

const MOTION_QUALITIES = ['discrete', 'linear_cast'];

function settingsTable(ps, convexRadius) {
  return [
    { key: 'velocity_iterations', kind: 'integer', min: 1, max: 1000, default: ps.mNumVelocitySteps, what: 'velocity solver iterations per step (PhysicsSettings.mNumVelocitySteps)' },
    { key: 'position_iterations', kind: 'integer', min: 0, max: 1000, default: ps.mNumPositionSteps, what: 'position solver iterations per step (mNumPositionSteps)' },
    { key: 'baumgarte', kind: 'number', min: 0, max: 1, default: ps.mBaumgarte, what: 'fraction of the position error removed per position iteration' },
    { key: 'penetration_slop', kind: 'number', unit: 'm', min: 0, max: 1, default: ps.mPenetrationSlop, what: 'penetration left uncorrected' },
    { key: 'speculative_contact_distance', kind: 'number', unit: 'm', min: 0, max: 1, default: ps.mSpeculativeContactDistance, what: 'distance at which speculative contacts start' },
    { key: 'manifold_tolerance', kind: 'number', unit: 'm', min: 0, max: 1, default: ps.mManifoldTolerance, what: 'distance within which points join one contact manifold' },
    { key: 'max_penetration_distance', kind: 'number', unit: 'm', min: 0, max: 10, default: ps.mMaxPenetrationDistance, what: 'largest penetration corrected in one step' },
    { key: 'min_velocity_for_restitution', kind: 'number', unit: 'm/s', min: 0, max: 100, default: ps.mMinVelocityForRestitution, what: 'approach speed below which restitution is not applied' },
    { key: 'warm_start', kind: 'boolean', default: ps.mConstraintWarmStart, what: 'start each solve from the last step\'s impulses' },
    { key: 'body_pair_contact_cache', kind: 'boolean', default: ps.mUseBodyPairContactCache, what: 'reuse a pair\'s contacts while the bodies barely move' },
    { key: 'manifold_reduction', kind: 'boolean', default: ps.mUseManifoldReduction, what: 'merge the manifolds of a body pair' },
    { key: 'allow_sleeping', kind: 'boolean', default: ps.mAllowSleeping, what: 'bodies at rest fall asleep (their contacts are then the last reported)' },
    { key: 'convex_radius', kind: 'number', unit: 'm', min: 0, max: 1, default: convexRadius, what: 'rounding of every box\'s edges (BoxShape default), at most each box\'s smallest half extent' },
    { key: 'collision_steps', kind: 'integer', min: 1, max: 100, default: 1, what: 'collision substeps per step (JoltInterface.Step\'s second argument)' },
    { key: 'motion_quality', kind: 'choice', choices: MOTION_QUALITIES, default: 'discrete', what: 'continuous collision detection of moving bodies (BodyCreationSettings.mMotionQuality)' },
  ];
}

const key3 = (v) => [v.GetX(), v.GetY(), v.GetZ()];

class JoltEngine {
  name = 'jolt';
  precision = 'float32';
  version = `jolt-physics ${PACKAGE_VERSION} (Jolt Physics, WebAssembly, node ${process.versions.node})`;
  settings = [];
  J = null;
  jolt = null;

  async init() {
    this.J = await initJolt();
    const ps = new this.J.PhysicsSettings();
    const half = new this.J.Vec3(1, 1, 1);
    const box = new this.J.BoxShapeSettings(half);
    this.settings = settingsTable(ps, box.mConvexRadius);
    this.J.destroy(ps);
    this.J.destroy(box);
    this.J.destroy(half);
  }

  v3(v) {
    return new this.J.Vec3(v[0], v[1], v[2]);
  }
  r3(v) {
    return new this.J.RVec3(v[0], v[1], v[2]);
  }
  quat(q) {
    return new this.J.Quat(q[1], q[2], q[3], q[0]);
  }

  // The shape a ShapeSettings describes (BodyCreationSettings takes a Shape).
  shapeOf(shapeSettings, what) {
    const made = shapeSettings.Create();
    if (made.HasError()) throw new SceneError(`Jolt rejected ${what}: ${made.GetError().c_str()}`);
    return made.Get();
  }

  release() {
    if (!this.jolt) return;
    this.J.destroy(this.jolt);
    this.jolt = null;
  }

  createInterface(bodyCount) {
    const J = this.J;
    const settings = new J.JoltSettings();
    settings.mMaxBodies = bodyCount + 1;
    settings.mMaxBodyPairs = (bodyCount + 1) * kBodyPairsPerBody;
    settings.mMaxContactConstraints = (bodyCount + 1) * kContactConstraintsPerBody;
    const pairs = new J.ObjectLayerPairFilterTable(NUM_LAYERS);
    pairs.EnableCollision(LAYER_STATIC, LAYER_MOVING);
    pairs.EnableCollision(LAYER_MOVING, LAYER_MOVING);
    const bpStatic = new J.BroadPhaseLayer(0);
    const bpMoving = new J.BroadPhaseLayer(1);
    const bp = new J.BroadPhaseLayerInterfaceTable(NUM_LAYERS, 2);
    bp.MapObjectToBroadPhaseLayer(LAYER_STATIC, bpStatic);
    bp.MapObjectToBroadPhaseLayer(LAYER_MOVING, bpMoving);
    settings.mObjectLayerPairFilter = pairs;
    settings.mBroadPhaseLayerInterface = bp;
    settings.mObjectVsBroadPhaseLayerFilter = new J.ObjectVsBroadPhaseLayerFilterTable(bp, 2, pairs, NUM_LAYERS);
    const jolt = new J.JoltInterface(settings);
    J.destroy(settings);
    return jolt;
  }

  load(sceneJson, settings) {
    if (this.aborted) throw new SceneError(this.aborted);
    this.release();
    const scene = readScene(sceneJson);
    const count = scene.bodies.length + (scene.ground ? 1 : 0);
    if (count > kMaxBodies)
      throw new SceneError(`scene ${scene.name} needs ${count} Jolt bodies; the WebAssembly build's fixed 128 MiB heap holds at most ${kMaxBodies} here`);
    this.scene = scene;
    this.settingsUsed = settings;
    try {
      this.build(scene, settings, count);
    } catch (e) {
      if (e instanceof WebAssembly.RuntimeError)
        throw new SceneError(`Jolt failed building scene ${scene.name} (${e.message}): its fixed 128 MiB heap may be too small`);
      throw e;
    }
    this.time_ = 0;
  }

  build(scene, settings, count) {
    const J = this.J;
    this.jolt = this.createInterface(count);
    const system = this.jolt.GetPhysicsSystem();
    this.system = system;
    this.bodyInterface = system.GetBodyInterface();
    const g = this.v3(scene.gravity); // Jolt's default gravity is -9.81 along y: the scene's replaces it
    system.SetGravity(g);
    J.destroy(g);

    const ps = system.GetPhysicsSettings();
    ps.mNumVelocitySteps = settings.velocity_iterations;
    ps.mNumPositionSteps = settings.position_iterations;
    ps.mBaumgarte = settings.baumgarte;
    ps.mPenetrationSlop = settings.penetration_slop;
    ps.mSpeculativeContactDistance = settings.speculative_contact_distance;
    ps.mManifoldTolerance = settings.manifold_tolerance;
    ps.mMaxPenetrationDistance = settings.max_penetration_distance;
    ps.mMinVelocityForRestitution = settings.min_velocity_for_restitution;
    ps.mConstraintWarmStart = settings.warm_start;
    ps.mUseBodyPairContactCache = settings.body_pair_contact_cache;
    ps.mUseManifoldReduction = settings.manifold_reduction;
    ps.mAllowSleeping = settings.allow_sleeping;
    system.SetPhysicsSettings(ps);

    this.indexOf = new Map(); // Jolt body id -> scene index (-1: the ground)
    this.materialOf = new Map(); // Jolt body id -> material
    this.movingIds = new Map(); // Jolt body id -> BodyID, of the scene's moving bodies
    if (scene.ground) this.addGround(scene);
    this.bodyIds = scene.bodies.map((body, i) => this.addBody(scene, body, i, settings));
    this.installListener();
    this.contactCache = new Map();
    this.removed = [];
  }

  addGround(scene) {
    const J = this.J;
    const { normal, offset } = scene.ground;
    const n = this.v3(normal);
    const plane = new J.Plane(n, -offset); // Jolt's plane: n . x + c = 0, solid where negative
    const shape = this.shapeOf(new J.PlaneShapeSettings(plane, null, kGroundHalfWidth), 'the ground');
    const origin = this.r3([0, 0, 0]);
    const q = this.quat([1, 0, 0, 0]);
    const bcs = new J.BodyCreationSettings(shape, origin, q, J.EMotionType_Static, LAYER_STATIC);
    bcs.mFriction = scene.groundMaterial.friction;
    bcs.mRestitution = scene.groundMaterial.restitution;
    const body = this.bodyInterface.CreateBody(bcs);
    this.bodyInterface.AddBody(body.GetID(), J.EActivation_DontActivate);
    const id = body.GetID().GetIndexAndSequenceNumber();
    this.indexOf.set(id, -1);
    this.materialOf.set(id, scene.groundMaterial);
    for (const o of [n, plane, origin, q, bcs]) J.destroy(o);
  }

  // The body's shape in its frame: its boxes in a static compound, with the centre of mass moved
  // to the scene's (Jolt would put it at the boxes' centroid).
  bodyShape(body, settings) {
    const J = this.J;
    const compound = new J.StaticCompoundShapeSettings();
    for (const box of body.boxes) {
      const half = this.v3(box.halfExtents);
      const radius = Math.min(settings.convex_radius, ...box.halfExtents);
      const boxSettings = new J.BoxShapeSettings(half, radius);
      const p = this.v3(box.position);
      const q = this.quat(box.orientation);
      compound.AddShape(p, q, boxSettings, 0);
      for (const o of [half, p, q]) J.destroy(o);
    }
    const what = `the boxes of ${body.name}`;
    if (body.fixed) return this.shapeOf(compound, what);
    const centroid = key3(this.shapeOf(compound, what).GetCenterOfMass());
    const offset = this.v3(sub(body.centerOfMass, centroid));
    const shape = this.shapeOf(new J.OffsetCenterOfMassShapeSettings(offset, compound), what);
    J.destroy(offset);
    return shape;
  }

  addBody(scene, body, index, settings) {
    const J = this.J;
    const shape = this.bodyShape(body, settings);
    const pos = this.r3(body.position);
    const q = this.quat(body.orientation);
    const motion = body.fixed ? J.EMotionType_Static : J.EMotionType_Dynamic;
    const bcs = new J.BodyCreationSettings(shape, pos, q, motion, body.fixed ? LAYER_STATIC : LAYER_MOVING);
    bcs.mFriction = body.material.friction;
    bcs.mRestitution = body.material.restitution;
    if (!body.fixed) {
      bcs.mOverrideMassProperties = J.EOverrideMassProperties_MassAndInertiaProvided;
      const mp = bcs.mMassPropertiesOverride;
      mp.mMass = body.mass;
      const I = body.inertia; // about the centre of mass, in the body's axes, as Jolt's
      for (let c = 0; c < 3; ++c) {
        const column = new J.Vec4(I[0][c], I[1][c], I[2][c], 0);
        mp.mInertia.SetColumn4(c, column);
        J.destroy(column);
      }
      const last = new J.Vec4(0, 0, 0, 1);
      mp.mInertia.SetColumn4(3, last);
      J.destroy(last);
      const v = this.v3(body.velocity);
      const w = this.v3(body.angularVelocity);
      bcs.mLinearVelocity = v;
      bcs.mAngularVelocity = w;
      J.destroy(v);
      J.destroy(w);
      const damping = scene.effects.damping ? scene.damping : { linear: 0, angular: 0 };
      bcs.mLinearDamping = damping.linear; // Jolt's default 0.05 would damp every scene
      bcs.mAngularDamping = damping.angular;
      bcs.mApplyGyroscopicForce = scene.effects.gyroscopic;
      bcs.mAllowSleeping = settings.allow_sleeping;
      bcs.mMotionQuality = settings.motion_quality === 'discrete' ? J.EMotionQuality_Discrete : J.EMotionQuality_LinearCast;
      bcs.mMaxLinearVelocity = 1e4; // m/s: above Jolt's 500 so that no scene is clipped
      bcs.mMaxAngularVelocity = 1e4; // rad/s: above Jolt's 0.25 pi / step default
    }
    const created = this.bodyInterface.CreateBody(bcs);
    for (const o of [pos, q, bcs]) J.destroy(o);
    if (!created || created.ptr === 0) throw new SceneError(`Jolt could not create ${body.name}: its fixed 128 MiB heap may be full`);
    const bodyId = created.GetID();
    this.bodyInterface.AddBody(bodyId, body.fixed ? J.EActivation_DontActivate : J.EActivation_Activate);
    const id = bodyId.GetIndexAndSequenceNumber();
    this.indexOf.set(id, index);
    this.materialOf.set(id, body.material);
    if (!body.fixed) this.movingIds.set(id, bodyId);
    if (body.wire) this.addWire(body, created);
    return bodyId;
  }

  // The wire as one SixDOFConstraint between the world and the body at its anchor: translation
  // along the wire free between its ends, across it fixed, every rotation free. (A slider to a
  // light carriage plus a point constraint needs a carriage far lighter than the body, which
  // Jolt's iterative solver resolves poorly: the anchor sagged 8 mm and lagged 9 cm in the wire
  // test at a 1:1000 mass ratio.)
  addWire(body, created) {
    const J = this.J;
    const wire = wireGeometry(body);
    const normalAxis = normalize(Math.abs(wire.axis[0]) < 0.9 ? cross(wire.axis, [1, 0, 0]) : cross(wire.axis, [0, 1, 0]));
    const six = new J.SixDOFConstraintSettings();
    six.mSpace = J.EConstraintSpace_WorldSpace;
    const p = this.r3(wire.anchorWorld);
    const x = this.v3(wire.axis);
    const y = this.v3(normalAxis);
    six.mPosition1 = p;
    six.mPosition2 = p;
    six.mAxisX1 = x;
    six.mAxisX2 = x;
    six.mAxisY1 = y;
    six.mAxisY2 = y;
    six.SetLimitedAxis(J.SixDOFConstraintSettings_EAxis_TranslationX, -wire.s0, wire.length - wire.s0);
    six.MakeFixedAxis(J.SixDOFConstraintSettings_EAxis_TranslationY);
    six.MakeFixedAxis(J.SixDOFConstraintSettings_EAxis_TranslationZ);
    six.MakeFreeAxis(J.SixDOFConstraintSettings_EAxis_RotationX);
    six.MakeFreeAxis(J.SixDOFConstraintSettings_EAxis_RotationY);
    six.MakeFreeAxis(J.SixDOFConstraintSettings_EAxis_RotationZ);
    this.system.AddConstraint(six.Create(this.jolt.sGetFixedToWorldBody(), created));
    for (const o of [p, x, y, six]) J.destroy(o);
  }

  // Jolt reports contacts through a listener during the step. Each manifold is copied inside the
  // callback (its memory is Jolt's) and kept by sub-shape pair until Jolt removes the pair. Jolt
  // also removes the pairs of bodies that fall asleep: those are kept (after the step, a pair
  // whose moving bodies are all asleep), so that a sleeping pile still reports its last contacts.
  // The pair's friction and restitution are set to boxpile's law explicitly.
  installListener() {
    const J = this.J;
    const listener = new J.ContactListenerJS();
    const onContact = (body1Ptr, body2Ptr, manifoldPtr, settingsPtr) => {
      const body1 = J.wrapPointer(body1Ptr, J.Body);
      const body2 = J.wrapPointer(body2Ptr, J.Body);
      const manifold = J.wrapPointer(manifoldPtr, J.ContactManifold);
      const contactSettings = J.wrapPointer(settingsPtr, J.ContactSettings);
      const id1 = body1.GetID().GetIndexAndSequenceNumber();
      const id2 = body2.GetID().GetIndexAndSequenceNumber();
      const m1 = this.materialOf.get(id1);
      const m2 = this.materialOf.get(id2);
      if (m1 && m2) {
        const m = pairMaterial(this.scene.effects, m1, m2);
        contactSettings.mCombinedFriction = m.friction;
        contactSettings.mCombinedRestitution = m.restitution;
      }
      const normal = key3(manifold.mWorldSpaceNormal);
      const points = [];
      const count = manifold.mRelativeContactPointsOn1.size();
      for (let k = 0; k < count; ++k)
        points.push([key3(manifold.GetWorldSpaceContactPointOn1(k)), key3(manifold.GetWorldSpaceContactPointOn2(k))]);
      const key = pairKey(id1, manifold.mSubShapeID1.GetValue(), id2, manifold.mSubShapeID2.GetValue());
      this.contactCache.set(key, { id1, id2, normal, points });
    };
    listener.OnContactValidate = () => J.ValidateResult_AcceptAllContactsForThisBodyPair;
    listener.OnContactAdded = onContact;
    listener.OnContactPersisted = onContact;
    listener.OnContactRemoved = (pairPtr) => {
      const pair = J.wrapPointer(pairPtr, J.SubShapeIDPair);
      this.removed.push(pairKey(
        pair.GetBody1ID().GetIndexAndSequenceNumber(), pair.GetSubShapeID1().GetValue(),
        pair.GetBody2ID().GetIndexAndSequenceNumber(), pair.GetSubShapeID2().GetValue()));
    };
    this.system.SetContactListener(listener);
    this.listener = listener;
  }

  step(n) {
    let seconds = 0;
    const steps = this.settingsUsed.collision_steps;
    for (let k = 0; k < n; ++k) {
      const t0 = process.hrtime.bigint();
      try {
        this.jolt.Step(this.scene.dt, steps);
      } catch (e) {
        if (!(e instanceof WebAssembly.RuntimeError)) throw e;
        this.aborted = `Jolt aborted at ${this.time_.toFixed(6)} s of scene ${this.scene.name} (${e.message}): its fixed heap or step allocator is exhausted, and the module cannot run again in this process`;
        throw new SceneError(this.aborted);
      }
      seconds += Number(process.hrtime.bigint() - t0) * 1e-9;
      this.time_ += this.scene.dt;
      this.forgetRemoved();
    }
    return seconds;
  }

  forgetRemoved() {
    const bi = this.bodyInterface;
    const awake = (id) => {
      const bodyId = this.movingIds.get(id);
      return bodyId !== undefined && bi.IsActive(bodyId);
    };
    for (const key of this.removed) {
      const entry = this.contactCache.get(key);
      if (entry && (awake(entry.id1) || awake(entry.id2))) this.contactCache.delete(key);
    }
    this.removed.length = 0;
  }

  time() {
    return this.time_;
  }

  states() {
    const bi = this.bodyInterface;
    return this.bodyIds.map((id) => {
      const position = key3(bi.GetPosition(id));
      const r = bi.GetRotation(id);
      const orientation = [r.GetW(), r.GetX(), r.GetY(), r.GetZ()];
      return {
        position,
        orientation,
        velocity: key3(bi.GetLinearVelocity(id)), // of the centre of mass, as boxpile's
        angular_velocity: key3(bi.GetAngularVelocity(id)),
      };
    });
  }

  // mWorldSpaceNormal points from body 1 toward body 2 (moving body 2 along it separates them):
  // a is body 2, b body 1, swapped when the ground is body 2. The depth of each point is the
  // overlap of its two surface points along the normal; speculative points (apart) are left out.
  contacts() {
    const found = [];
    for (const { id1, id2, normal, points } of this.contactCache.values()) {
      let a = this.indexOf.get(id2);
      let b = this.indexOf.get(id1);
      if (a === undefined || b === undefined) continue;
      let n = normal;
      if (a === -1) {
        [a, b] = [b, a];
        n = scale(normal, -1);
      }
      for (const [p1, p2] of points) {
        const depth = dot(sub(p1, p2), normal);
        if (!(depth >= 0)) continue;
        found.push({ a, b, position: scale(add(p1, p2), 0.5), normal: n, depth });
      }
    }
    return withoutDuplicates(found);
  }
}

function pairKey(id1, sub1, id2, sub2) {
  return id1 < id2 || (id1 === id2 && sub1 <= sub2) ? `${id1}/${sub1}:${id2}/${sub2}` : `${id2}/${sub2}:${id1}/${sub1}`;
}


serve(new JoltEngine());
