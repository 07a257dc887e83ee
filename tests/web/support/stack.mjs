// The real controller stack for browser tests: core, UDP bridge, LCM bridge, a client (the demo,
// or hapticctrl-mujoco with a scene) and web bridge on loopback, for one unique instance; stopped and cleaned up (processes, /dev/shm) by
// stop(), which the tests call from after() so that a failure leaves nothing behind.
import { spawn, execFileSync } from 'node:child_process';
import { rmSync, existsSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { setTimeout as sleep } from 'node:timers/promises';

const env = (name) => {
  const value = process.env[name];
  if (!value) throw new Error(`${name} is not set (ctest sets it; see tests/web/CMakeLists.txt)`);
  return value;
};

export const binaries = {
  core: () => env('HAPTICCTRL_CORE'),
  udp: () => env('HAPTICCTRL_UDP'),
  lcm: () => env('HAPTICCTRL_LCM'),
  demo: () => env('HAPTICCTRL_DEMO'),
  web: () => env('HAPTICCTRL_WEB'),
  hmi: () => env('HAPTICCTRL_HMI'),
  mujoco: () => env('HAPTICCTRL_MUJOCO'),
  scenes: () => env('HAPTICCTRL_MUJOCO_SCENES'),
};

/** Polls `predicate` every `everyMs` until it is truthy or `timeoutMs` passes; returns its value. */
export async function until(predicate, { timeoutMs = 5000, everyMs = 50 } = {}) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const value = await predicate();
    if (value) return value;
    if (Date.now() >= end) return value;
    await sleep(everyMs);
  }
}

class Process {
  constructor(name, binary, args) {
    this.name = name;
    this.output = '';
    this.child = spawn(binary, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    this.exited = new Promise((resolve) => this.child.on('exit', (code, signal) => resolve(code ?? 128 + (signal === 'SIGKILL' ? 9 : 15))));
    this.running = true;
    this.exited.then(() => { this.running = false; });
    for (const stream of [this.child.stdout, this.child.stderr]) {
      stream.on('data', (chunk) => { this.output += chunk.toString(); });
    }
  }

  /** Waits for `pattern` in the output; returns the match. */
  async waitFor(pattern, timeoutMs = 10000) {
    const match = await until(() => this.output.match(pattern), { timeoutMs });
    if (!match) throw new Error(`${this.name}: no ${pattern} within ${timeoutMs} ms; output:\n${this.output}`);
    return match;
  }

  async stop(signal = 'SIGTERM', timeoutMs = 5000) {
    if (!this.running) return;
    this.child.kill(signal);
    const done = await Promise.race([this.exited, sleep(timeoutMs).then(() => null)]);
    if (done === null) {
      this.child.kill('SIGKILL');
      await this.exited;
    }
  }
}

export class Stack {
  constructor(tag) {
    this.instance = `w${process.pid}-${tag}`;
    // The cores' black boxes go to a directory of the stack's own (0700), removed by stop().
    this.blackBoxes = mkdtempSync(join(tmpdir(), 'hapticctrl-web-'));
    this.processes = {};
    this.finished = []; // replaced processes, for the logs
  }

  hmi(...args) {
    return execFileSync(binaries.hmi(), ['--instance', this.instance, ...args], { encoding: 'utf8', timeout: 10000 });
  }

  /** The controller's state read from shared memory (hapticctrl-hmi status --json). */
  status() {
    return JSON.parse(this.hmi('status', '--json'));
  }

  /**
   * Starts everything; `scene`: hapticctrl-mujoco on that shipped scene (powering the arm, on a
   * 1 ms core: its coupling is the one a user runs) instead of the demo.
   */
  async start({ scene = null } = {}) {
    const i = ['--instance', this.instance];
    // Benchmark mode: these tests judge the page, not the machine's timing. A stall of the VM
    // failed a plain 10 ms core safe in CI (2026-12-06: 5 consecutive misses mid-run, and the
    // tests after it found no controller); a fail-safe a test asks for is started without it.
    await this.startCore(['--benchmark-mode'], scene ? '1000' : '10000');
    const udp = this.run('udp', binaries.udp(), [...i, '--port', '0']);
    this.udpPort = Number((await udp.waitFor(/listening on 127\.0\.0\.1:(\d+)/))[1]);
    const lcm = this.run('lcm', binaries.lcm(), [...i, '--allow-remote-commands']);
    await lcm.waitFor(/remote commands enabled/);
    const server = ['--server', `127.0.0.1:${this.udpPort}`];
    const client = scene
      ? this.run('client', binaries.mujoco(), ['--model', join(binaries.scenes(), `${scene}.xml`), ...server, ...i, '--headless'])
      : this.run('client', binaries.demo(), [...server, ...i, '--headless', '--no-power']);
    await client.waitFor(/ready:/);
    await this.startWeb();
  }

  /** Starts a core (10 ms cycle unless `periodUs`) with `extra` options, after the last one ended. */
  async startCore(extra = [], periodUs = '10000') {
    // Sanitizer builds integrate the arm in coarser sub-steps, as tests/support/controller_stack.hpp
    // explains: instrumented, the simulator alone takes most of the period.
    const substepUs = process.env.HAPTICCTRL_SANITIZED ? '250' : '125';
    const core = this.run('core', binaries.core(), ['--instance', this.instance, '--period-us', periodUs,
      '--rt', 'warn', '--sim-substep-us', substepUs, '--state-dir', this.blackBoxes, ...extra]);
    await core.waitFor(/running, period/);
  }

  /** Starts the web bridge: on a free port the first time, on the same port after that. */
  async startWeb() {
    const web = this.run('web', binaries.web(), ['--instance', this.instance, '--listen', `127.0.0.1:${this.webPort ?? 0}`,
      '--allow-remote-commands', '--rate', '20']);
    this.webPort = Number((await web.waitFor(/listening on http:\/\/127\.0\.0\.1:(\d+)\//))[1]);
    this.url = `http://127.0.0.1:${this.webPort}/`;
  }

  async startLcm() {
    const lcm = this.run('lcm', binaries.lcm(), ['--instance', this.instance, '--allow-remote-commands']);
    await lcm.waitFor(/remote commands enabled/);
  }

  run(name, binary, args) {
    if (this.processes[name]) this.finished.push(this.processes[name]);
    this.processes[name] = new Process(name, binary, args);
    return this.processes[name];
  }

  async stopProcess(name, signal = 'SIGTERM') {
    await this.processes[name]?.stop(signal);
  }

  /** Everything down, the core first (its fail-safe order), then the rest; no segment left. */
  async stop() {
    await this.stopProcess('core');
    for (const name of ['client', 'udp', 'lcm', 'web']) await this.stopProcess(name);
    for (const suffix of ['', '.lock']) {
      const path = `/dev/shm/hapticctrl.${this.instance}${suffix}`;
      if (existsSync(path)) rmSync(path);
    }
    rmSync(this.blackBoxes, { recursive: true, force: true });
  }

  logs() {
    return [...this.finished, ...Object.values(this.processes)].map((p) => `--- ${p.name}\n${p.output}`).join('\n');
  }
}
