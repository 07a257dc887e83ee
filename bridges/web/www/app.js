// The operator view's main module: the WebSocket to hapticctrl-web, the status and alarms, the
// controls, and the wiring of the 3D view and the plots. The page holds no authority: every
// request goes through the web bridge and the LCM bridge, which validate it again.
import { ArmView } from './arm_view.js';
import { Plots } from './plots.js';
import { handleMismatch } from './kinematics.js';

// state_word bits (lcmtypes/arm_state_t.lcm)
const POWERED = 1;
const ESTOP = 2;
const FAIL_SAFE = 4;
const DEGRADED = 8;
const COUPLED = 16;
const CLIENT_STALE = 32;
const CORE_FAIL_SAFE = 2;
const CORE_STOPPING = 3;
const FORCE_SEND_MS = 50; // the LCM bridge lets an operator force decay after 200 ms of silence
const MODEL_TOLERANCE_M = 0.002;
const MAX_EVENTS = 200;
const SCENE_GONE_MS = 1000; // the demo publishes its scene, hapticctrl-mujoco its world, at 30 Hz
const LINK_WINDOW_MS = 10000; // the client link's drop-outs are counted over this window

const $ = (id) => document.getElementById(id);
const fmt = (v, digits = 3) => (v >= 0 ? '+' : '') + v.toFixed(digits);
const vec3 = (a, digits = 3, unit = '') => `${fmt(a[0], digits)} ${fmt(a[1], digits)} ${fmt(a[2], digits)}${unit}`;
const two = (n) => String(n).padStart(2, '0');
/** An event's time (its utime: when the core recorded it, µs since the epoch), 24-hour, local. */
const clockOf = (utime) => {
  const d = new Date(utime / 1000);
  return `${two(d.getHours())}:${two(d.getMinutes())}:${two(d.getSeconds())}`;
};

/** What tests and curious operators can read (window.hapticctrl). */
const status = {
  connected: false,
  hello: null,
  model: null,
  frame: null,
  stats: null,
  framesReceived: 0,
  replies: [],
  coreLost: null,
  failedSafe: null, // { reason, at }: the last fail-safe, until a core runs again
  staleOnsets: [], // when the page heard of each client drop-out (performance.now()), last 10 s
  webgl: true,
  modelMismatchM: null,
  view: null,
  plots: null,
};
window.hapticctrl = status;

let socket = null;
let view = null;
let plots = null;
try {
  view = new ArmView($('scene'));
} catch (error) {
  status.webgl = false;
  $('model-warning').textContent = `3D view unavailable (${error.message}); telemetry and controls still work`;
  $('model-warning').classList.remove('hidden');
}
status.view = view;
plots = new Plots();
status.plots = plots;

function setBadge(element, text, level) {
  element.textContent = text;
  element.className = `badge ${level}`;
}

function send(message) {
  if (socket && socket.readyState === WebSocket.OPEN) {
    socket.send(JSON.stringify(message));
    return true;
  }
  return false;
}

// ---- controls ------------------------------------------------------------------------------

const commandButtons = { 'power-on': 'power_on', 'power-off': 'power_off', reset: 'emergency_reset', estop: 'emergency_stop' };
for (const [id, command] of Object.entries(commandButtons)) {
  $(id).addEventListener('click', () => {
    if (!send({ type: 'command', command })) $('reply').textContent = 'not connected';
  });
}

const AXES = [
  { name: 'Fx', max: 20, step: 0.5, unit: 'N' },
  { name: 'Fy', max: 20, step: 0.5, unit: 'N' },
  { name: 'Fz', max: 20, step: 0.5, unit: 'N' },
  { name: 'Tx', max: 1, step: 0.05, unit: 'N·m' },
  { name: 'Ty', max: 1, step: 0.05, unit: 'N·m' },
  { name: 'Tz', max: 1, step: 0.05, unit: 'N·m' },
];
const sliders = AXES.map((axis, i) => {
  const label = document.createElement('label');
  label.innerHTML = `<span>${axis.name}</span><input type="range" min="${-axis.max}" max="${axis.max}" ` +
    `step="${axis.step}" value="0" data-testid="slider-${axis.name}"><output>0 ${axis.unit}</output>`;
  $('sliders').append(label);
  const input = label.querySelector('input');
  const output = label.querySelector('output');
  input.addEventListener('input', () => {
    output.textContent = `${Number(input.value).toFixed(i < 3 ? 1 : 2)} ${axis.unit}`;
    sendForce();
  });
  return { input, output, axis };
});

