// The replay page of boxpile: draws the recordings packed in #replay-data (docs/viewer.md) with
// three.js, one viewport per engine (cameras linked) or all engines overlaid, on one timeline.
// The page reports its state on <body> for tests: data-state ("loading", "ready" or
// "error: ..."), data-engines, data-frames, data-frame, data-contacts, data-mode, data-resources
// (resources loaded from outside the page: 0), data-picked (the picked body's name),
// data-canvas (the 3D view: left,top,width,height), data-framing (the share of the first
// viewport's width and height that the bodies of the first frame cover through the fitted first
// camera), data-contact-fill (each engine's contact colour), data-contact-pixels (a contact dot's
// diameter at the fitted camera's target) and data-energy-cursor (the energy graph's cursor on the
// timeline, 0 to 1).
(function () {
  'use strict';

  // Each engine's colour comes with its data (the engine registry's, the same in every plot);
  // data written before engines carried one draws them in this grey.
  var NO_COLOUR = '#a5aa99';
  var BACKGROUND = 0x14171c;
  var GROUND = 0x9c9c94;
  var GRID = 0x84847c;
  var WIRE = 0xd0d0d0;
  // A picked body glows by this much yellow, in every engine.
  var HIGHLIGHT = 0x555522;
  // Ambient light keeps every face's hue readable; the sun (from the front left, above) shades
  // faces apart. Together they stay below 1 on a lit face, so no colour clips to white.
  var AMBIENT = 0.55;
  var SUN = 0.5;
  // Body edges are drawn in the engine's colour darkened to this fraction.
  var EDGE_SHADE = 0.45;
  // Contacts are drawn in the engine's colour mixed this far toward white, a light tint that
  // stands out on the engine's own boxes however dark, and each dot has a dark rim, which stands
  // out on the light ground.
  var CONTACT_TINT = 0.85;
  var CONTACT_RIM = '#0b0d10';
  // A contact dot's diameter: this fraction of the median body's size as seen at the camera's
  // target (so it follows the scene and the zoom), kept within the pixels below so that it stays
  // readable far away and does not hide the box near by; the share of its radius taken by its rim.
  var DOT_FRACTION = 0.14;
  var DOT_PIXELS = [8, 20];
  var RIM_SHARE = 0.3;
  // An arrow head's radius and length, as fractions of the arrow's base length.
  var HEAD_RADIUS = 0.22;
  var HEAD_LENGTH = 0.45;
  // Vertical field of view, degrees; the first view leaves this much margin around the scene.
  var FOV = 40;
  var FIT_MARGIN = 1.08;
  // A fixed body counts in the first view only within this many times the moving bodies' extent
  // around them (a fixed floor slab of 100 m would leave the boxes on it a few pixels).
  var FIXED_REACH = 1.0;
  // The energy graph on the timeline: its drawing's size (stretched to the timeline's width) and
  // the margin above and below the lines.
  var GRAPH_WIDTH = 1000;
  var GRAPH_HEIGHT = 100;
  var GRAPH_MARGIN = 8;
  // Opacity of bodies when engines are overlaid.
  var OVERLAY_OPACITY = 0.45;
  // Floats per body state and per contact point (the packing of validation/replay/replay_data.cpp).
  var STATE_FLOATS = 13;
  var CONTACT_FLOATS = 7;
  // A normal arrow's length at zero depth, as a fraction of the median body's size.
  var ARROW_BASE_FRACTION = 0.25;
  // A click that moves less than this many pixels picks a body (more is an orbit drag).
  var CLICK_SLOP = 5;
  // Most grid lines drawn on the ground each way (cells of two body sizes, fewer on a large ground).
  var GRID_LINES = 60;
  // The first camera looks at the scene from this direction (from the front left, above: where the bone scene's bone comes from).
  var VIEW_DIRECTION = [-0.75, -1.0, 0.6];

  var body = document.body;
  var $ = function (id) { return document.getElementById(id); };

  function fail(error) {
    var message = (error && error.message) ? error.message : String(error);
    body.setAttribute('data-state', 'error: ' + message);
    var box = $('error');
    box.textContent = 'This replay cannot be shown: ' + message;
    box.style.display = 'block';
  }

  // --- data ---

  function bytesOf(text) {
    var bin = atob(text);
    var bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new DataView(bytes.buffer);
  }
  // Little-endian arrays, whatever the browser's byte order.
  function floats(text) {
    var view = bytesOf(text), out = new Float32Array(view.byteLength / 4);
    for (var i = 0; i < out.length; ++i) out[i] = view.getFloat32(4 * i, true);
    return out;
  }
  function int16s(text) {
    var view = bytesOf(text), out = new Int16Array(view.byteLength / 2);
    for (var i = 0; i < out.length; ++i) out[i] = view.getInt16(2 * i, true);
    return out;
  }
  function uint32s(text) {
    var view = bytesOf(text), out = new Uint32Array(view.byteLength / 4);
    for (var i = 0; i < out.length; ++i) out[i] = view.getUint32(4 * i, true);
    return out;
  }

  function readEngine(e, colour, bodies) {
    var counts = e.contact_counts, offsets = [0];
    for (var f = 0; f < counts.length; ++f) offsets.push(offsets[f] + counts[f]);
    var engine = {
      name: e.name, colour: colour, t: e.t, energy: e.energy, frames: e.t.length,
      states: floats(e.states), counts: counts, offsets: offsets, contacts: floats(e.contacts),
      pairs: int16s(e.contact_bodies), features: uint32s(e.contact_features), stopped: e.stopped,
      maxContacts: Math.max.apply(null, counts.concat([0]))
    };
    if (engine.states.length !== engine.frames * bodies * STATE_FLOATS) throw new Error(e.name + ': states do not match the frames');
    if (engine.contacts.length !== offsets[counts.length] * CONTACT_FLOATS) throw new Error(e.name + ': contacts do not match their counts');
    return engine;
  }

  // --- the scene ---

  function boxGroup(shape, material, edgeMaterial) {
    var group = new THREE.Group();
    shape.boxes.forEach(function (box) {
      var h = box.half_extents, geometry = new THREE.BoxBufferGeometry(2 * h[0], 2 * h[1], 2 * h[2]);
      var mesh = new THREE.Mesh(geometry, material);
      mesh.position.set(box.offset[0], box.offset[1], box.offset[2]);
      var q = box.orientation;
      mesh.quaternion.set(q[1], q[2], q[3], q[0]);
      group.add(mesh);
      var edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry), edgeMaterial);
      edges.position.copy(mesh.position);
      edges.quaternion.copy(mesh.quaternion);
      group.add(edges);
    });
    return group;
  }

  // The extent of every body over every frame of every engine (and of the wires), and the median
  // body's size (its largest box dimension).
  function sceneBounds(data, engines) {
    var box = new THREE.Box3(), sizes = [], reach = [];
    data.shapes.bodies.forEach(function (b) {
      var r = 0, size = 0;
      b.boxes.forEach(function (x) {
        var h = x.half_extents, o = x.offset;
        r = Math.max(r, Math.sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) + Math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]));
        size = Math.max(size, 2 * h[0], 2 * h[1], 2 * h[2]);
      });
      reach.push(r);
      sizes.push(size);
    });
    sizes.sort(function (a, b) { return a - b; });
    var n = data.shapes.bodies.length, p = new THREE.Vector3();
    engines.forEach(function (e) {
      for (var f = 0; f < e.frames; f += Math.max(1, Math.floor(e.frames / 60))) {
        for (var i = 0; i < n; ++i) {
          var k = (f * n + i) * STATE_FLOATS;
          p.set(e.states[k], e.states[k + 1], e.states[k + 2]);
          box.expandByPoint(p.clone().addScalar(reach[i])).expandByPoint(p.clone().addScalar(-reach[i]));
        }
      }
    });
    data.shapes.bodies.forEach(function (b) {
      if (!b.wire) return;
      box.expandByPoint(new THREE.Vector3().fromArray(b.wire.from)).expandByPoint(new THREE.Vector3().fromArray(b.wire.to));
    });
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    return { box: box, typical: sizes.length ? sizes[Math.floor(sizes.length / 2)] : 0.5 };
  }

  // The corners of every box of every body at the first frame (of the first engine: every engine
  // starts from the scene's poses). Fixed bodies count only near the moving ones (FIXED_REACH).
  function firstFramePoints(data, engine) {
    var moving = [], fixed = [], q = new THREE.Quaternion();
    data.shapes.bodies.forEach(function (b, i) {
      var s = i * STATE_FLOATS, st = engine.states;
      var at = new THREE.Vector3(st[s], st[s + 1], st[s + 2]);
      var turn = new THREE.Quaternion(st[s + 4], st[s + 5], st[s + 6], st[s + 3]);
      b.boxes.forEach(function (x) {
        var h = x.half_extents, o = x.offset, r = x.orientation;
        q.set(r[1], r[2], r[3], r[0]);
        for (var k = 0; k < 8; ++k) {
          var p = new THREE.Vector3(k & 1 ? h[0] : -h[0], k & 2 ? h[1] : -h[1], k & 4 ? h[2] : -h[2]).applyQuaternion(q);
          (b.fixed ? fixed : moving).push(p.add(new THREE.Vector3(o[0], o[1], o[2])).applyQuaternion(turn).add(at));
        }
      });
    });
    if (moving.length === 0) return fixed;
    var box = new THREE.Box3().setFromPoints(moving), reach = box.getSize(new THREE.Vector3()).multiplyScalar(FIXED_REACH);
    var near = new THREE.Box3(box.min.clone().sub(reach), box.max.clone().add(reach));
    return moving.concat(fixed.map(function (x) { return near.clampPoint(x, new THREE.Vector3()); }));
  }

  // The camera's right and up for a view along -direction (z up).
  function viewAxes(direction) {
    var forward = direction.clone().negate(), right = new THREE.Vector3().crossVectors(forward, new THREE.Vector3(0, 0, 1));
    if (right.lengthSq() < 1e-12) right.set(1, 0, 0);
    right.normalize();
    return { right: right, up: new THREE.Vector3().crossVectors(right, forward) };
  }

  // The camera distance along `direction` from `centre` at which every point is in view.
  function fitDistance(points, centre, direction, fov, aspect) {
    var axes = viewAxes(direction), tanV = Math.tan(fov * Math.PI / 360), tanH = tanV * aspect, distance = 0;
    points.forEach(function (x) {
      var c = x.clone().sub(centre), depth = c.dot(direction);  // toward the camera
      distance = Math.max(distance, depth + Math.abs(c.dot(axes.right)) / tanH, depth + Math.abs(c.dot(axes.up)) / tanV);
    });
    return distance;
  }

  // The extent of the points on the screen through `camera`: [xmin, xmax, ymin, ymax] in normalized
  // device coordinates (-1 to 1).
  function screenExtent(points, camera) {
    var e = [Infinity, -Infinity, Infinity, -Infinity];
    points.forEach(function (x) {
      var v = x.clone().project(camera);
      e = [Math.min(e[0], v.x), Math.max(e[1], v.x), Math.min(e[2], v.y), Math.max(e[3], v.y)];
    });
    return e;
  }

  // A round dot with a dark rim, as a texture for the contact points.
  function dotTexture(fill) {
    var size = 64, c = document.createElement('canvas');
    c.width = c.height = size;
    var g = c.getContext('2d');
    [[CONTACT_RIM, 1], [fill, 1 - RIM_SHARE]].forEach(function (ring) {
      g.beginPath();
      g.arc(size / 2, size / 2, (size / 2 - 1) * ring[1], 0, 2 * Math.PI);
      g.fillStyle = ring[0];
      g.fill();
    });
    return new THREE.CanvasTexture(c);
  }

  function addGround(scene, ground, bounds) {
    var size = bounds.box.getSize(new THREE.Vector3());
    var extent = 1.6 * Math.max(size.x, size.y, size.z, 1);
    var normal = new THREE.Vector3().fromArray(ground.normal).normalize();
    var centre = bounds.box.getCenter(new THREE.Vector3());
    // The plane's point nearest the scene's centre.
    var origin = centre.clone().sub(normal.clone().multiplyScalar(centre.dot(normal) - ground.offset));
    var turn = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal);
    var plane = new THREE.Mesh(new THREE.PlaneBufferGeometry(extent, extent),
      new THREE.MeshLambertMaterial({ color: GROUND, side: THREE.DoubleSide }));
    plane.position.copy(origin);
    plane.quaternion.copy(turn);
    scene.add(plane);
    var grid = new THREE.GridHelper(extent, Math.max(1, Math.min(GRID_LINES, Math.round(extent / (2 * bounds.typical)))), GRID, GRID);
    grid.quaternion.copy(turn).multiply(new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), Math.PI / 2));
    grid.position.copy(origin).add(normal.clone().multiplyScalar(1e-3 * extent));
    scene.add(grid);
  }

  function addWires(scene, shapes) {
    shapes.bodies.forEach(function (b) {
      if (!b.wire) return;
      var g = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3().fromArray(b.wire.from), new THREE.Vector3().fromArray(b.wire.to)]);
      scene.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: WIRE })));
    });
  }

  // An engine's bodies (one material per body, so that a picked body can be highlighted) and its
  // contact points, normal shafts and arrow heads, in buffers sized for its largest frame.
  function buildEngine(engine, shapes, arrowBase) {
    var colour = new THREE.Color(engine.colour);
    var dark = colour.clone().multiplyScalar(EDGE_SHADE);
    var tint = colour.clone().lerp(new THREE.Color(0xffffff), CONTACT_TINT);
    engine.contactFill = '#' + tint.getHexString();
    engine.group = new THREE.Group();
    engine.edgeMaterial = new THREE.LineBasicMaterial({ color: dark, transparent: true });
    engine.materials = [];
    engine.bodies = shapes.bodies.map(function (shape, i) {
      var material = new THREE.MeshLambertMaterial({ color: colour, emissive: 0x000000 });
      engine.materials.push(material);
      var g = boxGroup(shape, material, engine.edgeMaterial);
      g.userData = { engine: engine, body: i };
      g.children.forEach(function (c) { c.userData = g.userData; });
      engine.group.add(g);
      return g;
    });
    var n = Math.max(1, engine.maxContacts);
    var pointGeometry = new THREE.BufferGeometry();
    pointGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
    engine.points = new THREE.Points(pointGeometry, new THREE.PointsMaterial({
      map: dotTexture(engine.contactFill), size: DOT_PIXELS[0], sizeAttenuation: false, alphaTest: 0.5, depthTest: false }));
    var shaftGeometry = new THREE.BufferGeometry();
    shaftGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6 * n), 3));
    engine.shafts = new THREE.LineSegments(shaftGeometry, new THREE.LineBasicMaterial({ color: tint, depthTest: false }));
    engine.heads = new THREE.InstancedMesh(new THREE.ConeBufferGeometry(HEAD_RADIUS * arrowBase, HEAD_LENGTH * arrowBase, 10),
      new THREE.MeshBasicMaterial({ color: tint, depthTest: false }), n);
    engine.contactGroup = new THREE.Group();
    // The dots last, over their arrows.
    [engine.shafts, engine.heads, engine.points].forEach(function (o, k) {
      o.frustumCulled = false;
      o.renderOrder = 10 + k;
      engine.contactGroup.add(o);
    });
    engine.group.add(engine.contactGroup);
  }

  // --- the page ---

  function main() {
    var data = JSON.parse($('replay-data').textContent);
    if (typeof THREE === 'undefined') throw new Error('three.js is missing from the page');
    var shapes = data.shapes, nBodies = shapes.bodies.length;
    var engines = data.engines.map(function (e) { return readEngine(e, e.colour || NO_COLOUR, nBodies); });
    if (engines.length === 0) throw new Error('no engine in the data');
    var frames = Math.max.apply(null, engines.map(function (e) { return e.frames; }));
    var clock = engines.filter(function (e) { return e.frames === frames; })[0];
    var hash = new URLSearchParams(location.hash.slice(1));

    document.title = 'boxpile replay: ' + data.title;
    $('title').textContent = data.title;
    body.setAttribute('data-engines', engines.map(function (e) { return e.name; }).join(','));
    body.setAttribute('data-frames', String(frames));

    // Renderer, scene, one camera shared by every viewport.
    var canvas = $('canvas');
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(BACKGROUND);
    var scene = new THREE.Scene();
    scene.add(new THREE.AmbientLight(0xffffff, AMBIENT));
    var sun = new THREE.DirectionalLight(0xffffff, SUN);
    sun.position.set(0.4, -0.6, 1.0);
    scene.add(sun);
    var bounds = sceneBounds(data, engines);
    if (shapes.ground) addGround(scene, shapes.ground, bounds);
    addWires(scene, shapes);
    var arrowBase = ARROW_BASE_FRACTION * bounds.typical, dotSize = DOT_FRACTION * bounds.typical;
    engines.forEach(function (e) { buildEngine(e, shapes, arrowBase); scene.add(e.group); });
    var firstPoints = firstFramePoints(data, engines[0]);

    var camera = new THREE.PerspectiveCamera(FOV, 1, 0.01, 1000);
    camera.up.set(0, 0, 1);
    var controls = new THREE.OrbitControls(camera, canvas);
    controls.enableDamping = false;
    // The bodies of the first frame filling the first viewport, seen from VIEW_DIRECTION: fitted
    // about the centre of their box, then centred on their picture on the screen (which
    // perspective shifts) and fitted again.
    function fitCamera() {
      var direction = new THREE.Vector3().fromArray(VIEW_DIRECTION).normalize();
      var v = viewports()[0], aspect = v.w / Math.max(1, v.h), axes = viewAxes(direction);
      var centre = new THREE.Box3().setFromPoints(firstPoints).getCenter(new THREE.Vector3());
      camera.aspect = aspect;
      camera.updateProjectionMatrix();
      for (var pass = 0; ; ++pass) {
        var distance = FIT_MARGIN * fitDistance(firstPoints, centre, direction, camera.fov, aspect);
        camera.position.copy(centre).addScaledVector(direction, distance);
        camera.lookAt(centre);
        camera.updateMatrixWorld();
        if (pass === 2) break;
        var e = screenExtent(firstPoints, camera), tanV = Math.tan(camera.fov * Math.PI / 360);
        centre.addScaledVector(axes.right, 0.5 * (e[0] + e[1]) * distance * tanV * aspect)
          .addScaledVector(axes.up, 0.5 * (e[2] + e[3]) * distance * tanV);
      }
      controls.target.copy(centre);
    }
    // The first camera: fitCamera's, or what the address asks for (camera=x,y,z and target=x,y,z).
    // Until the user moves it, a fitted camera is fitted again whenever the first viewport's shape
    // changes (the window resized, the page laid out again, the mode switched): `fittedAspect`.
    var fittedAspect = null;
    function resetCamera() {
      fitCamera();
      fittedAspect = camera.aspect;
      var asked = function (key) {
        var xyz = (hash.get(key) || '').split(',').map(Number);
        return xyz.length === 3 && xyz.every(isFinite) ? new THREE.Vector3().fromArray(xyz) : null;
      };
      if (asked('target')) controls.target.copy(asked('target'));
      if (asked('camera')) camera.position.copy(asked('camera'));
      if (asked('target') || asked('camera')) fittedAspect = null;
      var size = bounds.box.getSize(new THREE.Vector3()).length();
      camera.near = size / 1000;
      camera.far = size * 100;
      controls.update();
    }
    var state = {
      frame: 0, mode: 'side', contacts: true, gain: 20,
      playing: false, speed: 1, picked: null, playTime: 0
    };

    // --- drawing ---

    function viewports() {
      var w = canvas.clientWidth, h = canvas.clientHeight;
      if (state.mode === 'overlay') return [{ x: 0, y: 0, w: w, h: h, engines: engines }];
      var n = engines.length;
      return engines.map(function (e, i) {
        var x0 = Math.round(i * w / n), x1 = Math.round((i + 1) * w / n);
        return { x: x0, y: 0, w: x1 - x0, h: h, engines: [e] };
      });
    }

    // A contact dot's diameter in pixels through the camera in viewport `v`.
    function dotPixels(v) {
      var seen = dotSize * v.h / (2 * camera.position.distanceTo(controls.target) * Math.tan(camera.fov * Math.PI / 360));
      return Math.max(DOT_PIXELS[0], Math.min(DOT_PIXELS[1], seen));
    }

    function render() {
      var w = canvas.clientWidth, h = canvas.clientHeight, first = viewports()[0];
      if (fittedAspect !== null && Math.abs(first.w / Math.max(1, first.h) - fittedAspect) > 1e-9) resetCamera();
      if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
        renderer.setSize(w, h, false);
      }
      var dot = dotPixels(first);
      engines.forEach(function (e) { e.points.material.size = dot * renderer.getPixelRatio(); });
      renderer.setScissorTest(true);
      viewports().forEach(function (v) {
        engines.forEach(function (e) { e.group.visible = v.engines.indexOf(e) >= 0; });
        renderer.setViewport(v.x, v.y, v.w, v.h);
        renderer.setScissor(v.x, v.y, v.w, v.h);
        camera.aspect = v.w / Math.max(1, v.h);
        camera.updateProjectionMatrix();
        renderer.render(scene, camera);
      });
      engines.forEach(function (e) { e.group.visible = true; });
      placeLabels();
    }

    var labels = engines.map(function (e) {
      var div = document.createElement('div');
      div.className = 'vlabel';
      $('labels').appendChild(div);
      return div;
    });
    function placeLabels() {
      var vs = viewports();
      engines.forEach(function (e, i) {
        var d = labels[i];
        if (state.mode === 'overlay') {
          d.style.display = 'none';
          return;
        }
        d.style.display = '';
        d.style.left = (vs[i].x + 8) + 'px';
        var k = Math.min(state.frame, e.frames - 1);
        d.innerHTML = '<span class="swatch" style="background:' + e.colour + '"></span>' + e.name +
          (e.stopped && state.frame >= e.frames - 1 ? ' (stopped: ' + e.stopped.body + ' ' + e.stopped.quantity + ' not finite)' : '') +
          (k < state.frame ? ' (last frame)' : '');
      });
    }

    var matrix = new THREE.Matrix4(), turn = new THREE.Quaternion(), up = new THREE.Vector3(0, 1, 0);
    var tip = new THREE.Vector3(), nrm = new THREE.Vector3(), one = new THREE.Vector3(1, 1, 1);

    function showContacts(e, k) {
      var count = state.contacts ? e.counts[k] : 0, first = e.offsets[k];
      var pos = e.points.geometry.attributes.position, shaft = e.shafts.geometry.attributes.position;
      for (var j = 0; j < count; ++j) {
        var c = (first + j) * CONTACT_FLOATS, d = e.contacts[c + 6];
        pos.setXYZ(j, e.contacts[c], e.contacts[c + 1], e.contacts[c + 2]);
        nrm.set(e.contacts[c + 3], e.contacts[c + 4], e.contacts[c + 5]);
        var length = arrowBase + state.gain * Math.max(d, 0);
        tip.set(e.contacts[c], e.contacts[c + 1], e.contacts[c + 2]).addScaledVector(nrm, length);
        shaft.setXYZ(2 * j, e.contacts[c], e.contacts[c + 1], e.contacts[c + 2]);
        shaft.setXYZ(2 * j + 1, tip.x, tip.y, tip.z);
        turn.setFromUnitVectors(up, nrm);
        matrix.compose(tip, turn, one);
        e.heads.setMatrixAt(j, matrix);
      }
      pos.needsUpdate = true;
      shaft.needsUpdate = true;
      e.heads.instanceMatrix.needsUpdate = true;
      e.points.geometry.setDrawRange(0, count);
      e.shafts.geometry.setDrawRange(0, 2 * count);
      e.heads.count = count;
      e.contactGroup.visible = count > 0;
      return count;
    }

    function showFrame(f) {
      state.frame = Math.max(0, Math.min(frames - 1, f));
      var drawn = 0, energyText = [];
      engines.forEach(function (e) {
        var k = Math.min(state.frame, e.frames - 1);
        for (var i = 0; i < nBodies; ++i) {
          var s = (k * nBodies + i) * STATE_FLOATS, g = e.bodies[i];
          g.position.set(e.states[s], e.states[s + 1], e.states[s + 2]);
          g.quaternion.set(e.states[s + 4], e.states[s + 5], e.states[s + 6], e.states[s + 3]);
        }
        drawn += showContacts(e, k);
        var energy = e.energy[k];
        energyText.push('<span class="swatch" style="background:' + e.colour + '"></span>' + e.name + ' ' +
          (energy === null ? '-' : energy.toFixed(3) + ' J') + (state.contacts ? ', ' + e.counts[k] + ' contacts' : ''));
      });
      moveEnergyCursor();
      $('slider').value = String(state.frame);
      $('time').textContent = 't = ' + clock.t[state.frame].toFixed(4) + ' s  (frame ' + state.frame + ' of ' + (frames - 1) + ')';
      $('energy').innerHTML = 'energy (kinetic + potential): ' + energyText.join(' &nbsp; ');
      body.setAttribute('data-frame', String(state.frame));
      body.setAttribute('data-contacts', String(drawn));
      showPicked();
      render();
    }

    // --- picking ---

    function setHighlight(on) {
      if (!state.picked) return;
      engines.forEach(function (e) { e.materials[state.picked.body].emissive.setHex(on ? HIGHLIGHT : 0x000000); });
    }
    function vec(a, s, digits) {
      return '(' + [a[s], a[s + 1], a[s + 2]].map(function (x) { return x.toFixed(digits); }).join(', ') + ')';
    }
    function showPicked() {
      var info = $('info');
      body.setAttribute('data-picked', state.picked ? shapes.bodies[state.picked.body].name : '');
      if (!state.picked) { info.textContent = ''; return; }
      var i = state.picked.body, lines = [shapes.bodies[i].name + (shapes.bodies[i].fixed ? ' (fixed)' : '')];
      engines.forEach(function (e) {
        var k = Math.min(state.frame, e.frames - 1), s = (k * nBodies + i) * STATE_FLOATS, st = e.states;
        lines.push(e.name + ':');
        lines.push('  position     ' + vec(st, s, 4) + ' m');
        lines.push('  orientation  (w ' + st[s + 3].toFixed(4) + ', ' + st[s + 4].toFixed(4) + ', ' + st[s + 5].toFixed(4) + ', ' + st[s + 6].toFixed(4) + ')');
        lines.push('  velocity     ' + vec(st, s + 7, 3) + ' m/s');
        lines.push('  angular vel. ' + vec(st, s + 10, 3) + ' rad/s');
      });
      info.textContent = lines.join('\n');
    }
    function pickAt(x, y) {
      var v = viewports().filter(function (p) { return x >= p.x && x < p.x + p.w; })[0];
      if (!v) return;
      camera.aspect = v.w / Math.max(1, v.h);
      camera.updateProjectionMatrix();
      var ndc = new THREE.Vector2(2 * (x - v.x) / v.w - 1, 1 - 2 * y / v.h);
      var ray = new THREE.Raycaster();
      ray.setFromCamera(ndc, camera);
      var meshes = [];
      v.engines.forEach(function (e) {
        e.bodies.forEach(function (g) { g.children.forEach(function (c) { if (c.isMesh) meshes.push(c); }); });
      });
      var hit = ray.intersectObjects(meshes, false)[0];
      setHighlight(false);
      state.picked = hit ? { body: hit.object.userData.body } : null;
      setHighlight(true);
      showFrame(state.frame);
    }
    var down = null;
    canvas.addEventListener('pointerdown', function (ev) { down = { x: ev.clientX, y: ev.clientY }; });
    canvas.addEventListener('pointerup', function (ev) {
      if (!down || Math.abs(ev.clientX - down.x) + Math.abs(ev.clientY - down.y) > CLICK_SLOP) return;
      var r = canvas.getBoundingClientRect();
      pickAt(ev.clientX - r.left, ev.clientY - r.top);
    });

    // --- controls ---

    function setMode(mode) {
      state.mode = mode;
      var overlay = mode === 'overlay';
      engines.forEach(function (e) {
        e.materials.concat([e.edgeMaterial]).forEach(function (m) {
          m.transparent = overlay;
          m.opacity = overlay ? OVERLAY_OPACITY : 1;
          m.depthWrite = !overlay;
          m.needsUpdate = true;
        });
      });
      $('mode-side').classList.toggle('on', !overlay);
      $('mode-overlay').classList.toggle('on', overlay);
      body.setAttribute('data-mode', mode);
      render();
    }
    function setContacts(on) {
      state.contacts = on;
      $('contacts').checked = on;
      showFrame(state.frame);
    }
    function setPlaying(on) {
      state.playing = on && frames > 1;
      if (state.playing && state.frame >= frames - 1) state.frame = 0;
      state.playTime = clock.t[state.frame];
      $('play').textContent = state.playing ? 'pause' : 'play';
      $('play').classList.toggle('on', state.playing);
      last = null;
      if (state.playing) requestAnimationFrame(tick);
    }
    var last = null;
    function tick(now) {
      if (!state.playing) return;
      if (last !== null) state.playTime += state.speed * (now - last) / 1000;
      last = now;
      var f = state.frame;
      while (f + 1 < frames && clock.t[f + 1] <= state.playTime) ++f;
      if (f !== state.frame) showFrame(f);
      if (state.frame >= frames - 1) { setPlaying(false); return; }
      requestAnimationFrame(tick);
    }

    function bindControls() {
      $('mode-side').addEventListener('click', function () { setMode('side'); });
      $('mode-overlay').addEventListener('click', function () { setMode('overlay'); });
      $('contacts').addEventListener('change', function (ev) { setContacts(ev.target.checked); });
      $('gain').addEventListener('input', function (ev) {
        state.gain = Number(ev.target.value);
        $('gain-value').textContent = ' ' + state.gain;
        showFrame(state.frame);
      });
      $('gain-value').textContent = ' ' + state.gain;
      $('reset').addEventListener('click', function () { resetCamera(); render(); });
      $('play').addEventListener('click', function () { setPlaying(!state.playing); });
      $('back').addEventListener('click', function () { setPlaying(false); showFrame(state.frame - 1); });
      $('forward').addEventListener('click', function () { setPlaying(false); showFrame(state.frame + 1); });
      $('speed').addEventListener('change', function (ev) { state.speed = Number(ev.target.value); });
      var slider = $('slider');
      slider.max = String(frames - 1);
      slider.addEventListener('input', function () { setPlaying(false); showFrame(Number(slider.value)); });
      controls.addEventListener('change', render);
      controls.addEventListener('start', function () { fittedAspect = null; });
      window.addEventListener('resize', render);
      document.addEventListener('keydown', function (ev) {
        if (ev.target.tagName === 'INPUT' && ev.target.type !== 'checkbox' && ev.key !== ' ') return;
        if (ev.key === ' ') { ev.preventDefault(); setPlaying(!state.playing); }
        else if (ev.key === 'ArrowLeft') { setPlaying(false); showFrame(state.frame - 1); }
        else if (ev.key === 'ArrowRight') { setPlaying(false); showFrame(state.frame + 1); }
        else if (ev.key === 'c') setContacts(!state.contacts);
        else if (ev.key === 'm') setMode(state.mode === 'side' ? 'overlay' : 'side');
        else if (ev.key === 'r') { resetCamera(); render(); }
      });
    }

    var duration = clock.t[frames - 1] - clock.t[0];
    function timelineX(t) { return duration > 0 ? (t - clock.t[0]) / duration : 0; }

    // Each engine's total energy over the run, a line in its colour on the timeline, all on one
    // scale, with a cursor at the frame shown.
    var SVG = 'http://www.w3.org/2000/svg', cursor = null;
    function drawEnergyGraph() {
      var svg = $('energy-graph'), lo = Infinity, hi = -Infinity;
      engines.forEach(function (e) {
        e.energy.forEach(function (x) { if (x !== null && isFinite(x)) { lo = Math.min(lo, x); hi = Math.max(hi, x); } });
      });
      if (!(hi >= lo)) { lo = 0; hi = 1; }
      var span = hi > lo ? hi - lo : 1;
      svg.setAttribute('viewBox', '0 0 ' + GRAPH_WIDTH + ' ' + GRAPH_HEIGHT);
      svg.setAttribute('preserveAspectRatio', 'none');
      engines.forEach(function (e) {
        var points = [];
        for (var k = 0; k < e.frames; ++k) {
          var x = e.energy[k];
          if (x === null || !isFinite(x)) continue;
          var y = GRAPH_HEIGHT - GRAPH_MARGIN - (GRAPH_HEIGHT - 2 * GRAPH_MARGIN) * (x - lo) / span;
          points.push((GRAPH_WIDTH * timelineX(e.t[k])).toFixed(1) + ',' + y.toFixed(1));
        }
        var line = document.createElementNS(SVG, 'polyline');
        line.setAttribute('points', points.join(' '));
        line.setAttribute('stroke', e.colour);
        line.setAttribute('data-engine', e.name);
        line.setAttribute('class', 'energy-line');
        svg.appendChild(line);
      });
      cursor = document.createElementNS(SVG, 'line');
      cursor.setAttribute('id', 'energy-cursor');
      cursor.setAttribute('y1', '0');
      cursor.setAttribute('y2', String(GRAPH_HEIGHT));
      svg.appendChild(cursor);
      $('energy-range').textContent = 'energy on the timeline: ' + lo.toFixed(2) + ' to ' + hi.toFixed(2) + ' J';
    }
    function moveEnergyCursor() {
      if (!cursor) return;
      var x = (GRAPH_WIDTH * timelineX(clock.t[state.frame])).toFixed(1);
      cursor.setAttribute('x1', x);
      cursor.setAttribute('x2', x);
      body.setAttribute('data-energy-cursor', timelineX(clock.t[state.frame]).toFixed(4));
    }

    function frameAt(t) {
      var best = 0;
      for (var f = 0; f < frames; ++f) if (Math.abs(clock.t[f] - t) < Math.abs(clock.t[best] - t)) best = f;
      return best;
    }

    // The engines' names, the legend, the marks of first disagreement and the notes.
    function showLabels() {
      $('engines').innerHTML = engines.map(function (e) {
        return '<span class="swatch" style="background:' + e.colour + '"></span>' + e.name;
      }).join(' &nbsp; ');
      $('legend').textContent = 'dots: contact points; arrows: normals (from body B to A), length ' +
        arrowBase.toFixed(3) + ' m + gain x depth; click a body to pick it';
      data.marks.forEach(function (m) {
        var div = document.createElement('div');
        div.className = 'mark';
        div.style.left = 100 * timelineX(m.t) + '%';
        div.title = m.label;
        div.addEventListener('click', function () { setPlaying(false); showFrame(frameAt(m.t)); });
        $('marks').appendChild(div);
        var line = document.createElement('div');
        var a = document.createElement('a');
        a.textContent = m.label;
        a.addEventListener('click', function () { setPlaying(false); showFrame(frameAt(m.t)); });
        line.appendChild(document.createTextNode('first disagreement (red on the timeline): '));
        line.appendChild(a);
        $('marklist').appendChild(line);
      });
      var notes = data.notes.slice();
      engines.forEach(function (e) {
        if (e.stopped) notes.push(e.name + ' stopped at t = ' + e.stopped.t + ' s: ' + e.stopped.quantity + ' of ' + e.stopped.body + ' not finite');
      });
      $('notes').textContent = notes.length ? 'Note: ' + notes.join('; ') : '';
    }

    // The start the address asks for: #frame=N or #t=T, mode=side|overlay, contacts=0|1, pick=NAME
    // (and camera=x,y,z, target=x,y,z: resetCamera).
    function applyAddress() {
      if (hash.get('mode') === 'side' || hash.get('mode') === 'overlay') state.mode = hash.get('mode');
      if (hash.get('contacts') === '0') state.contacts = false;
      $('contacts').checked = state.contacts;
      var pick = hash.get('pick');
      shapes.bodies.forEach(function (b, i) { if (b.name === pick) state.picked = { body: i }; });
      setHighlight(true);
      var start = hash.has('frame') ? Number(hash.get('frame')) : hash.has('t') ? frameAt(Number(hash.get('t'))) : 0;
      resetCamera();
      setMode(state.mode);
      showFrame(isFinite(start) ? start : 0);
    }

    // What the tests read on <body> once the first frame is drawn.
    function reportReady() {
      body.setAttribute('data-resources', String(performance.getEntriesByType('resource').length));
      var rect = canvas.getBoundingClientRect();
      body.setAttribute('data-canvas', [rect.left, rect.top, rect.width, rect.height].map(Math.round).join(','));
      // Through the fitted first camera (the address may have moved the camera shown): what the
      // bodies of the first frame cover, and a contact dot's diameter at the target.
      var position = camera.position.clone(), target = controls.target.clone();
      fitCamera();
      var e = screenExtent(firstPoints, camera), v = viewports()[0];
      body.setAttribute('data-framing', ((e[1] - e[0]) / 2).toFixed(3) + ',' + ((e[3] - e[2]) / 2).toFixed(3));
      body.setAttribute('data-contact-pixels', dotPixels(v).toFixed(1));
      body.setAttribute('data-contact-fill', engines.map(function (x) { return x.contactFill; }).join(','));
      body.setAttribute('data-contact-rim', CONTACT_RIM);
      camera.position.copy(position);
      controls.target.copy(target);
      controls.update();
      body.setAttribute('data-state', 'ready');
    }

    bindControls();
    showLabels();
    drawEnergyGraph();
    applyAddress();
    reportReady();
    if (hash.get('play') === '1') setPlaying(true);
  }

  try {
    main();
  } catch (error) {
    fail(error);
  }
})();
