// The engine side of docs/engine-protocol.md, shared by the node adapters: one JSON request a line
// on standard input, exactly one answer a line on standard output, everything else on standard
// error. An adapter supplies an engine object (see serve() below); this file owns the framing,
// the dispatch of hello/load/step/quit, the checking of settings and answers, and the exit.
import { createInterface } from 'node:readline';
import { checkSettings, describeSettings } from './settings.mjs';
import { InputError } from './errors.mjs';

export const PROTOCOL_VERSION = 1;

// Standard output carries the answers alone: the WebAssembly runtimes print through console.log
// (Emscripten's default `print`), so every console channel is sent to standard error.
console.log = console.error;
console.info = console.error;
console.warn = console.error;
console.debug = console.error;

const stdoutWrite = process.stdout.write.bind(process.stdout);
function answer(message) {
  stdoutWrite(JSON.stringify(message) + '\n');
}

class RequestError extends InputError {}

// A WebAssembly engine's first steps in a fresh node process compile and tier up its code: its
// first step in a process costs 20 ms (Jolt) to 0.9 s (Rapier) against tens of µs a step after
// it, measured on a one-box scene. That is the runtime's start, not the engine's step, and it would
// be charged to whatever scene the process runs first (it was: Rapier's costs came out nearly the
// same per simulated second at every dt). So before the first scene each process steps this one
// (two boxes and the ground meeting with friction and restitution, one spinning, one landing on
// the other) with the engine's default settings, untimed, and throws it away.
const kWarmUpSteps = 240;
function warmUpScene() {
  const box = (name, position, velocity, angularVelocity) => ({
    name, fixed: false, mass: 1, center_of_mass: [0, 0, 0],
    inertia: [[1 / 6, 0, 0], [0, 1 / 6, 0], [0, 0, 1 / 6]],
    position, orientation: [1, 0, 0, 0], velocity, angular_velocity: angularVelocity,
    friction: 0.5, restitution: 0.5,
    boxes: [{ half_extents: [0.5, 0.5, 0.5], position: [0, 0, 0], orientation: [1, 0, 0, 0] }],
  });
  return {
    name: 'warm_up', dt: 1 / 240, gravity: [0, 0, -9.81], ground: { normal: [0, 0, 1], offset: 0 },
    effects: { friction: true, restitution: true, damping: false, gyroscopic: true },
    damping: { linear: 0, angular: 0 },
    bodies: [box('slider', [0, 0, 0.5], [2, 0, 0], [0, 0, 3]), box('faller', [0.8, 0.1, 2], [0, 0, 0], [0.5, 0.3, 0])],
    ground_material: { friction: 0.5, restitution: 0.5 },
  };
}

function requireField(request, key, test, what) {
  if (!(key in request)) throw new RequestError(`${request.op}: missing "${key}"`);
  if (!test(request[key])) throw new RequestError(`${request.op}: "${key}" must be ${what}`);
  return request[key];
}

// Every number of an answer must be finite: a non-finite one is reported as an error naming the
// field instead of being written as null (which would break the protocol).
function findNonFinite(value, path) {
  if (typeof value === 'number') return Number.isFinite(value) ? null : path;
  if (Array.isArray(value)) {
    for (let i = 0; i < value.length; ++i) {
      const bad = findNonFinite(value[i], `${path}[${i}]`);
      if (bad) return bad;
    }
  } else if (value && typeof value === 'object') {
    for (const [k, v] of Object.entries(value)) {
      const bad = findNonFinite(v, `${path}.${k}`);
      if (bad) return bad;
    }
  }
  return null;
}

// engine: {
//   name, version, precision ('float32' | 'float64'), settings (the table of settings.mjs),
//   init(): Promise, once, before the first answer that needs the engine;
//   load(scene, settings): builds the world (settings complete: every declared key, checked);
//   step(n): advances n steps, returns the seconds spent in the engine's step calls;
//   states(): the bodies in scene order; contacts(): the last step's contact points;
//   time(): simulated seconds since load }
export function serve(engine) {
  let initialised = null;
  let warmedUp = null;
  let loaded = false;

  async function warmUp() {
    await (initialised ??= engine.init());
    engine.load(warmUpScene(), checkSettings(engine.settings, {}));
    engine.step(kWarmUpSteps);
  }

  async function handle(request) {
    switch (request.op) {
      case 'hello': {
        const protocol = requireField(request, 'protocol', Number.isInteger, 'an integer');
        if (protocol !== PROTOCOL_VERSION)
          throw new RequestError(`hello: this engine speaks protocol ${PROTOCOL_VERSION}, not ${protocol}`);
        await (initialised ??= engine.init());
        return {
          ok: true, protocol: PROTOCOL_VERSION, name: engine.name, version: engine.version,
          precision: engine.precision, contacts: true, timing: true,
          settings: describeSettings(engine.settings),
        };
      }
      case 'load': {
        const scene = requireField(request, 'scene', (v) => v && typeof v === 'object' && !Array.isArray(v), 'an object');
        const given = request.settings ?? {};
        if (typeof given !== 'object' || Array.isArray(given) || given === null)
          throw new RequestError('load: "settings" must be an object');
        await (initialised ??= engine.init());
        const settings = checkSettings(engine.settings, given);
        loaded = false;
        await (warmedUp ??= warmUp());
        engine.load(scene, settings);
        loaded = true;
        return { ok: true };
      }
      case 'step': {
        if (!loaded) throw new RequestError('step: no scene loaded (send load first)');
        const n = requireField(request, 'n', (v) => Number.isInteger(v) && v >= 1, 'an integer >= 1');
        for (const key of ['state', 'contacts'])
          if (key in request && typeof request[key] !== 'boolean')
            throw new RequestError(`step: "${key}" must be true or false`);
        const engineSeconds = engine.step(n);
        const reply = { ok: true, time: engine.time(), engine_seconds: engineSeconds };
        if (request.state) reply.bodies = engine.states();
        if (request.contacts) reply.contacts = engine.contacts();
        const bad = findNonFinite(reply, 'step');
        if (bad) throw new RequestError(`${engine.name} produced a non-finite number at ${bad} (time ${reply.time} s)`);
        return reply;
      }
      case 'quit':
        return { ok: true };
      default:
        throw new RequestError(`unknown op ${JSON.stringify(request.op)} (hello, load, step, quit)`);
    }
  }

  // Requests are answered strictly in order: each waits for the one before it.
  let queue = Promise.resolve();
  const lines = createInterface({ input: process.stdin, crlfDelay: Infinity, terminal: false });
  lines.on('line', (line) => {
    queue = queue.then(async () => {
      if (line.trim() === '') return;
      let request;
      try {
        request = JSON.parse(line);
      } catch (e) {
        answer({ ok: false, error: `not a JSON line: ${e.message}` });
        return;
      }
      if (!request || typeof request !== 'object' || Array.isArray(request) || typeof request.op !== 'string') {
        answer({ ok: false, error: 'a request must be a JSON object with a string "op"' });
        return;
      }
      try {
        answer(await handle(request));
      } catch (e) {
        if (!(e instanceof InputError)) console.error(e.stack ?? String(e));
        if (request.op === 'load') loaded = false;
        answer({ ok: false, error: e.message ?? String(e) });
      }
      if (request.op === 'quit') process.exit(0);
    });
  });
  lines.on('close', () => { queue = queue.then(() => process.exit(0)); });
}