function wrench() {
  return sliders.map((s) => Number(s.input.value));
}

let lastForceSent = 0;
function sendForce() {
  lastForceSent = performance.now();
  send({ type: 'force', wrench: wrench() });
}

// While the sliders hold a force, repeat it: the bridge drops a force that stops arriving.
setInterval(() => {
  if (wrench().some((v) => v !== 0) && performance.now() - lastForceSent >= FORCE_SEND_MS) sendForce();
}, FORCE_SEND_MS / 2);

$('release').addEventListener('click', () => {
  sliders.forEach((s) => {
    s.input.value = '0';
    s.output.textContent = `0 ${s.axis.unit}`;
  });
  sendForce();
});

function applyPermissions(remote) {
  for (const id of ['power-on', 'power-off', 'reset', 'release']) $(id).disabled = !remote;
  sliders.forEach((s) => { s.input.disabled = !remote; });
  $('controls-note').textContent = remote
    ? 'Commands go to the controller through the web and LCM bridges.'
    : 'Remote commands are disabled (hapticctrl-web --allow-remote-commands): only the emergency stop works.';
}

// ---- state ---------------------------------------------------------------------------------

function describeAlarm(frame, stats) {
  const arm = frame.arm;
  if (status.failedSafe) {
    return {
      level: 'bad',
      text: `Controller failed safe: ${status.failedSafe.reason} at ${status.failedSafe.at} — ` +
        'motors off; a controller started again comes up powered off',
    };
  }
  if (status.coreLost) return { level: 'bad', text: `CONTROLLER LOST — ${status.coreLost}` };
  if (frame.controller_silent) {
    const age = frame.age_ms.arm;
    return {
      level: 'bad',
      text: age === null
        ? 'No telemetry from the controller yet (is hapticctrl-lcm running?)'
        : `No telemetry from the controller for ${(age / 1000).toFixed(1)} s — the core or its LCM bridge is down`,
    };
  }
  const coreState = stats ? stats.core_state : arm?.core_state;
  const reason = stats ? stats.stop_reason_name : '';
  if ((arm && arm.state_word & FAIL_SAFE) || coreState === CORE_FAIL_SAFE) {
    return { level: 'bad', text: `FAIL-SAFE — ${reason || 'see the events'}` };
  }
  if (coreState >= CORE_STOPPING) return { level: 'bad', text: `Controller stopped — ${reason}` };
  if (arm && arm.state_word & ESTOP) return { level: 'bad', text: 'EMERGENCY STOP latched — reset it to power the arm again' };
  if (arm && arm.state_word & DEGRADED) return { level: 'warn', text: 'Degraded cycle: coupling off, gravity compensation and damping only' };
  return null;
}

function showAlarm(alarm) {
  const banner = $('alarm');
  banner.classList.toggle('hidden', !alarm);
  if (!alarm) return;
  banner.textContent = alarm.text;
  banner.className = `alarm ${alarm.level === 'warn' ? 'warn' : ''}`;
}

function showState(frame) {
  const { arm, coupling, scene, world } = frame;
  const stats = status.stats;
  showAlarm(describeAlarm(frame, stats));
  if (status.coreLost || frame.controller_silent) {
    setBadge($('core-state'), status.coreLost ? 'core: lost' : 'core: silent', 'bad');
  } else if (stats) {
    setBadge($('core-state'), `core: ${stats.core_state_name}`, stats.core_state === 1 ? 'good' : 'bad');
  }
  if (stats) {
    $('rt').textContent = `${(stats.period_ns / 1e6).toFixed(3)} ms cycle · ${stats.rt_mode_name} · ${stats.misses_total} misses`;
  }
  // A lost or silent controller's last state is not its state now: the badges say so instead of
  // a green "powered" / "client: coupled" from before (J8).
  const live = !(status.coreLost || frame.controller_silent);
  if (arm && !live) {
    setBadge($('power'), 'power: unknown', 'bad');
    setBadge($('coupling'), 'client: unknown', '');
  }
  if (arm) {
    const w = arm.state_word;
    if (live) {
      setBadge($('power'), w & POWERED ? 'powered' : 'unpowered', w & POWERED ? 'good' : '');
      const client = coupling && coupling.session_id !== 0;
      setBadge($('coupling'),
        !client ? 'client: none' : w & CLIENT_STALE ? 'client: stale' : w & COUPLED ? 'client: coupled' : 'client: connected',
        !client ? '' : w & CLIENT_STALE ? 'warn' : 'good');
      showClientLink(client, !!(w & CLIENT_STALE));
    } else {
      setBadge($('client-link'), 'link: unknown', '');
    }
    $('estop').classList.toggle('latched', !!(w & ESTOP));
    $('estop').textContent = w & ESTOP ? 'E-STOP LATCHED' : 'EMERGENCY STOP';
    $('handle-position').textContent = vec3(arm.handle_pose, 4, ' m');
    $('operator-force').textContent = vec3(arm.operator_wrench, 2, ' N');
    $('rendered-force').textContent = vec3(arm.rendered_wrench, 2, ' N');
    if (status.model) {
      status.modelMismatchM = handleMismatch(status.model, arm.joint_position, arm.handle_pose);
      const warning = $('model-warning');
      if (status.webgl) {
        const off = status.modelMismatchM > MODEL_TOLERANCE_M;
        warning.classList.toggle('hidden', !off);
        if (off) {
          warning.textContent = `The drawn arm is not the controller's: its handle is ${(status.modelMismatchM * 1000).toFixed(1)} mm ` +
            'off. Give hapticctrl-web the core\'s --arm-model.';
        }
      }
    }
  }
  if (scene) {
    $('contact').textContent = `${vec3(scene.contact_force, 2, ' N')} · ${(scene.penetration * 1000).toFixed(2)} mm`;
  } else if (world) {
    $('contact').textContent = `${vec3(world.contact_force, 2, ' N')} · ${world.contacts.length} contact(s) · ` +
      `${world.steps_per_second.toFixed(0)} of ${world.model_steps_per_second.toFixed(0)} steps/s` +
      (world.geoms_total > world.geoms.length ? ` · ${world.geoms.length} of ${world.geoms_total} geoms drawn` : '');
  } else {
    $('contact').textContent = 'no scene (a running hapticctrl-demo or hapticctrl-mujoco publishes it)';
  }
  const surface = coupling && coupling.contact_age_ms >= 0;
  $('surface').textContent = surface
    ? `${coupling.surface_force.toFixed(2)} N · ${coupling.surface_depth_mm.toFixed(2)} mm deep` +
      ` · ${coupling.contacts} contact(s), newest ${coupling.contact_age_ms.toFixed(0)} ms old` +
      (coupling.surface_hidden_mm > 0.05 ? ` · ${coupling.surface_hidden_mm.toFixed(1)} mm held back` : '')
    : 'none reported';
}

/**
 * The client link's quality from its drop-outs (the core's client_stale events): one badge
 * instead of a list that an unsteady link fills (11 of the last 11 events after 25 s, J8).
 */
function showClientLink(client, staleNow) {
  const now = performance.now();
  status.staleOnsets = status.staleOnsets.filter((t) => now - t < LINK_WINDOW_MS);
  const n = status.staleOnsets.length;
  if (!client) setBadge($('client-link'), 'link: –', '');
  else if (staleNow) setBadge($('client-link'), 'link: stale now', 'bad');
  else if (n === 0) setBadge($('client-link'), 'link: steady', 'good');
  else setBadge($('client-link'), `link: ${n} drop-out${n > 1 ? 's' : ''} in 10 s`, 'warn');
}

/** Events into the list, newest first; `live`: just happened (not the history of a new page). */
function addEvents(events, live) {
  const list = $('events');
  for (const e of events) {
    if (e.kind === 'client_stale') { // counted by the link badge, not listed
      if (live && e.code === 1) status.staleOnsets.push(performance.now());
      continue;
    }
    if (e.index === 0 && e.kind === 'core_state') status.coreLost = e.text;
    else if (e.kind === 'core_state' && e.code === CORE_FAIL_SAFE) {
      status.failedSafe = { reason: e.text.replace(/^fail-safe: /, ''), at: clockOf(e.utime) };
    } else if (e.kind === 'core_state' && e.code <= 1) { // a core is running again
      status.coreLost = null;
      status.failedSafe = null;
    }
    const item = document.createElement('li');
    const fault = (e.kind === 'core_state' && e.code >= CORE_FAIL_SAFE) || (e.kind === 'emergency_stop' && e.code === 1);
    item.className = fault ? 'fault' : '';
    item.textContent = `${clockOf(e.utime)} ${e.index === 0 ? 'bridge' : `#${e.index}`} cycle ${e.cycle}: ${e.text}` +
      (e.lost_before > 0 ? ` (${e.lost_before} lost before)` : '');
    list.prepend(item);
  }
  while (list.children.length > MAX_EVENTS) list.lastChild.remove();
}

// The web bridge only forwards: say so when a request had no visible effect (the LCM bridge
// refuses remote commands unless it runs with --allow-remote-commands).
const EFFECTS = {
  power_on: { done: (w) => !!(w & POWERED), hint: 'the arm did not power on (e-stop latched? hapticctrl-lcm without --allow-remote-commands?)' },
  power_off: { done: (w) => !(w & POWERED), hint: 'the arm is still powered (hapticctrl-lcm without --allow-remote-commands?)' },
  emergency_stop: { done: (w) => !!(w & ESTOP), hint: 'the emergency stop did not latch: is hapticctrl-lcm running?' },
  emergency_reset: { done: (w) => !(w & ESTOP), hint: 'the emergency stop is still latched (hapticctrl-lcm without --allow-remote-commands?)' },
};
const EFFECT_WAIT_MS = 1500;

function checkEffect(request) {
  const effect = EFFECTS[request];
  if (!effect) return;
  setTimeout(() => {
    const word = status.frame?.arm?.state_word;
    if (word !== undefined && !effect.done(word)) $('reply').textContent = `${request}: sent, but ${effect.hint}`;
  }, EFFECT_WAIT_MS);
}

function onMessage(text) {
  const message = JSON.parse(text);
  switch (message.type) {
    case 'hello':
      status.hello = message;
      $('instance').textContent = `instance ${message.instance}`;
      applyPermissions(message.remote_commands);
      break;
    case 'model':
      status.model = message;
      view?.setModel(message);
      break;
    case 'history':
      $('events').replaceChildren();
      if (message.stats) status.stats = message.stats;
      addEvents(message.events, false);
      break;
    case 'state':
      // A scene its client stopped publishing is gone, not frozen where it was.
      if (message.age_ms.scene === null || message.age_ms.scene > SCENE_GONE_MS) message.scene = null;
      if (message.age_ms.world === null || message.age_ms.world > SCENE_GONE_MS) message.world = null;
      status.frame = message;
      status.framesReceived += 1;
      if (message.stats) status.stats = message.stats;
      addEvents(message.events, true);
      showState(message);
      view?.update(message);
      plots.add(message);
      break;
    case 'reply':
      status.replies.push(message);
      $('reply').textContent = message.ok ? `${message.request}: sent` : `${message.request || 'request'}: refused — ${message.reason}`;
      if (message.ok) checkEffect(message.request);
      break;
    default:
      break;
  }
}

function connect() {
  const url = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`;
  socket = new WebSocket(url);
  socket.addEventListener('open', () => {
    status.connected = true;
    setBadge($('link'), 'web: connected', 'good');
  });
  socket.addEventListener('message', (event) => onMessage(event.data));
  socket.addEventListener('close', () => {
    status.connected = false;
    setBadge($('link'), 'web: lost', 'bad');
    showAlarm({ level: 'bad', text: 'CONNECTION TO THE CONTROLLER LOST — reconnecting…' });
    setTimeout(connect, 1000);
  });
}

setInterval(() => plots.redraw(), 250);
applyPermissions(false);
connect();
